"""Peer engines the benchmarks compare the levels with; never used by the levels themselves.
``mujoco_reference``: MuJoCo (optional; ``pip install 'partfeeder[mujoco]'``)."""
