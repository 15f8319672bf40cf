"""``--baseline`` names a design as ``--design`` does, and refuses a bad one in one line."""

from __future__ import annotations

import pytest

from experiments.cli.baseline import baseline_of
from experiments.cli.usage import UsageError
from feeders.design import preset


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
