"""Run a script's :class:`~rostui.compat.launcher.Plan` in this interpreter instead of exec'ing a new one.

``rostui python SCRIPT`` used to replace itself with ``python SCRIPT``: a second
interpreter start and a second import of what the launcher had already
imported (a third of a talker's start-up). When the plan's command is this very
Python with a script file, :func:`run_here` makes this interpreter look as that
one would at the script's first line: the plan's environment, ``sys.argv``,
``sys.path`` (the script's folder, then the plan's ``PYTHONPATH``), rostui's
``sitecustomize`` run as that interpreter would run it (the one it hides ran
when this interpreter started), and a fresh ``__main__``. An exception the script does not catch is printed from the
script's own frames down, as Python prints it; exit status and Ctrl-C are
Python's own, since the exception leaves this interpreter the same way.
"""

from __future__ import annotations

import builtins
import os
import sys
import types

TYPE_CHECKING = False
if TYPE_CHECKING:
    from .launcher import Plan

__all__ = ["can_run_here", "run_here"]


def can_run_here(how: Plan) -> bool:
    """Whether *how* runs a Python source file with this Python and no interpreter options we would lose."""
    flags = sys.flags
    return (len(how.argv) >= 2 and how.argv[0] == sys.executable and not how.argv[1].startswith("-")
            and not (flags.isolated or flags.ignore_environment or flags.no_site)
            and os.path.isfile(how.argv[1]) and _is_source(how.argv[1]))


def _is_source(path: str) -> bool:
    """Whether *path* is source code: not compiled code nor a zip application, which Python also runs."""
    try:
        with open(path, "rb") as file:
            head = file.read(4)
    except OSError:
        return False
    from importlib.util import MAGIC_NUMBER

    if path.endswith(".pyc") or head == MAGIC_NUMBER:
        return False
    import zipimport

    try:
        zipimport.zipimporter(path)
    except zipimport.ZipImportError:
        return True
    return False


def _trimming_hook(code: types.CodeType) -> None:
    """Make the uncaught-exception hook start tracebacks at *code*'s frame (the script's), not ours."""
    previous = sys.excepthook

    def hook(kind: type[BaseException], value: BaseException, tb: types.TracebackType | None) -> None:
        at = tb
        while at is not None and at.tb_frame.f_code is not code:
            at = at.tb_next
        if at is not None:
            value = value.with_traceback(at)  # Python prints the exception's own traceback, not tb
        previous(kind, value, at if at is not None else tb)

    sys.excepthook = hook


def _run_sitecustomize() -> None:
    from importlib.util import module_from_spec, spec_from_file_location

    from . import PYLIB, bootstrap

    spec = spec_from_file_location("sitecustomize", PYLIB / "sitecustomize.py")
    assert spec is not None and spec.loader is not None
    module = module_from_spec(spec)
    bootstrap.hidden_ran = True
    sys.modules["sitecustomize"] = module
    spec.loader.exec_module(module)


def _prepare(how: Plan) -> tuple[types.ModuleType, types.CodeType | None]:
    """Make this interpreter look as *how*'s would at its script's first line; the script's ``__main__`` and code
    (None when it does not compile: Python's message is printed)."""
    script, args = how.argv[1], how.argv[2:]
    for key in [k for k in os.environ if k not in how.env]:
        del os.environ[key]
    os.environ.update(how.env)
    path = os.path.abspath(script)
    extra = [p for p in how.env.get("PYTHONPATH", "").split(os.pathsep) if p]
    sys.path[:] = [os.path.dirname(path), *extra, *[p for p in sys.path[1:] if p not in extra]]
    sys.argv[:] = [script, *args]

    _run_sitecustomize()
    with open(path, "rb") as source:
        text = source.read()
    main = types.ModuleType("__main__")
    try:
        code = compile(text, path, "exec", dont_inherit=True)
    except (SyntaxError, ValueError) as exc:  # printed as Python prints a script it cannot compile: no traceback
        sys.excepthook(type(exc), exc.with_traceback(None), None)
        return main, None
    from importlib.machinery import SourceFileLoader

    main.__dict__.update(__file__=path, __cached__=None, __loader__=SourceFileLoader("__main__", path),
                         __spec__=None, __builtins__=builtins)
    sys.modules["__main__"] = main
    _trimming_hook(code)
    return main, code


def run_here(how: Plan, *, collecting: bool | None = None) -> int:
    """Run *how*'s script here (see the module's docstring); 0 when it returns, else its exception propagates.

    *collecting* is what :func:`~rostui.compat.deferred.pause_gc` returned when the caller paused the garbage
    collector for its start: the collector runs again (everything imported so far frozen out of its reach)
    just before the script's first line, and ``None`` means the caller did not pause it."""
    try:
        main, code = _prepare(how)
    finally:
        if collecting is not None:
            from .deferred import resume_gc

            resume_gc(collecting, freeze=True)
    if code is None:
        return 1
    exec(code, main.__dict__)  # noqa: S102 (the user's script, as python SCRIPT would run it)
    return 0
