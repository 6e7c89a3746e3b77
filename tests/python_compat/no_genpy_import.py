"""Message modules alone, genpy never imported by the script; prints what it sees (written for these tests)."""

from std_msgs.msg import Header, String
from std_msgs.msg._String import String as StringFromItsModule

header = Header(stamp=Header().stamp)
print(repr(header.stamp), repr(header.stamp - header.stamp))
print(StringFromItsModule is String, String.__module__)
