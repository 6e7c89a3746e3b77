"""`rostui action list | info | send`: actionlib servers from the command line (axclient's job, in a terminal)."""

from __future__ import annotations

from typing import Any, List, Optional

import typer

from rostui.cli.common import examples

CONTEXT = {"help_option_names": ["-h", "--help"]}

action_app = typer.Typer(name="action", help="Action servers: list them, show one, send one a goal (like axclient); "
                         "alone, the app.", invoke_without_command=True, context_settings=CONTEXT)


@action_app.callback()
def action_main(ctx: typer.Context) -> None:
    """Action servers: with no command, the app (like axclient): the servers, a goal to edit and send, its
    feedback, status and result; ctrl+x cancels it."""
    if ctx.invoked_subcommand is None:
        from rostui.apps.action.app import run_app

        raise typer.Exit(run_app())


def _actions() -> list[Any]:
    """The action servers on the master."""
    from rostui.cli.common import master_caller
    from rostui.tools.action import find_actions

    call = master_caller("/rostui_action")
    publishers, subscribers, _services = call("getSystemState")
    types = {str(topic): str(kind) for topic, kind in call("getTopicTypes")}
    return find_actions(publishers, subscribers, types)


def _named(name: str) -> Any:
    """The action server ``name`` (resolved in ROS_NAMESPACE); one error line with a "did you mean" otherwise."""
    from rostui.cli.common import fail, suggestion
    from rostui.tools.node import script_resolve

    wanted = script_resolve(name)
    actions = _actions()
    found = next((action for action in actions if action.name == wanted), None)
    if found is None:
        fail(f"ERROR: no action server {wanted} on the master",
             hint=suggestion(wanted, lambda: [action.name for action in actions]))
    return found


@action_app.command("list", epilog=examples(("every action server", "rostui action list"),
                                            ("with types and the nodes serving them", "rostui action list -v")))
def list_command(
    verbose: bool = typer.Option(False, "--verbose", "-v", help="Each action's type and the nodes serving it."),
) -> None:
    """List the action servers on the master (the namespaces of actionlib's five topics)."""
    for action in _actions():
        if verbose:
            print(f"{action.name} [{action.type or '?'}] served by {', '.join(action.servers)}")
        else:
            print(action.name)


@action_app.command("info", epilog=examples(("the type, server, clients and messages of /fibonacci",
                                             "rostui action info /fibonacci")))
def info_command(name: str = typer.Argument(..., metavar="ACTION", help="The action's namespace.")) -> None:
    """Show an action server: its type, the nodes serving it and sending it goals, and its goal, result and
    feedback messages."""
    from rostui.tools.msgtypes import TypeLookupError, message_lines

    action = _named(name)
    print(f"Action: {action.name}\nType: {action.type or 'unknown (the master gives no type for its topics)'}")
    print("Servers:\n" + "".join(f" * {node}\n" for node in action.servers), end="")
    print("Clients:\n" + ("".join(f" * {node}\n" for node in action.clients) or " None\n"), end="")
    if action.type is None:
        return
    for part in ("Goal", "Result", "Feedback"):
        try:
            lines = message_lines(f"{action.type}{part}")
        except TypeLookupError:
            lines = [f"(not known here: put {action.type.split('/')[0]} on ROS_PACKAGE_PATH)"]
        print(f"\n{part} ({action.type}{part}):\n" + "".join(f"  {line}\n" for line in lines), end="")


@action_app.command("send", epilog=examples(
    ("a Fibonacci goal of order 5", "rostui action send /fibonacci '{order: 5}'"),
    ("the same, fields in order", "rostui action send /fibonacci 5"),
    ("a goal of a type the master does not name", "rostui action send /move -t move_base_msgs/MoveBase '{...}'"),
))
def send_command(
    name: str = typer.Argument(..., metavar="ACTION", help="The action's namespace."),
    goal: Optional[List[str]] = typer.Argument(None, metavar="[GOAL]...",
                                               help="The goal as YAML, as `rostopic pub` takes a message."),
    action_type: Optional[str] = typer.Option(None, "--type", "-t", metavar="TYPE",
                                              help="The action's type (default: what the master says)."),
    timeout: float = typer.Option(10.0, "--timeout", metavar="SECONDS", help="How long to wait for the server."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="Print only the result, not each feedback."),
) -> None:
    """Send a goal to an action server and print its status, feedback and result. Ctrl-C cancels the goal.

    The exit status is 0 when the goal SUCCEEDED, 1 when it was aborted,
    rejected, preempted or lost, 130 after Ctrl-C.
    """
    import asyncio

    from rostui.cli.common import fail, master_uri
    from rostui.tools.action import ActionError
    from rostui.tools.topic.common import TopicToolError, UsageError
    from rostui.tools.topic.pub_args import parse_yaml_args

    if not timeout > 0:
        fail("--timeout must be more than 0 seconds")
    action = _named(name)
    kind = action_type or action.type
    if kind is None:
        fail(f"ERROR: the master names no type for {action.name}: give it with --type")
    try:
        args = parse_yaml_args(goal or [])
    except (UsageError, TopicToolError) as exc:
        fail(str(exc))
    try:
        raise typer.Exit(asyncio.run(_send(master_uri(), action.name, kind, args, timeout, quiet)))
    except ActionError as exc:
        fail(f"ERROR: {exc}")
    except TopicToolError as exc:
        fail(f"ERROR: {exc}")


async def _send(uri: str, ns: str, kind: str, args: list[Any], timeout: float, quiet: bool) -> int:
    """The goal session: connect, send, print what comes; Ctrl-C cancels and waits a little for the answer."""
    import asyncio
    import signal

    from rostui.core.msg.convert import message_to_yaml
    from rostui.core.node.node import AsyncNode
    from rostui.tools.action import STATUS_NAMES, GoalSession
    from rostui.tools.topic.pub_args import build_message

    def said_status(state: int, text: str) -> None:
        print(f"status: {STATUS_NAMES.get(state, state)}" + (f" ({text})" if text else ""), flush=True)

    def said_feedback(msg: Any) -> None:
        if not quiet:
            print("feedback:\n" + _indented(message_to_yaml(msg)) + "---", flush=True)

    node = await AsyncNode("rostui_action", anonymous=True, argv=[], master_uri=uri).start(announce=False)
    loop = asyncio.get_running_loop()
    interrupted = asyncio.Event()
    loop.add_signal_handler(signal.SIGINT, interrupted.set)
    try:
        session = GoalSession(node, ns, kind, on_feedback=said_feedback, on_status=said_status)
        goal = build_message(session.goal_class, args)
        await session.connect(timeout)
        print(f"goal {session.send_goal(goal)} sent to {ns} [{kind}]", flush=True)
        sending = asyncio.ensure_future(session.result())
        stop = asyncio.ensure_future(interrupted.wait())
        await asyncio.wait({sending, stop}, return_when=asyncio.FIRST_COMPLETED)
        if not sending.done():
            print("cancelling the goal…", flush=True)
            session.cancel()
            done, _ = await asyncio.wait({sending}, timeout=5.0)
            if not done:
                sending.cancel()
                print("the server did not answer the cancel within 5 s", flush=True)
                return 130
        stop.cancel()
        outcome = sending.result()
        print("result:\n" + _indented(message_to_yaml(outcome.result)), flush=True)
        print(f"goal {outcome.status_name}" + (f": {outcome.text}" if outcome.text else ""), flush=True)
        return 130 if interrupted.is_set() else 0 if outcome.status == 3 else 1
    finally:
        loop.remove_signal_handler(signal.SIGINT)
        await node.shutdown("rostui action done")


def _indented(text: str) -> str:
    """Each line of ``text`` two spaces in, and a newline at the end."""
    return "".join(f"  {line}\n" for line in text.splitlines()) if text.strip() else "  {}\n"


def register(app: typer.Typer) -> None:
    """Add ``rostui action ...``."""
    app.add_typer(action_app, name="action")
