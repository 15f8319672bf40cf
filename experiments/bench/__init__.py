"""Benchmarks of the levels (``partfeeder bench``): measure, never assert.

``timing`` holds what every benchmark shares (repeats, statistics, where it was measured);
``geometric``, ``kinematic`` and ``dynamic`` measure one level each. ``peers`` holds the other
engines a benchmark compares with (MuJoCo), kept apart from the product code they measure.
"""
