"""Specification of feeders.scene_spec: every way a user names a design gives the same scene,
and a bad one is one ValueError naming what is wrong.

References: build_feeder and load_scene (the spec layer must not change the device or the
file's scene), the paper's Table 3 values typed in."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from feeders.design import PRESETS, DesignError, DesignParameters
from feeders.feeder import build_feeder
from feeders.scene_spec import CUSTOM_DESIGN, design_of_text, design_scene, scene_of
from feeders.scene_yaml import SceneError, load_scene

SCENES = Path(__file__).resolve().parents[2] / "experiments" / "scenes"
TABLE3 = [1.1, 1.1086, 0.7979, 3.0078, -1.9, -0.9849, 1.0098, 0.733, 2.0388, 0.101, 0.4673, 1.0472]


@pytest.mark.parametrize(
    "spec",
    [
        "table3",
        " table3 ",
        TABLE3,
        tuple(TABLE3),
        np.array(TABLE3),
        ",".join(map(str, TABLE3)),
        ", ".join(map(str, TABLE3)),
        DesignParameters.from_vector(TABLE3),
    ],
    ids=["name", "padded", "list", "tuple", "array", "text", "spaced", "parameters"],
)
def test_every_form_of_table3_is_table3s_feeder(spec) -> None:
    scene = scene_of(spec)
    assert scene.design == PRESETS["table3"]
    reference = build_feeder(PRESETS["table3"])
    assert scene.bounds == reference.bounds and scene.starts == reference.starts
    assert scene.goal == reference.goal


def test_a_preset_is_named_after_itself_and_values_are_a_custom_design() -> None:
    assert scene_of("fig7a").name == "fig7a"
    assert scene_of(TABLE3).name == CUSTOM_DESIGN
    assert design_scene("1.1,1.1,0.75,2.5,-1,-0.6,0.5,0.2,1.5,0.1,0.3,0.9").name == CUSTOM_DESIGN


def test_a_scene_file_by_path_or_text_is_the_files_scene() -> None:
    by_loader = load_scene(SCENES / "incline.yaml")
    for spec in (SCENES / "incline.yaml", str(SCENES / "incline.yaml")):
        scene = scene_of(spec)
        assert (scene.name, scene.starts, scene.goal) == (
            "incline",
            by_loader.starts,
            by_loader.goal,
        )
        assert np.array_equal(scene.obstacles.polygons[0], by_loader.obstacles.polygons[0])


def test_text_that_names_a_file_in_the_working_directory_is_that_file(tmp_path, monkeypatch):
    (tmp_path / "mine").write_text("feeder: {preset: fig4}\nfriction: 0.4\n")
    monkeypatch.chdir(tmp_path)
    scene = scene_of("mine")
    assert scene.design == PRESETS["fig4"] and scene.friction == 0.4


def test_a_scene_is_returned_checked_and_unchanged() -> None:
    scene = dataclasses.replace(scene_of("table3"), friction=0.05)
    assert scene_of(scene) is scene
    buried = dataclasses.replace(scene, starts={"heavy_leading": (0.0, -50.0, 0.0)})
    with pytest.raises(SceneError, match="start"):
        scene_of(buried)


@pytest.mark.parametrize(
    ("spec", "error", "says"),
    [
        ("fig99", DesignError, "unknown design preset 'fig99'; presets: fig4"),
        ("", DesignError, "design is empty"),
        ("1,2,3", DesignError, "a design has 12 values"),
        ("1,x,3", DesignError, "is not 12 comma-separated numbers"),
        ([1.0] * 3, DesignError, "a design has 12 values"),
        (["a"] * 12, DesignError, "must be 12 numbers"),
        ([*TABLE3[:9], 99.0, *TABLE3[10:]], DesignError, "'r'"),
        ([*TABLE3[:4], float("nan"), *TABLE3[5:]], DesignError, "'e'"),
        ([*TABLE3[:1], 0.5, *TABLE3[2:]], SceneError, "degenerate design: exit chute width"),
        ("no/such/scene.yaml", SceneError, "cannot read scene file"),
        ("missing.yaml", SceneError, "cannot read scene file"),
    ],
)
def test_a_bad_design_is_one_valueerror_naming_it(spec, error, says) -> None:
    with pytest.raises(error) as caught:
        scene_of(spec)
    assert isinstance(caught.value, ValueError)
    message = str(caught.value)
    assert says in message and "\n" not in message


def test_something_that_is_no_design_is_a_typeerror_saying_what_is() -> None:
    with pytest.raises(TypeError, match="preset name, 12 values"):
        scene_of(3)  # type: ignore[arg-type]


def test_design_text_never_reads_a_file(tmp_path, monkeypatch) -> None:
    (tmp_path / "table3.yaml").write_text("feeder: {preset: fig4}\n")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(DesignError, match=r"unknown design preset 'table3\.yaml'"):
        design_of_text("table3.yaml")


def test_the_spec_layer_is_pure_data() -> None:
    code = "import sys, feeders.scene_spec; print(sorted({'ompl', 'numba'} & set(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
