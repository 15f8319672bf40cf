"""Issue 16's families of bad input, as fixed cases through the ``partfeeder`` entry point:
each is exit status 2 and exactly one line on stderr naming what is wrong, never a traceback,
and nothing written where nothing may be. A real bug still shows its traceback. At the end, a
seeded CI-sized sample of the malformed-input corpus (``bad_input_corpus.py``) run as users run
it, each case classified independently of the code under test (exit status and stderr only).
"""

from __future__ import annotations

import os
import sqlite3
from pathlib import Path

import pytest
import yaml
from bad_input_corpus import (
    BASE_CONFIG,
    BASE_SCENE,
    DELETE,
    corpus,
    damage_database,
    make_template_database,
    run_corpus,
    sample,
    with_value,
)
from cli_process import run_cli

from experiments.cli import run
from experiments.sweep.lock import sweep_lock

# A hang guard only: a bad input is answered in well under a second, a control runs in
# seconds; only a hang reaches it, never a loaded machine (issue 22: a 10 s limit did).
HANG_S = 300.0


def _one_line_error(capsys, argv: list[str]) -> str:
    """Run ``argv``; assert exit 2 and one line on stderr; return that line."""
    assert run(argv) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def _write(tmp_path: Path, name: str, doc: object) -> Path:
    path = tmp_path / name
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    return path


def _config(tmp_path: Path, doc: object = BASE_CONFIG) -> Path:
    return _write(tmp_path, "cfg.yaml", doc)


# -- run configs ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("path", "value", "says"),
    [
        ("feeder.gravity", [0.0, 1e308], "feeder.gravity"),
        ("feeder.part.mass", 0, "mass"),
        ("feeder.part.length", 1e308, "length"),
        ("ladder.0.planners", ["rrt", "rrt"], "names a planner twice"),
        ("ladder.0.planners", ["rrt", "RRT"], "names a planner twice"),
        ("name", "n" * 5000, "name: 5000 characters"),
        ("name", "../escape", "cannot hold '/'"),
        ("designs.count", 10**400, "designs.count"),
        ("ladder.0.budget.time", float("nan"), "ladder[0].budget.time"),
        ("workers", DELETE, None),  # a control: workers is optional
    ],
)
def test_a_bad_run_config_is_one_line_naming_the_field(
    tmp_path: Path, capsys, monkeypatch, path: str, value: object, says: str | None
) -> None:
    reached = []
    monkeypatch.setattr(
        "experiments.sweep.ladder.run_sweep", lambda *a, **k: reached.append(a) or 1 / 0
    )
    config = _config(tmp_path, with_value(BASE_CONFIG, path, value))
    out = tmp_path / "sweep"
    if says is None:
        with pytest.raises(ZeroDivisionError):  # the stand-in job was reached
            run(["run", str(config), "--out", str(out), "--quiet"])
        assert len(reached) == 1
        return
    line = _one_line_error(capsys, ["run", str(config), "--out", str(out), "--quiet"])
    assert says in line and "cfg.yaml" in line
    assert not reached and not out.exists()


@pytest.mark.parametrize(
    ("body", "says"),
    [
        ("a: &a [x, x]\nb: [*a, *a]\n", "aliases"),
        ("[" * 1000 + "]" * 1000, "nested deeper"),
        (b"name: caf\xe9\n", "not UTF-8"),
        ("workers: " + "9" * 5000 + "\n", "4300 digits"),
    ],
)
def test_a_config_that_is_not_a_sound_document_is_one_line(
    tmp_path: Path, capsys, body: str | bytes, says: str
) -> None:
    config = tmp_path / "cfg.yaml"
    config.write_bytes(body if isinstance(body, bytes) else body.encode())
    assert says in _one_line_error(capsys, ["run", str(config), "--out", str(tmp_path / "s")])


def test_a_fifo_or_device_as_config_is_refused_at_once(tmp_path: Path, capsys) -> None:
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    for path in (fifo, Path("/dev/zero")):
        line = _one_line_error(capsys, ["run", str(path), "--out", str(tmp_path / "s")])
        assert "not a regular file" in line


SHADOW = (  # /etc/shadow's form; the tab and ': ' on the second line break YAML
    "root:$6$SECRETsalt$SECREThashhash:19000:0:99999:7:::\n"
    "operator:\t$6$SECRET2salt: 19000:0:99999:7:::\n"
    "SECRETkey: 1\n"
)


@pytest.mark.parametrize(
    ("text", "line"),
    [
        (SHADOW, 2),
        ("SECRETkey: 1\nSECRETkey: 2\n", 2),  # a repeated key was quoted
        ("name: !SECRETtag box\n", 1),  # so was a tag
    ],
)
@pytest.mark.parametrize("command", ["run", "optimize", "plan", "stress"])
def test_a_file_that_is_not_yaml_is_named_by_line_never_echoed(
    tmp_path: Path, capsys, command: str, text: str, line: int
) -> None:
    """Issue 23: a config that is /etc/shadow (or any non-YAML text) had its text in the
    error. Every file read as YAML (run and optimisation configs, scenes, stress cases) is
    named with the line and column where it stops being YAML, and none of its text."""
    path = tmp_path / "secrets"
    path.write_text(text)
    argv = {
        "run": ["run", str(path), "--out", str(tmp_path / "out")],
        "optimize": ["optimize", str(path), "--out", str(tmp_path / "out")],
        "plan": ["plan", "--scene", str(path), "--time", "0.2"],
        "stress": ["stress", "--replay", str(path)],
    }[command]
    said = _one_line_error(capsys, argv)
    assert f"{path}' is not valid YAML" in said and f"(line {line}, column" in said
    assert "SECRET" not in said and "$6$" not in said and "19000" not in said
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("name", [" corpus", "corpus ", "\u00a0corpus"])
def test_a_name_with_space_at_an_end_is_refused_not_stripped(
    tmp_path: Path, capsys, name: str
) -> None:
    """Issue 23: a config name with a leading space ran, and OMPL's log reader stripped it
    (the sweep was recorded under another name than the one written). Refused, naming it."""
    config = _config(tmp_path, with_value(BASE_CONFIG, "name", name))
    out = tmp_path / "sweep"
    said = _one_line_error(capsys, ["run", str(config), "--out", str(out), "--quiet"])
    assert "cfg.yaml" in said and "name = " in said and "white space" in said
    assert not out.exists()


# -- scenes and designs --------------------------------------------------------------------


@pytest.mark.parametrize(
    ("path", "value", "says"),
    [
        ("starts.drop", [4.0, 0.0, 0.0], "starts.drop: the part there overlaps"),
        ("starts.drop", [9.0, 0.0, 0.0], "inside the bounds"),
        ("starts.drop", [0.0, 0.0, 1e308], "yaw"),
        ("goal.x", [20, 30], "goal"),
        ("part", {"length": 100, "width": 50}, "part.length"),
        ("bounds", [-1e308, 1e308, -5, 5], "bounds"),
        ("gravity", [0.0, -1e308], "gravity"),
        ("obstacles.0.polygon.0", [1e308, -4], "obstacles[0].polygon[0]"),
        ("starts", {f"s{i}": [0, 0, 0] for i in range(10_000)}, "at most 100"),
    ],
)
@pytest.mark.parametrize("command", ["plan", "draw", "simulate"])
def test_a_nonsense_scene_is_refused_by_every_command_that_reads_one(
    tmp_path: Path, capsys, command: str, path: str, value: object, says: str
) -> None:
    scene = _write(tmp_path, "scene.yaml", with_value(BASE_SCENE, path, value))
    extra = {"plan": ["--time", "0.2"], "draw": ["--out", str(tmp_path / "p.png")]}
    line = _one_line_error(capsys, [command, "--scene", str(scene), *extra.get(command, [])])
    assert says in line and "scene.yaml" in line


@pytest.mark.parametrize(
    ("design", "says"),
    [
        ("", "--design is empty"),
        ("  ", "--design is empty"),
        ("d" * 5000, "characters)"),  # shortened, not 5,000 characters on the line
        ("1,2,3", "12 values"),
        (",".join(["nan"] * 12), "outside the allowed range"),
    ],
)
def test_a_bad_design_is_one_line(capsys, design: str, says: str) -> None:
    line = _one_line_error(capsys, ["plan", "--design", design, "--time", "0.2"])
    assert says in line and len(line) < 1100


# -- output directories --------------------------------------------------------------------


@pytest.mark.parametrize(
    ("target", "says"),
    [
        ("{tmp}/file.txt", "is an existing file"),
        ("{tmp}/cfg.yaml", "is the input file"),
        ("{tmp}/file.txt/sub", "is a file, not a directory"),
        ("/proc/partfeeder-out", "cannot write in '/proc'"),
        ("{tmp}/" + "o" * 5000, "bytes long"),
        ("{tmp}/" + "c" * 300 + "/x", "a file name has at most 255"),
    ],
)
def test_an_out_directory_that_cannot_be_one_is_refused_and_nothing_is_written(
    tmp_path: Path, capsys, target: str, says: str
) -> None:
    config = _config(tmp_path)
    (tmp_path / "file.txt").write_text("a file\n")
    before = {p: p.read_bytes() for p in tmp_path.iterdir()}
    out = target.replace("{tmp}", str(tmp_path))
    line = _one_line_error(capsys, ["run", str(config), "--out", out, "--quiet"])
    assert "--out" in line and says in line
    assert {p: p.read_bytes() for p in tmp_path.iterdir()} == before  # nothing new, nothing changed


def test_draw_refuses_to_overwrite_its_scene_or_write_an_unknown_format(tmp_path, capsys):
    scene = _write(tmp_path, "scene.yaml", BASE_SCENE)
    before = scene.read_bytes()
    assert "is the input file" in _one_line_error(
        capsys, ["draw", "--scene", str(scene), "--out", str(scene)]
    )
    assert ".png" in _one_line_error(
        capsys, ["draw", "--scene", str(scene), "--out", str(tmp_path / "x.yaml")]
    )
    assert scene.read_bytes() == before


# -- scheduler, lock, database -------------------------------------------------------------


def test_an_unreachable_scheduler_is_one_line_naming_it(tmp_path: Path, capsys) -> None:
    config = _config(tmp_path)
    argv = ["run", str(config), "--out", str(tmp_path / "s"), "--executor", "dask"]
    line = _one_line_error(capsys, [*argv, "--scheduler", "tcp://127.0.0.1:1"])
    assert "tcp://127.0.0.1:1" in line and "Connection refused" in line
    assert not (tmp_path / "s").exists()


def test_a_directory_in_use_is_refused_naming_the_holder(tmp_path: Path, capsys) -> None:
    config = _config(tmp_path)
    out = tmp_path / "sweep"
    out.mkdir()
    with sweep_lock(out):
        line = _one_line_error(capsys, ["run", str(config), "--out", str(out), "--quiet"])
    assert f"pid {os.getpid()}" in line and "in use by another partfeeder run" in line
    assert not (out / "results.sqlite").exists()


@pytest.fixture(scope="module")
def results_template(tmp_path_factory) -> Path:
    """A real sweep's results database (BASE_CONFIG, one design, the geometric rung)."""
    return make_template_database(tmp_path_factory.mktemp("template"), dict(os.environ))


@pytest.mark.parametrize(
    "damage",
    [
        "truncate-half",
        "truncate-minus-100",
        "garbage-header-16",
        "garbage-page-2",
        "data-page-runs@0",
        "data-page-designs@1",
        "data-page-evaluations@2",
        "wrong-schema-missing-column",
        "text-file",
    ],
)
@pytest.mark.parametrize("command", ["report", "run"])
def test_a_damaged_results_database_is_refused_and_left_as_it_was(
    tmp_path: Path, capsys, results_template: Path, damage: str, command: str
) -> None:
    out = tmp_path / "sweep"
    out.mkdir()
    db = out / "results.sqlite"
    db.write_bytes(results_template.read_bytes())
    damage_database(db, damage)
    before = db.read_bytes()
    config = _config(tmp_path)
    argv = ["report", str(out)] if command == "report" else ["run", str(config), "--out", str(out)]
    line = _one_line_error(capsys, [*argv, "--quiet"] if command == "run" else argv)
    assert "results database" in line and "move it aside" in line
    assert db.read_bytes() == before


def test_the_sound_template_database_reports(results_template: Path, capsys) -> None:
    """The control of the damage cases: the same file undamaged is reported."""
    db = sqlite3.connect(results_template)
    assert db.execute("SELECT count(*) FROM evaluations").fetchone()[0] == 1
    db.close()
    assert run(["report", str(results_template.parent), "--json"]) == 0


# -- what is not bad input keeps its traceback ---------------------------------------------


@pytest.mark.parametrize(
    "error",
    [KeyError("x"), ValueError("ours"), sqlite3.ProgrammingError("ours"), OSError(5, "EIO")],
)
def test_a_bug_is_not_dressed_as_bad_input(monkeypatch, error: Exception) -> None:
    def broken(args):
        raise error

    monkeypatch.setattr("experiments.cli.draw.run", broken)
    with pytest.raises(type(error)):
        run(["draw", "--design", "table3", "--out", "x.png"])


# -- as users run it: fresh processes, and a sample of the corpus ----------------------------


def test_fresh_processes_answer_bad_input_in_one_line(tmp_path: Path) -> None:
    bomb = tmp_path / "bomb.yaml"
    bomb.write_text("a: &a [x, x]\nb: [*a, *a]\n")
    for argv in (
        ("run", str(bomb)),
        ("run", str(_config(tmp_path)), "--out", "/proc/partfeeder"),
        ("plan", "--design", ""),
        ("plan", "--time", "soon"),
    ):
        proc = run_cli(*argv, timeout=HANG_S)
        assert proc.returncode == 2, proc.stderr
        assert len(proc.stderr.strip().splitlines()) == 1 and "Traceback" not in proc.stderr


@pytest.mark.slow  # ~30 s
def test_a_sample_of_the_corpus_is_refused_cleanly_and_the_controls_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Three seeded cases of every family (and the controls), each in a forked process: every
    malformed case must be a clean one-line exit 2 with its protected files unchanged; every
    control must run. With the suite's numba cache (the corpus's default is a fresh one in
    its scratch directory, where every control compiled the kernels again), restored after."""
    monkeypatch.setenv("NUMBA_CACHE_DIR", os.environ.get("NUMBA_CACHE_DIR", ""))
    cases = sample(corpus(), per_family=3, seed=16)
    outcomes = run_corpus(cases, tmp_path, timeout=HANG_S)
    wrong = [
        (o.case.family, o.case.name, o.outcome, o.stderr[-300:])
        for o in outcomes
        if o.outcome != ("accepted" if o.case.valid else "clean")
    ]
    assert not wrong
