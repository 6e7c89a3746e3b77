"""What the dynamic_reconfigure tests share: dynamic_reconfigure's own test server, Debian's side of it, and a
clean environment for it.

Sources and licences of the real scripts: tests/python_compat/real/SOURCES.md.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import REPO, SYSTEM_PYTHON, need_peer, wait_until
from rospy_scripts import Running, script_command

REAL = REPO / "tests" / "python_compat" / "real"
DR = REAL / "dynamic_reconfigure"
DEBIAN_DYNPARAM = Path("/usr/lib/dynamic_reconfigure/dynparam")
DEBIAN_GENERATOR_DIR = Path("/usr/share/dynamic_reconfigure")
NODE = "/dynamic_reconfigure_test_server"


def need_debian_dynamic_reconfigure() -> None:
    """Debian's dynamic_reconfigure: its Python modules, dynparam, and the package files dynparam and the
    generator read."""
    imports = subprocess.run([SYSTEM_PYTHON, "-c", "import dynamic_reconfigure.server, dynamic_reconfigure.client, "
                              "dynamic_reconfigure.cfg.TestConfig"], capture_output=True)
    need_peer(imports.returncode == 0 and DEBIAN_DYNAMIC_FILES_PRESENT(),
              "dynamic_reconfigure (Debian python3-dynamic-reconfigure, libdynamic-reconfigure-config-init-mutex-dev)")


def DEBIAN_DYNAMIC_FILES_PRESENT() -> bool:  # noqa: N802 (reads as the condition it is)
    return DEBIAN_DYNPARAM.is_file() and (DEBIAN_GENERATOR_DIR / "templates" / "ConfigType.py.template").is_file()


def clean_env(ros_env: dict[str, str]) -> dict[str, str]:
    """The test's ROS environment without rostui python's own choices."""
    return {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}


def wait_for_services(env: dict[str, str], *names: str) -> None:
    """Wait until the master lists every service in *names*."""
    from rostui.core.xmlrpc import call_sync

    def listed() -> bool:
        services = {name for name, _ in call_sync(env["ROS_MASTER_URI"], "getSystemState", "/test")[2][2]}
        return services.issuperset(names)

    wait_until(listed, f"services {names}")


def forget_parameters(env: dict[str, str], *namespaces: str) -> None:
    """Delete what a server left on the parameter server (a new server starts from those values)."""
    from rostui.core.xmlrpc import call_sync

    for ns in namespaces:
        call_sync(env["ROS_MASTER_URI"], "deleteParam", "/test", ns)


def start_server(side: str, env: dict[str, str], log: Path, script: str = "testserver.py",
                 namespaces: tuple[str, ...] = (NODE,)) -> Running:
    """dynamic_reconfigure's test server, named as its client expects, once its services are on the master."""
    server = Running(script_command(side, DR / "test" / script, f"__name:={NODE[1:]}"), env, log)
    try:
        wait_for_services(env, *(f"{ns}/set_parameters" for ns in namespaces))
    except AssertionError:
        raise AssertionError(f"the {side} server did not offer its services; it printed:\n{server.interrupt()}")
    return server
