"""One ``partfeeder run`` per sweep directory (issue 16: two runs on one directory both ran,
and one died of a ``disk I/O error``). The lock is an ``flock``: held while a run lives,
released by the system however it ends, so a run killed with SIGKILL leaves nothing stale."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from experiments.sweep.lock import LOCK_FILE, DirectoryInUse, sweep_lock

HOLD = """
import sys, time
from experiments.sweep.lock import sweep_lock
with sweep_lock(sys.argv[1]):
    print("held", flush=True)
    time.sleep(600)
"""


def _holder(directory: Path) -> subprocess.Popen:
    process = subprocess.Popen(
        [sys.executable, "-c", HOLD, str(directory)], stdout=subprocess.PIPE, text=True
    )
    assert process.stdout is not None and process.stdout.readline().strip() == "held"
    return process


def test_a_directory_held_by_another_process_is_refused_naming_the_holder(tmp_path: Path):
    holder = _holder(tmp_path)
    try:
        with pytest.raises(DirectoryInUse) as info, sweep_lock(tmp_path):
            pass
        message = str(info.value)
        assert f"pid {holder.pid}" in message and socket.gethostname() in message
        assert "since 20" in message and "\n" not in message
    finally:
        holder.kill()
        holder.wait()


def test_the_lock_of_a_process_killed_with_sigkill_is_taken_over(tmp_path: Path) -> None:
    holder = _holder(tmp_path)
    os.kill(holder.pid, signal.SIGKILL)
    holder.wait()
    stale = json.loads((tmp_path / LOCK_FILE).read_text())
    assert stale["pid"] == holder.pid  # the dead holder's line is still there ...
    with sweep_lock(tmp_path) as path:  # ... but the lock went with its process
        assert json.loads(path.read_text())["pid"] == os.getpid()


def test_the_lock_is_held_inside_and_free_after(tmp_path: Path) -> None:
    with sweep_lock(tmp_path), pytest.raises(DirectoryInUse), sweep_lock(tmp_path):
        pass  # a second open file description conflicts, even in the same process
    with sweep_lock(tmp_path):
        pass


@pytest.mark.parametrize("kind", ["symlink", "dangling symlink", "fifo"])
def test_a_lock_path_that_is_not_a_regular_file_is_refused_and_left_alone(
    tmp_path: Path, kind: str
) -> None:
    """Issue 23: a symbolic link at DIR/partfeeder.lock was followed, and its target truncated
    and overwritten with the holder's line. The lock is opened without following links, and
    anything but a regular file there is refused in one line; the target is untouched."""
    target = tmp_path / "precious.txt"
    target.write_text("keep me\n")
    lock = tmp_path / LOCK_FILE
    if kind == "symlink":
        lock.symlink_to(target)
    elif kind == "dangling symlink":
        lock.symlink_to(tmp_path / "nowhere")
    else:
        os.mkfifo(lock)
    with pytest.raises(DirectoryInUse) as info, sweep_lock(tmp_path):
        pass
    message = str(info.value)
    assert "not a regular file" in message and "\n" not in message
    assert target.read_text() == "keep me\n"
    assert not (tmp_path / "nowhere").exists()


def test_a_directory_of_another_job_is_refused_naming_the_job(tmp_path: Path) -> None:
    """Issue 23: ``optimize --out SWEEP_DIR`` and ``run --out OPTIMIZE_DIR`` both ran and
    overwrote the other job's summary.json and report.html. A job's directory holds its
    database; another job's directory is refused by name, the same job's is taken again."""
    with sweep_lock(tmp_path, job="optimize"):
        (tmp_path / "evaluations.sqlite").write_bytes(b"")  # what optimize leaves
    with pytest.raises(DirectoryInUse) as info, sweep_lock(tmp_path, job="run"):
        pass
    message = str(info.value)
    assert "partfeeder optimize" in message and "--out" in message and "\n" not in message
    with sweep_lock(tmp_path, job="optimize") as path:
        assert json.loads(path.read_text())["job"] == "optimize"


def test_a_lock_file_an_older_version_left_naming_another_job_is_refused(tmp_path: Path):
    (tmp_path / LOCK_FILE).write_text(json.dumps({"pid": 1, "job": "optimize"}))
    with pytest.raises(DirectoryInUse, match="partfeeder optimize"), sweep_lock(tmp_path):
        pass


@pytest.mark.parametrize("ending", ["clean", "exception"])
def test_no_lock_file_remains_after_the_job(tmp_path: Path, ending: str) -> None:
    """Issue 37 (and 39): partfeeder.lock stayed in the directory after a clean exit."""
    try:
        with sweep_lock(tmp_path) as path:
            assert path.exists()
            if ending == "exception":
                raise KeyboardInterrupt
    except KeyboardInterrupt:
        pass
    assert not (tmp_path / LOCK_FILE).exists()


def test_a_lock_taken_on_a_file_its_holder_removed_is_taken_again_on_a_new_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The file is removed while still locked; a process that opened it just before locks
    the removed file: it must not count that as holding the directory, or it and the next
    process (which makes a new file) would both hold it. Simulated: the first lock call finds
    its file removed (and another made) by the time it has locked it."""
    import fcntl

    from experiments.sweep import lock as lock_module

    real = fcntl.flock
    calls = []

    def flock_after_the_holder_ended(fd: int, operation: int) -> None:
        calls.append(fd)
        real(fd, operation)
        if len(calls) == 1:
            os.unlink(tmp_path / LOCK_FILE)  # the holder ended: its file removed
            (tmp_path / LOCK_FILE).write_text("")  # and a new one made by another process

    monkeypatch.setattr(lock_module.fcntl, "flock", flock_after_the_holder_ended)
    with sweep_lock(tmp_path) as path:
        assert len(calls) == 2  # locked a second time, on the file the path names
        assert json.loads(path.read_text())["pid"] == os.getpid()


def test_a_held_lock_names_the_holders_job(tmp_path: Path) -> None:
    """The lock message said 'another partfeeder run' even for optimize."""
    with sweep_lock(tmp_path, job="optimize"), pytest.raises(DirectoryInUse) as info:
        with sweep_lock(tmp_path, job="optimize"):
            pass
    assert "another partfeeder optimize" in str(info.value)


def test_a_lock_file_from_before_jobs_were_recorded_is_taken(tmp_path: Path) -> None:
    (tmp_path / LOCK_FILE).write_text(json.dumps({"pid": 1, "host": "h", "started": "t"}))
    with sweep_lock(tmp_path, job="run") as path:
        assert json.loads(path.read_text())["job"] == "run"
