"""Allow ``python -m rostui``."""

from rostui.cli.main import main

main()
