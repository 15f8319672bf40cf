"""Issue 37's last "done when": a run stopped by a full disk resumes after space is freed,
with rows identical to an uninterrupted run. A real full disk: a small tmpfs, filled by a
filler file until only a part of what the run's database needs is left (its first pages fit,
the whole run does not), the filler deleted, the same command run again. Needs ``mount``
(root, as CI runs); skipped where mounting is refused."""

from __future__ import annotations

import json
import os
import shutil
import sqlite3
import subprocess
from pathlib import Path

import pytest
import yaml
from cli_process import ROOT, noise, run_cli

TMPFS_SIZE = "2m"
# What is left free for the stopped run: the database's first pages, the ``-shm`` and a WAL
# holding about half of the run's evaluations (measured: the whole run's WAL is about 270 KiB
# besides a 32 KiB ``-shm``; 160 to 280 KiB left all stop a run after storing some rows).
LEFT_FREE = 200 << 10

EVALUATIONS = (
    "SELECT design_id, level, rung, status, reason, heavy_leading, heavy_trailing, attempts "
    "FROM evaluations ORDER BY design_id, rung"
)
VERDICTS = (
    "SELECT design_id, decision, target, trials, heavy_leading, heavy_trailing, both_entries, "
    "exit_heavy_leading_s, exit_heavy_trailing_s, seed, verdict FROM verdicts ORDER BY design_id"
)


def _config(tmp_path: Path) -> Path:
    """The shipped default config cut to 8 designs, the screen and the passive verdict, one
    worker: a few seconds."""
    config = yaml.safe_load((ROOT / "experiments/configs/default.yaml").read_text())
    config.update(name="fulldisk", designs={"count": 8, "seed": 0}, workers=1)
    config["ladder"] = [rung for rung in config["ladder"] if rung["level"] in ("screen", "passive")]
    assert [rung["level"] for rung in config["ladder"]] == ["screen", "passive"]
    path = tmp_path / "fulldisk.yaml"
    path.write_text(yaml.safe_dump(config))
    return path


def _rows(directory: Path, scratch: Path) -> dict[str, list[tuple]]:
    """The stored rows of the sweep in ``directory`` without times or workers (a verdict's
    JSON without its ``wall_time_s``), read from a copy of its files in ``scratch`` so that the
    directory is left as it is (a reader may write a ``-shm``, a closing connection
    checkpoints)."""
    scratch.mkdir()
    for name in ("results.sqlite", "results.sqlite-wal", "results.sqlite-shm"):
        if (directory / name).exists():
            shutil.copyfile(directory / name, scratch / name)
    db = sqlite3.connect(scratch / "results.sqlite")
    try:
        verdicts = []
        for row in db.execute(VERDICTS):
            verdict = json.loads(row[-1])
            verdict.pop("wall_time_s")
            verdicts.append((*row[:-1], verdict))
        return {
            "designs": db.execute("SELECT * FROM designs ORDER BY design_id").fetchall(),
            "evaluations": db.execute(EVALUATIONS).fetchall(),
            "verdicts": verdicts,
        }
    finally:
        db.close()


def _sweep(config: Path, out: Path) -> subprocess.CompletedProcess:
    return run_cli("run", str(config), "--out", str(out), "--no-report", "--quiet", timeout=300)


@pytest.mark.slow
def test_a_run_stopped_by_a_full_disk_resumes_to_the_uninterrupted_rows(tmp_path: Path) -> None:
    config = _config(tmp_path)
    whole = _sweep(config, tmp_path / "uninterrupted")
    assert whole.returncode == 0, whole.stderr
    expected = _rows(tmp_path / "uninterrupted", tmp_path / "read-whole")
    assert len(expected["evaluations"]) == 16 and len(expected["verdicts"]) == 8

    disk = tmp_path / "disk"
    disk.mkdir()
    try:
        mounted = subprocess.run(
            ["mount", "-t", "tmpfs", "-o", f"size={TMPFS_SIZE}", "tmpfs", str(disk)],
            capture_output=True,
            text=True,
        )
    except OSError as exc:  # no mount command
        pytest.skip(f"cannot mount a tmpfs here: {exc}")
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip() or mounted.returncode}")
    try:
        filler = disk / "filler"
        free = os.statvfs(disk)
        with filler.open("wb") as handle:
            handle.write(b"\0" * (free.f_bavail * free.f_frsize - LEFT_FREE))
        out = disk / "sweep"

        stopped = _sweep(config, out)
        err = noise(stopped.stderr)
        assert stopped.returncode not in (0, None), stopped.stdout
        assert "Traceback" not in err and err.count("\n") == 1, err
        assert "database or disk is full" in err, err
        assert not (out / "partfeeder.lock").exists()
        partial = _rows(out, tmp_path / "read-stopped")
        stored = len(partial["evaluations"])
        assert 0 < stored < len(expected["evaluations"]), partial  # stopped mid-run
        assert set(partial["evaluations"]) <= set(expected["evaluations"])

        filler.unlink()  # the space freed
        resumed = _sweep(config, out)
        err = noise(resumed.stderr)
        assert resumed.returncode == 0, err
        assert err == "", err  # nothing to move aside or delete
        assert _rows(out, tmp_path / "read-resumed") == expected
    finally:
        unmounted = subprocess.run(["umount", str(disk)], capture_output=True, text=True)
        if unmounted.returncode != 0:
            subprocess.run(["umount", "-l", str(disk)], capture_output=True)
