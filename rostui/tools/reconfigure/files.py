"""Configurations in YAML, as ``dynparam dump`` writes them and ``dynparam load`` and ``dynparam set`` read them.

A dump is PyYAML's picture of dynamic_reconfigure's ``Config`` (``!!python/object/new:
dynamic_reconfigure.encoding.Config`` with its ``dictitems``), byte for byte what dynparam writes. Reading is
safe where dynparam's is not: dynparam loads with PyYAML's full Loader (any Python object a file names);
here only plain YAML and that one class are read, as dicts.
"""

from __future__ import annotations

from typing import Any

import yaml

from .encoding import Config

__all__ = ["ConfigFileError", "dump_text", "load_values", "parse_values"]

CONFIG_TAG = "tag:yaml.org,2002:python/object/new:dynamic_reconfigure.encoding.Config"
"""The tag PyYAML gives a dumped ``Config``."""


class ConfigFileError(ValueError):
    """A file or text that is not a configuration (one line, with file:line where there is a file)."""


class _ConfigLoader(yaml.SafeLoader):
    """Plain YAML plus dynamic_reconfigure's dumped ``Config``, read as a dict."""


def _construct_config(loader: yaml.SafeLoader, node: yaml.Node) -> dict[str, Any]:
    if not isinstance(node, yaml.MappingNode):
        raise yaml.constructor.ConstructorError(None, None, "a Config must be a mapping", node.start_mark)
    fields = loader.construct_mapping(node, deep=True)
    items = fields.get("dictitems", {})
    if not isinstance(items, dict):
        raise yaml.constructor.ConstructorError(None, None, "a Config's dictitems must be a mapping", node.start_mark)
    return dict(items)


_ConfigLoader.add_constructor(CONFIG_TAG, _construct_config)


def dump_text(config: Config) -> str:
    """*config* as ``dynparam dump`` writes it."""
    return str(yaml.dump(config))


def _documents(text: str, source: str) -> list[Any]:
    try:
        return list(yaml.load_all(text, Loader=_ConfigLoader))  # noqa: S506 (a SafeLoader with one class added)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        where = f"{source}:{mark.line + 1}" if mark is not None else source
        raise ConfigFileError(f"{where}: {exc.problem or exc}") from None
    except yaml.YAMLError as exc:
        raise ConfigFileError(f"{source}: {exc}") from None


def load_values(text: str, source: str) -> dict[str, Any]:
    """The values of a dump (every document of it merged, as ``dynparam load`` does)."""
    values: dict[str, Any] = {}
    for document in _documents(text, source):
        if document is None:
            continue
        if not isinstance(document, dict):
            raise ConfigFileError(f"{source}: a configuration is a mapping of names to values, not "
                                  f"{type(document).__name__}")
        values.update(document)
    return values


def parse_values(text: str) -> dict[str, Any] | None:
    """The values of ``dynparam set NODE "{'name': value, ...}"``; None when the text is not a mapping."""
    try:
        documents = _documents(text, "values")
    except ConfigFileError:
        return None
    return documents[0] if len(documents) == 1 and isinstance(documents[0], dict) else None
