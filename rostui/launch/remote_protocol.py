"""roslaunch's remote protocol: what a parent launcher and its children on other machines say to each other.

The parent (the ``rostui launch`` or ``roslaunch`` the user started) serves
XML-RPC at the URI it also stores under ``/roslaunch/uris/``.  For each remote
machine it logs in over SSH and runs, through the machine's env-loader,
``roslaunch -c NAME -u PARENT_URI --run_id RUN_ID --sigint-timeout S
--sigterm-timeout S`` with ``ROS_MASTER_URI`` set (rostui's parent runs
``rostui launch --child ...`` instead when ``rostui`` is on that PATH).  The
child serves XML-RPC of its own and then:

- child -> parent ``register(NAME, CHILD_URI)``; the parent gives up on a
  machine that has not registered within its ``timeout``;
- parent -> child ``launch(XML)``: a ``<launch>`` of that machine's nodes (no
  params, no ``machine``), answered ``[1, msg, [started, failed]]``;
- child -> parent ``log(NAME, LEVEL, MESSAGE)`` for the child's own lines
  (``process[LABEL]: started with pid [PID]``...) and
  ``process_died(LABEL, EXIT_CODE)`` for each node that ends (the child
  respawns ``respawn`` nodes itself);
- parent -> child ``shutdown()``: the child stops its nodes (SIGINT, then
  SIGTERM, then SIGKILL) and answers when they are gone, then exits.

Neither side takes a caller id.  Output of a rostui child's nodes comes back
on the SSH connection, one line each, as ``[LABEL]<TAB>TEXT`` (a tab, so
roslaunch's own ``[LABEL] message`` lines are not taken for them): stdout
lines on stdout, stderr lines on stderr.
"""

from __future__ import annotations

import re
import shlex
from typing import Any

from lxml import etree

from rostui.launch.model import NodeSpec
from rostui.launch.substitution import SubstitutionContext, resolve

#: rosgraph_msgs/Log levels the ``log`` call carries.
LOG_INFO = 2
LOG_ERROR = 8

_STARTED = re.compile(r"process\[([^\]]+)\]: (?:re)?started(?: on request)? with pid \[(\d+)\]")

#: The remote shell's choice between rostui and roslaunch; $1..$5: name, parent URI, run id, timeouts.
_CHOOSE = ('if command -v rostui >/dev/null 2>&1; then exec rostui launch --child "$1" -u "$2" --run_id "$3" '
           '--sigint-timeout "$4" --sigterm-timeout "$5"; else exec roslaunch -c "$1" -u "$2" --run_id "$3" '
           '--sigint-timeout "$4" --sigterm-timeout "$5"; fi')


def child_command(name: str, parent_uri: str, run_id: str, master_uri: str, sigint_timeout: float,
                  sigterm_timeout: float, env_loader: str | None = None) -> list[str]:
    """The command run on a remote machine: its env-loader, then rostui's child if installed, else roslaunch's."""
    loader = shlex.split(env_loader) if env_loader else []
    return [*loader, "env", f"ROS_MASTER_URI={master_uri}", "sh", "-c", _CHOOSE, "sh", name, parent_uri, run_id,
            f"{sigint_timeout:g}", f"{sigterm_timeout:g}"]


def started_pid(message: str) -> tuple[str, int] | None:
    """``(label, pid)`` when a child's log line says a node process started, else None."""
    match = _STARTED.search(message)
    return (match.group(1), int(match.group(2))) if match else None


def label_matches(label: str, node: NodeSpec) -> bool:
    """True when a child's process label (``ns-name-N``, roslaunch: ``ns/name-N``) names ``node``."""
    base, _, counter = label.rpartition("-")
    if not counter.isdigit():
        return False
    return base.replace("/", "-") == node.resolved_name.lstrip("/").replace("/", "-")


def nodes_xml(nodes: list[NodeSpec], anons: dict[str, str], screen: bool = False) -> str:
    """The ``<launch>`` document a child gets for its machine's nodes (anon names already resolved).

    ``screen`` (``--screen``) sends every node's output to the screen.
    """
    root = etree.Element("launch")
    for node in nodes:
        ctx = SubstitutionContext(anons=anons, filename=node.filename)
        attrs: dict[str, Any] = {
            "pkg": node.package, "type": node.type, "name": resolve(node.name, ctx) or node.name,
            "ns": node.namespace, "args": resolve(node.args, ctx) or "",
            "respawn": _flag(node.respawn), "respawn_delay": f"{node.respawn_delay:g}",
            "required": _flag(node.required),
        }
        output = "screen" if screen else node.output
        for key, value in (("output", output), ("cwd", node.cwd), ("launch-prefix", node.launch_prefix)):
            if value:
                attrs[key] = value
        element = etree.SubElement(root, "node", {k: str(v) for k, v in attrs.items()})
        for src, dst in node.remaps:
            etree.SubElement(element, "remap", {"from": src, "to": dst})
        for env_name, env_value in node.env:
            etree.SubElement(element, "env", {"name": env_name, "value": env_value})
    body = etree.tostring(root, pretty_print=True, encoding="unicode")
    return '<?xml version="1.0" encoding="utf-8"?>\n' + body


def _flag(value: bool) -> str:
    return "true" if value else "false"


def format_output_line(label: str, text: str) -> str:
    """A node's output line as a rostui child sends it to its parent."""
    return f"[{label}]\t{text}"


def output_line(line: str) -> tuple[str, str] | None:
    """``(label, text)`` for a ``[LABEL]<TAB>TEXT`` line of a child's output, else None."""
    if not line.startswith("["):
        return None
    label, sep, text = line[1:].partition("]\t")
    if not sep or not label:
        return None
    return label, text
