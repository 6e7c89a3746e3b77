"""``rostui launch check FILE``: everything roslaunch would only warn about, or fail on later, as errors.

One ``FILE:LINE: message`` line per problem: unknown elements and attributes,
nodes naming an undeclared ``<machine>``, machines whose address does not
resolve, and executables missing for the nodes that would run on this host.
An error that stops loading (bad XML, a missing include, ...) raises
:class:`~rostui.launch.errors.LaunchError` as for every other launch mode.
"""

from __future__ import annotations

from dataclasses import replace

from rostui.launch.errors import LaunchError
from rostui.launch.files import LaunchRequest
from rostui.launch.inspect import load_config, node_argv
from rostui.launch.machines import assign_machines, unknown_machine


def check_request(request: LaunchRequest) -> list[str]:
    """The problems of the files of ``request``, one line each (empty when there are none)."""
    config, loader = load_config(replace(request, strict=False))
    lines = [str(problem) for problem in config.problems]
    missing = unknown_machine(config)
    if missing is not None:
        return [*lines, str(missing)]
    try:
        assign_machines(config)
    except LaunchError as exc:
        return [*lines, str(exc)]
    for node in config.all_nodes():
        if node.remote:
            continue
        try:
            node_argv(node, loader.anons)
        except LaunchError as exc:
            lines.append(str(exc))
    return lines
