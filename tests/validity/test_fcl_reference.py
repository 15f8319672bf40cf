"""FCL (python-fcl) and the geometry kernel, two independent implementations, agree.

Band: poses whose kernel signed distance is within ``FCL_TOLERANCE_BAND`` (1e-6 length
units) of zero are excluded and counted: FCL's GJK decides contact with a tolerance of that
order (see :mod:`validity.fcl_reference`). Outside it the verdicts must be identical.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from feeders.design import PRESETS
from feeders.feeder import build_feeder
from feeders.part import Peg
from feeders.scene import Scene
from feeders.shapes import Obstacles
from validity.fcl_reference import FCL_TOLERANCE_BAND, FclScene
from validity.geometric import GeometricLevel
from validity.pose_samples import cross_check_poses

N_POSES = 6000


@functools.cache
def _table3() -> Scene:
    return build_feeder(PRESETS["table3"], name="table3")


def test_fcl_agrees_with_kernel_on_table3() -> None:
    """6,000 seeded poses of table3 (half uniform, half in contact within 1e-1..1e-11 of a
    wall): FCL's collision verdict equals the kernel's (clearance < 0) outside the band."""
    scene = _table3()
    level = GeometricLevel(scene)
    reference = FclScene(scene)
    poses = cross_check_poses(scene, N_POSES, 2024)
    clearance = np.array([level.clearance(p) for p in poses])
    fcl_hit = np.array([reference.penetrates(p) for p in poses])
    outside = np.abs(clearance) >= FCL_TOLERANCE_BAND
    n_out = int(outside.sum())
    n_pen = int((outside & (clearance < 0)).sum())
    disagree = outside & (fcl_hit != (clearance < 0))
    counts = (
        f"{N_POSES} poses, {N_POSES - n_out} in the band |d| < {FCL_TOLERANCE_BAND:g} "
        f"(excluded), {n_out} compared: {n_pen} penetrating, {n_out - n_pen} clear (kernel)"
    )
    assert min(n_pen, n_out - n_pen) >= 0.1 * n_out, f"unbalanced sample; {counts}"
    assert not disagree.any(), (
        f"{counts}; {int(disagree.sum())} disagreements, kernel distances "
        f"{clearance[disagree][:5]} at poses {poses[disagree][:5].tolist()}"
    )


@pytest.mark.parametrize(
    ("pose", "expected"),
    [
        ((0.0, 0.0, 0.0), False),  # 0.5 below the wall, 1.25 left of the disc
        ((2.0, 0.0, 0.0), True),  # disc centre inside the part: depth 0.25 + 0.5
        ((0.0, 2.0, 0.0), True),  # inside the wall
        ((0.0, 1.0 - 0.5 - 1e-3, 0.0), False),  # 1e-3 below the wall's underside
        ((0.0, 1.0 - 0.5 + 1e-3, 0.0), True),  # 1e-3 into the wall
    ],
)
def test_fcl_simple_cases(pose: tuple, expected: bool) -> None:
    """Hand-made cases: a wall y in [1, 3] (x in [-5, 5]) and a disc of radius 0.5 at (2.5,
    0); the part (2 x 1, centre of mass 0.25 toward +x from the centre) at yaw 0. The
    centre of mass off the box centre is what ``FclScene`` must account for: at (2, 0) the
    part spans x in [0.75, 2.75] and reaches past the disc's centre."""
    wall = np.array([[-5.0, 1.0], [5.0, 1.0], [5.0, 3.0], [-5.0, 3.0]])
    scene = dataclasses.replace(
        _table3(),
        obstacles=Obstacles((wall,), np.array([[2.5, 0.0, 0.5]])),
        part=Peg.two_density(length=2.0, width=1.0, heavy_fraction=0.75),
    )
    assert FclScene(scene).penetrates(pose) is expected
    assert (GeometricLevel(scene).clearance(pose) < 0) is expected


def test_fcl_accounts_for_centre_of_mass_offset() -> None:
    """The part's box is centred 0.25 behind the centre of mass (toward -x at yaw 0): its
    right end is at x + 0.75 and its left at x - 1.25. A wall face at x = 1 is touched by
    the right end at x = 0.25; at x = 0.25 - 1e-3 FCL sees no collision, at 0.25 + 1e-3 it
    does, and turned by pi (the long end now to the right) it collides already at x = 0."""
    wall = np.array([[1.0, -5.0], [3.0, -5.0], [3.0, 5.0], [1.0, 5.0]])
    scene = dataclasses.replace(
        _table3(),
        obstacles=Obstacles((wall,), np.zeros((0, 3))),
        part=Peg.two_density(length=2.0, width=1.0, heavy_fraction=0.75),
    )
    reference = FclScene(scene)
    assert not reference.penetrates((0.25 - 1e-3, 0.0, 0.0))
    assert reference.penetrates((0.25 + 1e-3, 0.0, 0.0))
    assert reference.penetrates((0.0, 0.0, np.pi))
    assert not reference.penetrates((-0.25 - 1e-3, 0.0, np.pi))
