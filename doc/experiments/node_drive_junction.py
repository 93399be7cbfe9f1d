#!/usr/bin/python3
"""drive_junction.py through the node: a bag of the drive played into mrs_vpr.launch on a loaded map.

  doc/experiments/node_drive_junction.py DATA [--port P]

The map is Nordland summer 0..799, written by build_map at its defaults; the node starts on it
(replay.launch database:=..., every other setting the defaults: continuous mode every second). The
drive, winter 600..1782, is played from a bag at 10 frames a second (2 minutes); it retraces the
map's last stretch and goes on over ground the map does not hold. Each accepted ~loop_closure is
judged by place as drive_junction.py judges it (within 5 places, frames where the recording train
stood counting as one place). Starts its own ROS master on --port (11411). Needs python3-rospy,
python3-rosbag, python3-sensor-msgs, python3-opencv and the package built and sourced.
"""

import argparse
import glob
import os
import subprocess
import tempfile
import time

import cv2

from build_map_visits import write_visit
from repeated_traversals import TOLERANCE, route_places

DRIVE_FROM = 600
MAP_END = 800
BAG_START = 100000.0  # the drive's first stamp [s]; build_map stamps summer frame i at i s
RATE = 10.0


def write_bag(path, frames):
    """The drive as sensor_msgs/Image (bgr8) on /camera/image_raw, RATE frames a second."""
    import rosbag
    import rospy
    from sensor_msgs.msg import Image

    with rosbag.Bag(path, "w") as bag:
        for index, name in enumerate(frames):
            image = cv2.imread(name)
            message = Image(height=image.shape[0], width=image.shape[1], encoding="bgr8", step=image.shape[1] * 3,
                            data=image.tobytes())
            message.header.stamp = rospy.Time.from_sec(BAG_START + index / RATE)
            message.header.seq = DRIVE_FROM + index
            message.header.frame_id = "camera"
            bag.write("/camera/image_raw", message, message.header.stamp)


def route_frame_of(stamp):
    """The route frame of a map or drive frame's stamp [s]."""
    return int(round(stamp)) if stamp < BAG_START else DRIVE_FROM + int(round((stamp - BAG_START) * RATE))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    parser.add_argument("--port", type=int, default=11411, help="port of the ROS master the run starts")
    args = parser.parse_args()
    summer = sorted(glob.glob(os.path.join(args.data, "nordland", "summer", "*.png")))
    winter = sorted(glob.glob(os.path.join(args.data, "nordland", "winter", "*.png")))
    place = route_places(summer, winter, len(summer))

    scratch = tempfile.TemporaryDirectory()
    folder = os.path.join(scratch.name, "map")
    write_visit(folder, summer[:MAP_END])
    database = os.path.join(scratch.name, "map.db")
    subprocess.run(["rosrun", "mrs_vpr", "build_map", "--images", folder, "--output", database],
                   check=True, stderr=subprocess.DEVNULL)
    bag = os.path.join(scratch.name, "drive.bag")
    write_bag(bag, winter[DRIVE_FROM:])

    os.environ["ROS_MASTER_URI"] = "http://localhost:%d" % args.port
    log = open(os.path.join(scratch.name, "launch.log"), "w")
    launch = subprocess.Popen(["roslaunch", "-p", str(args.port), "mrs_vpr", "replay.launch", "bag:=" + bag,
                               "database:=" + database], stdout=log, stderr=subprocess.STDOUT)
    import rospy
    from mrs_vpr.msg import LoopClosure

    closures = []
    try:
        time.sleep(5.0)  # the master and the node start; replay.launch waits 2 s more before playing
        rospy.init_node("node_drive_junction", anonymous=True, disable_signals=True)
        rospy.Subscriber("/mrs_vpr/loop_closure", LoopClosure, closures.append, queue_size=10000)
        time.sleep(len(winter[DRIVE_FROM:]) / RATE + 15.0)
    finally:
        launch.terminate()
        launch.wait()
        rospy.signal_shutdown("done")
    accepted = [c for c in closures if c.accepted]
    wrong = []
    for closure in accepted:
        localised = route_frame_of(closure.header.stamp.to_sec())
        named = route_frame_of(closure.reference_stamp.to_sec())
        if abs(place[named] - place[localised]) > TOLERANCE:
            wrong.append("winter %d -> %s %d (%d places off), confidence %.2f" % (
                localised, "summer" if closure.reference_stamp.to_sec() < BAG_START else "winter", named,
                place[named] - place[localised], closure.confidence))
    print("node on summer 0..%d, winter %d..%d played at %g Hz: %d answers, %d accepted (%d right, %d wrong)" % (
        MAP_END - 1, DRIVE_FROM, len(winter) - 1, RATE, len(closures), len(accepted), len(accepted) - len(wrong),
        len(wrong)))
    for line in wrong:
        print("  wrong: " + line)


if __name__ == "__main__":
    main()
