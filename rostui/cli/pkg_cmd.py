"""`rostui pkg`: Packages: list, find, ls (like `rospack` / `rosls`)."""

from __future__ import annotations

import typer

from rostui.cli.common import JSON_OPTION_HELP
from rostui.cli.complete import complete_packages

CONTEXT = {"help_option_names": ["-h", "--help"]}

pkg_app = typer.Typer(name="pkg", help="Packages: list, find, ls (like `rospack` / `rosls`).", no_args_is_help=True, context_settings=CONTEXT)


@pkg_app.command("list")
def list_cmd(as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP)) -> None:
    """List every package and its directory (like `rospack list`)."""
    from rostui.cli.common import print_json
    from rostui.core.packages import list_packages
    from rostui.tools.pkg import list_lines

    if as_json:
        print_json({name: str(path) for name, path in sorted(list_packages().items())})
        return
    for line in list_lines():
        print(line)


@pkg_app.command("find")
def find_cmd(package: str = typer.Argument(..., metavar="PACKAGE", help="Package name.", autocompletion=complete_packages)) -> None:
    """Print the directory of a package (like `rospack find`)."""
    from rostui.cli.common import fail
    from rostui.tools.pkg import PackageToolError, find

    try:
        print(find(package))
    except PackageToolError as exc:
        fail(exc.message, exc.code)


@pkg_app.command("ls")
def ls_cmd(
    path: str = typer.Argument(..., metavar="PACKAGE[/SUBDIR]", help="A package, optionally followed by a path inside it.",
                               autocompletion=complete_packages),
    as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP),
) -> None:
    """List a package directory or a folder inside it (like `rosls`)."""
    import shutil
    import sys

    from rostui.cli.common import fail, print_json
    from rostui.tools.pkg import PackageToolError, columns, ls_entries, ls_target

    try:
        names = ls_entries(ls_target(path))
    except PackageToolError as exc:
        fail(exc.message, exc.code)
    if as_json:
        print_json(names)
    elif sys.stdout.isatty():
        for line in columns(names, shutil.get_terminal_size().columns):
            print(line)
    else:
        for name in names:
            print(name)


def register(app: typer.Typer) -> None:
    """Add ``rostui pkg ...``."""
    app.add_typer(pkg_app, name="pkg")
