"""The compiled build of a feeder gives what the numpy and shapely build gave (issue 21, "the
cost of a trial"): the same walls bit for bit, the same first pair of crossing walls, and a
clearance shortcut that never clears a part shapely finds within 1e-9 of a wall.

References: :func:`feeders.feeder.walls_reference` (the numpy walls as they were), shapely's
intersection of every pair of edges in edge order (the crossing test as it was), shapely's
distances (the clearance), exact rational arithmetic (the fused multiply-add, the orientation).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numba
import numpy as np
import pytest
import shapely

from experiments.drop.perturbations import PARAMETER_NAMES, Perturbations, draw, toleranced
from feeders.design import PHYSICAL_BOUNDS, PRESETS, DesignParameters
from feeders.feeder import (
    DegenerateDesign,
    Edge,
    _check_crossings,
    _segments,
    build_feeder,
    interior_edges,
    walls,
    walls_reference,
)
from feeders.halton import halton_designs
from feeders.wall_kernel import (
    UNSURE,
    _fma,
    _orientation,
    first_reached,
    point_inside,
    surely_apart,
)


def _box_designs(count: int, seed: int) -> list[DesignParameters]:
    """Designs drawn uniformly from the physical bounds (clipped to +-20): most cannot be
    built, for every reason there is."""
    rng = np.random.default_rng(seed)
    low = np.array([max(PHYSICAL_BOUNDS[n][0], -20.0) for n in PARAMETER_NAMES])
    high = np.array([min(PHYSICAL_BOUNDS[n][1], 20.0) for n in PARAMETER_NAMES])
    return [
        DesignParameters.from_vector(list(low + (high - low) * rng.uniform(size=12)))
        for _ in range(count)
    ]


def _made_designs() -> list[DesignParameters]:
    """Every preset made to 1% and to 10% tolerance, and Halton designs."""
    made = [
        toleranced(d, draw(Perturbations(tolerance=t), 5, i).design_factors)
        for d in PRESETS.values()
        for t in (0.01, 0.1)
        for i in range(10)
    ]
    return made + halton_designs(100, seed=4)


def _ring(points: np.ndarray) -> list[Edge]:
    n = len(points)
    return [
        Edge(tuple(points[i]), tuple(points[(i + 1) % n]), f"edge {i}", (f"p{i}",))
        for i in range(n)
    ]


def _star(rng: np.random.Generator, n: int) -> np.ndarray:
    """A random star-shaped ring, counter-clockwise: left and right turns, sharp spikes."""
    angles = np.sort(rng.uniform(0.0, 2 * math.pi, n))
    radii = rng.uniform(0.2, 5.0, n)
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


def _assert_same_walls(edges: list[Edge]) -> None:
    new, old = walls(edges), walls_reference(edges)
    assert len(new) == len(old)
    for a, b in zip(new, old, strict=True):
        assert a.shape == b.shape and np.array_equal(a, b)


def test_walls_of_designs_are_the_numpy_walls_bit_for_bit() -> None:
    """Made presets, Halton designs and designs from the whole box, buildable or not."""
    for design in _made_designs() + _box_designs(300, seed=6):
        _assert_same_walls(interior_edges(design))


def test_walls_of_random_rings_are_the_numpy_walls_bit_for_bit() -> None:
    """Rings with sharp right turns clip every wall twice, some down to a sliver."""
    rng = np.random.default_rng(7)
    for _ in range(400):
        _assert_same_walls(_ring(_star(rng, int(rng.integers(3, 16)))))


def _crossing_reference(edges: list[Edge]) -> str | None:
    """The message of the first pair of edges, in edge order, whose shapely intersection is
    not empty and is not the shared end of adjacent edges."""
    n = len(edges)
    for i in range(n):
        for j in range(i + 1, n):
            inter = shapely.intersection(
                shapely.LineString([edges[i].start, edges[i].end]),
                shapely.LineString([edges[j].start, edges[j].end]),
            )
            if inter.is_empty:
                continue
            if (j == i + 1 or (i == 0 and j == n - 1)) and inter.geom_type == "Point":
                continue
            return f"walls cross: the {edges[i].label} meets the {edges[j].label}"
    return None


def _crossing(edges: list[Edge]) -> str | None:
    try:
        _check_crossings(edges, _segments(edges))
    except DegenerateDesign as error:
        return error.reason
    return None


@pytest.mark.parametrize("grid", [None, 0.5])
def test_the_first_crossing_pair_is_shapelys(grid: float | None) -> None:
    """Random rings, simple or tangled; on a grid of 0.5 edges touch, end on each other and
    run along each other (exact zeros of the orientation, which shapely decides)."""
    rng = np.random.default_rng(8)
    found = clear = 0
    for k in range(600):
        n = int(rng.integers(3, 10))
        points = _star(rng, n) if k % 3 == 0 else rng.uniform(-3.0, 3.0, (n, 2))
        if grid is not None:
            points = np.round(points / grid) * grid
            keep = np.any(points != np.roll(points, 1, axis=0), axis=1)
            points = points[keep]
            if len(points) < 3:
                continue
        edges = _ring(points)
        expected = _crossing_reference(edges)
        assert _crossing(edges) == expected
        found += expected is not None
        clear += expected is None
    assert found > 50 and clear > 50


def test_a_ring_whose_pairs_were_all_certain_is_a_valid_polygon() -> None:
    """What lets the build skip shapely's validity test: no crossing among pairs the
    kernel decided alone makes the ring a valid polygon of positive area."""
    rng = np.random.default_rng(13)
    skipped = 0
    for k in range(600):
        n = int(rng.integers(3, 10))
        points = _star(rng, n) if k % 2 == 0 else rng.uniform(-3.0, 3.0, (n, 2))
        edges = _ring(points)
        try:
            decided = _check_crossings(edges, _segments(edges))
        except DegenerateDesign:
            continue
        if decided:
            skipped += 1
            polygon = shapely.Polygon(points)
            assert polygon.is_valid and polygon.area > 0
    assert skipped > 100


def test_the_tip_is_inside_where_shapely_says_so() -> None:
    """Points inside, outside, on edges and at vertices of random rings (on a grid: exact
    boundary cases): wherever the kernel decides, it decides as shapely's ``contains``."""
    rng = np.random.default_rng(14)
    decided = 0
    for _ in range(300):
        points = np.round(_star(rng, int(rng.integers(3, 12))) * 4) / 4
        keep = np.any(points != np.roll(points, 1, axis=0), axis=1)
        points = points[keep]
        if len(points) < 3 or not shapely.Polygon(points).is_valid:
            continue
        segments = _segments(_ring(points))
        polygon = shapely.Polygon(points)
        for x, y in np.round(rng.uniform(-5.0, 5.0, (20, 2)) * 4) / 4:
            inside = point_inside(segments, x, y)
            if inside != UNSURE:
                decided += 1
                assert bool(inside) == polygon.contains(shapely.Point(x, y))
    assert decided > 2000


def test_the_first_edge_the_tip_reaches_is_shapelys() -> None:
    """For discs about random rings, every edge the kernel names as reached is within r by
    shapely's distance, and the first one shapely finds within r beyond ``tol`` is named."""
    rng = np.random.default_rng(15)
    tol = 1e-9
    for _ in range(300):
        points = _star(rng, int(rng.integers(3, 12)))
        segments = _segments(_ring(points))
        lines = shapely.linestrings(segments)
        skip = rng.uniform(size=len(points)) < 0.3
        x, y = rng.uniform(-3.0, 3.0, 2)
        r = rng.uniform(0.05, 2.0)
        distances = shapely.distance(lines, shapely.Point(x, y))
        i, status = first_reached(segments, x, y, r, skip, 0, tol)
        reached = [k for k in range(len(points)) if not skip[k] and distances[k] <= r]
        if status == UNSURE:
            assert abs(distances[i] - r) <= 2 * tol
            continue
        assert i == (reached[0] if reached else -1)


def test_crossing_walls_of_designs_are_named_as_shapely_names_them() -> None:
    found = 0
    for design in _box_designs(600, seed=9) + _made_designs():
        edges = interior_edges(design)
        expected = _crossing_reference(edges)
        assert _crossing(edges) == expected
        found += expected is not None
    assert found > 10


# One design from the box per reason, with the numpy and shapely build's reason and
# parameters (recorded before the kernels, issue 21).
RECORDED_REASONS = (
    (
        (
            8.654735990815036,
            8.560260023573987,
            8.110233987843422,
            5.302782592187883,
            -18.459870818517494,
            17.858631217842536,
            4.551667641884073,
            -19.89476985494801,
            18.208143561316756,
            4.924169341435402,
            0.44685068815641127,
            1.2874128471734905,
        ),
        "walls cross: the underside of the lip meets the left cavity wall",
        ("gx", "gy", "b", "e"),
    ),
    (
        (
            0.8699590416190169,
            4.410886470669042,
            8.177037747448075,
            8.233793320526495,
            -9.670893341619808,
            -15.318404660997347,
            12.560260770004476,
            -0.08530366669951306,
            4.965583897733438,
            3.8856639184443336,
            1.52837591686072,
            0.8687104129381071,
        ),
        "the lip (g.y = 4.96558) is not above the cavity floor (c = 8.17704)",
        ("gy", "c"),
    ),
    (
        (
            7.384644715076796,
            9.92796885404121,
            0.3012749637532397,
            12.019655282098746,
            -0.7024592080578458,
            -15.306537046267326,
            -11.075940200243188,
            2.009135559334915,
            14.44654621439592,
            2.768234552820198,
            0.8548509508175741,
            0.12838006255191753,
        ),
        "the left cavity wall (e = -0.702459) is not left of the exit chute (-b/2 = -4.96398)",
        ("e", "b"),
    ),
    (
        (
            4.217356361947158,
            4.028993987528992,
            9.633892562820304,
            1.1848447473350139,
            -1.475506631567601,
            16.33277969688907,
            3.992010003079155,
            -12.510838101811244,
            15.826086677441836,
            0.8159932358343939,
            0.5004543345750929,
            1.0634937829247335,
        ),
        "input chute length d = 1.18484 cannot hold the part (length 2.2)",
        ("d",),
    ),
    (
        (
            8.101887998215068,
            5.094442638580652,
            5.074810993396169,
            18.347942299645393,
            -12.515894525122738,
            11.2760637315635,
            9.182654730515956,
            9.493713704633542,
            9.11289186742098,
            3.429814740177806,
            1.3068561448127445,
            0.49968878839808845,
        ),
        "the protuberance tip f = (11.2761, 9.18265) lies inside a wall (input chute floor)",
        ("fx", "fy", "gx", "gy", "d", "theta"),
    ),
    (
        (
            0.4778911838588617,
            7.449455927118276,
            2.643461110644502,
            1.3106314283806444,
            -16.417973230912462,
            10.03621076374641,
            16.348180988754592,
            11.01570625947998,
            5.695995392037041,
            2.4877508413122986,
            0.18492198324870657,
            0.6881904121297777,
        ),
        "input chute width a = 0.477891 is not wider than the part (0.7)",
        ("a",),
    ),
    (
        (
            2.6155098834957946,
            0.3645992420640081,
            2.9120038868152562,
            18.574899016270546,
            -9.412260475101315,
            -9.045860883172745,
            -15.441278703054051,
            15.912638082540482,
            1.8299775654255868,
            0.20115850403688704,
            0.17499574572096716,
            1.1945928344645853,
        ),
        "exit chute width b = 0.364599 is not wider than the part (0.7)",
        ("b",),
    ),
    (
        (
            1.239462596122205,
            2.8012678976564973,
            4.84690594038057,
            7.937144530704879,
            -15.143763639427114,
            -1.386727246003101,
            -0.6222352840793377,
            7.9454150977003515,
            19.95252639845034,
            3.1735709923997626,
            0.12235662648681588,
            0.2801002479649596,
        ),
        "the protuberance (f, r = 3.17357) reaches the exit chute right wall",
        ("fx", "fy", "r", "b"),
    ),
    (
        (
            7.921907872545151,
            4.403758288749469,
            2.232706782255761,
            17.790377951734573,
            -11.146922500729474,
            13.398451866592524,
            -16.67541075638713,
            -19.106169370907104,
            2.3779265712105335,
            4.601739781012435,
            1.0435383501517088,
            1.0842515872544214,
        ),
        "walls cross: the underside of the lip meets the left chamfer",
        ("gx", "gy", "b", "c", "alpha"),
    ),
    (
        (
            6.656432465357025,
            6.482559296136551,
            4.578089423120181,
            19.923100594458603,
            -18.213886203624718,
            -2.7539118709197794,
            6.951171627993947,
            -14.300067464185688,
            9.428333641891676,
            2.367336275300619,
            0.9673762584367761,
            1.2421905329325704,
        ),
        "walls cross: the underside of the lip meets the cavity floor (left)",
        ("gx", "gy", "b", "c", "e"),
    ),
    (
        (
            9.01218913013057,
            2.376204234407251,
            1.005803204046125,
            11.11798614415976,
            -2.388820284746366,
            15.795204900320641,
            14.581299221117739,
            14.267734315772564,
            6.506488874263168,
            2.258654426466714,
            0.9803441253417171,
            1.019114940893153,
        ),
        "the part does not fit at the top of the input chute (heavy_leading)",
        ("a", "d", "theta"),
    ),
    (
        (
            9.058086486966758,
            3.0723684019408872,
            5.17227157596993,
            3.167280566709526,
            -11.813089622832095,
            -1.8903648860238604,
            0.7149234834882598,
            -11.412664625660636,
            7.371898669764394,
            1.506841317038608,
            1.1573620454149396,
            0.09773345738520253,
        ),
        "walls cross: the input chute cap meets the cavity roof",
        ("a", "d", "theta", "e", "gy"),
    ),
)


@pytest.mark.parametrize(("values", "reason", "parameters"), RECORDED_REASONS)
def test_degenerate_designs_give_the_same_reason_as_before(
    values: tuple[float, ...], reason: str, parameters: tuple[str, ...]
) -> None:
    with pytest.raises(DegenerateDesign) as error:
        build_feeder(DesignParameters.from_vector(list(values)))
    assert (error.value.reason, error.value.parameters) == (reason, parameters)


def test_a_part_surely_apart_is_more_than_the_gap_from_every_piece() -> None:
    """Random squares against random convex pieces and a disc, some touching: wherever the
    kernel says apart, shapely's distances exceed the gap; and it says so for most of those
    clearly apart."""
    rng = np.random.default_rng(10)
    gap, slack = 1e-9, 1e-9
    said = clear = 0
    for _ in range(3000):
        square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        angle = rng.uniform(0, 2 * math.pi)
        rotation = np.array(
            [[math.cos(angle), math.sin(angle)], [-math.sin(angle), math.cos(angle)]]
        )
        shape = square @ rotation + rng.uniform(-1.0, 1.0, 2)
        piece = _star(rng, 3) * 0.3 + rng.uniform(-2.5, 2.5, 2)
        piece = np.array(shapely.convex_hull(shapely.MultiPoint(piece)).exterior.coords)[:-1]
        if rng.uniform() < 0.2:  # a piece touching the square's corner, or nearly
            piece = piece - piece[0] + shape[0] + rng.choice([0.0, 1e-10, 1e-8]) * np.ones(2)
        disc = np.array([*rng.uniform(-3.0, 3.0, 2), rng.uniform(0.1, 1.0)])
        pieces = np.zeros((1, 16, 2))
        pieces[0, : len(piece)] = piece
        apart = surely_apart(shape[None], pieces, np.array([len(piece)]), disc, gap, slack)
        polygon = shapely.Polygon(shape)
        truth = min(
            shapely.distance(polygon, shapely.Polygon(piece)),
            shapely.distance(polygon, shapely.Point(disc[:2])) - disc[2],
        )
        if apart:
            said += 1
            assert truth > gap
        clear += truth > 1e-6
    assert said > 0.95 * clear > 100


@numba.njit
def _fused(a: float, b: float, c: float) -> float:
    return _fma(a, b, c)


def test_fma_rounds_once() -> None:
    rng = np.random.default_rng(11)
    unfused = 0
    for a, b, c in rng.normal(size=(2000, 3)) * 10.0 ** rng.integers(-8, 8, (2000, 3)):
        exact = float(Fraction(float(a)) * Fraction(float(b)) + Fraction(float(c)))
        assert _fused(a, b, c) == exact
        unfused += a * b + c != exact
    assert unfused > 100  # rounding twice differs: the test can tell


def test_a_certain_orientation_is_the_exact_one() -> None:
    """Near-collinear triples (on a line, then nudged by an ulp or so): every sign the
    filter calls certain is the sign of the exact determinant, and the exact zeros are never
    called otherwise."""
    rng = np.random.default_rng(12)
    certain = 0
    for _ in range(5000):
        a, b = rng.uniform(-5.0, 5.0, (2, 2))
        c = a + rng.uniform(-2.0, 2.0) * (b - a)
        c = c + rng.choice([0.0, 1e-16, 1e-15, 1e-12]) * rng.normal(size=2)
        turn, sure = _orientation(a[0], a[1], b[0], b[1], c[0], c[1])
        fa, fb, fc = ([Fraction(float(x)) for x in p] for p in (a, b, c))
        det = (fa[0] - fc[0]) * (fb[1] - fc[1]) - (fa[1] - fc[1]) * (fb[0] - fc[0])
        exact = (det > 0) - (det < 0)
        if sure:
            certain += 1
            assert turn == exact
    assert certain > 1000
