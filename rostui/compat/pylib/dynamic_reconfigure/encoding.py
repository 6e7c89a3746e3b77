"""``dynamic_reconfigure.encoding``: configurations as dicts and as dynamic_reconfigure's messages, both ways.

The conversions are rostui's :mod:`rostui.tools.reconfigure.encoding`, which rostui's reconfigure app and
``rostui dynparam`` use too.
"""

from __future__ import annotations

from rostui.tools.reconfigure.encoding import (
    BoolParameter, Config, ConfigDescrMsg, ConfigMsg, DoubleParameter, GroupMsg, GroupState, IntParameter,
    ParamDescription, StrParameter, decode_config, decode_description, encode_config, encode_description,
    encode_groups, extract_params, get_parents, get_tree, group_dict, initial_config,
)

__all__ = [
    "BoolParameter", "Config", "ConfigDescrMsg", "ConfigMsg", "DoubleParameter", "GroupMsg", "GroupState",
    "IntParameter", "ParamDescription", "StrParameter", "decode_config", "decode_description", "encode_config",
    "encode_description", "encode_groups", "extract_params", "get_parents", "get_tree", "group_dict",
    "initial_config",
]
