"""A verdict's settings are read with a sweep's config, before the dynamic level is imported
(issue 22: a bad config value waited for numba); their default step is the level's own."""

from __future__ import annotations

import subprocess
import sys

from experiments.drop.verdict_settings import DYNAMIC_STEP, VerdictSettings


def test_the_default_step_is_the_dynamic_levels_own():
    from validity.dynamic import DEFAULT_STEP

    assert DYNAMIC_STEP == DEFAULT_STEP
    assert VerdictSettings().step == DEFAULT_STEP


def test_reading_the_settings_imports_no_level():
    code = (
        "import sys; import experiments.drop.verdict_settings, experiments.sweep.config; "
        "print(sorted(m for m in ('numba', 'ompl', 'validity', 'matplotlib') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
