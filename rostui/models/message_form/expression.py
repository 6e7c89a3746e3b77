"""Expressions in a form's rows, as rqt_publisher takes them, evaluated without running Python code.

A row holds a Python-like expression: literals (numbers, strings, ``True``, lists, dicts), arithmetic,
comparisons, ``a if c else b``, the variables a form gives (``i`` the message's number, 1 for the first, as
rqt_publisher counts; ``t`` seconds since the first message; ``now`` the current time) and the functions of
:data:`FUNCTIONS` (``sin(t)``, ``math.cos(2*pi*t)``, ``random()``). Nothing else is allowed: no attribute but
``math.X``, no import, no name the form did not give, no ``%`` formatting of strings. Every value an expression
makes is bounded, and checked before the larger ones are computed: integers to :data:`MAX_INT_BITS` bits, all the
items of a string, list or dict and of the lists inside it to :data:`MAX_ITEMS` together, ``round``'s digits to
:data:`MAX_DIGITS`; so a typed expression costs bounded time and memory.
"""

from __future__ import annotations

import ast
import math
import operator
import random
from typing import Any, Callable, Mapping

from rostui.core.one_line import exception_line

__all__ = ["ExpressionError", "FUNCTIONS", "CONSTANTS", "MAX_DIGITS", "MAX_ITEMS", "MAX_INT_BITS", "MAX_TEXT",
           "evaluate", "check_syntax", "is_number_literal"]

#: Longest expression text taken.
MAX_TEXT = 100_000

#: Most items a string, list or dict an expression makes may hold.
MAX_ITEMS = 1_000_000

#: Most bits an integer an expression makes may have.
MAX_INT_BITS = 4096

#: Most digits ``round`` may be asked for, either side of the point.
MAX_DIGITS = 400


def _round(number: Any, digits: Any = None) -> Any:
    """``round``, with its digits bounded (``round(1, -10**9)`` would compute ``10**(10**9)``)."""
    if digits is None:
        return round(number)
    if isinstance(digits, int) and abs(digits) > MAX_DIGITS:
        raise ExpressionError(f"round to at most {MAX_DIGITS} digits")
    return round(number, digits)


#: Functions an expression may call, by name (also as ``math.<name>`` where math has it).
FUNCTIONS: dict[str, Callable[..., Any]] = {
    **{name: getattr(math, name) for name in (
        "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "sqrt", "exp", "log",
        "log10", "log2", "floor", "ceil", "fabs", "hypot", "degrees", "radians", "fmod", "copysign")},
    "abs": abs, "min": min, "max": max, "round": _round, "int": int, "float": float, "bool": bool, "str": str,
    "len": len, "random": random.random, "uniform": random.uniform, "gauss": random.gauss,
}

#: Names every expression knows besides the form's variables.
CONSTANTS: dict[str, Any] = {"pi": math.pi, "e": math.e, "tau": math.tau, "inf": math.inf, "nan": math.nan,
                             "True": True, "False": False, "None": None, "true": True, "false": False}

_BINARY: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod, ast.Pow: operator.pow,
}
_UNARY: dict[type, Callable[[Any], Any]] = {ast.USub: operator.neg, ast.UAdd: operator.pos, ast.Not: operator.not_}
_COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt,
    ast.GtE: operator.ge,
}


class ExpressionError(Exception):
    """What is wrong with an expression, in one line."""


def evaluate(text: str, variables: Mapping[str, Any] | None = None) -> Any:
    """The value of ``text`` with ``variables`` (and :data:`CONSTANTS`, :data:`FUNCTIONS`); :class:`ExpressionError`
    for anything it cannot or may not compute."""
    if len(text) > MAX_TEXT:
        raise ExpressionError(f"expression longer than {MAX_TEXT} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ExpressionError(f"not an expression: {exc.msg}") from None
    except (ValueError, RecursionError, MemoryError):
        raise ExpressionError("not an expression") from None
    try:
        return _Evaluator({**CONSTANTS, **(variables or {})}).value(tree.body)
    except ExpressionError:
        raise
    except RecursionError:
        raise ExpressionError("expression nested too deeply") from None
    except Exception as exc:  # whatever an operator or a function raises is the expression's mistake
        raise ExpressionError(f"{type(exc).__name__}: {exception_line(exc)}") from None


def check_syntax(text: str) -> None:
    """:class:`ExpressionError` when ``text`` is not an expression at all (what a form file can be checked for
    before anything is sent)."""
    if len(text) > MAX_TEXT:
        raise ExpressionError(f"expression longer than {MAX_TEXT} characters")
    try:
        ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ExpressionError(f"not an expression: {exc.msg}") from None
    except (ValueError, RecursionError, MemoryError):
        raise ExpressionError("not an expression") from None


def is_number_literal(text: str) -> bool:
    """True when ``text`` is a plain number (``2``, ``-0.5``): what a slider may replace with another."""
    try:
        node = ast.parse(text.strip(), mode="eval").body
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return False
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        node = node.operand
    return isinstance(node, ast.Constant) and type(node.value) in (int, float)


class _Evaluator:
    """Walks one expression's tree, allowing only what the module's docstring lists."""

    def __init__(self, names: Mapping[str, Any]) -> None:
        self.names = names

    def value(self, node: ast.AST) -> Any:
        """The value of ``node``."""
        method = getattr(self, f"_{type(node).__name__}", None)
        if method is None:
            raise ExpressionError(f"{_describe(node)} is not allowed in an expression")
        return _bounded(method(node))

    def _Constant(self, node: ast.Constant) -> Any:
        if isinstance(node.value, (bytes, complex)) or node.value is Ellipsis:
            raise ExpressionError(f"{node.value!r} is not allowed in an expression")
        return node.value

    def _Name(self, node: ast.Name) -> Any:
        if node.id in self.names:
            return self.names[node.id]
        if node.id in FUNCTIONS:
            raise ExpressionError(f"{node.id} is a function: call it, as {node.id}(...)")
        raise ExpressionError(f"unknown name {node.id!r} (a string needs quotes)")

    def _UnaryOp(self, node: ast.UnaryOp) -> Any:
        op = _UNARY.get(type(node.op))
        if op is None:
            raise ExpressionError(f"{_describe(node.op)} is not allowed in an expression")
        return op(self.value(node.operand))

    def _BinOp(self, node: ast.BinOp) -> Any:
        op = _BINARY.get(type(node.op))
        if op is None:
            raise ExpressionError(f"{_describe(node.op)} is not allowed in an expression")
        left, right = self.value(node.left), self.value(node.right)
        if isinstance(node.op, ast.Pow) and isinstance(left, int) and isinstance(right, int) and right > 0:
            if max(abs(left).bit_length(), 1) * right > MAX_INT_BITS and abs(left) > 1:
                raise ExpressionError(f"{left} ** {right} is too large")
        if isinstance(node.op, ast.Mult):
            _check_repeat(left, right)
        if isinstance(node.op, ast.Mod) and isinstance(left, str):
            raise ExpressionError("% formatting of text is not allowed in an expression")
        return op(left, right)

    def _BoolOp(self, node: ast.BoolOp) -> Any:
        result: Any = None
        for operand in node.values:
            result = self.value(operand)
            if isinstance(node.op, ast.And) and not result or isinstance(node.op, ast.Or) and result:
                return result
        return result

    def _Compare(self, node: ast.Compare) -> Any:
        left = self.value(node.left)
        for op, right_node in zip(node.ops, node.comparators):
            compare = _COMPARE.get(type(op))
            if compare is None:
                raise ExpressionError(f"{_describe(op)} is not allowed in an expression")
            right = self.value(right_node)
            if not compare(left, right):
                return False
            left = right
        return True

    def _IfExp(self, node: ast.IfExp) -> Any:
        return self.value(node.body) if self.value(node.test) else self.value(node.orelse)

    def _List(self, node: ast.List) -> Any:
        return [self.value(item) for item in node.elts]

    def _Tuple(self, node: ast.Tuple) -> Any:
        return [self.value(item) for item in node.elts]

    def _Dict(self, node: ast.Dict) -> Any:
        if any(key is None for key in node.keys):
            raise ExpressionError("** is not allowed in an expression")
        return {self.value(key): self.value(value) for key, value in zip(node.keys, node.values)  # type: ignore[arg-type]
                }

    def _Call(self, node: ast.Call) -> Any:
        if node.keywords or any(isinstance(arg, ast.Starred) for arg in node.args):
            raise ExpressionError("only plain arguments are allowed in a call")
        function = self._function(node.func)
        return function(*(self.value(arg) for arg in node.args))

    def _function(self, node: ast.AST) -> Callable[..., Any]:
        if isinstance(node, ast.Name) and node.id in FUNCTIONS:
            return FUNCTIONS[node.id]
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "math"
                and node.attr in FUNCTIONS and hasattr(math, node.attr)):
            return FUNCTIONS[node.attr]
        name = ast.unparse(node)
        raise ExpressionError(f"unknown function {name!r} (known: {', '.join(sorted(FUNCTIONS))})")

    def _Attribute(self, node: ast.Attribute) -> Any:
        if isinstance(node.value, ast.Name) and node.value.id == "math" and node.attr in ("pi", "e", "tau", "inf",
                                                                                         "nan"):
            return CONSTANTS[node.attr]
        if isinstance(node.value, ast.Name) and node.value.id == "math" and node.attr in FUNCTIONS:
            raise ExpressionError(f"math.{node.attr} is a function: call it, as math.{node.attr}(...)")
        raise ExpressionError(f"attribute {ast.unparse(node)!r} is not allowed in an expression")


def _check_repeat(left: Any, right: Any) -> None:
    """``"ab" * n`` and ``[0] * n`` only while the result, the lists inside it counted, stays within
    :data:`MAX_ITEMS` (checked before it is made)."""
    for seq, count in ((left, right), (right, left)):
        if isinstance(seq, (str, list)) and isinstance(count, int) and _size(seq) * max(count, 0) > MAX_ITEMS:
            raise ExpressionError(f"a repeated {type(seq).__name__} longer than {MAX_ITEMS} items")


def _size(value: Any, seen: dict[int, int] | None = None) -> int:
    """Items in ``value`` and in the strings, lists and dicts inside it, each shared one counted where it appears."""
    if isinstance(value, str):
        return len(value)
    if not isinstance(value, (list, dict)):
        return 1
    seen = {} if seen is None else seen
    known = seen.get(id(value))
    if known is not None:
        return known
    seen[id(value)] = len(value)  # a list that holds itself cannot be made here; this only ends the walk
    items = value.values() if isinstance(value, dict) else value
    total = len(value)
    for item in items:
        total += _size(item, seen) if isinstance(item, (str, list, dict)) else 0
        if total > MAX_ITEMS:
            break
    seen[id(value)] = total
    return total


def _bounded(value: Any) -> Any:
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > MAX_INT_BITS:
        raise ExpressionError(f"an integer of more than {MAX_INT_BITS} bits")
    if isinstance(value, (str, list, dict)) and _size(value) > MAX_ITEMS:
        raise ExpressionError(f"a {type(value).__name__} of more than {MAX_ITEMS} items")
    return value


def _describe(node: ast.AST) -> str:
    return {"Lambda": "lambda", "ListComp": "a comprehension", "GeneratorExp": "a comprehension",
            "SetComp": "a comprehension", "DictComp": "a comprehension", "Subscript": "indexing",
            "NamedExpr": ":=", "Starred": "*", "JoinedStr": "an f-string", "Set": "a set",
            "BitAnd": "&", "BitOr": "|", "BitXor": "^", "LShift": "<<", "RShift": ">>", "MatMult": "@",
            "Is": "is", "IsNot": "is not", "In": "in", "NotIn": "not in", "Invert": "~"}.get(
        type(node).__name__, type(node).__name__)
