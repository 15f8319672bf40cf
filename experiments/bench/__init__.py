"""Benchmarks (``partfeeder bench``): measure, never assert.

``suite`` runs the sections and writes the JSON, figures (``figures``) and Markdown
(``summary``, with ``comparisons``' ratios and goals): ``work_precision`` (the analytic scenes
of ``analytic`` against the closed forms of ``closed_forms``, on every engine of ``engines``),
``speed`` (per check, step, LCP, drop; the skips), ``feeder_convergence`` (what converges in
the feeder's drops) and ``ladder_cost`` (what each rung buys). ``timing`` holds what every
benchmark shares; ``geometric`` and ``kinematic`` are one level's detailed text reports
(``--level``). ``peers`` holds the other engines (MuJoCo, pymunk), kept apart from the product
code they are compared with.
"""
