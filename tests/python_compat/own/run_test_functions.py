"""Run a test file written for pytest or unittest with no test runner installed, and print one line a test.

    python run_test_functions.py FILE

Each ``test_*`` function and each ``unittest.TestCase`` method in FILE is run; the line says ``NAME ok`` or
``NAME FAIL ExceptionType``; what a test prints is left out. tests/test_ros_upstream_suites.py runs real projects' own test files (rospkg's,
ros_comm's rosgraph) so under Debian's python3 and under ``rostui python``, and compares the lines.
"""

import contextlib
import importlib.util
import io
import sys
import unittest


def load(path):
    """The module in *path* (its folder first on sys.path, as pytest would put it)."""
    spec = importlib.util.spec_from_file_location("suite_under_test", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def outcome(call):
    """'ok', or 'FAIL' and the type of what *call* raised."""
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            call()
    except Exception as exc:  # a failing test is a line of output here, not the end of the run
        return f"FAIL {type(exc).__name__}"
    return "ok"


def main(path):
    """Print each test's outcome in name order."""
    module = load(path)
    for name in sorted(vars(module)):
        item = getattr(module, name)
        if name.startswith("test_") and callable(item):
            print(name, outcome(item), flush=True)
        elif isinstance(item, type) and issubclass(item, unittest.TestCase) and item is not unittest.TestCase:
            for method in unittest.defaultTestLoader.getTestCaseNames(item):
                result = unittest.TestResult()
                with contextlib.redirect_stdout(io.StringIO()):
                    item(method).run(result)
                problems = result.errors + result.failures
                print(f"{name}.{method}", "ok" if not problems else "FAIL " + problems[0][1].strip().splitlines()[-1]
                      .split(":")[0], flush=True)


if __name__ == "__main__":
    main(sys.argv[1])
