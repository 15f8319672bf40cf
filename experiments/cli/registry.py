"""Every ``partfeeder`` subcommand, in one place: its name, the module that runs it, its help.

A subcommand is a module with ``add_arguments(parser)`` (its flags, on an
``argparse.ArgumentParser``) and ``run(args) -> int`` (the exit status: 0 done, 2 bad input).
Adding one is that module plus one line below. The module is imported whenever the parser is
built, so ``partfeeder --help`` too: it must import nothing heavy at module level (no numba,
OMPL or matplotlib; better no NumPy either) and import those inside ``run``.
``tests/experiments/cli/test_cli_imports.py`` holds every subcommand to that.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType


@dataclass(frozen=True)
class Subcommand:
    """``partfeeder NAME``: run by the module at dotted path ``module``; ``help`` for --help."""

    name: str
    module: str
    help: str

    def load(self) -> ModuleType:
        """The module, with its ``add_arguments`` and ``run``."""
        return importlib.import_module(self.module)


# fmt: off
SUBCOMMANDS: tuple[Subcommand, ...] = (
    Subcommand("plan", "experiments.cli.plan", "plan the part through a scene with OMPL"),
    Subcommand("simulate", "experiments.cli.simulate",
               "drop the part passively through a scene with the dynamic level"),
    Subcommand("draw", "experiments.cli.draw", "draw designs (feeder, start poses, goal region)"),
    Subcommand("calibrate", "experiments.cli.calibrate",
               "the geometric level's verdict on the paper's designs"),
    Subcommand("bench", "experiments.cli.bench",
               "work-precision diagrams, speed tables and the ladder's cost vs error"),
    Subcommand("feasibility", "experiments.cli.feasibility",
               "fraction of Halton designs feasible at level A vs level B "
               "(is A's set within B's?)"),
    Subcommand("run", "experiments.cli.run_sweep",
               "the main job: Halton designs up the ladder of levels (geometric, kinematic, "
               "dynamic) through OMPL's Benchmark; resumes when started again"),
    Subcommand("report", "experiments.cli.report", "summary and HTML report of a sweep directory"),
    Subcommand("optimize", "experiments.cli.optimize",
               "the design optimisation (Eq. 10-11), robust to perturbation; resumes when "
               "started again"),
    Subcommand("stress", "experiments.stress.command", "the numerical stress suite of the levels"),
    Subcommand("margins", "experiments.cli.margins",
               "a design's tolerance margins: per parameter, friction and part dimension"),
    Subcommand("planners", "experiments.cli.planners",
               "compare OMPL's control planners on the suite's problems at every level "
               "(performance profiles, Planner Arena's database)"),
    Subcommand("part", "experiments.cli.part",
               "a part's mass, centre of mass, inertia, area and stable resting poses"),
    Subcommand("family", "experiments.cli.family",
               "device families: 'family new NAME --part FILE' writes one made for a part"),
)
# fmt: on
