"""rostui's commands load numpy without OpenBLAS's thread pool, and leave the environment their children get alone."""

from __future__ import annotations

import json
import os
import subprocess
import sys

PROBE = """
import json, os, sys
from rostui.cli.blas_threads import single_threaded_blas
single_threaded_blas()
import numpy
print(json.dumps({"threads": len(os.listdir("/proc/self/task")), "env": os.environ.get("OPENBLAS_NUM_THREADS"),
                  "inverse": float(numpy.linalg.inv(numpy.eye(3) * 2).sum())}))
"""


def probe(**env: str) -> dict[str, object]:
    """What a process that set the hook up sees after ``import numpy``."""
    clean = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    out = subprocess.run([sys.executable, "-c", PROBE], env={**clean, **env}, capture_output=True, text=True,
                         check=True, timeout=60).stdout
    return dict(json.loads(out))


def test_numpy_loads_with_one_thread_and_the_environment_is_put_back() -> None:
    seen = probe()
    assert seen == {"threads": 1, "env": None, "inverse": 1.5}


def test_a_users_own_setting_is_kept() -> None:
    seen = probe(OPENBLAS_NUM_THREADS="2")
    assert seen["env"] == "2"
    assert seen["threads"] == 2  # the main thread and one OpenBLAS worker, as asked
