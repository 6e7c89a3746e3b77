"""`rostui param`: Parameters: list, get, set, delete, dump, load (like `rosparam`)."""

from __future__ import annotations

from typing import Any, NoReturn, Optional

import typer

from rostui.cli.common import JSON_OPTION_HELP as _JSON_HELP
from rostui.cli.common import examples, master_caller
from rostui.cli.complete import complete_params

CONTEXT = {"help_option_names": ["-h", "--help"]}

param_app = typer.Typer(name="param", help="Parameters: list, get, set, delete, dump, load (like `rosparam`).", no_args_is_help=True, context_settings=CONTEXT)

CALLER = "/rosparam"


def _resolve(name: str) -> str:
    from rostui.tools.param import script_resolve

    return script_resolve(name)


def _fail(exc: Exception, hint: str | None = None) -> NoReturn:
    from rostui.cli.common import fail

    fail(str(exc), hint=hint)


def _param_hint(key: str) -> str | None:
    """``did you mean …?`` among the parameters and namespaces the master holds."""
    from rostui.cli.common import suggestion
    from rostui.tools.suggest import with_namespaces

    return suggestion(key, lambda: with_namespaces(master_caller(CALLER)("getParamNames")))


@param_app.command("list")
def list_command(
    namespace: Optional[str] = typer.Argument(None, metavar="NAMESPACE", help="Only names under this namespace.",
                                              autocompletion=complete_params),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """List parameter names (like `rosparam list`)."""
    from rostui.tools.param import list_names

    ns = _resolve(namespace) if namespace else None
    found = list_names(master_caller(CALLER)("getParamNames"), ns)
    if json_out:
        from rostui.cli.common import print_json

        print_json(found)
        return
    print("\n".join(found))


@param_app.command("get")
def get_command(
    name: str = typer.Argument(..., metavar="NAME", help="Parameter or namespace.", autocompletion=complete_params),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """Print a parameter's value as YAML (like `rosparam get`)."""
    from rostui.core.xmlrpc import RosApiError

    key = _resolve(name)
    try:
        value = master_caller(CALLER)("getParam", key)
    except RosApiError:
        from rostui.cli.common import fail

        fail(f"ERROR: Parameter [{key}] is not set", hint=_param_hint(key))
    if json_out:
        import base64

        from rostui.cli.common import print_json

        print_json(_jsonable(value, base64))
        return
    from rostui.tools.param import format_get

    print(format_get(value))


def _jsonable(value: Any, base64: Any) -> Any:
    if isinstance(value, dict):
        return {k: _jsonable(v, base64) for k, v in value.items()}
    if isinstance(value, list):
        return [_jsonable(v, base64) for v in value]
    data = getattr(value, "data", None)
    if isinstance(data, bytes):
        return base64.b64encode(data).decode("ascii")
    return value


SET_EXAMPLES = examples(
    ("a yellow background, seen after `rostui service call /clear` (chapter 7)",
     "rostui param set /background_r 255"),
    ("a dictionary sets every key below the namespace",
     "rostui param set /duck_colors '{huey: red, dewey: blue, louie: green}'"),
    ("negative numbers after -- (otherwise they read as options)", "rostui param set -- /offset -3"),
    ("a string that looks like a number", "rostui param set /version \"'1.0'\""),
)


@param_app.command("set", epilog=SET_EXAMPLES)
def set_command(
    name: str = typer.Argument(..., metavar="NAME", help="Parameter (or namespace, for a YAML dictionary).",
                               autocompletion=complete_params),
    value: Optional[str] = typer.Argument(None, metavar="VALUE", help="The value, typed as YAML."),
    textfile: Optional[str] = typer.Option(None, "-t", "--textfile", metavar="FILE", help="Set to the contents of a text file."),
    verbose: bool = typer.Option(False, "-v", help="Print what is set."),
) -> None:
    """Set a parameter; the value is YAML-typed, a dictionary merges into the namespace (like `rosparam set`)."""
    from rostui.tools.param import ParamError, apply_assignments, check_marshallable, leaf_assignments, set_param

    key = _resolve(name)
    call = master_caller(CALLER)
    try:
        if textfile is not None:
            if value is not None:
                _fail(ParamError("ERROR: give either a value or -t FILE, not both"))
            from rostui.tools.param import read_param_file

            text = read_param_file(textfile)
            check_marshallable(key, text)
            apply_assignments(call, leaf_assignments(key, text))
        elif value is None:
            _fail(ParamError("ERROR: rosparam set requires a parameter name and a value"))
        else:
            set_param(call, key, value)
    except ParamError as exc:
        _fail(exc)
    if verbose:
        print(f"set parameter [{key}]")


@param_app.command("delete")
def delete_command(
    name: str = typer.Argument(..., metavar="NAME", help="Parameter or namespace to delete.", autocompletion=complete_params),
    verbose: bool = typer.Option(False, "-v", help="Print what is deleted."),
) -> None:
    """Delete a parameter or a whole namespace (like `rosparam delete`)."""
    from rostui.tools.param import ParamError, delete_param

    key = _resolve(name)
    try:
        delete_param(master_caller(CALLER), key)
    except ParamError as exc:
        _fail(exc, _param_hint(key))
    if verbose:
        print(f"deleted parameter [{key}]")


@param_app.command("dump")
def dump_command(
    file: str = typer.Argument(..., metavar="FILE", help="File to write ('-' for stdout)."),
    namespace: Optional[str] = typer.Argument(None, metavar="NAMESPACE", help="Namespace to dump (default /).",
                                              autocompletion=complete_params),
    verbose: bool = typer.Option(False, "-v", help="Print what is dumped."),
) -> None:
    """Write a namespace's parameters to a YAML file (like `rosparam dump`)."""
    from rostui.core.xmlrpc import RosApiError
    from rostui.tools.param import format_dump

    key = _resolve(namespace or "/")
    try:
        value = master_caller(CALLER)("getParam", key)
    except RosApiError:
        from rostui.cli.common import fail

        fail(f"ERROR: Parameter [{key}] is not set")
    text = format_dump(value)
    if verbose:
        print(f"dumping namespace [{key}] to file [{file}]")
    from rostui.cli.common import write_output

    write_output(file, text)


@param_app.command("load")
def load_command(
    file: str = typer.Argument(..., metavar="FILE", help="YAML file to load ('-' for stdin)."),
    namespace: Optional[str] = typer.Argument(None, metavar="NAMESPACE", help="Namespace to load into (default /).",
                                              autocompletion=complete_params),
    verbose: bool = typer.Option(False, "-v", help="Print what is loaded."),
) -> None:
    """Load parameters from a YAML file, merging into the namespace (like `rosparam load`)."""
    from rostui.tools.param import ParamError, apply_assignments, load_text, read_param_file

    ns = _resolve(namespace or "/")
    try:
        assignments = load_text(read_param_file(file), ns, file)
    except ParamError as exc:
        _fail(exc)
    apply_assignments(master_caller(CALLER), assignments)
    if verbose:
        for key, _ in assignments:
            print(f"set parameter [{key}]")


def register(app: typer.Typer) -> None:
    """Add ``rostui param ...``."""
    app.add_typer(param_app, name="param")
