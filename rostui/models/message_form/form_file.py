"""A form saved as YAML, and read back: where it sends, the type, the rate, each field's expression, the sliders.

::

    # rostui form: `rostui publish --form FILE` opens it
    publish: /turtle1/cmd_vel        # or  call: /spawn
    type: geometry_msgs/Twist
    rate: 10                         # Hz; left out, a message is sent once per ctrl+s
    fields:
      linear.x: '2.0'
      angular.z: sin(t)
    sliders:
      linear.x: [-2.0, 2.0]

Every problem is one line with the file and line (a field's expression that is not an expression at all
included). A file larger than :data:`MAX_FILE_BYTES` or one using YAML aliases is refused before it is read
further. A value written by hand is an expression as written (``x: 5.5``, ``frame_id: map``); a YAML list or
mapping becomes the expression of the same list or dict.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from rostui.core.one_line import exception_line
from rostui.tools.yaml_file import MAX_FILE_BYTES, YamlFileError, read_yaml_node

from .expression import ExpressionError, check_syntax
from .rows import MessageForm

__all__ = ["FormFileError", "FormSpec", "MAX_FILE_BYTES", "read_form", "write_form", "apply_spec", "spec_of"]

_KEYS = ("publish", "call", "type", "rate", "fields", "sliders")


class FormFileError(Exception):
    """What is wrong with a form file: one line, ``FILE:LINE: what``."""


@dataclass
class FormSpec:
    """What a form file holds: ``kind`` (``publish`` or ``call``), the topic or service ``name``, ``type_name``,
    ``rate`` (Hz, publish only) and per-field ``expressions`` and slider ranges; ``lines`` has the line of each
    field, for errors found later."""

    kind: str
    name: str
    type_name: str
    rate: float | None = None
    expressions: dict[str, str] = field(default_factory=dict)
    sliders: dict[str, tuple[float, float]] = field(default_factory=dict)
    path: str = ""
    lines: dict[str, int] = field(default_factory=dict)


def spec_of(form: MessageForm, kind: str, name: str, type_name: str, rate: float | None) -> FormSpec:
    """The spec of ``form`` as it stands: every row's expression and every slider range set."""
    return FormSpec(kind, name, type_name, rate, {row.path: row.expression for row in form.rows},
                    {row.path: (row.low, row.high) for row in form.rows
                     if row.low is not None and row.high is not None})


def write_form(spec: FormSpec, path: Path) -> None:
    """Write ``spec`` to ``path`` as YAML (OSError as the system says it)."""
    document: dict[str, Any] = {spec.kind: spec.name, "type": spec.type_name}
    if spec.rate is not None:
        document["rate"] = spec.rate
    document["fields"] = dict(spec.expressions)
    if spec.sliders:
        document["sliders"] = {key: [low, high] for key, (low, high) in spec.sliders.items()}
    text = yaml.dump(document, Dumper=_FormDumper, sort_keys=False, default_flow_style=False, width=100,
                     allow_unicode=True)
    path.write_text(f"# rostui form: `rostui {spec.kind} --form {path.name}` opens it\n{text}", encoding="utf-8")


class _FormDumper(yaml.SafeDumper):
    """Block mappings, with each slider's range on its key's line."""


_FormDumper.add_representer(list, lambda dumper, value: dumper.represent_sequence(
    "tag:yaml.org,2002:seq", value, flow_style=True))


def read_form(path: Path) -> FormSpec:
    """The spec in the file at ``path``; :class:`FormFileError` (``FILE:LINE: what``) for anything wrong in it."""
    where = str(path)
    try:
        root = read_yaml_node(path, "a form")
    except YamlFileError as exc:
        raise FormFileError(str(exc)) from None
    if not isinstance(root, yaml.MappingNode):
        raise FormFileError(f"{where}:{_line(root)}: a form is a mapping of {', '.join(_KEYS)}")
    top = _mapping(root, where)
    for key, (key_node, _) in top.items():
        if key not in _KEYS:
            raise FormFileError(f"{where}:{_line(key_node)}: unknown key {key!r} (a form has {', '.join(_KEYS)})")
    kinds = [kind for kind in ("publish", "call") if kind in top]
    if len(kinds) != 1:
        raise FormFileError(f"{where}:{_line(root)}: a form names either `publish: TOPIC` or `call: SERVICE`")
    kind = kinds[0]
    if kind == "publish" and "type" not in top:
        raise FormFileError(f"{where}:{_line(root)}: a publish form needs `type: pkg/Type`")
    spec = FormSpec(kind, _text(top[kind][1], where, kind), _text(top["type"][1], where, "type") if "type" in top
                    else "", path=where)
    if "rate" in top:
        spec.rate = _rate(top["rate"][1], where)
    for name, (key_node, value) in (_mapping(top["fields"][1], where) if "fields" in top else {}).items():
        spec.expressions[name] = _expression(value, where)
        spec.lines[name] = _line(key_node)
    for name, (key_node, value) in (_mapping(top["sliders"][1], where) if "sliders" in top else {}).items():
        spec.sliders[name] = _range(value, where, name)
        spec.lines.setdefault(name, _line(key_node))
    return spec


def apply_spec(form: MessageForm, spec: FormSpec) -> None:
    """Set ``form``'s rows from ``spec``; :class:`FormFileError` for a field the type does not have."""
    for name in list(spec.expressions) + list(spec.sliders):
        if form.row(name) is None:
            raise FormFileError(f"{spec.path}:{spec.lines.get(name, 1)}: {form.type_name} has no field {name!r} "
                                f"(it has {', '.join(row.path for row in form.rows) or 'none'})")
    for name, expression in spec.expressions.items():
        row = form.row(name)
        assert row is not None
        if row.type != "string":  # a string field takes any text
            try:
                check_syntax(expression)
            except ExpressionError as exc:
                raise FormFileError(f"{spec.path}:{spec.lines.get(name, 1)}: {name}: {exc}") from None
        row.expression = expression
    for name, (low, high) in spec.sliders.items():
        row = form.row(name)
        assert row is not None
        if not row.numeric:
            raise FormFileError(f"{spec.path}:{spec.lines.get(name, 1)}: {name} is a {row.type}, not a number: "
                                "it has no slider")
        row.low, row.high = low, high


def _line(node: yaml.Node | None) -> int:
    return node.start_mark.line + 1 if node is not None else 1


def _mapping(node: yaml.Node, where: str) -> dict[str, tuple[yaml.Node, yaml.Node]]:
    if not isinstance(node, yaml.MappingNode):
        raise FormFileError(f"{where}:{_line(node)}: expected a mapping here")
    out: dict[str, tuple[yaml.Node, yaml.Node]] = {}
    for key_node, value in node.value:
        if not isinstance(key_node, yaml.ScalarNode):
            raise FormFileError(f"{where}:{_line(key_node)}: a key must be a plain name")
        if key_node.value in out:
            raise FormFileError(f"{where}:{_line(key_node)}: {key_node.value!r} is given twice")
        out[key_node.value] = (key_node, value)
    return out


def _value(node: yaml.Node, where: str) -> Any:
    try:
        return yaml.SafeLoader("").construct_object(node, deep=True)
    except (yaml.YAMLError, ValueError, TypeError, OverflowError, RecursionError) as exc:
        raise FormFileError(f"{where}:{_line(node)}: not a value: {exception_line(exc)}") from None


def _text(node: yaml.Node, where: str, what: str) -> str:
    if not isinstance(node, yaml.ScalarNode) or not node.value.strip():
        raise FormFileError(f"{where}:{_line(node)}: {what} must be a name")
    return node.value.strip()


def _rate(node: yaml.Node, where: str) -> float | None:
    value = _value(node, where) if isinstance(node, yaml.ScalarNode) else None
    if value is None and isinstance(node, yaml.ScalarNode) and node.value in ("", "null", "~"):
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0 or math.isinf(value):
        raise FormFileError(f"{where}:{_line(node)}: rate must be a positive number of Hz")
    return float(value)


def _expression(node: yaml.Node, where: str) -> str:
    if isinstance(node, yaml.ScalarNode):
        return node.value
    return repr(_value(node, where))


def _range(node: yaml.Node, where: str, name: str) -> tuple[float, float]:
    value = _value(node, where)
    if (not isinstance(value, list) or len(value) != 2
            or any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in value)
            or not value[0] < value[1]):
        raise FormFileError(f"{where}:{_line(node)}: the slider of {name} needs [LOW, HIGH] with LOW < HIGH")
    return float(value[0]), float(value[1])
