"""rospy.service: the service error scripts catch (``rospy.service.ServiceException``), under rospy's module name."""

from __future__ import annotations

from .exceptions import ServiceException

__all__ = ["ServiceException"]
