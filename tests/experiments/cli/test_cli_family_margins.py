"""``partfeeder margins --family`` (issue 24): a device family's design's margins over its
parameters and mu, as JSON end to end; bad ``--family`` / ``--values`` input is one line on
stderr naming the option, exit status 2."""

from __future__ import annotations

import json

import pytest
from cli_process import noise, run_cli

OPTIMUM = "0.6907,1.2855,1.2213,1.8129,1.1795,0.5437,0.1447,0.4392"  # fig1-cup's optimum (120/120)
NAMES = [
    "theta", "chute_width", "exit_width", "lip_height", "pin_dx", "pin_dy", "pin_r", "head_width",
]  # fmt: skip


@pytest.mark.slow  # ~20 s
def test_a_familys_margins_as_json_over_its_parameters_and_mu(tmp_path):
    done = run_cli(
        "margins", "--family", "fig1-cup", "--values", OPTIMUM, "--drops", "2",
        "--workers", "2", "--json", "--out", str(tmp_path / "m"),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert noise(done.stderr) == ""
    data = json.loads(done.stdout)
    assert data["works"] is True and data["design"] == "fig1-cup"
    assert data["family"] == {
        "name": "fig1-cup",
        "parameters": NAMES,
        "entries": ["open_leading", "open_trailing"],
    }
    assert data["part"] is None  # no part axes for a family
    assert list(data["values"].values()) == [float(v) for v in OPTIMUM.split(",")]
    assert [row["parameter"] for row in data["margins"]] == [*NAMES, "mu"]
    assert [row["box_source"] for row in data["margins"]] == ["the family's box"] * 8 + [
        "stated range"
    ]
    assert [row["box"] for row in data["margins"][:8]] == [
        [0.3, 0.7], [1.1, 1.3], [1.1, 1.3], [1.2, 2.2], [1.1, 1.6], [0.0, 1.0], [0.1, 0.3],
        [0.4, 1.0],
    ]  # fmt: skip
    for row in data["margins"]:
        if row["interval"] is not None:
            low, high = row["interval"]
            assert row["box"][0] <= low <= row["nominal"] <= high <= row["box"][1]
    cost = data["cost"]
    assert cost["drops"] == 2 * cost["trials"] > 0
    written = json.loads((tmp_path / "m" / "margins_fig1-cup.json").read_text())
    assert written["margins"] == data["margins"]
    assert (tmp_path / "m" / "margins_fig1-cup.png").stat().st_size > 0


BAD = {
    "unknown family": (
        ["--family", "nosuch"],
        "--family: 'nosuch' is neither a file nor a packaged family",
    ),
    "too few values": (
        ["--family", "fig1-cup", "--values", "0.4,1.2"],
        "--values: 2 numbers given; the family fig1-cup has 8 parameters",
    ),
    "not numbers": (
        ["--family", "fig1-cup", "--values", "a,b,c,d,e,f,g,h"],
        "--values = 'a,b,c,d,e,f,g,h': expected 8 comma-separated numbers",
    ),
    "not finite": (
        ["--family", "fig1-cup", "--values", "nan,1.2,1.2,1.7,1.35,0.4,0.2,0.7"],
        "--values: fig1-cup: parameter theta = nan is not finite",
    ),
    "cannot be built": (
        ["--family", "fig1-cup", "--values", "0.45,1.2,1.2,1.2,1.6,1.0,0.2,1.0"],
        "--values: the family's design cannot be built: pin B sinks into the funnel",
    ),
    "values without a family": (
        ["--values", "0.4,1.2"],
        "--values needs --family",
    ),
    "a design and a family": (
        ["--design", "table3", "--family", "fig1-cup"],
        "argument --family: not allowed with argument --design",
    ),
}


@pytest.mark.parametrize("case", BAD)
def test_bad_family_input_is_one_line_and_exit_2(case):
    args, expected = BAD[case]
    done = run_cli("margins", *args, timeout=300)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith("partfeeder margins: error: ")
    assert expected in lines[0]
    assert done.stdout == ""


def test_a_family_file_that_cannot_be_read_is_one_line_naming_the_file_and_field(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text(
        "parameters:\n  w: {low: 1, high: 2, default: 1.5}\n"
        "pieces:\n  - circle: {centre: [0, 0], radius: zeta}\n"
        "entries:\n  a: [0, 3, 0]\n"
        "goal: {x: [-1, 1], y: [-3, -2], yaw: 0, yaw_tol: 0.3}\n"
    )
    done = run_cli("margins", "--family", str(path), timeout=300)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "broken.yaml" in lines[0] and "zeta" in lines[0], done.stderr
