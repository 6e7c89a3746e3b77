"""Import asyncio and xmlrpc.client without what a ROS node never uses: OpenSSL and http.client.

asyncio imports ``ssl`` at once, and with it OpenSSL (5 MB of a rospy talker's
peak memory); xmlrpc.client imports ``http.client`` (and with it ``email`` and
``ssl`` again) for its ServerProxy alone, which rostui's XML-RPC does not use.
:func:`import_lean` imports both with a stand-in in those places: it answers
``ssl is not None`` as the real module would, and the first attribute read
through it (an ``SSLContext`` check, a TLS handshake, a ServerProxy call)
imports the real module and puts it in the stand-in's place. Only asyncio's
and xmlrpc.client's own globals see a stand-in: a script's ``import ssl`` or
``from http import client`` gets the real module.
"""

from __future__ import annotations

import importlib
import sys
import types
from collections.abc import Callable

__all__ = ["import_lean"]


class _NoInstances:
    """A class nothing is an instance of: an ``SSLSocket`` before ssl is imported."""


class _Deferred(types.ModuleType):
    """Stands for a module, in the places given, until an attribute of it is read.

    The *classes* named are only tested with ``isinstance`` (asyncio asks whether each socket is an
    ``SSLSocket``): no object is an instance of them until the module is imported, so until then the
    stand-in answers them with :class:`_NoInstances` instead of importing it.
    """

    def __init__(self, name: str, put_back: Callable[[types.ModuleType], None],
                 classes: frozenset[str] = frozenset()) -> None:
        super().__init__(name, f"Stands for {name}; imports it when first used.")
        self._put_back = put_back
        self._classes = classes

    def __getattr__(self, attr: str) -> object:
        if attr.startswith("__") or attr in ("_put_back", "_classes"):
            raise AttributeError(attr)
        if attr in self._classes and self.__name__ not in sys.modules:
            return _NoInstances
        real = importlib.import_module(self.__name__)
        self._put_back(real)
        return getattr(real, attr)


def _import_asyncio() -> None:
    sys.modules["ssl"] = None  # type: ignore[assignment]  # asyncio's "import ssl" fails as on a build without it
    try:
        import asyncio  # noqa: F401
    finally:
        if sys.modules.get("ssl", False) is None:
            del sys.modules["ssl"]
    users = [m for name, m in list(sys.modules.items())
             if name.startswith("asyncio.") and m is not None and "ssl" in vars(m) and m.ssl is None]

    def put_back(ssl: types.ModuleType) -> None:
        for module in users:
            module.ssl = ssl  # type: ignore[attr-defined]
        sslproto = sys.modules.get("asyncio.sslproto")
        if sslproto is not None and not hasattr(sslproto, "SSLAgainErrors"):
            # what asyncio.sslproto defines at import when ssl is there
            sslproto.SSLAgainErrors = (ssl.SSLWantReadError, ssl.SSLSyscallError)  # type: ignore[attr-defined]

    stand_in = _Deferred("ssl", put_back, frozenset({"SSLSocket", "SSLObject", "SSLContext"}))
    for module in users:
        module.ssl = stand_in  # type: ignore[attr-defined]


def _import_xmlrpc_client() -> None:
    import http

    def put_back(real: types.ModuleType) -> None:
        setattr(client, "http", http)  # the package, its client now imported

    stand_in = _Deferred("http.client", put_back)
    sys.modules["http.client"] = stand_in
    try:
        import xmlrpc.client as client
    finally:
        if sys.modules.get("http.client") is stand_in:
            del sys.modules["http.client"]
    # xmlrpc.client reaches http.client as its global http's attribute: only its own global sees the stand-in
    setattr(client, "http", types.SimpleNamespace(client=stand_in))


def import_lean() -> None:
    """Import asyncio and xmlrpc.client with stand-ins for ``ssl`` and ``http.client``, unless already imported."""
    if "asyncio" not in sys.modules and "ssl" not in sys.modules:
        _import_asyncio()
    if "xmlrpc.client" not in sys.modules and "http.client" not in sys.modules:
        _import_xmlrpc_client()
