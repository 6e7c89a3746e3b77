"""ROS nodes: the asyncio engine (AsyncNode) and the rospy-like sync face (sync)."""

from rostui.core.node.anymsg import AnyMsg
from rostui.core.node.node import (
    AsyncNode, MasterError, MasterRefusedError, MasterUnreachableError, Publisher, Subscriber,
)
from rostui.core.node.services import ServiceException, ServiceProxy, ServiceServer
from rostui.core.node.topics import TopicType

__all__ = [
    "AnyMsg", "AsyncNode", "MasterError", "MasterRefusedError", "MasterUnreachableError", "Publisher", "Subscriber",
    "ServiceException", "ServiceProxy", "ServiceServer", "TopicType",
]
