"""Benchmark: rostui message serialize/deserialize vs genpy (system Python) in the same run.

Run: .venv/bin/python bench/bench_msg.py
"""

from __future__ import annotations

import json
import subprocess
import timeit
from typing import Any

from rostui.core.msg import get_message_class
from rostui.core.msg.convert import fill_message

CASES: dict[str, dict[str, Any]] = {
    "std_msgs/String": {"data": "hello world"},
    "rosgraph_msgs/Log": {"header": {"frame_id": "x"}, "level": 2, "name": "/n", "msg": "m" * 40,
                          "file": "f.py", "function": "fn", "line": 3, "topics": ["/a", "/b"]},
    "geometry_msgs/PoseWithCovarianceStamped": {"pose": {"covariance": [0.5] * 36}},
    "sensor_msgs/Image": {"height": 480, "width": 640, "encoding": "rgb8", "step": 1920, "data": [0] * 921600},
}

_GENPY = r'''
import json, sys, timeit, importlib, io
from genpy.message import fill_message_args
cases = json.loads(sys.stdin.read())
out = {}
for t, v in cases.items():
    pkg, name = t.split("/")
    cls = getattr(importlib.import_module(pkg + ".msg"), name)
    m = cls(); fill_message_args(m, [v])
    if t == "sensor_msgs/Image": m.data = bytes(m.data)
    def rt():
        b = io.BytesIO(); m.serialize(b); cls().deserialize(b.getvalue())
    n, tt = timeit.Timer(rt).autorange()
    out[t] = n / tt
print(json.dumps(out))
'''


def main() -> None:
    """Print round trips per second for rostui and genpy, and their ratio."""
    ours: dict[str, float] = {}
    for t, v in CASES.items():
        cls = get_message_class(t)
        m = fill_message(cls, v)

        def rt(m: Any = m, cls: Any = cls) -> None:
            cls.deserialize(m.serialize())

        n, tt = timeit.Timer(rt).autorange()
        ours[t] = n / tt
    try:
        r = subprocess.run(["/usr/bin/python3", "-c", _GENPY], input=json.dumps(CASES),
                           capture_output=True, text=True, check=True)
        peer = json.loads(r.stdout)
    except (OSError, subprocess.CalledProcessError):
        peer = {}
    print(f"{'type':45} {'rostui rt/s':>12} {'genpy rt/s':>12} {'ratio':>7}")
    for t in CASES:
        p = peer.get(t)
        ratio = f"{ours[t] / p:7.2f}" if p else "    n/a"
        print(f"{t:45} {ours[t]:12.0f} {p or 0:12.0f} {ratio}")


if __name__ == "__main__":
    main()
