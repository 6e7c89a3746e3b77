"""What every command shares: one-line errors, exit codes, master calls, JSON output."""

from __future__ import annotations

import sys

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, Callable, Iterable, NoReturn


def fail(message: str, code: int = 1, hint: str | None = None) -> NoReturn:
    """Print one error line (and a ``did you mean …?`` hint line) to stderr and exit with ``code``.

    SystemExit: no Typer needed.
    """
    print(message, file=sys.stderr, flush=True)
    if hint:
        print(hint, file=sys.stderr, flush=True)
    raise SystemExit(code)


def interrupted(exc: BaseException) -> bool:
    """Whether ``exc`` is Ctrl-C, or an error raised because Ctrl-C came in its middle.

    A KeyboardInterrupt that lands while a module is being imported can come out as that import's
    failure (numpy re-raises it as ``ImportError: numpy._core.multiarray failed to import``), with
    the interrupt only in its chain of causes.
    """
    seen: set[int] = set()
    current: BaseException | None = exc
    while current is not None and id(current) not in seen:
        if isinstance(current, KeyboardInterrupt):
            return True
        seen.add(id(current))
        current = current.__cause__ or current.__context__
    return False


def exit_if_interrupted(exc: BaseException) -> None:
    """End with code 130 and no traceback, as a shell's Ctrl-C, when ``exc`` is one (:func:`interrupted`)."""
    if interrupted(exc):
        raise SystemExit(130) from None


def suggestion(name: str, candidates: Callable[[], Iterable[str]]) -> str | None:
    """``did you mean …?`` for a misspelt ``name`` among ``candidates()`` (the master's names); None if none is close.

    Asked only on the error path; a failing master call just means no hint.
    """
    from rostui.tools.suggest import did_you_mean

    try:
        names = list(candidates())
    except (Exception, SystemExit):
        return None
    return did_you_mean(name, names)


def master_uri() -> str:
    """The master URI the command uses (ROS_MASTER_URI or the ROS default)."""
    from rostui.core.masteruri import master_uri_from_env

    return master_uri_from_env()


def master_call(caller_id: str, method: str, *args: Any) -> Any:
    """Call the master and unwrap ``[code, msg, value]``; exit with one clear line on failure.

    No master: ``ERROR: Unable to communicate with master at <uri>``.  A
    refusal (code != 1) raises RosApiError for the caller to word.
    """
    from rostui.core.xmlrpc import XmlRpcConnectionError, call_sync, ros_result

    uri = master_uri()
    try:
        return ros_result(call_sync(uri, method, caller_id, *args, timeout=10.0))
    except XmlRpcConnectionError:
        from rostui.core.master_errors import unreachable_text  # only on the way out: not on a quick command's start

        fail(f"ERROR: {unreachable_text(uri)}")


def master_caller(caller_id: str) -> Callable[..., Any]:
    """``call(method, *args)`` against the master with a tool's caller id (see master_call)."""
    return lambda method, *args: master_call(caller_id, method, *args)


def write_output(file: str, text: str) -> None:
    """Write *text* to *file* (``-``: stdout); one ``ERROR: cannot write`` line and exit 1 when it cannot be."""
    if file == "-":
        sys.stdout.write(text)
        return
    try:
        with open(file, "w", encoding="utf-8") as out:
            out.write(text)
    except OSError as exc:
        fail(f"ERROR: cannot write [{file}]: {exc.strerror or exc}")


def print_json(value: Any) -> None:
    """Write ``value`` as indented JSON on stdout (``--json`` output)."""
    import json

    print(json.dumps(value, indent=2, sort_keys=False, default=str))


JSON_OPTION_HELP = "Print machine-readable JSON instead of ROS's text."


def examples(*items: tuple[str, str]) -> str:
    """A ``--help`` epilog: ``Examples:``, then each ``(what, command)`` as a shell comment and its command line.

    Keep each line within 78 columns, so that it is not wrapped at 80 (tests/test_cli_help.py checks);
    Typer renders the epilog as Rich markup, so a ``[`` followed by a letter must be written ``\\[``.
    """
    return "Examples:\n" + "\n".join(f"# {what}\n{command}" for what, command in items)
