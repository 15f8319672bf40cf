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
(:mod:`experiments.worker_process`).

Exit status: 0 done (whether or not a plan was found: see the output), 2 bad input: one
line on stderr, whether a subcommand found it (``UsageError``) or a reader or job below it did
(:func:`experiments.cli.errors.input_error_line`); any other exception is a bug and keeps its
traceback.
"""

from __future__ import annotations

import argparse
import signal
import sys
from collections.abc import Sequence
from types import ModuleType
from typing import NoReturn

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


def _terminate(signum: int, frame: object) -> NoReturn:
    raise KeyboardInterrupt  # SIGTERM (kill, a service manager, SLURM) stops as Ctrl-C does


def main(argv: Sequence[str] | None = None) -> None:
    signal.signal(signal.SIGTERM, _terminate)
    try:
        code = run(argv)
    except SystemExit as exc:  # argparse: --help, usage errors
        code = exc.code if isinstance(exc.code, int) else 2
    except BrokenPipeError:  # e.g. piped into `head`
        code = 0
    except KeyboardInterrupt:
        print("partfeeder: interrupted", file=sys.stderr)
        code = 130
    exit_now(code)


if __name__ == "__main__":
    main()
