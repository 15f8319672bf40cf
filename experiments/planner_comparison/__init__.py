"""``partfeeder planners``: every OMPL control planner that runs from Python on the suite's
contact-rich problems (issue 40).

A problem is a design (a paper preset, a Halton design, a device family's design, a scene
file), a fidelity level and an entry. :mod:`.suite` reads the comparison's config,
:mod:`.unsolvable` says which problems cannot be solved at all (the necessary conditions),
:mod:`.work` plans one problem with every planner in a worker (plain data in and out),
:mod:`.profiles` holds the statistics (performance profiles, ECDFs, the bootstrap),
:mod:`.summary` turns the runs into the report's data, :mod:`.figures` draws it,
:mod:`.report` writes it (markdown, HTML, JSON) and :mod:`.run` runs the whole comparison.
"""
