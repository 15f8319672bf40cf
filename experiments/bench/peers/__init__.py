"""Peer engines the benchmarks compare the dynamic level with; never used by the levels.

Optional extras (``pip install 'partfeeder[bench]'``): ``mujoco_engine`` (MuJoCo) and
``pymunk_engine`` (pymunk, Chipmunk2D). Each builds the same scene from the project's own
scene objects (``rectangles`` turns the obstacles into boxes for MuJoCo) and imports its engine
lazily, so these modules import without the engines installed.
"""
