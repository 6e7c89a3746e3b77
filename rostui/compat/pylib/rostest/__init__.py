"""rostest for unmodified ROS 1 scripts: ``rosrun`` (and ``run``) and the deprecated ``unitrun``.

``rosrun`` runs a unittest case that uses the ROS graph with rosunit's report, then shuts the node down
(``rospy.signal_shutdown('test complete')``) and exits 1 if a test failed. The ``rostest`` command itself
(launching a .test file) is not provided.
"""

from __future__ import annotations

import sys
import warnings
from typing import Any, Sequence

import rosunit
from rosunit.runner import run_suite

__all__ = ["rosrun", "run", "unitrun"]


def rosrun(package: str, test_name: str, test: Any, sysargs: Sequence[str] | None = None) -> None:
    """Run a unittest case of a ROS node, report as rosunit does, shut the node down; exit 1 on failure."""
    result = run_suite(package, test_name, test, sysargs)
    import rospy

    rospy.signal_shutdown("test complete")
    if not result.wasSuccessful():
        sys.exit(1)


run = rosrun
"""rostest's other name for :func:`rosrun`."""


def unitrun(package: str, test_name: str, test: Any, sysargs: Sequence[str] | None = None,
            coverage_packages: Any = None) -> None:
    """Deprecated in rostest (it says so): :func:`rosunit.unitrun`."""
    warnings.warn("Call to deprecated function unitrun.", category=DeprecationWarning, stacklevel=2)
    rosunit.unitrun(package, test_name, test, sysargs=sysargs, coverage_packages=coverage_packages)
