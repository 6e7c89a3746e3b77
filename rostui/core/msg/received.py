"""Classes for the types peers and files describe: a definition is used only once checked against its md5sum.

A publisher's connection header and a bag's connection each name a type, its md5sum and (usually) its full
``message_definition``.  :func:`connection_class` is the one way rostui turns those into a class:

- a type rostui knows itself (its ``share/`` packages, ROS_PACKAGE_PATH) is decoded with rostui's class when
  the md5sum declared is rostui's (or the wildcard ``*``), whatever the definition says;
- from the wire, a type rostui knows under another md5sum is refused with :class:`Md5MismatchError`, in the
  words ROS uses for a mismatch (a publisher of another version cannot talk to rostui, as in ROS);
- from a file (``stored=True``: a bag, a pickle), another version of a type rostui knows is what old bags hold:
  it is decoded with a class built from the file's own definition, as rosbag decodes it, once that definition
  hashes to the md5sum recorded with it.  The class is private: it is never registered where rostui looks
  its own types up, so it cannot stand for rostui's type later;
- any other type is built from the definition only when that text hashes, as genmsg hashes it, to the md5sum
  declared with it (:class:`DefinitionMismatchError` otherwise); from the wire, every type rostui knows among
  its sections must be rostui's own.

A class that is not rostui's version of its type (:func:`foreign_version` says why in one line) must not be
taken for it: the views that draw a type by its name check it first.

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

__all__ = ["WILDCARD_MD5", "CACHE_ENTRIES", "CACHE_CHARS", "connection_class", "definition_md5", "foreign_version",
           "rostui_md5"]

WILDCARD_MD5 = "*"
"""The md5sum that stands for any type (AnyMsg subscribers, files that could not compute one)."""
CACHE_ENTRIES = 256
"""How many (type, md5sum, definition, sender, stored) answers are remembered; the least recently used go first."""
CACHE_CHARS = 8 << 20
"""How many characters of definitions the remembered answers may hold together."""

_Answer = type[Message] | MessageError
_Key = tuple[str, str, str, str, bool]
_cache: OrderedDict[_Key, _Answer] = OrderedDict()
_cache_chars = 0
_cache_store: TypeStore | None = None
_lock = threading.RLock()


def definition_md5(type_name: str, definition: str) -> str:
    """The md5sum genmsg computes for *type_name* from a full ``message_definition`` alone.

    Raises :class:`MessageSpecError` when the text does not parse or lacks a section for a type it uses.
    """
    return _definition_store(type_name, definition).md5sum(normalize_type_name(type_name))


def connection_class(type_name: str, md5sum: str, definition: str = "", *, sender: str = "the sender",
                     stored: bool = False) -> type[Message]:
    """The class to decode messages a connection declares as *type_name* / *md5sum* / *definition*.

    *sender* names the peer or file in errors (``publisher [/talker]``); *stored* says the connection comes from
    a file (a bag), whose own version of a type rostui knows is decoded with its definition (see the module's
    docstring).  Raises :class:`Md5MismatchError`,
    :class:`DefinitionMismatchError`, :class:`UnknownMessageTypeError` or :class:`MessageSpecError`, each one
    line; the same question later gets the same answer from the cache.
    """
    global _cache_chars, _cache_store
    sender = shown(sender, 120) if isinstance(sender, str) else "the sender"
    key = (type_name, md5sum, definition, sender, bool(stored))
    with _lock:
        if _cache_store is not default_store():  # clear_cache() made a new store: forget what the old one said
            _cache.clear()
            _cache_chars = 0
            _cache_store = default_store()
        try:
            answer = _cache[key]
            _cache.move_to_end(key)
        except KeyError:
            answer = _answer(type_name, md5sum, definition, sender, bool(stored))
            _remember(key, answer)
        except TypeError:  # unhashable: not what a header or a bag holds
            raise UnknownMessageTypeError(repr(type_name)[:80], "the type, md5sum or definition is not text") from None
    if isinstance(answer, MessageError):
        raise answer.with_traceback(None)
    return answer


def _answer(type_name: str, md5sum: str, definition: str, sender: str, stored: bool) -> _Answer:
    try:
        return _resolve(type_name, md5sum, definition, sender, stored)
    except MessageError as exc:
        return exc


def _remember(key: _Key, answer: _Answer) -> None:
    global _cache_chars
    _cache[key] = answer
    _cache_chars += len(key[2])
    while len(_cache) > CACHE_ENTRIES or (_cache_chars > CACHE_CHARS and len(_cache) > 1):
        old, _ = _cache.popitem(last=False)
        _cache_chars -= len(old[2])


def _resolve(type_name: str, md5sum: str, definition: str, sender: str, stored: bool) -> type[Message]:
    if not all(isinstance(v, str) for v in (type_name, md5sum, definition)):
        raise UnknownMessageTypeError(repr(type_name)[:80], "the type, md5sum or definition is not text")
    type_name = normalize_type_name(type_name)
    ours = rostui_md5(type_name)
    if ours is not None:
        if md5sum in (ours, WILDCARD_MD5, ""):
            return default_store().get_class(type_name)
        if not stored or not definition:  # from a peer, or a file that cannot say what its version is
            raise Md5MismatchError(sender, type_name, shown(md5sum, 40), ours)
    elif not definition:
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
        known = rostui_md5(nested)
        if known is None:
            continue
        if known == store.md5sum(nested):
            store.use_class(default_store().get_class(nested))
        elif not stored:
            raise Md5MismatchError(f"{sender} (in {type_name})", nested, store.md5sum(nested), known)
    return store.get_class(type_name)


def foreign_version(obj: object) -> str | None:
    """Why the message or class *obj* is not rostui's version of the type it names, in one line; None when it is.

    A class from a bag's own definition (:func:`connection_class` with ``stored``) may carry the name of a type
    rostui knows and other fields; whatever reads a type's fields by its name asks this first.
    """
    type_name, md5sum = getattr(obj, "_type", None), getattr(obj, "_md5sum", None)
    if not isinstance(type_name, str):
        return f"{type(obj).__name__} is not a message"
    ours = rostui_md5(type_name)
    if ours is None:
        return f"{shown(type_name)} is not a type rostui knows"
    if md5sum != ours:
        return f"{shown(type_name)} here has md5sum {shown(str(md5sum), 40)}, not the one rostui knows ({ours})"
    return None


def rostui_md5(type_name: str) -> str | None:
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
        raise MessageSpecError(f"the definition has no 'MSG:' section for {shown(', '.join(missing), 200)}")
    store = TypeStore(load_from_packages=False)
    for spec in specs:
        store.add_spec(spec)
    return store


def reconstruct(type_name: str, md5: str, definition: str) -> Message:
    """Unpickling helper: an empty instance of the class *type_name* / *md5* / *definition* describe (a pickle is
    stored data, like a bag: its own version of a type is rebuilt from its definition)."""
    cls = connection_class(type_name, md5, definition, sender="the pickled message", stored=True)
    return cls.__new__(cls)
