"""Started by Python with ``PYTHONPATH`` naming this directory (`rostui python`, `rostui shell-env`).

Hands over to :mod:`rostui.compat.bootstrap`; says so in one line if rostui
itself cannot be imported, and the script then runs without it.
"""

from __future__ import annotations

import sys

try:
    from rostui.compat import bootstrap
except ImportError as _exc:
    print(f"rostui python: cannot import rostui ({_exc}); the script runs without its ROS modules", file=sys.stderr)
else:
    bootstrap.start()
    bootstrap.run_hidden_sitecustomize()
