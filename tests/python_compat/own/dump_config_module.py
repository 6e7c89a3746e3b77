"""Print a dynamic_reconfigure ``<Name>Config`` module's public names and values, one per line.

Given a dotted module name it imports it (as a script would); given a path to a ``.py`` file it loads
that file (a module Debian's generator wrote). The line and file a group or a parameter added through
``gen.add`` were made on point into the generator's own source, which differs between implementations:
those are printed as ``GEN``. tests/test_dynamic_reconfigure.py compares the output of both.
"""

import importlib
import importlib.util
import sys


def load(what):
    if what.endswith(".py"):
        spec = importlib.util.spec_from_file_location("generated", what)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    return importlib.import_module(what)


def norm(value):
    if isinstance(value, dict):
        out = {k: norm(v) for k, v in value.items()}
        if out.get("srcfile") == "parameter_generator_catkin.py":
            out["srcline"] = "GEN"
        return out
    if isinstance(value, list):
        return [norm(v) for v in value]
    return value


module = load(sys.argv[1])
for name in sorted(vars(module)):
    if not name.startswith("__") and name not in ("extract_params", "param"):
        print(name, "=", repr(norm(getattr(module, name))))
