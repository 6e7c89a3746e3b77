"""The unittest runner behind rosunit and rostest: results kept per test, written as JUnit XML, summarised."""

from __future__ import annotations

import io
import os
import sys
import time
import traceback
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Sequence

__all__ = ["XML_OUTPUT_FLAG", "XmlTestRunner", "create_xml_runner", "load_suite", "print_unittest_summary",
           "run_suite", "unitrun", "xml_results_file"]

XML_OUTPUT_FLAG = "--gtest_output=xml:"
"""The argument that names the results file, as gtest and rosunit take it."""

_FORBIDDEN_IN_NAMES = ' "\'&$!`/\\'


def _results_dir() -> Path:
    explicit = os.environ.get("ROS_TEST_RESULTS_DIR")
    if explicit:
        return Path(explicit)
    home = os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    return Path(home) / "test_results"


def xml_results_file(test_pkg: str, test_name: str, is_rostest: bool = False) -> str:
    """Where the JUnit file of ``test_name`` in ``test_pkg`` goes (the directory is made)."""
    directory = _results_dir() / test_pkg
    directory.mkdir(parents=True, exist_ok=True)
    for c in _FORBIDDEN_IN_NAMES:
        test_name = test_name.replace(c, "_")
    return str(directory / f"{'rostest' if is_rostest else 'rosunit'}-{test_name}.xml")


class _Outcome:
    """One test's name, time and failure or error, if any."""

    def __init__(self, test: unittest.TestCase, seconds: float, failure: Any, error: Any) -> None:
        self.classname = f"{type(test).__module__}.{type(test).__name__}"
        self.method = getattr(test, "_testMethodName", str(test))
        self.seconds, self.failure, self.error = seconds, failure, error

    def element(self) -> ET.Element:
        case = ET.Element("testcase", classname=self.classname, name=self.method, time=f"{self.seconds:.4f}")
        for tag, err in (("failure", self.failure), ("error", self.error)):
            if err is not None:
                sub = ET.SubElement(case, tag, type=err[0].__name__)
                sub.text = f"{err[1]}\n{''.join(traceback.format_tb(err[2]))}"
        return case

    def report(self) -> str:
        lines = [f"[Testcase: {self.method}]"]
        for tag, err, word in (("failure", self.failure, "FAILURE!"), ("error", self.error, "ERROR!")):
            if err is not None:
                lines.append(f" ... {word}\n{tag.upper()}: {err[1]}\n{''.join(traceback.format_tb(err[2]))}"
                             + "-" * 80 + "\n")
        if self.failure is None and self.error is None:
            lines.append(" ... ok\n")
        return "".join(lines)


class _Result(unittest.TestResult):
    """Keeps an :class:`_Outcome` per test."""

    def __init__(self) -> None:
        super().__init__()
        self.outcomes: list[_Outcome] = []
        self._started = 0.0
        self._failure: Any = None
        self._error: Any = None

    def startTest(self, test: unittest.TestCase) -> None:  # noqa: N802 (unittest's name)
        super().startTest(test)
        self._failure = self._error = None
        self._started = time.time()

    def stopTest(self, test: unittest.TestCase) -> None:  # noqa: N802
        super().stopTest(test)
        self.outcomes.append(_Outcome(test, time.time() - self._started, self._failure, self._error))

    def addError(self, test: unittest.TestCase, err: Any) -> None:  # noqa: N802
        super().addError(test, err)
        self._error = err

    def addFailure(self, test: unittest.TestCase, err: Any) -> None:  # noqa: N802
        super().addFailure(test, err)
        self._failure = err


class XmlTestRunner:
    """Runs a suite with the test's own output captured into the report, writes the JUnit XML to ``path``."""

    def __init__(self, path: str) -> None:
        self.path = path

    def run(self, suite: unittest.TestSuite) -> unittest.TestResult:
        """Run ``suite``; print a line per test; return the result."""
        result = _Result()
        started = time.time()
        saved = sys.stdout, sys.stderr
        sys.stdout, sys.stderr = io.StringIO(), io.StringIO()
        try:
            suite.run(result)
            out, err = sys.stdout.getvalue(), sys.stderr.getvalue()
        finally:
            sys.stdout, sys.stderr = saved
        root = ET.Element("testsuite", errors=str(len(result.errors)), failures=str(len(result.failures)),
                          name=next((o.classname for o in result.outcomes), "unittest"), tests=str(result.testsRun),
                          time=f"{time.time() - started:.3f}")
        root.extend(o.element() for o in result.outcomes)
        ET.SubElement(root, "system-out").text = out
        ET.SubElement(root, "system-err").text = err
        with open(self.path, "w", encoding="utf-8") as stream:
            stream.write('<?xml version="1.0" encoding="utf-8"?>\n')
            stream.write(ET.tostring(root, encoding="unicode"))
        sys.stdout.write("".join(o.report() for o in result.outcomes))
        return result


def create_xml_runner(test_pkg: str, test_name: str, results_file: str | None = None,
                      is_rostest: bool = False) -> XmlTestRunner:
    """A runner writing to ``results_file`` (or rosunit's place for it), saying where."""
    path = results_file or xml_results_file(test_pkg, os.path.basename(test_name), is_rostest)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    print("[ROSUNIT] Outputting test results to " + path)
    return XmlTestRunner(path)


def _names(errors: Sequence[Any]) -> list[str]:
    return [getattr(test, "_testMethodName", str(test)) for test, _ in errors]


def print_unittest_summary(result: unittest.TestResult) -> None:
    """rosunit's SUMMARY block: the result, and how many tests ran, erred and failed (named)."""
    verdict = "\033[32m * RESULT: SUCCESS\033[0m" if result.wasSuccessful() else " * RESULT: FAIL"
    print("-------------------------------------------------------------\nSUMMARY:\n" + verdict + "\n"
          f" * TESTS: {result.testsRun}\n"
          f" * ERRORS: {len(result.errors)} [{', '.join(_names(result.errors))}]\n"
          f" * FAILURES: {len(result.failures)} [{', '.join(_names(result.failures))}]\n")


def load_suite(test: Any) -> unittest.TestSuite:
    """A suite from a TestCase class, or a dotted name of one."""
    if isinstance(test, str):
        return unittest.TestLoader().loadTestsFromName(test)
    return unittest.TestLoader().loadTestsFromTestCase(test)


def run_suite(package: str, test_name: str, test: Any, sysargs: Sequence[str] | None) -> unittest.TestResult:
    """Run ``test`` as rosunit and rostest do: ``--text`` verbose, else with a JUnit file; then the summary."""
    args = list(sys.argv if sysargs is None else sysargs)
    results_file = next((a[len(XML_OUTPUT_FLAG):] for a in args if a.startswith(XML_OUTPUT_FLAG)), None)
    suite = load_suite(test)
    if "--text" in args:
        result: unittest.TestResult = unittest.TextTestRunner(verbosity=2).run(suite)
    else:
        result = create_xml_runner(package, test_name, results_file).run(suite)
    print_unittest_summary(result)
    return result


def unitrun(package: str, test_name: str, test: Any, sysargs: Sequence[str] | None = None,
            coverage_packages: Any = None) -> None:
    """Run an offline unittest case; exit 1 if it failed (meant as a script's main)."""
    if not run_suite(package, test_name, test, sysargs).wasSuccessful():
        sys.exit(1)
