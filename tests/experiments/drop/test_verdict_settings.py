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


def test_the_rule_is_wilson_or_sprt_and_the_sprts_hypotheses_are_ordered():
    import pytest

    with pytest.raises(ValueError, match=r"verdict\.rule = 'bayes' is not one of wilson, sprt"):
        VerdictSettings(rule="bayes")
    with pytest.raises(ValueError, match=r"verdict\.fails_p = 0\.95 must be below works_p"):
        VerdictSettings(rule="sprt", works_p=0.9, fails_p=0.95)
    with pytest.raises(ValueError, match=r"verdict\.error = 0\.5 is outside .*\[1e-06, 0\.25\]"):
        VerdictSettings(rule="sprt", error=0.5)


def test_a_wilson_configs_results_key_is_as_before_and_the_sprt_changes_it():
    """The SPRT's fields are held only when it is the rule, so a sweep of the Wilson rule
    resumes into the database it wrote before the SPRT existed."""
    from experiments.config_files import resolve_config
    from experiments.sweep.config import config_from_dict, load_config

    default = load_config(resolve_config("default")).to_dict()
    # the default as it was before the screen, the audit and the SPRT: the Wilson rule
    default["ladder"] = [r for r in default["ladder"] if r["level"] != "screen"]
    default.pop("audit")
    passive = next(r for r in default["ladder"] if r["level"] == "passive")
    passive["verdict"] = {"target": 0.9, "min_drops": 10, "batch": 10, "max_drops": 200}
    wilson = config_from_dict(default)
    rung = next(r for r in wilson.ladder if r.level == "passive")
    assert set(rung.verdict) == {"target", "min_drops", "batch", "max_drops", "step", "t_max"}
    assert wilson.results_key() == "ed7814f1f940c9e3"  # the default sweep's key before
    data = wilson.to_dict()
    passive = next(r for r in data["ladder"] if r["level"] == "passive")
    passive["verdict"].update(rule="sprt", min_drops=1, batch=1)
    sprt = config_from_dict(data)
    rung = next(r for r in sprt.ladder if r.level == "passive")
    assert rung.verdict["rule"] == "sprt" and rung.verdict["error"] == 0.01
    assert sprt.results_key() != wilson.results_key()
