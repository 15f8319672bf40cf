"""``partfeeder stress``: random cases in and near contact at every level, measured
independently (shapely, energy sums), with replayable files of the cases that break a bound.

Modules: ``case`` (a case as plain data), ``scenes`` (free-form scene families), ``placement``
(poses in and near contact), ``parts`` (the composite parts of the cases, issue 24),
``generate`` (cases from a seed), ``measures`` (independent
measures), ``bounds`` (the tolerances and the verdict), ``runner`` (one case's record),
``pool`` (worker processes), ``report`` (summary, table, case files), ``command`` (the CLI).
"""

from experiments.stress.command import add_arguments, run

__all__ = ["add_arguments", "run"]
