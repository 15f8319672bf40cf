"""Specification of ``--design`` and ``--scene`` (experiments/cli/scenes.py): ``--scene`` takes
a file or the name of a scene packaged with partfeeder, from any directory; ``--design`` takes
a preset or 12 values and never reads a file; every problem is one line naming what to fix.

References: feeders.scene_yaml.load_scene on the repository's own experiments/scenes files
(the packaged scenes must be those files), and feeders.design.PRESETS."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from experiments.cli.scenes import (
    SCENE_EXAMPLES,
    load_scene,
    packaged_scene_names,
    scene_path,
)
from experiments.cli.usage import UsageError
from feeders.design import PRESETS
from feeders.scene_yaml import load_scene as load_file

SCENES = Path(__file__).resolve().parents[3] / "experiments" / "scenes"


def test_the_packaged_scenes_are_the_repositorys_scene_files() -> None:
    assert packaged_scene_names() == sorted(p.stem for p in SCENES.glob("*.yaml"))
    assert set(SCENE_EXAMPLES) <= set(packaged_scene_names())  # what --scene's help names


@pytest.mark.parametrize("given", ["incline", "incline.yaml"])
def test_a_packaged_scene_by_name_from_another_directory(tmp_path, monkeypatch, given) -> None:
    monkeypatch.chdir(tmp_path)
    scene = load_scene(None, Path(given))
    reference = load_file(SCENES / "incline.yaml")
    assert (scene.name, scene.starts, scene.goal) == ("incline", reference.starts, reference.goal)


def test_a_file_of_that_name_comes_first(tmp_path, monkeypatch) -> None:
    (tmp_path / "table3").write_text("feeder: {preset: fig4}\nname: mine\n")
    monkeypatch.chdir(tmp_path)
    assert load_scene(None, Path("table3")).design == PRESETS["fig4"]
    assert scene_path(Path("table3")) == Path("table3")


@pytest.mark.parametrize(
    ("given", "says"),
    [
        ("tabel3", "'tabel3' is neither a file nor a packaged scene; packaged scenes: "),
        ("sub/table3.yaml", "cannot read scene file 'sub/table3.yaml'"),
    ],
)
def test_a_scene_that_is_neither_is_one_line(tmp_path, monkeypatch, given, says) -> None:
    monkeypatch.chdir(tmp_path)
    with pytest.raises(UsageError) as caught:
        load_scene(None, Path(given))
    message = str(caught.value)
    assert says in message and "\n" not in message
    if "packaged" in says:
        assert "table3" in message and "incline" in message


@pytest.mark.parametrize(
    ("design", "says"),
    [
        ("", "--design is empty"),
        ("fig99", "unknown design preset 'fig99'; presets: fig4"),
        ("1,2", "a design has 12 values"),
        ("1,a,2", "is not 12 comma-separated numbers"),
        ("table3.yaml", "unknown design preset 'table3.yaml'"),  # a design, never a file
    ],
)
def test_a_bad_design_is_one_line(tmp_path, monkeypatch, design, says) -> None:
    (tmp_path / "table3.yaml").write_text("feeder: {preset: fig4}\n")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(UsageError) as caught:
        load_scene(design, None)
    assert says in str(caught.value) and "\n" not in str(caught.value)


def test_the_default_and_a_preset_name_their_scene() -> None:
    assert load_scene(None, None).name == "table3"
    assert load_scene("fig8a", None).design == PRESETS["fig8a"]
    assert load_scene(",".join(map(str, PRESETS["fig4"].to_vector())), None).name == (
        "custom design"
    )


def test_partfeeder_plans_a_packaged_scene_by_name_outside_the_repository(tmp_path) -> None:
    proc = subprocess.run(
        [sys.executable, "-c", "from experiments.cli import main; main()", "plan",
         "--scene", "drop", "--level", "geometric", "--time", "0.2", "--json"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert '"scene": "drop"' in proc.stdout and '"orientation": "above_pin"' in proc.stdout


def _values(**changed: float) -> str:
    """table3's 12 values as ``--design`` takes them, with ``changed`` ones replaced."""
    from feeders.design import PARAMETER_NAMES, preset

    values = dict(zip(PARAMETER_NAMES, preset("table3").to_vector(), strict=True))
    return ",".join(repr(float(v)) for v in {**values, **changed}.values())


def test_a_design_outside_table_2s_box_is_used_with_one_line_naming_the_value_and_box(
    capsys,
) -> None:
    """Issue 39: ``--design`` with a = 9 planned without a word. Table 2's box for a is
    [1.1, 1.2] (feeders.design.TABLE2_BOUNDS, the paper's Table 2)."""
    scene = load_scene(_values(a=9.0), None)
    err = capsys.readouterr().err
    assert scene.name == "custom design"
    assert err == (
        "partfeeder: warning: --design: a = 9 is outside Table 2's box [1.1, 1.2]; used as given\n"
    )


def test_every_parameter_outside_the_box_is_named_in_the_one_line(capsys) -> None:
    load_scene(_values(d=6.0, theta=0.2), None)
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "d = 6 is outside Table 2's box [2.5, 5], theta = 0.2 is outside" in err


@pytest.mark.parametrize("design", [None, "table3", "fig5a", "table3-values"])
def test_a_design_inside_the_box_or_a_paper_preset_says_nothing(capsys, design) -> None:
    # fig5a's theta = 0.235 lies below the box: the paper's own design, named by its preset
    load_scene(_values() if design == "table3-values" else design, None)
    assert capsys.readouterr().err == ""


def test_a_baseline_outside_the_box_gets_the_same_line(capsys) -> None:
    from experiments.cli.baseline import baseline_of

    label, values = baseline_of(_values(a=9.0))
    assert (label, values[0]) == ("baseline", 9.0)
    assert capsys.readouterr().err == (
        "partfeeder: warning: --baseline: a = 9 is outside Table 2's box [1.1, 1.2]; "
        "used as given\n"
    )


class Stopped(Exception):
    """Raised where a command's work would start: its design was read by then."""


@pytest.mark.parametrize(
    ("command", "work"),
    [
        ("plan", "experiments.cli.plan.compile_once"),
        ("simulate", "experiments.cli.simulate.compile_once"),
        ("margins", "experiments.cli.margins.compile_once"),
        ("draw", "experiments.pictures.scenes.scene_figure"),
    ],
)
def test_each_command_that_takes_design_warns_before_its_work(
    tmp_path, monkeypatch, capsys, command, work
) -> None:
    """The one shared check (scenes.load_scene) warns in every command taking ``--design``."""
    from experiments.cli import entry

    def stop(*args: object, **kwargs: object) -> None:
        raise Stopped

    monkeypatch.setattr(work, stop)
    out = ["--out", str(tmp_path / "d.png")] if command == "draw" else []
    with pytest.raises(Stopped):
        entry.run([command, "--design", _values(a=9.0), *out])
    assert capsys.readouterr().err == (
        "partfeeder: warning: --design: a = 9 is outside Table 2's box [1.1, 1.2]; used as given\n"
    )
