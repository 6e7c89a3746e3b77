"""``dynamic_reconfigure.server.Server``: offer a node's parameters, described by a ``.cfg`` module, for live change.

Under its namespace (the node's private one unless given) the server publishes the description
(``parameter_descriptions``, latched), the current values (``parameter_updates``, latched, after every
change) and answers ``set_parameters``. It starts from the ``.cfg`` defaults, takes values already on the
parameter server, clamps them into their ranges, and calls the callback once with level -1 before it
answers anyone, as dynamic_reconfigure's server does; every change is mirrored on the parameter server.
"""

from __future__ import annotations

import copy
import threading
from collections.abc import Callable, Mapping
from types import ModuleType
from typing import Any

import rospy
from . import DynamicReconfigureCallbackException
from .encoding import Config, decode_config, encode_config, encode_description, extract_params, \
    get_tree, initial_config
from .encoding import ConfigDescrMsg, ConfigMsg

from rostui.core.msg import get_service_class

ReconfigureSrv = get_service_class("dynamic_reconfigure/Reconfigure")

__all__ = ["Server"]

ALL_LEVELS = ~0
"""The level of the first callback (every parameter is new)."""


def server_namespace(namespace: str) -> str:
    """The namespace a server's topics and service live in: ``~`` by default; a relative one under ``~``."""
    if not namespace:
        return "~"
    if namespace[0] not in "/~":
        namespace = "~" + namespace
    return (namespace + "/").replace("//", "/")


class Server:
    """A dynamic_reconfigure server for the generated module *type*, calling ``callback(config, level)``."""

    def __init__(self, type: ModuleType, callback: Callable[[Config, int], Any], namespace: str = "") -> None:
        self.mutex = threading.Lock()
        self.ns = server_namespace(namespace)
        self.type = type
        self.callback = callback
        self.description = encode_description(type)
        config = dict(type.defaults)
        self.config: Any = config
        self._copy_from_parameter_server()
        self._clamp(config)
        config["groups"] = get_tree(self.description)
        self.config = initial_config(encode_config(config), type.config_description)
        self.descr_topic = rospy.Publisher(self.ns + "parameter_descriptions", ConfigDescrMsg, latch=True,
                                           queue_size=10)
        self.descr_topic.publish(self.description)
        self.update_topic = rospy.Publisher(self.ns + "parameter_updates", ConfigMsg, latch=True, queue_size=10)
        self._change_config(self.config, ALL_LEVELS)
        self.set_service = rospy.Service(self.ns + "set_parameters", ReconfigureSrv, self._set_callback)

    def _params(self) -> list[dict[str, Any]]:
        return extract_params(self.type.config_description)

    def update_configuration(self, changes: Mapping[str, Any]) -> Any:
        """Apply *changes* (name to value) as a client's request would, and return the new configuration."""
        with self.mutex:
            new_config = copy.deepcopy(self.config)
            new_config.update(changes)
            self._clamp(new_config)
            return self._change_config(new_config, self._calc_level(new_config, self.config))

    def _copy_from_parameter_server(self) -> None:
        for param in self._params():
            try:
                self.config[param["name"]] = rospy.get_param(self.ns + param["name"])
            except KeyError:
                pass

    def _copy_to_parameter_server(self) -> None:
        for param in self._params():
            rospy.set_param(self.ns + param["name"], self.config[param["name"]])

    def _change_config(self, config: Any, level: int) -> Any:
        self.config = self.callback(config, level)
        if self.config is None:
            message = "Reconfigure callback should return a possibly updated configuration."
            rospy.logerr(message)
            raise DynamicReconfigureCallbackException(message)
        self._copy_to_parameter_server()
        self.update_topic.publish(encode_config(self.config))
        return self.config

    def _calc_level(self, new: Mapping[str, Any], old: Mapping[str, Any]) -> int:
        """The OR of the levels of the parameters whose values differ."""
        level = 0
        for param in self._params():
            if new[param["name"]] != old[param["name"]]:
                level |= param["level"]
        return level

    def _clamp(self, config: dict[str, Any]) -> None:
        """Bring each value into its parameter's range (strings have none)."""
        for param in self._params():
            name = param["name"]
            highest, lowest, value = self.type.max[name], self.type.min[name], config[name]
            if value > highest and highest != "":
                config[name] = highest
            elif value < lowest and lowest != "":
                config[name] = lowest

    def _set_callback(self, req: Any) -> Any:
        return encode_config(self.update_configuration(decode_config(req.config, self.type.config_description)))
