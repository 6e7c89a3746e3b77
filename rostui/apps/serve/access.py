"""Who may use `rostui serve`: whoever holds the token it printed, from a page this server served.

Three checks on every request, page, file and websocket alike:

- **the token**: a random one for each start of serve, given in the URL serve prints
  (``/?token=...``, as Jupyter does); the page then keeps it in a cookie of its own, HttpOnly and
  SameSite=Strict, so the files and the websocket it opens carry it;
- **Host**: one of this server's own names (the loopback names, the address it listens on, the
  public URL's host) with its port, so a name of another site that resolves here (DNS rebinding)
  gets nothing;
- **Origin**, when the browser sends one (it always does for a websocket): this server's own
  origin.  Cookies do not tell ports apart, so a page on another port of localhost would carry the
  cookie; its Origin does not match.

Pure functions of the request's headers: no aiohttp here.
"""

from __future__ import annotations

import hmac
import secrets
import socket
from dataclasses import dataclass
from typing import Iterable, Optional
from urllib.parse import urlsplit

#: The query parameter that carries the token.
TOKEN_PARAMETER = "token"

#: Names every machine gives itself.
LOOPBACK_NAMES = frozenset({"localhost", "127.0.0.1", "::1"})

#: Addresses that mean every interface of this machine.
EVERYWHERE = frozenset({"0.0.0.0", "::", ""})

#: Bytes of randomness in a token (32 URL-safe characters).
TOKEN_BYTES = 24


def new_token() -> str:
    """A fresh random token."""
    return secrets.token_urlsafe(TOKEN_BYTES)


@dataclass(frozen=True)
class Refusal:
    """Why a request is refused: which check (``host``, ``origin`` or ``token``), an HTTP status, and one line
    for the browser and serve's terminal."""

    check: str
    status: int
    reason: str


def _default_port(scheme: str) -> int:
    return 443 if scheme in ("https", "wss") else 80


def host_and_port(netloc: str, scheme: str = "http") -> Optional[tuple[str, int]]:
    """``("localhost", 8000)`` from ``localhost:8000`` (lower case, brackets off); None when it is no address."""
    try:
        parts = urlsplit(f"//{netloc}")
        port = parts.port
    except ValueError:
        return None
    if not parts.hostname or parts.username is not None or parts.path or parts.query:
        return None
    return parts.hostname.lower(), port if port is not None else _default_port(scheme)


def machine_names(host: str) -> frozenset[str]:
    """The names a browser may use for this server listening on ``host``: the loopback names, ``host``
    itself, and when it listens everywhere this machine's host names and interface addresses."""
    names = set(LOOPBACK_NAMES)
    if host in EVERYWHERE:
        import psutil

        names.update({socket.gethostname(), socket.getfqdn()})
        for addresses in psutil.net_if_addrs().values():
            names.update(a.address.split("%")[0] for a in addresses if a.family in (socket.AF_INET, socket.AF_INET6))
    else:
        names.add(host)
    return frozenset(n.lower() for n in names if n)


class Access:
    """The token of one start of serve, and the addresses its pages come from."""

    def __init__(self, token: str, port: int, names: Iterable[str], public_url: str) -> None:
        self.token = token
        self.cookie = f"rostui-serve-{port}"
        public = urlsplit(public_url)
        self.public_scheme = public.scheme or "http"
        addresses = {(name, port) for name in names}
        public_address = host_and_port(public.netloc, self.public_scheme)
        if public_address is not None:
            addresses.add(public_address)
        self.addresses = frozenset(addresses)

    @classmethod
    def for_server(cls, host: str, port: int, public_url: str, token: Optional[str] = None) -> Access:
        """The access rules of a server listening on ``host:port`` that browsers open at ``public_url``."""
        return cls(token or new_token(), port, machine_names(host), public_url)

    def token_matches(self, given: Optional[str]) -> bool:
        """True when ``given`` is the token (compared in constant time)."""
        return given is not None and hmac.compare_digest(given.encode(), self.token.encode())

    def check(self, host: Optional[str], origin: Optional[str], query_token: Optional[str],
              cookie_token: Optional[str]) -> Optional[Refusal]:
        """None when a request with these headers may go on; otherwise why it may not."""
        address = host_and_port(host or "", self.public_scheme)
        if address is None or address not in self.addresses:
            return Refusal("host", 403,
                           f"rostui serve: Host {(host or '')[:80]!r} is not this server's address: open the URL serve printed")
        if origin is not None:
            parts = urlsplit(origin)
            source = host_and_port(parts.netloc, parts.scheme) if parts.scheme in ("http", "https") else None
            if source is None or source not in self.addresses:
                return Refusal("origin", 403, f"rostui serve: a page from {origin[:80]!r} may not use this server")
        if not (self.token_matches(query_token) or self.token_matches(cookie_token)):
            what = "a wrong token" if query_token or cookie_token else "no token"
            return Refusal("token", 403, f"rostui serve: {what}: open the URL with ?token= that rostui serve printed")
        return None
