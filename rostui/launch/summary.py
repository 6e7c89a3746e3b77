"""The SUMMARY block roslaunch prints before it starts anything: parameters, machines and nodes.

Its layout is roslaunch's (``ROSLaunchConfig.summary``): the parameters sorted, each value cut to 20
characters (``...``) or shown as ``<...>`` when it holds a character outside printable ASCII; the machines
only when some node runs on another host; the nodes grouped by namespace, sorted, as ``name (pkg/type)``.
Like roslaunch it lists ``/rosdistro`` and ``/rosversion`` among the parameters (a master rostui starts
sets them).
"""

from __future__ import annotations

from typing import Any

from rostui.core.master.master import DEFAULT_ROSDISTRO, DEFAULT_ROSVERSION
from rostui.launch.model import LaunchConfig, NodeSpec

__all__ = ["launch_summary", "shown_value"]

#: Longest value shown whole.
VALUE_WIDTH = 20


def shown_value(value: Any) -> str:
    """A parameter's value as the summary shows it: ``str(value)``, cut to :data:`VALUE_WIDTH` with ``...``;
    ``<...>`` when a character outside printable ASCII remains (trailing whitespace is dropped first)."""
    text = str(value)
    if len(text) > VALUE_WIDTH:
        text = text[:VALUE_WIDTH - 3] + "..."
    if all(32 <= ord(c) <= 126 for c in text):
        return text
    text = text.rstrip()
    return text if all(32 <= ord(c) <= 126 for c in text) else "<...>"


def _node_label(node: NodeSpec) -> str:
    return f"{node.name} ({node.package}/{node.type})" if node.name else f"{node.package}/{node.type}"


def _namespace(node: NodeSpec) -> str:
    ns = node.namespace or "/"
    return ns if ns.endswith("/") else ns + "/"


def launch_summary(config: LaunchConfig) -> str:
    """roslaunch's SUMMARY text for ``config`` (starting with an empty line, as roslaunch prints it)."""
    remote = bool(config.remote_nodes())
    lines = ["", "SUMMARY", "========"]
    if config.clear_params:
        lines += ["", "CLEAR PARAMETERS", *sorted(f" * {key}" for key in config.clear_params)]
    params = {"/rosdistro": DEFAULT_ROSDISTRO.strip(), "/rosversion": DEFAULT_ROSVERSION.strip(), **config.params}
    lines += ["", "PARAMETERS", *sorted(f" * {key}: {shown_value(value)}" for key, value in params.items())]
    if remote:
        lines += ["", "MACHINES", *sorted(f" * {name}" for name in config.machines if name)]
    lines += ["", "NODES"]
    nodes = config.nodes if remote else [n for n in config.nodes if not n.remote]
    by_namespace: dict[str, list[str]] = {}
    for node in nodes:
        by_namespace.setdefault(_namespace(node), []).append(_node_label(node))
    for namespace in sorted(by_namespace):
        lines += [f"  {namespace}", *sorted(f"    {label}" for label in by_namespace[namespace])]
    return "\n".join(lines) + "\n"
