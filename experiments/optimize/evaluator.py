"""Evaluations of designs for an optimiser: in parallel on the sweep's executors, stored as
they finish, never run twice.

An optimiser asks for a batch of designs (a generation of differential evolution or CMA-ES,
a single point of Nelder-Mead); :meth:`Evaluator.batch` answers with their robust objective
values. A design already stored is answered from the database; the others go to the pool as
plain-data jobs, each design's K trials split over the workers when the batch is smaller than
the pool (so a single-point method uses every core too). The calls of each run are stored in
order, so a run started again after a kill asks the same designs (the methods are seeded),
gets the stored ones back at once and goes on where it stopped.
"""

from __future__ import annotations

import itertools
import math
import sqlite3
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from experiments.optimize import store
from experiments.optimize.config import OptimizeConfig
from experiments.optimize.objective import (
    TrialsJob,
    evaluate_trials,
    robust_value,
    trial_from_dict,
)

Progress = Callable[[str, dict[str, Any]], None]


class BudgetSpent(Exception):
    """The run has had its budget of evaluations (those asked are stored)."""


@dataclass
class _Pending:
    values: list[float]
    chunks: int
    trials: list[dict] = field(default_factory=list)
    reason: str | None = None
    wall: float = 0.0
    done: int = 0


@dataclass
class Evaluator:
    """Answers optimisers' batches for one optimisation (one database, one pool)."""

    db: sqlite3.Connection
    pool: Any  # experiments.executors LocalPool or DaskPool, entered
    config: OptimizeConfig
    progress: Progress | None = None
    workers: int = 2
    cache: dict[str, dict[str, Any]] = field(init=False)
    stored_calls: dict[str, list[str]] = field(init=False)
    asked: dict[str, int] = field(init=False, default_factory=dict)
    best: dict[str, dict[str, Any]] = field(init=False, default_factory=dict)
    computed: int = field(init=False, default=0)  # designs evaluated by this process

    def __post_init__(self) -> None:
        self.cache = store.evaluations(self.db)
        self.stored_calls = store.calls(self.db)

    def _job(self, key: str, values: list[float], seed: int, first: int, count: int) -> TrialsJob:
        c = self.config
        return TrialsJob(
            key=key,
            values=values,
            first=first,
            count=count,
            seed=seed,
            feeder=c.feeder,
            step=c.step,
            t_max=c.t_max,
            perturbations=c.perturbations,
            family=c.family_yaml if c.family is not None else "",
            family_name=Path(c.family).stem if c.family is not None else "",
        )

    def run_trials(
        self,
        designs: dict[str, list[float]],
        seed: int,
        count: int,
        on_design: Callable[[str, _Pending], None] | None = None,
    ) -> dict[str, _Pending]:
        """Trials 0 .. count - 1 (draws of ``seed``) of each design, on the pool: key ->
        its trials (in index order), reason when degenerate or quarantined, worker time.
        ``on_design(key, pending)`` is called as each design's last trial comes in."""
        chunks = max(1, min(count, math.ceil(self.workers / max(1, len(designs)))))
        pending = {k: _Pending(v, chunks) for k, v in designs.items()}
        jobs = []
        for key, values in designs.items():
            bounds = [round(i * count / chunks) for i in range(chunks + 1)]
            for first, last in itertools.pairwise(bounds):
                jobs.append(self._job(key, values, seed, first, last - first))

        def on_done(job: TrialsJob, result: dict[str, Any], attempts: int) -> list:
            p = pending[job["key"]]
            p.trials.extend(result["trials"])
            p.reason = p.reason or result["reason"]
            p.wall += result["wall_time_s"]
            p.done += 1
            if p.done == p.chunks and on_design is not None:
                on_design(job["key"], p)
            return []

        def on_quarantine(job: TrialsJob, attempts: int, reason: str) -> None:
            p = pending[job["key"]]
            p.reason = p.reason or f"quarantined after {attempts} attempt(s): {reason}"
            p.done += 1
            if p.done == p.chunks and on_design is not None:
                on_design(job["key"], p)

        self.pool.run(evaluate_trials, jobs, on_done, on_quarantine)
        for p in pending.values():
            p.trials.sort(key=lambda t: t["index"])
        return pending

    def batch(self, run: str, budget: int, designs: Sequence[Sequence[float]]) -> list[float]:
        """The robust objective of each design (its values: 12, or a family's) for the
        optimiser run ``run`` (e.g. ``nelder-mead/seed0``); raises :class:`BudgetSpent` once
        the run has asked for ``budget`` evaluations (after storing those it could have)."""
        n0 = self.asked.get(run, 0)
        room = max(0, budget - n0)
        spent = len(designs) > room
        keys = [store.design_key(list(d)) for d in designs[:room]]
        stored = self.stored_calls.get(run, [])
        for i, key in enumerate(keys):
            n = n0 + i
            if n < len(stored) and stored[n] != key:
                raise store.StoreMismatch(
                    f"run {run} asked another design as its evaluation {n} than the stored run "
                    "did (the method's settings or the starts differ); choose another --out"
                )
        new = {k: store.design_of_key(k) for k in keys if k not in self.cache}
        order = list(dict.fromkeys(keys))  # calls are stored in the order asked

        def store_design(key: str, p: _Pending) -> None:
            trials = sorted(p.trials, key=lambda t: t["index"])
            result = robust_value(
                [trial_from_dict(t) for t in trials],
                self.config.weight,
                reason=p.reason,
                expected=self.config.trials,
            )
            result["trial_data"] = trials
            result["wall_time_s"] = p.wall
            store.record(self.db, key, result)
            self.cache[key] = result
            self.computed += 1

        if new:
            self.run_trials(new, self.config.seed, self.config.trials, store_design)
        assert all(k in self.cache for k in order)
        values = []
        for i, key in enumerate(keys):
            n = n0 + i
            if n >= len(stored):
                store.record_call(self.db, run, n, key)
            result = self.cache[key]
            values.append(result["value"])
            self._note(run, n, key, result, budget)
        self.asked[run] = n0 + len(keys)
        if spent:
            raise BudgetSpent(run)
        return values

    def _note(self, run: str, n: int, key: str, result: dict[str, Any], budget: int) -> None:
        best = self.best.get(run)
        if best is None or result["value"] < best["value"]:
            best = {"value": result["value"], "both": result["both"], "key": key, "n": n}
            self.best[run] = best
        if self.progress is not None:
            self.progress(
                "evaluation",
                {"run": run, "n": n, "budget": budget, "value": result["value"], "best": best},
            )

    def wall_time(self) -> float:
        """Worker time of every stored evaluation (s)."""
        return sum(r["wall_time_s"] for r in self.cache.values())
