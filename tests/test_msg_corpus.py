"""md5sums and message definitions of 1,000+ public message and service types equal genmsg's and genpy's.

The types are real packages' ``.msg``/``.srv`` files (``tests/msg_corpus``, sources in its
SOURCES.md) plus ``tests/msg_odd``, written to reach the corners of genmsg's grammar that public
packages seldom do.  Debian's genmsg and genpy, run once under the system Python, read the same
files; every type must hash and print alike in rostui.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from cli_helpers import rostui
from conftest import SYSTEM_PYTHON, need_command, need_peer
from rostui.core import packages
from rostui.core.msg import MessageSpecError
from rostui.core.msg.registry import TypeStore, split_definition
from rostui.core.packages import BUILTIN_SHARE

HERE = Path(__file__).resolve().parent
CORPUS = HERE / "msg_corpus"
ODD = HERE / "msg_odd"
ROOTS = (CORPUS, ODD, BUILTIN_SHARE)

# Each type as Debian's genmsg (md5, full text) and genpy (the generated class's _md5sum and _full_text)
# see it; an exception is recorded as the type's "error".
_ORACLE = r'''
import ast, json, os, sys, warnings
warnings.simplefilter("ignore")
import genmsg.gentools as gt, genmsg.msg_loader as ml, genpy.generator as gg

search, types = {}, []
for root in sys.argv[1:]:
    for pkg in sorted(os.listdir(root)):
        for kind in ("msg", "srv"):
            d = os.path.join(root, pkg, kind)
            if os.path.isdir(d) and pkg not in search:
                types += [(kind, pkg + "/" + f[:-4]) for f in sorted(os.listdir(d)) if f.endswith("." + kind)]
        dirs = [os.path.join(root, pkg, k) for k in ("msg", "srv") if os.path.isdir(os.path.join(root, pkg, k))]
        if dirs and pkg not in search:
            search[pkg] = dirs

def genpy_classes(lines):
    out = {}
    for node in ast.parse("\n".join(lines)).body:
        if isinstance(node, ast.ClassDef):
            out[node.name] = {a.targets[0].id: ast.literal_eval(a.value) for a in node.body
                              if isinstance(a, ast.Assign) and isinstance(a.targets[0], ast.Name)
                              and a.targets[0].id in ("_md5sum", "_full_text")}
    return out

def half(ctx, spec):
    return {"md5": gt.compute_md5(ctx, spec), "full_text": gt.compute_full_text(ctx, spec)}

def genpy_half(entry, cls):
    entry.update(genpy_md5=cls["_md5sum"], genpy_full_text=cls["_full_text"])

out = {}
for kind, t in types:
    short = t.split("/")[1]
    ctx = ml.MsgContext.create_default()
    try:
        if kind == "msg":
            spec = ml.load_msg_by_type(ctx, t, search)
            ml.load_depends(ctx, spec, search)
            out[t] = e = {"kind": kind, **half(ctx, spec)}
        else:
            spec = ml.load_srv_by_type(ctx, t, search)
            ml.load_depends(ctx, spec, search)
            out[t] = e = {"kind": kind, "md5": gt.compute_md5(ctx, spec),
                          "request": half(ctx, spec.request), "response": half(ctx, spec.response)}
    except Exception as ex:
        out[t] = {"kind": kind, "error": "%s: %s" % (type(ex).__name__, ex)}
        continue
    try:  # genpy's class for the type: a definition genmsg hashes may still be no Python
        if kind == "msg":
            genpy_half(e, genpy_classes(gg.msg_generator(ctx, spec, search))[short])
        else:
            classes = genpy_classes(gg.srv_generator(ctx, spec, search))
            e["genpy_md5"] = classes[short]["_md5sum"]
            genpy_half(e["request"], classes[short + "Request"])
            genpy_half(e["response"], classes[short + "Response"])
    except Exception as ex:
        e["genpy_error"] = "%s: %s" % (type(ex).__name__, ex)
json.dump(out, sys.stdout)
'''


def _genmsg_ok() -> bool:
    if not Path(SYSTEM_PYTHON).exists():
        return False
    return subprocess.run([SYSTEM_PYTHON, "-c", "import genmsg.gentools, genpy.generator"],
                          capture_output=True).returncode == 0


@pytest.fixture(scope="module")
def oracle() -> dict[str, Any]:
    """Every corpus type as Debian's genmsg and genpy compute it (one subprocess for all)."""
    need_peer(_genmsg_ok(), "genmsg, genpy (python3-genmsg, python3-genpy) under /usr/bin/python3")
    r = subprocess.run([SYSTEM_PYTHON, "-c", _ORACLE, *map(str, ROOTS)], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    result: dict[str, Any] = json.loads(r.stdout)
    return result


@pytest.fixture(scope="module")
def store() -> Iterator[TypeStore]:
    """A fresh type store loading from the corpus roots as ROS_PACKAGE_PATH, as a user's would."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("ROS_PACKAGE_PATH", f"{CORPUS}:{ODD}")
        packages.clear_cache()
        yield TypeStore(load_from_packages=True)
    packages.clear_cache()


def _corpus_types(root: Path) -> set[str]:
    return {f"{p.parent.parent.name}/{p.stem}" for p in root.glob("*/msg/*.msg")} | \
           {f"{p.parent.parent.name}/{p.stem}" for p in root.glob("*/srv/*.srv")}


def _ours(store: TypeStore, type_name: str, kind: str) -> dict[str, Any]:
    """What rostui computes for *type_name*, shaped like the oracle's entry (without genpy's keys)."""
    try:
        if kind == "msg":
            return {"kind": kind, "md5": store.md5sum(type_name), "full_text": store.full_text(type_name)}
        halves = {h: {"md5": store.md5sum(type_name + suffix), "full_text": store.full_text(type_name + suffix)}
                  for h, suffix in (("request", "Request"), ("response", "Response"))}
        return {"kind": kind, "md5": store.srv_md5sum(type_name), **halves}
    except Exception as e:  # every failure is a difference to report, with the others
        return {"kind": kind, "error": f"{type(e).__name__}: {e}"}


def _genmsg_view(entry: dict[str, Any]) -> dict[str, Any]:
    """The oracle's entry without genpy's keys."""
    out = {k: v for k, v in entry.items() if not k.startswith("genpy_")}  # genpy_error too
    for h in ("request", "response"):
        if h in out:
            out[h] = {k: v for k, v in out[h].items() if not k.startswith("genpy_")}
    return out


def test_corpus_is_wide_and_every_package_is_sourced(oracle: dict[str, Any]) -> None:
    corpus = _corpus_types(CORPUS)
    pkgs = {t.split("/")[0] for t in corpus}
    assert len(corpus) >= 1000 and len(pkgs) >= 60, (len(corpus), len(pkgs))
    sources = (CORPUS / "SOURCES.md").read_text()
    named = set(re.findall(r"^\| (\w+) \| \d+ \| \d+ \|", sources, re.M))
    assert named == pkgs
    assert corpus | _corpus_types(ODD) <= set(oracle)


def test_genmsg_reads_every_type(oracle: dict[str, Any]) -> None:
    """The corpus is whole: genmsg finds every dependency (else the comparison would skip types)."""
    errors = {t: e["error"] for t, e in oracle.items() if "error" in e}
    assert not errors


def test_md5sums_and_definitions_equal_genmsg(oracle: dict[str, Any], store: TypeStore) -> None:
    differ = []
    for t, entry in sorted(oracle.items()):
        want = _genmsg_view(entry)
        got = _ours(store, t, entry["kind"])
        if got != want:
            keys = sorted(k for k in set(got) | set(want) if got.get(k) != want.get(k))
            differ.append(f"{t}: {', '.join(keys)}: ours {json.dumps({k: got.get(k) for k in keys})[:300]} "
                          f"genmsg {json.dumps({k: want.get(k) for k in keys})[:300]}")
    assert not differ, f"{len(differ)} of {len(oracle)} types differ from genmsg:\n" + "\n".join(differ)


def test_md5sums_equal_genpy_and_definitions_except_where_genpy_reads_escapes(
        oracle: dict[str, Any], store: TypeStore) -> None:
    """genpy pastes the definition into a Python literal unescaped, so ``\\x03`` in a comment becomes a
    control character in its ``_full_text`` (what rospy publishes); rostui ships the file's text,
    as genmsg, gencpp and roscpp do.  Anywhere else genpy's text is rostui's."""
    differ, escaped, no_class = [], [], []
    for t, entry in sorted(oracle.items()):
        if "genpy_error" in entry:
            no_class.append(t)
            continue
        halves = [(t, entry)] if entry["kind"] == "msg" else \
                 [(t + "Request", entry["request"]), (t + "Response", entry["response"])]
        if entry["kind"] == "srv" and store.srv_md5sum(t) != entry["genpy_md5"]:
            differ.append(f"{t}: service md5")
        for name, e in halves:
            if store.md5sum(name) != e["genpy_md5"]:
                differ.append(f"{name}: md5")
            ours = store.full_text(name)
            if ours != e["genpy_full_text"]:
                (escaped if "\\" in ours else differ).append(name)
    assert not differ, "differ from genpy: " + ", ".join(differ)
    assert escaped == ["jsk_recognition_msgs/ExifTags"]
    assert no_class == ["odd_msgs/StringConstants"]  # its indented constant's name is no Python name


def test_odd_rules(store: TypeStore) -> None:
    """Spot checks of the rules the odd package reaches, as genmsg reads them."""
    consts = {c.name: (c.value, c.val_text) for c in store.get_spec("odd_msgs/StringConstants").constants}
    assert consts["NAME"] == ("value", "value")
    assert consts["TWO"] == ("two words  # not a comment",) * 2
    assert consts["EQUALS"] == ("a=b=c",) * 2
    assert consts["EMPTY"] == ("", "")
    assert "string INDENTED" in consts  # genmsg's name for an indented string constant
    assert "string NAME=value\n" in store.md5_text("odd_msgs/StringConstants") + "\n"
    headers = {f.name: f.type for f in store.get_spec("odd_msgs/Headers").fields}
    assert headers == {"header": "std_msgs/Header", "own_headers": "odd_msgs/Header[]",
                       "two_own_headers": "odd_msgs/Header[2]", "explicit": "std_msgs/Header",
                       "explicit_own": "odd_msgs/Header"}
    assert store.md5sum("odd_msgs/Empty") == "d41d8cd98f00b204e9800998ecf8427e"


@pytest.mark.parametrize("type_name,why", [
    ("odd_msgs/StringConstants", "cannot be a constant's name"),
    ("odd_msgs/NameClash", "both a constant and a field"),
])
def test_types_genmsg_hashes_but_no_class_can_hold_are_refused_when_built(
        store: TypeStore, type_name: str, why: str) -> None:
    """genmsg hashes these (so does rostui), but genpy's class would not load; rostui says why instead."""
    assert len(store.md5sum(type_name)) == 32
    with pytest.raises(MessageSpecError, match=why):
        store.get_class(type_name)


def test_the_popular_flight_stack_state_talks_to_real_nodes(oracle: dict[str, Any], store: TypeStore) -> None:
    """mavros_msgs/State writes ``string MODE_... = VALUE``: its md5 was off by the name's trailing space."""
    assert store.md5sum("mavros_msgs/State") == oracle["mavros_msgs/State"]["genpy_md5"]
    assert any(c.name == "MODE_APM_PLANE_MANUAL" for c in store.get_spec("mavros_msgs/State").constants)


def test_md5sums_from_shipped_definitions_equal_genmsg(oracle: dict[str, Any]) -> None:
    """A bag or MCAP without md5sums has the definition only: hashing genmsg's full text (roscpp's) and
    genpy's (rospy's) alone, with nothing installed, gives the md5sum real nodes use."""
    differ = []
    for t, entry in sorted(oracle.items()):
        halves = [(t, entry)] if entry["kind"] == "msg" else \
                 [(t + "Request", entry["request"]), (t + "Response", entry["response"])]
        for name, e in halves:
            for key in ("full_text", "genpy_full_text"):
                if key not in e:
                    continue
                alone = TypeStore(load_from_packages=False)
                try:
                    for spec in split_definition(name, e[key]):
                        alone.add_spec(spec)
                    got = alone.md5sum(name)
                except Exception as ex:  # reported with the others
                    got = f"{type(ex).__name__}: {ex}"
                if got != e["md5"]:
                    differ.append(f"{name} from {key}: {got}")
    assert not differ, f"{len(differ)} definitions hash differently from genmsg:\n" + "\n".join(differ)


CLI_SAME = [
    ("rosmsg", ["show", "mavros_msgs/State"]),
    ("rosmsg", ["show", "odd_msgs/Headers"]),
    ("rosmsg", ["show", "odd_msgs/Constants"]),
    ("rosmsg", ["show", "odd_msgs/StringConstants"]),
    ("rossrv", ["show", "odd_msgs/Odd"]),
    ("rossrv", ["show", "uuv_thruster_manager/SetThrusterManagerConfig"]),
]
CLI_MD5 = ["mavros_msgs/State", "odd_msgs/Headers", "odd_msgs/StringConstants", "odd_msgs/Odd",
           "uuv_thruster_manager/SetThrusterManagerConfig"]


@pytest.fixture(scope="module")
def cli_env(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """ROS_PACKAGE_PATH with the corpus and copies of the built-in packages it needs (Debian ships no .msg)."""
    deps = tmp_path_factory.mktemp("deps")
    for dep in ("std_msgs", "geometry_msgs", "sensor_msgs"):
        shutil.copytree(BUILTIN_SHARE / dep, deps / dep)
    return {**os.environ, "ROS_PACKAGE_PATH": f"{CORPUS}:{ODD}:{deps}",
            "ROS_HOME": str(tmp_path_factory.mktemp("home"))}


@pytest.mark.parametrize("tool,args", CLI_SAME, ids=[" ".join([t, *a]) for t, a in CLI_SAME])
def test_msg_and_srv_commands_print_what_rosmsg_and_rossrv_print(
        cli_env: dict[str, str], tool: str, args: list[str]) -> None:
    need_command(tool)
    want = subprocess.run([tool, *args], env=cli_env, capture_output=True, text=True, timeout=60,
                          stdin=subprocess.DEVNULL)
    assert want.returncode == 0, want.stderr
    got = rostui([tool[3:], *args], cli_env)
    assert (got.returncode, got.stdout) == (0, want.stdout)


@pytest.mark.parametrize("type_name", CLI_MD5)
def test_md5_commands_print_genmsgs_md5sum(oracle: dict[str, Any], cli_env: dict[str, str], type_name: str) -> None:
    """(rosmsg md5 imports the package's generated Python, which these packages do not have here.)"""
    kind = oracle[type_name]["kind"]
    got = rostui([kind, "md5", type_name], cli_env)
    assert (got.returncode, got.stdout) == (0, oracle[type_name]["md5"] + "\n")
