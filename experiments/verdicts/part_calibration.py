"""Calibrating what the paper does not give: the peg's length, width, mass split and friction.

The paper (Sections 3-5) never states the part's dimensions, its mass distribution or the
Coulomb coefficient mu of the feeder's walls. Its verdicts are the targets: its eleven
geometric verdicts (:data:`feeders.design.PAPER_GEOMETRIC_VERDICT`) and ``table3`` working
both ways in the dynamic model (Figs. 10-11). This module searches a grid of
(length, width, heavy fraction, mu) and measures, per grid point:

- ``table3``'s passive verdict (:func:`experiments.drop.verdict.design_verdict`, seeded
  perturbed drops, a fixed first batch so the Wilson intervals of P(both) compare across the
  grid);
- how many of the first Halton designs (seed 0) that build leave heavy end down from both
  entries in their nominal drop (no perturbation: the scene's starts);
- how many of the paper's eleven geometric verdicts the geometric level reproduces
  (:func:`experiments.verdicts.calibration.calibrate`; RRT, small budget).

The first two are the cheap columns and run on every grid point. The geometric verdicts do
not depend on mu and cost more, so they run per part shape (length, width, heavy fraction),
only for the shapes at which ``table3`` works at some mu (the candidates), and afterwards for
the shapes next to the chosen point (for the sensitivity report). A point whose ``table3``
does not work cannot be chosen, whatever its geometric verdicts.

The choice (:func:`choose`): among the *eligible* points (all eleven geometric verdicts agree
with the paper and ``table3``'s verdict is "works"), the highest Wilson lower bound of
``table3``'s P(both); ties by the number of eligible grid neighbours (points one grid step
away in one coordinate: robustness); then by the number of Halton designs working both ways;
then the higher mu (nearer the 0.2-0.4 of everyday materials); then grid order.

Grid points run in a process pool (plain data in and out, each worker builds its own part,
feeders and levels; ``spawn`` start, OMPL's log off).
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from experiments.executors.local import LocalPool, map_jobs
from experiments.executors.worker import quiet_ompl
from feeders.design import PAPER_GEOMETRIC_VERDICT

AXES = ("length", "width", "heavy_fraction", "friction")


@dataclass(frozen=True)
class GridPoint:
    """One candidate: peg ``length`` x ``width`` (length units), the heavy half's share of the
    mass (``heavy_fraction``, 0.5-1) and the walls' Coulomb ``friction`` mu."""

    length: float
    width: float
    heavy_fraction: float
    friction: float

    @property
    def shape(self) -> tuple[float, float, float]:
        """What the geometric level sees: (length, width, heavy_fraction); not mu."""
        return (self.length, self.width, self.heavy_fraction)

    def label(self) -> str:
        return f"{self.length:g} x {self.width:g}, {self.heavy_fraction:g}, mu {self.friction:g}"


@dataclass(frozen=True)
class Grid:
    """The landscape searched: every combination of the four axes' values (ascending), less
    the pegs wider than long."""

    lengths: tuple[float, ...]
    widths: tuple[float, ...]
    heavy_fractions: tuple[float, ...]
    frictions: tuple[float, ...]

    def __post_init__(self) -> None:
        ranges = {
            "lengths": (1e-3, 100.0),
            "widths": (1e-3, 100.0),
            "heavy_fractions": (0.5, 1.0),
            "frictions": (0.0, 10.0),
        }
        for name, (low, high) in ranges.items():
            values = getattr(self, name)
            if not values:
                raise ValueError(f"grid.{name} is empty; give at least one value")
            for v in values:
                if not (isinstance(v, int | float) and math.isfinite(v) and low <= v <= high):
                    raise ValueError(
                        f"grid.{name} value {v!r} is outside the allowed range [{low:g}, {high:g}]"
                    )
            if list(values) != sorted(set(values)):
                raise ValueError(f"grid.{name} = {values} must be strictly ascending")

    @property
    def axes(self) -> tuple[tuple[float, ...], ...]:
        return (self.lengths, self.widths, self.heavy_fractions, self.frictions)

    def points(self) -> list[GridPoint]:
        """Every grid point a peg can have (width <= length), in grid order."""
        return [
            GridPoint(*values) for values in itertools.product(*self.axes) if values[1] <= values[0]
        ]

    def neighbours(self, point: GridPoint) -> list[tuple[str, GridPoint]]:
        """The grid points one step away from ``point`` along one axis, with that axis' name."""
        out = []
        values = (point.length, point.width, point.heavy_fraction, point.friction)
        for k, (name, axis) in enumerate(zip(AXES, self.axes, strict=True)):
            i = axis.index(values[k])
            for j in (i - 1, i + 1):
                if 0 <= j < len(axis):
                    moved = list(values)
                    moved[k] = axis[j]
                    if moved[1] <= moved[0]:
                        out.append((name, GridPoint(*moved)))
        return out

    def to_dict(self) -> dict[str, list[float]]:
        return {k: list(v) for k, v in asdict(self).items()}


FULL_GRID = Grid((1.6, 1.8, 2.0, 2.2), (0.6, 0.7, 0.8, 1.0), (0.75, 0.9), (0.05, 0.1, 0.3))
QUICK_GRID = Grid((2.0,), (0.8,), (0.9,), (0.05, 0.3))


@dataclass(frozen=True)
class Budget:
    """What each column costs: ``halton`` first Halton designs of ``halton_seed``; ``table3``
    trials in the verdict's first batch (then batches of ``table3_batch`` up to
    ``table3_max`` while undecided) with ``verdict_seed``; ``geometric_runs`` seeded RRT runs
    of ``geometric_time`` s per orientation and design."""

    halton: int = 200
    halton_seed: int = 0
    table3: int = 100
    table3_batch: int = 20
    table3_max: int = 200
    verdict_seed: int = 0
    target: float = 0.9
    geometric_runs: int = 2
    geometric_time: float = 5.0

    def __post_init__(self) -> None:
        checks = (
            ("halton", self.halton, 1, 100_000),
            ("table3", self.table3, 1, 100_000),
            ("table3_batch", self.table3_batch, 1, 100_000),
            ("table3_max", self.table3_max, self.table3, 100_000),
            ("target", self.target, 0.0, 1.0),
            ("geometric_runs", self.geometric_runs, 1, 1000),
            ("geometric_time", self.geometric_time, 1e-3, 3600.0),
        )
        for name, value, low, high in checks:
            number = isinstance(value, int | float) and math.isfinite(value)
            if not (number and low <= value <= high):
                raise ValueError(
                    f"budget.{name} = {value!r} is outside the allowed range [{low:g}, {high:g}]"
                )


FULL_BUDGET = Budget()
QUICK_BUDGET = Budget(
    halton=12,
    table3=20,
    table3_batch=10,
    table3_max=20,
    target=0.7,
    geometric_runs=1,
    geometric_time=0.5,
)
"""A smoke run's budget (every stage runs, nothing is settled): 20 drops cannot show P > 0.9
(20/20 has lower bound 0.84), so the target is 0.7 there."""


@dataclass(frozen=True)
class PointResult:
    """The measured columns of one grid point (plain data). ``geometric_agree`` is None when
    the geometric verdicts were not run at this point's shape."""

    point: GridPoint
    halton_built: int
    halton_working: int
    table3_decision: str
    table3_both: int
    table3_drops: int
    table3_interval: tuple[float, float]
    table3_orientations: dict[str, dict[str, Any]] = field(default_factory=dict)
    geometric_agree: int | None = None
    geometric_disagree: tuple[str, ...] = ()

    @property
    def eligible(self) -> bool:
        """All eleven geometric verdicts as in the paper and ``table3`` works."""
        return self.geometric_agree == len(PAPER_GEOMETRIC_VERDICT) and (
            self.table3_decision == "works"
        )

    def to_dict(self) -> dict[str, Any]:
        out = asdict(self)
        out["eligible"] = self.eligible
        return out


# ---- the workers (plain data in and out) ----


def passive_columns(point: GridPoint, budget: Budget) -> dict[str, Any]:
    """The cheap columns of one grid point: Halton designs working both ways in their nominal
    drop, and ``table3``'s passive verdict."""
    from experiments.drop.passive import passive_drop
    from experiments.drop.verdict import VerdictSettings, design_verdict
    from feeders.design import PRESETS
    from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
    from feeders.halton import halton_designs
    from feeders.part import Peg

    part = Peg.two_density(point.length, point.width, 1.0, point.heavy_fraction)
    built = working = 0
    for design in halton_designs(budget.halton, budget.halton_seed):
        try:
            scene = build_feeder(design, part, friction=point.friction)
        except DegenerateDesign:
            continue
        built += 1
        # all() stops at the first entry that fails: it cannot change the count
        working += all(passive_drop(scene, o).success for o in ORIENTATIONS)
    settings = VerdictSettings(
        target=budget.target,
        min_drops=budget.table3,
        batch=budget.table3_batch,
        max_drops=budget.table3_max,
    )
    verdict = design_verdict(PRESETS["table3"], part, point.friction, settings, budget.verdict_seed)
    summary = verdict.to_dict()
    return {
        "halton_built": built,
        "halton_working": working,
        "table3_decision": verdict.decision,
        "table3_both": verdict.both,
        "table3_drops": verdict.drops,
        "table3_interval": tuple(verdict.both_interval),
        "table3_orientations": {
            o: {"successes": v["successes"], "interval": v["interval"]}
            for o, v in summary["orientations"].items()
        },
    }


def geometric_columns(shape: tuple[float, float, float], budget: Budget) -> dict[str, Any]:
    """The paper's eleven geometric verdicts for a peg ``shape`` (length, width, heavy
    fraction): how many agree, and the designs that do not."""
    from experiments.verdicts.calibration import calibrate
    from feeders.part import Peg

    part = Peg.two_density(shape[0], shape[1], 1.0, shape[2])
    rows = calibrate(runs=budget.geometric_runs, time_limit=budget.geometric_time, part=part)
    return {
        "geometric_agree": sum(r.agrees for r in rows),
        "geometric_disagree": tuple(r.design for r in rows if not r.agrees),
    }


# ---- the choice ----


def robustness(result: PointResult, by_point: dict[GridPoint, PointResult], grid: Grid) -> int:
    """How many of the point's grid neighbours are eligible too."""
    return sum(
        1 for _, n in grid.neighbours(result.point) if n in by_point and by_point[n].eligible
    )


def choose(results: Sequence[PointResult], grid: Grid) -> PointResult | None:
    """The defaults by the module's rule: among eligible points the highest lower bound of
    ``table3``'s P(both), then most eligible neighbours, then most Halton designs working,
    then the higher mu, then grid order. None when no point is eligible."""
    by_point = {r.point: r for r in results}
    order = {p: i for i, p in enumerate(grid.points())}
    eligible = [r for r in results if r.eligible]
    if not eligible:
        return None
    return min(
        eligible,
        key=lambda r: (
            -r.table3_interval[0],
            -robustness(r, by_point, grid),
            -r.halton_working,
            -r.point.friction,
            order.get(r.point, len(order)),
        ),
    )


RULE = (
    "Eligible: the geometric level reproduces all eleven of the paper's geometric verdicts "
    "and table3's passive verdict is *works* (both entries' Wilson 95% lower bounds above "
    "the target). Among eligible points: the highest Wilson lower bound of table3's P(both); "
    "ties broken by the number of eligible grid neighbours (one step along one axis), then by "
    "the number of Halton designs working both ways, then by the higher mu, then grid order."
)


# ---- the landscape ----


@dataclass(frozen=True)
class Landscape:
    """Every grid point's columns, the choice and the rule (plain data)."""

    grid: Grid
    budget: Budget
    results: tuple[PointResult, ...]
    chosen: PointResult | None

    def by_point(self) -> dict[GridPoint, PointResult]:
        return {r.point: r for r in self.results}

    def sensitivity(self) -> list[tuple[str, PointResult]]:
        """The chosen point's neighbours (axis moved, their columns)."""
        if self.chosen is None:
            return []
        table = self.by_point()
        return [(axis, table[n]) for axis, n in self.grid.neighbours(self.chosen.point)]

    def to_dict(self) -> dict[str, Any]:
        table = self.by_point()
        return {
            "grid": self.grid.to_dict(),
            "budget": asdict(self.budget),
            "rule": RULE,
            "chosen": None if self.chosen is None else asdict(self.chosen.point),
            "points": [
                {**r.to_dict(), "eligible_neighbours": robustness(r, table, self.grid)}
                for r in self.results
            ],
            "sensitivity": [
                {"axis": axis, **asdict(r.point), "eligible": r.eligible}
                for axis, r in self.sensitivity()
            ],
        }


def run_landscape(
    grid: Grid,
    budget: Budget,
    workers: int = 1,
    progress: Callable[[str, int], object] | None = None,
) -> Landscape:
    """Measure the grid: the cheap columns on every point, the geometric verdicts on the
    candidate shapes, choose, then the geometric verdicts on the chosen point's neighbour
    shapes. ``progress(label, new_jobs)`` is called with ``new_jobs`` > 0 when jobs are
    queued and with 0 as each finishes; ``workers`` processes (1: in this process)."""
    if workers < 1:
        raise ValueError(f"workers = {workers} must be >= 1")
    points = grid.points()
    if not points:
        raise ValueError("the grid has no peg with width <= length")
    note = progress or (lambda _label, _n: None)
    if workers == 1:
        quiet_ompl()
        return _landscape(grid, budget, points, None, note)
    with LocalPool(workers, max_attempts=1) as pool:
        return _landscape(grid, budget, points, pool, note)


def _with_budget(fn: Callable[[Any, Budget], dict], budget: Budget, item: Any) -> dict:
    return fn(item, budget)


def _gather(
    pool: LocalPool | None, fn, items: Sequence, budget: Budget, note, label: str
) -> dict[Any, dict]:
    """``{item: fn(item, budget)}`` on ``pool`` (None: here), with ``note`` as each ends."""
    note(label, len(items))
    evaluate = functools.partial(_with_budget, fn, budget)

    def ended(_index: int, _result: dict) -> None:
        note(label, 0)

    if pool is None:
        results = map_jobs(evaluate, items, 1, on_result=ended)
    else:
        results = pool.map(evaluate, items, on_result=ended)
    return dict(zip(items, results, strict=True))


def _landscape(grid, budget, points, pool, note) -> Landscape:
    cheap = _gather(pool, passive_columns, points, budget, note, "passive")
    candidates = sorted({p.shape for p in points if cheap[p]["table3_decision"] == "works"})
    geometric = _gather(pool, geometric_columns, candidates, budget, note, "geometric")

    def assemble() -> list[PointResult]:
        return [PointResult(p, **cheap[p], **geometric.get(p.shape, {})) for p in points]

    chosen = choose(assemble(), grid)
    if chosen is not None:
        around = sorted({n.shape for _, n in grid.neighbours(chosen.point)} - set(geometric))
        geometric.update(_gather(pool, geometric_columns, around, budget, note, "geometric"))
    results = assemble()
    chosen = choose(results, grid)  # the same point: the new columns are not-eligible ones
    return Landscape(grid, budget, tuple(results), chosen)


# ---- output ----


def _geometric_cell(r: PointResult) -> str:
    if r.geometric_agree is None:
        return "-"
    cell = f"{r.geometric_agree}/{len(PAPER_GEOMETRIC_VERDICT)}"
    return cell + (f" ({', '.join(r.geometric_disagree)})" if r.geometric_disagree else "")


def _row(r: PointResult, neighbours: int | None = None, axis: str | None = None) -> str:
    lo, hi = r.table3_interval
    cells = [axis] if axis is not None else []
    cells += [
        f"{r.point.length:g} x {r.point.width:g}",
        f"{r.point.heavy_fraction:g}",
        f"{r.point.friction:g}",
        _geometric_cell(r),
        f"{r.halton_working} / {r.halton_built}",
        f"{r.table3_both / r.table3_drops:.2f} [{lo:.2f}, {hi:.2f}] ({r.table3_drops})",
        r.table3_decision,
        "**yes**" if r.eligible else "no",
    ]
    if neighbours is not None:
        cells.append(str(neighbours))
    return "| " + " | ".join(cells) + " |"


def markdown(landscape: Landscape) -> str:
    """The landscape table, the rule, the choice and its neighbours, as Markdown."""
    table = landscape.by_point()
    head = (
        "| L x W | heavy fraction | mu | geometric verdicts vs paper | Halton working both ways "
        "(nominal) | table3 P(both) [95%] (drops) | table3 verdict | eligible |"
    )
    lines = [
        head + " eligible neighbours |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in landscape.results:
        lines.append(_row(r, robustness(r, table, landscape.grid)))
    lines += ["", f"Rule: {RULE}", ""]
    if landscape.chosen is None:
        lines.append("Chosen: none (no grid point is eligible).")
        return "\n".join(lines)
    lines += [
        f"Chosen: **{landscape.chosen.point.label()}**",
        "",
        "Its neighbours (one grid step along one axis):",
        "",
        "| axis moved " + head,
        "|---|---|---|---|---|---|---|---|---|",
    ]
    lines.append(_row(landscape.chosen, axis="(chosen)"))
    for axis, r in landscape.sensitivity():
        lines.append(_row(r, axis=axis))
    return "\n".join(lines)


def heatmap(landscape: Landscape, path: Path) -> Path:
    """One panel per (heavy fraction, mu): table3's lower bound of P(both) over length x
    width, each cell annotated with the Halton count and the geometric agreement; the chosen
    point framed. Written with matplotlib's Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    grid, table = landscape.grid, landscape.by_point()
    rows, cols = len(grid.heavy_fractions), len(grid.frictions)
    fig, axes = plt.subplots(
        rows, cols, figsize=(3.2 * cols + 1, 2.9 * rows + 0.6), squeeze=False, sharey=True
    )
    image = None
    for (i, hf), (j, mu) in itertools.product(
        enumerate(grid.heavy_fractions), enumerate(grid.frictions)
    ):
        ax = axes[i][j]
        values = np.full((len(grid.widths), len(grid.lengths)), np.nan)
        for (a, length), (b, width) in itertools.product(
            enumerate(grid.lengths), enumerate(grid.widths)
        ):
            r = table.get(GridPoint(length, width, hf, mu))
            if r is None:
                continue
            values[b, a] = r.table3_interval[0]
            text = f"{r.halton_working}\n{_geometric_cell(r).split(' ')[0]}"
            colour = "white" if r.table3_interval[0] < 0.6 else "black"
            ax.text(a, b, text, ha="center", va="center", fontsize=7, color=colour)
            if landscape.chosen is not None and r.point == landscape.chosen.point:
                ax.add_patch(
                    plt.Rectangle((a - 0.5, b - 0.5), 1, 1, fill=False, lw=2.5, ec="black")
                )
        image = ax.imshow(values, origin="lower", vmin=0.0, vmax=1.0, cmap="viridis")
        ax.set_xticks(range(len(grid.lengths)), [f"{v:g}" for v in grid.lengths])
        ax.set_yticks(range(len(grid.widths)), [f"{v:g}" for v in grid.widths])
        ax.set_title(f"heavy {hf:g}, mu {mu:g}", fontsize=9)
        if i == rows - 1:
            ax.set_xlabel("length")
        if j == 0:
            ax.set_ylabel("width")
    fig.suptitle(
        "table3: lower bound of P(both) (colour); cells: Halton designs working, geometric "
        "verdicts agreeing",
        fontsize=9,
    )
    if image is not None:
        fig.colorbar(image, ax=axes, shrink=0.8)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
