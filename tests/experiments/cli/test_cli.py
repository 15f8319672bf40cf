"""The ``partfeeder`` command as a user meets it: summaries, JSON, pictures, clear errors."""

from __future__ import annotations

import json

import pytest
from cli_process import ROOT, noise, run_cli

from experiments.cli import run

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
# A planning budget in propagations, not seconds, so a loaded machine cannot cut a run
# (issue 22); table3's geometric entries need 3,400-52,600 with rrt and seeds 1-20.
BUDGET = ("--propagations", "200000")


_cli = run_cli


def test_plan_both_orientations_prints_summary_and_writes_picture(tmp_path):
    """A normal run: a table on stdout, nothing on stderr (no OMPL log, no nanobind leak lines)."""
    out = tmp_path / "out"
    proc = _cli(
        "plan",
        "--design",
        "table3",
        "--level",
        "geometric",
        "--planner",
        "rrt",
        "--orientation",
        "both",
        *BUDGET,
        "--seed",
        "1",
        "--out",
        str(out),
    )
    assert proc.returncode == 0, proc.stderr
    assert noise(proc.stderr) == ""
    lines = proc.stdout.splitlines()
    assert any(line.startswith("heavy_leading") and " yes " in line for line in lines)
    assert any(line.startswith("heavy_trailing") and " yes " in line for line in lines)
    picture = out / "plan_table3_geometric_rrt.png"
    assert picture.read_bytes()[:8] == PNG_MAGIC
    assert "leaked" not in proc.stdout + proc.stderr and "Info:" not in proc.stdout


def test_verbose_shows_ompl_log():
    proc = _cli(
        "plan", "--design", "table3", "--orientation", "heavy_trailing", *BUDGET, "--verbose"
    )
    assert proc.returncode == 0
    assert "RRT" in proc.stdout + proc.stderr


def test_json_output_is_machine_readable(capsys):
    assert run(["plan", "--design", "table3", *BUDGET, "--seed", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [r["orientation"] for r in data["runs"]] == ["heavy_leading", "heavy_trailing"]
    for r in data["runs"]:
        assert r["solved"] is True and r["tree_size"] > 1 and r["path_length"] > 0
        assert r["seed"] == 2 and r["level"] == "geometric" and r["planner"] == "rrt"


def test_twelve_values_and_scene_file_are_accepted(tmp_path, capsys):
    values = "1.1,1.1086,0.7979,3.0078,-1.9,-0.9849,1.0098,0.733,2.0388,0.101,0.4673,1.0472"
    argv = ["--orientation", "heavy_trailing", *BUDGET, "--json"]
    assert run(["plan", "--design", values, *argv]) == 0
    by_values = json.loads(capsys.readouterr().out)["runs"][0]
    scene = tmp_path / "t3.yaml"
    scene.write_text("feeder:\n  preset: table3\n")
    assert run(["plan", "--scene", str(scene), *argv]) == 0
    by_file = json.loads(capsys.readouterr().out)["runs"][0]
    # Same geometry and seed: the same plan.
    assert by_values["tree_size"] == by_file["tree_size"]
    assert by_values["path_length"] == by_file["path_length"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--design", "fig99"], "unknown design preset 'fig99'; presets: fig4"),
        (["--design", "1,2,3"], "a design has 12 values"),
        (["--design", "1.1,1.1,0.8,3,-1.5,-0.8,1,1,2,99,0.5,1"], "'r'"),
        (["--scene", "/no/such/scene.yaml"], "cannot read scene file"),
        (["--orientation", "sideways"], "--orientation 'sideways'"),
        (["--time", "-1"], "--time = -1.0 is outside the allowed range"),
        (["--propagations", "0"], "--propagations = 0 is outside the allowed range"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, args, message):
    assert run(["plan", *args]) == 2
    err = capsys.readouterr().err
    assert message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_out_of_range_value_names_field_and_range(capsys):
    assert run(["plan", "--design", "1.1,1.1,0.8,3,-1.5,-0.8,1,1,2,99,0.5,1"]) == 2
    err = capsys.readouterr().err
    assert "'r'" in err and "[0.01, 5]" in err


def test_bad_yaml_is_one_line_error_in_a_real_process(tmp_path):
    scene = tmp_path / "bad.yaml"
    scene.write_text("feeder: {preset: table3}\nfriction: -2\n")
    proc = _cli("plan", "--scene", str(scene))
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert "friction" in proc.stderr and "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def test_draw_writes_a_picture(tmp_path, capsys):
    target = tmp_path / "pics" / "fig7a.png"
    assert run(["draw", "--design", "fig7a", "--out", str(target)]) == 0
    assert target.read_bytes()[:8] == PNG_MAGIC


@pytest.mark.slow  # ~20 s
def test_simulate_reports_both_drops_and_writes_strip_animation_and_json(tmp_path):
    """``partfeeder simulate``: a row per entry orientation (goal, why it ended, T, overlap,
    energy rise, LCP failures) and Eq. 10's objective; the strip (PNG), the animation (GIF)
    and the summaries (JSON) in --out; nothing on stderr."""
    out = tmp_path / "drop"
    proc = _cli("simulate", "--design", "table3", "--time", "4", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    assert noise(proc.stderr) == ""
    assert "heavy_leading" in proc.stdout and "heavy_trailing" in proc.stdout
    assert "Eq. 10 objective" in proc.stdout
    assert (out / "drop_table3.png").read_bytes()[:8] == PNG_MAGIC
    assert (out / "drop_table3.gif").read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    runs = json.loads((out / "drop_table3.json").read_text())["runs"]
    assert [r["orientation"] for r in runs] == ["heavy_leading", "heavy_trailing"]
    for r in runs:
        assert r["lcp_failures"] == 0 and r["energy_rise"] <= 1e-9
        assert 0.0 < r["T_s"] <= 4.0


def test_simulate_json_on_a_free_form_scene(capsys):
    """The incline scene from YAML: its one start, the box slides into the goal box."""
    code = run(["simulate", "--scene", str(ROOT / "experiments/scenes/incline.yaml"), "--json"])
    assert code == 0
    report = json.loads(capsys.readouterr().out)
    (only,) = report["runs"]
    assert only["orientation"] == "resting"
    assert only["end"] == "crossed" and only["success"]


@pytest.mark.parametrize(
    "args,message",
    [
        (["simulate", "--step", "0"], "--step = 0.0 is outside the allowed range"),
        (["simulate", "--time", "-1"], "--time = -1.0 is outside the allowed range"),
        (["simulate", "--orientation", "sideways"], "--orientation 'sideways' is not a start"),
    ],
)
def test_simulate_bad_input_is_one_line_and_exit_2(capsys, args, message):
    assert run(args) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
