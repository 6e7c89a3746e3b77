"""dynamic_reconfigure under `rostui python` against Debian's python3-dynamic-reconfigure, with real scripts and peers.

- The generator: real ``.cfg`` files (navigation's costmap_2d, move_base and dwa_local_planner, the last
  importing base_local_planner's ``local_planner_limits``; turtlebot3_autorace's camera configs;
  dynamic_reconfigure's own ``Test.cfg``) become ``<pkg>.cfg.<Name>Config`` modules with the same names
  and values as the modules Debian's generator writes.
- The server and client: dynamic_reconfigure's own ``test/testserver.py`` changed by the real ``dynparam``
  (list, get, set with enum names, booleans as words and values out of range, dump, load, an unknown name,
  set_from_parameters from the parameter server and from ``_name:=value`` words),
  and its ``test/testclient.py`` against the server, each pairing of rostui's side and Debian's compared
  with Debian's on both sides. ``testserver_multiple_ns.py``'s four servers are listed and read alike.
- Hostile descriptions: groups that are their own ancestors and an ``edit_method`` holding code cost
  nothing (Debian's client evaluates the text).

Sources and licences: tests/python_compat/real/SOURCES.md.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import pytest

from conftest import REPO, SYSTEM_PYTHON, new_ros_env, rostui_cmd, running_core, shared_build
from reconfigure_helpers import (
    DEBIAN_DYNPARAM, DEBIAN_GENERATOR_DIR, DR, NODE, REAL, clean_env, forget_parameters,
    need_debian_dynamic_reconfigure, start_server,
)
from rospy_scripts import script_command

DYNPARAM = DR / "scripts" / "dynparam"
DUMP = REPO / "tests" / "python_compat" / "own" / "dump_config_module.py"
WHOLE_PRINT = REPO / "tests" / "python_compat" / "own" / "atomic_print_run.py"
PREFIX = re.compile(r"^\[(DEBUG|INFO|WARN|ERROR|FATAL)\] \[\d+\.\d+\]: ", re.M)
PROBE_NOISE = "Inbound TCP/IP connection failed: connection from sender terminated before handshake header received"
"""What Debian's rospy server logs, now and then, when a client's wait_for_service probe (a connection closed
before any header) is read as a failed connection: a race in the server, not a reconfigure result."""

CFG_PACKAGES = {  # package -> (its folder under tests/python_compat/real, the .cfg names it has)
    "costmap_2d": ("navigation/costmap_2d", ["Costmap2D"]),
    "move_base": ("navigation/move_base", ["MoveBase"]),
    "dwa_local_planner": ("navigation/dwa_local_planner", ["DWAPlanner"]),
    "base_local_planner": ("navigation/base_local_planner", []),
    "turtlebot3_autorace_camera": ("turtlebot3_autorace_2020/turtlebot3_autorace_camera",
                                   ["ImageProjectionParams", "ImageCompensationParams"]),
}


# -- the generator ---------------------------------------------------------------------------------------------


def _package_tree(root: Path) -> Path:
    """A ROS_PACKAGE_PATH folder holding the real .cfg packages (one without its package.xml here gets one)."""
    root.mkdir()
    for package, (folder, _) in CFG_PACKAGES.items():
        target = root / package
        shutil.copytree(REAL / folder, target)
        if not (target / "package.xml").is_file():
            (target / "package.xml").write_text(f"<package><name>{package}</name></package>\n")
    return root


def _debian_generated(cfg: Path, out: Path, env: dict[str, str]) -> Path:
    """Run a .cfg file through Debian's generator as catkin does; the Python module it wrote."""
    done = subprocess.run([SYSTEM_PYTHON, str(cfg), str(DEBIAN_GENERATOR_DIR), str(out / "bin"), str(out / "cpp"),
                           str(out / "py")], env=env, cwd=out, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stdout + done.stderr
    return out / "py" / "cfg" / f"{cfg.stem}Config.py"


def test_cfg_files_make_the_modules_debians_generator_writes(tmp_path: Path, ros_env: dict[str, str]) -> None:
    need_debian_dynamic_reconfigure()
    tree = _package_tree(tmp_path / "packages")
    env = dict(clean_env(ros_env), PYTHONPATH=str(tree / "base_local_planner" / "src"))
    pairs: list[tuple[str, Path | None]] = [("dynamic_reconfigure.cfg.TestConfig", None)]
    for package, (_, names) in CFG_PACKAGES.items():
        pairs += [(f"{package}.cfg.{name}Config", tree / package / "cfg" / f"{name}.cfg") for name in names]
    ours_env = dict(clean_env(ros_env), ROS_PACKAGE_PATH=str(tree))
    for module, cfg in pairs:
        debian_module = module if cfg is None else str(_debian_generated(cfg, tmp_path, env))
        debian = subprocess.run([SYSTEM_PYTHON, str(DUMP), debian_module], env=env, capture_output=True, text=True)
        ours = subprocess.run(rostui_cmd("python", "--rostui", str(DUMP), module), env=ours_env, capture_output=True,
                              text=True)
        assert debian.returncode == 0 and ours.returncode == 0, debian.stderr + ours.stderr
        assert "config_description = {'name': 'Default'" in ours.stdout
        assert ours.stdout == debian.stdout, module


def test_a_broken_cfg_file_fails_the_import_naming_its_line(tmp_path: Path, ros_env: dict[str, str]) -> None:
    package = tmp_path / "broken_cfg"
    (package / "cfg").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>broken_cfg</name></package>\n")
    (package / "cfg" / "Bad.cfg").write_text(
        "from dynamic_reconfigure.parameter_generator_catkin import *\n"
        "gen = ParameterGenerator()\n"
        "gen.add('fine', int_t, 0, 'A fine one', 1, 0, 5)\n"
        "gen.add('not-a-name', int_t, 0, 'A dash', 1)\n"
        "exit(gen.generate('broken_cfg', 'node', 'Bad'))\n")
    env = dict(clean_env(ros_env), ROS_PACKAGE_PATH=str(tmp_path))
    done = subprocess.run(rostui_cmd("python", "--rostui", "-c", "import broken_cfg.cfg.BadConfig"), env=env,
                          capture_output=True, text=True)
    assert done.returncode != 0
    assert f"{package / 'cfg' / 'Bad.cfg'}:4: Exception: The name of field 'not-a-name' does not follow the ROS " \
           "naming conventions" in done.stderr, done.stderr
    missing = subprocess.run(rostui_cmd("python", "--rostui", "-c", "from broken_cfg.cfg import OtherConfig"),
                             env=env, capture_output=True, text=True)
    assert missing.stderr.splitlines()[-1].endswith("no .cfg file of package broken_cfg generates OtherConfig"), \
        missing.stderr


# -- the server and the client -----------------------------------------------------------------------------


def dynparam(side: str, env: dict[str, str], cwd: Path, *args: str) -> str:
    """Run dynparam: the real one (rostui python on the repository's copy, or Debian's) or ``rostui dynparam``;
    what it said, tracebacks cut to their last line (the files in them differ)."""
    if side == "rostui":
        cmd = rostui_cmd("dynparam", *args)
    elif side == "shim":
        cmd = script_command("shim", DYNPARAM, *args)
    else:
        cmd = [SYSTEM_PYTHON, str(DEBIAN_DYNPARAM), *args]
    done = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, timeout=120)
    said = [line for line in (done.stdout + done.stderr).splitlines()
            if not line.startswith(("  ", "Traceback (most recent call last)"))]
    return "\n".join([f"$ dynparam {' '.join(args)} -> exit {done.returncode}", *said, ""])


SESSION = [
    ("list",),
    ("get", NODE),
    ("set", NODE, "{'int_': 5, 'int_enum_': 'Large', 'double_': 20, 'bool_': 'yes', 'str_': 'hi'}"),
    ("set", NODE, "int_", "-30"),
    ("dump", NODE, "dump.yaml"),
    ("set", NODE, "int_", "3"),
    ("get", NODE),
    ("set", NODE, "no_such_parameter", "1"),
]
LOAD = ("load", NODE, "dump.yaml")
DEBIAN_LOAD_FAILS = "error processing request: 'list' object has no attribute 'items'"
"""What Debian's Python server answers any request that carries group states, as every dump does: its
decode_config walks the generated description's list of groups as if it were a dict."""


@dataclass(frozen=True)
class Session:
    """What a dynparam session against testserver.py gave: its transcript with the file it dumped, what the
    server printed meanwhile, and what loading the dump back then said and left (a get after it)."""

    transcript: str
    server_said: str
    loaded: str

    @classmethod
    def run(cls, server_side: str, dynparam_side: str, env: dict[str, str], work: Path) -> Session:
        """Start the server on *server_side*, drive it with dynparam of *dynparam_side*, in the folder *work*."""
        work.mkdir()
        server = start_server(server_side, env, work / "server.log")
        try:
            transcript = "".join(dynparam(dynparam_side, env, work, *args) for args in SESSION)
            transcript += (work / "dump.yaml").read_text()
            server_said = "".join(line for line in PREFIX.sub("[\\1] ", server.output()).splitlines(True)
                                  if PROBE_NOISE not in line)
            loaded = dynparam(dynparam_side, env, work, *LOAD) + dynparam(dynparam_side, env, work, "get", NODE)
        finally:
            server.interrupt()
            forget_parameters(env, NODE)
        return cls(transcript, server_said, loaded)


@dataclass(frozen=True)
class DebianBaseline:
    """Debian on both sides, on Debian's roscore: the dynparam session and testclient.py's lines."""

    session: Session
    client: Counter[str]


@pytest.fixture(scope="session")
def debian(tmp_path_factory: pytest.TempPathFactory) -> DebianBaseline:
    """What every pairing is compared with, made once per test run and shared by the workers: each of the six
    session tests and three client tests once ran Debian's side again (ten dynparam processes a session)."""
    need_debian_dynamic_reconfigure()

    def build(folder: Path) -> None:
        env = clean_env(new_ros_env(folder))
        with running_core("roscore", env):
            session = Session.run("real", "real", env, folder / "session")
            client = client_lines("real", "real", env, folder / "client")
        (folder / "baseline.json").write_text(json.dumps({"session": session.__dict__, "client": client}))

    made = json.loads((shared_build(tmp_path_factory, "dynparam-debian", build) / "baseline.json").read_text())
    return DebianBaseline(Session(**made["session"]), Counter(made["client"]))


UNKNOWN_NAME_EXIT = (f"$ dynparam set {NODE} no_such_parameter 1 -> exit 0",
                     f"$ dynparam set {NODE} no_such_parameter 1 -> exit 1")
"""dynparam's exit status for an unknown parameter, and `rostui dynparam`'s: the same line said, but an error
exits non-zero."""


def check_session(server_side: str, dynparam_side: str, env: dict[str, str], work: Path,
                  expected: Session) -> None:
    """The session with rostui on one side or both gives what it gives with Debian on both (*expected*); loading
    a dump fails against Debian's server and works against rostui's."""
    session = Session.run(server_side, dynparam_side, env, work / "mixed")
    assert "'int_enum_': 2" in session.transcript and "'str_': 'hiAAA'" in session.transcript, session.transcript
    assert "error updating parameters: don't know parameter: no_such_parameter" in session.transcript
    transcript = expected.transcript
    if dynparam_side == "rostui":
        assert UNKNOWN_NAME_EXIT[1] in session.transcript, session.transcript
        transcript = transcript.replace(*UNKNOWN_NAME_EXIT)
    assert session.transcript == transcript
    assert session.server_said == expected.server_said
    assert DEBIAN_LOAD_FAILS in expected.loaded, expected.loaded
    if server_side == "real":
        assert DEBIAN_LOAD_FAILS in session.loaded, session.loaded
    else:  # the dump's int_ (-9) and str_ ('hiAA') are back, through the server's callback (int_ |= 1, str_ += 'A')
        assert f"$ dynparam {' '.join(LOAD)} -> exit 0" in session.loaded, session.loaded
        assert "'int_': -9," in session.loaded and "'str_': 'hiAAA'," in session.loaded, session.loaded


@pytest.mark.parametrize("server_side,dynparam_side", [("shim", "real"), ("real", "shim"), ("shim", "shim")])
def test_dynparam_session_matches_debians(server_side: str, dynparam_side: str, rostui_core: object,
                                          ros_env: dict[str, str], tmp_path: Path, debian: DebianBaseline) -> None:
    check_session(server_side, dynparam_side, clean_env(ros_env), tmp_path, debian.session)


@pytest.mark.parametrize("server_side", ["real", "shim"])
def test_rostui_dynparam_session_matches_debians(server_side: str, rostui_core: object, ros_env: dict[str, str],
                                                 tmp_path: Path, debian: DebianBaseline) -> None:
    check_session(server_side, "rostui", clean_env(ros_env), tmp_path, debian.session)


def test_debians_dynparam_changes_a_rostui_server_on_roscore(real_roscore: object, ros_env: dict[str, str],
                                                             tmp_path: Path, debian: DebianBaseline) -> None:
    check_session("shim", "real", clean_env(ros_env), tmp_path, debian.session)


def client_lines(client_side: str, server_side: str, env: dict[str, str], work: Path) -> Counter[str]:
    """Every line testclient.py printed against testserver.py. Its config callback prints from a subscriber thread
    while the main thread prints: each print is made whole (WHOLE_PRINT), and the lines compared as a multiset."""
    work.mkdir()
    server = start_server(server_side, env, work / "server.log")
    try:
        done = subprocess.run(script_command(client_side, WHOLE_PRINT, str(DR / "test" / "testclient.py")), env=env,
                              capture_output=True, text=True, timeout=120)
    finally:
        server.interrupt()
        forget_parameters(env, NODE)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stdout + done.stderr
    return Counter(done.stdout.splitlines())


@pytest.mark.parametrize("client_side,server_side", [("shim", "real"), ("real", "shim"), ("shim", "shim")])
def test_testclient_prints_what_it_prints_under_debian(client_side: str, server_side: str, rostui_core: object,
                                                       ros_env: dict[str, str], tmp_path: Path,
                                                       debian: DebianBaseline) -> None:
    said = client_lines(client_side, server_side, clean_env(ros_env), tmp_path / "mixed")
    assert said["Medium is a constant that is set to 1: 1"] == 1
    assert said["New callback is done..."] == 1
    assert said == debian.client


def test_four_servers_of_one_node_list_and_read_alike(rostui_core: object, ros_env: dict[str, str],
                                                     tmp_path: Path) -> None:
    need_debian_dynamic_reconfigure()
    env = clean_env(ros_env)
    outputs = []
    namespaces = ("/absolute_ns", NODE, f"{NODE}/alternate_ns", f"{NODE}/alternate_ns/second_lvl")
    for side in ("real", "shim"):
        work = tmp_path / side
        work.mkdir()
        server = start_server(side, env, work / "server.log", "testserver_multiple_ns.py", namespaces)
        try:
            outputs.append("".join(dynparam("real", env, work, *args) for args in (
                ("list",), ("get", "/absolute_ns"), ("get", f"{NODE}/alternate_ns/second_lvl"))))
        finally:
            server.interrupt()
            forget_parameters(env, "/absolute_ns", NODE)
    debian, ours = outputs
    assert ours.splitlines()[1:5] == list(namespaces)
    assert ours == debian


def test_hostile_descriptions_cost_nothing(ros_env: dict[str, str], tmp_path: Path) -> None:
    script = tmp_path / "hostile.py"
    script.write_text(
        "from dynamic_reconfigure.encoding import decode_description, get_tree\n"
        "from dynamic_reconfigure.client import Client\n"
        "from dynamic_reconfigure.msg import ConfigDescription, Group, ParamDescription\n"
        "loop = ConfigDescription(groups=[Group(name='Default', id=0, parent=0),\n"
        "    Group(name='a', id=1, parent=0), Group(name='b', id=2, parent=1), Group(name='back', id=1, parent=2),\n"
        "    Group(name='c', id=4, parent=0, parameters=[ParamDescription(name='x', type='int',\n"
        "        edit_method=\"__import__('os').system('touch PWNED')\")])])\n"
        "tree = decode_description(loop)\n"
        "print(sorted(tree['groups']), list(tree['groups']['a']['groups']), list(tree['groups']['a']['groups']['b']['groups']))\n"
        "print(sorted(get_tree(loop)['groups']))\n"
        "client = Client.__new__(Client)\n"
        "client._description_callback = None\n"
        "import threading; client._cv = threading.Condition()\n"
        "client._descriptions_msg(loop)\n"
        "print(client._convert('x', 'Small'))\n")
    done = subprocess.run(rostui_cmd("python", "--rostui", str(script)), env=clean_env(ros_env), cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode != 0  # 'Small' is no int and no enum constant: the conversion fails, nothing runs
    # the group that would be its own grandparent is left out; the rest of the tree is read
    assert done.stdout.splitlines()[:2] == ["['a', 'c'] ['b'] []", "['a', 'c']"], done.stdout + done.stderr
    assert "can't set parameter 'x'" in done.stderr, done.stderr
    assert not (tmp_path / "PWNED").exists()


def test_debians_server_on_roscore_is_changed_by_rostui_dynparam(real_roscore: object, ros_env: dict[str, str],
                                                                 tmp_path: Path, debian: DebianBaseline) -> None:
    check_session("real", "rostui", clean_env(ros_env), tmp_path, debian.session)


def test_rostui_dynparam_says_what_is_wrong_in_one_line(rostui_core: object, ros_env: dict[str, str],
                                                        tmp_path: Path) -> None:
    env = clean_env(ros_env)
    bad = tmp_path / "bad.yaml"
    bad.write_text("int_: 1\nstr_: [unclosed\n")
    cases = [
        (("get", "/nope"), "ERROR: no reconfigure server [/nope]: no service /nope/set_parameters on the master"),
        (("load", "/nope", str(bad)), f"ERROR: {bad}:3: "),
        (("load", "/nope", str(tmp_path / "missing.yaml")), f"ERROR: cannot read [{tmp_path / 'missing.yaml'}]: "),
        (("set", "/nope", "[1, 2]"), "rostui dynparam set: give a parameter and its value, or a YAML mapping"),
    ]
    for args, first_line in cases:
        done = subprocess.run(rostui_cmd("dynparam", *args), env=env, capture_output=True, text=True, timeout=60)
        assert done.returncode == 1, (args, done.stdout, done.stderr)
        assert done.stderr.startswith(first_line) and len(done.stderr.splitlines()) == 1, (args, done.stderr)
    unreachable = dict(env, ROS_MASTER_URI="http://127.0.0.1:9/")
    done = subprocess.run(rostui_cmd("dynparam", "get", "/x"), env=unreachable, capture_output=True, text=True,
                          timeout=60)
    assert (done.returncode, done.stderr) == (1, "ERROR: Unable to communicate with master at http://127.0.0.1:9/\n")


FROM_PARAMETERS = [  # (this dynparam's node name, what the parameter server holds under it, the _name:=value words)
    ("adjust_server", {"int_": 4, "double_": 2.5}, ["_str_:=from_words"]),
    ("adjust_words", {}, ["_int_:=-20", "_bool_:=true"]),
]


def test_set_from_parameters_does_what_debians_does(rostui_core: object, ros_env: dict[str, str],
                                                    tmp_path: Path) -> None:
    """`dynparam set_from_parameters NODE` sends NODE what the parameter server holds under its own name and its
    ``_name:=value`` words (as a launch file's <param> tags put them): Debian's dynparam and rostui's, each against
    a fresh Debian test server and each change followed by a `get`, give the same transcript; with nothing to send
    both say so, and rostui's exits 1."""
    from rostui.core.xmlrpc import call_sync

    need_debian_dynamic_reconfigure()
    env = clean_env(ros_env)
    said: dict[str, str] = {}
    for side in ("real", "rostui"):
        server = start_server("real", env, tmp_path / f"server_{side}.log")
        said[side] = ""
        try:
            for me, stored, words in FROM_PARAMETERS:
                for name, value in stored.items():
                    call_sync(env["ROS_MASTER_URI"], "setParam", "/test", f"/{me}/{name}", value)
                said[side] += dynparam(side, env, tmp_path, "set_from_parameters", NODE, f"__name:={me}", *words)
                said[side] += dynparam(side, env, tmp_path, "get", NODE)
                forget_parameters(env, f"/{me}")
            said[side] += dynparam(side, env, tmp_path, "set_from_parameters", NODE, "__name:=adjust_nothing")
        finally:
            server.interrupt()
            forget_parameters(env, NODE)
    assert "'int_': 5," in said["real"] and "'str_': 'from_wordsA'," in said["real"], said["real"]
    assert "'int_': -9," in said["real"], said["real"]  # -20 clamped to the minimum -10, then the server's | 1
    nothing = f"$ dynparam set_from_parameters {NODE} __name:=adjust_nothing -> exit 0\n" \
        "error updating parameters: no parameters found on parameter server\n"
    assert said["real"].endswith(nothing), said["real"]
    assert said["rostui"] == said["real"][:-len(nothing)] + nothing.replace("exit 0", "exit 1"), said


@pytest.mark.parametrize("word, says", [
    ("_x:=[1", "ERROR: invalid value for parameter '_x': '[1' is not valid YAML"),
    ("_a b:=1", "ERROR: invalid ROS parameter name '_a b'"),
    ("extra", "rostui dynparam set_from_parameters: too many arguments: extra"),
])
def test_set_from_parameters_refuses_bad_words_in_one_line(ros_env: dict[str, str], tmp_path: Path, word: str,
                                                           says: str) -> None:
    done = dynparam("rostui", ros_env, tmp_path, "set_from_parameters", NODE, word)
    assert done.startswith(f"$ dynparam set_from_parameters {NODE} {word} -> exit 1\n{says}"), done
    assert done.count("\n") == 2, done
