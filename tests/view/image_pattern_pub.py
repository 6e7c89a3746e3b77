#!/usr/bin/env python3
"""Publish a known test pattern as sensor_msgs/Image or CompressedImage, as a camera driver would (rospy).

Runs unmodified under Debian's rospy (/usr/bin/python3) and under `rostui python` (rostui's client).

    image_pattern_pub.py TOPIC ENCODING [RATE] [FILE]

RATE 0 publishes one message, latched, with a zero stamp, and waits.  ENCODING is a raw encoding (rgb8, bgr8, rgba8, bgra8, mono8, mono16, 16UC1, 32FC1), or jpeg/png with
FILE holding the compressed picture.  The raw pattern (WIDTH x HEIGHT): four quadrants, top left red,
top right green, bottom left blue, bottom right white, and a yellow square marker in the middle of the
top-left quadrant.  Mono encodings get the grey level of each colour; depth encodings a left-to-right
ramp of 0.5 m to 4.5 m with a 0 (no reading) column band on the left.
"""

import struct
import sys

import rospy
from sensor_msgs.msg import CompressedImage, Image

WIDTH, HEIGHT = 64, 48
RED, GREEN, BLUE, WHITE, YELLOW = (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (255, 255, 0)


def colour(x, y):
    """The pattern's colour at pixel (x, y)."""
    if WIDTH // 8 <= x < WIDTH * 3 // 8 and HEIGHT // 8 <= y < HEIGHT * 3 // 8:
        return YELLOW
    left, top = x < WIDTH // 2, y < HEIGHT // 2
    if top:
        return RED if left else GREEN
    return BLUE if left else WHITE


def grey(rgb):
    """A colour's grey level (ITU-R 601 weights)."""
    return int(round(0.299 * rgb[0] + 0.587 * rgb[1] + 0.114 * rgb[2]))


def depth(x):
    """Metres at column x: nothing (0) in the leftmost eighth, then a ramp from 0.5 m to 4.5 m."""
    if x < WIDTH // 8:
        return 0.0
    return 0.5 + 4.0 * (x - WIDTH // 8) / (WIDTH - 1 - WIDTH // 8)


def raw_image(encoding):
    """The pattern as a sensor_msgs/Image of ``encoding``."""
    rows = []
    for y in range(HEIGHT):
        row = bytearray()
        for x in range(WIDTH):
            rgb = colour(x, y)
            if encoding == "rgb8":
                row += bytes(rgb)
            elif encoding == "bgr8":
                row += bytes(rgb[::-1])
            elif encoding == "rgba8":
                row += bytes(rgb + (255,))
            elif encoding == "bgra8":
                row += bytes(rgb[::-1] + (255,))
            elif encoding == "mono8":
                row += bytes([grey(rgb)])
            elif encoding == "mono16":
                row += struct.pack("<H", grey(rgb) * 257)
            elif encoding == "16UC1":
                row += struct.pack("<H", int(round(depth(x) * 1000)))
            elif encoding == "32FC1":
                row += struct.pack("<f", depth(x))
            else:
                raise SystemExit("unknown encoding " + encoding)
        rows.append(bytes(row))
    msg = Image()
    msg.height, msg.width, msg.encoding, msg.is_bigendian = HEIGHT, WIDTH, encoding, 0
    msg.step = len(rows[0])
    msg.data = b"".join(rows)
    return msg


def main():
    topic, encoding = sys.argv[1], sys.argv[2]
    rate = float(sys.argv[3]) if len(sys.argv) > 3 else 10.0
    rospy.init_node("image_pattern", anonymous=True)
    if encoding in ("jpeg", "png"):
        with open(sys.argv[4], "rb") as f:
            data = f.read()
        msg = CompressedImage()
        msg.format = encoding
        msg.data = data
        pub = rospy.Publisher(topic, CompressedImage, queue_size=1, latch=rate == 0)
    else:
        msg = raw_image(encoding)
        pub = rospy.Publisher(topic, Image, queue_size=1, latch=rate == 0)
    msg.header.frame_id = "camera"
    if rate == 0:
        pub.publish(msg)
        rospy.spin()
        return
    r = rospy.Rate(rate)
    while not rospy.is_shutdown():
        msg.header.stamp = rospy.Time.now()
        msg.header.seq += 1
        pub.publish(msg)
        r.sleep()


if __name__ == "__main__":
    try:
        main()
    except rospy.ROSInterruptException:
        pass
