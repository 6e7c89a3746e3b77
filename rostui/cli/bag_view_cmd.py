"""`rostui bag view FILE ...` (play, step, seek, inspect) and `rostui bag view --record TOPIC ... | -a`.

Bad input (a missing or unreadable file, a file with no messages, a bad
rate or compression, no topics to record) is one line and exit status 1,
before Textual is imported.
"""

from __future__ import annotations

import typer

from rostui.cli.common import fail

CONTEXT = {"help_option_names": ["-h", "--help"], "allow_interspersed_args": True}
COMPRESSIONS = ("none", "lz4", "zstd", "bz2")


def _check_bags(files: list[str]) -> None:
    """Open each file and read its summary; one line and exit 1 for the first that cannot be played."""
    from rostui.core.bag.files import open_reader
    from rostui.core.bag.model import BagError

    for path in files:
        try:
            reader = open_reader(path)
            try:
                summary = reader.summary()
            finally:
                reader.close()
        except BagError as exc:
            fail(f"rostui bag view: {exc}")
        if not summary.message_count:
            why = f" ({summary.problem})" if summary.problem else ""
            fail(f"rostui bag view: {path} holds no messages{why}")


def run_view(files: list[str], *, rate: float, loop: bool, pause: bool, topics: list[str], publish: bool) -> int:
    """Open the bag view on ``files``."""
    if not files:
        fail("rostui bag view: no bag file given (or --record TOPIC ... / -a to record)")
    if not rate > 0:
        fail(f"rostui bag view: the rate must be greater than 0, not {rate:g}")
    _check_bags(files)
    from rostui.apps.bagview.app import run_app

    return run_app(files, rate=rate, loop=loop, start_playing=not pause, topics=topics, publish=publish)


def run_record_view(topics: list[str], *, all_topics: bool, name: str | None, prefix: str | None,
                    compression: str) -> int:
    """Open the recording view."""
    from rostui.core.bag.recorder import RecordOptions

    if not topics and not all_topics:
        fail("rostui bag view --record: name topics to record, or use -a (all)")
    if name and prefix:
        fail("rostui bag view --record: use -O NAME or -o PREFIX, not both")
    if compression not in COMPRESSIONS:
        fail(f"rostui bag view --record: unknown compression '{compression}' (none, lz4, zstd or bz2)")
    is_bag = (name or prefix or "").endswith(".bag")
    if is_bag and compression == "zstd":
        fail("rostui bag view --record: a .bag file cannot use zstd compression (none, bz2 or lz4)")
    if compression == "bz2" and not is_bag:
        fail("rostui bag view --record: MCAP files use lz4 or zstd compression, not bz2 (name the file .bag)")
    opts = RecordOptions(topics=topics, all_topics=all_topics, output_name=name, output_prefix=prefix,
                         compression=compression)
    from rostui.apps.bagview.record_app import run_record_app

    return run_record_app(opts)


def register(bag_app: typer.Typer) -> None:
    """Add ``rostui bag view`` to the ``rostui bag`` group."""

    @bag_app.command("view", context_settings=CONTEXT)
    def view_command(
        args: list[str] = typer.Argument(None, metavar="FILE ... | --record TOPIC ...",
                                         help="Bags to view, or with --record the topics to record."),
        record: bool = typer.Option(False, "--record", help="Record instead: live counts, sizes and rates per "
                                                            "topic; r start/stop, n split."),
        all_topics: bool = typer.Option(False, "-a", "--all", help="With --record: record all topics."),
        name: str | None = typer.Option(None, "-O", "--output-name", metavar="NAME",
                                        help="With --record: file name (.bag: rosbag v2.0, otherwise MCAP); "
                                             "files are NAME_0, NAME_1, ..."),
        prefix: str | None = typer.Option(None, "-o", "--output-prefix", metavar="PREFIX",
                                          help="With --record: prepend PREFIX to the date-and-time file name."),
        compression: str = typer.Option("none", "--compression", metavar="none|lz4|zstd|bz2",
                                        help="With --record: chunk compression."),
        rate: float = typer.Option(1.0, "-r", "--rate", help="Playback rate factor (+/- change it in the app)."),
        loop: bool = typer.Option(False, "-l", "--loop", help="Loop playback."),
        pause: bool = typer.Option(True, "--pause/--play", help="Open paused (default) or playing."),
        topics: list[str] | None = typer.Option(None, "--topics", metavar="TOPIC",
                                                help="Publish only these topics at first (t toggles in the app)."),
        no_publish: bool = typer.Option(False, "--no-publish", help="Browse only: no node, nothing published."),
    ) -> None:
        """View a bag like a video player: timeline, play/pause/step/seek, rate, loop, topics, inspector.

        Keys: space play/pause, s step, arrows/PgUp/PgDn/Home/End/0-9/g seek, , and . the selected
        topic's previous/next message, +/- rate, l loop, up/down and t choose topics to publish
        (a all), i inspector, q quit.
        """
        items = list(args or [])
        if record or all_topics:
            raise typer.Exit(run_record_view(items, all_topics=all_topics, name=name, prefix=prefix,
                                             compression=compression))
        raise typer.Exit(run_view(items, rate=rate, loop=loop, pause=pause, topics=list(topics or []),
                                  publish=not no_publish))
