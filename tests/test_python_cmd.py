"""`rostui python` and `rostui shell-env`: unmodified scripts get rostui's genpy, roslib and message modules.

Each script in tests/python_compat/ runs unmodified under Debian's genpy (/usr/bin/python3) and under
`rostui python`; their outputs must be equal: the bytes every message and service type serializes to
(each filled with deterministic non-default values), its text, md5sum, definition and fields.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer

SCRIPTS = REPO / "tests" / "python_compat"
SERIALIZE = SCRIPTS / "serialize_types.py"
CUSTOM_ROOTS = (REPO / "tests" / "msg_corpus", REPO / "tests" / "msg_odd")
BUILTIN_SHARE = REPO / "rostui" / "share"

# Every msg and srv module the system Python's ROS message packages hold, as [kind, "pkg/Name", [message
# types its definition uses, from genpy's _full_text]].
_LIST_DEBIAN_TYPES = r'''
import importlib, json, os, site
types = []
for sp in site.getsitepackages():
    if not os.path.isdir(sp):
        continue
    for pkg in sorted(os.listdir(sp)):
        for kind in ("msg", "srv"):
            d = os.path.join(sp, pkg, kind)
            if os.path.isfile(os.path.join(d, "__init__.py")):
                for f in sorted(os.listdir(d)):
                    if f.startswith("_") and not f.startswith("__") and f.endswith(".py"):
                        module = importlib.import_module(f"{pkg}.{kind}.{f[:-3]}")
                        cls = getattr(module, f[1:-3])
                        texts = [cls._request_class._full_text, cls._response_class._full_text] \
                            if kind == "srv" else [cls._full_text]
                        uses = sorted({line[5:].strip() for text in texts for line in text.splitlines()
                                       if line.startswith("MSG: ")})
                        types.append([kind, pkg + "/" + f[1:-3], uses])
print(json.dumps(types))
'''


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "ROS_PACKAGE_PATH") and not k.startswith("ROSTUI_PYTHON")}
    env.update(extra)
    return env


def _genpy_ok() -> bool:
    if not Path(SYSTEM_PYTHON).exists():
        return False
    return subprocess.run([SYSTEM_PYTHON, "-c", "import genpy, genmsg, roslib, std_msgs.msg, geometry_msgs.msg, "
                           "sensor_msgs.msg, std_srvs.srv"], capture_output=True).returncode == 0


def need_genpy() -> None:
    need_peer(_genpy_ok(), "genpy, genmsg, roslib, the message packages (python3-genpy, python3-genmsg, "
                           "python3-roslib, python3-std-msgs, ...) under /usr/bin/python3")


def rostui_python(args: list[str], env: dict[str, str] | None = None, timeout: float = 120.0,
                  cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    """`rostui python ARGS` (this Python, ``-m rostui``) to completion."""
    return subprocess.run([sys.executable, "-m", "rostui", "python", *args], env=env or _env(), cwd=cwd,
                          capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL)


def system_python(args: list[str], env: dict[str, str] | None = None,
                  timeout: float = 300.0) -> subprocess.CompletedProcess[str]:
    """Debian's /usr/bin/python3 with ARGS, to completion."""
    return subprocess.run([SYSTEM_PYTHON, *args], env=env or _env(), cwd=REPO, capture_output=True, text=True,
                          timeout=timeout, stdin=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def debian_types(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A JSON file listing every message and service type Debian's python3-*-msgs packages ship."""
    need_genpy()
    listing = system_python(["-c", _LIST_DEBIAN_TYPES])
    assert listing.returncode == 0, listing.stderr
    path = tmp_path_factory.mktemp("types") / "debian.json"
    listed = json.loads(listing.stdout)
    path.write_text(json.dumps([[kind, name] for kind, name, uses in listed
                                if _definition_installed(kind, name) and all(_definition_installed("msg", u)
                                                                             for u in uses)]))
    return path


def _definition_installed(kind: str, type_name: str) -> bool:
    """True when Debian installs the type's .msg/.srv file or rostui has it built in.

    Some Debian packages ship only the generated Python (python3-move-base-msgs has no .msg anywhere,
    python3-actionlib needs actionlib_msgs' files from a -dev package): no tool without that ROS Python
    can know those types, or the types they use.
    """
    pkg, name = type_name.split("/")
    return any((share / pkg / kind / f"{name}.{kind}").is_file() for share in (Path("/usr/share"), BUILTIN_SHARE))


def test_every_debian_type_serializes_and_prints_as_genpy_does(debian_types: Path) -> None:
    types = json.loads(debian_types.read_text())
    assert len(types) > 90 and ["srv", "std_srvs/SetBool"] in types
    theirs = system_python([str(SERIALIZE), "modules", str(debian_types)])
    ours = rostui_python([str(SERIALIZE), "modules", str(debian_types)])
    assert theirs.returncode == 0, theirs.stderr[-3000:]
    assert ours.returncode == 0, ours.stderr[-3000:]
    assert ours.stderr == ""
    want, got = json.loads(theirs.stdout), json.loads(ours.stdout)
    assert not [t for t, e in want.items() if "error" in e]
    differ = sorted(t for t in want if want[t] != got.get(t))
    assert not differ, f"differ from genpy: {differ[:10]}"


def _without_definition(entry: dict[str, Any]) -> dict[str, Any]:
    if "request" in entry:
        return {k: _without_definition(entry[k]) for k in ("request", "response")}
    return {k: v for k, v in entry.items() if k not in ("full_text", "md5", "type")}


@pytest.mark.timeout(600)
def test_custom_packages_serialize_as_genpy_does(tmp_path: Path) -> None:
    """The corpus packages: genpy's classes from genpy.dynamic, rostui's from `<pkg>.msg` on ROS_PACKAGE_PATH."""
    need_genpy()
    types = [[kind, f"{p.parent.parent.name}/{p.stem}"] for root in CUSTOM_ROOTS for kind in ("msg", "srv")
             for p in sorted(root.glob(f"*/{kind}/*.{kind}"))]
    listing = tmp_path / "custom.json"
    listing.write_text(json.dumps(types))
    theirs = system_python([str(SERIALIZE), "dynamic", str(listing), *map(str, CUSTOM_ROOTS), str(BUILTIN_SHARE)],
                           timeout=600)
    ours = rostui_python([str(SERIALIZE), "modules", str(listing)],
                         env=_env(ROS_PACKAGE_PATH=os.pathsep.join(map(str, CUSTOM_ROOTS))))
    assert theirs.returncode == 0, theirs.stderr[-3000:]
    assert ours.returncode == 0, ours.stderr[-3000:]
    want, got = json.loads(theirs.stdout), json.loads(ours.stdout)
    built = {t: e for t, e in want.items() if "error" not in e}
    assert len(built) > 900
    differ = sorted(t for t, e in built.items() if _without_definition(e) != _without_definition(got[t]))
    assert not differ, f"differ from genpy: {differ[:10]}"
    assert "lambda_" in built["uuv_control_msgs/GetMBSMControllerParams"]["response"]["slots"]


@pytest.mark.parametrize("name,shows", [("genpy_basics.py", "genpy.Time[12000000345]"),
                                        ("no_genpy_import.py", "genpy.Time[0] genpy.Duration[0]")])
def test_a_plain_script_prints_what_it_prints_under_debians_genpy(name: str, shows: str) -> None:
    need_genpy()
    script = str(SCRIPTS / name)
    theirs = system_python([script, "a", "__name:=x"])
    ours = rostui_python([script, "a", "__name:=x"])
    assert theirs.returncode == 0, theirs.stderr
    assert (ours.returncode, ours.stderr) == (0, "")
    assert ours.stdout == theirs.stdout
    assert shows in ours.stdout


def test_argv_exit_status_and_main_pass_through() -> None:
    script = str(SCRIPTS / "argv_and_exit.py")
    args = ["3", "__name:=talker", "chatter:=/other", "_rate:=5", "--which", "-h", "--rostui"]
    r = rostui_python([script, *args])
    assert r.returncode == 3, r.stderr
    assert json.loads(r.stdout) == [[script, *args], "__main__", "beside the script"]


def test_a_missing_package_is_pythons_own_module_not_found_error() -> None:
    r = rostui_python([str(SCRIPTS / "missing_package.py")])
    assert r.returncode == 1
    assert r.stderr.splitlines()[-1] == "ModuleNotFoundError: No module named 'no_such_pkg_anywhere'"
    r = rostui_python([str(SCRIPTS / "missing_type.py")])
    assert r.returncode == 1
    assert r.stderr.splitlines()[-1].startswith("ImportError: cannot import name 'NoSuchType' from 'std_msgs.msg'")


def test_ctrl_c_reaches_the_script(tmp_path: Path) -> None:
    script = tmp_path / "waits.py"
    script.write_text(textwrap.dedent("""\
        import sys, time
        try:
            print("ready", flush=True)
            time.sleep(60)
        except KeyboardInterrupt:
            print("interrupted", flush=True)
            sys.exit(130)
        """))
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "python", str(script)], env=_env(), cwd=REPO,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        assert proc.stdout.readline() == "ready\n"
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
        proc.wait()
    assert (proc.returncode, out, err) == (130, "interrupted\n", "")


def no_real_ros_here() -> None:
    """These tests need this Python (the venv's) to see no real ROS, as CI's venv does."""
    from rostui.compat.choice import find_real_ros

    if find_real_ros(sys.path) is not None:
        pytest.skip("this Python imports a real ROS (a venv with system site packages)")


def test_which_names_rostuis_modules_when_no_real_ros_is_importable() -> None:
    no_real_ros_here()
    r = rostui_python(["--which"])
    assert r.returncode == 0
    assert r.stdout.startswith(
        "rostui python: the script gets rostui's rospy, genpy, roslib, rosbag and message modules (")
    r = rostui_python(["--which", "--real-ros"])
    assert "no real ROS is importable" in r.stdout
    r = rostui_python(["--real-ros", "--rostui", "x.py"])
    assert r.returncode == 2 and "exclude each other" in r.stderr


def test_real_ros_chosen_where_there_is_none_gives_no_ros_modules() -> None:
    no_real_ros_here()
    r = rostui_python(["--real-ros", str(SCRIPTS / "no_genpy_import.py")])
    assert r.returncode == 1
    assert r.stderr.splitlines()[-1] == "ModuleNotFoundError: No module named 'std_msgs'"


_USES_STRING = ("import io, genpy\nfrom std_msgs.msg import String\nb = io.BytesIO()\nString('hi').serialize(b)\n"
                "print(b.getvalue(), genpy.__file__)\n")


def _shell_env(args: list[str]) -> str:
    r = subprocess.run([sys.executable, "-m", "rostui", "shell-env", *args], env=_env(), cwd=REPO,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_shell_env_gives_a_plain_python_rostuis_modules(tmp_path: Path) -> None:
    script = tmp_path / "plain.py"
    script.write_text(_USES_STRING)
    exports = _shell_env([])
    assert exports.startswith("export PYTHONPATH=")
    r = subprocess.run(["bash", "-c", f'{exports}\nexec "$0" "$1"', sys.executable, str(script)], env=_env(),
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("b'\\x02\\x00\\x00\\x00hi' ") and "/rostui/compat/pylib/genpy/" in r.stdout


def test_a_real_ros_is_never_shadowed_silently(tmp_path: Path) -> None:
    """Debian's python3 with shell-env's path: the real ROS by default, rostui's on request; stderr says which."""
    need_genpy()
    script = tmp_path / "plain.py"
    script.write_text(_USES_STRING)
    for args, origin, says in (([], "/dist-packages/genpy/", "gets the real ROS at "),
                               (["--rostui"], "/rostui/compat/pylib/genpy/", "gets rostui's rospy, genpy")):
        exports = _shell_env(args)
        r = subprocess.run(["bash", "-c", f'{exports}\nexec "$0" "$1"', SYSTEM_PYTHON, str(script)], env=_env(),
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, r.stderr
        assert r.stdout.startswith("b'\\x02\\x00\\x00\\x00hi' ") and origin in r.stdout
        assert len(r.stderr.splitlines()) == 1 and says in r.stderr


def test_the_sitecustomize_ours_hides_still_runs(tmp_path: Path) -> None:
    own = tmp_path / "own_site"
    own.mkdir()
    (own / "sitecustomize.py").write_text(
        "import builtins\nbuiltins.OWN_SITE_RAN = getattr(builtins, 'OWN_SITE_RAN', 0) + 1\n")
    script = tmp_path / "site_ran.py"
    script.write_text("import builtins, sys\nprint(builtins.OWN_SITE_RAN, sys.modules['sitecustomize'].__file__)\n")
    r = rostui_python([str(script)], env=_env(PYTHONPATH=str(own)))
    assert r.returncode == 0, r.stderr
    runs, ours = r.stdout.split()
    assert runs == "1" and ours.endswith("/rostui/compat/pylib/sitecustomize.py")


def test_numpy_forms_read_numeric_arrays_as_numpy_arrays() -> None:
    import io

    import numpy

    from rostui.core.msg import get_message_class

    Floats = get_message_class("std_msgs/Float32MultiArray")
    Image = get_message_class("sensor_msgs/Image")
    msg = Floats(data=[0.5, 1.5, -2.0])
    plain, with_numpy = io.BytesIO(), io.BytesIO()
    msg.serialize(plain)
    Floats(data=numpy.array([0.5, 1.5, -2.0], dtype=numpy.float32)).serialize_numpy(with_numpy, numpy)
    assert plain.getvalue() == with_numpy.getvalue()
    back = Floats().deserialize_numpy(plain.getvalue(), numpy)
    assert isinstance(back.data, numpy.ndarray) and back.data.dtype == numpy.float32
    assert back.data.tolist() == [0.5, 1.5, -2.0]
    image = Image().deserialize_numpy(Image(height=1, width=2, data=b"\x01\x02").serialize(), numpy)
    assert image.data == b"\x01\x02"  # uint8[] stays bytes, as in genpy
