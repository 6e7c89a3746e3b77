"""`rostui graph`: the ROS graph in the terminal (like `rqt_graph`), or as Graphviz DOT with `--dot`.

Textual is imported only when the app opens; `--dot` talks to the master,
prints and exits.
"""

from __future__ import annotations

import typer

#: Caller id of the graph's master queries.
CALLER = "/rostui_graph"

VIEWS = ("nodes", "active", "all")


def graph_command(
    dot: bool = typer.Option(False, "--dot", help="Print the graph as Graphviz DOT and exit (no UI)."),
    view: str = typer.Option("nodes", "--view", metavar="VIEW", help="nodes (Nodes only), active (Nodes/Topics active) "
                                                     "or all (Nodes/Topics all)."),
    show_debug: bool = typer.Option(False, "--show-debug", help="Show debug nodes and topics (/rosout, "
                                                                "anonymous tool nodes such as /rostopic_PID_MS)."),
    hide_dead_sinks: bool = typer.Option(False, "--hide-dead-sinks", help="Hide topics nobody subscribes to."),
    hide_leaf_topics: bool = typer.Option(False, "--hide-leaf-topics", help="Hide topics used by one node only."),
    group: bool = typer.Option(False, "--group", help="Fold each namespace into one box."),
    include: str = typer.Option("", "--include", metavar="REGEX",
                                help="Show only names matching REGEX (and what they connect to)."),
    exclude: str = typer.Option("", "--exclude", metavar="REGEX", help="Hide names matching REGEX."),
    book: bool = typer.Option(False, "--book", help="The book's setup: Nodes/Topics (all), only Hide debug on."),
    period: float = typer.Option(1.5, "--period", metavar="SECONDS", help="Seconds between master polls."),
) -> None:
    """Show the ROS graph: nodes, topics and who talks to whom (like `rqt_graph`).

    Keys in the app: v view, d hide debug, b the book's setup, / search,
    f focus, Enter details, ? all keys, q quit.
    """
    from rostui.cli.common import fail
    from rostui.models.graph.view import FilterError, GraphOptions, ViewMode, book_setup, compile_pattern

    if view not in VIEWS:
        fail(f"ERROR: --view must be one of {', '.join(VIEWS)}, not {view!r}")
    if not period > 0:
        fail(f"ERROR: --period must be a positive number of seconds, not {period:g}")
    options = GraphOptions(view=ViewMode(view), hide_debug=not show_debug, hide_dead_sinks=hide_dead_sinks,
                           hide_leaf_topics=hide_leaf_topics, group_namespaces=group, include=include,
                           exclude=exclude)
    if book:
        options = book_setup().with_(include=include, exclude=exclude, hide_debug=not show_debug)
    try:
        compile_pattern(include, "include")
        compile_pattern(exclude, "exclude")
    except FilterError as exc:
        fail(f"ERROR: {exc}")
    if dot:
        from rostui.cli.common import master_caller
        from rostui.models.graph.dot import to_dot
        from rostui.models.graph.model import fetch_graph
        from rostui.models.graph.view import build_view

        graph = fetch_graph(master_caller(CALLER))
        shown = build_view(graph, options)
        print(to_dot(shown, label_edges=options.view is ViewMode.NODES), end="")
        return
    from rostui.apps.graph.app import run_app

    raise typer.Exit(run_app(options, period=period))


def register(app: typer.Typer) -> None:
    """Add `rostui graph` to the rostui app."""
    app.command("graph")(graph_command)
