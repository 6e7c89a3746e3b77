"""Import asyncio and xmlrpc.client without what a ROS node never uses: OpenSSL, subprocess, inspect, http.client,
base64, decimal, datetime.py.

asyncio imports ``ssl`` at once, and with it OpenSSL (5 MB of a rospy talker's
peak memory), ``subprocess`` (with ``locale``: 2 ms of its start) and
``inspect`` (with ``ast`` and ``dis``: 8 ms), which it calls only in debug
mode, on error paths and when a signal handler is added (the stand-in answers
that check itself for a function, a method, a ``functools.partial`` or a builtin); xmlrpc.client
imports ``http.client`` (and with it ``email`` and ``ssl`` again) for its
ServerProxy alone, which rostui's XML-RPC does not use, and ``base64`` and
``decimal`` for values ROS never sends (2.5 ms of a talker's start, with the
``http`` package's status enums).
:func:`import_lean` imports both with a stand-in in those places: it answers
``ssl is not None`` as the real module would, and the first attribute read
through it (an ``SSLContext`` check, a TLS handshake, a ServerProxy call, an
``inspect`` function called) imports the real module and puts it in the stand-in's place (subprocess's
stand-in answers ``PIPE``, ``STDOUT`` and ``DEVNULL``, which asyncio reads at
import, by itself). xmlrpc.client's ``from datetime import datetime`` gets the
class from CPython's ``_datetime``, the same class the datetime module exports,
without that module's Python (1.3 ms). Only asyncio's and xmlrpc.client's own
globals see a stand-in: a script's ``import ssl``, ``import subprocess``,
``import inspect``, ``import datetime`` or ``from http import client`` gets the
real module.
"""

from __future__ import annotations

import gc
import importlib
import sys
import types
from collections.abc import Callable, Mapping

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

__all__ = ["import_lean", "import_urllib_parse_lean", "pause_gc", "resume_gc"]


class _NoInstances:
    """A class nothing is an instance of: an ``SSLSocket`` before ssl is imported."""


class _Deferred(types.ModuleType):
    """Stands for a module, in the places given, until an attribute of it is read.

    The *classes* named are only tested with ``isinstance`` (asyncio asks whether each socket is an
    ``SSLSocket``): no object is an instance of them until the module is imported, so until then the
    stand-in answers them with :class:`_NoInstances` instead of importing it. The *callables* named are
    only called (xmlrpc.client's ``Decimal``, taken by ``from decimal import Decimal``): the stand-in
    answers them with a function that imports the module when first called, unless *answers* holds a
    function of the same name that knows the real one's answer without it (NotImplemented when it does not).
    """

    def __init__(self, name: str, put_back: Callable[[types.ModuleType], None],
                 classes: frozenset[str] = frozenset(), callables: frozenset[str] = frozenset(),
                 constants: Mapping[str, object] | None = None,
                 answers: Mapping[str, Callable[..., object]] | None = None) -> None:
        super().__init__(name, f"Stands for {name}; imports it when first used.")
        self._put_back = put_back
        self._classes = classes
        self._callables = callables
        self._answers = answers or {}
        for attr, value in (constants or {}).items():  # read without importing the module
            setattr(self, attr, value)

    def __getattr__(self, attr: str) -> object:
        if attr.startswith("__") or attr in ("_put_back", "_classes", "_callables", "_answers"):
            raise AttributeError(attr)
        if attr in self._classes and self.__name__ not in sys.modules:
            return _NoInstances
        if attr in self._callables:
            answer = self._answers.get(attr)

            def call(*args: object, **kwargs: object) -> object:
                if answer is not None and self.__name__ not in sys.modules:
                    known = answer(*args, **kwargs)
                    if known is not NotImplemented:
                        return known
                return getattr(self._real(), attr)(*args, **kwargs)

            return call
        return getattr(self._real(), attr)

    def _real(self) -> types.ModuleType:
        real = importlib.import_module(self.__name__)
        self._put_back(real)
        return real


_SUBPROCESS_CONSTANTS = {"PIPE": -1, "STDOUT": -2, "DEVNULL": -3}
"""What asyncio reads of ``subprocess`` at import (its ``asyncio.subprocess.PIPE``, default arguments): the
values subprocess documents."""


_INSPECT_CALLS = frozenset({"iscoroutinefunction", "unwrap", "isfunction", "isgenerator", "isawaitable"})
"""What asyncio's modules use of ``inspect``: functions called on a callback, a coroutine's result or an awaitable
(in debug mode, in a handle's repr, on a coroutine that yields garbage, in ``add_signal_handler``), never at
import."""


_CO_COROUTINE = 0x80
"""``inspect.CO_COROUTINE``: the code flag of an ``async def`` function (the same in every CPython 3)."""


def _iscoroutinefunction_before_inspect(obj: object) -> object:
    """``inspect.iscoroutinefunction(obj)`` while inspect is not imported, for what asyncio is mostly given
    (``add_signal_handler``'s check, which every command that stops on Ctrl-C makes): a Python function, a method
    of one, a ``functools.partial`` of those, a builtin; NotImplemented for anything else (the real one answers).
    inspect's other mark of a coroutine function (``markcoroutinefunction``) needs inspect imported first."""
    import functools

    while True:
        if isinstance(obj, types.MethodType):
            obj = obj.__func__
        elif isinstance(obj, functools.partial):
            obj = obj.func
        else:
            break
    if isinstance(obj, types.FunctionType):
        return bool(obj.__code__.co_flags & _CO_COROUTINE)
    if isinstance(obj, (types.BuiltinFunctionType, types.MethodWrapperType, types.WrapperDescriptorType,
                        types.MethodDescriptorType)):
        return False
    return NotImplemented


def _deferred_in_asyncio(name: str, **what: Any) -> tuple[_Deferred, list[types.ModuleType]] | None:
    """A stand-in for module *name* in the globals of asyncio's modules that import it, until first used there
    (see :class:`_Deferred` for *what*), and the list of those modules for the caller to fill once asyncio is
    imported; None, and nothing stands in, when *name* is imported already."""
    if name in sys.modules:
        return None
    users: list[types.ModuleType] = []

    def put_back(real: types.ModuleType) -> None:
        for module in users:
            setattr(module, name, real)

    return _Deferred(name, put_back, **what), users


def _import_asyncio() -> None:
    """asyncio without ``ssl``, ``subprocess`` (with ``locale`` and ``fcntl``, 2 ms of a talker's start) and
    ``inspect`` (with ``ast`` and ``dis``, 8 ms of a talker's start here): stand-ins in asyncio's modules import the
    real ones when first used (a TLS connection, a child process, a debug-mode check)."""
    stand_ins = {name: made for name, made in (
        ("subprocess", _deferred_in_asyncio("subprocess", constants=_SUBPROCESS_CONSTANTS)),
        ("inspect", _deferred_in_asyncio("inspect", callables=_INSPECT_CALLS,
                                         answers={"iscoroutinefunction": _iscoroutinefunction_before_inspect})),
    ) if made is not None}
    for name, (stand_in, _users) in stand_ins.items():
        sys.modules[name] = stand_in  # asyncio imports them unconditionally: it gets the stand-ins
    sys.modules["ssl"] = None  # type: ignore[assignment]  # asyncio's "import ssl" fails as on a build without it
    try:
        import asyncio  # noqa: F401
    finally:
        if sys.modules.get("ssl", False) is None:
            del sys.modules["ssl"]
        for name, (stand_in, _users) in stand_ins.items():
            if sys.modules.get(name) is stand_in:
                del sys.modules[name]  # everyone else's import gets the real module
    for name, (stand_in, users) in stand_ins.items():
        users.extend(_asyncio_modules_with(name, stand_in))
    _stand_in_for_ssl()


def _asyncio_modules_with(name: str, value: object) -> list[types.ModuleType]:
    """asyncio's modules whose global *name* is *value*."""
    return [m for key, m in list(sys.modules.items())
            if key.startswith("asyncio.") and m is not None and name in vars(m) and vars(m)[name] is value]


def _stand_in_for_ssl() -> None:
    users = _asyncio_modules_with("ssl", None)

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


def _datetime_class_only() -> types.ModuleType | None:
    """A ``datetime`` module holding only the ``datetime`` class, from CPython's ``_datetime``: the very class
    the real module exports (datetime.py ends by importing ``_datetime``'s), without the 1.3 ms of datetime.py's
    own Python. None where there is no ``_datetime``."""
    try:
        _datetime = importlib.import_module("_datetime")
    except ImportError:  # pragma: no cover - a Python without the C module
        return None
    module = types.ModuleType("datetime", "Stands for datetime while xmlrpc.client imports its datetime class.")
    module.datetime = _datetime.datetime  # type: ignore[attr-defined]
    return module


def _import_xmlrpc_client() -> None:
    """xmlrpc.client without ``http`` (its status enums), ``http.client``, ``base64`` and ``decimal``: stand-ins
    that import the real module when xmlrpc.client first uses it (a ServerProxy call, a ``<base64>`` or
    ``<bigdecimal>`` value); and its ``from datetime import datetime`` gets the class without the datetime
    module being imported."""

    def put_back_http(real: types.ModuleType) -> None:
        setattr(client, "http", sys.modules["http"])  # the package, its client now imported

    def put_back(name: str) -> Callable[[types.ModuleType], None]:
        return lambda real: setattr(client, name, real)

    stand_ins: dict[str, types.ModuleType] = {
        "http.client": _Deferred("http.client", put_back_http),
        "base64": _Deferred("base64", put_back("base64")),
        "decimal": _Deferred("decimal", lambda real: setattr(client, "Decimal", real.Decimal),
                             callables=frozenset({"Decimal"})),
    }
    datetime = _datetime_class_only()
    if datetime is not None:
        stand_ins["datetime"] = datetime  # taken out of sys.modules again below, like every stand-in
    if "http" not in sys.modules:  # only ``import http.client`` reads it, and never through xmlrpc.client's global
        stand_ins["http"] = types.ModuleType("http")
    stand_ins = {name: module for name, module in stand_ins.items() if name not in sys.modules}
    sys.modules.update(stand_ins)
    try:
        import xmlrpc.client as client
    finally:
        for name, module in stand_ins.items():
            if sys.modules.get(name) is module:
                del sys.modules[name]
    # xmlrpc.client reaches http.client as its global http's attribute: only its own global sees the stand-in
    setattr(client, "http", types.SimpleNamespace(client=stand_ins.get("http.client", sys.modules.get("http.client"))))


def import_urllib_parse_lean() -> None:
    """Import urllib.parse (pathlib's first import of it, at rostui.compat's) with a stand-in for ``ipaddress``
    (1.3 ms of a talker's start): urllib.parse uses it only to check a bracketed host (``http://[::1]/``), and the
    stand-in imports it then. Nothing is done when either is already imported."""
    if "urllib.parse" in sys.modules or "ipaddress" in sys.modules:
        return

    def put_back(real: types.ModuleType) -> None:
        setattr(sys.modules["urllib.parse"], "ipaddress", real)

    stand_in = _Deferred("ipaddress", put_back)
    sys.modules["ipaddress"] = stand_in
    try:
        import urllib.parse  # noqa: F401
    finally:
        if sys.modules.get("ipaddress") is stand_in:
            del sys.modules["ipaddress"]  # a script's "import ipaddress" gets the real module


def import_lean() -> None:
    """Import asyncio and xmlrpc.client with stand-ins for ``ssl`` and ``http.client``, unless already imported."""
    if "asyncio" not in sys.modules and "ssl" not in sys.modules:
        _import_asyncio()
    if "xmlrpc.client" not in sys.modules and "http.client" not in sys.modules:
        _import_xmlrpc_client()


def pause_gc() -> bool:
    """Stop the cyclic garbage collector for a burst of start-up work (imports, a node's start) that makes some
    thousands of objects and next to no garbage: Python would otherwise collect after every 700 of them (40
    collections, 8-10 ms of a rospy talker's start). True when it was running; give that to :func:`resume_gc`."""
    running = gc.isenabled()
    gc.disable()
    return running


def resume_gc(running: bool, *, freeze: bool = False) -> None:
    """Run the collector again if it was *running*; with *freeze*, first move every object alive now (the
    modules imported so far) out of its reach for good, so later full collections do not walk them."""
    if freeze:
        gc.freeze()
    if running:
        gc.enable()
