#!/usr/bin/env python3
"""Writes the bgr8 images of a bag as sensor_msgs/CompressedImage on <topic>/compressed, as
image_transport's compressed publisher does. Usage: compress_bag.py IN.bag OUT.bag jpeg|png"""
import sys, cv2, numpy as np, rosbag
from sensor_msgs.msg import CompressedImage
if len(sys.argv) != 4 or sys.argv[3] not in ('jpeg', 'png'):
    sys.exit(__doc__)
src, dst, codec = sys.argv[1], sys.argv[2], sys.argv[3]
with rosbag.Bag(src) as bag, rosbag.Bag(dst, 'w') as out:
    for topic, msg, t in bag.read_messages():
        img = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.step)[:, :msg.width * 3].reshape(msg.height, msg.width, 3)
        c = CompressedImage(header=msg.header, format='bgr8; %s compressed bgr8' % codec)
        c.data = cv2.imencode('.jpg' if codec == 'jpeg' else '.png', img)[1].tobytes()
        out.write(topic + '/compressed', c, t)
