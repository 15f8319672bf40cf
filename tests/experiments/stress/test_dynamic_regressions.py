"""Dynamic-level faults the full stress run (seed 0, 10,000 cases) found, kept as replayable
cases (the files under ``cases/`` are what ``partfeeder stress`` wrote for them, with the
record of the code that failed). Each is run again and must now keep every hard bound; the
references are the suite's own independent measures (shapely depths, energy sums from the
recorded states), not the level's telemetry."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from experiments.stress.bounds import vacuous
from experiments.stress.report import read_case
from experiments.stress.runner import record_of

CASES = Path(__file__).parent / "cases"


def _rerun(name: str) -> tuple[dict, dict]:
    case, stored = read_case(CASES / f"case-0-{name}-dynamic.yaml")
    return record_of(case), stored


def test_part_wedged_between_two_walls_is_not_spun_up():
    """Case 2606: a part started 1.1e-3 into two walls whose contacts cannot both separate by a
    translation. The psi/h push-out of the velocity spun it to 466 rad/s and 300 length/s
    (energy gain 2.8e6); the pose correction adds no kinetic energy."""
    record, stored = _rerun("002606")
    assert stored["energy_gain"] > 1e6 and "energy" in stored["hard"]  # the old code's record
    assert record["hard"] == []
    assert record["energy_gain"] == 0.0
    assert record["push_out"] <= record["push_out_allowed"]


def test_part_pushed_by_a_wrench_into_an_overlap_gains_no_energy():
    """Case 7007: a wrench presses a part that starts 8.8e-3 deep; with the push-out in the
    velocity it gained 800 times the allowed energy."""
    record, stored = _rerun("007007")
    assert "energy" in stored["hard"]
    assert record["hard"] == []


def test_corner_inside_a_piece_next_to_a_seam_is_pushed_to_the_near_surface():
    """Case 1682 (h = 6e-5): a corner 8.4e-3 inside a non-convex obstacle, in one convex piece
    next to a seam. Its depth was read to the far surface line of its own piece (0.31), so the
    contact pushed the wrong way and the part sank under gravity (to 0.025 deep, growing);
    the depth in the whole solid pushes it out."""
    record, stored = _rerun("001682")
    assert "penetration" in stored["hard"]
    assert record["hard"] == []
    assert record["max_depth"] <= record["start_depth"] + 1e-9


def test_far_corner_outside_the_margin_is_caught_within_a_large_step():
    """Case 2801 (h = 0.057): a box resting on one corner, its other corner 6.5e-3 above the
    floor. The contact margin allowed for the part's speed but not for what gravity adds
    within the step (h^2 g = 0.03), so the far corner fell 0.028 into the floor unseen."""
    record, stored = _rerun("002801")
    assert "penetration" in stored["hard"]
    assert record["hard"] == []
    assert record["max_depth"] < 1e-3


@pytest.mark.parametrize("name", ["004358"])
def test_large_step_overlap_stays_within_the_linearisation_bound(name):
    """Case 4358 (h = 0.045, a part spinning against discs): the overlap reaches 0.18, within
    the first-order scheme's one-step error at that h (experiments.stress.bounds.
    DYNAMIC_PENETRATION: a face turning 0.9 rad against discs up to 1.2 in radius). That
    allowance (about 3) is more than the part's size (0.83): the report counts the case as
    vacuous (issue 35), so its pass says nothing about the contacts."""
    record, _ = _rerun(name)
    assert record["hard"] == []
    assert record["max_depth"] > 0.05  # the step really is that coarse
    assert vacuous(record) and record["step_error"] > record["part_size"]


OPEN = sorted((CASES / "open").glob("*.yaml"))


@pytest.mark.xfail(
    strict=True,
    reason="open, large steps only: case 0-9401 (issue 11) ends straddling a thin piece, 0.044 "
    "deep at h = 3.9e-2, within the bound at h <= 4e-3, where the contacts catch it; case "
    "21-443 (discs, flush: crosses a piece in step 7 "
    "at h = 8.9e-2), found by a 1,000-case run of seed 21, keeps every bound at h <= 4e-2",
)
@pytest.mark.parametrize("path", OPEN, ids=[p.stem for p in OPEN])
def test_open_cases_of_the_full_run(path):
    """Hard failures left in the full runs; strict: each passes once the fault is fixed, and
    its mark must go."""
    case, _ = read_case(path)
    assert record_of(case)["hard"] == []


def _rerun_at(path: Path, h: float) -> dict:
    case, _ = read_case(path)
    return record_of(dataclasses.replace(case, h=h))


@pytest.mark.parametrize("h", [None, 1e-3, 1e-4])
@pytest.mark.parametrize("name", ["0-003599", "0-001034"])
def test_a_corner_resting_on_a_spike_tip_does_not_slip_through_it(
    name: str, h: float | None
) -> None:
    """Case 3599 of seed 0: a part whose corner rests on the tip of a star's spike passed the
    tip in one step; then neither shape had a vertex inside the other and the part sank about
    1e-4 a step, to 0.078 deep (at its own h, 7e-3, and at 1e-3 and 1e-4). Case 1034 (h =
    5e-3): the same straddle of a thin sliver. The separating-axis test sees the overlap that
    vertex tests miss. Reference: shapely's depths (the suite's measure)."""
    path = CASES / f"case-{name}-dynamic.yaml"
    case, stored = read_case(path)
    assert stored is not None and "penetration" in stored["hard"]  # the old code's record
    record = _rerun_at(path, h or case.h)
    assert record["hard"] == []
    assert record["max_depth"] <= record["depth_allowed"]


@pytest.mark.parametrize("h", [None, 1e-3, 2.5e-4])
def test_a_part_does_not_straddle_a_thin_piece(h: float | None) -> None:
    """Case 1061 of seed 7: a part crossed a thin piece of a non-convex obstacle, 0.189 deep at
    its h (0.032) and at 1e-3 and 2.5e-4, with no vertex of either inside the other."""
    path = CASES / "case-7-001061-dynamic.yaml"
    record = _rerun_at(path, h or read_case(path)[0].h)
    assert record["hard"] == []


@pytest.mark.parametrize("h", [None, 1e-3])
def test_a_star_vertex_does_not_end_inside_the_part(h: float | None) -> None:
    """Case 4193 of seed 7: a star's 73 degree vertex ended inside the part at rest, 0.171
    deep, at its h (4e-3) and at 1e-3."""
    path = CASES / "case-7-004193-dynamic.yaml"
    record = _rerun_at(path, h or read_case(path)[0].h)
    assert record["hard"] == []


def test_a_corner_touching_a_corner_is_searched_again_next_step() -> None:
    """Case 4190 of seed 0 (h = 1.4e-5), found by the first run of the new feature rules: a
    part's corner touching an obstacle's corner (gap 1e-13) while turning into it at 20
    length/s. Its candidate contact was not kept, and the contact search still reported the
    obstacle as 0.14 away, so the stepper skipped the search for hundreds of steps while the
    corner sank 0.10 deep; a candidate not kept now bounds the clearance."""
    record, stored = _rerun("004190")[0], read_case(CASES / "case-0-004190-dynamic.yaml")[1]
    assert stored is not None and "penetration" in stored["hard"]
    assert record["hard"] == []


def test_a_corner_touching_the_floor_where_a_ramp_leaves_it_is_held_by_the_floor() -> None:
    """Case 8546 of seed 11 (h = 0.037), found by the full run of the new feature rules: a
    part's corner touching the floor (gap 2e-14) exactly where a ramp piece leaves it. Its
    nearest floor feature is a covered seam, and the floor's vertex there touched the part's
    face at its very end, so only the ramp's normal was kept and the corner sank 0.042 into
    the floor in one step. A vertex within FEATURE_SLOP of the other shape is in contact."""
    path = CASES / "case-11-008546-dynamic.yaml"
    case, stored = read_case(path)
    assert stored is not None and "penetration" in stored["hard"]
    assert record_of(case)["hard"] == []


@pytest.mark.parametrize("h", [None, 8e-3, 4e-3, 1e-3])
def test_the_shared_edge_fall_of_seed_5_keeps_the_bound(h: float | None):
    """Case 5-122 of seed 5: a corner sliding down into the foot of a piece standing on the
    floor, whose nearest floor point lay under that piece (a seam), so the floor was no
    contact and the corner went 0.034 deep at its own h = 1.6e-2 (0.028 at 8e-3) against
    0.0127 allowed (issue 35, part 1; open until the floor's face in front of the corner
    became its contact). At its own h, at 8e-3, and at the screen's (4e-3) and the verdict's
    (1e-3) steps the part lands within the bound; below 1e-3 deep at the two finer steps."""
    path = CASES / "case-5-000122-dynamic.yaml"
    record = _rerun_at(path, h or read_case(path)[0].h)
    assert record["hard"] == []
    if h is not None and h <= 4e-3:
        assert record["max_depth"] < 1e-3


@pytest.mark.parametrize("h", [4e-3, 1e-3])
@pytest.mark.parametrize("name", ["case-13-000896", "open/case-21-000443"])
def test_the_large_step_faults_of_seeds_13_and_21_keep_the_bound_at_the_screens_step(
    name: str, h: float
) -> None:
    """Cases 13-896 and 21-443 (found at their own h, 8.3e-2 and 8.9e-2): at the screen's step
    (4e-3) and the verdict's (1e-3) no hard bound breaks and the part stays within 2e-3 of the
    obstacles (shapely's depths, the suite's measure)."""
    record = _rerun_at(CASES / f"{name}-dynamic.yaml", h)
    assert record["hard"] == []
    assert record["max_depth"] < 2e-3


def test_the_large_step_overlap_of_seed_13_is_within_its_allowance_and_counted_vacuous() -> None:
    """Case 13-896 (h = 8.3e-2, a part near a convex piece, 0.051 deep) broke the issue-11 rule
    (0.049 allowed: R dtheta^2 / 2 + d^2 / (2 r), which left out the turn of the part's face
    against the piece's corners). Issue 35's allowance from the contacts it has in each step
    allows 0.096 (the errors 0.086, 5.3 % of the part's 1.61), and the overlap stays within it;
    that is above the report's 5 % rule, so the case is counted and listed as one whose bound
    says little. Reference: the closed forms of
    experiments.stress.measures.linearisation_errors and shapely's depth."""
    case, stored = read_case(CASES / "case-13-000896-dynamic.yaml")
    assert stored is not None and "penetration" in stored["hard"]  # the issue-11 rule's record
    record = record_of(case)
    assert record["hard"] == []
    assert 0.05 < record["max_depth"] <= record["depth_allowed"] < 0.1
    assert vacuous(record)
