"""The Python client API for user scripts: rospy's shape, rostui's engine.

``from rostui import client as ros`` gives init_node, Publisher, Subscriber,
Service, ServiceProxy, Rate, Timer, spin, parameters and logging; message
classes come from ``rostui.core.msg.get_message_class`` (or ``msg`` below).
"""

from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node.anymsg import AnyMsg
from rostui.core.node.services import ServiceException
from rostui.core.node.sync import (
    Publisher, Rate, ROSException, ROSInterruptException, ROSTimeMovedBackwardsException, Service, ServiceProxy, Subscriber, Timer,
    TimerEvent, delete_param, get_master_uri, get_name, get_namespace, get_node_uri, get_param,
    get_loggers, get_param_cached, get_param_names, get_rostime, get_time, has_param, init_node,
    is_shutdown, is_wallclock, logdebug, logdebug_once, logdebug_throttle, logerr, logerr_once, logerr_throttle, logfatal,
    logfatal_once, logfatal_throttle, loginfo, loginfo_once, loginfo_throttle, logwarn, logwarn_once,
    logwarn_throttle, myargv, ok, on_shutdown, probe_service_header, set_logger_level,
    resolve_name, search_param, set_param, signal_shutdown, sleep, spin, wait_for_message,
    wait_for_service,
)
from rostui.core.rostime import Duration, Time

msg = get_message_class
srv = get_service_class

__all__ = [
    "AnyMsg", "Duration", "Publisher", "ROSException", "ROSInterruptException", "ROSTimeMovedBackwardsException",
    "Rate", "Service",
    "ServiceException", "ServiceProxy", "Subscriber", "Time", "Timer", "TimerEvent", "delete_param",
    "get_master_uri", "get_message_class", "get_name", "get_namespace", "get_node_uri", "get_param",
    "get_param_cached", "get_param_names", "get_rostime", "get_service_class", "get_time", "has_param",
    "get_loggers", "init_node", "is_shutdown", "is_wallclock", "logdebug", "logdebug_once", "logdebug_throttle", "logerr",
    "logerr_once", "logerr_throttle", "logfatal", "logfatal_once", "logfatal_throttle", "loginfo",
    "loginfo_once", "loginfo_throttle", "logwarn", "logwarn_once", "logwarn_throttle", "msg", "myargv",
    "ok", "on_shutdown", "probe_service_header", "resolve_name", "search_param", "set_logger_level", "set_param",
    "signal_shutdown", "sleep", "spin", "srv", "wait_for_message", "wait_for_service",
]
