"""``python -m rostui.core.master -p PORT``: a bare master, for tests and benchmarks."""

from __future__ import annotations

import argparse
import sys

from .run import run_master_forever


def main(argv: list[str] | None = None) -> int:
    """Parse ``-p/--port`` and run the master until interrupted."""
    parser = argparse.ArgumentParser(prog="python -m rostui.core.master", description=__doc__)
    parser.add_argument("-p", "--port", type=int, default=11311, help="port to listen on")
    args = parser.parse_args(argv)
    return run_master_forever(args.port)


if __name__ == "__main__":
    sys.exit(main())
