"""The read-only views of ``rostui launch``: --nodes, --args NODE, --dump-params, --files, --ros-args."""

from __future__ import annotations

import os
import shlex
import sys
from pathlib import Path
from typing import Any

import yaml

from rostui.core.names import canonicalize_name
from rostui.launch.errors import LaunchError, StrictError
from rostui.launch.files import LaunchRequest
from rostui.launch.loader import XmlLoader
from rostui.launch.model import LaunchConfig, NodeSpec
from rostui.launch.substitution import SubstitutionContext, resolve


def load_config(request: LaunchRequest, *, args_only: bool = False) -> tuple[LaunchConfig, XmlLoader]:
    """Load every file of ``request`` into one config (the loader is returned for its shared anon names).

    With ``request.strict`` an unknown element or attribute raises :class:`StrictError`.
    """
    config = LaunchConfig()
    loader = XmlLoader(args_only=args_only)
    for filename in request.files:
        loader.load(filename, config, request.args, request.namespace)
    if request.strict and config.problems:
        raise StrictError([str(problem) for problem in config.problems])
    return config, loader


def node_list(request: LaunchRequest) -> str:
    """``--nodes``: each node's (and test's) global name on a line."""
    config, _ = load_config(request)
    return "\n".join(n.resolved_name for n in config.all_nodes())


def file_list(request: LaunchRequest) -> list[str]:
    """``--files``: every launch file read (absolute paths, each once)."""
    config, _ = load_config(request)
    seen: list[str] = []
    for name in config.files:
        path = os.path.abspath(name)
        if path not in seen:
            seen.append(path)
    return seen


def dump_params(request: LaunchRequest) -> str:
    """``--dump-params``: the params the launch would set, as YAML (``name: value`` per key)."""
    config, _ = load_config(request)
    return yaml.safe_dump({key: _plain(value) for key, value in config.params.items()})


def _plain(value: Any) -> Any:
    import xmlrpc.client

    if isinstance(value, xmlrpc.client.Binary):
        return value.data
    return value


def args_doc(request: LaunchRequest) -> str:
    """``--ros-args``: the top-level args of the file, required ones first, as roslaunch lists them."""
    config, _ = load_config(request, args_only=True)
    docs = config.arg_docs
    if not docs:
        return "No arguments."
    lines: list[str] = []
    required = sorted((name, doc or "undocumented") for name, (doc, default) in docs.items() if not default)
    optional = sorted((name, doc or "undocumented", default) for name, (doc, default) in docs.items() if default)
    if required:
        lines.append("Required Arguments:")
        lines += [f"  {name}: {doc}" for name, doc in required]
    if optional:
        lines.append("Optional Arguments:")
        lines += [f'  {name} (default "{default}"): {doc}' for name, doc, default in optional]
    return "\n".join(lines)


def find_node(config: LaunchConfig, wanted: str, files: list[str]) -> NodeSpec:
    """The node called ``wanted`` (relative names are global); raises :class:`LaunchError`."""
    if not wanted.startswith("$"):
        wanted = canonicalize_name(wanted if wanted.startswith("/") else "/" + wanted)
    matches = [n for n in config.all_nodes() if n.resolved_name == wanted]
    if not matches:
        raise LaunchError(f"Cannot find node named [{wanted}] in [{', '.join(files)}]; node names are: "
                          + ", ".join(n.resolved_name for n in config.all_nodes()))
    if len(matches) > 1:
        raise LaunchError(f"multiple nodes named [{wanted}] in [{', '.join(files)}]")
    return matches[0]


def node_env(node: NodeSpec, master_uri: str, base: dict[str, str] | None = None) -> dict[str, str]:
    """The environment a node starts with: ROS_MASTER_URI, ROS_NAMESPACE and its ``<env>`` values."""
    env = dict(os.environ if base is None else base)
    env["ROS_MASTER_URI"] = master_uri
    env.pop("ROS_NAMESPACE", None)
    namespace = node.namespace.rstrip("/")
    if namespace:
        env["ROS_NAMESPACE"] = namespace
    for name, value in node.env:
        env[name] = value
    return env


def node_executable(node: NodeSpec, anons: dict[str, str]) -> tuple[Path, list[str]]:
    """The file that runs ``node`` and its arguments: args, remaps and ``__name`` (``$(anon)`` resolved).

    Raises :class:`LaunchError` when the executable cannot be found.
    """
    from rostui.tools.run import RunError, locate

    ctx = SubstitutionContext(anons=anons, filename=node.filename)
    name = resolve(node.name, ctx) or node.name
    args = shlex.split(resolve(node.args, ctx) or "")
    remaps = [f"{src}:={dst}" for src, dst in node.remaps] + [f"__name:={name}"]
    try:
        path = locate(node.package, node.type, choose=lambda found: found[0])  # roslaunch takes the first match
    except RunError as exc:
        raise LaunchError(f"cannot launch node of type [{node.package}/{node.type}]: {exc.lines[0]}",
                          node.filename, node.line) from None
    return path, [*args, *remaps]


def node_argv(node: NodeSpec, anons: dict[str, str], *, as_shown: bool = False) -> list[str]:
    """The command line that starts ``node``: launch-prefix, the executable, its args, remaps and ``__name``.

    Resolves ``$(anon)`` in the name and args with the launch's shared anon names.
    rostui's run resolver starts built-in Python scripts with this Python; with
    ``as_shown`` that interpreter is left out (the script itself is executable),
    as roslaunch --args prints it.  Raises :class:`LaunchError` when the
    executable cannot be found.
    """
    from rostui.tools.run import argv_for

    path, args = node_executable(node, anons)
    argv = argv_for(path, args, None)
    if as_shown and len(argv) > 1 and argv[0] == sys.executable and os.access(argv[1], os.X_OK):
        argv = argv[1:]
    prefix = shlex.split(node.launch_prefix) if node.launch_prefix else []
    return [*prefix, *argv]


def default_master_uri() -> str:
    """ROS_MASTER_URI exactly as set (roslaunch's default when unset)."""
    return os.environ.get("ROS_MASTER_URI") or "http://localhost:11311/"


def node_args_line(request: LaunchRequest, wanted: str, master_uri: str) -> str:
    """``--args NODE``: the environment settings that differ from ours, then the node's command line."""
    config, loader = load_config(request)
    node = find_node(config, wanted, request.files)
    env = node_env(node, master_uri)
    changed = [f'{key}="{value}"' for key, value in env.items() if os.environ.get(key) != value]
    return " ".join([*changed, *node_argv(node, loader.anons, as_shown=True)])
