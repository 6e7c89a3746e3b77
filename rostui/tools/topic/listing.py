"""``rostui topic list``, ``info``, ``type`` and ``find``: views of the master's registrations, printed as rostopic prints them."""

from __future__ import annotations

from typing import Any, Sequence

from rostui.tools.topic.common import MasterCall, TopicToolError


def topic_types(call: MasterCall) -> list[tuple[str, str]]:
    """``[(topic, type), ...]`` from getTopicTypes."""
    return [(t, ty) for t, ty in call("getTopicTypes")]


def system_state(call: MasterCall) -> tuple[list, list, list]:
    """``(publishers, subscribers, services)`` from getSystemState."""
    pubs, subs, srvs = call("getSystemState")
    return pubs, subs, srvs


def topic_list(call: MasterCall) -> tuple[list[tuple[str, str, list[str]]], list[tuple[str, str, list[str]]]]:
    """Published and subscribed topics as ``(topic, type, nodes)``, in the master's order."""
    pubs, subs, _ = system_state(call)
    types = dict(reversed(topic_types(call)))

    def typed(entries: list) -> list[tuple[str, str, list[str]]]:
        return [(t, types.get(t, "unknown type"), list(nodes)) for t, nodes in entries]

    return typed(pubs), typed(subs)


def _in_namespace(topic: str, ns: str | None) -> bool:
    if not ns:
        return True
    prefix = ns if ns.endswith("/") else ns + "/"
    return topic == ns or topic.startswith(prefix)


def _verbose_section(title: str, rows: Sequence[tuple[str, str, list[str]]], noun: str) -> list[str]:
    """One part of ``rostopic list -v``: a blank line, the title, and `` * topic [type] N nouns`` per topic."""
    lines = ["", title]
    for topic, type_name, nodes in rows:
        count = len(nodes)
        lines.append(f" * {topic} [{type_name}] {count} {noun}s" if count > 1 else f" * {topic} [{type_name}] 1 {noun}")
    return lines


def format_list(pubs: Sequence[tuple[str, str, list[str]]], subs: Sequence[tuple[str, str, list[str]]], *,
                verbose: bool = False, publishers_only: bool = False, subscribers_only: bool = False,
                namespace: str | None = None) -> str:
    """The text ``rostopic list [-v] [-p|-s] [/ns]`` prints (with its final newline)."""
    pubs = [p for p in pubs if _in_namespace(p[0], namespace)]
    subs = [s for s in subs if _in_namespace(s[0], namespace)]
    lines: list[str] = []
    if verbose:
        if not subscribers_only:
            lines += _verbose_section("Published topics:", pubs, "publisher")
        if not publishers_only:
            lines += _verbose_section("Subscribed topics:", subs, "subscriber")
        lines.append("")
        return "\n".join(lines) + "\n"
    if publishers_only:
        topics = [t for t, _, _ in pubs]
    elif subscribers_only:
        topics = [t for t, _, _ in subs]
    else:
        topics = list({t for t, _, _ in pubs} | {t for t, _, _ in subs})
    topics.sort()
    return "\n".join(topics) + "\n"


def list_json(pubs: Sequence[tuple[str, str, list[str]]], subs: Sequence[tuple[str, str, list[str]]], *,
              namespace: str | None = None) -> list[dict[str, Any]]:
    """Every topic with its type, publishers and subscribers (``--json``)."""
    out: dict[str, dict[str, Any]] = {}
    for t, ty, nodes in pubs:
        if _in_namespace(t, namespace):
            out.setdefault(t, {"topic": t, "type": ty, "publishers": [], "subscribers": []})["publishers"] += nodes
    for t, ty, nodes in subs:
        if _in_namespace(t, namespace):
            out.setdefault(t, {"topic": t, "type": ty, "publishers": [], "subscribers": []})["subscribers"] += nodes
    return [out[t] for t in sorted(out)]


def topic_info(call: MasterCall, topic: str) -> dict[str, Any]:
    """Type, publishers and subscribers (with their XML-RPC URIs) of one topic."""
    pubs, subs = topic_list(call)
    pubs = [p for p in pubs if p[0] == topic]
    subs = [s for s in subs if s[0] == topic]
    if not pubs and not subs:
        raise TopicToolError(f"Unknown topic {topic}")
    types = dict(reversed(topic_types(call)))
    cache: dict[str, str] = {}

    def api(node: str) -> str:
        if node not in cache:
            from rostui.core.xmlrpc import RosApiError

            try:
                cache[node] = call("lookupNode", node)
            except RosApiError:
                cache[node] = f"unknown address {node}"
        return cache[node]

    return {
        "topic": topic,
        "type": types.get(topic, "unknown type"),
        "publishers": [{"node": n, "uri": api(n)} for _, _, nodes in pubs for n in nodes],
        "subscribers": [{"node": n, "uri": api(n)} for _, _, nodes in subs for n in nodes],
    }


def format_info(info: dict[str, Any]) -> str:
    """The text ``rostopic info`` prints (``print`` adds one more newline)."""
    out = [f"Type: {info['type']}\n\n"]
    for key, title in (("publishers", "Publishers"), ("subscribers", "Subscribers")):
        entries = info[key]
        if entries:
            out.append(f"{title}: \n")
            out.extend(f" * {e['node']} ({e['uri']})\n" for e in entries)
        else:
            out.append(f"{title}: None\n")
        out.append("\n")
    return "".join(out)


def find_topic_type(call: MasterCall, topic: str) -> tuple[str | None, str | None, str]:
    """``(type, real_topic, field_path)`` for a topic or a field of one (``/rosout/msg``).

    The exact topic wins; otherwise the longest published topic that is a
    prefix, skipping types that lack the field.  ``(None, None, "")`` when
    nothing matches.
    """
    val = topic_types(call)
    matches = [(t, ty) for t, ty in val if t == topic]
    if not matches:
        matches = sorted(((t, ty) for t, ty in val if topic.startswith(t + "/")), key=lambda m: m[0], reverse=True)
        while matches:
            t, ty = matches[0]
            attrs = topic[len(t) + 1:].rstrip("/").split("[")[0]
            if not attrs:
                break
            cls = _local_class(ty)
            if cls is None:
                break
            try:
                _nested_attribute(cls(), attrs)
            except AttributeError:
                matches.pop(0)
                continue
            matches = [(t, ty)]
            break
    if not matches:
        return None, None, ""
    t, ty = matches[0]
    if ty == "*":
        return None, None, ""
    return ty, t, topic[len(t):]


def _local_class(type_name: str) -> Any:
    from rostui.core.msg import MessageError, get_message_class

    try:
        return get_message_class(type_name)
    except (MessageError, ValueError, OSError):
        return None


def _nested_attribute(msg: Any, path: str) -> Any:
    for attr in path.split("/"):
        if attr not in getattr(msg, "__slots__", ()):
            raise AttributeError(attr)
        msg = getattr(msg, attr)
    return msg


def type_text(call: MasterCall, topic: str) -> str:
    """What ``rostopic type TOPIC`` prints: the type, or ``TYPE field fieldtype`` for a field."""
    ty, real, _ = find_topic_type(call, topic)
    if ty is None or real is None:
        raise TopicToolError(f"unknown topic type [{topic}]")
    if topic == real:
        return ty
    field = topic[len(real) + 1:]
    field_type = ty
    for part in field.split("/"):
        cls = _local_class(field_type.split("[")[0])
        if cls is None or part not in cls.__slots__:
            raise TopicToolError(f"unknown field [{field}] in {ty}")
        field_type = cls._slot_types[cls.__slots__.index(part)]
    return f"{ty} {field} {field_type}"


def find_by_type(call: MasterCall, type_name: str) -> list[str]:
    """Topics whose type is *type_name* (``rostopic find``)."""
    return [t for t, ty in topic_types(call) if ty == type_name]
