"""Classes for the types peers and files describe: a definition is used only once checked against its md5sum.

A publisher's connection header and a bag's connection each name a type, its md5sum and (usually) its full
``message_definition``.  :func:`connection_class` is the one way rostui turns those into a class:

- a type rostui knows itself (its ``share/`` packages, ROS_PACKAGE_PATH) is decoded with rostui's class when
  the md5sum declared is rostui's (or the wildcard ``*``), whatever the definition says; under another md5sum
  it is refused with :class:`Md5MismatchError`, in the words ROS uses for a mismatch;
- any other type is built from the definition only when that text hashes, as genmsg hashes it, to the md5sum
  declared with it (:class:`DefinitionMismatchError` otherwise), and only when every type rostui knows among
  its sections is rostui's own.

Built classes and refusals are both remembered (a bounded cache), so a peer that repeats its header with every
message costs one lookup per message, not a parse.
"""

from __future__ import annotations

import threading
from collections import OrderedDict

from .errors import DefinitionMismatchError, Md5MismatchError, MessageError, MessageSpecError, UnknownMessageTypeError
from .message import Message
from .registry import TypeStore, default_store, normalize_type_name, split_definition
from .spec import shown

__all__ = ["WILDCARD_MD5", "CACHE_ENTRIES", "CACHE_CHARS", "connection_class", "definition_md5"]

WILDCARD_MD5 = "*"
"""The md5sum that stands for any type (AnyMsg subscribers, files that could not compute one)."""
CACHE_ENTRIES = 256
"""How many (type, md5sum, definition, sender) answers are remembered; the least recently used go first."""
CACHE_CHARS = 8 << 20
"""How many characters of definitions the remembered answers may hold together."""

_Answer = type[Message] | MessageError
_cache: OrderedDict[tuple[str, str, str, str], _Answer] = OrderedDict()
_cache_chars = 0
_cache_store: TypeStore | None = None
_lock = threading.RLock()


def definition_md5(type_name: str, definition: str) -> str:
    """The md5sum genmsg computes for *type_name* from a full ``message_definition`` alone.

    Raises :class:`MessageSpecError` when the text does not parse or lacks a section for a type it uses.
    """
    return _definition_store(type_name, definition).md5sum(normalize_type_name(type_name))


def connection_class(type_name: str, md5sum: str, definition: str = "", *, sender: str = "the sender") -> type[Message]:
    """The class to decode messages a connection declares as *type_name* / *md5sum* / *definition*.

    *sender* names the peer or file in errors (``publisher [/talker]``).  Raises :class:`Md5MismatchError`,
    :class:`DefinitionMismatchError`, :class:`UnknownMessageTypeError` or :class:`MessageSpecError`, each one
    line; the same question later gets the same answer from the cache.
    """
    global _cache_chars, _cache_store
    sender = shown(sender, 120) if isinstance(sender, str) else "the sender"
    key = (type_name, md5sum, definition, sender)
    with _lock:
        if _cache_store is not default_store():  # clear_cache() made a new store: forget what the old one said
            _cache.clear()
            _cache_chars = 0
            _cache_store = default_store()
        try:
            answer = _cache[key]
            _cache.move_to_end(key)
        except KeyError:
            answer = _answer(type_name, md5sum, definition, sender)
            _remember(key, answer)
        except TypeError:  # unhashable: not what a header or a bag holds
            raise UnknownMessageTypeError(repr(type_name)[:80], "the type, md5sum or definition is not text") from None
    if isinstance(answer, MessageError):
        raise answer.with_traceback(None)
    return answer


def _answer(type_name: str, md5sum: str, definition: str, sender: str) -> _Answer:
    try:
        return _resolve(type_name, md5sum, definition, sender)
    except MessageError as exc:
        return exc


def _remember(key: tuple[str, str, str, str], answer: _Answer) -> None:
    global _cache_chars
    _cache[key] = answer
    _cache_chars += len(key[2])
    while len(_cache) > CACHE_ENTRIES or (_cache_chars > CACHE_CHARS and len(_cache) > 1):
        old, _ = _cache.popitem(last=False)
        _cache_chars -= len(old[2])


def _resolve(type_name: str, md5sum: str, definition: str, sender: str) -> type[Message]:
    if not all(isinstance(v, str) for v in (type_name, md5sum, definition)):
        raise UnknownMessageTypeError(repr(type_name)[:80], "the type, md5sum or definition is not text")
    type_name = normalize_type_name(type_name)
    ours = _our_md5(type_name)
    if ours is not None:
        if md5sum not in (ours, WILDCARD_MD5, ""):
            raise Md5MismatchError(sender, type_name, shown(md5sum, 40), ours)
        return default_store().get_class(type_name)
    if not definition:
        raise UnknownMessageTypeError(type_name, f"rostui does not know it and {sender} sent no definition")
    if md5sum in (WILDCARD_MD5, ""):
        raise DefinitionMismatchError(f"{sender} declares no md5sum for {type_name}, so its definition "
                                      "cannot be checked; not used")
    store = _definition_store(type_name, definition)
    theirs = store.md5sum(type_name)
    if theirs != md5sum:
        raise DefinitionMismatchError(f"{sender} declares md5sum [{shown(md5sum, 40)}] for {type_name}, but its "
                                      f"definition has md5sum [{theirs}]; not used")
    for nested in store.all_depends(type_name):
        known = _our_md5(nested)
        if known is None:
            continue
        if known != store.md5sum(nested):
            raise Md5MismatchError(f"{sender} (in {type_name})", nested, store.md5sum(nested), known)
        store.use_class(default_store().get_class(nested))
    return store.get_class(type_name)


def _our_md5(type_name: str) -> str | None:
    """rostui's own md5sum of *type_name*, or None when rostui does not know the type (or cannot read it)."""
    try:
        return default_store().md5sum(type_name)
    except (UnknownMessageTypeError, MessageSpecError):
        return None


def _definition_store(type_name: str, definition: str) -> TypeStore:
    """A store holding exactly the types *definition* describes (nothing looked up elsewhere)."""
    specs = split_definition(type_name, definition)
    have = {spec.type_name for spec in specs}
    missing = sorted({dep for spec in specs for dep in spec.dependencies()} - have)
    if missing:
        raise MessageSpecError(f"the definition of {specs[0].type_name} has no 'MSG:' section for "
                               f"{shown(', '.join(missing))}", "<message_definition>")
    store = TypeStore(load_from_packages=False)
    for spec in specs:
        store.add_spec(spec)
    return store


def reconstruct(type_name: str, md5: str, definition: str) -> Message:
    """Unpickling helper: an empty instance of the class *type_name* / *md5* / *definition* describe."""
    cls = connection_class(type_name, md5, definition, sender="the pickled message")
    return cls.__new__(cls)
