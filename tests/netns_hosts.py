"""Several "hosts" on one machine for multi-machine tests: Linux network namespaces, each with its own sshd.

Needs root (``ip netns``).  :func:`make_hosts` builds, for one test:

- a switch namespace holding a bridge, and one namespace per host joined to
  it by a veth pair, with a 10.x/24 address that exists only inside these
  namespaces (nothing is added to the machine's own network);
- in each host, ``/usr/sbin/sshd -D`` listening on the host's address with a
  host key made for the test, accepting one client key made for the test;
- a client side that never touches the real ``~/.ssh``: ``home`` holds
  ``.ssh/config``, ``.ssh/known_hosts`` (every host's key, written by the
  test) and ``.ssh/id_ed25519``.  OpenSSH's client reads its files from the
  user's passwd entry, not ``$HOME``, so rostui is pointed at the config with
  ``ROSTUI_SSH_CONFIG``; paramiko (real roslaunch) reads ``$HOME/.ssh``.

Everything (processes in the namespaces, the namespaces, the veths) is
removed on exit, also when the test fails.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

import pytest

from conftest import need_peer

SSHD = "/usr/sbin/sshd"


@dataclass
class NetnsHost:
    """One host: its namespace, address, directory and sshd."""

    name: str
    namespace: str
    address: str
    root: Path
    sshd: subprocess.Popen | None = None

    def command(self, argv: list[str]) -> list[str]:
        """``argv`` run inside this host's network namespace."""
        return in_namespace(self.namespace, argv)

    def popen(self, argv: list[str], env: dict[str, str], **kwargs: object) -> subprocess.Popen:
        """Start ``argv`` on this host."""
        return subprocess.Popen(self.command(argv), env=env, **kwargs)  # type: ignore[call-overload]

    def run(self, argv: list[str], env: dict[str, str], timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
        """Run ``argv`` on this host to its end."""
        return subprocess.run(self.command(argv), env=env, capture_output=True, text=True, timeout=timeout)

    def pids(self) -> list[int]:
        """Every process in this host's namespace (``ip netns pids``)."""
        out = subprocess.run(["ip", "netns", "pids", self.namespace], capture_output=True, text=True, check=False)
        return [int(word) for word in out.stdout.split()]

    def env_loader(self, path_first: list[str], extra: dict[str, str] | None = None) -> Path:
        """Write an env-loader script for this host (PATH, ROS_IP, a private ROS_HOME) and return its path."""
        ros_home = self.root / "ros_home"
        ros_home.mkdir(exist_ok=True)
        lines = ["#!/bin/sh",
                 f"export PATH={':'.join(path_first)}:/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin",
                 f"export ROS_IP={self.address}",
                 f"export ROS_HOME={ros_home}",
                 "export PYTHONUNBUFFERED=1",
                 "unset ROS_HOSTNAME"]
        lines += [f"export {key}={value}" for key, value in (extra or {}).items()]
        lines.append('exec "$@"')
        script = self.root / "env_loader.sh"
        script.write_text("\n".join(lines) + "\n")
        script.chmod(0o755)
        return script


@dataclass
class NetnsHosts:
    """The hosts of one test and the client-side SSH files."""

    hosts: dict[str, NetnsHost]
    home: Path
    ssh_config: Path
    switch: str
    extra_namespaces: list[str] = field(default_factory=list)

    def __getitem__(self, name: str) -> NetnsHost:
        return self.hosts[name]

    def client_env(self, base: dict[str, str]) -> dict[str, str]:
        """``base`` with HOME and ROSTUI_SSH_CONFIG pointing at the test's SSH client files."""
        env = dict(base)
        env["HOME"] = str(self.home)
        env["ROSTUI_SSH_CONFIG"] = str(self.ssh_config)
        return env


def in_namespace(namespace: str, argv: list[str]) -> list[str]:
    """``argv`` run in the network namespace ``namespace`` (made by ``ip netns add``).

    ``nsenter --net`` enters the network namespace only.  ``ip netns exec`` and
    ``ip -n`` also make ``/`` a slave mount first, which fails where ``/`` is
    not a mount point (a chroot, as a fresh CI root is).
    """
    return ["nsenter", f"--net=/run/netns/{namespace}", *argv]


def _ip(*args: str) -> None:
    if args[0] == "-n":
        command = in_namespace(args[1], ["ip", *args[2:]])
    else:
        command = ["ip", *args]
    done = subprocess.run(command, capture_output=True, text=True, timeout=30)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {done.stderr.strip() or f'exit {done.returncode}'}")


def have_netns() -> bool:
    """True when this process may create network namespaces and run sshd (root, iproute2, openssh)."""
    return (os.geteuid() == 0 and shutil.which("ip") is not None and shutil.which("nsenter") is not None
            and Path(SSHD).exists()
            and shutil.which("ssh") is not None and shutil.which("ssh-keygen") is not None)


def _keygen(path: Path) -> None:
    subprocess.run(["ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-f", str(path)], check=True, timeout=30)


def _start_sshd(host: NetnsHost, authorized: Path) -> None:
    config = host.root / "sshd_config"
    config.write_text("\n".join([
        "Port 22",
        f"ListenAddress {host.address}",
        f"HostKey {host.root / 'host_key'}",
        f"AuthorizedKeysFile {authorized}",
        f"PidFile {host.root / 'sshd.pid'}",
        "PubkeyAuthentication yes",
        "PasswordAuthentication no",
        "KbdInteractiveAuthentication no",
        "PermitRootLogin prohibit-password",
        "StrictModes no",
        "UsePAM no",
        "",
    ]))
    log = open(host.root / "sshd.log", "w")  # noqa: SIM115 (closed with the process)
    host.sshd = subprocess.Popen(host.command([SSHD, "-D", "-e", "-f", str(config)]), stdout=log,
                                 stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 20
    while "Server listening" not in (host.root / "sshd.log").read_text():
        if host.sshd.poll() is not None or time.monotonic() > deadline:
            raise RuntimeError(f"sshd on {host.name} did not start: {(host.root / 'sshd.log').read_text()}")
        time.sleep(0.05)


def _kill_namespace(namespace: str) -> None:
    out = subprocess.run(["ip", "netns", "pids", namespace], capture_output=True, text=True, check=False)
    for word in out.stdout.split():
        with contextlib.suppress(ProcessLookupError):
            os.kill(int(word), signal.SIGKILL)
    subprocess.run(["ip", "netns", "del", namespace], capture_output=True, check=False)


@contextlib.contextmanager
def make_hosts(tmp_path: Path, names: list[str], unreachable: list[str] | None = None) -> Iterator[NetnsHosts]:
    """Hosts ``names`` (e.g. ``["a", "b", "c"]``) on a private bridge, each with sshd; cleaned up on exit.

    Each name in ``unreachable`` gets an address on the same subnet that no
    namespace answers (for a host that does not answer).
    """
    need_peer(have_netns(), "ip (iproute2), nsenter (util-linux), sshd (openssh-server), ssh (openssh-client), run as root")
    tag = secrets.token_hex(3)
    subnet = f"10.{200 + secrets.randbelow(50)}.{secrets.randbelow(250)}"
    switch = f"rt{tag}sw"
    made: list[str] = []
    hosts: dict[str, NetnsHost] = {}
    try:
        _ip("netns", "add", switch)
        made.append(switch)
        _ip("-n", switch, "link", "add", "br0", "type", "bridge")
        _ip("-n", switch, "link", "set", "br0", "up")
        _ip("-n", switch, "link", "set", "lo", "up")
        for index, name in enumerate(names, start=1):
            namespace = f"rt{tag}{name}"
            _ip("netns", "add", namespace)
            made.append(namespace)
            _ip("link", "add", "eth0", "netns", namespace, "type", "veth", "peer", "name", f"p{index}",
                "netns", switch)
            _ip("-n", switch, "link", "set", f"p{index}", "master", "br0")
            _ip("-n", switch, "link", "set", f"p{index}", "up")
            address = f"{subnet}.{index}"
            _ip("-n", namespace, "addr", "add", f"{address}/24", "dev", "eth0")
            _ip("-n", namespace, "link", "set", "eth0", "up")
            _ip("-n", namespace, "link", "set", "lo", "up")
            root = tmp_path / "hosts" / name
            root.mkdir(parents=True)
            hosts[name] = NetnsHost(name, namespace, address, root)
        for offset, name in enumerate(unreachable or [], start=len(names) + 1):
            hosts[name] = NetnsHost(name, "", f"{subnet}.{offset + 100}", tmp_path / "hosts" / name)
        home = tmp_path / "ssh_home"
        ssh_dir = home / ".ssh"
        ssh_dir.mkdir(parents=True)
        ssh_dir.chmod(0o700)
        _keygen(ssh_dir / "id_ed25519")
        authorized = tmp_path / "hosts" / "authorized_keys"
        authorized.write_text((ssh_dir / "id_ed25519.pub").read_text())
        Path("/run/sshd").mkdir(mode=0o755, exist_ok=True)  # sshd's privilege-separation directory
        known: list[str] = []
        for host in hosts.values():
            if not host.namespace:
                continue
            _keygen(host.root / "host_key")
            key_type, key = (host.root / "host_key.pub").read_text().split()[:2]
            known.append(f"{host.address} {key_type} {key}")
            _start_sshd(host, authorized)
        (ssh_dir / "known_hosts").write_text("\n".join(known) + "\n")
        config = ssh_dir / "config"
        config.write_text("\n".join([
            "Host *",
            f"  IdentityFile {ssh_dir / 'id_ed25519'}",
            "  IdentitiesOnly yes",
            f"  UserKnownHostsFile {ssh_dir / 'known_hosts'}",
            "  GlobalKnownHostsFile /dev/null",
            "  User root",
            "",
        ]))
        yield NetnsHosts(hosts, home, config, switch)
    finally:
        for namespace in reversed(made):
            _kill_namespace(namespace)
        for host in hosts.values():
            if host.sshd is not None:
                with contextlib.suppress(Exception):
                    host.sshd.wait(timeout=5)


@pytest.fixture
def netns_required() -> None:
    """Skip (locally) or fail (in CI) when network namespaces cannot be made."""
    need_peer(have_netns(), "ip (iproute2), nsenter (util-linux), sshd (openssh-server), ssh (openssh-client), run as root")
