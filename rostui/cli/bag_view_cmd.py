"""`rostui bag view FILE ...` (play, step, seek, inspect) and `rostui bag view --record TOPIC ... | -a | -e REGEX ...`.

Bad input (a missing or unreadable file, a file with no messages, a bad
rate, clock rate or compression, no topics to record, an option of the
other mode) is one line and exit status 1, before Textual is imported.
Recording flags mean what they mean for ``rostui bag record``: both commands
build their options with :func:`rostui.tools.bag.record_options.record_options`.
"""

from __future__ import annotations

from dataclasses import dataclass

import typer

from rostui.cli.common import fail

CONTEXT = {"help_option_names": ["-h", "--help"], "allow_interspersed_args": True}


@dataclass
class RecordFlags:
    """The recording flags of ``bag view`` as typed (None or False: not given)."""

    exclude: str | None = None
    name: str | None = None
    prefix: str | None = None
    bz2: bool = False
    lz4: bool = False
    compression: str | None = None
    split: bool = False
    size: float | None = None
    duration: str | None = None
    mcap: bool = False

    def given(self) -> list[str]:
        """The flags given, as a user typed them."""
        flags = {"-x": self.exclude, "-O": self.name, "-o": self.prefix, "-j": self.bz2, "--lz4": self.lz4,
                 "--compression": self.compression, "--split": self.split, "--size": self.size,
                 "--duration": self.duration, "--mcap": self.mcap}
        return [flag for flag, value in flags.items() if value not in (None, False)]


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


def run_view(files: list[str], *, rate: float, loop: bool, pause: bool, topics: list[str], publish: bool,
             publish_all: bool = False, clock: bool = False, hz: float | None = None,
             record_flags: RecordFlags | None = None) -> int:
    """Open the bag view on ``files``; nothing is published unless ``publish_all`` or ``topics`` ask for it
    (or the t and a keys, later)."""
    from rostui.core.bag.clock import DEFAULT_HZ, BagClock
    from rostui.core.bag.model import BagError

    stray = record_flags.given() if record_flags is not None else []
    if stray:
        what = "is a recording option" if len(stray) == 1 else "are recording options"
        fail(f"rostui bag view: {', '.join(stray)} {what} (add --record)")
    if not files:
        fail("rostui bag view: no bag file given (or --record TOPIC ... / -a / -e REGEX ... to record)")
    if not rate > 0:
        fail(f"rostui bag view: the rate must be greater than 0, not {rate:g}")
    try:
        BagClock(DEFAULT_HZ if hz is None else hz)
    except BagError as exc:
        fail(f"rostui bag view: {exc}")
    if not publish:
        asked = [flag for flag, given in (("--clock", clock), ("--publish", publish_all), ("--topics", topics))
                 if given]
        if asked:
            fail(f"rostui bag view: {asked[0]} publishes; it cannot go with --no-publish")
    _check_bags(files)
    from rostui.apps.bagview.app import run_app

    return run_app(files, rate=rate, loop=loop, start_playing=not pause, topics=topics, publish=publish,
                   publish_all=publish_all, publish_clock=clock, clock_hz=DEFAULT_HZ if hz is None else hz)


def run_record_view(topics: list[str], *, all_topics: bool, regex: bool, flags: RecordFlags) -> int:
    """Open the recording view."""
    from rostui.core.bag.model import BagError
    from rostui.tools.bag.record_options import record_options

    try:
        opts = record_options(topics, all_topics=all_topics, regex=regex, exclude=flags.exclude, name=flags.name,
                              prefix=flags.prefix, bz2=flags.bz2, lz4=flags.lz4, compression=flags.compression,
                              split=flags.split, size_mb=flags.size, duration=flags.duration, mcap=flags.mcap)
    except BagError as exc:
        fail(f"rostui bag view --record: {exc}")
    from rostui.apps.bagview.record_app import run_record_app

    return run_record_app(opts)


def register(bag_app: typer.Typer) -> None:
    """Add ``rostui bag view`` to the ``rostui bag`` group."""

    @bag_app.command("view", context_settings=CONTEXT)
    def view_command(
        args: list[str] = typer.Argument(None, metavar="FILE... | --record TOPIC...",
                                         help="Bags to view, or with --record the topics to record."),
        record: bool = typer.Option(False, "--record", help="Record instead: live counts, sizes and rates per "
                                                            "topic; r start/stop, n split."),
        all_topics: bool = typer.Option(False, "-a", "--all", help="Record all topics, also those that appear "
                                                                   "later (implies --record)."),
        regex: bool = typer.Option(False, "-e", "--regex",
                                   help="The topics are regular expressions: record every topic whose whole name "
                                        "matches one, also those that appear later (implies --record)."),
        exclude: str | None = typer.Option(None, "-x", "--exclude", metavar="REGEX",
                                           help="With --record: leave out topics whose whole name matches "
                                                "(from -a and -e)."),
        name: str | None = typer.Option(None, "-O", "--output-name", metavar="NAME",
                                        help="With --record: file name (.mcap: MCAP, otherwise rosbag v2.0); "
                                             "files are NAME_0, NAME_1, ..."),
        mcap: bool = typer.Option(False, "--mcap", help="With --record: MCAP instead of rosbag's .bag."),
        prefix: str | None = typer.Option(None, "-o", "--output-prefix", metavar="PREFIX",
                                          help="With --record: prepend PREFIX to the date-and-time file name."),
        bz2_flag: bool = typer.Option(False, "-j", "--bz2", help="With --record: compress (bz2 in .bag files, "
                                                                 "zstd in MCAP)."),
        lz4_flag: bool = typer.Option(False, "--lz4", help="With --record: lz4 compression."),
        compression: str | None = typer.Option(None, "--compression", metavar="none|lz4|zstd|bz2",
                                               help="With --record: chunk compression."),
        split: bool = typer.Option(False, "--split", help="With --record: at --size or --duration go on in the "
                                                          "next file instead of stopping."),
        size: float | None = typer.Option(None, "--size", metavar="MB",
                                          help="With --record: stop (or split) when a file reaches MB."),
        duration: str | None = typer.Option(None, "--duration", metavar="DURATION",
                                            help="With --record: stop (or split) after DURATION: seconds, or with "
                                                 "s, m or h (30, 30s, 5m, 2h)."),
        clock: bool = typer.Option(False, "--clock", help="Publish the bag time on /clock while viewing "
                                                          "(also while paused)."),
        hz: float | None = typer.Option(None, "--hz", metavar="HZ", help="Rate of /clock messages (default 100)."),
        rate: float = typer.Option(1.0, "-r", "--rate", metavar="FACTOR", help="Playback rate factor (+/- change it in the app)."),
        loop: bool = typer.Option(False, "-l", "--loop", help="Loop playback."),
        pause: bool = typer.Option(True, "--pause/--play", help="Open paused (default) or playing."),
        publish_all: bool = typer.Option(False, "--publish", help="Publish every topic from the start, as rosbag "
                                                                  "play does (by default nothing is published "
                                                                  "until t or a)."),
        topics: list[str] | None = typer.Option(None, "--topics", metavar="TOPIC",
                                                help="Publish these topics from the start (t toggles in the app)."),
        no_publish: bool = typer.Option(False, "--no-publish", help="Browse only: no node; t and a publish "
                                                                    "nothing."),
    ) -> None:
        """View a bag like a video player: timeline, play/pause/step/seek, rate, loop, topics, inspector.

        Keys: space play/pause, s step, arrows/PgUp/PgDn/Home/End/0-9/g seek, , and . the selected
        topic's previous/next message, +/- rate, l loop, up/down choose a topic, t publishes it (a every
        topic), i inspector, q quit.  Nothing is published until t, a, --publish or --topics asks.
        """
        items = list(args or [])
        flags = RecordFlags(exclude=exclude, name=name, prefix=prefix, bz2=bz2_flag, lz4=lz4_flag,
                            compression=compression, split=split, size=size, duration=duration, mcap=mcap)
        if record or all_topics or regex:
            if clock or hz is not None:
                fail("rostui bag view --record: --clock and --hz are for viewing a bag, not recording")
            raise typer.Exit(run_record_view(items, all_topics=all_topics, regex=regex, flags=flags))
        raise typer.Exit(run_view(items, rate=rate, loop=loop, pause=pause, topics=list(topics or []),
                                  publish=not no_publish, publish_all=publish_all, clock=clock, hz=hz,
                                  record_flags=flags))
