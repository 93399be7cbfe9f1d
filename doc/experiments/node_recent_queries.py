#!/usr/bin/python3
"""Median elapsed_ms of ~query {recent_frames: K, method: M} on a running node, both methods per K.

A node that loaded a map database, with no camera, answers repeated service calls about its own
newest frames (doc/short_sequences.md). Each K is asked `--calls` times with each method, the methods
taking turns so that both see the same machine load. Prints one row per K: the median elapsed_ms of
each, their ratio, in how many calls both gave the same frame and the same acceptance, and every mrs
time (the first calls search and then fill the rows in).

    cp /tmp/mrs_vpr_map_scale/map-100k-hog-seed42.db /tmp/map100k.db  # the node extends its database
    roslaunch mrs_vpr mrs_vpr.launch database:=/tmp/map100k.db &
    /usr/bin/python3 doc/experiments/node_recent_queries.py [--node /mrs_vpr] [--lengths 10,50,100] [--calls 10]

The map-scale benchmark writes that database.
"""
import argparse
import statistics

import rospy
from mrs_vpr.srv import QuerySequence, QuerySequenceRequest


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--node", default="/mrs_vpr")
    parser.add_argument("--lengths", default="10,50,100")
    parser.add_argument("--calls", type=int, default=10)
    args = parser.parse_args()
    rospy.init_node("node_recent_queries", anonymous=True)
    rospy.wait_for_service(args.node + "/query", timeout=600)
    query = rospy.ServiceProxy(args.node + "/query", QuerySequence)
    print("K  mrs_ms(median)  seqslam_ms(median)  speed-up  same_frame  same_accepted  mrs_ms(all)")
    for length in [int(k) for k in args.lengths.split(",")]:
        times = {"mrs": [], "seqslam": []}
        same_frame = same_accepted = 0
        for _ in range(args.calls):
            answers = {}
            for method in ("mrs", "seqslam"):
                answer = query(QuerySequenceRequest(recent_frames=length, method=method))
                if not answer.success:
                    raise SystemExit("query failed: " + answer.message)
                times[method].append(answer.elapsed_ms)
                answers[method] = answer
            same_frame += answers["mrs"].reference_index == answers["seqslam"].reference_index
            same_accepted += answers["mrs"].accepted == answers["seqslam"].accepted
        mrs, brute = statistics.median(times["mrs"]), statistics.median(times["seqslam"])
        print("%d  %.2f  %.2f  %.1fx  %d/%d  %d/%d  %s" % (length, mrs, brute, brute / mrs, same_frame, args.calls,
              same_accepted, args.calls, " ".join("%.1f" % t for t in times["mrs"])))


if __name__ == "__main__":
    main()
