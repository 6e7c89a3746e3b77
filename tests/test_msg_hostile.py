"""Hostile message definitions: every name from the wire is checked against ROS's grammar before any use.

A ``message_definition`` comes from any publisher's connection header or any bag.  Its type, field and
constant names end up in generated Python source, so a definition that is not ROS's grammar (or that Python
cannot turn into a class) is refused with one MessageError, and nothing of it is ever executed: not when
the definition is registered, not when a later connection names one of its types, not when a message is
decoded.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Iterator

import pytest

from conftest import wait_until
from rostui.core.msg import (
    Message,
    MessageError,
    MessageSpecError,
    UnknownMessageTypeError,
    clear_cache,
    connection_class,
    definition_md5,
    get_message_class,
)

SEP = "\n" + "=" * 80 + "\n"
#: Runs a shell command when pasted into generated source as a class variable's name (or a type's name).
PAYLOAD = 'x if __import__("os").system("touch pwned") else _C_x'


def from_definition(type_name: str, definition: str) -> type[Message]:
    """The class a peer gets by sending ``definition`` with the md5sum it hashes to (any md5sum, when the text
    cannot be hashed: the checks before hashing are what is tested then)."""
    try:
        md5 = definition_md5(type_name, definition)
    except MessageError:
        md5 = "0123456789abcdef0123456789abcdef"
    return connection_class(type_name, md5, definition)


def poisoned_definition(marker_cmd: str = "touch pwned") -> tuple[str, str]:
    """A definition whose extra ``MSG:`` sections are named with Python code, and the name a later peer uses."""
    payload = PAYLOAD.replace("touch pwned", marker_cmd)
    definition = "int32 a" + SEP + f"MSG: {payload}/B\nLeaf z\n" + SEP + f"MSG: {payload}/Leaf\nint32 w\n"
    return definition, f"{payload}/B"


@pytest.fixture(autouse=True)
def fresh_types(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A fresh type store around each test (nothing a hostile definition registered survives it), cwd = tmp."""
    clear_cache()
    monkeypatch.chdir(tmp_path)
    yield tmp_path
    clear_cache()


def test_section_named_with_code_is_refused_and_never_run(fresh_types: Path) -> None:
    """Before the fix the ``MSG:`` sections were registered under their names, and naming one later ran it."""
    definition, later_name = poisoned_definition()
    with pytest.raises(MessageSpecError, match="not a valid pkg/Type name"):
        from_definition("evil_pkg/Evil", definition)
    with pytest.raises(UnknownMessageTypeError):
        get_message_class(later_name).deserialize(b"\0\0\0\0")
    assert not (fresh_types / "pwned").exists()


@pytest.mark.parametrize("type_name,definition,why", [
    ("evil_pkg/Evil\n", "int32 a\n", "not a valid pkg/Type name"),
    ("evil_pkg/Evil\nimport os", "int32 a\n", "not a valid pkg/Type name"),
    ("evil_pkg/Evil", "int32 a" + SEP + "MSG: evil_pkg/Inner\rimport os\nint32 b\n", "not a valid pkg/Type name"),
    ("evil_pkg/Evil", "int32 a" + SEP + "MSG: evil'pkg/Inner\nint32 b\n", "not a valid pkg/Type name"),
    ("evil_pkg/Evil", "int32 __import__('os').system\n", "not a legal message field name"),
    ("evil_pkg/Evil", "int32 class\nint32 class_\n", "two fields are named class_"),
    ("evil_pkg/Evil", "int32 serialize\n", "method of messages"),
    ("evil_pkg/Evil", "int32 serialize=1\nint32 a\n", "constant's name"),
    ("evil_pkg/Evil", "evil_pkg/Other X=1\n", "not a legal constant type"),
    ("evil_pkg/Evil", "float64[1000000000] x\n", "fixed-size arrays too large"),
    ("evil_pkg/Evil", "Inner[100000] x" + SEP + "MSG: evil_pkg/Inner\nfloat64[100000] y\n", "too large"),
])
def test_hostile_definition_is_refused_with_one_message_error(type_name: str, definition: str, why: str) -> None:
    with pytest.raises(MessageError) as caught:
        from_definition(type_name, definition)
    text = str(caught.value)
    assert why in text
    assert "\n" not in text and "\r" not in text  # one line, control characters quoted


def test_a_field_named_like_a_python_keyword_gets_genpys_name() -> None:
    """genpy names a field ``lambda`` (or ``self``) ``lambda_`` on its class; the wire and the md5 keep ``lambda``."""
    Keyed = from_definition("kw_pkg/Keyed", "float64[] lambda\nint32 self\nint32 class=3\n")
    assert Keyed.__slots__ == ["lambda_", "self_"] and Keyed.class_ == 3
    msg = Keyed(lambda_=[1.5], self_=2)
    assert Keyed.deserialize(msg.serialize()) == msg
    assert "lambda_: [1.5]" in str(msg)


def test_nesting_too_deep_is_refused_not_a_recursion_error() -> None:
    parts = ["T0 a\n"] + [f"MSG: z/T{i}\n" + (f"T{i + 1} a\n" if i < 599 else "int32 x\n") for i in range(600)]
    with pytest.raises(MessageSpecError, match="nesting too deep"):
        from_definition("z/Top", SEP.join(parts))


@pytest.mark.timeout(120)
def test_exponential_inlining_is_refused() -> None:
    """40 types of two fields each of the next: 2**40 inlined fields; refused, not generated (nor hung on)."""
    parts = ["T0 a\nT0 b\n"] + [f"MSG: z/T{i}\n" + (f"T{i + 1} a\nT{i + 1} b\n" if i < 39 else "int32 x\n")
                                 for i in range(40)]
    with pytest.raises(MessageSpecError, match="too many fields"):
        from_definition("z/Top", SEP.join(parts))


def test_nested_types_never_share_a_class_variable() -> None:
    """``p__q/T`` and ``p/q__T`` once mapped to the same variable of the generated code: the wrong class."""
    definition = ("p__q/T a\np/q__T b\n" + SEP + "MSG: p__q/T\nint32 x\n" + SEP + "MSG: p/q__T\nstring y\n")
    Outer = from_definition("z/Outer", definition)
    msg = Outer()
    assert (msg.a._type, msg.b._type) == ("p__q/T", "p/q__T")
    assert Outer.deserialize(msg.serialize()) == msg


def test_legal_definitions_still_build() -> None:
    """What ROS allows stays allowed: odd but legal names, Header, arrays, constants."""
    definition = ("Header header\nint32 CONST_a=3\nstring S=a'b\"c\ntime self\nInner[2] in_\nuint8[4] raw\n"
                  + SEP + "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
                  + SEP + "MSG: z/Inner\nfloat64[9] covariance\n")
    cls = from_definition("z/Odd", definition)
    msg = cls()
    assert cls.S == "a'b\"c" and cls.CONST_a == 3
    assert cls.deserialize(msg.serialize()) == msg


def test_bag_reader_reports_a_hostile_definition(tmp_path: Path) -> None:
    from rostui.core.bag.index import message_yaml
    from rostui.core.bag.model import BagError, Connection
    from rostui.core.bag.rosbag2_0 import BagReader, BagWriter

    definition, later_name = poisoned_definition()
    path = tmp_path / "hostile.bag"
    writer = BagWriter(str(path))
    writer.add_connection(Connection(0, "/evil", "evil_pkg/Evil", "*", definition))
    writer.add_connection(Connection(1, "/evil", later_name, "*", ""))
    writer.write(0, 1_000_000_000, b"\0\0\0\0")
    writer.write(1, 2_000_000_000, b"\0\0\0\0")
    writer.close()
    reader = BagReader(str(path))
    errors = []
    try:
        for conn, _t, data in reader.messages():
            with pytest.raises(BagError) as caught:
                message_yaml(conn, data)
            errors.append(str(caught.value))
    finally:
        reader.close()
    assert len(errors) == 2
    assert all("\n" not in e for e in errors)
    assert not (tmp_path / "pwned").exists()


# ------------------------------------------------------------------ through a live publisher's connection header

HOSTILE_PUBLISHER = r'''
"""A raw ROS 1 publisher (stdlib only) whose connection header says what argv says."""
import socket, struct, sys, threading, time, xmlrpc.client
from xmlrpc.server import SimpleXMLRPCServer

master, topic, name, header_type, definition_file, delay = sys.argv[1:7]
definition = open(definition_file, encoding="utf-8").read()


def field(key, value):
    item = key.encode() + b"=" + value.encode()
    return struct.pack("<I", len(item)) + item


def serve(conn):
    try:
        size = struct.unpack("<I", conn.recv(4, socket.MSG_WAITALL))[0]
        conn.recv(size, socket.MSG_WAITALL)
        header = b"".join(field(k, v) for k, v in (
            ("callerid", name), ("topic", topic), ("type", header_type), ("md5sum", "0123456789abcdef0123456789abcdef"),
            ("message_definition", definition), ("latching", "0")))
        conn.sendall(struct.pack("<I", len(header)) + header)
        time.sleep(float(delay))
        while True:
            conn.sendall(struct.pack("<I", 4) + b"\0\0\0\0")
            time.sleep(0.2)
    except OSError:
        pass


tcp = socket.socket()
tcp.bind(("127.0.0.1", 0))
tcp.listen(8)
port = tcp.getsockname()[1]


def accept():
    while True:
        threading.Thread(target=serve, args=(tcp.accept()[0],), daemon=True).start()


threading.Thread(target=accept, daemon=True).start()


class Slave:
    def requestTopic(self, caller, t, protocols):
        return [1, "", ["TCPROS", "127.0.0.1", port]]

    def getPid(self, caller):
        return [1, "", 0]

    def publisherUpdate(self, caller, t, pubs):
        return [1, "", 0]

    def shutdown(self, caller, msg=""):
        return [1, "", 0]


slave = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
slave.register_instance(Slave())
uri = f"http://127.0.0.1:{slave.server_address[1]}/"
xmlrpc.client.ServerProxy(master).registerPublisher(name, topic, "evil_pkg/Evil", uri)
print("ready", flush=True)
slave.serve_forever()
'''


def test_live_publisher_header_is_refused_and_never_run(rostui_core: subprocess.Popen, ros_env: dict[str, str],
                                                         tmp_path: Path) -> None:
    """`rostui topic echo` decodes with each publisher's header: a poisoning definition from one publisher, then
    another publisher naming the poisoned type, must each be refused in one clear line, and no code run."""
    import signal

    definition, later_name = poisoned_definition()
    work = tmp_path / "echo_cwd"
    work.mkdir()
    script = tmp_path / "hostile_publisher.py"
    script.write_text(HOSTILE_PUBLISHER)
    poison, empty = tmp_path / "poison.txt", tmp_path / "empty.txt"
    poison.write_text(definition)
    empty.write_text("")
    master = ros_env["ROS_MASTER_URI"]
    publishers: list[subprocess.Popen] = []

    def publisher(name: str, header_type: str, definition_file: Path, delay: str) -> None:
        proc = subprocess.Popen([sys.executable, str(script), master, "/evil", name, header_type,
                                 str(definition_file), delay], env=ros_env, stdout=subprocess.PIPE, text=True)
        publishers.append(proc)
        assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"

    out, err = tmp_path / "echo.out", tmp_path / "echo.err"
    try:
        publisher("/poisoner", "evil_pkg/Evil", poison, "0")
        echo = subprocess.Popen([sys.executable, "-m", "rostui", "topic", "echo", "/evil"], env=ros_env, cwd=work,
                                stdout=out.open("w"), stderr=err.open("w"), stdin=subprocess.DEVNULL)
        try:
            wait_until(lambda: echo.poll() is not None or "a: 0" in out.read_text() or "/poisoner" in err.read_text(),
                       "echo to decode or refuse the poisoner")
            publisher("/namer", later_name, empty, "0.5")  # its messages come after the poisoner's
            wait_until(lambda: echo.poll() is not None or "/namer" in err.read_text(), "echo to refuse the namer")
            assert echo.poll() is None, "one refused publisher ended the echo"
            echo.send_signal(signal.SIGINT)
            echo.wait(timeout=60)
        finally:
            if echo.poll() is None:
                echo.kill()
                echo.wait()
    finally:
        for proc in publishers:
            proc.kill()
            proc.wait()
    assert not (work / "pwned").exists(), "the definition's code ran in the subscriber"
    lines = err.read_text().strip().splitlines()
    assert len(lines) == 2 and all(line.startswith("ERROR: refused a publisher of /evil: ") for line in lines), lines
    assert "publisher [/poisoner]" in lines[0] and "not a valid pkg/Type name" in lines[0], lines[0]
    assert "publisher [/namer]" in lines[1] and "not a valid pkg/Type name" in lines[1], lines[1]
    assert out.read_text() == "" and "Traceback" not in err.read_text()
