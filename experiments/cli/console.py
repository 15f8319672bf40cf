"""Keep OMPL's console log and nanobind's exit-time leak report away from CLI users.

OMPL logs through its own handler (hidden unless ``--verbose``). At interpreter exit
nanobind reports objects it considers leaked, a wall of text on stderr after a normal run;
the CLI therefore ends its process with ``os._exit`` once its own output is flushed, which
skips that report (and nothing else the CLI needs: files are written and closed before).
"""

from __future__ import annotations

import os
import sys


def set_ompl_logging(verbose: bool) -> None:
    """OMPL's log at INFO with ``verbose``, otherwise off (OMPL is imported here, when a
    subcommand runs, not when the parser is built)."""
    from ompl import util as ou

    ou.setLogLevel(ou.LogLevel.LOG_INFO if verbose else ou.LogLevel.LOG_NONE)


def exit_now(code: int) -> None:
    """Flush our streams and end the process without the interpreter's exit hooks."""
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    finally:
        os._exit(code)
