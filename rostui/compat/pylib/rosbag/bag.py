"""rosbag.bag: the same names as :mod:`rosbag` (scripts import ``from rosbag.bag import Bag`` too)."""

from __future__ import annotations

from rostui.compat.rosbag_bag import (
    Bag,
    BagMessage,
    BagMessageWithConnectionHeader,
    Compression,
    ROSBagEncryptNotSupportedException,
    ROSBagException,
    ROSBagFormatException,
    ROSBagUnindexedException,
)

__all__ = ["Bag", "BagMessage", "BagMessageWithConnectionHeader", "Compression", "ROSBagException",
           "ROSBagFormatException", "ROSBagUnindexedException", "ROSBagEncryptNotSupportedException"]
