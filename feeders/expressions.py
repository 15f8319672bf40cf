"""A small, safe expression language for parametric devices (issue 24's device families).

A device family writes its pieces, entries, goal and rules as expressions of named design
parameters (``"b/2 + 0.4"``, ``"pin_x + pin_r < 1.0"``). Text is parsed by :mod:`ast` in
"eval" mode and accepted only when every node is one of::

    expression := number | name | "pi" | ( expression )
                | (+|-) expression
                | expression (+ | - | * | / | % | **) expression
                | function ( expression, ... )
    condition  := expression (< | <= | > | >= | == | !=) expression [(<|...) expression ...]
                | condition and condition | condition or condition | not condition
                | ( condition )

``function`` is one of :data:`FUNCTIONS` (``min``, ``max``, ``abs``, ``sqrt``, trigonometry in
radians, ``atan2``, ``hypot``...). Numbers and conditions do not mix: ``a + (b < c)`` and
``a and b`` are refused. The text is compiled once into a tree of plain tuples and evaluated
against a mapping of parameter values with IEEE floats (``**`` is :func:`math.pow`, so a
negative base with a fractional power is a domain error, never a complex number); nothing is
ever handed to ``eval`` or ``exec``.

Every error is a :class:`ExpressionError`, one line naming the field the expression came
from and what is allowed: a syntax error, a name that is not a parameter (with the known
ones), a construct outside the grammar (attributes, subscripts, lambdas, comprehensions,
strings...) and, at evaluation, division by zero, a math domain error or a non-finite result
(with the parameter values that gave it).
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from feeders.fields import FieldError, shown, shown_value

MAX_SOURCE = 500  # characters of one expression: a device's expressions are a line each
MAX_NODES = 200  # nodes of one expression's tree (bounds the evaluation's recursion)


class ExpressionError(FieldError):
    """An expression that cannot be compiled or evaluated; the message names the field."""


# name: (function, least arguments, most arguments)
FUNCTIONS: dict[str, tuple[Callable[..., float], int, int]] = {
    "min": (min, 2, 16),
    "max": (max, 2, 16),
    "abs": (abs, 1, 1),
    "sqrt": (math.sqrt, 1, 1),
    "sin": (math.sin, 1, 1),
    "cos": (math.cos, 1, 1),
    "tan": (math.tan, 1, 1),
    "asin": (math.asin, 1, 1),
    "acos": (math.acos, 1, 1),
    "atan": (math.atan, 1, 1),
    "atan2": (math.atan2, 2, 2),
    "hypot": (math.hypot, 2, 2),
    "radians": (math.radians, 1, 1),
    "degrees": (math.degrees, 1, 1),
}
CONSTANTS: dict[str, float] = {"pi": math.pi}
RESERVED = frozenset(FUNCTIONS) | frozenset(CONSTANTS)
"""Names a parameter may not take: the functions and constants of the language."""

_BINARY: dict[type, tuple[str, Callable[[float, float], float]]] = {
    ast.Add: ("+", lambda x, y: x + y),
    ast.Sub: ("-", lambda x, y: x - y),
    ast.Mult: ("*", lambda x, y: x * y),
    ast.Div: ("/", lambda x, y: x / y),
    ast.Mod: ("%", lambda x, y: x % y),
    ast.Pow: ("**", math.pow),
}
_COMPARE: dict[type, tuple[str, Callable[[float, float], bool]]] = {
    ast.Lt: ("<", lambda x, y: x < y),
    ast.LtE: ("<=", lambda x, y: x <= y),
    ast.Gt: (">", lambda x, y: x > y),
    ast.GtE: (">=", lambda x, y: x >= y),
    ast.Eq: ("==", lambda x, y: x == y),
    ast.NotEq: ("!=", lambda x, y: x != y),
}
_BINARY_BY_SYMBOL = {symbol: f for symbol, f in _BINARY.values()}
_COMPARE_BY_SYMBOL = {symbol: f for symbol, f in _COMPARE.values()}

ALLOWED = (
    "numbers, parameter names, pi, + - * / % ** and parentheses, "
    f"calls of {', '.join(FUNCTIONS)}; in rules also comparisons (< <= > >= == !=) "
    "joined by and, or, not"
)

# What a refused construct is called in a message, by ast node type name.
_CONSTRUCTS = {
    "Attribute": "attribute access (x.y)",
    "Subscript": "subscripts (x[i])",
    "Lambda": "lambdas",
    "ListComp": "comprehensions",
    "SetComp": "comprehensions",
    "DictComp": "comprehensions",
    "GeneratorExp": "comprehensions",
    "IfExp": "conditional expressions (x if c else y)",
    "NamedExpr": "assignment (:=)",
    "List": "lists",
    "Tuple": "tuples",
    "Set": "sets",
    "Dict": "mappings",
    "JoinedStr": "f-strings",
    "Starred": "starred arguments",
    "Await": "await",
    "Yield": "yield",
    "YieldFrom": "yield",
    "Slice": "slices",
}

Tree = tuple[Any, ...]
"""A compiled expression: ``("num", v)``, ``("name", n)``, ``("neg", t)``, ``("bin", op, l, r)``,
``("call", f, (t, ...))``, ``("cmp", (op, ...), (t, ...))``, ``("and"|"or", (t, ...))`` or
``("not", t)``: plain data, with operators and functions by name."""


@dataclass(frozen=True)
class Expression:
    """A compiled expression: its ``source`` (as written, or the number), the ``field`` it came
    from (for messages), its ``tree``, the parameter ``names`` it uses and whether it is a
    ``condition`` (a rule: true or false) or a number."""

    source: str
    field: str
    tree: Tree
    names: frozenset[str]
    condition: bool = False

    def evaluate(self, values: Mapping[str, float]) -> float:
        """The number this expression gives with these parameter values (a finite float).

        Raises :class:`ExpressionError` naming the field and the values used on division by
        zero, a math domain error or a non-finite result."""
        if self.condition:
            raise ExpressionError(f"{self.field}: a condition where a number is expected")
        return float(self._run(values))

    def holds(self, values: Mapping[str, float]) -> bool:
        """Whether this condition is true with these parameter values (errors as
        :meth:`evaluate`)."""
        if not self.condition:
            raise ExpressionError(f"{self.field}: a number where a condition is expected")
        return bool(self._run(values))

    def _run(self, values: Mapping[str, float]) -> float | bool:
        missing = sorted(self.names - set(values))
        if missing:
            raise ExpressionError(f"{self.field}: no value given for {', '.join(missing)}")
        try:
            result = _evaluate(self.tree, values)
        except ZeroDivisionError:
            problem = "division by zero"
        except _NonFinite as exc:
            problem = f"a non-finite result ({exc})"
        except (ValueError, OverflowError) as exc:
            problem = f"math error ({exc})"
        else:
            if isinstance(result, bool) or math.isfinite(result):
                return result
            problem = f"a non-finite result ({result})"
        at = ", ".join(f"{n} = {values[n]:.6g}" for n in sorted(self.names)) or "no parameters"
        raise ExpressionError(
            f"{self.field} = {shown_value(self.source)}: {problem} at {at}; "
            "an expression must give a finite number for every parameter value it is used with"
        )


def names_used(expression: Expression) -> frozenset[str]:
    """The parameter names ``expression`` reads (not functions or ``pi``)."""
    return expression.names


def compile_expression(
    value: Any, field: str, known: Iterable[str], condition: bool = False
) -> Expression:
    """``value`` (a YAML number or text) as an :class:`Expression` over the parameter names
    ``known``; ``condition`` says whether it must be a rule (true or false) or a number.

    Refused with :class:`ExpressionError` naming ``field``: anything outside the grammar of
    this module, a name not in ``known``, a number that is not finite."""
    known = tuple(known)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if condition:
            raise ExpressionError(f"{field}: expected a condition (e.g. 'x < y'), got a number")
        number = _finite_literal(value, field)
        return Expression(repr(value), field, ("num", number), frozenset())
    if not isinstance(value, str):
        what = "a condition" if condition else "a number or an expression"
        raise ExpressionError(f"{field}: expected {what} as text, got {shown_value(value)}")
    if not value.strip():
        raise ExpressionError(f"{field}: an empty expression; allowed: {ALLOWED}")
    if len(value) > MAX_SOURCE:
        raise ExpressionError(
            f"{field}: {len(value)} characters; an expression has at most {MAX_SOURCE}"
        )
    try:
        parsed = ast.parse(value.strip(), mode="eval")
    except SyntaxError as exc:
        where = f" (column {exc.offset})" if exc.offset else ""
        raise ExpressionError(
            f"{field} = {shown_value(value)}: not a valid expression{where}; allowed: {ALLOWED}"
        ) from None
    except (ValueError, RecursionError, MemoryError) as exc:  # a 5,000-digit integer, nesting
        raise ExpressionError(
            f"{field} = {shown_value(value)}: cannot be read ({type(exc).__name__}); "
            f"allowed: {ALLOWED}"
        ) from None
    count = sum(1 for _ in ast.walk(parsed))
    if count > MAX_NODES:
        raise ExpressionError(
            f"{field}: an expression of {count} nodes; at most {MAX_NODES} are allowed"
        )
    compiler = _Compiler(value, field, known)
    tree, is_condition = compiler.node(parsed.body)
    if is_condition != condition:
        wanted = "a condition (a comparison, and, or, not)" if condition else "a number"
        raise ExpressionError(f"{field} = {shown_value(value)}: expected {wanted}")
    return Expression(value, field, tree, frozenset(compiler.names), condition)


def _finite_literal(value: int | float, field: str, source: str = "") -> float:
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        raise ExpressionError(
            f"{field} = {shown_value(source or value)}: a number that is not finite; "
            "numbers must lie within +-1.8e308"
        )
    return number


class _Compiler:
    """Walks a parsed expression into a :data:`Tree`, refusing what the grammar does not
    allow; ``names`` collects the parameters used."""

    def __init__(self, source: str, field: str, known: tuple[str, ...]):
        self.source, self.field, self.known = source, field, known
        self.names: set[str] = set()

    def refuse(self, what: str) -> ExpressionError:
        return ExpressionError(
            f"{self.field} = {shown_value(self.source)}: {what} not allowed; allowed: {ALLOWED}"
        )

    def number(self, node: ast.expr) -> Tree:
        tree, is_condition = self.node(node)
        if is_condition:
            return self._mixed()
        return tree

    def condition(self, node: ast.expr) -> Tree:
        tree, is_condition = self.node(node)
        if not is_condition:
            return self._mixed()
        return tree

    def _mixed(self) -> Tree:
        raise self.refuse("mixing numbers and conditions (e.g. 'a + (b < c)', 'a and b')")

    def node(self, node: ast.expr) -> tuple[Tree, bool]:
        """``(tree, is_condition)`` of ``node``."""
        if isinstance(node, ast.Constant):
            value = node.value
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise self.refuse(f"the constant {shown_value(value)}")
            return ("num", _finite_literal(value, self.field, self.source)), False
        if isinstance(node, ast.Name):
            return self.name(node.id), False
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.Not):
                return ("not", self.condition(node.operand)), True
            if isinstance(node.op, ast.USub):
                return ("neg", self.number(node.operand)), False
            if isinstance(node.op, ast.UAdd):
                return self.number(node.operand), False
            raise self.refuse("the operator ~")
        if isinstance(node, ast.BinOp):
            if type(node.op) not in _BINARY:
                raise self.refuse(f"the operator {type(node.op).__name__}")
            symbol = _BINARY[type(node.op)][0]
            return ("bin", symbol, self.number(node.left), self.number(node.right)), False
        if isinstance(node, ast.Compare):
            symbols = []
            for op in node.ops:
                if type(op) not in _COMPARE:
                    raise self.refuse(f"the comparison {type(op).__name__}")
                symbols.append(_COMPARE[type(op)][0])
            operands = tuple(self.number(n) for n in (node.left, *node.comparators))
            return ("cmp", tuple(symbols), operands), True
        if isinstance(node, ast.BoolOp):
            kind = "and" if isinstance(node.op, ast.And) else "or"
            return (kind, tuple(self.condition(v) for v in node.values)), True
        if isinstance(node, ast.Call):
            return self.call(node), False
        name = type(node).__name__
        raise self.refuse(_CONSTRUCTS.get(name, f"the construct {name}"))

    def name(self, name: str) -> Tree:
        if name in CONSTANTS:
            return ("num", CONSTANTS[name])
        if name in FUNCTIONS:
            raise self.refuse(f"the function {name} without a call")
        if name not in self.known:
            known = ", ".join(self.known) or "none"
            raise ExpressionError(
                f"{self.field} = {shown_value(self.source)}: unknown name '{shown(name)}'; "
                f"the parameters are: {shown(known)} (and the constant pi)"
            )
        self.names.add(name)
        return ("name", name)

    def call(self, node: ast.Call) -> Tree:
        if not isinstance(node.func, ast.Name):
            raise self.refuse("calling anything but a named function")
        name = node.func.id
        if name not in FUNCTIONS:
            raise self.refuse(f"the function '{shown(name)}' (known: {', '.join(FUNCTIONS)})")
        if node.keywords:
            raise self.refuse("keyword arguments")
        args = tuple(self.number(a) for a in node.args)
        _, least, most = FUNCTIONS[name]
        if not least <= len(node.args) <= most:
            count = str(least) if least == most else f"{least} to {most}"
            raise ExpressionError(
                f"{self.field} = {shown_value(self.source)}: {name} takes {count} "
                f"argument(s), got {len(node.args)}"
            )
        return ("call", name, args)


class _NonFinite(ArithmeticError):
    """An operation whose result is infinite or NaN (IEEE arithmetic does not raise)."""


def _evaluate(tree: Tree, values: Mapping[str, float]) -> Any:
    """The value of a compiled tree (float, or bool for a condition); Python's arithmetic
    errors pass through for :meth:`Expression._run` to name."""
    kind = tree[0]
    if kind == "num":
        return tree[1]
    if kind == "name":
        return float(values[tree[1]])
    if kind == "neg":
        return -_evaluate(tree[1], values)
    if kind == "bin":
        result = _BINARY_BY_SYMBOL[tree[1]](_evaluate(tree[2], values), _evaluate(tree[3], values))
        if not math.isfinite(result):  # no infinity is carried on to hide as 1/inf = 0
            raise _NonFinite(f"{tree[1]} gave {result}")
        return result
    if kind == "call":
        result = FUNCTIONS[tree[1]][0](*(_evaluate(a, values) for a in tree[2]))
        if not math.isfinite(result):
            raise _NonFinite(f"{tree[1]} gave {result}")
        return float(result)
    if kind == "cmp":
        operands = [_evaluate(t, values) for t in tree[2]]
        return all(
            _COMPARE_BY_SYMBOL[op](operands[i], operands[i + 1]) for i, op in enumerate(tree[1])
        )
    if kind == "and":
        return all(_evaluate(t, values) for t in tree[1])
    if kind == "or":
        return any(_evaluate(t, values) for t in tree[1])
    if kind == "not":
        return not _evaluate(tree[1], values)
    raise AssertionError(f"unknown node {kind}")
