"""Messages out of a bag: each connection's bytes deserialised with the class its recorded type, md5sum and
definition describe, once checked (:func:`rostui.core.msg.connection_class` with ``stored``): rostui's class when
the md5sum recorded is rostui's, else a private class built from the bag's own definition, used only when that
definition hashes to the md5sum recorded with it (a bag of an older or newer version of a type is read as
rosbag reads it).  Such a message is not rostui's version of its type: ask
:func:`rostui.core.msg.foreign_version` before reading it as one."""

from __future__ import annotations

from typing import Any

from rostui.core.bag.model import BagError, Connection

__all__ = ["Decoder", "decode_message"]


def decode_message(conn: Connection, data: bytes) -> Any:
    """The message ``data`` holds on ``conn``; one-line BagError when its definition or its bytes are refused."""
    from rostui.core.msg import connection_class
    from rostui.core.msg.spec import shown

    try:
        cls = connection_class(conn.type, conn.md5sum, conn.definition, sender=f"the connection of {shown(conn.topic)}",
                               stored=True)
        if not cls.__slots__ and data:  # rosbag would print an empty message and drop every byte
            raise BagError(f"its definition has no fields, but the message holds {len(data)} bytes")
        return cls.deserialize(data)
    except Exception as exc:  # a refused definition, or the generated deserialiser's errors on damaged data
        raise BagError(f"cannot decode a {shown(conn.type)} message on {shown(conn.topic)}: {exc}") from None


class Decoder:
    """Deserialises the messages of each connection with the class its type, md5sum and definition describe."""

    def __call__(self, conn: Connection, data: bytes) -> Any:
        """The message ``data`` holds; BagError when its definition or its bytes are broken."""
        return decode_message(conn, data)
