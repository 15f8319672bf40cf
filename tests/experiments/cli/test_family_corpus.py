"""A malformed-family corpus (issue 37): over 300 generated cases over run configs, family
files (``--family`` and a config's ``family:``), parts inside a family and the family texts a
sweep's database stores. Every case must end in exit status 2 with one line on stderr, no
traceback, within seconds, without a file it was given being changed; a few of the biggest
run in a child process whose peak memory is checked against ``MEMORY_CAP_MB``.

The cases run in-process through :func:`experiments.cli.run` (one process for all of them:
a subprocess each would take minutes); ``python -m pytest ... -s`` prints the table.
"""

from __future__ import annotations

import collections
import json
import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import pytest
import yaml

from experiments.cli import run

ROOT = Path(__file__).resolve().parents[3]
FIG1_TEXT = (ROOT / "feeders" / "families" / "fig1.yaml").read_text()
FIG1 = yaml.safe_load(FIG1_TEXT)
CASE_BOUND_S = 20.0  # a case that takes longer is a hang (generous: a loaded machine)
MEMORY_CAP_MB = 512  # peak RSS of a child running the biggest cases (measured: 191 MB)
THETA = "theta: {low: 0.3, high: 0.9, default: 0.5}"

ALIAS_BOMB = (
    "a: &a [x, x, x, x, x, x, x, x, x]\n"
    + "".join(
        f"{c}: &{c} [{', '.join(['*' + p] * 9)}]\n"
        for p, c in zip("abcdefgh", "bcdefghi", strict=True)
    )
    + "name: *i\n"
)


def _text_mutations(text: str) -> dict[str, str | bytes]:
    """Hostile variants of a valid document's ``text`` (each one refused by the reader or a
    field's check): the reader's limits and refusals, numbers, types."""
    head, _, rest = text.partition("\n")
    return {
        "alias bomb": ALIAS_BOMB,
        "alias at a field": text + "x: &x [1, 2]\ny: *x\n",
        "deep nesting list": "name: " + "[" * 5000 + "]" * 5000 + "\n",
        "deep nesting map": "name: " + "{a: " * 400 + "1" + "}" * 400 + "\n",
        "5000-digit integer": "name: s\nx: " + "7" * 5000 + "\n",
        "4300+ digit integer in place": text.replace("0.5", "9" * 4400, 1),
        "duplicate key": text + "name: again\n",
        "duplicate nested key": text.replace(THETA, THETA[:-1] + ", low: 0.2}", 1)
        if THETA in text
        else text + "name: again\n",
        "tag !!str": text.replace("name: ", "name: !!str ", 1),
        "tag !!python": "name: !!python/object:os.system x\n",
        "local tag": "name: !custom x\n" + rest,
        "merge key": text + "m: {<<: {a: 1}}\n",
        "octal": text + "x: 017\n",
        "sexagesimal": text + "x: 1:30\n",
        "nan value": text.replace("0.5", ".nan", 1),
        "inf value": text.replace("0.5", ".inf", 1),
        "-inf value": text.replace("0.5", "-.inf", 1),
        "1e999": text.replace("0.5", "1e999", 1),
        "huge float": text.replace("0.5", "1.0e300", 1),
        "list document": "- 1\n- 2\n",
        "scalar document": "just text\n",
        "empty": "",
        "null document": "~\n",
        "not YAML": "name: [unclosed\n",
        "tab indentation": "name: s\n\tx: 1\n",
        "control character": "name: s\x07\n",
        "key: value lines": "aws_secret_key: SECRETVALUE\nsession: SECRET2\n",
        "long key": text + "k" * 5000 + ": 1\n",
        "many values": "x: [" + ", ".join(["1"] * 120_000) + "]\n",
        "wrong type mapping": head + "\n" + "parameters: [1, 2]\n",
        "non-UTF-8": text.encode() + b"\nname2: caf\xe9\n",
        "binary": bytes(range(256)) * 8,
        "oversized": text + "#" * (1 << 20) + "\n",
        "BOM then garbage": "\ufeff: : :\n",
    }


def _family_variants() -> dict[str, str | bytes]:
    """The family file's own fields broken (beyond the reader)."""
    out: dict[str, str | bytes] = {}

    def put(label: str, change: Callable[[dict], None]) -> None:
        data = json.loads(json.dumps(FIG1))
        change(data)
        out[label] = yaml.safe_dump(data, sort_keys=False)

    for key in ("low", "high", "default"):
        for bad in ("x", [1], None, True, 1e300, -1e300):
            put(
                f"parameters.theta.{key} = {bad!r}",
                lambda d, k=key, b=bad: d["parameters"]["theta"].__setitem__(k, b),
            )
    for name in ("1x", "import", "pi", "a-b", "x" * 200, "é"):
        put(
            f"parameter name {name[:10]!r}",
            lambda d, n=name: d.__setitem__(
                "parameters", {n: {"low": 0, "high": 1, "default": 0.5}}
            ),
        )
    for field in ("pieces", "entries", "goal", "rules", "bounds", "orientations"):
        for bad in (3, "text", [], {}, [[1, 2]], None):
            if field in ("rules", "bounds", "orientations") and bad in (None, []):
                continue  # optional: absent or empty is a valid family
            put(f"{field} = {bad!r}", lambda d, f=field, b=bad: d.__setitem__(f, b))
    for expr in ("__import__('os')", "x.y", "1 if 2 else 3", "1e999", "(" * 300 + "1" + ")" * 300):
        put(
            f"expression {expr[:12]!r}",
            lambda d, e=expr: d["entries"].__setitem__("open_leading", [e, 0, 0]),
        )
    for key, bad in (("friction", -1), ("friction", "nan"), ("gravity", 1e9), ("restitution", 5)):
        put(f"{key} = {bad!r}", lambda d, k=key, b=bad: d.__setitem__(k, b))
    return out


def _part_variants() -> dict[str, str]:
    """A family whose ``part`` is broken."""
    parts: dict[str, object] = {
        "cupp": "cupp",
        "number": 3,
        "list": [1, 2],
        "length nan": {"length": float("nan")},
        "length inf": {"length": float("inf")},
        "length -1": {"length": -1.0},
        "length huge": {"length": 1e300},
        "length text": {"length": "long"},
        "width 0": {"width": 0.0},
        "mass 0": {"mass": 0.0},
        "heavy_fraction 2": {"heavy_fraction": 2.0},
        "unknown key": {"colour": "red"},
        "pieces empty": {"pieces": []},
        "pieces not a list": {"pieces": 3},
        "piece zero density": {"pieces": [{"polygon": [[0, 0], [1, 0], [1, 1]], "density": 0.0}]},
        "piece nan density": {
            "pieces": [{"polygon": [[0, 0], [1, 0], [1, 1]], "density": float("nan")}]
        },
        "piece self-crossing": {
            "pieces": [{"polygon": [[0, 0], [1, 1], [1, 0], [0, 1]], "density": 1.0}]
        },
        "piece 5000 vertices": {
            "pieces": [{"polygon": [[i, i % 2] for i in range(5000)], "density": 1.0}]
        },
        "outline crossing": {"outline": [[0, 0], [1, 1], [1, 0], [0, 1]], "density": 1.0},
        "outline two points": {"outline": [[0, 0], [1, 1]], "density": 1.0},
        "outline of text": {"outline": "square"},
        "disc radius nan": {"pieces": [{"circle": {"centre": [0, 0], "radius": float("nan")}}]},
        "disc radius -1": {"pieces": [{"circle": {"centre": [0, 0], "radius": -1}}]},
        "pieces and outline": {"pieces": [], "outline": []},
        "deep": {"pieces": [[[[[[[[[[[[1]]]]]]]]]]]]},
    }
    out = {}
    for label, part in parts.items():
        data = json.loads(json.dumps(FIG1))
        data["part"] = part
        out[f"part {label}"] = yaml.safe_dump(data, sort_keys=False)
    return out


def _config_variants() -> dict[str, str]:
    """A run config's own fields broken."""
    base = {"name": "s", "designs": {"count": 2, "seed": 1}, "ladder": [{"level": "passive"}]}
    changes: dict[str, object] = {
        "designs.count nan": {"designs": {"count": float("nan"), "seed": 1}},
        "designs.count 1e300": {"designs": {"count": 1e300, "seed": 1}},
        "designs.count text": {"designs": {"count": "many", "seed": 1}},
        "designs.seed -1": {"designs": {"count": 2, "seed": -1}},
        "ladder empty": {"ladder": []},
        "ladder text": {"ladder": "passive"},
        "ladder unknown level": {"ladder": [{"level": "quantum"}]},
        "workers 0": {"workers": 0},
        "workers 1e9": {"workers": 10**9},
        "name with slash": {"name": "a/b"},
        "name too long": {"name": "n" * 500},
        "name control": {"name": "a\nb"},
        "family number": {"family": 3},
        "family nowhere": {"family": "no-such-family"},
        "family list": {"family": ["fig1"]},
        "family nan": {"family": float("nan")},
        "holdout fraction 2": {"holdout": {"fraction": 2.0, "seed": 1}},
        "holdout fraction nan": {"holdout": {"fraction": float("nan"), "seed": 1}},
        "unknown key": {"colour": "red"},
    }
    return {
        f"config {label}": yaml.safe_dump({**base, **change}, sort_keys=False)
        for label, change in changes.items()
    }


def _write(path: Path, content: str | bytes) -> Path:
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8", errors="surrogatepass")
    return path


def _stored_database(directory: Path, text: str) -> Path:
    """A family sweep's directory whose database stores ``text`` as the family's."""
    from experiments.family_config import family_record
    from experiments.sweep import results_db
    from feeders.device_family import load_family

    family = load_family(ROOT / "feeders" / "families" / "fig1.yaml")
    directory.mkdir()
    db = results_db.connect(directory / "results.sqlite", parameters=family.vector_names)
    try:
        config = {"designs": {"count": 1, "seed": 1}, "ladder": []}
        results_db.claim(db, config, "k", family_record(family, text))
    finally:
        db.close()
    return directory


def _cases(tmp: Path) -> list[tuple[str, str, list[str]]]:
    """(kind, label, argv) of every case, its files written under ``tmp``."""
    cases: list[tuple[str, str, list[str]]] = []
    out = str(tmp / "out")
    config_text = (
        "name: s\ndesigns: {count: 2, seed: 1}\nladder: [{level: passive}]\n"
        "holdout: {fraction: 0.5, seed: 1}\n"
    )
    n = 0

    def path(suffix: str = ".yaml") -> Path:
        nonlocal n
        n += 1
        return tmp / f"case{n:04d}{suffix}"

    specials: dict[str, Callable[[Path], None]] = {
        "FIFO": lambda p: os.mkfifo(p),
        "directory": lambda p: p.mkdir(),
        "missing": lambda p: None,
        "dangling link": lambda p: p.symlink_to(tmp / "nowhere"),
    }
    # run configs: the reader's refusals and the config's fields
    for label, content in {**_text_mutations(config_text), **_config_variants()}.items():
        cases.append(("run config", label, ["run", str(_write(path(), content)), "--out", out]))
    for label, make in specials.items():
        p = path()
        make(p)
        cases.append(("run config", label, ["run", str(p), "--out", out]))
    # family files through --family (simulate, draw, plan, margins) and through family:
    family_inputs = {**_text_mutations(FIG1_TEXT), **_family_variants()}
    commands = [["simulate"], ["draw", "--out", str(tmp / "pic.png")], ["plan"], ["margins"]]
    for k, (label, content) in enumerate(family_inputs.items()):
        p = _write(path(), content)
        cases.append(("family --family", label, [*commands[k % 4], "--family", str(p)]))
        config = _write(path(), f"name: s{k}\nfamily: {p.name}\n" + config_text.split("\n", 1)[1])
        cases.append(("family: in a config", label, ["run", str(config), "--out", out]))
    for label, make in specials.items():
        p = path()
        make(p)
        cases.append(("family --family", label, ["simulate", "--family", str(p)]))
        config = _write(path(), f"name: s\nfamily: {p}\n" + config_text.split("\n", 1)[1])
        cases.append(("family: in a config", label, ["run", str(config), "--out", out]))
    # parts inside a family
    for k, (label, content) in enumerate(_part_variants().items()):
        p = _write(path(), content)
        cases.append(("part", label, [*commands[k % 4], "--family", str(p)]))
    # family texts a sweep's database stores, read back by report
    for k, (label, content) in enumerate(_text_mutations(FIG1_TEXT).items()):
        if isinstance(content, bytes):
            content = content.decode("utf-8", "surrogateescape")
        try:
            directory = _stored_database(tmp / f"stored{k:03d}", content)
        except UnicodeEncodeError:  # SQLite cannot store it: not a stored text
            continue
        cases.append(("stored text", label, ["report", str(directory)]))
    return cases


def _run_case(argv: list[str], capsys: pytest.CaptureFixture) -> tuple[int | str, str, float]:
    start = time.perf_counter()
    try:
        code: int | str = run(argv)
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 2
    except BaseException as exc:  # the case's outcome, classified below
        code = f"raised {type(exc).__name__}"
    took = time.perf_counter() - start
    err = capsys.readouterr().err
    return code, err, took


@pytest.mark.slow  # ~15 s
def test_the_malformed_family_corpus_is_refused_in_one_line_each(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    cases = _cases(tmp_path)
    assert len(cases) >= 300, len(cases)
    table: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
    bad = []
    slowest = 0.0
    for kind, label, argv in cases:
        code, err, took = _run_case(argv, capsys)
        slowest = max(slowest, took)
        row = table[kind]
        row["cases"] += 1
        row[f"exit {code}"] += 1
        row["tracebacks"] += "Traceback" in err
        row["hangs"] += took > CASE_BOUND_S
        clean = code == 2 and err.count("\n") == 1 and "Traceback" not in err
        clean = clean and took <= CASE_BOUND_S and "SECRET" not in err
        if not clean:
            bad.append(f"{kind} / {label}: exit {code}, {took:.1f} s, {err[:300]!r}")
    with capsys.disabled():
        print(f"\n{'kind':22} cases  exit 2  tracebacks  hangs (slowest case {slowest:.1f} s)")
        for kind, row in table.items():
            print(
                f"{kind:22} {row['cases']:5}  {row['exit 2']:6}  {row['tracebacks']:10}  "
                f"{row['hangs']:5}"
            )
    assert not bad, "\n".join(bad)


_CHILD = """
import sys, time
from pathlib import Path
from experiments.cli import run
tmp = Path(sys.argv[1])
codes = []
for name in sorted(p.name for p in tmp.iterdir() if p.suffix == ".yaml"):
    try:
        codes.append(run(["simulate", "--family", str(tmp / name)]))
    except SystemExit as exc:
        codes.append(exc.code)
# VmHWM, this program's own peak: ru_maxrss keeps the peak of the process it was forked from
# across exec (a 750 MB pytest made a 13 MB child read 713 MB)
peak = next(line for line in open("/proc/self/status") if line.startswith("VmHWM:"))
print(codes, int(peak.split()[1]) // 1024)
"""


def test_the_biggest_cases_stay_under_the_memory_cap(tmp_path: Path) -> None:
    """In a child of its own (peak RSS is per process): the alias bomb, 5,000-deep nesting, a
    120,000-value list, a 1 MiB+ file, a 5,000-vertex part and 4,400-digit numbers."""
    mutations = _text_mutations(FIG1_TEXT)
    big = ["alias bomb", "deep nesting list", "many values", "oversized", "5000-digit integer"]
    big += ["4300+ digit integer in place"]
    for k, label in enumerate(big):
        _write(tmp_path / f"big{k}.yaml", mutations[label])
    _write(tmp_path / "part.yaml", _part_variants()["part piece 5000 vertices"])
    done = subprocess.run(
        [sys.executable, "-c", _CHILD, str(tmp_path)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )
    assert "Traceback" not in done.stderr, done.stderr[-2000:]
    codes_text, peak = done.stdout.strip().rsplit(" ", 1)
    assert codes_text == str([2] * (len(big) + 1))
    assert int(peak) < MEMORY_CAP_MB, f"peak {peak} MB"
    print(f"peak RSS of the biggest cases: {peak} MB (cap {MEMORY_CAP_MB} MB)")
