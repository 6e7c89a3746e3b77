"""`rostui bag record|play|info|reindex|convert|filter|compress|decompress`: rosbag's commands; recordings are
rosbag's ``.bag`` by default, MCAP with ``--mcap`` or by name."""

from __future__ import annotations

import os
import sys

import typer

from rostui.cli import bag_view_cmd
from rostui.cli.bag_progress import progress_bar
from rostui.cli.bag_run import ros_log, run_play, split_ros_args, status_writer
from rostui.cli.common import examples, fail, interrupted

CONTEXT = {"help_option_names": ["-h", "--help"], "allow_interspersed_args": True}


def run_record(args: list[str], *, all_topics: bool, regex: bool, exclude: str | None, name: str | None,
               prefix: str | None, bz2_flag: bool, lz4_flag: bool, compression: str | None, split: bool,
               size: float | None, duration: str | None, max_size: float | None, mcap: bool = False) -> int:
    """Record until Ctrl-C or a limit; 1 with one line on error."""
    from rostui.core.bag.model import BagError
    from rostui.tools.bag.record_options import record_options
    from rostui.tools.bag.recorder import record
    from rostui.core.node.engine import new_event_loop

    topics, ros_args = split_ros_args(args)
    try:
        opts = record_options(topics, all_topics=all_topics, regex=regex, exclude=exclude, name=name, prefix=prefix,
                              bz2=bz2_flag, lz4=lz4_flag, compression=compression, split=split, size_mb=size,
                              duration=duration, max_size_mb=max_size, mcap=mcap)
    except BagError as exc:
        fail(f"rostui bag record: {exc}")
    status = status_writer(sys.stderr) if sys.stderr.isatty() else None
    loop = new_event_loop()
    try:
        count, files, error = loop.run_until_complete(record(opts, ros_args, status=status, report=ros_log))
    except BagError as exc:
        fail(f"rostui bag record: {exc}")
    finally:
        loop.close()
    if status is not None:
        sys.stderr.write("\n")
    if error:
        fail(f"rostui bag record: {error}; {', '.join(files)} holds what was recorded before")
    from rostui.tools.bag.recorder import file_format

    ros_log(f"Recorded {count} messages to {', '.join(files)} ({file_format(files[-1]) if files else 'no file'})")
    return 0


def run_info(files: list[str], as_json: bool, exact: bool = False) -> int:
    """Print info for each file (``exact``: the messages' own start, end and duration); 1 when any could not be
    read. Where rosbag's duration is not the messages' span a note on stderr says both."""
    from rostui.tools.bag.info import format_info, info_dict, span_note, summarize
    from rostui.core.bag.model import BagError

    failed = False
    results = []
    for i, path in enumerate(files):
        try:
            summary = summarize(path)
        except BagError as exc:
            print(f"rostui bag info: {exc}", file=sys.stderr)
            failed = True
            continue
        if as_json:
            results.append(info_dict(summary))
        else:
            if i:
                print("---")
            print(format_info(summary, exact), flush=True)
            note = None if exact else span_note(summary)
            if note:
                print(note, file=sys.stderr, flush=True)
    if as_json:
        from rostui.cli.common import print_json

        print_json(results[0] if len(files) == 1 and results else results)
    return 1 if failed else 0


def run_reindex(files: list[str]) -> int:
    """Rewrite each file with a full index; the original is kept as NAME.orig.EXT."""
    from rostui.core.bag.files import reindex
    from rostui.core.bag.model import BagError

    for path in files:
        try:
            with progress_bar(path) as progress:
                count, problem = reindex(path, progress)
        except BagError as exc:
            fail(f"rostui bag reindex: {exc}")
        except OSError as exc:
            fail(f"rostui bag reindex: {path}: {exc.strerror or exc}")
        note = f" (the original ended early: {problem})" if problem else ""
        print(f"{path}: reindexed {count} messages{note}", flush=True)
    return 0


def run_convert(src: str, dst: str, compression: str) -> int:
    """Copy a bag into the format its new name asks for."""
    from rostui.core.bag.files import convert
    from rostui.core.bag.model import BagError

    try:
        with progress_bar(dst) as progress:
            count = convert(src, dst, compression, progress)
    except BagError as exc:
        fail(f"rostui bag convert: {exc}")
    except OSError as exc:
        fail(f"rostui bag convert: {exc.strerror or exc}")
    print(f"{dst}: {count} messages", flush=True)
    return 0


def run_filter(src: str, dst: str, expr: str, print_expr: str | None) -> int:
    """Write the messages of SRC for which EXPR holds to DST; 1 with one line on error (DST untouched)."""
    from rostui.tools.bag.filter import filter_bag
    from rostui.core.bag.model import BagError

    def show(line: str) -> None:
        print(line, flush=True)

    try:
        with progress_bar(dst) as progress:
            filter_bag(src, dst, expr, print_expr=print_expr, printer=show, progress=progress)
    except BrokenPipeError:  # --print's reader went away (`| head`): stop quietly, OUT not written
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except (KeyboardInterrupt, ImportError) as exc:
        if not interrupted(exc):
            raise
        fail(f"rostui bag filter: interrupted; {dst} not written")
    except BagError as exc:
        fail(f"rostui bag filter: {exc}")
    except OSError as exc:
        fail(f"rostui bag filter: {exc.filename or dst}: {exc.strerror or exc}")
    return 0


def run_change_compression(command: str, files: list[str], kind: str, output_dir: str | None, force: bool,
                           quiet: bool) -> int:
    """Rewrite each bag with ``kind`` chunks; 1 when any could not be (the others are still done)."""
    from rostui.tools.bag.compress import change_compression
    from rostui.core.bag.model import BagError

    failed = False
    for path in files:
        try:
            with progress_bar(path) as progress:
                outcome = change_compression(path, kind, output_dir=output_dir, force=force, progress=progress)
        except (KeyboardInterrupt, ImportError) as exc:
            if not interrupted(exc):
                raise
            fail(f"rostui bag {command}: interrupted; {path} is as it was")
        except BagError as exc:
            print(f"rostui bag {command}: {exc}", file=sys.stderr)
            failed = True
            continue
        except OSError as exc:
            print(f"rostui bag {command}: {exc.filename or path}: {exc.strerror or exc}", file=sys.stderr)
            failed = True
            continue
        if outcome.skipped and not quiet:
            print(outcome.skipped, file=sys.stderr)
    return 1 if failed else 0


RECORD_EXAMPLES = examples(
    ("the turtle's commands and poses into square.bag (chapter 9)",
     "rostui bag record -O square.bag /turtle1/command_velocity /turtle1/pose"),
    ("every topic, also later ones, into a .bag named by date and time", "rostui bag record -a"),
    ("the same as MCAP (rosbag cannot read it)", "rostui bag record -a --mcap"),
    ("every topic but the log", "rostui bag record -a -x '/rosout.*'"),
    ("a compressed rosbag .bag file that stops after one minute",
     "rostui bag record -j --duration 1m -O run.bag /turtle1/pose"),
)

PLAY_EXAMPLES = examples(
    ("replay what was recorded (chapter 9)", "rostui bag play square.bag"),
    ("twice as fast, over and over", "rostui bag play -r 2 -l square.bag"),
    ("drive a second turtle: remap the topic",
     "rostui bag play square.bag \\\n    /turtle1/command_velocity:=/turtle2/command_velocity"),
    ("publish the bag's time on /clock, from 5 s in", "rostui bag play --clock -s 5 square.bag"),
)


bag_app = typer.Typer(name="bag",
                      help="Record, play and inspect bags: rosbag .bag by default, MCAP with --mcap or by name.",
                      no_args_is_help=True, context_settings={"help_option_names": ["-h", "--help"]})


@bag_app.command("record", context_settings=CONTEXT, epilog=RECORD_EXAMPLES)
def record_command(
    args: list[str] = typer.Argument(None, metavar="[TOPIC]...", help="Topics to record (and name:=value)."),
    all_topics: bool = typer.Option(False, "-a", "--all", help="Record all topics, also those that appear later."),
    regex: bool = typer.Option(False, "-e", "--regex",
                               help="The topics are regular expressions: record every topic whose whole name "
                                    "matches one, also those that appear later."),
    exclude: str | None = typer.Option(None, "-x", "--exclude", metavar="REGEX",
                                       help="Leave out topics whose whole name matches (from -a and -e)."),
    name: str | None = typer.Option(None, "-O", "--output-name", metavar="NAME",
                                    help="File name (.mcap: MCAP; otherwise rosbag v2.0, .bag added when "
                                         "missing)."),
    prefix: str | None = typer.Option(None, "-o", "--output-prefix", metavar="PREFIX",
                                      help="Prepend PREFIX to the date-and-time file name."),
    mcap: bool = typer.Option(False, "--mcap", help="Record MCAP instead of rosbag's .bag (rosbag cannot read "
                                                    "it; `rostui bag convert` makes a .bag)."),
    bz2_flag: bool = typer.Option(False, "-j", "--bz2", help="Compress: bz2 in .bag files, zstd in MCAP."),
    lz4_flag: bool = typer.Option(False, "--lz4", help="lz4 compression."),
    compression: str | None = typer.Option(None, "--compression", metavar="none|lz4|zstd|bz2",
                                           help="Chunk compression."),
    split: bool = typer.Option(False, "--split", help="Start a new file at --size or --duration."),
    size: float | None = typer.Option(None, "--size", metavar="MB", help="File size limit in MB."),
    duration: str | None = typer.Option(None, "--duration", metavar="DURATION",
                                        help="File duration: seconds, or with s, m or h (30, 30s, 5m, 2h)."),
    max_size: float | None = typer.Option(None, "--max-size", metavar="MB",
                                          help="Stop when the recording reaches this many MB in all."),
) -> None:
    """Record topics into a bag until Ctrl-C (like `rosbag record`)."""
    raise typer.Exit(run_record(list(args or []), all_topics=all_topics, regex=regex, exclude=exclude,
                                name=name, prefix=prefix, bz2_flag=bz2_flag, lz4_flag=lz4_flag,
                                compression=compression, split=split, size=size, duration=duration,
                                max_size=max_size, mcap=mcap))


@bag_app.command("play", context_settings=CONTEXT, epilog=PLAY_EXAMPLES)
def play_command(
    args: list[str] = typer.Argument(..., metavar="FILE...", help="Bags to play (and topic:=newtopic)."),
    rate: float = typer.Option(1.0, "-r", "--rate", metavar="FACTOR", help="Multiply the publish rate by this factor."),
    loop_play: bool = typer.Option(False, "-l", "--loop", help="Loop playback."),
    pause: bool = typer.Option(False, "--pause", help="Start paused."),
    start: float = typer.Option(0.0, "-s", "--start", metavar="SECONDS", help="Start SECONDS into the bag."),
    duration: float | None = typer.Option(None, "-u", "--duration", metavar="SECONDS",
                                          help="Play only SECONDS of the bag."),
    delay: float = typer.Option(0.2, "-d", "--delay", metavar="SECONDS",
                                help="Wait SECONDS after advertising each topic."),
    clock: bool = typer.Option(False, "--clock", help="Publish the bag time on /clock."),
    hz: float = typer.Option(100.0, "--hz", metavar="HZ", help="Rate of /clock messages."),
    topics: list[str] | None = typer.Option(None, "--topics", metavar="TOPIC",
                                            help="Play only these topics (repeat the option)."),
    queue: int = typer.Option(100, "--queue", metavar="SIZE", help="Outgoing queue size of each publisher."),
    quiet: bool = typer.Option(False, "-q", "--quiet", help="No status line."),
) -> None:
    """Play bags back with their original timing (like `rosbag play`)."""
    raise typer.Exit(run_play(list(args), rate=rate, loop_play=loop_play, pause=pause, start=start,
                              duration=duration, delay=delay, clock=clock, hz=hz, topics=topics, queue=queue,
                              quiet=quiet))


@bag_app.command("info")
def info_command(
    files: list[str] = typer.Argument(..., metavar="FILE...", help="Bags to describe."),
    as_json: bool = typer.Option(False, "--json", help="Print machine-readable JSON instead of text."),
    exact: bool = typer.Option(False, "--exact", help="Duration, start and end of the earliest and latest "
                                                      "message (rosbag takes the first and last chunk)."),
) -> None:
    """Summarize bags: times, size, counts, types and topics (like `rosbag info`)."""
    raise typer.Exit(run_info(list(files), as_json, exact))


@bag_app.command("reindex")
def reindex_command(
    files: list[str] = typer.Argument(..., metavar="FILE...", help="Bags to rewrite with an index."),
) -> None:
    """Repair bags whose recording was cut short (the original is kept as NAME.orig.EXT)."""
    raise typer.Exit(run_reindex(list(files)))


@bag_app.command("convert")
def convert_command(
    src: str = typer.Argument(..., metavar="IN", help="The bag to read."),
    dst: str = typer.Argument(..., metavar="OUT", help="The file to write (.bag: rosbag v2.0, else MCAP)."),
    compression: str = typer.Option("none", "--compression", metavar="none|lz4|zstd|bz2",
                                    help="Chunk compression of OUT."),
) -> None:
    """Convert between MCAP and rosbag .bag."""
    raise typer.Exit(run_convert(src, dst, compression))


@bag_app.command("filter")
def filter_command(
    src: str = typer.Argument(..., metavar="INBAG", help="The bag to read."),
    dst: str = typer.Argument(..., metavar="OUTBAG", help="The file to write (.bag: rosbag v2.0, else MCAP)."),
    expr: str = typer.Argument(..., metavar="EXPRESSION",
                               help="Python expression over topic, m (the message) and t (its time)."),
    print_expr: str | None = typer.Option(None, "-p", "--print", metavar="PRINT-EXPRESSION",
                                          help="Print MATCH or NO MATCH and this expression for each message."),
) -> None:
    """Copy the messages for which EXPRESSION is true (like `rosbag filter`).

    For example "topic == '/chatter'", "m.data > 5" or "t.to_sec() > 1700000000.5".
    """
    raise typer.Exit(run_filter(src, dst, expr, print_expr))


@bag_app.command("compress")
def compress_command(
    files: list[str] = typer.Argument(..., metavar="BAGFILE...", help="Bags to compress."),
    bz2_flag: bool = typer.Option(False, "-j", "--bz2", help="bz2 compression (the default; zstd in MCAP)."),
    lz4_flag: bool = typer.Option(False, "--lz4", help="lz4 compression."),
    output_dir: str | None = typer.Option(None, "--output-dir", metavar="DIR", help="Write to folder DIR."),
    force: bool = typer.Option(False, "-f", "--force", help="Overwrite a backup file that exists."),
    quiet: bool = typer.Option(False, "-q", "--quiet", help="Say nothing of skipped bags."),
) -> None:
    """Compress bags in place, keeping NAME.orig.EXT (like `rosbag compress`)."""
    kind = "lz4" if lz4_flag and not bz2_flag else "strong"
    raise typer.Exit(run_change_compression("compress", list(files), kind, output_dir, force, quiet))


@bag_app.command("decompress")
def decompress_command(
    files: list[str] = typer.Argument(..., metavar="BAGFILE...", help="Bags to decompress."),
    output_dir: str | None = typer.Option(None, "--output-dir", metavar="DIR", help="Write to folder DIR."),
    force: bool = typer.Option(False, "-f", "--force", help="Overwrite a backup file that exists."),
    quiet: bool = typer.Option(False, "-q", "--quiet", help="Say nothing of skipped bags."),
) -> None:
    """Decompress bags in place, keeping NAME.orig.EXT (like `rosbag decompress`)."""
    raise typer.Exit(run_change_compression("decompress", list(files), "none", output_dir, force, quiet))


bag_view_cmd.register(bag_app)


def register(app: typer.Typer) -> None:
    """Add ``rostui bag ...``."""
    app.add_typer(bag_app, name="bag")
