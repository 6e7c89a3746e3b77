"""ROS logging: levels, records, logger levels, console output, log files.

Every message a node logs becomes a :class:`LogRecord`; :class:`NodeLog` gates
it by the level in a :class:`LoggerTree`, writes it through a :class:`Console`
and hands it to sinks (the ``/rosout`` publisher, a :class:`NodeLogFile`).
The rosout node writes ``rosout.log`` with a :class:`RosoutLogWriter`;
:mod:`rostui.core.log.clean` measures and purges the log directory.
"""

from __future__ import annotations

from rostui.core.log.console import (
    COLORS, DEFAULT_FORMAT, RESET, Console, ConsoleLogger, color_wanted, compile_format,
    console_stream, format_line, stamp_text, wall_time_text,
)
from rostui.core.log.files import (
    DISK_CHECK_NOTICE, DISK_OK_NOTICE, DISK_WARNING_BYTES, NodeLogFile, dir_size,
    disk_usage_warning, log_root, node_log_filename, ros_home, run_log_dir, update_latest_link,
)
from rostui.core.log.levels import Level
from rostui.core.log.nodelog import NodeLog, Sink, package_logger
from rostui.core.log.record import LogRecord
from rostui.core.log.rosout_log import RosoutLogWriter, format_rosout_line, startup_text
from rostui.core.log.tree import ROOT_LOGGER, LoggerTree

__all__ = [
    "COLORS", "DEFAULT_FORMAT", "DISK_CHECK_NOTICE", "DISK_OK_NOTICE", "DISK_WARNING_BYTES",
    "RESET", "ROOT_LOGGER", "Console", "ConsoleLogger", "Level", "LogRecord", "LoggerTree",
    "NodeLog", "NodeLogFile", "RosoutLogWriter", "Sink", "color_wanted", "compile_format",
    "console_stream", "dir_size", "disk_usage_warning", "format_line", "format_rosout_line",
    "log_root", "node_log_filename", "package_logger", "ros_home", "run_log_dir", "stamp_text",
    "startup_text", "update_latest_link", "wall_time_text",
]
