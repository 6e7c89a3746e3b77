"""Expat parsers that refuse any DTD, whatever the document's encoding.

Looking for ``<!DOCTYPE`` in the raw bytes misses a document in UTF-16 or
UTF-32 (with or without a byte order mark), which expat decodes and whose
entities it then expands.  Asking expat instead sees every encoding it reads:
the parse stops at the ``<!DOCTYPE`` itself, before any entity is declared.
Light on purpose: :mod:`.quick` uses it without importing ``xmlrpc.client``.
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import NoReturn

    from pyexpat import XMLParserType

__all__ = ["UnsafeXmlError", "forbid_dtd", "refuse_dtd"]


class UnsafeXmlError(ValueError):
    """The document holds a DTD or entity declaration, which XML-RPC never needs."""


def refuse_dtd(*_args: object) -> NoReturn:
    """An expat handler that stops the parse by raising :class:`UnsafeXmlError`."""
    raise UnsafeXmlError("DTD and entity declarations are not allowed")


def forbid_dtd(parser: XMLParserType) -> None:
    """Make ``parser`` raise :class:`UnsafeXmlError` from ``Parse`` at the first DTD it meets."""
    parser.StartDoctypeDeclHandler = refuse_dtd
    parser.EntityDeclHandler = refuse_dtd
