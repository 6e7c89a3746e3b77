"""Writing a whole new bag from another: into a hidden partial file that takes the final name only when complete."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator

from rostui.core.bag.files import Writer, is_rosbag_name
from rostui.core.bag.mcapfile import McapBagWriter
from rostui.core.bag.model import BagError
from rostui.core.bag.rosbag2_0 import BagWriter


def partial_name(dst: str) -> str:
    """The hidden name ``dst`` is written under until it is complete."""
    folder, base = os.path.split(dst)
    return os.path.join(folder, f".{base}.{os.getpid()}.partial")


@contextlib.contextmanager
def new_file(dst: str, compression: str = "none", *, rosbag: bool | None = None) -> Iterator[Writer]:
    """A writer whose file becomes ``dst`` only when the block ends without an exception.

    ``rosbag`` chooses the format (None: by ``dst``'s name, as :func:`~rostui.core.bag.files.open_writer`);
    on any exception the partial file is removed and ``dst`` is left as it was.
    """
    tmp = partial_name(dst)
    as_rosbag = is_rosbag_name(dst) if rosbag is None else rosbag
    writer: Writer | None = None
    try:  # Ctrl-C may come while the writer is still being made, its file already there
        try:
            writer = (BagWriter(tmp, compression=compression, max_chunk_age=float("inf")) if as_rosbag
                      else McapBagWriter(tmp, compression=compression, max_chunk_age=float("inf")))
        except OSError as exc:
            raise BagError(f"cannot create {dst}: {exc.strerror}") from None
        yield writer
        writer.close()
        os.replace(tmp, dst)
    except BaseException:
        if writer is not None:
            with contextlib.suppress(Exception):
                writer.close()
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
