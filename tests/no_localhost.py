"""Run a rostui command on a resolver that knows no localhost name, as in a Debian root with no /etc/hosts.

``python tests/no_localhost.py wtf`` is ``rostui wtf`` with ``socket.getaddrinfo`` refusing ``localhost``
and ``ip6-localhost`` (a mount namespace with an empty /etc/hosts would do the same, but cannot be made
inside a chroot, where fresh-ci runs the suite).
"""

from __future__ import annotations

import socket
import sys
from typing import Any

_real_getaddrinfo = socket.getaddrinfo


def getaddrinfo(host: Any, *args: Any, **kwargs: Any) -> Any:
    """The resolver's answer, except "Name or service not known" for the localhost names."""
    if (host.decode() if isinstance(host, bytes) else host) in ("localhost", "ip6-localhost"):
        raise socket.gaierror(socket.EAI_NONAME, "Name or service not known")
    return _real_getaddrinfo(host, *args, **kwargs)


if __name__ == "__main__":
    socket.getaddrinfo = getaddrinfo  # type: ignore[assignment]
    from rostui.cli.main import main

    sys.argv = ["rostui", *sys.argv[1:]]
    main()
