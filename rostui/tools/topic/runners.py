"""The long-running topic tools (echo, hz, bw, pub) as coroutines driving an anonymous ``/rostopic`` node."""

from __future__ import annotations

import sys
import time
from typing import Any, Callable, Iterable, Sequence

from rostui.tools.topic.common import Out, TopicToolError, one_line
from rostui.tools.topic.echo import EchoFormatter, decode
from rostui.tools.topic.listing import find_topic_type
from rostui.tools.topic.pub_args import build_message
from rostui.tools.topic.rates import BwStats, HzStats, format_hz, format_hz_table

#: How long ``pub -1`` stays up after publishing (rostopic's _ONCE_DELAY).
ONCE_DELAY = 3.0
#: How long file/stdin publishing waits for a first subscriber.
SUBSCRIBER_TIMEOUT = 5.0
#: How many publishers echo names when their messages do not decode (each once); after that it says nothing more.
MAX_NAMED_PUBLISHERS = 100


class _Run:
    """A tool node and its stop signal (SIGINT/SIGTERM or the tool finishing)."""

    def __init__(self) -> None:
        import asyncio

        self.node: Any = None
        self.stop = asyncio.Event()

    async def __aenter__(self) -> "_Run":
        import asyncio
        import signal

        from rostui.core.node import AsyncNode

        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            try:
                loop.add_signal_handler(sig, self.stop.set)
            except (NotImplementedError, RuntimeError):  # pragma: no cover - non-Unix
                pass
        self.node = await AsyncNode("rostopic", anonymous=True, argv=[]).start(announce=False)
        return self

    async def __aexit__(self, *exc: object) -> None:
        import asyncio

        if self.node is not None:
            try:
                await asyncio.wait_for(self.node.shutdown(), 3.0)
            except (asyncio.TimeoutError, Exception):
                pass

    async def sleep(self, seconds: float) -> bool:
        """Sleep, or return True at once when asked to stop."""
        import asyncio

        if self.stop.is_set():
            return True
        try:
            await asyncio.wait_for(self.stop.wait(), seconds)
            return True
        except asyncio.TimeoutError:
            return False


async def _wait_for_topic(run: _Run, topic: str) -> tuple[str, str, str] | None:
    """Block until *topic* (or the topic holding that field) is published; None when stopped.

    Its first master call is the command's check of the master (MasterUnreachableError when none answers).
    """
    warned = False
    while True:
        types = await run.node.master_call("getTopicTypes")
        type_name, real_topic, path = find_topic_type(lambda _m: types, topic)
        if type_name is not None and real_topic is not None:
            return type_name, real_topic, path
        if not warned:
            from rostui.tools.suggest import did_you_mean, registered_topics

            hint = did_you_mean(topic, registered_topics(await run.node.master_call("getSystemState")))
            sys.stderr.write(f"WARNING: topic [{topic}] does not appear to be published yet\n"
                             + (f"{hint}\n" if hint else ""))
            sys.stderr.flush()
            warned = True
        if await run.sleep(0.1):
            return None


async def run_echo(topic: str, out: Out, *, plot: bool = False, noarr: bool = False, nostr: bool = False,
                   offset: bool = False, count: int | None = None, fixed_width: int | None = None,
                   clear: bool = False, as_json: bool = False) -> int:
    """``rostopic echo``: print messages of *topic* (or a field of it) until stopped or *count* reached.

    Waits, like rostopic, while the topic is not published; decodes any type from its publisher's
    message_definition once checked (:func:`rostui.core.node.header_check.decodable`).  A publisher whose
    header is refused loses its connection and one line on stderr says why; a publisher whose messages do not
    decode gets one line too; the echo goes on with the others.
    """
    from rostui.core.node import AnyMsg
    from rostui.core.node.header_check import RefusalLog, decodable, publisher_name

    async with _Run() as run:
        found = await _wait_for_topic(run, topic)
        if found is None:
            return 0
        _, real, field = found
        fmt = EchoFormatter(field, plot=plot, noarr=noarr, nostr=nostr, offset=offset, count=count,
                            fixed_width=fixed_width, clear=clear, as_json=as_json)
        undecodable: set[str] = set()

        def say(line: str) -> None:
            sys.stderr.write(line + "\n")
            sys.stderr.flush()

        def on_msg(raw: Any) -> None:
            if fmt.done or run.stop.is_set():
                return
            try:
                text = fmt.format(decode(raw))
            except Exception as e:  # a message its own type cannot read: said once per publisher, then skipped
                sender = publisher_name(raw._connection_header or {})
                if sender not in undecodable and len(undecodable) < MAX_NAMED_PUBLISHERS:
                    undecodable.add(sender)
                    say(f"ERROR: cannot decode messages on {real} from {sender}: {one_line(str(e))}")
                return
            if text is not None:
                try:
                    out(text)
                except BrokenPipeError:
                    run.stop.set()
                    return
            if fmt.done:
                run.stop.set()

        refused = RefusalLog(decodable, lambda why: say(f"ERROR: refused a publisher of {real}: {why}"))
        await run.node.subscribe(real, AnyMsg, on_msg, check=refused)
        await run.stop.wait()
    return 0


async def run_hz(topics: Sequence[str], window: int, out: Out, *, clock: Callable[[], float] = time.time) -> int:
    """``rostopic hz``: report each topic's rate every second from arrival times (no decoding)."""
    from rostui.core.node import AnyMsg

    async with _Run() as run:
        stats: dict[str, HzStats] = {}
        for topic in topics:
            found = await _wait_for_topic(run, topic)
            if found is None:
                return 0
            st = stats.setdefault(topic, HzStats(window))
            add = st.add

            def on_msg(_raw: Any, add: Callable[[float], None] = add) -> None:
                add(clock())

            await run.node.subscribe(found[1], AnyMsg, on_msg)
            out(f"subscribed to [{found[1]}]\n")
        while not await run.sleep(1.0):
            if len(topics) == 1:
                out(format_hz(stats[topics[0]].stats()))
            else:
                out(format_hz_table([(t, stats[t].stats()) for t in topics]))
    return 0


async def run_bw(topic: str, window: int | None, out: Out) -> int:
    """``rostopic bw``: report the bandwidth of *topic* every second."""
    from rostui.core.node import AnyMsg

    async with _Run() as run:
        found = await _wait_for_topic(run, topic)
        if found is None:
            return 0
        st = BwStats(window)
        await run.node.subscribe(found[1], AnyMsg, lambda raw: st.add(time.time(), len(raw._buff)))
        out(f"subscribed to [{found[1]}]\n")
        while not await run.sleep(1.0):
            text = st.report(time.time())
            if text:
                out(text)
    return 0


async def _wait_for_subscriber(run: _Run, pub: Any, timeout: float) -> None:
    deadline = time.monotonic() + timeout
    while pub.get_num_connections() == 0 and time.monotonic() < deadline:
        if await run.sleep(0.01):
            return


async def run_pub(topic: str, cls: Any, pub_args: list[Any], out: Out, *, rate: float | None, once: bool,
                  latch: bool, documents: Iterable[Any] | None = None, verbose: bool = False,
                  substitute: bool = False, single_document: bool = False) -> int:
    """``rostopic pub``: latch one message, repeat it at *rate*, or play *documents* (file/stdin)."""
    import asyncio

    from rostui.core.rostime import Time

    latched = rate is None or latch
    async with _Run() as run:
        try:
            pub = await run.node.advertise(topic, cls, queue_size=100, latch=latched)
        except Exception as e:
            raise TopicToolError(one_line(str(e))) from None

        def announce(msg: Any, once_: bool) -> None:
            from rostui.core.msg.convert import message_to_yaml

            s = f"publishing and latching [{message_to_yaml(msg)}]" if verbose else "publishing and latching message"
            out(s + (f" for {ONCE_DELAY} seconds\n" if once_ else ". Press ctrl-C to terminate\n"))

        async def at_rate(msg: Any, args: list[Any], hz: float) -> None:
            period = 1.0 / hz
            loop = asyncio.get_running_loop()
            nxt = loop.time()
            while not run.stop.is_set():
                if substitute:
                    msg = build_message(cls, args, Time.now())
                if verbose:
                    from rostui.core.msg.convert import message_to_yaml
                    out(f"publishing {message_to_yaml(msg)}\n")
                pub.publish(msg)
                nxt += period
                delay = nxt - loop.time()
                if delay < -period:  # fell far behind: do not burst to catch up
                    nxt = loop.time()
                    delay = 0.0
                if await run.sleep(max(delay, 0.0)):
                    return

        if documents is None:
            msg = build_message(cls, pub_args, Time.now())
            if rate is None:
                announce(msg, once)
                pub.publish(msg)
                if once:
                    await run.sleep(ONCE_DELAY)
                else:
                    await run.stop.wait()
            else:
                await at_rate(msg, pub_args, rate)
            return 0

        await _wait_for_subscriber(run, pub, SUBSCRIBER_TIMEOUT)
        docs = iter(documents)
        end = object()
        while not run.stop.is_set():
            doc = await asyncio.to_thread(next, docs, end)
            if doc is end:
                break
            if doc is None:
                continue
            args = doc if isinstance(doc, list) else [doc]
            msg = build_message(cls, args, Time.now())
            if single_document and rate is not None:
                out("Got one message and a rate, publishing repeatedly\n")
                await at_rate(msg, args, rate)
            elif rate is None and not once:
                announce(msg, False)
                pub.publish(msg)
                await run.stop.wait()
            else:
                announce(msg, True)
                pub.publish(msg)
            if rate is not None:
                if await run.sleep(1.0 / rate):
                    break
            if once:
                break
        await asyncio.sleep(0.05)  # let the last frames leave before unregistering
    return 0
