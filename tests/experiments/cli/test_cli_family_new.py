"""``partfeeder family new NAME --part FILE``: the family it writes loads with the project's
family loader and draws, an edited family is never replaced unasked, and bad input is one line
and exit 2 (issue 39). What the family holds is feeders/test_family_template.py's."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.cli import run
from feeders.device_family import load_family
from feeders.family_template import ENTRY_DOWN, ENTRY_UP

ROOT = Path(__file__).resolve().parents[3]
L_FILE = ROOT / "examples" / "l-part.yaml"


def test_the_written_family_loads_and_draws(tmp_path, capsys):
    out = tmp_path / "l-fig1.yaml"
    assert run(["family", "new", "l-fig1", "--part", str(L_FILE), "--out", str(out)]) == 0
    assert capsys.readouterr().out.strip() == str(out)
    family = load_family(out)
    assert family.name == "l-fig1"
    assert [name for name, _ in family.entries] == [ENTRY_UP, ENTRY_DOWN]
    picture = tmp_path / "l-fig1.png"
    assert run(["draw", "--family", str(out), "--out", str(picture)]) == 0
    assert picture.read_bytes()[:4] == b"\x89PNG"


def test_without_out_the_family_is_printed(capsys, tmp_path):
    assert run(["family", "new", "cup-fig1", "--part", "cup"]) == 0
    text = capsys.readouterr().out
    path = tmp_path / "printed.yaml"
    path.write_text(text)
    assert load_family(path).name == "cup-fig1"


def test_an_existing_family_is_replaced_only_with_force(tmp_path, capsys):
    out = tmp_path / "mine.yaml"
    out.write_text("# edited by hand\n")
    argv = ["family", "new", "mine", "--part", "cup", "--out", str(out)]
    assert run(argv) == 2
    assert "exists; give --force to replace it" in capsys.readouterr().err
    assert out.read_text() == "# edited by hand\n"
    assert run([*argv, "--force"]) == 0
    assert load_family(out).name == "mine"


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["family", "new", "x", "--part", "bowl"], "part 'bowl' is neither a file nor"),
        (["family", "new", "x", "--part", "{tmp}/missing.yaml"], "cannot read part file"),
        (["family", "new", "x", "--part", "{tmp}/flat.yaml"], "the outline has zero area"),
        (["family", "new", "x", "--part", "peg"], "cannot be built: pin B touches"),
        (["family", "new", "a/b", "--part", "cup"], "NAME = 'a/b'"),
        (["family", "new", "x", "--part", "cup", "--out", "{tmp}/x.txt"], "ends in .yaml"),
        (["family", "new", "x", "--part", "cup", "--out", "{tmp}"], "is a directory"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys, argv, says):
    (tmp_path / "flat.yaml").write_text("outline: [[0, 0], [1, 0], [3, 0]]\ndensity: 1\n")
    (tmp_path / "dir.yaml").mkdir()
    argv = [a.format(tmp=tmp_path / "dir.yaml" if a == "{tmp}" else tmp_path) for a in argv]
    assert run(argv) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert lines[0].startswith("partfeeder family: error: ") and says in lines[0]
