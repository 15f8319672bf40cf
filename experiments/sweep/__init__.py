"""The main job (``partfeeder run``): Halton designs climb the ladder of levels (Sec. 4).

``config`` reads and checks the experiment config; ``job`` is one design at one level, from
plain data to plain data (what workers run); ``ladder`` climbs: survivors go up, the holdout
climbs every rung, results are stored as they come and a sweep resumes; ``executors`` run jobs
in local processes or on Dask; ``results_db`` is the SQLite store; ``summary`` computes the
statistics (survivors, pruning precision and recall, speed-up); ``report`` writes the HTML page
with ``report_figures``, ``report_html`` and ``report_verdicts``, on the shared pieces of
:mod:`experiments.report_kit`.
"""
