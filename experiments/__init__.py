"""What users run: the ``partfeeder`` command and the jobs behind it, one package per job.

Imports go one way, top to bottom, and no job imports a sibling job:

* ``cli``: the command line (one module per subcommand, registered in ``cli.registry``);
* jobs: ``sweep`` (the main job: Halton designs up the ladder of levels), ``verdicts`` (levels
  judged against the paper's verdicts and against each other), ``drop`` (the passive drop of
  the part through a feeder), ``bench`` (speed of the levels, and the peer engines compared
  with, under ``bench.peers``);
* shared at the bottom: ``pictures`` (scenes, parts, trees, the design atlas),
  ``proportions`` (statistics of fractions) and ``names`` (the names users type).

Data: ``configs/`` (the sweep's shipped configs) and ``scenes/`` (example scenes).
"""
