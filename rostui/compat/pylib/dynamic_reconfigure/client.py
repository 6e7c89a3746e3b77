"""``dynamic_reconfigure.client.Client``: read and change a running node's reconfigurable parameters.

The client waits for the server's ``set_parameters`` service, follows its ``parameter_descriptions`` and
``parameter_updates`` topics, and sends changes converted to each parameter's declared type
(:mod:`rostui.tools.reconfigure.values`). Without a timeout it waits a second, says on stderr what it waits
for, then waits for good, as dynamic_reconfigure's client does.

Unlike dynamic_reconfigure's client, an enum's ``edit_method`` (text the server sends) is read as a
Python literal, never evaluated as code.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable
from typing import Any

import rospy
from . import DynamicReconfigureCallbackException, DynamicReconfigureParameterException
from .encoding import Config, decode_config, decode_description, encode_config, extract_params
from .encoding import ConfigDescrMsg, ConfigMsg

from rostui.core.msg import get_service_class
from rostui.tools.reconfigure.live import set_group_states
from rostui.tools.reconfigure.values import ParameterValueError, convert_value, type_of

ReconfigureSrv = get_service_class("dynamic_reconfigure/Reconfigure")

__all__ = ["Client"]

FIRST_WAIT = 1.0
"""Seconds waited quietly before saying on stderr what the client waits for."""


class Client:
    """A client of the reconfigure server *name* (usually the node's name)."""

    def __init__(self, name: str, timeout: float | None = None,
                 config_callback: Callable[[Any], Any] | None = None,
                 description_callback: Callable[[Any], Any] | None = None) -> None:
        self.name = name
        self.config: Config | None = None
        self.param_description: list[dict[str, Any]] | None = None
        self.group_description: Config | None = None
        self._param_types: dict[str, type] | None = None
        self._cv = threading.Condition()
        self._config_callback = config_callback
        self._description_callback = description_callback
        self._set_service = self._get_service_proxy("set_parameters", timeout)
        self._descriptions_sub = self._get_subscriber("parameter_descriptions", ConfigDescrMsg,
                                                      self._descriptions_msg)
        self._updates_sub = self._get_subscriber("parameter_updates", ConfigMsg, self._updates_msg)

    def _wait_for(self, attribute: str, timeout: float | None) -> Any:
        """The attribute once it is set; None at shutdown or when *timeout* (seconds, None or 0 for ever) passes."""
        deadline = None if not timeout else time.monotonic() + timeout
        with self._cv:
            while getattr(self, attribute) is None:
                if rospy.is_shutdown():
                    return None
                left = None if deadline is None else deadline - time.monotonic()
                if left is not None and left <= 0.0:
                    break
                self._cv.wait(left)
        return getattr(self, attribute)

    def get_configuration(self, timeout: float | None = None) -> Config | None:
        """The server's latest configuration (waiting for one; None on timeout or shutdown)."""
        if not timeout and self.get_configuration(timeout=FIRST_WAIT) is None:
            print("Waiting for configuration...", file=sys.stderr)
        return self._wait_for("config", timeout)

    def get_parameter_descriptions(self, timeout: float | None = None) -> list[dict[str, Any]] | None:
        """The server's parameters as dicts (name, type, level, description, edit_method, min, max, default)."""
        return self._wait_for("param_description", timeout)

    def get_group_descriptions(self, timeout: float | None = None) -> Config | None:
        """The server's groups as a tree."""
        return self._wait_for("group_description", timeout)

    def _convert(self, name: str, value: Any) -> Any:
        """*value* as the declared type of parameter *name*."""
        assert self.param_description is not None
        try:
            return convert_value(self.param_description, name, value)
        except ParameterValueError as exc:
            raise DynamicReconfigureParameterException(str(exc)) from exc.__cause__

    def update_configuration(self, changes: dict[str, Any]) -> Config:
        """Send *changes* (name to value; ``groups`` to open or close groups) and return the server's new
        configuration. DynamicReconfigureParameterException for an unknown name or a value of the wrong kind."""
        if self.param_description is None:
            self.get_parameter_descriptions()
        if self.param_description is not None:
            for name, value in list(changes.items()):
                if name != "groups":
                    changes[name] = self._convert(name, value)
        if "groups" in changes:
            changes["groups"] = self.update_groups(changes["groups"])
        try:
            msg = self._set_service(encode_config(changes)).config
        except rospy.ServiceException:
            # raised while handling, as dynamic_reconfigure does: the traceback shows the service's error first
            raise DynamicReconfigureCallbackException("service call failed")  # noqa: B904
        if self.group_description is None:
            self.get_group_descriptions()
        return decode_config(msg, self.group_description)

    def update_groups(self, changes: dict[str, bool]) -> Any:
        """The group tree with the states of the groups named in *changes* set (the tree kept here changes too,
        as dynamic_reconfigure's does)."""
        return set_group_states(self.get_group_descriptions(), changes)

    def close(self) -> None:
        """Stop following the server's topics."""
        self._descriptions_sub.unregister()
        self._updates_sub.unregister()

    def get_config_callback(self) -> Callable[[Any], Any] | None:
        """The function called with each new configuration."""
        return self._config_callback

    def set_config_callback(self, value: Callable[[Any], Any] | None) -> None:
        """Call *value* with each new configuration, and at once with the current one."""
        self._config_callback = value
        if value is not None:
            value(self.config)

    config_callback = property(get_config_callback, set_config_callback)

    def get_description_callback(self) -> Callable[[Any], Any] | None:
        """The function called with each new parameter description."""
        return self._description_callback

    def set_description_callback(self, value: Callable[[Any], Any] | None) -> None:
        """Call *value* with each new parameter description, and at once with the current one."""
        self._description_callback = value
        if value is not None:
            value(self.param_description)

    description_callback = property(get_description_callback, set_description_callback)

    def _get_service_proxy(self, suffix: str, timeout: float | None) -> Any:
        service_name = rospy.resolve_name(self.name + "/" + suffix)
        if not timeout:
            try:
                rospy.wait_for_service(service_name, FIRST_WAIT)
            except rospy.exceptions.ROSException:
                print(f"Waiting for service {service_name}...", file=sys.stderr)
                rospy.wait_for_service(service_name, timeout)
        else:
            rospy.wait_for_service(service_name, timeout)
        return rospy.ServiceProxy(service_name, ReconfigureSrv)

    def _get_subscriber(self, suffix: str, msg_type: Any, callback: Callable[[Any], None]) -> Any:
        return rospy.Subscriber(rospy.resolve_name(self.name + "/" + suffix), msg_type, callback=callback)

    def _updates_msg(self, msg: Any) -> None:
        if self.group_description is None:
            self.get_group_descriptions()
        self.config = decode_config(msg, self.group_description)
        with self._cv:
            self._cv.notify_all()
        if self._config_callback is not None:
            self._config_callback(self.config)

    def _descriptions_msg(self, msg: Any) -> None:
        self.group_description = decode_description(msg)
        self.param_description = extract_params(self.group_description)
        self._param_types = {p["name"]: self._param_type_from_string(p["type"]) for p in self.param_description
                             if p.get("name") is not None and p.get("type") is not None}
        with self._cv:
            self._cv.notify_all()
        if self._description_callback is not None:
            self._description_callback(self.param_description)

    @staticmethod
    def _param_type_from_string(type_str: str) -> type:
        try:
            return type_of(type_str)
        except ParameterValueError as exc:
            raise DynamicReconfigureParameterException(str(exc)) from None
