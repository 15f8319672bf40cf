"""A report's cells: a number as text, a dash for what is unknown, never "nan"."""

from __future__ import annotations

import math

import numpy as np

from experiments.report_kit.cells import DASH, cell, interval, number


def test_unknown_values_are_a_dash():
    for value in (None, math.nan, math.inf, -math.inf):
        assert cell(value) == DASH
    assert number("not a number") is None


def test_integers_stay_integers_and_floats_follow_the_spec():
    assert cell(np.int64(12)) == "12"
    assert cell(0.123456, ".3f") == "0.123"
    assert cell(np.bool_(True)) == "True"


def test_an_interval_needs_both_ends():
    assert interval([0.912, 1.0]) == "[0.91, 1.00]"
    assert interval([0.9, None]) == DASH
    assert interval(None) == DASH
    assert interval([1234.5, 5678.9], ".3g") == "[1.23e+03, 5.68e+03]"


def test_a_quantity_has_its_unit_or_is_n_a_alone():
    from experiments.report_kit.cells import UNKNOWN, quantity

    assert quantity(1.25, "s", ".2f") == "1.25 s"
    assert quantity(3, "s") == "3 s"
    for value in (None, math.nan, math.inf):
        assert quantity(value, "s") == UNKNOWN == "n/a"  # never "– s"
