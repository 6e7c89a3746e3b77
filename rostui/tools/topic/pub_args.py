"""``rostui topic pub``'s input: YAML arguments, ``-f`` files and stdin documents, and building the message from them."""

from __future__ import annotations

import os
import sys
from typing import Any, Iterator, Sequence

from rostui.tools.topic.common import TopicToolError, UsageError, one_line
from rostui.tools.topic.echo import is_message


def yaml_error(e: Exception, where: str = "") -> str:
    """One line for a YAML error: what was wrong and where (``file:line:column``)."""
    problem = getattr(e, "problem", None) or getattr(e, "context", None) or one_line(str(e))
    mark = getattr(e, "problem_mark", None) or getattr(e, "context_mark", None)
    if mark is None:
        return f"{where}: {problem}" if where else str(problem)
    pos = f"{mark.line + 1}:{mark.column + 1}"
    return f"{where}:{pos}: {problem}" if where else f"{problem} (line {mark.line + 1}, column {mark.column + 1})"


def parse_yaml_args(args: Sequence[str]) -> list[Any]:
    """Each ``rostopic pub`` argument as YAML; :class:`UsageError` for malformed YAML."""
    import yaml

    out = []
    for a in args:
        try:
            out.append(yaml.safe_load(a))
        except yaml.YAMLError as e:
            raise UsageError(f"Argument error: argument {len(out) + 1} ({a!r}) is not valid YAML: {yaml_error(e)}") from None
    return out


def printable_args(msg: Any, prefix: str = "") -> str:
    """The field names a positional ``pub`` needs, as genpy lists them (``x y z``)."""
    names = []
    for f in msg.__slots__:
        v = getattr(msg, f)
        if is_message(v):
            names.append(printable_args(v, prefix + f + "."))
        else:
            names.append(prefix + f)
    return " ".join(names)


def build_message(cls: Any, pub_args: list[Any], now: Any = None) -> Any:
    """A *cls* message filled from parsed ``pub`` arguments (``now``/``auto`` substituted).

    Raises :class:`TopicToolError` with one line naming the problem.
    """
    from rostui.core.msg import MessageError
    from rostui.core.msg.convert import fill_message_args

    msg = cls()
    try:
        return fill_message_args(msg, list(pub_args), now=now)
    except (MessageError, ValueError, TypeError) as e:
        raise TopicToolError(f"{one_line(str(e))} (args are: [{printable_args(cls())}])") from None


def message_class(type_name: str) -> Any:
    """The class of a message type for ``pub``; one-line error for an unknown type."""
    from rostui.core.msg import MessageError, get_message_class

    try:
        return get_message_class(type_name)
    except (MessageError, ValueError, OSError):
        pkg = type_name.split("/", 1)[0] if "/" in type_name else type_name
        raise TopicToolError(f"invalid message type: {type_name}. If this is a valid message type, "
                             f"check that package '{pkg}' is on ROS_PACKAGE_PATH") from None


def yaml_documents_from_file(path: str) -> list[Any]:
    """Every YAML document of an echo-formatted file (``---`` separated)."""
    import yaml

    if not os.path.isfile(path):
        raise TopicToolError(f"file does not exist: {path}")
    try:
        with open(path, encoding="utf-8") as f:
            return list(yaml.safe_load_all(f))
    except yaml.YAMLError as e:
        raise TopicToolError(f"invalid YAML in file: {yaml_error(e, path)}") from None



def stdin_documents() -> Iterator[Any]:
    """YAML documents read from stdin, each ended by a ``---`` line; a partial last one is dropped."""
    import yaml

    buff: list[str] = []
    for line in sys.stdin:
        if line.strip() == "---":
            try:
                loaded = yaml.safe_load("".join(buff).rstrip())
            except yaml.YAMLError as e:
                sys.stderr.write("Invalid YAML: %s\n" % yaml_error(e, "<stdin>"))
                loaded = None
            buff = []
            if loaded is not None:
                yield loaded
        else:
            buff.append(line)
