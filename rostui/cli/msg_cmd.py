"""`rostui msg`: Message types: show, list, md5, package (like `rosmsg`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import typer

from rostui.cli.common import JSON_OPTION_HELP
from rostui.cli.complete import complete_msg_types, complete_packages, complete_srv_types

if TYPE_CHECKING:
    from rostui.tools.msgtypes import Kind

CONTEXT = {"help_option_names": ["-h", "--help"]}

msg_app = typer.Typer(name="msg", help="Message types: show, list, md5, package (like `rosmsg`).", no_args_is_help=True, context_settings=CONTEXT)


srv_app = typer.Typer(name="srv", help="Service types: show, list, md5, package (like `rossrv`).",
                      no_args_is_help=True, context_settings=CONTEXT)


def _show(kind: Kind, type_name: str, raw: bool, as_json: bool) -> None:
    import sys

    from rostui.cli.common import fail, print_json
    from rostui.tools.msgtypes import TypeLookupError, show, show_json

    try:
        if as_json:
            print_json(show_json(kind, type_name))
        else:
            sys.stdout.write(show(kind, type_name, raw))
    except TypeLookupError as exc:
        fail(exc.message, exc.code)


def _list(kind: Kind, as_json: bool) -> None:
    from rostui.cli.common import print_json
    from rostui.tools.msgtypes import list_types

    names = list_types(kind)
    if as_json:
        print_json(names)
    else:
        for name in names:
            print(name)


def _md5(kind: Kind, type_name: str) -> None:
    import sys

    from rostui.cli.common import fail
    from rostui.tools.msgtypes import TypeLookupError, md5

    try:
        out, notice = md5(kind, type_name)
    except TypeLookupError as exc:
        fail(exc.message, exc.code)
    sys.stdout.write(out)
    if notice:
        print(notice, file=sys.stderr)


def _package(kind: Kind, package: str, single_line: bool, as_json: bool) -> None:
    from rostui.cli.common import fail
    from rostui.tools.msgtypes import TypeLookupError, package_types

    try:
        names = package_types(kind, package)
    except TypeLookupError as exc:
        fail(exc.message, exc.code)
    _print_names(names, single_line, as_json)


def _packages(kind: Kind, single_line: bool, as_json: bool) -> None:
    from rostui.tools.msgtypes import packages_with_types

    _print_names(packages_with_types(kind), single_line, as_json)


def _print_names(names: list[str], single_line: bool, as_json: bool) -> None:
    """A list of names as JSON, on one line (``-s``) or one per line, as rosmsg prints them."""
    if as_json:
        from rostui.cli.common import print_json

        print_json(names)
    elif single_line:
        print(" ".join(names))
    else:
        print("\n".join(names))


def _add_commands(app: typer.Typer, kind: Kind) -> None:
    """The same five commands for messages and services."""
    what = "message" if kind == "msg" else "service"
    tool = "rosmsg" if kind == "msg" else "rossrv"
    completer = complete_msg_types if kind == "msg" else complete_srv_types

    @app.command("show")
    def show_cmd(
        type_name: str = typer.Argument(..., metavar="TYPE", help=f"{what.capitalize()} type (pkg/Name, or Name to search every package).",
                                        autocompletion=completer),
        raw: bool = typer.Option(False, "-r", "--raw", help="Show the definition text as written, with comments."),
        as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP),
    ) -> None:
        _show(kind, type_name, raw, as_json)

    show_cmd.__doc__ = f"Show the fields of a {what} type (like `{tool} show`)."

    @app.command("info", hidden=True)
    def info_cmd(
        type_name: str = typer.Argument(..., metavar="TYPE", autocompletion=completer),
        raw: bool = typer.Option(False, "-r", "--raw"),
        as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP),
    ) -> None:
        _show(kind, type_name, raw, as_json)

    info_cmd.__doc__ = f"Alias for `show` (like `{tool} info`)."

    @app.command("list")
    def list_cmd(as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP)) -> None:
        _list(kind, as_json)

    list_cmd.__doc__ = f"List every {what} type of every package (like `{tool} list`)."

    @app.command("md5")
    def md5_cmd(
        type_name: str = typer.Argument(..., metavar="TYPE", autocompletion=completer),
    ) -> None:
        _md5(kind, type_name)

    md5_cmd.__doc__ = f"Print the md5sum of a {what} type (like `{tool} md5`)."

    @app.command("package")
    def package_cmd(
        package: str = typer.Argument(..., metavar="PACKAGE", help="Package name.", autocompletion=complete_packages),
        single_line: bool = typer.Option(False, "-s", help="All types on one line."),
        as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP),
    ) -> None:
        _package(kind, package, single_line, as_json)

    package_cmd.__doc__ = f"List the {what} types of a package (like `{tool} package`)."

    @app.command("packages")
    def packages_cmd(
        single_line: bool = typer.Option(False, "-s", help="All packages on one line."),
        as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP),
    ) -> None:
        _packages(kind, single_line, as_json)

    packages_cmd.__doc__ = f"List the packages that define {what} types (like `{tool} packages`)."


_add_commands(msg_app, "msg")
_add_commands(srv_app, "srv")


def register(app: typer.Typer) -> None:
    """Add ``rostui msg ...`` and ``rostui srv ...``."""
    app.add_typer(msg_app, name="msg")
    app.add_typer(srv_app, name="srv")
