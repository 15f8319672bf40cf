"""Bad device-family input at the command line (issue 24): each is one line on stderr naming
the file, the field and what is allowed, and exit status 2, from ``partfeeder simulate
--family FILE`` in a process of its own.

Each case is fig1 (the packaged family) with one field broken."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest
import yaml
from cli_process import run_cli

FIG1 = yaml.safe_load(
    (Path(__file__).resolve().parents[3] / "feeders" / "families" / "fig1.yaml").read_text()
)
CUP_CLASSES = {
    "open end up": {"yaw": "-pi/2", "tolerance": "pi/4"},
    "on its side": {"yaw": [0, "pi"], "tolerance": "pi/4"},
    "open end down": {"yaw": "pi/2", "tolerance": "pi/4"},
}
GOAL_BOX = {"x": ["-exit_width/2", "exit_width/2"], "y": [-3.74, -2.2]}


def _with(path: tuple[Any, ...], value: Any) -> dict[str, Any]:
    data = copy.deepcopy(FIG1)
    *parents, last = path
    target = data
    for key in parents:
        target = target[key]
    target[last] = value
    return data


def _sunk_pin() -> dict[str, Any]:
    """Pin B of radius 0.4 at height 0.3 by default: within the box, through the floor."""
    data = _with(("parameters", "pin_r", "default"), 0.4)
    data["parameters"]["pin_y"]["default"] = 0.3
    return data


CASES = {
    "self-intersecting part outline": (
        _with(("part",), {"outline": [[0, 0], [1, 1], [1, 0], [0, 1]], "density": 1.0}),
        "part.outline: the outline intersects itself; give a simple polygon",
    ),
    "part of zero area": (
        _with(("part",), {"outline": [[0, 0], [1, 0], [2, 0]], "density": 1.0}),
        "part.outline: the outline has zero area",
    ),
    "piece of zero density": (
        _with(
            ("part",),
            {"pieces": [{"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 0.0}]},
        ),
        "part.pieces[0].density = 0.0 is outside the allowed range [1e-09, 1e+09]",
    ),
    "unknown parameter": (
        _with(("pieces", 11, "disc", "radius"), "pin_radius"),
        "pieces[11].disc.radius = 'pin_radius': unknown name 'pin_radius'; the parameters "
        "are: theta, chute_width, exit_width, pin_x, pin_y, pin_r",
    ),
    "division by zero at the default": (
        _with(("pieces", 11, "disc", "radius"), "0.25 / (theta - 0.5)"),
        "parameters: the defaults (theta = 0.5,",
    ),
    "default that breaks a rule": (
        _sunk_pin(),
        "cannot be built: pin B sinks into the cavity floor",
    ),
    "unknown orientation class": (
        {
            **_with(("goal",), {**GOAL_BOX, "orientation": "open end upright"}),
            "orientations": CUP_CLASSES,
        },
        "goal.orientation = 'open end upright': not an orientation class of the part; the "
        "classes are: open end up, on its side, open end down",
    ),
    "goal by a class of the peg's that the family does not name": (
        _with(("goal",), {**GOAL_BOX, "orientation": "open end up"}),
        "the classes are: heavy end down, heavy end up",
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_family_input_is_one_line_naming_the_file_and_field_and_exit_2(
    tmp_path: Path, case: str
) -> None:
    data, words = CASES[case]
    path = tmp_path / "family.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    done = run_cli("simulate", "--family", str(path), timeout=300)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert f"{path}: " in lines[0] and words in lines[0], lines[0]
    assert "Traceback" not in done.stderr


def test_the_division_by_zero_is_named_with_its_field_and_values(tmp_path: Path) -> None:
    data, _ = CASES["division by zero at the default"]
    path = tmp_path / "family.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    line = run_cli("simulate", "--family", str(path), timeout=300).stderr.strip()
    assert "pieces[11].disc.radius" in line and "division by zero" in line and "theta" in line


# issue 37, item 5: a value that reaches a simulation is checked for finiteness at the CLI
@pytest.mark.parametrize("command", ["simulate", "draw", "plan"])
@pytest.mark.parametrize("bad", ["nan", "inf", "-inf", "1e999"])
def test_values_that_are_not_finite_are_one_line_and_exit_2(
    tmp_path: Path, command: str, bad: str, capsys: pytest.CaptureFixture
) -> None:
    from experiments.cli import run

    values = f"0.5,1.2,1.2,{bad},1.4,0.25"
    extra = ["--out", str(tmp_path / "out.png")] if command == "draw" else []
    assert run([command, "--family", "fig1", "--values", values, *extra]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "--values" in err and "pin_x" in err and "finite" in err
    assert not (tmp_path / "out.png").exists()


# issue 37, item 7: a file of another kind given as a config or family: its keys not echoed
@pytest.mark.parametrize("given", ["run", "simulate --family", "run family:"])
def test_an_unrelated_file_of_key_value_lines_is_named_not_quoted(
    tmp_path: Path, given: str, capsys: pytest.CaptureFixture
) -> None:
    from experiments.cli import run

    secret = tmp_path / "credentials"
    secret.write_text("aws_secret_access_key: SECRETVALUE\nsession_token_name: SECRETKEY2\n")
    if given == "run":
        argv = ["run", str(secret), "--out", str(tmp_path / "out")]
    elif given == "simulate --family":
        argv = ["simulate", "--family", str(secret)]
    else:
        config = tmp_path / "sweep.yaml"
        config.write_text(f"name: s\nfamily: {secret}\n")
        argv = ["run", str(config), "--out", str(tmp_path / "out")]
    assert run(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "credentials" in err
    for word in ("aws_secret", "SECRET", "session_token"):
        assert word not in err, err


# issue 37, item 8
def test_draw_refuses_to_write_its_picture_over_the_family_file(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    from experiments.cli import run

    family = tmp_path / "fig1.svg"  # a family file whose name is a picture's
    family.write_text(yaml.safe_dump(FIG1))
    before = family.read_bytes()
    assert run(["draw", "--family", str(family), "--out", str(family)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "is the input file" in err
    assert family.read_bytes() == before


def test_a_refused_draw_leaves_no_out_directory(tmp_path: Path, capsys) -> None:
    from experiments.cli import run

    out = tmp_path / "new" / "deeper" / "pic.png"
    assert run(["draw", "--family", "fig1", "--values", "1,2", "--out", str(out)]) == 2
    assert not (tmp_path / "new").exists()
    assert run(["draw", "--family", str(tmp_path / "nowhere.yaml"), "--out", str(out)]) == 2
    assert not (tmp_path / "new").exists()
    assert capsys.readouterr().err.count("\n") == 2
