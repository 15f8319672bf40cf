"""Tolerance margins of a feeder design: per design parameter, friction and part dimension,
the interval over which the probability that the part leaves heavy end down from both entries
(P(both), :mod:`experiments.drop.verdict`) stays at or above the target, the others at nominal.

``axes.py`` what may vary and over what box, ``search.py`` the bracketing search on one side
of the nominal, ``measure.py`` P(both) at one value with common random numbers, ``run.py`` the
margins of a design (its verdict first, then every axis in the worker pool), ``figure.py``
the chart. The CLI is ``partfeeder margins`` (:mod:`experiments.cli.margins`).
"""
