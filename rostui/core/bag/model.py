"""What every bag format stores: connections and time-stamped raw messages."""

from __future__ import annotations

from dataclasses import dataclass, field


class BagError(Exception):
    """A bag cannot be read or written; the message is one line for the user."""


@dataclass(frozen=True)
class Connection:
    """One publisher connection as recorded: its topic, type, md5sum, definition, callerid and latching."""

    id: int
    topic: str
    type: str
    md5sum: str
    definition: str
    callerid: str = ""
    latching: bool = False

    def header_fields(self) -> dict[str, str]:
        """The connection-header fields a rosbag connection record carries."""
        fields = {"topic": self.topic, "type": self.type, "md5sum": self.md5sum,
                  "message_definition": self.definition}
        if self.callerid:
            fields["callerid"] = self.callerid
        if self.latching:
            fields["latching"] = "1"
        return fields


@dataclass
class BagSummary:
    """What ``info`` shows: times, counts per connection, compression, and whether the file was closed."""

    path: str
    format: str
    version: str
    size: int
    connections: list[Connection] = field(default_factory=list)
    counts: dict[int, int] = field(default_factory=dict)
    start_ns: int = 0
    end_ns: int = 0
    chunk_compression: dict[str, int] = field(default_factory=dict)
    closed: bool = True
    problem: str = ""

    @property
    def message_count(self) -> int:
        """All messages in the file."""
        return sum(self.counts.values())


def connection_key(topic: str, header: dict[str, str]) -> tuple[str, str, str, str, bool]:
    """What makes two publishers' connections one bag connection: topic, type, md5, callerid, latching."""
    return (topic, header.get("type", ""), header.get("md5sum", ""), header.get("callerid", ""),
            header.get("latching", "0") == "1")
