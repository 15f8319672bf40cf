"""How the levels judge designs. ``calibration``: the geometric level's verdict on the paper's
designs against the paper's. ``feasibility``: the fraction of Halton designs feasible at one
level against another on the same designs and budgets (is one feasible set within the other?),
and ``feasibility_figure``, where they agree in design space."""
