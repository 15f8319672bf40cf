"""The agreement suite: the same perturbed passive drops of feeder designs in partfeeder's
dynamic level, MuJoCo and pymunk, and how far they agree (issue 26).

Modules, one job each: :mod:`.designs` (the design set and how it is named), :mod:`.ending`
(the passive drop's end rule and outcome, applied to any engine's states), :mod:`.lip` (the
part's speed just past the input chute's lip against the Coulomb sliding closed form),
:mod:`.drops` (one drop in one engine), :mod:`.suite` (the same draws in every engine),
:mod:`.tables` (success fractions, outcome classes, agreement, verdicts, lip ratios) and
:mod:`.report` (Markdown, JSON, PNG). The peers' models of a feeder are in
:mod:`experiments.bench.peers` (walls as an outline chain in pymunk, convex prisms and a sphere
pin in MuJoCo).
"""
