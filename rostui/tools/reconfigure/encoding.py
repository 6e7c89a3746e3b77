"""Configurations as dicts and as dynamic_reconfigure's messages, both ways, as dynamic_reconfigure.encoding does
(the module scripts import as ``dynamic_reconfigure.encoding`` re-exports this one).

A configuration is a :class:`Config` (a dict whose keys read as attributes too) of parameter values,
plus, on the server side, a ``groups`` tree of the ``.cfg`` file's groups with their open/closed
state. On the wire a value goes into the message's list for its Python type (``bool`` before ``int``),
and the groups travel as a flat list of ``GroupState``. Trees read from a peer are built without
following a group that is its own ancestor, so a malformed description cannot recurse forever.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable, Mapping
from typing import Any

from rostui.core.msg import get_message_class

__all__ = [
    "BoolParameter", "ConfigDescrMsg", "ConfigMsg", "DoubleParameter", "GroupMsg", "GroupState", "IntParameter",
    "ParamDescription", "ROOT_ID", "StrParameter",
    "Config", "decode_config", "decode_description", "encode_config", "encode_description", "encode_groups",
    "extract_params", "get_parents", "get_tree", "group_dict", "initial_config",
]

BoolParameter = get_message_class("dynamic_reconfigure/BoolParameter")
DoubleParameter = get_message_class("dynamic_reconfigure/DoubleParameter")
GroupState = get_message_class("dynamic_reconfigure/GroupState")
IntParameter = get_message_class("dynamic_reconfigure/IntParameter")
ParamDescription = get_message_class("dynamic_reconfigure/ParamDescription")
StrParameter = get_message_class("dynamic_reconfigure/StrParameter")
ConfigMsg = get_message_class("dynamic_reconfigure/Config")
ConfigDescrMsg = get_message_class("dynamic_reconfigure/ConfigDescription")
GroupMsg = get_message_class("dynamic_reconfigure/Group")

ROOT_ID = 0
"""The id of a description's top group ("Default")."""


class Config(dict[str, Any]):
    """A configuration: a dict whose keys are also attributes (``config.speed`` is ``config['speed']``)."""

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name: str, value: Any) -> None:
        self[name] = value

    def __getstate__(self) -> list[tuple[str, Any]]:
        return list(self.__dict__.items())

    def __setstate__(self, items: Iterable[tuple[str, Any]]) -> None:
        self.__dict__.update(items)

    def copy(self) -> Config:
        """A shallow copy that is still a Config."""
        return Config(self)

    def __deepcopy__(self, memo: dict[int, Any]) -> Config:
        return type(self)({copy.deepcopy(k, memo): copy.deepcopy(v, memo) for k, v in self.items()})


# Configurations are written into files as dynamic_reconfigure's class (``dynparam dump`` pickles one into YAML
# as ``!!python/object/new:dynamic_reconfigure.encoding.Config``), and scripts read them back by that name.
Config.__module__ = "dynamic_reconfigure.encoding"


def encode_description(descr: Any) -> Any:
    """The ConfigDescription message of a generated ``<Name>Config`` module (its groups, bounds and defaults)."""
    msg: Any = ConfigDescrMsg()
    msg.max = encode_config(descr.max)
    msg.min = encode_config(descr.min)
    msg.dflt = encode_config(descr.defaults)
    msg.groups = encode_groups(None, descr.config_description)
    return msg


def encode_groups(parent: Any, group: Mapping[str, Any]) -> list[Any]:
    """*group* and its descendants (a generated module's description tree) as Group messages, parents first."""
    msg: Any = GroupMsg(name=group["name"], id=group["id"], parent=group["parent"], type=group["type"])
    msg.parameters = [ParamDescription(p["name"], p["type"], p["level"], p["description"], p["edit_method"])
                      for p in group["parameters"]]
    found = [msg]
    for child in group["groups"]:
        found.extend(encode_groups(msg, child))
    return found


def _group_state(group: Mapping[str, Any]) -> Any:
    return GroupState(group["name"], group["state"], group["id"], group["parent"])


def _descendant_states(group: Mapping[str, Any]) -> list[Any]:
    """GroupStates below *group*: each child after its own descendants."""
    states = []
    for child in group["groups"].values():
        states.extend(_descendant_states(child))
        states.append(_group_state(child))
    return states


def encode_config(config: Mapping[str, Any], flat: bool = True) -> Any:
    """The Config message of *config*: each value in the list for its exact Python type, a groups tree flattened.

    Values of other types are left out, as dynamic_reconfigure does. With *flat* False a ``groups``
    value is a list of group dicts sent as they are.
    """
    msg: Any = ConfigMsg()
    lists = {int: msg.ints, bool: msg.bools, str: msg.strs, float: msg.doubles}
    kinds = {int: IntParameter, bool: BoolParameter, str: StrParameter, float: DoubleParameter}
    for key, value in config.items():
        kind = type(value)
        if kind in lists:
            lists[kind].append(kinds[kind](key, value))
        elif kind is dict or isinstance(value, Config):
            if flat:
                msg.groups.append(_group_state(value))
                msg.groups.extend(_descendant_states(value))
            else:
                msg.groups = [_group_state(g) for g in value]
    return msg


def group_dict(group: Any) -> Config:
    """A tree node for a Group or GroupState message: its id, parent, name, type and state, no children yet."""
    return Config({
        "id": group.id,
        "parent": group.parent,
        "name": group.name,
        "type": getattr(group, "type", ""),
        "state": getattr(group, "state", True),
        "groups": Config({}),
        "parameters": Config({}),
    })


def _root(groups: Iterable[Any]) -> Any:
    """The last group whose id is the root's, or None."""
    found = None
    for group in groups:
        if group.id == ROOT_ID:
            found = group
    return found


def _children(groups: list[Any], parent_id: int, seen: frozenset[int], make: Any) -> Config:
    """The subtree under *parent_id*, each child made by ``make(msg, seen)``; a group already on the path is skipped."""
    children = Config({})
    for group in groups:
        if group.id != ROOT_ID and group.parent == parent_id and group.id not in seen:
            node = make(group, seen | {group.id})
            children[node["name"]] = node
    return children


def _params_of(group: Any, mins: Mapping[str, Any], maxes: Mapping[str, Any],
               defaults: Mapping[str, Any]) -> list[dict[str, Any]]:
    return [{
        "name": p.name, "min": mins.get(p.name), "max": maxes.get(p.name), "default": defaults.get(p.name),
        "type": p.type, "level": p.level, "description": p.description, "edit_method": p.edit_method,
    } for p in group.parameters]


def decode_description(msg: Any) -> Config:
    """A ConfigDescription message as a tree: each group with its parameters (bounds, default, type, level...)."""
    mins, maxes, defaults = decode_config(msg.min), decode_config(msg.max), decode_config(msg.dflt)
    groups = list(msg.groups)

    def make(group: Any, seen: frozenset[int]) -> Config:
        node = group_dict(group)
        node["parameters"] = _params_of(group, mins, maxes, defaults)
        node["groups"] = _children(groups, group.id, seen, make)
        return node

    root = _root(groups)
    if root is None:
        return Config({"groups": Config({}), "parameters": []})
    return make(root, frozenset({ROOT_ID}))


def get_tree(m: Any, group: Any = None) -> Any:
    """The groups of a Config or ConfigDescription message as a tree: the root's node, or a group's children."""
    groups = list(m.groups)

    def make(g: Any, seen: frozenset[int]) -> Config:
        node = group_dict(g)
        node["groups"] = _children(groups, g.id, seen, make)
        return node

    if group is None:
        group = _root(groups)
        if group is None:
            return Config({})
    if group.id == ROOT_ID:
        return make(group, frozenset({ROOT_ID}))
    return _children(groups, group.id, frozenset({group.id}), make)


def _first_chain_state(node: Config, description: Mapping[str, Any]) -> None:
    """Give *node* the state its group has in a generated description, looking as dynamic_reconfigure does:
    at each level only the first child is descended into, so a group off that chain keeps its state."""
    level = description
    while level["groups"]:
        first = level["groups"][0]
        if first["id"] == node["id"]:
            node["state"] = first["state"]
            return
        level = first


def _fill_parameters(node: Config, values: Mapping[str, Any], description: Mapping[str, Any],
                     into_parameters: bool) -> None:
    """Copy the values of *description*'s parameters into *node* (or its ``parameters``), then into its children."""
    target = node["parameters"] if into_parameters else node
    for param in description["parameters"]:
        if into_parameters or param["name"] in values:
            target[param["name"]] = values[param["name"]]
    described = description["groups"]
    described_groups = described.values() if isinstance(described, Mapping) else described
    for child in node["groups"].values():
        for match in described_groups:
            if match["name"] == child["name"]:
                _fill_parameters(child, values, match, into_parameters)


def _values(msg: Any) -> Config:
    return Config([(p.name, p.value) for p in [*msg.bools, *msg.ints, *msg.strs, *msg.doubles]])


def initial_config(msg: Any, description: Mapping[str, Any] | None = None) -> Config:
    """A server's first configuration from a Config message and its generated description: the values, and a
    groups tree whose nodes hold their parameters and the description's open/closed states."""
    config = _values(msg)
    if msg.groups and description is not None:
        groups = list(msg.groups)

        def make(g: Any, seen: frozenset[int]) -> Config:
            node = group_dict(g)
            if g.id != ROOT_ID:
                _first_chain_state(node, description)
            node["groups"] = _children(groups, g.id, seen, make)
            return node

        root = _root(groups)
        if root is not None:
            config["groups"] = make(root, frozenset({ROOT_ID}))
            _fill_parameters(config["groups"], config, description, into_parameters=True)
    return config


def decode_config(msg: Any, description: Mapping[str, Any] | None = None) -> Config:
    """A Config message as a :class:`Config`; with a *description*, its groups as a tree holding their values."""
    config = _values(msg)
    if msg.groups and description is not None:
        config["groups"] = get_tree(msg)
        if config["groups"]:
            _fill_parameters(config["groups"], config, description, into_parameters=False)
    return config


def extract_params(group: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Every parameter of a description tree, the group's own first, then each subgroup's, depth first."""
    params = list(group["parameters"])
    children = group["groups"]
    for child in children.values() if isinstance(children, Mapping) else children:
        params.extend(extract_params(child))
    return params


def get_parents(group: Mapping[str, Any], descriptions: Mapping[str, Any]) -> list[Any]:
    """The ancestors of *group* in ``descriptions['group']``, outermost first."""
    parents: list[Any] = []
    for candidate in descriptions["group"]:
        if candidate["id"] == group["parent"]:
            parents.extend(get_parents(candidate, descriptions))
            parents.append(candidate)
    return parents
