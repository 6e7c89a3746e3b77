"""roslaunch XML (read with lxml) -> :class:`LaunchConfig`.

Follows roslaunch's loading rules: ``ns`` pushes down through ``group``,
``include`` and ``node``; ``~param`` children of a node (and ``~param``s
declared earlier in the same scope) land under the node's name; remaps and
``env`` are inherited by later nodes of the scope; args are scoped to their
file (an included file sees only what its ``<include>`` passes, or everything
with ``pass_all_args``) and to their group; ``if``/``unless`` accept only
true/false/1/0.  An unknown element or attribute is, as in roslaunch, only a
warning (a :class:`~rostui.launch.model.LaunchProblem` with its file and
line); ``--strict`` turns those into errors.  Every error is a
:class:`LaunchError` carrying the file and line of the element at fault.
"""

from __future__ import annotations

import copy
import os
import re
import shlex
import subprocess
import xmlrpc.client
from dataclasses import dataclass, field
from typing import Any

import yaml
from lxml import etree

from rostui.core.names import (
    canonicalize_name, is_legal_name, is_private, join_names, make_global_ns,
)
from rostui.core.one_line import exception_line
from rostui.launch.errors import ArgNotSetError, LaunchError
from rostui.launch.model import LaunchConfig, LaunchProblem, Machine, NodeSpec, RosparamCommand
from rostui.launch.substitution import SubstitutionContext, resolve
from rostui.launch.values import convert_value

NODE_ATTRS = {"pkg", "type", "machine", "name", "args", "output", "respawn", "respawn_delay", "cwd", "ns",
              "clear_params", "launch-prefix", "required"}
TEST_ATTRS = NODE_ATTRS | {"test-name", "time-limit", "retry"}
PARAM_ATTRS = {"name", "value", "type", "textfile", "binfile", "command"}
ROSPARAM_ATTRS = {"command", "ns", "file", "param", "subst_value"}
ARG_ATTRS = {"name", "value", "default", "doc"}
MACHINE_ATTRS = {"name", "address", "env-loader", "ssh-port", "user", "password", "default", "timeout"}
#: ``<machine>`` attributes of ROS before Fuerte: roslaunch refuses them (env-loader replaced them).
PRE_FUERTE_MACHINE_ATTRS = ("ros-root", "ros-package-path", "ros-ip", "ros-hostname")
#: ``<machine default=…>`` -> (the machine becomes the default for later nodes, nodes may be assigned to it).
MACHINE_DEFAULTS = {"true": (True, True), "false": (False, True), "never": (False, False)}
ATTRS = {
    "launch": {"deprecated"}, "node": NODE_ATTRS, "test": TEST_ATTRS, "param": PARAM_ATTRS,
    "rosparam": ROSPARAM_ATTRS, "arg": ARG_ATTRS, "machine": MACHINE_ATTRS, "remap": {"from", "to"},
    "env": {"name", "value"}, "group": {"ns", "clear_params"},
    "include": {"file", "ns", "clear_params", "pass_all_args"}, "master": {"auto"},
}


_MISMATCH = re.compile(r"Opening and ending tag mismatch: (\S+) line (\d+) and (\S+)")


def _syntax_message(exc: etree.XMLSyntaxError) -> str:
    """lxml's complaint in expat's words where roslaunch users know them (``mismatched tag``)."""
    text = (exc.msg or str(exc)).split(", line ")[0]
    mismatch = _MISMATCH.match(text)
    if mismatch:
        opened, line, closer = mismatch.groups()
        return f"mismatched tag: </{closer}> closes <{opened}> opened on line {line}"
    return text


@dataclass
class Scope:
    """roslaunch's loader context: namespace, inherited remaps/env/~params and the args in scope."""

    ns: str
    filename: str
    parent: "Scope | None" = None
    remaps: list[tuple[str, str]] = field(default_factory=list)
    params: list[tuple[str, Any]] = field(default_factory=list)
    env: list[tuple[str, str]] = field(default_factory=list)
    args: dict[str, str] = field(default_factory=dict)
    arg_docs: dict[str, tuple[str | None, str | None]] = field(default_factory=dict)
    arg_names: list[str] = field(default_factory=list)
    include_args: dict[str, str] | None = None
    include_docs: dict[str, tuple[str | None, str | None]] | None = None
    args_passed: list[str] = field(default_factory=list)
    pass_all_args: bool = False

    def child(self, ns: str | None) -> "Scope":
        """A nested scope (``group``/``node``/``include``); ``~params`` list shared, args copied."""
        if ns:
            child_ns = ns if ns.startswith("/") or ns == "~" else join_names(self.ns, ns)
        else:
            child_ns = self.ns
        return Scope(ns=make_global_ns(child_ns) if child_ns != "~" else "~", filename=self.filename, parent=self,
                     params=self.params, env=list(self.env), args=copy.deepcopy(self.args),
                     arg_docs=copy.deepcopy(self.arg_docs), arg_names=list(self.arg_names),
                     include_args=self.include_args, include_docs=self.include_docs)

    def all_remaps(self) -> list[tuple[str, str]]:
        """Remaps in effect: the parent's, overridden by this scope's own for the same ``from``."""
        if self.parent is None:
            return list(self.remaps)
        own = {src for src, _ in self.remaps}
        return [r for r in self.parent.all_remaps() if r[0] not in own] + list(self.remaps)

    def add_remap(self, src: str, dst: str) -> None:
        """Add (or replace) a remap of this scope, validated like roslaunch."""
        src, dst = canonicalize_name(src), canonicalize_name(dst)
        if not src or not dst:
            raise LaunchError("remap from/to attributes cannot be empty")
        for name, what in ((src, "from"), (dst, "to")):
            if not is_legal_name(name):
                raise LaunchError(f"remap {what} [{name}] is not a valid ROS name")
        self.remaps = [r for r in self.remaps if r[0] != src] + [(src, dst)]

    def add_param(self, key: str, value: Any) -> None:
        """Add a ``~param`` for later nodes of this scope (a later one of the same name replaces it)."""
        self.params[:] = [p for p in self.params if p[0] != key]
        self.params.append((key, value))

    def add_arg(self, name: str, value: str | None, default: str | None, doc: str | None) -> None:
        """Declare an arg; a ``value`` cannot override one already set (unless all args were passed)."""
        if name in self.arg_names:
            if not self.pass_all_args:
                raise LaunchError(f"arg '{name}' has already been declared")
        else:
            self.arg_names.append(name)
        target = self.args if self.include_args is None else self.include_args
        docs = self.arg_docs if self.include_docs is None else self.include_docs
        if value is not None:
            if name in target and not self.pass_all_args:
                raise LaunchError(f"cannot override arg '{name}', which has already been set")
            target[name] = value
        elif default is not None and name not in target:
            target[name] = default
        if not value:
            docs[name] = (doc, default)


class XmlLoader:
    """Loads launch files into one :class:`LaunchConfig`; ``$(anon)`` names are shared by the whole load."""

    def __init__(self, args_only: bool = False) -> None:
        """``args_only`` reads only the top-level ``<arg>`` elements (for --ros-args)."""
        self.args_only = args_only
        self.anons: dict[str, str] = {}
        self.root: Scope | None = None
        self.config: LaunchConfig | None = None

    # -- entry points ------------------------------------------------------------------------------------------

    def load(self, filename: str, config: LaunchConfig, argv_args: dict[str, str], namespace: str = "/") -> None:
        """Load ``filename`` (with ``name:=value`` args from the command line) into ``config``."""
        self.config = config
        root = self._parse(filename, None)
        config.files.append(filename)
        self._launch_tag(root, config, filename)
        scope = Scope(ns=make_global_ns(namespace or "/"), filename=filename, args=dict(argv_args))
        self.root = scope
        self._recurse(root, scope, config, None)
        config.arg_docs.update(scope.arg_docs)

    # -- helpers ----------------------------------------------------------------------------------------------

    def _parse(self, filename: str, include: etree._Element | None) -> etree._Element:
        parser = etree.XMLParser(remove_comments=True, resolve_entities=False, remove_pis=True)
        try:
            tree = etree.parse(filename, parser)
        except OSError:
            raise LaunchError(f"launch file {filename} does not exist or cannot be read") from None
        except etree.XMLSyntaxError as exc:
            raise LaunchError(f"Invalid roslaunch XML syntax: {_syntax_message(exc)}", filename,
                              exc.lineno or None) from None
        root = tree.getroot()
        if root.tag != "launch":
            raise LaunchError("Invalid roslaunch XML syntax: no root <launch> tag", filename, _line(root))
        return root

    def _sub(self, text: str | None, scope: Scope) -> str | None:
        ctx = SubstitutionContext(args=scope.args, anons=self.anons, filename=scope.filename)
        return resolve(text, ctx)

    def _opt(self, tag: etree._Element, scope: Scope, name: str) -> str | None:
        return self._sub(tag.get(name), scope)

    def _req(self, tag: etree._Element, scope: Scope, name: str) -> str:
        value = tag.get(name)
        if value is None:
            raise LaunchError(f"<{tag.tag}> tag is missing required attribute: '{name}'")
        return self._sub(value, scope) or ""

    def _problem(self, message: str, filename: str, tag: etree._Element) -> None:
        """Record an unknown element or attribute (a warning; an error with --strict)."""
        if self.config is None:
            return
        problem = LaunchProblem(message, filename, _line(tag))
        self.config.problems.append(problem)
        self.config.warnings.append(str(problem))

    def _check_attrs(self, tag: etree._Element, scope: Scope) -> None:
        allowed = ATTRS.get(_str(tag.tag).lower(), set()) | {"if", "unless"}
        for attr in map(_str, tag.attrib):
            if attr not in allowed:
                self._problem(f"unknown <{tag.tag}> attribute '{attr}'", scope.filename, tag)

    def _included(self, tag: etree._Element, scope: Scope) -> bool:
        """Evaluate ``if``/``unless``: True when the element applies."""
        if_val, unless_val = self._opt(tag, scope, "if"), self._opt(tag, scope, "unless")
        if if_val is not None and unless_val is not None:
            raise LaunchError("cannot set both 'if' and 'unless' on the same tag")
        for label, raw in (("if", if_val), ("unless", unless_val)):
            if raw is None:
                continue
            try:
                flag = convert_value(raw, "bool")
            except ValueError:
                raise LaunchError(f"invalid '{label}' value '{raw}': only true, false, 1 or 0") from None
            return flag if label == "if" else not flag
        return True

    @staticmethod
    def _bool(value: str | None, default: bool, label: str) -> bool:
        if value is None:
            return default
        if value.lower() in ("true", "false"):
            return value.lower() == "true"
        if not value:
            raise LaunchError(f"bool value for {label} must be non-empty")
        raise LaunchError(f"invalid bool value for {label}: {value}")

    @staticmethod
    def _float(value: str | None, default: float, label: str) -> float:
        if value is None:
            return default
        try:
            return float(value)
        except ValueError:
            raise LaunchError(f"invalid float value for {label}: {value}") from None

    # -- elements ----------------------------------------------------------------------------------------------

    def _launch_tag(self, root: etree._Element, config: LaunchConfig, filename: str) -> None:
        deprecated = root.get("deprecated")
        if deprecated:
            config.warnings.append(f"[{filename}] DEPRECATED: {deprecated}")

    def _recurse(self, parent: etree._Element, scope: Scope, config: LaunchConfig,
                 default_machine: Machine | None) -> Machine | None:
        for tag in parent:
            if not isinstance(tag.tag, str):
                continue
            try:
                default_machine = self._element(tag, scope, config, default_machine)
            except LaunchError as exc:
                raise exc.located(scope.filename, _line(tag)) from None
        return default_machine

    def _element(self, tag: etree._Element, scope: Scope, config: LaunchConfig,
                 default_machine: Machine | None) -> Machine | None:
        name = tag.tag
        if name == "arg":
            if self._included(tag, scope):
                self._arg_tag(tag, scope)
            return default_machine
        if self.args_only:
            return default_machine
        if name not in ATTRS or name == "launch":
            self._problem(f"unrecognized tag <{name}>", scope.filename, tag)
            return default_machine
        if not self._included(tag, scope):
            return default_machine
        self._check_attrs(tag, scope)
        if name == "group":
            child = self._ns_clear_params(tag, scope, config)
            child.params = list(child.params)
            return self._recurse(tag, child, config, default_machine)
        if name in ("node", "test"):
            node = self._node_tag(tag, scope, config, default_machine, is_test=name == "test")
            self._add_node(node, config)
        elif name == "param":
            self._param_tag(tag, scope, config, force_local=False)
        elif name == "remap":
            scope.add_remap(self._req(tag, scope, "from"), self._req(tag, scope, "to"))
        elif name == "rosparam":
            self._rosparam_tag(tag, scope, config)
        elif name == "env":
            self._env_tag(tag, scope)
        elif name == "machine":
            machine, is_default = self._machine_tag(tag, scope)
            previous = config.machines.get(machine.name)
            if previous is not None and not previous.same_as(machine):
                raise LaunchError(f"Machine [{machine.name}] already added and does not match duplicate entry "
                                  f"(first declared at {previous.filename}:{previous.line})")
            config.machines.setdefault(machine.name, machine)
            if is_default:
                return machine
        elif name == "include":
            return self._include_tag(tag, scope, config, default_machine)
        elif name == "master":
            config.warnings.append("ignoring defunct <master /> tag")
        return default_machine

    def _add_node(self, node: NodeSpec, config: LaunchConfig) -> None:
        if node.name:
            resolved = join_names(node.namespace, node.name)
            if any(join_names(n.namespace, n.name) == resolved for n in config.all_nodes()):
                raise LaunchError(f"roslaunch file contains multiple nodes named [{resolved}]; node names must be "
                                  "unique (and $(anon id) ids different)")
        (config.tests if node.is_test else config.nodes).append(node)

    def _arg_tag(self, tag: etree._Element, scope: Scope) -> None:
        self._check_attrs(tag, scope)
        name = self._req(tag, scope, "name")
        value, default, doc = (self._opt(tag, scope, a) for a in ("value", "default", "doc"))
        if value is not None and default is not None:
            raise LaunchError("<arg> tag must have one and only one of value/default.")
        scope.add_arg(name, value=value, default=default, doc=doc)

    def _ns_clear_params(self, tag: etree._Element, scope: Scope, config: LaunchConfig,
                         node_name: str | None = None, include_file: str | None = None) -> Scope:
        ns: str | None = None
        if tag.get("ns") is not None:
            ns = self._opt(tag, scope, "ns")
            if not ns:
                raise LaunchError(f"<{tag.tag}> tag has an empty 'ns' attribute")
        child = scope.child(ns)
        if include_file is not None:
            child.arg_names = []
            child.filename = include_file
            child.include_args = {}
            child.include_docs = {}
        clear = self._opt(tag, scope, "clear_params")
        if clear and self._bool(clear, False, "clear_params"):
            if tag.tag == "node":
                config.clear_params.append(make_global_ns(join_names(child.ns, node_name or "")))
            else:
                if not ns:
                    raise LaunchError("'ns' attribute must be set in order to use 'clear_params'")
                config.clear_params.append(child.ns)
        return child

    def _node_tag(self, tag: etree._Element, scope: Scope, config: LaunchConfig,
                  default_machine: Machine | None, is_test: bool) -> NodeSpec:
        test_name: str | None = None
        time_limit: float | None = None
        retry = 0
        if is_test:
            for attr in ("respawn", "respawn_delay", "output"):
                if tag.get(attr) is not None:
                    raise LaunchError(f"<test> tags cannot have '{attr}' attribute")
            name = self._opt(tag, scope, "name")
            test_name = self._req(tag, scope, "test-name")
            raw_limit = self._opt(tag, scope, "time-limit")
            if raw_limit:
                time_limit = self._float(raw_limit, 60.0, "time-limit")
                if time_limit <= 0:
                    raise LaunchError("'time-limit' must be a positive number")
            raw_retry = self._opt(tag, scope, "retry")
            if raw_retry:
                try:
                    retry = int(raw_retry)
                except ValueError:
                    raise LaunchError(f"'retry' must be a number: [{raw_retry}]") from None
            name = name or test_name
        else:
            name = self._req(tag, scope, "name")
        if not is_legal_name(name):
            config.warnings.append(f"illegal <node> name '{name}' (see http://ros.org/wiki/Names)")
        child = self._ns_clear_params(tag, scope, config, node_name=name)
        param_scope = child.child(name)
        param_scope.params = []
        pkg, node_type = self._req(tag, scope, "pkg"), self._req(tag, scope, "type")
        machine, args, output, respawn, respawn_delay, cwd, prefix, required = (
            self._opt(tag, scope, a) for a in ("machine", "args", "output", "respawn", "respawn_delay", "cwd",
                                                "launch-prefix", "required"))
        if not machine and default_machine is not None:
            machine = default_machine.name
        required_flag = self._bool(required, False, "required")
        respawn_flag = self._bool(respawn, False, "respawn")
        delay = self._float(respawn_delay, 0.0, "respawn_delay")
        remap_scope = scope.child("")
        env_scope = scope.child("")
        for sub in tag:
            if not isinstance(sub.tag, str):
                continue
            kind = _str(sub.tag).lower()
            try:
                if kind not in ("remap", "param", "rosparam", "env"):
                    self._problem(f"unrecognized '{sub.tag}' child tag in <{tag.tag}>", scope.filename, sub)
                    continue
                if not self._included(sub, scope):
                    continue
                self._check_attrs(sub, scope)
                if kind == "remap":
                    remap_scope.add_remap(self._req(sub, scope, "from"), self._req(sub, scope, "to"))
                elif kind == "param":
                    self._param_tag(sub, param_scope, config, force_local=True)
                elif kind == "rosparam":
                    self._rosparam_tag(sub, param_scope, config)
                else:
                    self._env_tag(sub, env_scope)
            except LaunchError as exc:
                raise exc.located(scope.filename, _line(sub)) from None
        for key, value in [*scope.params, *param_scope.params]:
            if is_private(key):
                key = key[1:]
            config.params[canonicalize_name(param_scope.ns + key)] = value
        if cwd == "ros_home":
            cwd = "ROS_HOME"
        if respawn_flag and required_flag:
            raise LaunchError("respawn and required cannot both be set to true")
        if "/" in name:
            raise LaunchError("node name cannot contain a namespace")
        if not pkg.strip():
            raise LaunchError("package must be non-empty")
        if not node_type.strip():
            raise LaunchError("type must be non-empty")
        if output not in ("log", "screen", None):
            raise LaunchError("output must be one of 'log', 'screen'")
        if cwd not in ("ROS_HOME", "node", None):
            raise LaunchError("cwd must be one of 'ROS_HOME', 'node'")
        namespace = make_global_ns(canonicalize_name(child.ns))
        return NodeSpec(
            package=pkg, type=node_type, name=name, namespace=namespace, args=args or "",
            remaps=remap_scope.all_remaps(), env=list(env_scope.env), machine=machine or None,
            respawn=respawn_flag, respawn_delay=delay, required=required_flag, output=output, cwd=cwd,
            launch_prefix=prefix or None, filename=scope.filename, line=_line(tag),
            test_name=test_name, time_limit=time_limit, retry=retry)

    def _param_tag(self, tag: etree._Element, scope: Scope, config: LaunchConfig, force_local: bool) -> None:
        ptype = (tag.get("type") or "auto").lower().strip()
        value, textfile, binfile, command = (self._opt(tag, scope, a)
                                             for a in ("value", "textfile", "binfile", "command"))
        if sum(v is not None for v in (value, textfile, binfile, command)) != 1:
            raise LaunchError("<param> tag must have one and only one of value/textfile/binfile/command.")
        name = (self._sub(self._req(tag, scope, "name").strip(), scope) or "")
        try:
            resolved = self._param_value(name, ptype, value, textfile, binfile, command)
        except (ValueError, OSError) as exc:
            raise LaunchError(f"Invalid <param> tag: {exc}") from None
        if is_private(name) or force_local:
            scope.add_param(name, resolved)
        else:
            self._set_param(config, join_names(scope.ns, name), resolved)

    @staticmethod
    def _set_param(config: LaunchConfig, key: str, value: Any) -> None:
        key = canonicalize_name(key)
        if not key:
            raise LaunchError("no parameter name specified")
        config.params[key] = value

    def _put_tree(self, config: LaunchConfig, key: str, value: Any) -> None:
        if key == "/" and not isinstance(value, dict):
            raise LaunchError("Cannot load non-dictionary types into global namespace '/'")
        if isinstance(value, dict):
            for sub_key, sub_value in value.items():
                self._put_tree(config, join_names(key, str(sub_key)), sub_value)
        else:
            self._set_param(config, key, value)

    @staticmethod
    def _param_value(name: str, ptype: str, value: str | None, textfile: str | None, binfile: str | None,
                     command: str | None) -> Any:
        if value is not None:
            return convert_value(value.strip(), ptype)
        if textfile is not None:
            with open(textfile, encoding="utf-8") as fh:
                return convert_value(fh.read(), ptype)
        if binfile is not None:
            with open(binfile, "rb") as fh:
                return xmlrpc.client.Binary(fh.read())
        assert command is not None
        try:
            proc = subprocess.run(shlex.split(command), stdout=subprocess.PIPE, check=False)
        except FileNotFoundError:
            raise ValueError(f"Cannot load command parameter [{name}]: no such command [{command}]") from None
        if proc.returncode != 0:
            raise ValueError(f"Cannot load command parameter [{name}]: command [{command}] returned with code "
                             f"[{proc.returncode}]")
        return convert_value(proc.stdout.decode("utf-8"), ptype)

    def _rosparam_tag(self, tag: etree._Element, scope: Scope, config: LaunchConfig) -> None:
        command, ns, file_, param, subst = (self._opt(tag, scope, a)
                                            for a in ("command", "ns", "file", "param", "subst_value"))
        subst_value = self._bool(subst, False, "subst_value")
        param = join_names(ns or "", param or "") if ns else (param or "")
        command = command or "load"
        if command not in ("load", "dump", "delete"):
            raise LaunchError("error loading <rosparam> tag: command must be 'load', 'dump', or 'delete'")
        if file_ is not None:
            if command == "load" and not os.path.isfile(file_):
                raise LaunchError(f"error loading <rosparam> tag: file does not exist [{file_}]")
            if command == "delete":
                raise LaunchError("error loading <rosparam> tag: 'file' attribute is invalid with 'delete' command.")
        full = join_names(scope.ns, param) if param else scope.ns
        if command in ("dump", "delete"):
            config.rosparam_commands.append(RosparamCommand(command, full, file_))
            return
        if file_:
            with open(file_, encoding="utf-8") as fh:
                text = fh.read()
        else:
            text = "".join(map(_str, tag.itertext()))
        if subst_value:
            text = self._sub(text, scope) or ""
        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError as exc:
            where = f"file {file_} contains" if file_ else "<rosparam> holds"
            raise LaunchError(f"{where} invalid YAML: {exception_line(exc, None)}") from None
        if data is None:
            data = {}
        if not param and not isinstance(data, dict):
            raise LaunchError("error loading <rosparam> tag: 'param' attribute must be set for non-dictionary "
                              "values")
        self._put_tree(config, full, data)

    def _env_tag(self, tag: etree._Element, scope: Scope) -> None:
        name, value = self._req(tag, scope, "name"), self._req(tag, scope, "value")
        if not name:
            raise LaunchError("Invalid <env> tag: 'name' attribute must be non-empty")
        scope.env.append((name, value))

    def _machine_tag(self, tag: etree._Element, scope: Scope) -> tuple[Machine, bool]:
        """A ``<machine>`` and whether it becomes the default machine of later nodes."""
        if any(self._opt(tag, scope, a) for a in PRE_FUERTE_MACHINE_ATTRS):
            raise LaunchError("<machine>: ros-* attributes are not supported since ROS Fuerte; use env-loader "
                              "instead")
        name, address = self._req(tag, scope, "name"), self._req(tag, scope, "address")
        env_loader, ssh_port, user, password, default, timeout = (
            self._opt(tag, scope, a) for a in ("env-loader", "ssh-port", "user", "password", "default", "timeout"))
        try:
            port = int(ssh_port or "22")
        except ValueError:
            raise LaunchError(f"'ssh-port' must be a number: [{ssh_port}]") from None
        default = (default or "false").lower()
        if default not in MACHINE_DEFAULTS:
            raise LaunchError(f"Invalid value for 'default': {default} (true, false or never)")
        is_default, assignable = MACHINE_DEFAULTS[default]
        for sub in tag:
            if not isinstance(sub.tag, str):
                continue
            if sub.tag == "env":
                raise LaunchError("<machine>: <env> tag is not supported since ROS Fuerte; use env-loader instead")
            self._problem(f"unrecognized '{sub.tag}' tag in <machine> tag", scope.filename, sub)
        limit: float | None = None
        if timeout == "":
            raise LaunchError("'timeout' cannot be empty")
        if timeout is not None:
            try:
                limit = float(timeout)
            except ValueError:
                raise LaunchError(f"'timeout' must be a number: [{timeout}]") from None
            if limit <= 0:
                raise LaunchError(f"'timeout' must be a positive number: [{limit}]")
        machine = Machine(name, address, env_loader, port, user or None, password, limit, _line(tag), scope.filename,
                          assignable=assignable)
        return machine, is_default

    def _include_tag(self, tag: etree._Element, scope: Scope, config: LaunchConfig,
                     default_machine: Machine | None) -> Machine | None:
        filename = self._req(tag, scope, "file")
        pass_all = self._bool(self._opt(tag, scope, "pass_all_args"), False, "pass_all_args")
        child = self._ns_clear_params(tag, scope, config, include_file=filename)
        if pass_all:
            for name, value in scope.args.items():
                child.add_arg(name, value=value, default=None, doc=None)
            child.pass_all_args = True
        child.filename = scope.filename
        for sub in tag:
            if not isinstance(sub.tag, str):
                continue
            kind = _str(sub.tag).lower()
            try:
                if kind not in ("arg", "env"):
                    self._problem(f"unrecognized '{sub.tag}' tag in <include> tag", scope.filename, sub)
                    continue
                if not self._included(sub, child):
                    continue
                if kind == "arg":
                    self._arg_tag(sub, child)
                else:
                    self._check_attrs(sub, child)
                    self._env_tag(sub, child)
            except LaunchError as exc:
                raise exc.located(scope.filename, _line(sub)) from None
        child.filename = filename
        passed = child.include_args or {}
        for name in child.arg_names:
            if name not in passed:
                raise LaunchError("include args must have declared values")
        child.args_passed = list(passed)
        child.arg_names = []
        child.args = passed
        child.arg_docs = child.include_docs or {}
        child.include_args = None
        child.include_docs = None
        if not os.path.isfile(filename):
            raise LaunchError(f"included file {filename} does not exist")
        root = self._parse(filename, tag)
        config.files.append(filename)
        self._launch_tag(root, config, filename)
        try:
            default_machine = self._recurse(root, child, config, default_machine)
        except ArgNotSetError as exc:
            exc.message = f"included file [{filename}] requires the '{exc.name}' arg to be set"
            raise
        if not pass_all:
            unused = [a for a in child.args_passed if a not in child.arg_names]
            if unused:
                raise LaunchError(f"unused args [{', '.join(unused)}] for include of [{filename}]")
        return default_machine


# lxml-stubs 0.5 types an element's line as ``...`` and its attribute names and text as
# ``str | bytes``; lxml gives a parsed document's lines as int (None when unknown) and its text as str.
def _line(element: etree._Element) -> int | None:
    """The line of ``element`` in its file, if known."""
    line = element.sourceline
    return line if isinstance(line, int) else None


def _str(text: str | bytes) -> str:
    """An attribute name or text node of a parsed element, as str."""
    return text if isinstance(text, str) else text.decode("utf-8")
