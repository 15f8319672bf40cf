"""What users install is a wheel: every data file the commands read must be in it (issue 22:
`partfeeder bench` exited 2 as installed, because the analytic scenes were left out; the tests
import the source tree, so nothing caught it). Reference: the files the source tree holds."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = ["experiments/configs/*.yaml", "experiments/scenes/*.yaml", "*/py.typed"]
PACKAGES = ["feeders", "validity", "planners", "experiments"]
BUILT = {"__pycache__"}  # made by running the code, not part of the source
BUILT_SUFFIXES = {".pyc", ".nbi", ".nbc"}  # bytecode and numba's on-disk cache


@pytest.fixture(scope="module")
def wheel_names(tmp_path_factory) -> set[str]:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "-q",
            "-w",
            str(out),
            str(ROOT),
        ],
        check=True,
        capture_output=True,
    )
    (wheel,) = out.glob("partfeeder-*.whl")
    with zipfile.ZipFile(wheel) as z:
        return set(z.namelist())


@pytest.mark.parametrize("pattern", DATA)
def test_every_data_file_of_the_source_tree_is_in_the_wheel(wheel_names, pattern):
    files = sorted(p.relative_to(ROOT).as_posix() for p in ROOT.glob(pattern))
    assert files, pattern
    missing = [f for f in files if f not in wheel_names]
    assert missing == []


def test_every_file_of_the_packages_is_in_the_wheel(wheel_names):
    """Whatever a package directory holds (modules and any data a command may read, e.g. a
    new kind of file beside the scenes) is installed: a file left out of package-data is a
    command broken as installed that the tests, reading the source tree, cannot see."""
    files = sorted(
        p.relative_to(ROOT).as_posix()
        for package in PACKAGES
        for p in (ROOT / package).rglob("*")
        if p.is_file() and not BUILT & set(p.parts) and p.suffix not in BUILT_SUFFIXES
    )
    assert len(files) > 100
    missing = [f for f in files if f not in wheel_names]
    assert missing == []
