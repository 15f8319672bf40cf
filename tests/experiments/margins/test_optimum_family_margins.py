"""The optimiser measures a device family's optimum's margins (issue 24) as it does the
feeder's: over the family's parameters and friction (the family's text from the config, the
design's vector from its store key), with the optimiser's margin settings, stored under the
design and the settings' digest so a run started again measures nothing again."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from experiments.margins.measure import FamilySubject
from experiments.optimize import store
from experiments.optimize.config import config_from_dict
from experiments.optimize.run import DATABASE
from experiments.optimize.tolerance import family_margins, margin_settings

OPTIMUM = [0.6907, 1.2855, 1.2213, 1.8129, 1.1795, 0.5437, 0.1447, 0.4392]
CUP = {
    "name": "tiny-cup",
    "family": "fig1-cup",
    "objective": {"trials": 3, "seed": 0},
    "start": {"presets": ["default"]},
    "methods": [{"method": "differential-evolution", "budget": 6, "seeds": [0], "population": 5}],
    "final": {"trials": 4, "seed": 1000, "candidates": 2},
    "workers": 2,
}


class _Report:
    def __init__(self, data: dict[str, Any]) -> None:
        self.data = data

    def to_dict(self) -> dict[str, Any]:
        return self.data


def test_a_familys_optimum_gets_its_margins_once(tmp_path: Path) -> None:
    config = config_from_dict(CUP)
    family = config.device_family()
    assert family is not None
    calls: list[tuple[Any, ...]] = []

    def measure(subject, settings, workers, on_axis=None):
        calls.append((subject, settings, workers))
        return _Report({"design": subject.name, "axes": [*subject.names, "mu"]})

    key = store.design_key(OPTIMUM)
    db = store.connect(tmp_path / DATABASE)
    try:
        first = family_margins(db, config, family, key, "optimum", 2, measure=measure)
        again = family_margins(db, config, family, key, "optimum", 2, measure=measure)
    finally:
        db.close()
    assert first == again == {"design": "optimum", "axes": [*family.vector_names, "mu"]}
    assert len(calls) == 1  # the second read the store
    subject, settings, workers = calls[0]
    assert subject == FamilySubject.of_family(family, config.family_yaml, OPTIMUM, "optimum")
    assert settings == margin_settings(config) and workers == 2
