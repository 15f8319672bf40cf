"""Keep OMPL's console log and nanobind's exit-time leak report away from CLI users.

OMPL logs through its own handler (hidden unless ``--verbose``), set when OMPL is first
imported, so a command that never plans (``--help``, a bad argument, ``simulate``) never
imports it. At interpreter exit nanobind reports objects it considers leaked, a wall of text
on stderr after a normal run; the CLI therefore ends its process with ``os._exit`` once its
own output is flushed, which skips that report (and nothing else the CLI needs: files are
written and closed before).
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import importlib.util
import os
import sys
from collections.abc import Callable, Sequence
from types import ModuleType
from typing import Any, NoReturn

OMPL = "ompl"


def _apply_ompl_logging(verbose: bool) -> None:
    from ompl import util as ou

    ou.setLogLevel(ou.LogLevel.LOG_INFO if verbose else ou.LogLevel.LOG_NONE)


class _ThenLoader(importlib.abc.Loader):
    """A module's own loader, then ``then()`` once the module has run."""

    def __init__(self, loader: Any, then: Callable[[], None]):
        self._loader = loader
        self._then = then

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
        return self._loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        self._loader.exec_module(module)
        self._then()

    def __getattr__(self, name: str) -> Any:  # resource readers and the like: the loader's
        return getattr(self._loader, name)


class _AfterImport(importlib.abc.MetaPathFinder):
    """Runs ``then()`` right after the top-level module ``name`` is first imported (and
    steps aside: it acts once)."""

    def __init__(self, name: str, then: Callable[[], None]):
        self.name = name
        self.then = then

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname != self.name:
            return None
        _forget(self.name)
        spec = importlib.util.find_spec(fullname)  # by the finders there are without us
        if spec is not None and spec.loader is not None:
            spec.loader = _ThenLoader(spec.loader, self.then)
        return spec


def _forget(name: str) -> None:
    sys.meta_path[:] = [
        f for f in sys.meta_path if not (isinstance(f, _AfterImport) and f.name == name)
    ]


def set_ompl_logging(verbose: bool) -> None:
    """OMPL's log at INFO with ``verbose``, otherwise off: now if OMPL is imported, else as
    soon as it is (importing OMPL takes about 15 ms and the subcommand may never need it; a
    bad argument's error must not wait for it)."""
    _forget(OMPL)
    if OMPL in sys.modules:
        _apply_ompl_logging(verbose)
    else:
        sys.meta_path.insert(0, _AfterImport(OMPL, lambda: _apply_ompl_logging(verbose)))


def exit_now(code: int) -> NoReturn:
    """Flush our streams and end the process without the interpreter's exit hooks, after
    releasing what multiprocessing releases at exit: its finalizers of priority 0 and above
    unlink the named semaphores of spawn-context pools and queues still alive (an interrupt
    can land while a pool shuts down), which the resource tracker would otherwise report as
    leaked, on the terminal, after the command's last line."""
    try:
        mp_util = sys.modules.get("multiprocessing.util")
        if mp_util is not None:
            mp_util._run_finalizers(0)  # what its atexit hook runs first
        sys.stdout.flush()
        sys.stderr.flush()
    finally:
        os._exit(code)
