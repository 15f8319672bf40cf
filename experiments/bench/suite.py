"""``partfeeder bench``: every section, then the JSON, the figures and the Markdown summary.

Sections (each optional, in this order): ``analytic`` (work-precision of the analytic scenes
against MuJoCo and pymunk, :mod:`experiments.bench.work_precision`), ``speed``
(:mod:`experiments.bench.speed`), ``feeder`` (:mod:`experiments.bench.feeder_convergence`)
and ``ladder`` (:mod:`experiments.bench.ladder_cost`). ``quick`` shrinks every section to a
smoke test (under a minute with compiled kernels cached); the full run takes about five
minutes on two cores.

Writes into the output directory: ``bench.json`` (every figure's data, the machine and the
versions of every engine), ``perf-*.png`` and ``summary.md``.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from experiments.bench.timing import machine_info

SECTIONS = ("analytic", "speed", "feeder", "ladder")
JSON_FILE = "bench.json"
SUMMARY_FILE = "summary.md"


@dataclass(frozen=True)
class SuiteSettings:
    """How much of everything: repeats of every timing, the seed of every random choice."""

    quick: bool = False
    repeats: int = 5
    seed: int = 1
    sections: tuple[str, ...] = SECTIONS

    def __post_init__(self) -> None:
        if not 1 <= self.repeats <= 1000:
            raise ValueError(f"repeats = {self.repeats} is outside the allowed range [1, 1000]")
        unknown = [s for s in self.sections if s not in SECTIONS]
        if unknown or not self.sections:
            raise ValueError(f"sections = {list(self.sections)}; allowed: {', '.join(SECTIONS)}")


def _analytic(s: SuiteSettings) -> dict:
    from experiments.bench import work_precision as wp

    h = wp.H_QUICK if s.quick else wp.H_FULL
    return wp.run_work_precision(h, s.repeats, creep_duration=1.0 if s.quick else 10.0)


def _speed(s: SuiteSettings) -> dict:
    from experiments.bench.speed import run_speed

    return run_speed(s.repeats, s.seed, s.quick)


def _feeder(s: SuiteSettings) -> dict:
    from experiments.bench import feeder_convergence as fc

    if s.quick:
        return fc.run_feeder_convergence(fc.DESIGNS_QUICK, fc.H_QUICK, drops=4, seed=s.seed)
    return fc.run_feeder_convergence(fc.DESIGNS_FULL, fc.H_FULL, drops=30, seed=s.seed)


def _ladder(s: SuiteSettings) -> dict:
    from experiments.bench import ladder_cost as lc

    if s.quick:
        return lc.run_ladder(lc.DESIGNS_QUICK, lc.BUDGETS_QUICK, lc.PASSIVE_QUICK, s.seed)
    return lc.run_ladder(lc.DESIGNS_FULL, lc.BUDGETS_FULL, lc.PASSIVE_FULL, s.seed)


_RUNNERS: dict[str, tuple[str, Callable[[SuiteSettings], dict]]] = {
    "analytic": ("work_precision", _analytic),
    "speed": ("speed", _speed),
    "feeder": ("feeder", _feeder),
    "ladder": ("ladder", _ladder),
}


def run_suite(settings: SuiteSettings, progress: Callable[[str], object] | None = None) -> dict:
    """Every chosen section's data, with the machine, versions and timings of the sections."""
    from experiments.bench.engines import engine_versions

    data: dict = {
        "machine": machine_info(),
        "versions": engine_versions(),
        "settings": {
            "quick": settings.quick,
            "repeats": settings.repeats,
            "seed": settings.seed,
            "sections": list(settings.sections),
        },
        "section_seconds": {},
    }
    for section in SECTIONS:
        if section not in settings.sections:
            continue
        if progress is not None:
            progress(section)
        key, runner = _RUNNERS[section]
        t0 = time.perf_counter()
        data[key] = runner(settings)
        data["section_seconds"][section] = time.perf_counter() - t0
    return data


def write_outputs(data: dict, out: Path) -> list[Path]:
    """``bench.json``, the figures and ``summary.md`` into ``out`` (made if needed)."""
    from experiments.bench.figures import draw_all
    from experiments.bench.summary import markdown

    out.mkdir(parents=True, exist_ok=True)
    paths = [out / JSON_FILE]
    paths[0].write_text(json.dumps(data, indent=1, allow_nan=False))
    paths += draw_all(data, out)
    summary = out / SUMMARY_FILE
    summary.write_text(markdown(data))
    return [*paths, summary]


def sections_of(text: str) -> Sequence[str]:
    """``"analytic,speed"`` as a tuple of section names (checked by :class:`SuiteSettings`)."""
    return tuple(s.strip() for s in text.split(",") if s.strip())
