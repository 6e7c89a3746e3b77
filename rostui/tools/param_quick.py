"""The parts of `rostui param get` that must not load PyYAML: name resolution and simple-value text.

``rosparam get`` prints every value YAML-dumped.  For booleans, integers and
strings that YAML writes as plain, unquoted scalars the text is the value
itself, so :func:`simple_value_text` gives it without importing ``yaml``
(which costs more than the whole query).  Anything it is not certain about
returns None and goes through PyYAML (:func:`rostui.tools.param.format_get`).
"""

from __future__ import annotations

import os

__all__ = ["script_resolve", "simple_value_text"]

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

#: Characters of strings this module may print unquoted.
_PLAIN_CHARS = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./-")
#: Words YAML 1.1 reads as booleans or null (compared lower-cased, with a margin: y, n).
_KEYWORDS = frozenset(("yes", "no", "true", "false", "on", "off", "null", "y", "n"))


def script_resolve(name: str, script: str = "rosparam") -> str:
    """Resolve a name typed on the command line like rosparam does.

    Relative names resolve in ``ROS_NAMESPACE`` (default ``/``); ``~x`` under
    the tool's own node name ``/<script>``.
    """
    if name == "/" or (name.startswith("/") and "//" not in name and not name.endswith("/")):
        return name  # already global and canonical: skip importing the name machinery
    from rostui.core import names

    ns = os.environ.get("ROS_NAMESPACE") or "/"
    if not name:
        return names.resolve_name("", ns)
    if name.startswith("~"):
        return names.resolve_name(name, ns, node_name=names.join_names(ns, script))
    return names.resolve_name(name, ns)


def _is_plain_string(text: str) -> bool:
    """True when YAML dumps ``text`` unquoted and reads it back as the same string.

    Deliberately narrow: ASCII letters, digits and ``_./-``, starting with a
    letter, ``_`` or ``/`` (then only the boolean/null words are ambiguous), or
    with a digit when the rest cannot be read as an int, float or date.
    """
    if not text or not _PLAIN_CHARS.issuperset(text):
        return False
    first = text[0]
    if first.isalpha() or first in "_/":
        return text.lower() not in _KEYWORDS
    if not first.isdigit() or "." in text or text[4:5] == "-":  # floats need a dot; dates are dddd-dd-dd
        return False
    if first == "0" and text[1:2].isalpha():  # 0x1f, 0b101
        return False
    return not frozenset(text).issubset("0123456789_")  # ints (1_000, 017)


def simple_value_text(value: Any) -> str | None:
    """What ``rosparam get`` prints for ``value`` (without the final newline), or None if YAML must decide."""
    if value is True:
        return "true"
    if value is False:
        return "false"
    if type(value) is int:
        return str(value)
    if type(value) is str and _is_plain_string(value):
        return value
    return None
