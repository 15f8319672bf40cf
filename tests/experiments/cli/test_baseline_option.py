"""``--baseline`` names a design as ``--design`` does, and refuses a bad one in one line; a
device family's is its ``default`` or its values (issue 24), as the optimiser and the sweep's
report read it."""

from __future__ import annotations

import re

import pytest

from experiments.cli.baseline import (
    baseline_for,
    baseline_of,
    check_baseline_form,
    family_baseline_of,
)
from experiments.cli.usage import UsageError
from feeders.design import preset
from feeders.device_family import load_family, packaged_family


def test_a_preset_keeps_its_name_and_values() -> None:
    label, values = baseline_of("fig7a")
    assert label == "fig7a" and values == list(preset("fig7a").to_vector())


def test_twelve_values_are_the_baseline() -> None:
    text = ",".join(str(v) for v in preset("table3").to_vector())
    label, values = baseline_of(text)
    assert label == "baseline" and values == pytest.approx(list(preset("table3").to_vector()))


@pytest.mark.parametrize("text", ["nosuch", "1,2,3", "table3,x"])
def test_a_bad_baseline_is_one_line_naming_the_option(text: str) -> None:
    with pytest.raises(UsageError) as err:
        baseline_of(text)
    assert str(err.value).startswith("--baseline:") and "\n" not in str(err.value)


FIG1 = load_family(packaged_family("fig1"))


@pytest.mark.parametrize("text", [None, "default"])
def test_a_familys_baseline_is_its_default_unless_given(text: str | None) -> None:
    assert family_baseline_of(text, FIG1) == ("default", FIG1.default().tolist())


def test_a_familys_values_are_its_baseline() -> None:
    label, values = family_baseline_of("0.5,1.2,1.2,-0.6,1.6,0.2", FIG1)
    assert label == "baseline" and values == [0.5, 1.2, 1.2, -0.6, 1.6, 0.2]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("table3", "allowed with family fig1: default, or 6 comma-separated numbers (theta, "),
        ("1,2,3", "allowed with family fig1: default, or 6 comma-separated numbers (theta, "),
        ("0.5,1.2,1.2,0.0,0.5,0.25", "cannot be built: pin B hangs"),
    ],
)
def test_a_bad_family_baseline_is_one_line(text: str, message: str) -> None:
    with pytest.raises(UsageError, match=re.escape(message)) as err:
        family_baseline_of(text, FIG1)
    assert str(err.value).startswith(f"--baseline = '{text}'") and "\n" not in str(err.value)


def test_what_is_designed_decides_how_a_baseline_is_read() -> None:
    assert baseline_for(None, None)[0] == "table3"
    assert baseline_for(None, FIG1)[0] == "default"
    with pytest.raises(UsageError):
        baseline_for("default", None)


@pytest.mark.parametrize("text", [None, "default", "table3", "1,2,3", "0.5,1.2,1.2,-0.6,1.6,0.2"])
def test_a_baseline_some_design_could_be_passes_the_first_check(text: str | None) -> None:
    check_baseline_form(text)


@pytest.mark.parametrize("text", ["nosuch", "table3,x", "1,nan,3"])
def test_a_baseline_no_design_could_be_is_refused_at_once(text: str) -> None:
    with pytest.raises(UsageError, match=r"^--baseline"):
        check_baseline_form(text)


def test_a_family_baseline_that_is_not_finite_is_called_so_not_a_wrong_count() -> None:
    """Issue 37, item 8: a NaN --baseline on a family sweep was reported as a wrong count."""
    from experiments.cli.baseline import family_baseline_of
    from experiments.cli.usage import UsageError
    from feeders.device_family import load_family, packaged_family

    family = load_family(packaged_family("fig1"))
    for bad in ("nan", "inf", "1e999"):
        with pytest.raises(UsageError) as caught:
            family_baseline_of(f"0.5,1.2,1.2,{bad},1.4,0.25", family)
        message = str(caught.value)
        assert "pin_x" in message and "not a finite number" in message, message
        assert "comma-separated numbers (" not in message


def test_a_baseline_that_is_not_finite_is_refused_at_once_as_such() -> None:
    from experiments.cli.baseline import check_baseline_form
    from experiments.cli.usage import UsageError

    with pytest.raises(UsageError, match=r"^--baseline: value 4 = nan is not a finite number"):
        check_baseline_form("0.5,1.2,1.2,nan,1.4,0.25")
