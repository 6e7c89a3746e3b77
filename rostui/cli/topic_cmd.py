"""`rostui topic`: Topics: list, info, type, find, echo, hz, bw, pub (like `rostopic`).

Commands parse, call :mod:`rostui.tools.topic` and print; everything
heavier than Typer is imported inside the command that needs it, so
``rostui topic list`` starts fast.
"""

from __future__ import annotations

import sys
from typing import Any, Callable, Coroutine, Iterable, List, NoReturn, Optional

import typer

from rostui.cli.common import JSON_OPTION_HELP as _JSON_HELP
from rostui.cli.common import examples
from rostui.cli.complete import complete_msg_types as _complete_type
from rostui.cli.complete import complete_topics as _complete_topic

CONTEXT = {"help_option_names": ["-h", "--help"]}

topic_app = typer.Typer(name="topic", help="Topics: list, info, type, find, echo, hz, bw, pub (like `rostopic`).", no_args_is_help=True, context_settings=CONTEXT)



def register(app: typer.Typer) -> None:
    """Add ``rostui topic ...``."""
    app.add_typer(topic_app, name="topic")


# ----------------------------------------------------------------------------- shell completion
# ----------------------------------------------------------------------------- helpers
def _call(method: str, *args: Any) -> Any:
    """A master call as rostopic makes it; no master -> one line, exit 1."""
    from rostui.cli.common import master_call

    return master_call("/rostopic", method, *args)


def _resolve(name: str) -> str:
    from rostui.tools.topic.common import resolve_topic

    try:
        return resolve_topic(name)
    except Exception as e:  # invalid names
        _fail(f"ERROR: invalid topic name [{name}]: {e}")


def _fail(message: str, hint: Optional[str] = None) -> NoReturn:
    from rostui.cli.common import fail

    fail(message, hint=hint)


def _topic_hint(name: str) -> Optional[str]:
    """``did you mean …?`` among the topics someone publishes or subscribes to now."""
    from rostui.cli.common import suggestion
    from rostui.tools.suggest import registered_topics

    return suggestion(name, lambda: registered_topics(_call("getSystemState")))


def _out(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()


def _run_async(coro: Any) -> int:
    """Run a long-running tool; one-line errors for what it reports."""
    import asyncio

    from rostui.core.master_errors import MasterUnreachableError, unreachable_text
    from rostui.tools.topic.common import TopicToolError

    runner: Callable[[Coroutine[Any, Any, int]], int]
    try:
        import uvloop

        runner = uvloop.run
    except ImportError:  # pragma: no cover - uvloop is a dependency
        runner = asyncio.run
    try:
        return runner(coro)
    except MasterUnreachableError as e:
        _fail(f"ERROR: {unreachable_text(e.master_uri)}")
    except TopicToolError as e:
        _fail(f"ERROR: {e}")
    except KeyboardInterrupt:
        return 0
    except BrokenPipeError:
        return 0
    return 0


def _check_master() -> None:
    """Before `topic pub` reads its type, as rostopic does (echo, hz and bw learn it from their first master
    call, in the runner)."""
    _call("getPid")


# ----------------------------------------------------------------------------- master-only commands
@topic_app.command("list")
def list_command(
    namespace: Optional[str] = typer.Argument(None, metavar="NAMESPACE", help="Only topics in this namespace.", autocompletion=_complete_topic),
    verbose: bool = typer.Option(False, "-v", "--verbose", help="List full details about each topic."),
    publishers: bool = typer.Option(False, "-p", help="List only publishers."),
    subscribers: bool = typer.Option(False, "-s", help="List only subscribers."),
    as_json: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """List active topics (like `rostopic list`)."""
    from rostui.tools.topic.listing import format_list, list_json, topic_list

    if publishers and subscribers:
        _fail("ERROR: you may only specify one of -p, -s")
    ns = _resolve(namespace) if namespace else None
    pubs, subs = topic_list(_call)
    if as_json:
        from rostui.cli.common import print_json

        print_json(list_json(pubs, subs, namespace=ns))
        return
    _out(format_list(pubs, subs, verbose=verbose, publishers_only=publishers,
                     subscribers_only=subscribers, namespace=ns))


@topic_app.command("info")
def info_command(
    topic: str = typer.Argument(..., metavar="TOPIC", help="Topic name.", autocompletion=_complete_topic),
    as_json: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """Print type, publishers and subscribers of a topic (like `rostopic info`)."""
    from rostui.tools.topic.common import TopicToolError
    from rostui.tools.topic.listing import format_info, topic_info

    name = _resolve(topic)
    try:
        info = topic_info(_call, name)
    except TopicToolError as e:
        _fail(f"ERROR: {e}", _topic_hint(name))
    if as_json:
        from rostui.cli.common import print_json

        print_json(info)
        return
    _out(format_info(info) + "\n")


@topic_app.command("type")
def type_command(
    topic: str = typer.Argument(..., metavar="TOPIC", help="Topic or field name (/topic/field).", autocompletion=_complete_topic),
    as_json: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """Print the message type of a topic or field (like `rostopic type`)."""
    from rostui.tools.topic.common import TopicToolError
    from rostui.tools.topic.listing import type_text

    name = _resolve(topic)
    try:
        text = type_text(_call, name)
    except TopicToolError as e:
        _fail(str(e), _topic_hint(name))
    if as_json:
        from rostui.cli.common import print_json

        parts = text.split(" ")
        value = {"topic": name, "type": parts[0]}
        if len(parts) == 3:
            value.update(field=parts[1], field_type=parts[2])
        print_json(value)
        return
    _out(text + "\n")


@topic_app.command("find")
def find_command(
    msg_type: str = typer.Argument(..., metavar="TYPE", help="Message type (pkg/Type).", autocompletion=_complete_type),
    as_json: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """List the topics of a message type (like `rostopic find`)."""
    from rostui.tools.topic.listing import find_by_type

    found = find_by_type(_call, msg_type)
    if as_json:
        from rostui.cli.common import print_json

        print_json(found)
        return
    _out("\n".join(found) + "\n")


# ----------------------------------------------------------------------------- node commands
ECHO_EXAMPLES = examples(
    ("print each command the turtle gets (chapter 2)", "rostui topic echo /turtle1/command_velocity"),
    ("one field, five messages, then exit", "rostui topic echo -n 5 /turtle1/pose/x"),
    ("JSON Lines, one message a line, for jq", "rostui topic echo --json /turtle1/pose | jq .theta"),
    ("from a bag file, no master needed", "rostui topic echo -b square.bag /turtle1/pose"),
)


@topic_app.command("echo", epilog=ECHO_EXAMPLES)
def echo_command(
    topic: Optional[str] = typer.Argument(None, metavar="TOPIC", help="Topic, or a field of it (/turtle1/pose/x, /a/b[0]).", autocompletion=_complete_topic),
    bag: Optional[str] = typer.Option(None, "-b", "--bag", metavar="BAGFILE", help="Echo messages from a bag file (.bag or MCAP), no master needed."),
    all_topics: bool = typer.Option(False, "-a", "--all", help="Display all messages in the bag (only with -b)."),
    count: Optional[int] = typer.Option(None, "-n", metavar="COUNT", help="Number of messages to echo."),
    plot: bool = typer.Option(False, "-p", help="Echo in a plotting friendly format (CSV)."),
    noarr: bool = typer.Option(False, "--noarr", help="Exclude arrays."),
    nostr: bool = typer.Option(False, "--nostr", help="Exclude string fields."),
    offset: bool = typer.Option(False, "--offset", help="Display time as offsets from current time."),
    width: Optional[int] = typer.Option(None, "-w", metavar="NUM_WIDTH", help="Fixed width for numeric values."),
    clear: bool = typer.Option(False, "-c", "--clear", help="Clear screen before printing next message."),
    as_json: bool = typer.Option(False, "--json", help="Print each message as one JSON object a line (JSON Lines, "
                                                       "for jq): time as {secs, nsecs}, uint8[] as a list of ints."),
) -> None:
    """Print messages of a topic (like `rostopic echo`); waits until the topic is published, or reads a bag (-b)."""
    from rostui.tools.topic.echo import echo_usage_problem
    from rostui.tools.topic.runners import run_echo

    name = None if all_topics or topic is None else _resolve(topic)
    problem = echo_usage_problem(topic=name, bag=bool(bag), all_topics=all_topics, offset=offset, plot=plot,
                                 clear=clear, width=width, as_json=as_json)
    if problem is not None:
        _fail(f"ERROR: {problem}")
    if bag:
        _echo_bag(bag, name, plot=plot, noarr=noarr, nostr=nostr, count=count, fixed_width=width, clear=clear,
                  as_json=as_json)
    assert name is not None
    raise typer.Exit(_run_async(run_echo(
        name, _out, plot=plot, noarr=noarr, nostr=nostr, offset=offset, count=count,
        fixed_width=width, clear=clear, as_json=as_json)))


def _echo_bag(path: str, topic: Optional[str], **options: Any) -> NoReturn:
    """``echo -b``: print the bag's messages and exit (1 with one line when it cannot be read)."""
    from rostui.tools.topic.bag_echo import echo_bag
    from rostui.tools.topic.common import TopicToolError
    from rostui.tools.topic.echo import EchoFormatter

    formatter = EchoFormatter("", from_bag=True, **options)
    try:
        echo_bag(path, topic, formatter, _out, warn=lambda line: print(line, file=sys.stderr, flush=True))
    except TopicToolError as e:
        _fail(f"ERROR: {e}")
    except (BrokenPipeError, KeyboardInterrupt):
        pass
    raise typer.Exit(0)


@topic_app.command("hz")
def hz_command(
    topics: List[str] = typer.Argument(..., metavar="TOPIC...", help="Topic names.", autocompletion=_complete_topic),
    window: int = typer.Option(-1, "-w", "--window", metavar="WINDOW", help="Window size, in # of messages, for calculating rate."),
) -> None:
    """Print the publishing rate of topics every second (like `rostopic hz`)."""
    from rostui.tools.topic.runners import run_hz

    names = [_resolve(t) for t in topics]
    raise typer.Exit(_run_async(run_hz(names, window, _out)))


@topic_app.command("bw")
def bw_command(
    topic: str = typer.Argument(..., metavar="TOPIC", help="Topic name.", autocompletion=_complete_topic),
    window: Optional[int] = typer.Option(None, "-w", "--window", metavar="WINDOW", help="Window size, in # of messages, for calculating rate."),
) -> None:
    """Print the bandwidth used by a topic every second (like `rostopic bw`)."""
    from rostui.tools.topic.runners import run_bw

    name = _resolve(topic)
    raise typer.Exit(_run_async(run_bw(name, window, _out)))


PUB_EXAMPLES = examples(
    ("1 Hz, values in `rostui msg show` order (chapter 2)",
     "rostui topic pub -r 1 /turtle1/command_velocity turtlesim/Velocity 1 0"),
    ("one YAML dictionary, latched (the default without -r)",
     "rostui topic pub /turtle1/command_velocity turtlesim/Velocity \\\n    '{linear: 0.1, angular: 0.0}'"),
    ("publish once (-1); negative numbers after --, or they read as options",
     "rostui topic pub -1 /turtle1/command_velocity turtlesim/Velocity -- -1 0.5"),
    ("messages from a file in `topic echo` format, at 10 Hz",
     "rostui topic pub -f poses.yaml /turtle1/pose turtlesim/Pose"),
)


@topic_app.command("pub", context_settings={"ignore_unknown_options": True}, epilog=PUB_EXAMPLES)
def pub_command(
    topic: str = typer.Argument(..., metavar="TOPIC", help="Topic name.", autocompletion=_complete_topic),
    msg_type: str = typer.Argument(..., metavar="TYPE", help="Message type (pkg/Type).", autocompletion=_complete_type),
    values: Optional[List[str]] = typer.Argument(None, metavar="[ARGS]...", help="Field values in `msg show` order, or one YAML dict."),
    rate: Optional[float] = typer.Option(None, "-r", "--rate", metavar="RATE", help="Publishing rate (Hz). For -f and stdin input, this defaults to 10."),
    once: bool = typer.Option(False, "-1", "--once", help="Publish one message and exit."),
    file: Optional[str] = typer.Option(None, "-f", "--file", metavar="FILE", help="Read messages from a YAML file (echo format, --- separated)."),
    latch: bool = typer.Option(False, "-l", "--latch", help="Enable latching for -f, -r and piped input (latches the first message)."),
    substitute: bool = typer.Option(False, "-s", "--substitute-keywords", help="With a rate, substitute 'now'/'auto' for each message."),
    verbose: bool = typer.Option(False, "-v", help="Print verbose output."),
) -> None:
    """Publish a message to a topic (like `rostopic pub`); latched unless a rate is given."""
    from rostui.tools.topic.common import TopicToolError, UsageError
    from rostui.tools.topic.pub_args import (
        build_message, message_class, parse_yaml_args, stdin_documents, yaml_documents_from_file,
    )
    from rostui.tools.topic.runners import run_pub

    values = list(values or [])
    if rate is not None:
        if once:
            _fail("ERROR: You cannot select both -r and -1 (--once)")
        if rate <= 0:
            _fail("ERROR: rate must be greater than zero")
    if values and file:
        _fail("ERROR: args conflict with -f setting")
    try:
        pub_args = parse_yaml_args(values)
    except UsageError as e:
        _fail(f"ERROR: {e}")
    _check_master()
    name = _resolve(topic)
    try:
        cls = message_class(msg_type)
    except TopicToolError as e:
        _fail(f"ERROR: {e}")
    documents: Iterable[Any] | None = None
    single = False
    if not pub_args and len(cls.__slots__):
        if file:
            try:
                docs = yaml_documents_from_file(file)
            except TopicToolError as e:
                _fail(f"ERROR: {e}")
            single = len(docs) == 1
            documents = docs
        elif sys.stdin.isatty():
            _fail("ERROR: Please specify message values")
        else:
            documents = stdin_documents()
        if rate is None and not latch and not once:
            rate = 10.0
    else:
        from rostui.core.rostime import Time

        try:
            build_message(cls, pub_args, Time.now())  # bad values: one line before advertising
        except TopicToolError as e:
            _fail(f"ERROR: {e}")
    raise typer.Exit(_run_async(run_pub(
        name, cls, pub_args, _out, rate=rate, once=once, latch=latch, documents=documents,
        verbose=verbose, substitute=substitute, single_document=single)))
