"""numpy without OpenBLAS's thread pool in rostui's own commands.

numpy's wheels load OpenBLAS, which starts a thread per CPU at import; the threads
spin for a while before they sleep. rostui's commands use numpy for arrays of bag
index entries, images and scans, never for linear algebra big enough to share out,
and the pool cost 50-70 ms of CPU at every start here (`import numpy`: 0.16 s of
CPU, 0.10 s with one thread). :func:`single_threaded_blas` makes the first import
of numpy in this process see ``OPENBLAS_NUM_THREADS=1`` and puts the environment
back as it was once numpy is loaded, so programs the command starts (launched
nodes, served apps) inherit the user's setting, not ours. Where the user set it
already, nothing changes.
"""

from __future__ import annotations

import importlib.machinery
import os
import sys
from collections.abc import Sequence
from types import ModuleType
from typing import Any

VARIABLE = "OPENBLAS_NUM_THREADS"


class _OneThreadWhileNumpyLoads:
    """A meta path finder that finds nothing itself: when ``numpy`` is looked for, wraps the real loader so the
    variable is set while it runs, then leaves ``sys.meta_path``.  (Not a subclass of importlib.abc's classes:
    importing importlib.abc costs 12-24 ms of CPU at every start here, and the import system asks only for the
    methods.)"""

    def find_spec(self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None) -> Any:
        """The real spec of ``numpy``, its loader wrapped; None for every other name."""
        if fullname != "numpy":
            return None
        sys.meta_path.remove(self)
        spec = importlib.machinery.PathFinder.find_spec(fullname, path)
        if spec is None or spec.loader is None or not hasattr(spec.loader, "exec_module"):
            return spec
        real = spec.loader

        class OneThreadLoader:
            """``real``, run with the variable set."""

            def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
                return real.create_module(spec)

            def exec_module(self, module: ModuleType) -> None:
                os.environ[VARIABLE] = "1"
                try:
                    real.exec_module(module)
                finally:
                    os.environ.pop(VARIABLE, None)

        spec.loader = OneThreadLoader()  # type: ignore[assignment]  # a loader by its methods
        return spec


def single_threaded_blas() -> None:
    """Make this process's first ``import numpy`` load OpenBLAS with one thread (unless the user chose a number,
    or numpy is loaded already)."""
    if VARIABLE in os.environ or "numpy" in sys.modules:
        return
    sys.meta_path.insert(0, _OneThreadWhileNumpyLoads())
