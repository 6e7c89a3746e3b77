"""Fuzz: a few hundred seeded mutants of real bags through every bag reader a user meets.

Mutants (tests/bag_mutants.py) of the real files in tests/bag_corpus and of small files Debian's rosbag and the
``mcap`` library write from them go through ``bag info``, ``bag play``'s reading, ``topic echo -b`` and bag view's
reader, all in one child process (tests/bag_fuzz_child.py) whose memory is sampled and whose address space is
limited. What a user must see for every mutant: no traceback, no hang, no process above 500 MB, and a refusal
that is one line naming the file. A seeded sample then goes through the real commands.
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from bag_mutants import CORPUS, debian_bags, mcap_library_files, mutate
from conftest import REPO, need_peer, rostui_cmd, wait_until
from hostile.hostile_helpers import MB, RssSampler, record

SEED = 20260530
#: Mutants per base file: the large real bags are costly to decode, so they get fewer (and a capped echo).
SMALL_BASE_MUTANTS = 40
LARGE_BASE_MUTANTS = 12
LARGE_ECHO_COUNT = 200
PEAK_LIMIT_MB = 500
AS_LIMIT = 1536 * MB
CHILD_TIMEOUT = 100.0
"""Only a hang comes near this (the run takes about 4 s of CPU); it ends before pytest's own time-out, so the
failure names the mutant that hangs."""
LARGE = {"example-bz2.bag", "example-lz4.bag"}


def _have_debian_rosbag() -> bool:
    probe = subprocess.run(["/usr/bin/python3", "-c", "import rosbag, roslz4"], capture_output=True)
    return probe.returncode == 0


@pytest.fixture(scope="module")
def mutants(tmp_path_factory: pytest.TempPathFactory) -> list[dict[str, Any]]:
    """The manifest of every mutant written to a folder: ``{"path", "echo_count"}``."""
    need_peer(_have_debian_rosbag(), "rosbag Python API (Debian python3-rosbag)")
    folder = tmp_path_factory.mktemp("bag-fuzz")
    derived = folder / "bases"
    derived.mkdir()
    bases = sorted(p for p in CORPUS.iterdir() if p.suffix in (".bag", ".mcap"))
    bases += debian_bags(derived)
    bases += mcap_library_files(derived / "debian-none.bag", derived)
    rng = random.Random(SEED)
    manifest = []
    for base in bases:
        large = base.name in LARGE
        for mutant in mutate(base.name, base.read_bytes(), rng, LARGE_BASE_MUTANTS if large else SMALL_BASE_MUTANTS):
            path = folder / f"m{len(manifest):03d}{base.suffix}"
            path.write_bytes(mutant.data)
            manifest.append({"path": str(path), "mutant": mutant.name,
                             "echo_count": LARGE_ECHO_COUNT if large else 0})
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return manifest


def _run_child(manifest: list[dict[str, Any]], folder: Path) -> tuple[list[dict[str, Any]], float, float, str]:
    """Run every mutant in one child; its result lines, its sampled and its own peak RSS (MB), its stderr tail."""
    listing = folder / "manifest.json"
    progress = folder / "progress.txt"
    with open(progress, "w") as err:
        proc = subprocess.Popen([sys.executable, str(REPO / "tests" / "bag_fuzz_child.py"), str(listing),
                                 str(AS_LIMIT)], stdout=subprocess.PIPE, stderr=err, text=True, cwd=REPO)
        with RssSampler(proc.pid) as rss:
            try:
                out, _ = proc.communicate(timeout=CHILD_TIMEOUT)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.communicate()
                tail = progress.read_text().splitlines()[-1:]
                pytest.fail(f"the readers hang: still running after {CHILD_TIMEOUT:.0f} s on {tail}")
    lines = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
    peak = next((line["peak_rss_mb"] for line in lines if "peak_rss_mb" in line), float("nan"))
    results = [line for line in lines if "victim" in line]
    return results, rss.peak / MB, peak, progress.read_text()[-2000:]


def test_no_mutant_of_a_real_bag_crashes_hangs_or_grows_a_reader(mutants: list[dict[str, Any]]) -> None:
    folder = Path(mutants[0]["path"]).parent
    results, sampled_mb, own_peak_mb, stderr_tail = _run_child(mutants, folder)
    names = {m["path"]: m["mutant"] for m in mutants}
    assert len(results) == 4 * len(mutants), f"the child stopped early:\n{stderr_tail}"
    crashes = [r for r in results if r["outcome"] == "crash"]
    shown = "\n".join(f"{r['victim']} {names[r['path']]}:\n{r['line']}" for r in crashes[:6])
    assert not crashes, f"{len(crashes)} of {len(results)} runs end in a traceback; the first:\n{shown}"
    refusals = [r for r in results if r["outcome"] == "refused"]
    long = [r for r in refusals if len(r["line"].strip().splitlines()) != 1]
    assert not long, f"refusals of more than one line: {[(r['victim'], r['line']) for r in long[:4]]}"
    unnamed = [r for r in refusals if r["path"] not in r["line"]]
    assert not unnamed, f"refusals that do not name the file: {[(r['victim'], r['line']) for r in unnamed[:4]]}"
    assert max(sampled_mb, own_peak_mb) < PEAK_LIMIT_MB, (sampled_mb, own_peak_mb)
    outcomes = Counter((r["victim"], r["outcome"]) for r in results)
    slowest = max(results, key=lambda r: r["cpu"])
    record("bag_fuzz", "rostui bag readers (in-process)", mutants=len(mutants), runs=len(results),
           outcomes={f"{v}:{o}": n for (v, o), n in sorted(outcomes.items())}, peak_rss_mb=round(max(sampled_mb,
           own_peak_mb), 1), cpu_s=round(sum(r["cpu"] for r in results), 1),
           slowest=f"{slowest['victim']} {names[slowest['path']]} {slowest['cpu']} s")


#: How many mutants of the seeded sample go through the real commands (with one real ROS 2 MCAP, unchanged: a
#: master refuses its types, which bag play once answered with a traceback).
CLI_SAMPLE = 4


def _peak_run(cmd: list[str], env: dict[str, str], timeout: float = 120.0) -> tuple[int, str, float]:
    """Run a command to its end with its memory sampled; exit status, stderr and peak RSS in MB."""
    proc = subprocess.Popen(cmd, env=env, cwd=REPO, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    with RssSampler(proc.pid) as rss:
        _, err = proc.communicate(timeout=timeout)
    return proc.returncode, err, rss.peak / MB


def test_a_sample_of_mutants_through_the_real_commands(mutants: list[dict[str, Any]], rostui_core: Any,
                                                       ros_env: dict[str, str]) -> None:
    sample = random.Random(SEED).sample([m for m in mutants if m["echo_count"] == 0], CLI_SAMPLE)
    sample.append({"path": str(CORPUS / "talker.mcap"), "mutant": "talker.mcap itself (ROS 2 types)"})
    commands = {"info": ["bag", "info"], "play": ["bag", "play", "-q", "-d", "0", "-r", "1000"],
                "echo": ["topic", "echo", "-a", "-b"]}
    figures = []
    for item in sample:
        for victim, args in commands.items():
            code, err, peak = _peak_run(rostui_cmd(*args, item["path"]), ros_env)
            where = f"rostui {' '.join(args)} on {item['mutant']}"
            assert "Traceback" not in err, f"{where}:\n{err}"
            assert code in (0, 1), f"{where}: exit status {code}\n{err}"
            if code:
                errors = [line for line in err.splitlines() if line.startswith(("rostui bag", "ERROR"))]
                assert len(errors) == 1 and item["path"] in errors[0], f"{where}:\n{err}"
            assert peak < PEAK_LIMIT_MB, f"{where}: {peak:.0f} MB"
            figures.append((victim, code, round(peak, 1)))
    record("bag_fuzz_cli", "rostui bag info/play, topic echo -b", runs=len(figures),
           refused=sum(1 for _, code, _ in figures if code), peak_rss_mb=max(p for _, _, p in figures))
