"""Messages, genpy and roslib as a plain ROS 1 script uses them; prints what it sees.

Written for these tests (not from a public source); run unmodified under Debian's genpy and under
`rostui python`, the two outputs must be equal.
"""

import io
import sys

import genpy
import roslib

roslib.load_manifest("std_msgs")
import roslib.message
from geometry_msgs.msg import Point, Pose, PoseStamped, Quaternion
from sensor_msgs.msg import Image
from std_msgs.msg import Header, String, UInt8MultiArray
from std_srvs.srv import SetBool, SetBoolRequest, SetBoolResponse

s = String("hello")
buff = io.BytesIO()
s.serialize(buff)
print(repr(buff.getvalue()))
print(String().deserialize(buff.getvalue()) == s, String(data="x") != s)
print(String._type, String._md5sum, String._has_header, String.__slots__, String._slot_types)
print(type(s), type(s).__name__, isinstance(s, genpy.Message))

p = PoseStamped(header=Header(seq=7, stamp=genpy.Time(12, 345), frame_id="map"),
                pose=Pose(Point(1.0, 2.5, -3.0), Quaternion(0.0, 0.0, 0.0, 1.0)))
print(p)
print(repr(p.pose.position))
print(PoseStamped._has_header, PoseStamped._slot_types)
print(PoseStamped._full_text.splitlines()[:3])
raw = io.BytesIO()
p.serialize(raw)
q = PoseStamped()
print(q.deserialize(raw.getvalue()) is q, q == p, q.header.stamp, repr(q.header.stamp))

img = Image(height=2, width=3, encoding="mono8", step=3, data=bytes(range(6)))
out = io.BytesIO()
img.serialize(out)
print(out.getvalue().hex())
print(Image().deserialize(out.getvalue()).data)
print(UInt8MultiArray(data=b"\x01\x02"))

t1, t2 = genpy.Time(10, 500000000), genpy.Time.from_sec(12.25)
d = t2 - t1
print(d, repr(d), d.to_sec(), d.to_nsec(), t1 + d == t2, t2 - d == t1, t1 < t2, t2 >= t1)
print(genpy.Duration(1, 500000000) * 3, genpy.Duration(5) / 2, genpy.Duration(7) // 2, genpy.Duration(-1, 0).to_sec())
print(abs(genpy.Duration(-3)), -genpy.Duration(2), genpy.Duration(7) % genpy.Duration(2),
      divmod(genpy.Duration(7), genpy.Duration(2)))
print(genpy.Time(3, 2000000000), genpy.Time(1).to_nsec(), genpy.Time().is_zero(), bool(genpy.Duration()))
print(hash(genpy.Time(4, 5)) == hash(genpy.Time(4, 5)), genpy.Time(4, 5) == genpy.Time(4, 5))
try:
    genpy.Time(-1)
except TypeError as exc:
    print("TypeError", exc)

try:
    String(data=5).serialize(io.BytesIO())
except genpy.SerializationError:
    print("SerializationError", issubclass(genpy.SerializationError, genpy.message.MessageException))
try:
    PoseStamped().deserialize(b"\x01\x02")
except genpy.DeserializationError:
    print("DeserializationError")

print(roslib.message.get_message_class("std_msgs/String") is String)
print(roslib.message.get_message_class("geometry_msgs/Twist")())
print(roslib.message.get_message_class("no_such_pkg/Nothing"))
srv = roslib.message.get_service_class("std_srvs/SetBool")
print(srv is SetBool, SetBool._type, SetBool._md5sum, SetBool._request_class is SetBoolRequest,
      SetBool._response_class is SetBoolResponse)
print(SetBoolRequest(True), SetBoolResponse(success=True, message="done")._type)
print(sys.argv[1:])
