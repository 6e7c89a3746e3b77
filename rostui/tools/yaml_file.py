"""A YAML file a person wrote (a form, a view, an rviz configuration), read within bounds, as a node tree.

The file is refused before it is parsed when it is larger than :data:`MAX_FILE_BYTES`, not UTF-8, nested
(brackets) more than :data:`MAX_FLOW_DEPTH` deep, or uses aliases (the way to a billion laughs); every problem
is one line, ``FILE:LINE: what``.  Nodes keep their lines, so a reader can say where a bad value is.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

__all__ = ["YamlFileError", "MAX_FILE_BYTES", "MAX_FLOW_DEPTH", "read_yaml_node", "node_line", "node_value"]

#: Largest file read.
MAX_FILE_BYTES = 1 << 20

#: Deepest nesting of brackets read: PyYAML's pure-Python parser takes time growing with the square of it.
MAX_FLOW_DEPTH = 64

#: libyaml's parser where PyYAML has it (it also bounds nesting); PyYAML's own otherwise.
LOADER: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class YamlFileError(ValueError):
    """What is wrong with the file: one line, ``FILE:LINE: what``."""


def read_yaml_node(path: Path, what: str) -> yaml.Node | None:
    """The YAML node tree of the file at ``path`` (None for an empty file); ``what`` names the kind of file in
    errors (``"a form"``)."""
    where = str(path)
    try:
        with open(path, "rb") as stream:
            data = stream.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise YamlFileError(f"{where}: {exc.strerror or exc}") from None
    if len(data) > MAX_FILE_BYTES:
        raise YamlFileError(f"{where}: larger than {MAX_FILE_BYTES} bytes: not {what}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise YamlFileError(f"{where}: not UTF-8 text (byte {exc.start})") from None
    deepest, deepest_line = _flow_depth(text)
    if deepest > MAX_FLOW_DEPTH:
        raise YamlFileError(f"{where}:{deepest_line}: YAML nested more than {MAX_FLOW_DEPTH} deep: not {what}")
    try:
        for event in yaml.parse(text, Loader=LOADER):
            if isinstance(event, yaml.AliasEvent):
                at = f":{event.start_mark.line + 1}" if event.start_mark is not None else ""
                raise YamlFileError(f"{where}{at}: YAML aliases are not allowed in {what}")
        return yaml.compose(text, Loader=LOADER)
    except RecursionError:
        raise YamlFileError(f"{where}: YAML nested too deeply for {what}") from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        at = f":{mark.line + 1}" if mark is not None else ""
        raise YamlFileError(f"{where}{at}: YAML error: {exc.problem or exc.context}") from None
    except yaml.YAMLError as exc:
        raise YamlFileError(f"{where}: YAML error: {exc}") from None


def node_line(node: yaml.Node | None) -> int:
    """The 1-based line ``node`` starts on (1 when unknown)."""
    mark = getattr(node, "start_mark", None)
    return mark.line + 1 if mark is not None else 1


def node_value(node: yaml.Node) -> Any:
    """``node`` as plain Python values (YAML's safe types)."""
    return yaml.SafeLoader("").construct_object(node, deep=True)


def _flow_depth(text: str) -> tuple[int, int]:
    """The deepest nesting of ``[`` and ``{`` outside quotes, and the line where it is deepest."""
    depth = deepest = 0
    line = deepest_line = 1
    quote = ""
    for char in text:
        if char == "\n":
            line += 1
        elif quote:
            quote = "" if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char in "[{":
            depth += 1
            if depth > deepest:
                deepest, deepest_line = depth, line
        elif char in "]}":
            depth = max(depth - 1, 0)
    return deepest, deepest_line
