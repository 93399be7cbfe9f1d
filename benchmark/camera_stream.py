#!/usr/bin/env python3
"""Publishes a synthetic camera stream (sensor_msgs/Image) at a fixed rate for the node's CPU benchmark
(benchmark/node_cpu.sh). Runs in a process of its own, so its CPU is not the node's.

Usage: camera_stream.py TOPIC WIDTH HEIGHT RATE SECONDS [ENCODING]
ENCODING: bgr8 (the default), or bayer_rggb8, the raw mosaic a colour camera's driver publishes.
Prints the number of frames published when done."""
import sys
import time

import numpy as np
import rospy
from sensor_msgs.msg import Image


def mosaic(bgr):
    """The frame an RGGB colour filter records of `bgr`: red, green / green, blue in each 2 x 2 block."""
    raw = bgr[:, :, 1].copy()
    raw[0::2, 0::2] = bgr[0::2, 0::2, 2]
    raw[1::2, 1::2] = bgr[1::2, 1::2, 0]
    return raw


def main():
    if len(sys.argv) not in (6, 7):
        sys.exit(__doc__)
    topic, width, height, rate, seconds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    encoding = sys.argv[6] if len(sys.argv) == 7 else "bgr8"
    if encoding not in ("bgr8", "bayer_rggb8"):
        sys.exit("camera_stream.py: encoding must be bgr8 or bayer_rggb8, got " + encoding)
    rospy.init_node("camera_stream", anonymous=True, disable_signals=True)
    publisher = rospy.Publisher(topic, Image, queue_size=int(rate) * 2)
    # A textured scene panned by a few pixels a frame, so that frames differ as a camera's do.
    rng = np.random.RandomState(1)
    scene = rng.randint(0, 256, (height // 8 + 1, (width + 4 * 200) // 8 + 1, 3)).astype(np.uint8)
    scene = np.kron(scene, np.ones((8, 8, 1), dtype=np.uint8))
    # At most 200 frames and about 400 MB of them.
    count = max(2, min(200, (400 << 20) // (width * height * 3)))
    views = [scene[:height, 4 * i:4 * i + width] for i in range(count)]
    if encoding == "bayer_rggb8":
        frames = [mosaic(view).tobytes() for view in views]
    else:
        frames = [view.tobytes() for view in views]
    while publisher.get_num_connections() == 0 and not rospy.is_shutdown():
        time.sleep(0.05)
    channels = 3 if encoding == "bgr8" else 1
    message = Image(height=height, width=width, encoding=encoding, step=width * channels)
    message.header.frame_id = "camera"
    period = 1.0 / rate
    start = time.monotonic()
    count = 0
    while time.monotonic() - start < seconds and not rospy.is_shutdown():
        message.header.stamp = rospy.Time.from_sec(1000.0 + count * period)
        message.data = frames[count % len(frames)]
        publisher.publish(message)
        count += 1
        time.sleep(max(0.0, start + count * period - time.monotonic()))
    time.sleep(1.0)  # the last frames in flight
    print(count)


if __name__ == "__main__":
    main()
