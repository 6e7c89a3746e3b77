"""What the diagnostics tests share: a robot's diagnostics from Debian's side, aggregated or flat.

A rospy node (Debian's rospy and diagnostic_updater) publishes three statuses on /diagnostics
(tests/python_compat/own/diagnostics_publisher.py); Debian's diagnostic_aggregator groups them with the analyzers
of tests/python_compat/own/diagnostics_aggregator.yaml and publishes /diagnostics_agg. Debian's rosdiagnostic is
the reference for `rostui diagnostics --once --format rosdiagnostic`.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd
from rospy_scripts import Running

OWN = REPO / "tests" / "python_compat" / "own"
PUBLISHER = OWN / "diagnostics_publisher.py"
ANALYZERS = OWN / "diagnostics_aggregator.yaml"
AGGREGATOR = Path("/usr/lib/diagnostic_aggregator/aggregator_node")
AGGREGATOR_NODE = "/diagnostic_aggregator"
ROSDIAGNOSTIC = [SYSTEM_PYTHON, "-c", "import sys, rosdiagnostic; rosdiagnostic.rosdiagnosticmain(sys.argv)"]


def need_debian_diagnostics() -> None:
    """Debian's diagnostic_updater (Python), diagnostic_aggregator's node and rosdiagnostic."""
    imports = subprocess.run([SYSTEM_PYTHON, "-c", "import diagnostic_updater, rosdiagnostic, dateutil"],
                             capture_output=True)
    need_peer(imports.returncode == 0 and AGGREGATOR.is_file(),
              "Debian's diagnostics (python3-diagnostic-updater, libdiagnostic-aggregator-tools, rosdiagnostic)")


def clean_env(ros_env: dict[str, str]) -> dict[str, str]:
    """The test's ROS environment without rostui python's own choices."""
    return {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}


def start_publisher(env: dict[str, str], log: Path) -> Running:
    """The rospy node publishing /diagnostics, once it has started."""
    running = Running([SYSTEM_PYTHON, str(PUBLISHER)], env, log)
    running.wait_for("publishing diagnostics")
    return running


def start_aggregator(env: dict[str, str], log: Path) -> Running:
    """Debian's aggregator with the tests' analyzers (loaded under its name first)."""
    done = subprocess.run(rostui_cmd("param", "load", str(ANALYZERS), AGGREGATOR_NODE), env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return Running([str(AGGREGATOR), f"__name:={AGGREGATOR_NODE[1:]}"], env, log)
