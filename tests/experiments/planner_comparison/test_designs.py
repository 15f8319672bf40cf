"""A config's design as a scene, built where it is planned: every kind, with its entries."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from experiments.config_files import CONFIG_DIR
from experiments.planner_comparison.designs import scene_for
from experiments.planner_comparison.suite import design_name
from feeders.design import PRESETS
from feeders.halton import halton_designs

SCENES = CONFIG_DIR.parent / "scenes"


@pytest.mark.parametrize(
    ("design", "entries"),
    [
        ({"preset": "table3"}, {"heavy_leading", "heavy_trailing"}),
        ({"halton": {"seed": 1, "index": 7}}, {"heavy_leading", "heavy_trailing"}),
        ({"family": "fig1-cup"}, {"open_leading", "open_trailing"}),
        ({"scene": "table3"}, {"heavy_leading", "heavy_trailing"}),  # a packaged scene
    ],
)
def test_each_kind_of_design_builds_its_scene_with_both_entries(design, entries) -> None:
    scene = scene_for(design)
    assert set(scene.starts) == entries
    if "preset" not in design and "scene" not in design:
        assert scene.name == design_name(design)


def test_a_halton_design_is_the_sweeps_design_of_that_index() -> None:
    scene = scene_for({"halton": {"seed": 1, "index": 7}})
    assert scene.design == halton_designs(8, 1)[7]
    assert scene_for({"preset": "fig4"}).design == PRESETS["fig4"]


def test_a_scene_file_is_read_relative_to_the_config(tmp_path: Path) -> None:
    shutil.copy(SCENES / "table3.yaml", tmp_path / "mine.yaml")
    scene = scene_for({"scene": "mine.yaml"}, str(tmp_path))
    assert set(scene.starts) == {"heavy_leading", "heavy_trailing"}


def test_a_family_design_with_values_is_named_custom() -> None:
    cup = scene_for({"family": "fig1-cup"})
    assert design_name({"family": "fig1-cup", "values": [0.5] * 8}) == "fig1-cup-custom"
    assert cup.name == "fig1-cup"
