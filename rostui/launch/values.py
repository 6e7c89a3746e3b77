"""Typed parameter values from launch-file text, as roslaunch converts them."""

from __future__ import annotations

from typing import Any

import yaml


def convert_value(text: str, type_name: str) -> Any:
    """``text`` as a value of ``type_name`` (auto, str/string, int, double, bool/boolean, yaml).

    ``auto`` gives a float when the text has a ``.``, else an int when it has no
    ``_``, else a bool for true/false (any case), else the text.  Raises ValueError.
    """
    kind = type_name.lower()
    if kind == "auto":
        try:
            if "." in text:
                return float(text)
            if "_" not in text:
                return int(text)
        except ValueError:
            pass
        if text.lower() in ("true", "false"):
            return text.lower() == "true"
        return text
    if kind in ("str", "string"):
        return text
    if kind == "int":
        return int(text)
    if kind == "double":
        return float(text)
    if kind in ("bool", "boolean"):
        word = text.lower().strip()
        if word in ("true", "1"):
            return True
        if word in ("false", "0"):
            return False
        raise ValueError(f"{word} is not a '{type_name}' type")
    if kind == "yaml":
        try:
            return yaml.safe_load(text)
        except yaml.YAMLError as exc:
            raise ValueError(str(exc)) from None
    raise ValueError(f"Unknown type '{type_name}'")
