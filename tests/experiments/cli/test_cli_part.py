"""``partfeeder part FILE|NAME``: what it reports agrees with feeders.cup and shapely, its
picture is written, and bad input is one line and exit 2 (issue 39).

References: the cup's U outline built from feeders.cup's dimensions and measured by shapely
(Polygon.area, Polygon.centroid); a rectangle's inertia m (w^2 + h^2) / 12."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
import shapely
import yaml

from experiments.cli import run
from experiments.cli.part import SHIPPED_NAMES
from feeders.cup import CUP_HEIGHT, CUP_WALL, CUP_WIDTH, cup_part
from feeders.part_file import SHIPPED_PARTS

ROOT = Path(__file__).resolve().parents[3]
L_FILE = ROOT / "examples" / "l-part.yaml"


def _json(capsys, *argv: str) -> dict:
    assert run(["part", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _u_outline() -> shapely.Polygon:
    h, half, inner = CUP_HEIGHT, CUP_WIDTH / 2, CUP_WIDTH / 2 - CUP_WALL
    return shapely.Polygon(
        [(0, -half), (h, -half), (h, half), (0, half), (0, inner), (h - CUP_WALL, inner),
         (h - CUP_WALL, -inner), (0, -inner)]
    )  # fmt: skip


def test_the_cups_report_agrees_with_feeders_cup_and_shapely(capsys):
    report = _json(capsys, "cup")
    u = _u_outline()
    assert report["part"] == "cup"
    assert report["mass"] == pytest.approx(cup_part().mass, rel=1e-12)
    assert report["area"] == pytest.approx(u.area, rel=1e-12)
    assert report["centre_of_mass"] == pytest.approx([u.centroid.x, u.centroid.y], abs=1e-12)
    assert report["centre_of_mass"] == pytest.approx([0.555, 0.0], abs=1e-12)  # docs/parts.md
    assert report["inertia"] == pytest.approx(cup_part().inertia, rel=1e-12)
    poses = report["stable_poses"]
    assert len(poses) == 4
    assert [p["yaw"] for p in poses] == pytest.approx(
        [-math.pi, -math.pi / 2, 0.0, math.pi / 2], abs=1e-12
    )
    base_down = [v for point in poses[1]["face"] for v in point]
    assert base_down == pytest.approx([0.9, -0.5, 0.9, 0.5], abs=1e-12)


def test_a_rectangle_files_inertia_is_the_closed_form(tmp_path, capsys):
    w, h, rho = 1.6, 0.4, 2.5
    path = tmp_path / "plate.yaml"
    path.write_text(yaml.safe_dump({"outline": [[0, 0], [w, 0], [w, h], [0, h]], "density": rho}))
    report = _json(capsys, str(path))
    m = rho * w * h
    assert report["mass"] == pytest.approx(m, rel=1e-12)
    assert report["inertia"] == pytest.approx(m * (w * w + h * h) / 12.0, rel=1e-12)
    assert report["centre_of_mass"] == pytest.approx([w / 2, h / 2], abs=1e-12)


def test_the_text_report_names_each_number(capsys):
    assert run(["part", "cup"]) == 0
    out = capsys.readouterr().out
    assert "centre of mass      (0.555, 0) in the part's frame" in out
    assert "mass                1\n" in out and "area                0.375\n" in out
    assert "inertia             0.220308 about the centre of mass" in out
    assert "stable poses        4 on a floor" in out
    assert "face (0.9, -0.5) to (0.9, 0.5)" in out


def test_a_family_names_each_pose_by_its_orientation_class(capsys):
    report = _json(capsys, "cup", "--family", "fig1-cup")
    named = [p["orientation"] for p in report["stable_poses"]]
    assert named == ["on its side", "open end up", "on its side", "open end down"]
    assert [c["name"] for c in report["orientations"]] == [
        "open end up", "open end down", "on its side",
    ]  # fmt: skip


def test_out_draws_the_part_its_poses_and_a_familys_classes(tmp_path, capsys):
    out = tmp_path / "pics" / "l.png"
    assert run(["part", str(L_FILE), "--family", "fig1-cup", "--out", str(out)]) == 0
    assert f"picture: {out}" in capsys.readouterr().out
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000


def test_the_cli_names_the_shipped_parts_feeders_ships():
    assert set(SHIPPED_NAMES) == set(SHIPPED_PARTS)


def _one_line(capsys, argv: list[str]) -> str:
    assert run(argv) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


@pytest.mark.parametrize(
    ("content", "argv", "says"),
    [
        (None, ["part", "{tmp}/missing.yaml"], "cannot read part file '{tmp}/missing.yaml'"),
        (None, ["part", "bowl"], "part 'bowl' is neither a file nor a shipped part"),
        (
            "part: {outline: [[0, 0], [1, 1], [2, 2]], density: 1}",
            ["part", "{tmp}/p.yaml"],
            "part.outline: the outline has zero area",
        ),
        (None, ["part", "cup", "--out", "{tmp}/x.txt"], "--out '{tmp}/x.txt'"),
        (None, ["part", "cup", "--family", "nosuch"], "--family: 'nosuch'"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys, content, argv, says):
    if content is not None:
        (tmp_path / "p.yaml").write_text(content)
    line = _one_line(capsys, [a.format(tmp=tmp_path) for a in argv])
    assert line.startswith("partfeeder part: error: ") and says.format(tmp=tmp_path) in line
