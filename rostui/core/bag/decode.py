"""Messages out of a bag: each connection's bytes deserialised with the class its recorded definition describes."""

from __future__ import annotations

from typing import Any

from rostui.core.bag.model import BagError, Connection


class Decoder:
    """Deserialises the messages of each connection with the class its definition describes."""

    def __init__(self) -> None:
        self._classes: dict[tuple[str, str], Any] = {}

    def __call__(self, conn: Connection, data: bytes) -> Any:
        """The message ``data`` holds; BagError when its definition or its bytes are broken."""
        from rostui.core.msg import get_message_class, register_types_from_definition

        key = (conn.type, conn.definition)
        cls = self._classes.get(key)
        try:
            if cls is None:
                cls = self._classes[key] = (register_types_from_definition(conn.type, conn.definition)
                                            if conn.definition else get_message_class(conn.type))
            return cls().deserialize(data)
        except BagError:
            raise
        except Exception as exc:  # a bad definition, or the generated deserialiser's errors on damaged data
            raise BagError(f"cannot decode a {conn.type} message on {conn.topic}: {exc}") from None
