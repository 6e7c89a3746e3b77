"""rosunit for unmodified ROS 1 scripts: ``unitrun`` runs a unittest case with ROS's report and JUnit file.

What a test script sees is rosunit's: the line naming the results file (under ``$ROS_HOME/test_results``,
or ``$ROS_TEST_RESULTS_DIR``), one ``[Testcase: name] ... ok`` line per test, the SUMMARY block, and exit
status 1 when a test failed. ``--text`` runs unittest's own verbose runner instead; ``--gtest_output=xml:F``
names the results file.
"""

from __future__ import annotations

from .runner import create_xml_runner, print_unittest_summary, unitrun, xml_results_file

__all__ = ["create_xml_runner", "print_unittest_summary", "unitrun", "xml_results_file"]
