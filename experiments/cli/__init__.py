"""The ``partfeeder`` command line: the top of ``experiments``, above the jobs it runs.

``entry`` builds the parser from ``registry`` (one line per subcommand) and reports bad input.
One small module per subcommand declares its flags and runs its job, importing the job (and
numba, OMPL, matplotlib) only when it runs: ``plan``, ``simulate``, ``draw``, ``calibrate``,
``bench``, ``feasibility``, ``run_sweep`` (``partfeeder run``) and ``report``. Below them:
``scenes`` reads ``--design``/``--scene``, ``usage`` holds the shared checks and
``UsageError``, ``console`` keeps OMPL's log and nanobind's exit report away from users,
``kernels`` compiles the numba kernels once, before a job's workers start, and says so.
"""

from experiments.cli.entry import main, run

__all__ = ["main", "run"]
