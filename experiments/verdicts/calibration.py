"""Calibration: the geometric level's verdict on every design printed in the paper.

The paper calls fig4, fig5a, fig5b, fig6a, fig6b, fig8a, fig8b, fig9 and table3 geometrically
feasible and fig7a, fig7b not (Sections 3-4). A design is feasible here when RRT reaches the
goal from both entry orientations in at least one of ``runs`` seeded runs within ``time_limit``
each; the fraction of runs solved per orientation is reported too.
"""

from __future__ import annotations

from dataclasses import dataclass

from feeders.design import PAPER_GEOMETRIC_VERDICT, PRESETS
from feeders.feeder import ORIENTATIONS, DegenerateDesign, build_feeder
from feeders.part import DEFAULT_PEG, Peg
from planners.plan import plan


@dataclass(frozen=True)
class CalibrationRow:
    design: str
    paper_feasible: bool
    built: bool
    reason: str
    solved: dict[str, int]
    runs: int

    @property
    def feasible(self) -> bool:
        return self.built and all(self.solved[o] > 0 for o in ORIENTATIONS)

    @property
    def agrees(self) -> bool:
        return self.feasible == self.paper_feasible


def calibrate(
    runs: int = 5,
    time_limit: float = 10.0,
    planner: str = "rrt",
    names: tuple[str, ...] | None = None,
    progress=None,
    part: Peg = DEFAULT_PEG,
) -> list[CalibrationRow]:
    """Plan every named preset ``runs`` times per orientation (seeds 1..runs)."""
    rows = []
    for name in names or tuple(PRESETS):
        try:
            scene = build_feeder(PRESETS[name], part=part, name=name)
        except DegenerateDesign as exc:
            rows.append(
                CalibrationRow(
                    name,
                    PAPER_GEOMETRIC_VERDICT[name],
                    False,
                    str(exc),
                    dict.fromkeys(ORIENTATIONS, 0),
                    runs,
                )
            )
            continue
        solved = {}
        for orientation in ORIENTATIONS:
            solved[orientation] = sum(
                plan(scene, "geometric", planner, orientation, time_limit, seed).solved
                for seed in range(1, runs + 1)
            )
            if progress is not None:
                progress(name, orientation)
        rows.append(CalibrationRow(name, PAPER_GEOMETRIC_VERDICT[name], True, "", solved, runs))
    return rows


def markdown_table(rows: list[CalibrationRow]) -> str:
    lines = [
        "| design | paper | here | heavy leading solved | heavy trailing solved | agrees |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        here = "feasible" if r.feasible else ("not built" if not r.built else "infeasible")
        lines.append(
            f"| {r.design} | {'feasible' if r.paper_feasible else 'infeasible'} | {here} | "
            f"{r.solved['heavy_leading']}/{r.runs} | {r.solved['heavy_trailing']}/{r.runs} | "
            f"{'yes' if r.agrees else '**no**'} |"
        )
    return "\n".join(lines)
