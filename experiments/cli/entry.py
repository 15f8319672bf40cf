"""The ``partfeeder`` command line: the parser built from :mod:`experiments.cli.registry`, and
the one place that turns bad input into a one-line error.

``partfeeder plan``: plan the part through a feeder (a paper preset, 12 values, or a YAML
scene) with one level and one OMPL planner, for one or both entry orientations; prints a
summary (or JSON) and writes a picture of the tree and path. ``partfeeder draw``: pictures of
designs. ``partfeeder simulate``: the passive drop of the part through a feeder with the dynamic
level, per entry orientation. ``partfeeder bench``: speed of the levels and of planning.
``partfeeder feasibility``: the fraction of N Halton designs feasible at one level against
another on the same designs and budgets (is the first level's feasible set a subset?).
``partfeeder run`` / ``report``: the main job (the sweep up the ladder) and its report.

Building the parser imports only light modules (see the registry), so ``partfeeder --help``
and a bad argument answer at once; numba, OMPL and matplotlib load in the subcommand that runs.

SIGTERM is handled as Ctrl-C: a job stops, stores what is done, releases its lock and says so
in one line (exit status 130); its workers ignore SIGINT and die with it
(:mod:`experiments.executors.worker`). Whatever a command ends with after such a signal is the
interruption, one line and 130, not a traceback (:class:`_Stop`: an interrupt that lands in a
ctypes callback, as during a numba compile, is swallowed there and delivered again).

Exit status: 0 done (whether or not a plan was found: see the output), 2 bad input: one
line on stderr, whether a subcommand found it (``UsageError``) or a reader or job below it did
(:func:`experiments.cli.errors.input_error_line`); any other exception is a bug and keeps its
traceback.
"""

from __future__ import annotations

import _thread
import argparse
import gc
import signal
import sys
import threading
from collections.abc import Sequence
from types import FrameType, ModuleType
from typing import Any, NoReturn

from experiments.cli.console import exit_now, set_ompl_logging
from experiments.cli.errors import input_error_line, one_line
from experiments.cli.registry import SUBCOMMANDS
from experiments.cli.usage import UsageError


class _Parser(argparse.ArgumentParser):
    """argparse's parser, whose errors are one line (argparse prints its usage block first,
    several lines; ``--help`` still shows it). Subcommands' parsers are of this class too."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (see: {self.prog} --help)\n")


def _parser() -> tuple[argparse.ArgumentParser, dict[str, ModuleType]]:
    """The parser of every registered subcommand, and the module that runs each one."""
    parser = _Parser(
        prog="partfeeder",
        description="Design part feeders by motion planning with physics (geometric, "
        "kinematic and dynamic levels on OMPL).",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    modules: dict[str, ModuleType] = {}
    for command in SUBCOMMANDS:
        module = command.load()
        module.add_arguments(sub.add_parser(command.name, help=command.help))
        modules[command.name] = module
    return parser, modules


def run(argv: Sequence[str] | None = None) -> int:
    """Run a command; returns the exit status (for tests; ``main`` also exits)."""
    parser, modules = _parser()
    args = parser.parse_args(argv)
    set_ompl_logging(getattr(args, "verbose", False))
    try:
        return int(modules[args.command].run(args))
    except UsageError as exc:
        line = str(exc)
    except Exception as exc:
        found = input_error_line(exc)
        if found is None:
            raise  # a bug, not bad input: keep its traceback
        line = found
    print(f"partfeeder {args.command}: error: {one_line(line)}", file=sys.stderr)
    return 2


REDELIVER_S = 0.01  # delay before an interrupt swallowed by a ctypes callback is raised again


class _Stop:
    """The signals that stop a command, for one process's life: SIGTERM always, SIGINT when it
    is at Python's default (a command started in the background with SIGINT ignored keeps
    ignoring it), each raising KeyboardInterrupt and remembered.

    Remembered because a KeyboardInterrupt can land where it cannot propagate: inside a ctypes
    callback (llvmlite's object-cache callback while numba compiles a kernel), where Python
    prints "Exception ignored ..." with a traceback and carries on (issue 23: Ctrl-C in
    ``bench --quick`` during a compile went on to numba's ``RuntimeError`` on its half-made
    library, a 123-line traceback and exit 1). Such an interrupt is not printed but delivered
    again from another thread (it runs in the main thread where Python code resumes), and an
    exception that ends a command after a signal arrived is the interruption, not a bug."""

    def __init__(self) -> None:
        self.signum: int | None = None

    def install(self) -> None:
        signal.signal(signal.SIGTERM, self._handle)
        if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            signal.signal(signal.SIGINT, self._handle)
        sys.unraisablehook = self._unraisable

    def _handle(self, signum: int, frame: FrameType | None) -> NoReturn:
        self.signum = signum  # SIGTERM (kill, a service manager, SLURM) stops as Ctrl-C does
        raise KeyboardInterrupt

    def _unraisable(self, unraisable: Any) -> None:
        """``sys.unraisablehook``: an interrupt that could not propagate is raised again, a
        moment later, in the main thread; anything else is printed as Python would."""
        try:
            if self.signum is not None and issubclass(unraisable.exc_type, KeyboardInterrupt):
                self._deliver_again()
                return
        except KeyboardInterrupt:  # the re-delivered one, landed in this hook: once more
            self._deliver_again()
            return
        sys.__unraisablehook__(unraisable)

    def _deliver_again(self) -> None:
        assert self.signum is not None
        timer = threading.Timer(REDELIVER_S, _thread.interrupt_main, args=(self.signum,))
        timer.daemon = True
        timer.start()

    def quiet(self) -> None:
        """Ignore further signals: the command has ended and says so (a second Ctrl-C while
        the last line is printed must not add a traceback)."""
        for signum in (signal.SIGTERM, signal.SIGINT):
            if signal.getsignal(signum) == self._handle:
                signal.signal(signum, signal.SIG_IGN)


def main(argv: Sequence[str] | None = None) -> None:
    stop = _Stop()
    stop.install()
    try:
        try:
            code = run(argv)
        except SystemExit as exc:  # argparse: --help, usage errors
            code = exc.code if isinstance(exc.code, int) else 2
        except BrokenPipeError:  # e.g. piped into `head`
            code = 0
        except Exception:
            if stop.signum is None:
                raise  # a bug: keep its traceback
            raise KeyboardInterrupt from None  # what failed after a signal failed because of it
    except KeyboardInterrupt:
        stop.quiet()
        print("partfeeder: interrupted", file=sys.stderr)
        _exit_holding_the_interrupted_frames(130)
    stop.quiet()
    exit_now(code)


def _exit_holding_the_interrupted_frames(code: int) -> NoReturn:
    """End the process from inside the ``except`` block, its exception (and so every frame
    the interrupt unwound) still alive, with the cyclic collector off: an interrupt that lands
    mid-compile leaves numba's half-built LLVM objects in those frames, and freeing them runs
    llvmlite's disposers on inconsistent state, a segmentation fault (exit -11 instead of 130,
    seen once in CI's SIGTERM test). The process is ending; nothing of them is needed."""
    gc.disable()
    exit_now(code)


if __name__ == "__main__":
    main()
