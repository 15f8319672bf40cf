"""The designs the agreement suite drops, by name: a paper preset (``table3``), a Halton design
(``halton:SEED:INDEX``, the INDEX-th design of :func:`feeders.halton.halton_designs` with that
seed, as the sweeps number them) or 12 values ``a,b,c,d,e,fx,fy,gx,gy,r,theta,alpha``."""

from __future__ import annotations

from dataclasses import dataclass

from feeders.design import PARAMETER_NAMES, DesignError, DesignParameters, preset
from feeders.halton import halton_designs

MAX_HALTON_INDEX = 100_000


@dataclass(frozen=True)
class NamedDesign:
    """A design and the name it is reported under."""

    name: str
    design: DesignParameters


def named_design(token: str) -> NamedDesign:
    """The design a name stands for; DesignError (one line naming the token) otherwise."""
    token = token.strip()
    if token.startswith("halton:"):
        fields = token.split(":")
        try:
            seed, index = int(fields[1]), int(fields[2])
            if len(fields) != 3:
                raise ValueError
        except (ValueError, IndexError):
            raise DesignError(f"design {token!r}: a Halton design is halton:SEED:INDEX") from None
        if not (0 <= seed < 2**32 and 0 <= index < MAX_HALTON_INDEX):
            raise DesignError(
                f"design {token!r}: SEED in [0, 2^32), INDEX in [0, {MAX_HALTON_INDEX})"
            )
        return NamedDesign(token, halton_designs(index + 1, seed)[index])
    if "," in token:
        try:
            values = [float(v) for v in token.split(",")]
        except ValueError:
            raise DesignError(f"design {token!r}: the 12 values must be numbers") from None
        if len(values) != len(PARAMETER_NAMES):
            raise DesignError(
                f"design {token!r}: {len(values)} values, need 12 ({','.join(PARAMETER_NAMES)})"
            )
        return NamedDesign(token, DesignParameters.from_vector(values))
    return NamedDesign(token, preset(token))


OPTIMUM = NamedDesign(
    "optimum",
    DesignParameters.from_vector(
        [1.1156122541845623, 1.2084470847490687, 0.7533693361658794, 2.6935175182997213,
         -1.7955137602839462, -0.8738765303549423, 0.8710705062167202, 0.7097825503622526,
         2.751648296340009, 0.1521678198713024, 0.7559595787286619, 0.9180522111747866]
    ),
)  # fmt: skip
"""``partfeeder optimize`` with its default config from table3 (no ``--from``), run for this
suite with the contact kernel of 311df68 (docs/agreement.md): P(both) 150/150 on its fresh
trials, mean G 4.52 s (table3 6.22 s on its own fresh trials)."""

DEFAULT_TOKENS = (
    "table3",
    "halton:0:3",  # works in every engine
    "halton:0:34",  # works in every engine
    "halton:0:0",  # heavy trailing fails in every engine
    "halton:0:31",  # heavy trailing: the old kernel 19/40, the peers work (issue 26)
    "halton:0:42",  # heavy trailing: the old kernel 30/40, the peers work
    "halton:0:6",  # heavy trailing near 0.1-0.3 in every engine
    "halton:0:8",  # heavy leading: MuJoCo 10/10, partfeeder and pymunk 4/10
    "halton:0:14",  # heavy trailing: MuJoCo 7/10, partfeeder and pymunk 0/10
)
"""The default set beside :data:`OPTIMUM`: presets and Halton designs (seed 0) that work, fail
and sit near the threshold, and where the engines differed in a scan of the first 64 Halton
designs (10 trials each, docs/agreement.md)."""


def default_designs() -> list[NamedDesign]:
    """table3, the optimum, then the Halton designs of :data:`DEFAULT_TOKENS`."""
    return [named_design(DEFAULT_TOKENS[0]), OPTIMUM, *map(named_design, DEFAULT_TOKENS[1:])]
