"""Specification of feeders.expressions, the safe expression language of device families.

Reference: Python's own arithmetic on the same literals (each case is written twice, once as
text for the language and once as Python code), and math's functions.
"""

from __future__ import annotations

import math

import pytest

from feeders.expressions import ExpressionError, compile_expression, names_used

KNOWN = ("a", "b", "theta")
VALUES = {"a": 1.5, "b": -0.25, "theta": 0.4}

# (text, Python's value of the same text with a = 1.5, b = -0.25, theta = 0.4)
_a, _b, _theta = 1.5, -0.25, 0.4
ARITHMETIC = [
    ("2 + 3 * 4", 2 + 3 * 4),
    ("(2 + 3) * 4", (2 + 3) * 4),
    ("2 - 3 - 4", 2 - 3 - 4),
    ("2 / 4 / 8", 2 / 4 / 8),
    ("2 ** 3 ** 2", 2.0**3.0**2.0),
    ("-2 ** 2", -(2.0**2.0)),
    ("(-2) ** 2", (-2.0) ** 2.0),
    ("2 ** -1", 2.0**-1.0),
    ("7 % 3 * 2", 7 % 3 * 2),
    ("-7 % 3", -7 % 3),
    ("7.5 % -2", 7.5 % -2),
    ("+a - -b", +_a - -_b),
    ("a * b + a / b - b ** 2", _a * _b + _a / _b - _b**2),
    ("1e-3 * 2.5e2", 1e-3 * 2.5e2),
    ("a / 2 * b", _a / 2 * _b),
    ("sin(theta) ** 2 + cos(theta) ** 2", math.sin(_theta) ** 2 + math.cos(_theta) ** 2),
    ("atan2(b, a) + tan(theta)", math.atan2(_b, _a) + math.tan(_theta)),
    ("hypot(a, b) - sqrt(a)", math.hypot(_a, _b) - math.sqrt(_a)),
    ("min(a, b, 0.1) + max(a, b) + abs(b)", min(_a, _b, 0.1) + max(_a, _b) + abs(_b)),
    (
        "pi / 2 - acos(0.3) + asin(0.2) + atan(a)",
        math.pi / 2 - math.acos(0.3) + math.asin(0.2) + math.atan(_a),
    ),
    ("degrees(radians(30))", math.degrees(math.radians(30))),
]


@pytest.mark.parametrize(("text", "expected"), ARITHMETIC)
def test_arithmetic_and_precedence_are_pythons(text: str, expected: float) -> None:
    assert compile_expression(text, "f", KNOWN).evaluate(VALUES) == expected


CONDITIONS = [
    ("a > b", _a > _b),
    ("b < a < 1", _b < _a < 1),
    ("a >= 1.5 and b <= -0.25", _a >= 1.5 and _b <= -0.25),
    ("a == 1.5 or b != b", _a == 1.5 or _b != _b),
    ("not a < b", not _a < _b),
    ("not (a > 0 and b > 0) or theta > 1", not (_a > 0 and _b > 0) or _theta > 1),
    ("a > 0 or b > 0 and theta > 1", _a > 0 or (_b > 0 and _theta > 1)),
]


@pytest.mark.parametrize(("text", "expected"), CONDITIONS)
def test_conditions_are_pythons(text: str, expected: bool) -> None:
    assert compile_expression(text, "f", KNOWN, condition=True).holds(VALUES) is expected


def test_plain_numbers_are_expressions() -> None:
    for number in (0, 3, -2.5, 1e-9):
        expression = compile_expression(number, "f", KNOWN)
        assert expression.evaluate({}) == float(number)
        assert names_used(expression) == frozenset()
    assert compile_expression("1e3", "f", KNOWN).evaluate({}) == 1000.0  # YAML reads it as text


def test_names_used_are_the_parameters_read() -> None:
    assert names_used(compile_expression("a * sin(theta) + pi", "f", KNOWN)) == {"a", "theta"}
    assert names_used(compile_expression("a < b or a > 2", "f", KNOWN, condition=True)) == {
        "a",
        "b",
    }


def test_and_or_stop_at_the_first_decisive_operand() -> None:
    """As in Python: a guard keeps a division from being evaluated."""
    rule = compile_expression("b != 0 and a / b > 1", "f", KNOWN, condition=True)
    assert rule.holds({"a": 1.0, "b": 0.0, "theta": 0.0}) is False


REFUSED = [
    ("a.real", "attribute access"),
    ("a[0]", "subscripts"),
    ("lambda: 1", "lambdas"),
    ("[x for x in (1, 2)]", "comprehensions"),
    ("sum(x for x in (1, 2))", "function 'sum'"),
    ("'text'", "constant 'text'"),
    ("b'x'", "constant"),
    ("f'{a}'", "f-strings"),
    ("1j", "constant 1j"),
    ("True", "constant True"),
    ("None", "constant None"),
    ("(a, b)", "tuples"),
    ("[a]", "lists"),
    ("{'a': 1}", "mappings"),
    ("a if b else theta", "conditional expressions"),
    ("(c := 1)", "assignment"),
    ("a // b", "FloorDiv"),
    ("a @ b", "MatMult"),
    ("a << 1", "LShift"),
    ("a & b", "BitAnd"),
    ("~a", "~"),
    ("a in b", "comparison In"),
    ("a is b", "comparison Is"),
    ("__import__('os')", "function '__import__'"),
    ("eval('1')", "function 'eval'"),
    ("math.sin(a)", "calling anything but a named function"),
    ("sin(x=a)", "keyword arguments"),
    ("min(*a)", "starred"),
    ("sin", "function sin without a call"),
    ("a + (b < theta)", "mixing numbers and conditions"),
    ("a and b", "mixing numbers and conditions"),
    ("not a", "mixing numbers and conditions"),
]


@pytest.mark.parametrize(("text", "words"), REFUSED)
def test_constructs_outside_the_grammar_are_refused_naming_the_field(text: str, words: str) -> None:
    field = "family.pieces[2].polygon[1][0]"
    with pytest.raises(ExpressionError) as error:
        compile_expression(text, field, KNOWN)
    message = str(error.value)
    assert message.startswith(field)
    assert words in message
    assert "\n" not in message


def test_syntax_errors_are_refused_with_what_is_allowed() -> None:
    for text in ("a +", "2 ** * 3", "(a", "a b", "", "   ", "import os", "a = 1"):
        with pytest.raises(ExpressionError, match=r"^family\.goal\.yaw") as error:
            compile_expression(text, "family.goal.yaw", KNOWN)
        assert "allowed" in str(error.value) or "empty" in str(error.value)


def test_an_unknown_name_is_refused_listing_the_known_ones() -> None:
    with pytest.raises(ExpressionError) as error:
        compile_expression("a + gamma", "family.entries.drop[0]", KNOWN)
    message = str(error.value)
    assert message.startswith("family.entries.drop[0]")
    assert "'gamma'" in message
    assert "a, b, theta" in message


def test_wrong_calls_are_refused() -> None:
    for text in ("atan2(a)", "sqrt(a, b)", "min(a)", "foo(a)"):
        with pytest.raises(ExpressionError, match=r"^f = "):
            compile_expression(text, "f", KNOWN)


def test_numbers_and_conditions_are_not_mixed_up() -> None:
    with pytest.raises(ExpressionError, match="expected a condition"):
        compile_expression("a + 1", "rules[0].require", KNOWN, condition=True)
    with pytest.raises(ExpressionError, match="expected a number"):
        compile_expression("a < 1", "pieces[0].disc.radius", KNOWN)
    with pytest.raises(ExpressionError, match="expected a condition"):
        compile_expression(1.0, "rules[0].require", KNOWN, condition=True)
    for value in (True, None, [1], {"a": 1}):
        with pytest.raises(ExpressionError, match=r"^f: expected"):
            compile_expression(value, "f", KNOWN)


def test_size_and_non_finite_literals_are_bounded() -> None:
    with pytest.raises(ExpressionError, match="characters"):
        compile_expression("a + " * 200 + "a", "f", KNOWN)
    with pytest.raises(ExpressionError, match="not finite"):
        compile_expression("1e400", "f", KNOWN)
    with pytest.raises(ExpressionError, match="not finite"):
        compile_expression(float("nan"), "f", KNOWN)


def test_division_by_zero_at_evaluation_names_the_field_and_the_values() -> None:
    expression = compile_expression("a / (b - 1)", "family.pieces[0].polygon[2][1]", KNOWN)
    assert expression.evaluate({"a": 2.0, "b": 3.0, "theta": 0.0}) == 1.0
    with pytest.raises(ExpressionError) as error:
        expression.evaluate({"a": 2.0, "b": 1.0, "theta": 0.0})
    message = str(error.value)
    assert message.startswith("family.pieces[0].polygon[2][1]")
    assert "division by zero" in message
    assert "a = 2" in message and "b = 1" in message
    with pytest.raises(ExpressionError, match="division by zero"):
        compile_expression("a % b", "f", KNOWN).evaluate({"a": 1.0, "b": 0.0})


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("sqrt(a)", "math error"),
        ("acos(a)", "math error"),
        ("a ** 0.5", "math error"),  # (-2) ** 0.5: a domain error, never a complex number
        ("0 ** b", "math error"),
        ("10 ** (b * -400)", "math error"),
        ("hypot(1.5e308, 1.5e308)", "non-finite"),
        ("1e308 * -a * 10", "non-finite"),
        ("1 / (1e308 * -a * 10)", "non-finite"),  # no infinity hides as 1/inf = 0
    ],
)
def test_math_errors_and_non_finite_results_are_named(text: str, words: str) -> None:
    values = {"a": -2.0, "b": -1.0, "theta": 0.0}
    expression = compile_expression(text, "g", KNOWN)
    with pytest.raises(ExpressionError, match=r"^g = ") as error:
        expression.evaluate(values)
    assert words in str(error.value)
    for name in names_used(expression):  # the values that gave it
        assert f"{name} = {values[name]:g}" in str(error.value)


def test_a_number_and_a_condition_are_asked_the_right_way() -> None:
    with pytest.raises(ExpressionError):
        compile_expression("a", "f", KNOWN).holds(VALUES)
    with pytest.raises(ExpressionError):
        compile_expression("a < 1", "f", KNOWN, condition=True).evaluate(VALUES)
    with pytest.raises(ExpressionError, match="no value given for theta"):
        compile_expression("theta", "f", KNOWN).evaluate({"a": 1.0})


def test_compiled_expressions_are_plain_data() -> None:
    """Equal text compiles to equal (and hashable) values: a family can be compared and
    shipped to worker processes."""
    first = compile_expression("a * 2 + sin(theta)", "f", KNOWN)
    second = compile_expression("a * 2 + sin(theta)", "f", KNOWN)
    assert first == second
    assert hash(first) == hash(second)
