"""The twelve design parameters of the part feeder (paper Table 1) and their box (Table 2).

A design is an immutable value: variants come from :func:`dataclasses.replace`. Lengths are in
the paper's units (the peg is 2 x 1, see :mod:`feeders.part`); angles are in radians.

Table 2 prints the range of ``e`` as ``[-1.0, -2.0]``; it is ``[-2.0, -1.0]``. The paper's own
Fig. 5 designs use ``theta = 0.235``, below the Table 2 box: a design may lie outside the
box (``DESIGN_SPACE.contains`` says whether it does); it may not be unphysical, which
``DesignParameters`` refuses with an error naming the field and its physical range.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

PARAMETER_NAMES: tuple[str, ...] = (
    "a",
    "b",
    "c",
    "d",
    "e",
    "fx",
    "fy",
    "gx",
    "gy",
    "r",
    "theta",
    "alpha",
)

PARAMETER_MEANINGS: dict[str, str] = {
    "a": "width of input chute",
    "b": "width of output chute",
    "c": "depth of chamfer",
    "d": "length of input chute",
    "e": "horizontal location of left cavity wall",
    "fx": "x of the centre of the tip of the protuberance",
    "fy": "y of the centre of the tip of the protuberance",
    "gx": "x of the lower left corner of the input chute (the lip)",
    "gy": "y of the lower left corner of the input chute (the lip)",
    "r": "radius of protuberance",
    "theta": "angle of input chute (rad, from horizontal)",
    "alpha": "angle of chamfer (rad, from horizontal)",
}

# Table 2 of the paper (e corrected to [-2, -1]).
TABLE2_BOUNDS: dict[str, tuple[float, float]] = {
    "a": (1.1, 1.2),
    "b": (1.1, 1.3),
    "c": (0.75, 0.8),
    "d": (2.5, 5.0),
    "e": (-2.0, -1.0),
    "fx": (-1.0, -0.6),
    "fy": (0.5, 2.5),
    "gx": (0.2, 2.0),
    "gy": (1.5, 3.0),
    "r": (0.1, 0.3),
    "theta": (0.3, 0.9),
    "alpha": (0.9, 1.1),
}

# What the reconstructed device can be built from at all (outside Table 2 included).
PHYSICAL_BOUNDS: dict[str, tuple[float, float]] = {
    "a": (0.05, 10.0),
    "b": (0.05, 10.0),
    "c": (0.0, 10.0),
    "d": (0.1, 50.0),
    "e": (-20.0, -0.05),
    "fx": (-20.0, 20.0),
    "fy": (-20.0, 20.0),
    "gx": (-20.0, 20.0),
    "gy": (0.0, 20.0),
    "r": (0.01, 5.0),
    "theta": (0.0, math.pi / 2 - 0.01),
    "alpha": (0.05, math.pi / 2),
}


class DesignError(ValueError):
    """A design value is missing, not a number, or outside its allowed range."""


@dataclass(frozen=True)
class DesignParameters:
    """One point of the design space P (paper Table 1).

    ``f = (fx, fy)`` is the centre of the rounded tip of the protuberance, ``g = (gx, gy)``
    the lower left corner of the input chute (the lip the part tips over).
    """

    a: float
    b: float
    c: float
    d: float
    e: float
    fx: float
    fy: float
    gx: float
    gy: float
    r: float
    theta: float
    alpha: float

    def __post_init__(self) -> None:
        for name in PARAMETER_NAMES:
            value = getattr(self, name)
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise DesignError(
                    f"design parameter '{name}' must be a number, got {value!r}"
                ) from None
            low, high = PHYSICAL_BOUNDS[name]
            if not math.isfinite(value) or not low <= value <= high:
                raise DesignError(
                    f"design parameter '{name}' ({PARAMETER_MEANINGS[name]}) = {value!r} "
                    f"is outside the allowed range [{low:g}, {high:g}]"
                )
            object.__setattr__(self, name, value)

    @classmethod
    def from_vector(cls, values: np.ndarray | list[float] | tuple[float, ...]) -> DesignParameters:
        """Build from the 12 values in the order of ``PARAMETER_NAMES``."""
        values = list(np.asarray(values, dtype=float).ravel())
        if len(values) != len(PARAMETER_NAMES):
            raise DesignError(
                f"a design has {len(PARAMETER_NAMES)} values ({', '.join(PARAMETER_NAMES)}), "
                f"got {len(values)}"
            )
        return cls(**dict(zip(PARAMETER_NAMES, values, strict=True)))

    @classmethod
    def from_mapping(cls, mapping: dict[str, object]) -> DesignParameters:
        """Build from a mapping with keys a..alpha; ``f`` and ``g`` may be given as pairs."""
        flat = dict(mapping)
        for pair in ("f", "g"):
            if pair in flat:
                value = flat.pop(pair)
                if not isinstance(value, (list, tuple)) or len(value) != 2:
                    raise DesignError(f"design parameter '{pair}' must be a pair [x, y]")
                flat[pair + "x"], flat[pair + "y"] = value
        unknown = sorted(set(flat) - set(PARAMETER_NAMES))
        if unknown:
            raise DesignError(
                f"unknown design parameter(s) {unknown}; known: {', '.join(PARAMETER_NAMES)}"
            )
        missing = [n for n in PARAMETER_NAMES if n not in flat]
        if missing:
            raise DesignError(f"design parameter(s) missing: {', '.join(missing)}")
        return cls(**flat)  # type: ignore[arg-type]

    def to_vector(self) -> np.ndarray:
        """The 12 values as a float array in the order of ``PARAMETER_NAMES``."""
        return np.array([getattr(self, n) for n in PARAMETER_NAMES], dtype=float)

    def to_dict(self) -> dict[str, float]:
        return asdict(self)


@dataclass(frozen=True)
class DesignSpace:
    """An axis-aligned box in the 12-dimensional design space."""

    bounds: tuple[tuple[float, float], ...]

    @property
    def low(self) -> np.ndarray:
        return np.array([lo for lo, _ in self.bounds])

    @property
    def high(self) -> np.ndarray:
        return np.array([hi for _, hi in self.bounds])

    def contains(self, design: DesignParameters, tol: float = 1e-12) -> bool:
        x = design.to_vector()
        return bool(np.all(x >= self.low - tol) and np.all(x <= self.high + tol))

    def outside(self, design: DesignParameters) -> list[str]:
        """Names of the parameters outside the box, e.g. ``['theta']`` for fig5a."""
        x = design.to_vector()
        return [
            name
            for name, value, (lo, hi) in zip(PARAMETER_NAMES, x, self.bounds, strict=True)
            if not lo - 1e-12 <= value <= hi + 1e-12
        ]

    def scale(self, unit: np.ndarray) -> np.ndarray:
        """Map points of the unit cube, shape (n, 12), onto the box."""
        return self.low + np.asarray(unit) * (self.high - self.low)


DESIGN_SPACE = DesignSpace(tuple(TABLE2_BOUNDS[n] for n in PARAMETER_NAMES))


def _d(a, b, c, d, e, f, g, r, theta, alpha) -> DesignParameters:
    return DesignParameters(a, b, c, d, e, f[0], f[1], g[0], g[1], r, theta, alpha)


# Every design printed in the paper, named after the figure or table that shows it.
PRESETS: dict[str, DesignParameters] = {
    "fig4": _d(
        1.113, 1.134, 0.7727, 3.462, -1.161, (-0.616, 1.929), (1.325, 2.666), 0.144, 0.4764, 0.9526
    ),
    "fig5a": _d(
        1.1, 1.1086, 0.798, 3.008, -1.9, (-0.985, 1.01), (0.733, 2.039), 0.101, 0.235, 1.047
    ),
    "fig5b": _d(
        1.1, 1.1086, 0.798, 3.008, -1.9, (-0.985, 1.01), (0.733, 2.039), 0.101, 0.529, 1.047
    ),
    "fig6a": _d(
        1.178, 1.1, 0.782, 3.106, -1.935, (-0.923, 0.949), (1.493, 2.518), 0.152, 0.725, 1.005
    ),
    "fig6b": _d(
        1.181, 1.107, 0.787, 3.298, -1.967, (-0.619, 1.234), (1.043, 1.685), 0.161, 0.761, 1.016
    ),
    "fig7a": _d(1.1, 1.1, 0.75, 2.5, -1.0, (-0.6, 0.5), (0.2, 1.5), 0.1, 0.3, 0.9),
    "fig7b": _d(
        1.127, 1.168, 0.795, 4.423, -1.322, (-0.632, 1.397), (0.762, 2.055), 0.186, 0.65, 1.005
    ),
    "fig8a": _d(1.14, 1.2, 0.769, 2.899, -1.483, (-0.65, 0.87), (1.88, 1.88), 0.23, 0.829, 1.06),
    "fig8b": _d(
        1.159, 1.25, 0.751, 4.245, -1.709, (-0.824, 0.908), (0.931, 2.277), 0.291, 0.478, 0.932
    ),
    "fig9": _d(1.2, 1.3, 0.8, 5.0, -1.0, (-0.7, 2.5), (1.5, 3.0), 0.3, 0.7854, 1.0472),
    "table3": _d(
        1.1, 1.1086, 0.7979, 3.0078, -1.9, (-0.9849, 1.0098), (0.733, 2.0388), 0.101, 0.4673, 1.0472
    ),
}

# What the paper says of each preset at the geometric level (Sections 3-4).
PAPER_GEOMETRIC_VERDICT: dict[str, bool] = {
    "fig4": True,
    "fig5a": True,
    "fig5b": True,
    "fig6a": True,
    "fig6b": True,
    "fig7a": False,
    "fig7b": False,
    "fig8a": True,
    "fig8b": True,
    "fig9": True,
    "table3": True,
}


def preset(name: str) -> DesignParameters:
    """The named design from the paper; the error lists the names there are."""
    try:
        return PRESETS[name]
    except KeyError:
        raise DesignError(
            f"unknown design preset '{name}'; presets: {', '.join(sorted(PRESETS))}"
        ) from None
