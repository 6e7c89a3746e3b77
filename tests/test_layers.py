"""The layers of docs/architecture.md hold: every import in rostui/ (lazy ones inside functions too) points down.

    cli  >  turtlesim  >  apps  >  launch, models  >  compat  >  tools, client  >  core

core is the ROS 1 runtime and imports nothing above it; no layer below the apps imports Textual, Typer or Rich.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from conftest import REPO

PACKAGE = REPO / "rostui"
UI_LIBRARIES = frozenset({"textual", "typer", "rich"})

#: What each layer may import of rostui (besides itself).
MAY_IMPORT: dict[str, frozenset[str]] = {
    "core": frozenset(),
    "tools": frozenset({"core"}),
    "models": frozenset({"core", "tools"}),
    "launch": frozenset({"core", "tools", "compat"}),
    "client": frozenset({"core"}),
    "compat": frozenset({"core", "client", "tools"}),
    "apps": frozenset({"core", "tools", "models", "launch"}),
    "turtlesim": frozenset({"core", "tools", "models", "apps", "client"}),
    "cli": frozenset({"core", "tools", "models", "launch", "apps", "turtlesim", "client", "compat", "version"}),
}
#: Layers that must run without a terminal library.
SCREEN_FREE = frozenset({"core", "tools", "models", "launch", "client", "compat"})


def _layer(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "rostui":
        return None
    if len(parts) == 1 or parts[1].startswith("__"):
        return "version"  # the package itself: rostui.__version__
    return parts[1]


def _imports(path: Path) -> list[tuple[int, str]]:
    """Every module ``path`` imports, absolute, with its line (relative imports resolved)."""
    module = ".".join(path.relative_to(REPO).with_suffix("").parts)
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            if base == "rostui":  # `from rostui import client`: the module named
                found += [(node.lineno, f"rostui.{alias.name}") for alias in node.names]
            else:
                found.append((node.lineno, base))
    return found


def _violations() -> list[str]:
    out = []
    for path in sorted(PACKAGE.rglob("*.py")):
        own = _layer(".".join(path.relative_to(REPO).with_suffix("").parts))
        if own in (None, "version", "__main__"):
            continue
        for line, target in _imports(path):
            where = f"{path.relative_to(REPO)}:{line}"
            top = target.split(".")[0]
            if top in UI_LIBRARIES and own in SCREEN_FREE:
                out.append(f"{where}: {own} imports {target}")
            layer = _layer(target)
            if layer is not None and layer != own and layer not in MAY_IMPORT[own]:
                out.append(f"{where}: {own} imports {target} (a layer above it)")
    return out


#: Modules that change a terminal's modes: the commands' business (cli, apps), never the runtime's.
TERMINAL_MODES = frozenset({"termios", "tty"})


def _imported_tops(path: Path) -> set[str]:
    return {target.split(".")[0] for _line, target in _imports(path)}


def test_core_leaves_terminals_and_signals_to_the_commands() -> None:
    """No terminal modes anywhere in core; no signal handling in core/bag (playing and recording are tools/bag)."""
    core = PACKAGE / "core"
    moded = [str(p.relative_to(REPO)) for p in sorted(core.rglob("*.py")) if _imported_tops(p) & TERMINAL_MODES]
    signalled = [str(p.relative_to(REPO)) for p in sorted((core / "bag").rglob("*.py"))
                 if "signal" in _imported_tops(p)]
    assert (moded, signalled) == ([], [])


def test_every_layer_is_known() -> None:
    layers = {p.stem if p.is_file() else p.name for p in PACKAGE.iterdir()
              if (p.suffix == ".py" or (p.is_dir() and (p / "__init__.py").exists()))}
    assert layers - {"__init__", "__main__"} == set(MAY_IMPORT) - {"version"}


def test_imports_point_down_the_layers() -> None:
    assert _violations() == []


@pytest.mark.parametrize("source,expected", [
    ("from rostui.apps.graph.app import GraphApp\n", "core imports rostui.apps.graph.app (a layer above it)"),
    ("def f():\n    import textual\n", "core imports textual"),
])
def test_a_wrong_import_is_found(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, source: str, expected: str) -> None:
    """The check sees module-level and lazy imports (it would catch the mistakes it exists for)."""
    fake = tmp_path / "rostui" / "core"
    fake.mkdir(parents=True)
    (fake / "bad.py").write_text(source)
    monkeypatch.setattr(__import__(__name__), "REPO", tmp_path)
    monkeypatch.setattr(__import__(__name__), "PACKAGE", tmp_path / "rostui")
    assert [v.split(": ", 1)[1] for v in _violations()] == [expected]


def test_every_folder_of_code_is_a_package() -> None:
    """setuptools packages only folders with an ``__init__.py``: one without it works in a checkout, not installed."""
    folders = {p.parent for p in PACKAGE.rglob("*.py")}
    assert sorted(str(f.relative_to(REPO)) for f in folders if not (f / "__init__.py").exists()) == []


def test_every_app_and_command_group_is_registered_in_one_place() -> None:
    """Each command module is a group of the registry (or registered by its group's module); each app package and
    the turtlesim have a row (the form app two: `publish` and `call` open it), and each row's words are a command
    of ``rostui``, no two rows the same."""
    import typer

    from rostui.cli.main import app
    from rostui.cli.registry import APPS, COMMAND_GROUPS

    modules = {p.stem.removesuffix("_cmd") for p in (PACKAGE / "cli").glob("*_cmd.py")}
    registered_by_group = {"bag_view": "bag"}
    assert modules - set(registered_by_group) == set(COMMAND_GROUPS)
    packages = {f"rostui.apps.{p.parent.name}" for p in (PACKAGE / "apps").glob("*/app.py")} | {"rostui.turtlesim"}
    shared = {"rostui.apps.form": 2}
    assert sorted(a.package for a in APPS) == sorted(p for p in packages for _ in range(shared.get(p, 1)))
    assert len({a.words for a in APPS}) == len(APPS)
    root = typer.main.get_command(app)
    for entry in APPS:
        command = root
        for word in entry.words:
            command = command.get_command(None, word)  # type: ignore[attr-defined, arg-type]
            assert command is not None, entry.name
