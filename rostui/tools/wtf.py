"""`rostui wtf`: roswtf's useful checks, each finding one line with a hint.

Checks, in order: the environment (ROS_MASTER_URI well formed and its host
resolvable, ROS_IP / ROS_HOSTNAME resolvable and local), the log directory
size, then, when the master answers, the graph: registered nodes that do not
answer ``getPid`` (dead), topics whose publishers and subscribers disagree on
the type, and subscribed topics that nobody publishes.
"""

from __future__ import annotations

import ipaddress
import os
import socket
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from typing import Any, Callable, Literal, Mapping
from urllib.parse import urlparse

from rostui.core.log.files import DISK_WARNING_BYTES, dir_size, log_root
from rostui.core.network import master_uri_from_env
from rostui.core.xmlrpc import XmlRpcError, call_sync, ros_result
from rostui.core.xmlrpc.errors import RosApiError

__all__ = ["Finding", "Report", "run_checks", "format_finding", "summary_line", "CALLER_ID"]

CALLER_ID = "/rostui_wtf"
"""The caller id rostui wtf uses towards the master and nodes."""

Level = Literal["ERROR", "WARNING"]

Caller = Callable[..., Any]
"""``call(uri, method, *args, timeout=...)``: an XML-RPC call returning the raw reply."""


@dataclass(frozen=True)
class Finding:
    """One problem: its level, the check that found it, what is wrong and what to do."""

    level: Level
    check: str
    message: str
    hint: str


@dataclass
class Report:
    """Every finding of a run, and whether the graph could be checked at all."""

    findings: list[Finding]
    master_uri: str
    online: bool

    @property
    def errors(self) -> list[Finding]:
        """The ERROR findings."""
        return [f for f in self.findings if f.level == "ERROR"]

    @property
    def warnings(self) -> list[Finding]:
        """The WARNING findings."""
        return [f for f in self.findings if f.level == "WARNING"]

    def as_json(self) -> dict[str, Any]:
        """A JSON-ready view (``--json``)."""
        return {
            "master_uri": self.master_uri,
            "online": self.online,
            "errors": len(self.errors),
            "warnings": len(self.warnings),
            "findings": [asdict(f) for f in self.findings],
        }


def format_finding(finding: Finding, color: bool = False) -> str:
    """One line: ``ERROR what is wrong (hint: what to do)``, the level colored like roswtf on a TTY."""
    level: str = finding.level
    if color:
        level = "\x1b[31m\x1b[1mERROR\x1b[0m" if level == "ERROR" else "\x1b[1mWARNING\x1b[0m"
    return f"{level} {finding.message} (hint: {finding.hint})"


def summary_line(report: Report) -> str:
    """``No errors or warnings`` or ``Found N error(s) and M warning(s).``"""
    if not report.findings:
        return "No errors or warnings"
    return f"Found {len(report.errors)} error(s) and {len(report.warnings)} warning(s)."


def _reason(exc: BaseException) -> str:
    """The short cause of a failed call (without repeating the URI)."""
    return getattr(exc, "reason", None) or str(exc) or type(exc).__name__


# -- environment ---------------------------------------------------------------

def _is_local_address(address: str) -> bool:
    """True when this machine can bind *address* (so it is one of its own)."""
    family = socket.AF_INET6 if ":" in address else socket.AF_INET
    try:
        with socket.socket(family, socket.SOCK_STREAM) as s:
            s.bind((address, 0))
        return True
    except OSError:
        return False


def _resolve(host: str) -> list[str]:
    """The addresses of ``host``; a localhost name this machine cannot resolve (a root with no /etc/hosts) is
    the loopback address it always means, as for every other rostui command."""
    from rostui.core.localhost import connect_host

    return sorted({str(info[4][0]) for info in socket.getaddrinfo(connect_host(host), None,
                                                                  proto=socket.IPPROTO_TCP)})


def _check_environment(env: Mapping[str, str], uri: str) -> list[Finding]:
    out: list[Finding] = []
    parsed = urlparse(uri)
    try:
        port = parsed.port
    except ValueError:
        port = None
    if parsed.scheme != "http" or not parsed.hostname or port is None:
        out.append(Finding("ERROR", "environment", f"ROS_MASTER_URI [{uri}] is not of the form http://host:port/",
                           "set it to e.g. http://localhost:11311"))
    else:
        try:
            _resolve(parsed.hostname)
        except OSError:
            out.append(Finding("ERROR", "environment",
                               f"cannot resolve the host [{parsed.hostname}] of ROS_MASTER_URI [{uri}]",
                               "use an IP address or add the name to /etc/hosts or DNS"))
    ip = env.get("ROS_IP") or ""
    hostname = env.get("ROS_HOSTNAME") or ""
    if ip:
        try:
            ipaddress.ip_address(ip)
        except ValueError:
            out.append(Finding("ERROR", "environment", f"ROS_IP [{ip}] is not an IP address",
                               "set ROS_IP to an address of this machine, or use ROS_HOSTNAME for names"))
        else:
            if not _is_local_address(ip):
                out.append(Finding("ERROR", "environment", f"ROS_IP [{ip}] is not an address of this machine",
                                   "other nodes would connect to the wrong host; set it to one of this machine's addresses"))
    if hostname:
        try:
            addresses = _resolve(hostname)
        except OSError:
            out.append(Finding("ERROR", "environment", f"ROS_HOSTNAME [{hostname}] does not resolve",
                               "add it to /etc/hosts or DNS on every machine, or use ROS_IP"))
        else:
            if not any(_is_local_address(a) for a in addresses):
                out.append(Finding("ERROR", "environment",
                                   f"ROS_HOSTNAME [{hostname}] resolves to {', '.join(addresses)}, not to this machine",
                                   "set it to a name of this machine"))
    if ip and hostname:
        out.append(Finding("WARNING", "environment", f"both ROS_HOSTNAME [{hostname}] and ROS_IP [{ip}] are set",
                           "ROS_HOSTNAME wins; unset one of them"))
    return out


def _check_log_dir(env: Mapping[str, str], limit: int) -> list[Finding]:
    root = log_root(env)
    size = dir_size(root)
    if size <= limit:
        return []
    from rostui.core.log.clean import human_size

    return [Finding("WARNING", "log", f"log directory [{root}] uses {human_size(size)}, over {human_size(limit)}",
                    "free space with 'rostui clean purge'")]


# -- graph ----------------------------------------------------------------------

@dataclass
class _NodeState:
    name: str
    uri: str | None
    alive: bool
    reason: str
    publications: dict[str, str]
    subscriptions: dict[str, str]


def _probe_node(call: Caller, master: str, name: str, timeout: float) -> _NodeState:
    """Look up *name*, then ask it for its pid and its topics (each with *timeout*)."""
    state = _NodeState(name, None, False, "", {}, {})
    try:
        state.uri = ros_result(call(master, "lookupNode", CALLER_ID, name, timeout=timeout))
    except (XmlRpcError, RosApiError, OSError) as exc:
        state.reason = f"the master has no URI for it ({exc})"
        return state
    try:
        ros_result(call(state.uri, "getPid", CALLER_ID, timeout=timeout))
    except (XmlRpcError, RosApiError, OSError) as exc:
        state.reason = _reason(exc)
        return state
    state.alive = True
    for method, target in (("getPublications", state.publications), ("getSubscriptions", state.subscriptions)):
        try:
            for topic, type_name in ros_result(call(state.uri, method, CALLER_ID, timeout=timeout)):
                target[topic] = type_name
        except (XmlRpcError, RosApiError, OSError, TypeError, ValueError):
            pass
    return state


def _check_graph(call: Caller, master: str, timeout: float) -> list[Finding]:
    pubs, subs, srvs = ros_result(call(master, "getSystemState", CALLER_ID, timeout=timeout))
    nodes = sorted({n for group in (pubs, subs, srvs) for _, names in group for n in names})
    with ThreadPoolExecutor(max_workers=min(16, max(1, len(nodes)))) as pool:
        states = {s.name: s for s in pool.map(lambda n: _probe_node(call, master, n, timeout), nodes)}

    out: list[Finding] = []
    for name in nodes:
        s = states[name]
        if not s.alive:
            where = f" at {s.uri}" if s.uri else ""
            out.append(Finding("ERROR", "dead_node", f"node {name} is registered but does not answer{where}: {s.reason}",
                               "it probably died; 'rostui node cleanup' unregisters it"))

    publishers = {t: sorted(ns) for t, ns in pubs}
    subscribers = {t: sorted(ns) for t, ns in subs}
    for topic in sorted(set(publishers) | set(subscribers)):
        uses: dict[str, list[str]] = {}
        for role, group, attr in (("publishes", publishers, "publications"), ("subscribes", subscribers, "subscriptions")):
            for n in group.get(topic, []):
                state = states.get(n)
                t = getattr(state, attr).get(topic) if state is not None and state.alive else None
                if t and t != "*":
                    uses.setdefault(t, []).append(f"{n} {role}")
        if len(uses) > 1:
            parts = "; ".join(f"{t} ({', '.join(who)})" for t, who in sorted(uses.items()))
            out.append(Finding("ERROR", "type_mismatch", f"topic {topic} is used with different types: {parts}",
                               "nodes with different types never connect; make them use one message type"))
    for topic in sorted(subscribers):
        if not publishers.get(topic):
            who = ", ".join(subscribers[topic])
            out.append(Finding("WARNING", "unconnected", f"topic {topic} is subscribed by {who} but nobody publishes it",
                               "check the topic name and remappings ('rostui topic list'), or start the publisher"))
    return out


def run_checks(env: Mapping[str, str] | None = None, *, timeout: float = 1.0,
               log_limit: int = DISK_WARNING_BYTES, call: Caller = call_sync) -> Report:
    """Run every check and return the findings (errors first within each stage)."""
    env = os.environ if env is None else env
    uri = master_uri_from_env(env.get("ROS_MASTER_URI") or None)
    findings = _check_environment(env, uri)
    findings += _check_log_dir(env, log_limit)
    online = False
    try:
        call(uri, "getPid", CALLER_ID, timeout=max(timeout, 2.0))
        online = True
    except (XmlRpcError, OSError) as exc:
        findings.append(Finding("ERROR", "master", f"the master at ROS_MASTER_URI [{uri}] does not answer: {_reason(exc)}",
                                "start one with 'rostui core', or point ROS_MASTER_URI at the running master"))
    if online:
        try:
            findings += _check_graph(call, uri, timeout)
        except (XmlRpcError, RosApiError, OSError, TypeError, ValueError) as exc:
            findings.append(Finding("ERROR", "master", f"the master at [{uri}] gave no usable system state: {exc}",
                                    "check that ROS_MASTER_URI points at a ROS master"))
    order = {"ERROR": 0, "WARNING": 1}
    findings.sort(key=lambda f: order[f.level])
    return Report(findings, uri, online)
