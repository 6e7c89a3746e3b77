"""A rospy node under `rostui python` imports only what it uses (issue 35).

The ROS wiki's talker, run unmodified but for a last line that prints which heavy modules it
has imported once its first message has been published and heard, has none of them: no numpy,
no OpenSSL, no YAML, no http.client, no uvloop. What it does not import stays usable: numpy
messages import numpy when asked, and TLS, http.client and xmlrpc.client's ServerProxy work
in the same script.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import rostui_cmd

HEAVY = ("numpy", "ssl", "_ssl", "_hashlib", "yaml", "http.client", "email.parser", "uvloop", "importlib.resources",
         "tempfile", "textual", "typer", "rich", "subprocess", "dataclasses", "datetime", "inspect", "ast", "dis")
"""Modules a talker needs none of (OpenSSL alone is 5 MB of its memory; subprocess, dataclasses, datetime and
inspect cost its start). Not ipaddress: a regular install's talker does without it, but the editable install's import
hook imports pathlib, and so urllib.parse with it, before rostui.compat can."""

TALKER = '''#!/usr/bin/env python
import rospy
from std_msgs.msg import String

def talker():
    pub = rospy.Publisher('chatter', String, queue_size=10)
    rospy.init_node('talker', anonymous=True)
    rate = rospy.Rate(10) # 10hz
    while not rospy.is_shutdown():
        hello_str = "hello world %s" % rospy.get_time()
        rospy.loginfo(hello_str)
        pub.publish(hello_str)
        if heard:
            break
        rate.sleep()

heard = []
rospy.Subscriber('chatter', String, heard.append)
talker()
import json, sys
print(json.dumps({"heard": heard[0].data.startswith("hello world"),
                  "heavy": sorted(m for m in HEAVY if m in sys.modules)}))
'''


def _run(tmp_path: Path, name: str, code: str, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    script = tmp_path / name
    script.write_text(code)
    return subprocess.run(rostui_cmd("python", str(script)), env=env, cwd=tmp_path, capture_output=True, text=True,
                          timeout=120)


def test_talker_imports_nothing_heavy(rostui_core: subprocess.Popen, ros_env: dict[str, str],
                                      tmp_path: Path) -> None:
    """The wiki's talker, heard by its own subscriber, has loaded none of HEAVY."""
    code = TALKER.replace("heard = []", f"HEAVY = {HEAVY!r}\nheard = []")
    out = _run(tmp_path, "talker.py", code, ros_env)
    assert out.returncode == 0, out.stderr
    said = json.loads(out.stdout.splitlines()[-1])
    assert said == {"heard": True, "heavy": []}, out.stdout + out.stderr


def test_numpy_msg_imports_numpy_when_asked(rostui_core: subprocess.Popen, ros_env: dict[str, str],
                                             tmp_path: Path) -> None:
    """rospy.numpy_msg still gives numpy arrays: numpy comes in with it, not before."""
    pytest.importorskip("numpy")
    code = '''import io, sys
import rospy
from std_msgs.msg import Float32MultiArray
print("numpy" in sys.modules)
from rospy.numpy_msg import numpy_msg
print("numpy" in sys.modules)
import numpy
Floats = numpy_msg(Float32MultiArray)
buf = io.BytesIO()
Floats(data=numpy.array([1.5, 2.5], dtype=numpy.float32)).serialize(buf)
back = Floats().deserialize(buf.getvalue())
print(type(back.data).__name__, back.data.tolist())
'''
    out = _run(tmp_path, "floats.py", code, ros_env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-3:] == ["False", "True", "ndarray [1.5, 2.5]"], out.stdout + out.stderr


def test_tls_and_http_client_still_work(rostui_core: subprocess.Popen, ros_env: dict[str, str],
                                        tmp_path: Path) -> None:
    """After `import rospy`, asyncio still speaks TLS (a handshake with a plain-text server fails as an SSL
    error), and xmlrpc.client's ServerProxy asks the master over http.client."""
    code = '''import asyncio, os, socket, threading
import rospy
import xmlrpc.client

from http import client as http_client
print("real http.client", http_client.__file__.endswith("client.py"))
master = xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"])
print("pid", master.getPid("/probe")[0])

server = socket.create_server(("127.0.0.1", 0))
def answer():
    conn, _ = server.accept()
    conn.recv(4096)
    conn.sendall(b"HTTP/1.0 400 Bad Request\\r\\n\\r\\n")
    conn.close()
threading.Thread(target=answer, daemon=True).start()

async def main():
    import ssl
    try:
        await asyncio.open_connection("127.0.0.1", server.getsockname()[1], ssl=ssl.create_default_context(),
                                      server_hostname="localhost")
    except ssl.SSLError:
        print("ssl error")
asyncio.run(main())
'''
    out = _run(tmp_path, "tls.py", code, ros_env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-3:] == ["real http.client True", "pid 1", "ssl error"], out.stdout + out.stderr


def test_script_error_shows_the_scripts_frames(tmp_path: Path) -> None:
    """An uncaught exception prints as `python SCRIPT` prints it: from the script's frame, exit status 1."""
    out = _run(tmp_path, "fails.py", "import sys\n\ndef f():\n    raise ValueError('bad ' + sys.argv[0])\n\nf()\n",
               dict(os.environ))
    assert out.returncode == 1
    lines = out.stderr.splitlines()
    assert lines[0] == "Traceback (most recent call last):", out.stderr
    assert lines[1].startswith(f'  File "{tmp_path / "fails.py"}", line 6, in <module>'), out.stderr
    assert lines[-1] == f"ValueError: bad {tmp_path / 'fails.py'}", out.stderr


def test_script_that_does_not_compile_prints_as_python(tmp_path: Path) -> None:
    """A syntax error is printed as `python SCRIPT` prints it (no traceback), exit status 1."""
    script = tmp_path / "broken.py"
    script.write_text("x = (\nprint(1)\n")
    ours = subprocess.run(rostui_cmd("python", str(script)), capture_output=True, text=True, timeout=60)
    plain = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=60)
    assert (ours.returncode, ours.stderr) == (plain.returncode, plain.stderr) == (1, plain.stderr)
    assert plain.stderr.rstrip().endswith("SyntaxError: '(' was never closed")


def test_ctrl_c_ends_the_script_as_python_does(tmp_path: Path) -> None:
    """SIGINT: KeyboardInterrupt from the script's own line, and the process ends by SIGINT, as under python."""
    script = tmp_path / "waits.py"
    script.write_text("import time\nprint('waiting', flush=True)\ntime.sleep(60)\n")
    proc = subprocess.Popen(rostui_cmd("python", str(script)), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    assert proc.stdout is not None and proc.stdout.readline() == "waiting\n"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == -signal.SIGINT
    lines = err.splitlines()
    assert lines[1].startswith(f'  File "{script}", line ') and lines[-1] == "KeyboardInterrupt", err


def test_asyncio_subprocess_after_rospy(ros_env: dict[str, str], tmp_path: Path) -> None:
    """asyncio imported without subprocess (a stand-in in its modules) still starts child processes, and the
    script's own ``import subprocess`` is the real module."""
    code = '''import sys
import rospy
print("subprocess" in sys.modules)
import asyncio
async def main():
    proc = await asyncio.create_subprocess_exec(sys.executable, "-c", "print('child')", stdout=asyncio.subprocess.PIPE)
    print((await proc.communicate())[0].decode().strip(), asyncio.subprocess.PIPE == -1)
asyncio.run(main())
import subprocess
print(subprocess.run([sys.executable, "-c", "print(1)"], capture_output=True, text=True).stdout.strip(),
      type(subprocess).__name__)
'''
    out = _run(tmp_path, "children.py", code, ros_env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["False", "child True", "1 module"], out.stdout + out.stderr


def test_asyncio_inspect_after_rospy(ros_env: dict[str, str], tmp_path: Path) -> None:
    """asyncio imported without inspect (a stand-in in its modules) still tells coroutine functions apart (without
    importing it for functions, methods, partials and builtins, as every Ctrl-C handler asks) and names a callback in
    debug mode, and the script's own ``import inspect`` is the real module."""
    code = '''import sys
import rospy
print("inspect" in sys.modules)
import asyncio, functools, signal
async def job():
    pass
def plain():
    pass
print(asyncio.iscoroutinefunction(job), asyncio.iscoroutinefunction(plain))
loop = asyncio.new_event_loop()
stop = asyncio.Event()
for handler in (stop.set, functools.partial(plain), print, plain):
    loop.add_signal_handler(signal.SIGUSR1, handler)
try:
    loop.add_signal_handler(signal.SIGUSR1, functools.partial(job))
except TypeError:
    print("refused", "inspect" in sys.modules)
class Job:
    async def __call__(self):
        pass
print(asyncio.iscoroutinefunction(Job()), "inspect" in sys.modules)
loop.set_debug(True)
print("plain() at " in repr(loop.call_soon(plain)))
loop.close()
import inspect
print(type(inspect).__name__, inspect.isfunction(plain))
'''
    out = _run(tmp_path, "coroutines.py", code, ros_env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["False", "True False", "refused False", "False True", "True", "module True"], \
        out.stdout + out.stderr


def test_xmlrpc_datetime_after_rospy(ros_env: dict[str, str], tmp_path: Path) -> None:
    """xmlrpc.client imported without the datetime module still marshals the datetime class a script's
    ``import datetime`` gives (the same class), both ways."""
    code = '''import sys
import rospy
import xmlrpc.client
print("datetime" in sys.modules)
import datetime
stamp = datetime.datetime(2020, 1, 2, 3, 4, 5)
body = xmlrpc.client.dumps((stamp,), "m")
print("<dateTime.iso8601>20200102T03:04:05</dateTime.iso8601>" in body,
      xmlrpc.client.loads(body, use_builtin_types=True)[0][0] == stamp, xmlrpc.client.datetime is datetime.datetime)
'''
    out = _run(tmp_path, "stamps.py", code, ros_env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["False", "True True True"], out.stdout + out.stderr


def test_compat_imports_urllib_parse_without_ipaddress() -> None:
    """rostui.compat imports pathlib (and so urllib.parse) with a stand-in for ipaddress, which imports the real
    module when a bracketed host needs it; run without site, so no editable install's hook imports them first."""
    code = ("import sys, rostui.compat, urllib.parse; print('ipaddress' in sys.modules); "
            "print(urllib.parse.urlsplit('http://[::1]:11311/').hostname, 'ipaddress' in sys.modules); "
            "import ipaddress; print(urllib.parse.ipaddress is ipaddress)")
    out = subprocess.run([sys.executable, "-S", "-c", code], env={"PYTHONPATH": str(Path(__file__).parent.parent)},
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["False", "::1 True", "True"], out.stdout + out.stderr
