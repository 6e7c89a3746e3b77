"""Allow ``python -m rostui``."""

from rostui.cli.fast import main

main()
