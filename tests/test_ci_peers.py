"""CI installs every Debian peer the tests use: a test that names a program, file or module that no
package on .ci/run's apt-get line gives fails here, on any machine, even one where the package was
installed by hand (the way rosbash and rospack-tools once went missing from .ci/run).
"""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path

import pytest

from debian_peers import (
    BASE_COMMANDS, BASE_FILES, COMMANDS, FILES, GENERATED_MODULES, MODULES, NAMED_NOT_READ, OPTIONAL_COMMANDS,
)

TESTS = Path(__file__).resolve().parent
CI = TESTS.parent / ".ci"

#: Calls whose first argument, when a list literal, is an argv: its first string is a program.
ARGV_CALLS = frozenset({"run", "Popen", "check_output", "check_call", "call", "run_tool", "spawn"})
IMPORT_LINE = re.compile(r"^\s*(?:import\s+([\w.]+(?:\s*,\s*[\w.]+)*)|from\s+([\w.]+)\s+import\b)", re.M)


def installed_by_ci() -> set[str]:
    """The package names on .ci/run's ``apt-get install`` command (its continuation lines joined)."""
    command = re.search(r"^apt-get install ((?:.*\\\n)*.*)$", (CI / "run").read_text(), re.M)
    assert command is not None, ".ci/run has no apt-get install command"
    words = command.group(1).replace("\\\n", " ").split()
    return {w for w in words if not w.startswith("-") and not w.startswith(">")}


def test_ci_run_installs_the_ros_core_peers() -> None:
    assert {"ros-core", "python3-rospy", "python3-rosbag", "rosbash", "libroscpp-dev"} <= installed_by_ci()


def _sources() -> list[Path]:
    return sorted(p for p in TESTS.rglob("*.py") if "launch_corpus" not in p.parts)


def _call_name(node: ast.Call) -> str:
    func = node.func
    return func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""


class PeerScan(ast.NodeVisitor):
    """Collects the programs, /usr files and system-Python imports one test file names."""

    def __init__(self) -> None:
        self.commands: set[str] = set()
        self.files: set[str] = set()
        self.modules: set[str] = set()

    def visit_Call(self, node: ast.Call) -> None:
        name = _call_name(node)
        first = node.args[0] if node.args else None
        if name == "which" and isinstance(first, ast.Constant) and isinstance(first.value, str):
            self.commands.add(first.value)
        if name in ARGV_CALLS and isinstance(first, ast.List) and first.elts:
            program = first.elts[0]
            if isinstance(program, ast.Constant) and isinstance(program.value, str):
                self.commands.add(program.value)
        self.generic_visit(node)

    def visit_Constant(self, node: ast.Constant) -> None:
        if isinstance(node.value, str):
            text = node.value
            if re.fullmatch(r"/(usr|opt|bin|sbin|etc)/[\w./+-]+", text):
                self.files.add(text)
            for names, source in IMPORT_LINE.findall(text):
                for module in (names.split(",") if names else [source]):
                    self.modules.add(module.strip().split(".")[0])


def scan() -> PeerScan:
    """What every test source names."""
    found = PeerScan()
    for path in _sources():
        found.visit(ast.parse(path.read_text(), str(path)))
    for path in (TESTS / "peers").glob("rospy_*.py"):  # run by the system Python
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                found.modules.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.module:
                found.modules.add(node.module.split(".")[0])
    return found


def test_every_peer_package_is_installed_by_ci() -> None:
    packages = installed_by_ci()
    missing = {name: pkg for table in (COMMANDS, FILES, MODULES) for name, pkg in table.items() if pkg not in packages}
    assert not missing, f"tests use these, but .ci/run's apt-get line does not install their packages: {missing}"


def test_every_program_a_test_names_comes_from_a_listed_package() -> None:
    programs = {c for c in scan().commands if not c.startswith("/")}
    unknown = programs - COMMANDS.keys() - BASE_COMMANDS - OPTIONAL_COMMANDS
    assert not unknown, f"tests run {sorted(unknown)}: name their Debian packages in tests/debian_peers.py"


def test_every_system_file_a_test_names_comes_from_a_listed_package() -> None:
    found = scan()
    files = found.files | {c for c in found.commands if c.startswith("/")}
    unknown = files - FILES.keys() - BASE_FILES - NAMED_NOT_READ
    assert not unknown, f"tests read {sorted(unknown)}: name their Debian packages in tests/debian_peers.py"


def test_every_module_a_system_python_script_imports_comes_from_a_listed_package() -> None:
    def available_without_ros(module: str) -> bool:
        return (module in sys.stdlib_module_names or module == "rostui" or module in GENERATED_MODULES
                or find_spec(module) is not None)

    unknown = {m for m in scan().modules if m not in MODULES and not available_without_ros(m)}
    assert not unknown, f"tests import {sorted(unknown)} under the system Python: add them to tests/debian_peers.py"


def _dpkg_owner(path: str) -> str | None:
    r = subprocess.run(["dpkg", "-S", path], capture_output=True, text=True)
    return r.stdout.split(":")[0].strip() if r.returncode == 0 else None


@pytest.mark.parametrize("table", ["COMMANDS", "FILES"])
def test_the_table_names_the_package_dpkg_says(table: str) -> None:
    """Where a peer is installed here, the table's package is the one that owns it."""
    if shutil.which("dpkg") is None:
        pytest.skip("not a Debian machine")
    entries = COMMANDS if table == "COMMANDS" else FILES
    wrong = {}
    for name, package in entries.items():
        path = shutil.which(name) if table == "COMMANDS" else name
        if path is None or not Path(path).exists():
            continue
        owner = _dpkg_owner(path) or _dpkg_owner(str(Path(path).resolve()))
        if owner is not None and owner != package:
            wrong[name] = (package, owner)
    assert not wrong, f"tests/debian_peers.py names the wrong packages (table, dpkg): {wrong}"
