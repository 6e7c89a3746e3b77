"""Allow ``python -m rostui``."""

from rostui.cli.chosen_exit import forget_handled_interrupts
from rostui.cli.fast import main

try:
    main()
finally:
    forget_handled_interrupts()
