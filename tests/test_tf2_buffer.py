"""rostui's tf2 (tf2_py, tf2_ros, tf2_geometry_msgs under `rostui python`) answers as Debian's real tf2 does.

tests/tf_compare/buffer_scenarios.py builds random tf trees (static edges, single samples, stamps nanoseconds
apart, data older than the cache, a second tree) and asks lookups at every kind of time, the advanced
lookup, can-transform, the latest common time, ``Buffer.transform`` of the four stamped geometry types,
the frame listings, and frame-id mistakes. The same script runs under Debian's python3-tf2-ros and
python3-tf2-geometry-msgs and under `rostui python`: every number agrees to 1e-9 (the issue's bound), every
error has the same class and text, and the same warnings reach stderr.
"""

from __future__ import annotations

import json
import subprocess
from typing import Any

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "tf_compare" / "buffer_scenarios.py"
TOLERANCE = 1e-9


def _debian_tf2() -> bool:
    probe = "import tf2_ros, tf2_geometry_msgs"
    return subprocess.run([SYSTEM_PYTHON, "-c", probe], capture_output=True).returncode == 0


def differences(ours: Any, theirs: Any, path: str = "") -> list[str]:
    """Where two answers differ: numbers by more than :data:`TOLERANCE`, anything else at all."""
    if isinstance(ours, float) or isinstance(theirs, float):
        if isinstance(ours, (int, float)) and isinstance(theirs, (int, float)) and abs(ours - theirs) <= TOLERANCE:
            return []
        return [f"{path}: {ours!r} != {theirs!r}"]
    if isinstance(ours, dict) and isinstance(theirs, dict):
        if ours.keys() != theirs.keys():
            return [f"{path}: keys {sorted(ours)} != {sorted(theirs)}"]
        return [d for key in ours for d in differences(ours[key], theirs[key], f"{path}.{key}")]
    if isinstance(ours, list) and isinstance(theirs, list) and len(ours) == len(theirs):
        return [d for i, pair in enumerate(zip(ours, theirs)) for d in differences(*pair, f"{path}[{i}]")]
    return [] if ours == theirs else [f"{path}: {ours!r} != {theirs!r}"]


def run(cmd: list[str]) -> tuple[list[dict[str, Any]], list[str]]:
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    warnings = [line for line in out.stderr.splitlines() if not line.startswith("         at line ")]
    return [json.loads(line) for line in out.stdout.splitlines()], warnings


@pytest.mark.parametrize("seed", [11, 12])
def test_random_trees_answer_as_debians_tf2(seed: int) -> None:
    need_peer(_debian_tf2(), "Debian's tf2 (python3-tf2-ros, python3-tf2-geometry-msgs)")
    args = [str(SCRIPT), str(seed), "30"]
    theirs, their_warnings = run([SYSTEM_PYTHON, *args])
    ours, our_warnings = run(rostui_cmd("python", "--rostui", *args))
    assert [a["q"] for a in ours] == [a["q"] for a in theirs]
    assert len(theirs) > 3000
    kinds = {("err" if "err" in a else "ok") for a in theirs}
    assert kinds == {"ok", "err"}  # the scenarios reach both answers and failures
    found = {a["q"]: d for a, b in zip(ours, theirs) if (d := differences(a, b))}
    assert found == {}
    assert our_warnings == their_warnings
