#!/usr/bin/env python3
"""What ~debug_image adds to the node's answers: the same ~query calls without and with a subscriber.

Starts a private roscore (on a free port) and mrs_vpr_node, plays the reference frames into it, then
sends --queries test sequences of --length frames, each --runs times (the fastest counts), for each
method, first with no subscriber on ~debug_image and then with one, and prints the median of the
responses' elapsed_ms side by side, with the images received and ~map_info's debug_images count.
Prints figures; it is not a test.

  benchmark/debug_image_node.py --reference DIR --query DIR [--length 300] [--queries 20] [--runs 3]

Run with the workspace's devel/setup.bash sourced and Debian's python3 (/usr/bin/python3).
"""
import argparse
import glob
import os
import socket
import statistics
import subprocess
import time

import cv2


def free_port():
    with socket.socket() as probe:
        probe.bind(('localhost', 0))
        return probe.getsockname()[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--reference', required=True, help='image folder mapped by the node')
    parser.add_argument('--query', required=True, help='image folder of the test sequences')
    parser.add_argument('--length', type=int, default=300)
    parser.add_argument('--queries', type=int, default=20)
    parser.add_argument('--runs', type=int, default=3)
    options = parser.parse_args()

    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    os.environ['ROS_HOSTNAME'] = 'localhost'
    quiet = subprocess.DEVNULL
    processes = [subprocess.Popen(['roscore', '-p', str(port)], stdout=quiet, stderr=quiet)]
    try:
        time.sleep(4.0)
        processes.append(subprocess.Popen(['rosrun', 'mrs_vpr', 'mrs_vpr_node', '__name:=mrs_vpr',
                                           'image:=/camera/image_raw', '_image_queue_size:=10000'],
                                          stdout=quiet, stderr=quiet))
        measure(options, processes[-1])
    finally:
        for process in reversed(processes):
            process.terminate()
            process.wait()


def measure(options, node):
    import rospy  # After ROS_MASTER_URI is set.
    from sensor_msgs.msg import Image
    from mrs_vpr.msg import MapInfo
    from mrs_vpr.srv import QuerySequence, QuerySequenceRequest

    def wait(condition, what):
        deadline = time.time() + 120.0
        while not condition():
            if node.poll() is not None:
                raise SystemExit('mrs_vpr_node exited with code %d while waiting for %s' % (node.returncode, what))
            if time.time() > deadline:
                raise SystemExit('timed out waiting for ' + what)
            time.sleep(0.05)

    def message(path, stamp):
        image = cv2.imread(path, cv2.IMREAD_COLOR)
        result = Image()
        result.header.stamp = rospy.Time.from_sec(stamp)
        result.header.frame_id = 'camera'
        result.height, result.width = image.shape[:2]
        result.encoding = 'bgr8'
        result.step = result.width * 3
        result.data = image.tobytes()
        return result

    rospy.init_node('debug_image_node_benchmark')
    reference = sorted(glob.glob(os.path.join(options.reference, '*.png')))
    test = sorted(glob.glob(os.path.join(options.query, '*.png')))
    latest = {}
    rospy.Subscriber('/mrs_vpr/map_info', MapInfo, lambda info: latest.__setitem__('info', info))
    images = rospy.Publisher('/camera/image_raw', Image, queue_size=10000)
    wait(lambda: images.get_num_connections() > 0, 'the node to subscribe')
    for i, path in enumerate(reference):
        images.publish(message(path, 1000.0 + i * 0.1))
        time.sleep(0.001)
    # Every frame received and none waiting: at the default min_appearance_change the map keeps only
    # the keyframes, fewer than the frames sent.
    wait(lambda: 'info' in latest and latest['info'].frames_received == len(reference)
         and latest['info'].frames_pending == 0, 'the map')
    rospy.wait_for_service('/mrs_vpr/query')
    query = rospy.ServiceProxy('/mrs_vpr/query', QuerySequence)
    span = len(test) - options.length
    ends = [options.length - 1 + k * span // max(1, options.queries - 1) for k in range(options.queries)]
    requests = []
    for end in ends:
        request = QuerySequenceRequest()
        request.images = [message(test[i], 9000.0 + i * 0.1) for i in range(end - options.length + 1, end + 1)]
        requests.append(request)

    def median_elapsed(method):
        fastest = []
        for request in requests:
            request.method = method
            fastest.append(min(query(request).elapsed_ms for _ in range(options.runs)))
        return statistics.median(fastest)

    received = []
    results = {}
    for watched in (False, True):
        if watched:
            rospy.Subscriber('/mrs_vpr/debug_image', Image, received.append)
            time.sleep(1.0)
        for method in ('mrs', 'seqslam'):
            results[(watched, method)] = median_elapsed(method)
    time.sleep(1.0)
    print('reference %d frames, %d queries of %d frames, fastest of %d runs, median elapsed_ms of ~query'
          % (len(reference), options.queries, options.length, options.runs))
    print('%-8s %15s %15s %10s' % ('method', 'no subscriber', 'subscriber', 'added'))
    for method in ('mrs', 'seqslam'):
        alone, watched = results[(False, method)], results[(True, method)]
        print('%-8s %15.2f %15.2f %10.2f' % (method, alone, watched, watched - alone))
    print('debug images received: %d; ~map_info debug_images: %d'
          % (len(received), latest['info'].debug_images))


if __name__ == '__main__':
    main()
