"""dynamic_reconfigure for unmodified ROS 1 scripts: the client, the server and the ``.cfg`` generator.

``dynamic_reconfigure.client.Client`` changes a running node's parameters through its
``set_parameters`` service and follows its ``parameter_updates``; ``dynamic_reconfigure.server.Server``
offers a node's parameters described by a ``.cfg`` file. A package's ``cfg/<Name>.cfg`` becomes the
module ``<pkg>.cfg.<Name>Config`` when it is imported (rostui runs the file through its own
``parameter_generator_catkin``; no catkin build is needed). ``dynamic_reconfigure.msg`` and ``.srv`` are
rostui's message modules. Both speak dynamic_reconfigure's topics and service, so they work with real
ROS clients, servers and ``dynparam``.
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "DynamicReconfigureCallbackException", "DynamicReconfigureException", "DynamicReconfigureParameterException",
    "find_reconfigure_services", "get_parameter_names",
]

SET_PARAMETERS = "/set_parameters"
"""The suffix of a reconfigure server's service name."""


class DynamicReconfigureException(Exception):
    """The base of dynamic_reconfigure's errors."""


class DynamicReconfigureParameterException(DynamicReconfigureException):
    """A parameter the server does not have, or a value that cannot take the parameter's type."""


class DynamicReconfigureCallbackException(DynamicReconfigureException):
    """A server callback that returned no configuration, or a failed ``set_parameters`` call."""


def find_reconfigure_services() -> list[str]:
    """The names of the reconfigure servers on the master (their ``set_parameters`` services' namespaces), sorted."""
    import rosservice  # type: ignore[import-not-found]  # rostui's, a top-level module beside this one

    return sorted(name[: -len(SET_PARAMETERS)] for name in rosservice.get_service_list()
                  if name.endswith(SET_PARAMETERS))


def get_parameter_names(descr: Any) -> Any:
    """The parameter names of a generated ``<Name>Config`` module (the keys of its ``defaults``)."""
    return descr.defaults.keys()
