"""The bracketing search for one side of a margin: from the nominal value outward, steps
doubling until P(both) falls below the target or the box's edge is reached, then bisection
between the last value inside and the first outside to a stated resolution.

A value is *inside* by the full rule when at least ``required(target, N)`` of its first N
counted trials succeed (trial i is the verdict's draw i, the same at every value: common
random numbers), and *outside* when more of them have failed than that allows (its trials
stop there: curtailed). The search assumes P(both) falls once with distance from the
nominal (a *single crossing*): a value inside implies every value between it and the
nominal is inside, so the values the search passes on its way only steer it. Only the two
values it reports need the full rule: the last inside (all N trials counted) and the first
outside (failed, curtailed); every other value is judged on a *look* of a trial or two.

- **Look.** The value's trials likeliest to fail first (below), until ``look`` successes
  (tentatively inside; one more once the bracket is narrower than :data:`NEAR` of the box)
  or the first failure (tentatively outside; more failures than the full rule allows: outside
  for good). Trials a look skips are counted in no estimate.
- **Likeliest to fail first.** Common random numbers make a trial's outcome nearly a step
  in the value (97% of table3's trials, measured: success up to a threshold of its own, then
  failure). So a trial that failed at the nearest value beyond is the one to try first, and
  a trial that failed at a value nearer the nominal is taken as failing here (a look does
  not spend a trial on it; it counts toward the allowance). Ties in draw order, from an
  offset that moves on at every look, so that looks do not all see the same draws.
- **Confirmation.** When the bisection has closed (the last value accepted and the first
  rejected within ``resolution`` of the box), the rejected one gets the full rule first,
  then the accepted one, each on the trials it already has plus the rest of its N. A
  confirmation that contradicts the look makes the value inside (or outside) for good, and
  the search goes on from the bracket that gives. A wrong look costs trials, never a wrong
  statement. Where the full rule's answers cross once, the ends are those of the search on
  full estimates (:func:`bracket`); where they do not (noise near an end), another crossing
  may be found, its ends still meeting the full rule (table3, seeds 0-4: every end the
  same).
- **The box's edge first.** Its look, and its full rule when the look passes: a side whose
  edge is inside is done in one value after a *scan*: a look at each doubling point the
  search on full estimates would have judged on its way (an inside edge beyond a failing
  band: table3's fy fails from 1.12 on and works again at 2.5, its edge). A scan's failure sends the
  search back to bisection from there. A look of one trial sees a band where P(both) is
  p with probability 1 - p at each doubling point in it: a band where most trials fail is
  found, a shallow one may not be (the search on full estimates would have judged it).
- **The nominal** is taken as accepted (the caller's look, :func:`nominal_estimate`) and
  gets the full rule only when a side comes back to it: :class:`NominalFailed` when that
  fails (the axis has no margin).

The trials are injected (``outcome(value, index)``: does trial ``index`` at ``value``
succeed from every entry, None for a fault of the simulation), so the search is tested on
synthetic success functions with known thresholds; :func:`bracket` runs the same search on
an estimator of full estimates (``evaluate(value) -> Estimate``), every value by the full
rule: its ends are those of the doubling-then-bisection search before issue 34 (the edge
judged first, then every doubling point up to the first outside, as that search did).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from experiments.proportions import wilson_interval

FIRST_STEP = 1 / 32  # the first step outward, as a fraction of the box's width
RESOLUTION = 1 / 128  # bisection stops when inside and outside are this close (box fraction)
LOOK = 1  # successes that accept a value tentatively
NEAR = 4 * RESOLUTION  # a bracket this narrow (box fraction): a look takes one success more

_IN, _OUT, _IN_T, _OUT_T = "inside", "outside", "inside?", "outside?"  # ? : on a look


def required(target: float, planned: int) -> int:
    """The fewest successes of ``planned`` trials whose estimate k / planned reaches
    ``target``."""
    return max(0, math.ceil(target * planned - 1e-9))


@dataclass(frozen=True)
class Estimate:
    """P(both) at one value: ``successes`` of ``drops`` trials made (each a drop from every
    entry), of ``planned``; fewer made than planned means it stopped once it could not reach
    the target. A look (a value the search only passed) is an estimate of its few trials
    (``planned`` = ``drops``)."""

    value: float
    successes: int
    drops: int
    planned: int

    def inside(self, target: float) -> bool:
        return self.drops >= self.planned and self.successes >= required(target, self.planned)

    def failed(self, target: float) -> bool:
        """More of the trials failed than ``target`` allows over ``planned``: outside, by
        the full rule when ``planned`` is N."""
        return self.drops - self.successes > self.planned - required(target, self.planned)

    @property
    def interval(self) -> tuple[float, float]:
        """Wilson 95% interval of P(both) over the trials made."""
        return wilson_interval(self.successes, self.drops)

    def to_dict(self) -> dict:
        lo, hi = self.interval
        return {
            "value": self.value,
            "successes": self.successes,
            "drops": self.drops,
            "planned": self.planned,
            "p": self.successes / self.drops if self.drops else None,
            "interval": [lo, hi],
        }


@dataclass(frozen=True)
class Bracket:
    """One side of a margin: the last value found inside (``inside``, the margin's end, by
    the full rule), the first found outside (``outside``, by the full rule, curtailed; None
    when the box's ``edge`` is inside: the margin reaches the edge), and every value the
    search estimated, in the order first looked at, each over all the trials made at it."""

    nominal: float
    edge: float
    inside: Estimate
    outside: Estimate | None
    evaluations: tuple[Estimate, ...]
    resolution: float

    @property
    def limit(self) -> float:
        return self.inside.value

    @property
    def at_edge(self) -> bool:
        return self.outside is None

    @property
    def drops(self) -> int:
        return sum(e.drops for e in self.evaluations)

    def to_dict(self) -> dict:
        return {
            "limit": self.limit,
            "at_box_edge": self.at_edge,
            "edge": self.edge,
            "last_inside": self.inside.to_dict(),
            "first_outside": None if self.outside is None else self.outside.to_dict(),
            "evaluations": len(self.evaluations),
            "drops": self.drops,
            "resolution": self.resolution,
        }


class Trials(Protocol):
    """The trials the search judges values on: ``trial(value, index)`` is trial ``index``
    at ``value`` (True: a success from every entry, False: not, None: a fault of the
    simulation, left out), made once and kept; ``made_at(value)`` the trials made there by
    index; ``estimate(value)`` the estimate to report for it, a full one once
    ``mark_full(value)`` has said its full rule was run; ``drops`` is the full rule's N."""

    drops: int
    target: float

    def trial(self, value: float, index: int) -> bool | None: ...

    def made_at(self, value: float) -> dict[int, bool | None]: ...

    def mark_full(self, value: float) -> None: ...

    def estimate(self, value: float) -> Estimate: ...


class Sampler:
    """:class:`Trials` made as the search asks for them and kept: trial ``index`` at
    ``value`` is ``outcome(value, index)`` (True when it succeeds from every entry, False
    when not, None for a fault). ``made`` counts the trials made, faults left out as the
    estimates leave them out."""

    def __init__(
        self, outcome: Callable[[float, int], bool | None], drops: int, target: float
    ) -> None:
        self.outcome = outcome
        self.drops = drops
        self.target = target
        self._made: dict[float, dict[int, bool | None]] = {}
        self._full: set[float] = set()

    def trial(self, value: float, index: int) -> bool | None:
        made = self._made.setdefault(value, {})
        if index not in made:
            made[index] = self.outcome(value, index)
        return made[index]

    def made_at(self, value: float) -> dict[int, bool | None]:
        return self._made.get(value, {})

    def mark_full(self, value: float) -> None:
        self._full.add(value)

    def estimate(self, value: float) -> Estimate:
        results = [r for r in self.made_at(value).values() if r is not None]
        planned = self.drops if value in self._full else len(results)
        return Estimate(value, sum(results), len(results), planned)

    @property
    def made(self) -> int:
        return sum(1 for m in self._made.values() for r in m.values() if r is not None)


class _FromEstimates:
    """:class:`Trials` over an estimator of full estimates (:func:`bracket`'s): trial i at a
    value is a success below the estimate's successes, a failure below its drops, and a
    fault beyond, so that the full rule on them decides as the estimate does; the estimate
    reported is the estimator's."""

    def __init__(self, evaluate: Callable[[float], Estimate], nominal: Estimate, target: float):
        self.evaluate = evaluate
        self.drops = nominal.planned
        self.target = target
        self._estimates = {nominal.value: nominal}
        self._made: dict[float, dict[int, bool | None]] = {}

    def estimate(self, value: float) -> Estimate:
        if value not in self._estimates:
            self._estimates[value] = self.evaluate(value)
        return self._estimates[value]

    def trial(self, value: float, index: int) -> bool | None:
        e = self.estimate(value)
        result = True if index < e.successes else False if index < e.drops else None
        self._made.setdefault(value, {})[index] = result
        return result

    def made_at(self, value: float) -> dict[int, bool | None]:
        return self._made.get(value, {})

    def mark_full(self, value: float) -> None:
        pass


class NominalFailed(Exception):
    """A side's search came back to the nominal value and its full rule failed there: the
    axis has no margin (``estimate``: the nominal's)."""

    def __init__(self, estimate: Estimate) -> None:
        super().__init__(f"the nominal value {estimate.value:g} is not inside the margin")
        self.estimate = estimate


class _Side:
    """One side's judgements: what each value is believed to be (inside or outside, for good
    or on a look), and the values estimated, in order."""

    def __init__(self, trials: Trials, nominal: float, edge: float) -> None:
        self.trials = trials
        self.n = trials.drops
        self.allowed = self.n - required(trials.target, self.n)  # failures the rule allows
        self.nominal = nominal
        self.sign = 1.0 if edge >= nominal else -1.0
        self.belief: dict[float, str] = {nominal: _IN_T}
        self.order: list[float] = []  # the values estimated (not the nominal), first first
        self.offset = 0  # draw order's tie-break starts here; moves on at every look

    def far(self, value: float) -> float:
        """How far ``value`` lies from the nominal toward the edge."""
        return self.sign * (value - self.nominal)

    def counts(self, value: float) -> tuple[int, int]:
        """Successes and failures made at ``value``."""
        results = [r for r in self.trials.made_at(value).values() if r is not None]
        return sum(results), len(results) - sum(results)

    def rank(self, value: float, index: int) -> tuple[int, float, int]:
        """How likely trial ``index`` is to fail at ``value``, likeliest lowest: 0 failed at
        a value no farther out (taken as failing here), 1 failed beyond (the nearest first),
        2 never made beyond, 3 succeeded at the nearest value made beyond."""
        here, tie = self.far(value), (index - self.offset) % self.n
        beyond: list[tuple[float, bool]] = []
        for u in (self.nominal, *self.order):
            result = self.trials.made_at(u).get(index)
            if result is None:
                continue
            if not result and self.far(u) <= here:
                return (0, 0.0, tie)
            if self.far(u) > here:
                beyond.append((self.far(u) - here, result))
        if not beyond:
            return (2, 0.0, tie)
        distance, result = min(beyond)
        return (3 if result else 1, distance, tie)

    def ranked(self, value: float) -> list[int]:
        return sorted(range(self.n), key=lambda i: self.rank(value, i))

    def look(self, value: float, successes: int) -> str:
        """Trials at ``value``, likeliest to fail first, those taken as failing skipped
        (counted toward the allowance), until ``successes`` successes (inside, tentatively)
        or a failure (outside, tentatively; for good past the allowance)."""
        if successes >= self.n:
            return self.full(value)
        if value not in self.order:
            self.order.append(value)
        ranked = self.ranked(value)
        known = sum(1 for i in ranked if self.rank(value, i)[0] == 0)
        for i in ranked[known:]:
            s, f = self.counts(value)
            if s >= successes or f > 0 or known > self.allowed:
                break
            self.trials.trial(value, i)
        self.offset = (self.offset + successes) % self.n
        s, f = self.counts(value)
        if f > self.allowed:
            self.trials.mark_full(value)
            state = _OUT
        elif s >= successes and f == 0 and known <= self.allowed:
            state = _IN_T
        else:
            state = _OUT_T
        self.belief[value] = state
        return state

    def full(self, value: float) -> str:
        """The full rule at ``value``: its first N counted trials (a fault's place taken by
        the next draw past N), likeliest to fail first, stopped once more have failed than
        the rule allows. :class:`NominalFailed` at the nominal when outside."""
        if value != self.nominal and value not in self.order:
            self.order.append(value)
        if self.belief.get(value) in (_IN, _OUT):
            return self.belief[value]
        counted = 0
        for i in self.ranked(value) + list(range(self.n, 2 * self.n)):
            if counted >= self.n:
                break
            if i not in self.trials.made_at(value) and self.counts(value)[1] > self.allowed:
                break
            counted += self.trials.trial(value, i) is not None
        s, f = self.counts(value)
        self.trials.mark_full(value)
        state = _IN if s + f >= self.n and f <= self.allowed else _OUT
        self.belief[value] = state
        if value == self.nominal and state == _OUT:
            raise NominalFailed(self.trials.estimate(value))
        return state


def search(
    trials: Trials,
    nominal: float,
    edge: float,
    width: float,
    first_step: float = FIRST_STEP,
    resolution: float = RESOLUTION,
    look: int = LOOK,
) -> Bracket:
    """The side of the margin from ``nominal`` toward ``edge`` (the module's docstring):
    the edge's look first (then its full rule, and the scan, when the look passes); steps of
    ``first_step * width`` doubling, each clipped to the edge; bisection until the value
    accepted last and the one rejected first are within ``resolution * width``; then the
    full rule at both, the search going on wherever that contradicts a look. Values are
    passed on looks of ``look`` successes; the ends reported have the full rule over
    ``trials.drops`` trials. Every value estimated lies between the nominal and the edge."""
    if look < 1:
        raise ValueError(f"a look needs at least one success, not {look}")
    side = _Side(trials, nominal, edge)
    far, tol, n = side.far, resolution * width, trials.drops
    near = NEAR * width

    def result(inside: float, outside: float | None) -> Bracket:
        made = tuple(trials.estimate(v) for v in side.order)
        out = None if outside is None else trials.estimate(outside)
        return Bracket(nominal, edge, trials.estimate(inside), out, made, tol)

    if edge == nominal:  # no room: the nominal is the side's end, by the full rule
        side.full(nominal)
        return result(nominal, None)
    doubling: list[float] = []  # the values the search on full estimates steps through
    step = first_step * width
    while step < abs(edge - nominal):
        doubling.append(nominal + side.sign * step)
        step *= 2.0
    doubling.append(edge)
    side.look(edge, look)
    while True:
        belief = side.belief
        outs = [v for v, b in belief.items() if b in (_OUT, _OUT_T)]
        o = min(outs, key=far) if outs else None
        ins = [v for v, b in belief.items() if b in (_IN, _IN_T)]
        i = max((v for v in ins if o is None or far(v) < far(o)), key=far)
        if o is None:  # the edge inside on its look: its full rule, then the scan
            if side.full(edge) == _IN:
                unseen = [v for v in doubling if v not in belief]
                if not unseen:
                    return result(edge, None)
                side.look(unseen[0], look)
            continue
        between = [v for v in doubling if far(i) < far(v) < far(o) and v not in belief]
        if between:  # doubling
            side.look(between[0], look)
        elif far(o) - far(i) > tol:  # bisection
            side.look(0.5 * (i + o), min(n, look + (far(o) - far(i) <= near)))
        elif belief[o] == _OUT_T:  # closed: the full rule, the rejected value first
            side.full(o)
        elif belief[i] == _IN_T:
            side.full(i)
        else:
            return result(i, o)


def nominal_estimate(trials: Trials, nominal: float, look: int = LOOK) -> Estimate:
    """The nominal value's look: its trials in draw order until ``look`` successes, and at
    the first failure the full rule (outside: the axis has no margin)."""
    if look < 1:
        raise ValueError(f"a look needs at least one success, not {look}")
    side = _Side(trials, nominal, nominal)
    for index in range(trials.drops):
        s, f = side.counts(nominal)
        if f or s >= look:
            break
        trials.trial(nominal, index)
    if side.counts(nominal)[1] or look >= trials.drops:
        try:
            side.full(nominal)
        except NominalFailed as failed:
            return failed.estimate
    return trials.estimate(nominal)


def bracket(
    evaluate: Callable[[float], Estimate],
    nominal: Estimate,
    edge: float,
    width: float,
    target: float,
    first_step: float = FIRST_STEP,
    resolution: float = RESOLUTION,
) -> Bracket:
    """The side of the margin from ``nominal`` (an estimate inside) toward ``edge``, on an
    estimator of full estimates: :func:`search` with every value judged by the full rule
    (the edge first, then the doubling steps, then bisection until the last inside and the
    first outside are within ``resolution * width``). Every value evaluated lies between the
    nominal and the edge."""
    if not nominal.inside(target):
        raise ValueError(f"the nominal value {nominal.value:g} is not inside the margin")
    trials = _FromEstimates(evaluate, nominal, target)
    return search(trials, nominal.value, edge, width, first_step, resolution, trials.drops)
