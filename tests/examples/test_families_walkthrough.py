"""docs/families.md's "From an outline to a sweep" runs as written (issue 39): its files are
written from the page's heredocs, its ``partfeeder`` lines run in order in a fresh directory,
and the output it quotes is what ``partfeeder part`` prints. The part file on the page is
``examples/l-part.yaml``, byte for byte, so the two cannot drift apart.

The commands that simulate (``simulate``, ``run``: about 30 s) run in the slow test; the fast
one runs the rest and reads the sweep's config with the sweep's own loader.
"""

from __future__ import annotations

import re
import shlex
import textwrap
from pathlib import Path

import pytest

from experiments.cli import run

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "families.md"
SECTION = "## From an outline to a sweep"
HEREDOC = re.compile(r"^cat > (\S+) <<'EOF'\n(.*?)^EOF\n", re.MULTILINE | re.DOTALL)
SIMULATING = {"simulate", "run"}


def _section() -> str:
    text = PAGE.read_text()
    start = text.index(SECTION)
    end = text.index("\n## ", start + len(SECTION))
    return text[start:end]


def _script() -> tuple[dict[str, str], list[list[str]]]:
    """The bash block's files (name: text) and its ``partfeeder`` command lines, in order."""
    block = re.search(r"^```bash\n(.*?)^```", _section(), re.MULTILINE | re.DOTALL).group(1)
    files = {name: body for name, body in HEREDOC.findall(block)}
    rest = HEREDOC.sub("", block)
    commands = [shlex.split(line, comments=True) for line in rest.splitlines()]
    return files, [c[1:] for c in commands if c and c[0] == "partfeeder"]


def _run_in(tmp_path: Path, monkeypatch, skip: set[str]) -> list[list[str]]:
    files, commands = _script()
    monkeypatch.chdir(tmp_path)
    for name, body in files.items():
        Path(name).write_text(body)
    ran = []
    for argv in commands:
        if argv[0] in skip:
            continue
        assert run(argv) == 0, argv
        ran.append(argv)
    return ran


def test_the_pages_part_file_is_the_shipped_example():
    files, _ = _script()
    assert files["l-part.yaml"] == (ROOT / "examples" / "l-part.yaml").read_text()


def test_the_walkthrough_runs_to_the_sweeps_config(tmp_path, monkeypatch, capsys):
    ran = _run_in(tmp_path, monkeypatch, skip=SIMULATING)
    assert [a[0] for a in ran] == ["part", "family", "draw", "part"]
    assert (tmp_path / "l-part.png").stat().st_size > 0
    assert (tmp_path / "l-fig1.png").stat().st_size > 0
    from experiments.sweep.config import load_config

    config = load_config(tmp_path / "l-sweep.yaml")
    assert config.count == 64
    assert config.device_family().name == "l-fig1"  # the family new wrote, found beside it


def test_the_output_the_page_quotes_is_what_part_prints(tmp_path, monkeypatch, capsys):
    quoted = re.search(r"```text\n(.*?)```", _section(), re.DOTALL).group(1)
    monkeypatch.chdir(tmp_path)
    Path("l-part.yaml").write_text((ROOT / "examples" / "l-part.yaml").read_text())
    assert run(["part", "l-part.yaml"]) == 0
    assert capsys.readouterr().out == textwrap.dedent(quoted)


@pytest.mark.slow
def test_the_whole_walkthrough_runs_with_its_sweep(tmp_path, monkeypatch, capsys):
    """The L in the cup's device: the page says no design of the 64 works."""
    ran = _run_in(tmp_path, monkeypatch, skip=set())
    assert [a[0] for a in ran] == ["part", "family", "draw", "part", "simulate", "run"]
    out = capsys.readouterr().out
    assert "recommended: none" in out
    assert (tmp_path / "sweep" / "l-sweep" / "report.html").exists()
