#!/usr/bin/python3
"""A drive after a loaded map: the closures at the junction of the two, judged on real frames.

  doc/experiments/drive_junction.py DATA [--map-end M] [--drive-from F]

The map is Nordland summer 0..M-1 (M = 800), written by build_map at its defaults and loaded from
Python as a node loads its database. Then a drive: winter F..1782 (F = 600) offered frame by frame,
each new keyframe asked about as the node's continuous mode asks (match_recent at the default
sequence length, once the drive has that many keyframes). The drive retraces the map's last stretch
and goes on over ground the map does not hold. Each accepted answer is judged by place, as
repeated_traversals.py judges: right within 5 places of the truth (the map's summer frame of the
keyframe's place, or the drive's own earlier keyframe there), where route frames at which the
recording train stood count as one place. The answers that the junction rule took back (their
trajectory ran from the map's last frames into the drive's first, Match.across_drives) are judged
too: what they would have closed. Needs python3-numpy, python3-opencv, the mrs_vpr Python package
and build_map on the ROS package path.
"""

import argparse
import glob
import os
import sqlite3
import subprocess
import tempfile

import cv2

import mrs_vpr
from build_map_visits import write_visit
from repeated_traversals import TOLERANCE, route_places


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    parser.add_argument("--map-end", type=int, default=800, help="the map is summer 0..map-end - 1")
    parser.add_argument("--drive-from", type=int, default=600, help="the drive is winter drive-from..1782")
    args = parser.parse_args()
    summer = sorted(glob.glob(os.path.join(args.data, "nordland", "summer", "*.png")))
    winter = sorted(glob.glob(os.path.join(args.data, "nordland", "winter", "*.png")))
    if not 0 < args.map_end <= len(summer) or not 0 <= args.drive_from < len(winter):
        parser.error("--map-end or --drive-from outside the %d route frames" % len(summer))
    place = route_places(summer, winter, len(summer))

    scratch = tempfile.TemporaryDirectory()
    folder = os.path.join(scratch.name, "map")
    write_visit(folder, summer[:args.map_end])
    database = os.path.join(scratch.name, "map.db")
    subprocess.run(["rosrun", "mrs_vpr", "build_map", "--images", folder, "--output", database],
                   check=True, stderr=subprocess.DEVNULL)
    with sqlite3.connect(database) as connection:
        route_frame = [row[0] for row in connection.execute("SELECT sequence FROM frames ORDER BY id")]
    recognizer = mrs_vpr.PlaceRecognizer.from_map(database)
    loaded = len(recognizer)
    length = recognizer.parameters["sequence/sequence_length"]
    reach = 2 * length + recognizer.parameters["recent_exclusion"]

    counts = {"asked": 0, "accepted": 0, "right": 0, "wrong": 0, "across": 0, "across right": 0, "across wrong": 0}
    wrong = []
    for frame in range(args.drive_from, len(winter)):
        if not recognizer.add_frame(cv2.imread(winter[frame]), stamp=float(frame)):
            continue
        route_frame.append(frame)
        if len(recognizer) - loaded < length or len(recognizer) < reach:
            continue
        answer = recognizer.match_recent(length)
        counts["asked"] += 1
        if not (answer.accepted or answer.match.across_drives):
            continue
        localised = int(round(answer.localised_stamp))  # the drive's frames are stamped with their number
        named = route_frame[answer.reference_index]
        right = abs(place[named] - place[localised]) <= TOLERANCE
        kind = "across" if answer.match.across_drives else "accepted"
        counts[kind] += 1
        counts[("across " if answer.match.across_drives else "") + ("right" if right else "wrong")] += 1
        if not right:
            wrong.append("%swinter %d -> %s %d (%d places off), confidence %.2f" % (
                "taken back: " if answer.match.across_drives else "", localised,
                "summer" if answer.reference_index < loaded else "winter", named, place[named] - place[localised],
                answer.confidence))
    print("map: summer 0..%d, %d keyframes; drive: winter %d..%d" % (
        args.map_end - 1, loaded, args.drive_from, len(winter) - 1))
    print("%(asked)d questions, %(accepted)d accepted (%(right)d right, %(wrong)d wrong); %(across)d taken back as "
          "running across the junction (%(across right)d would have been right, %(across wrong)d wrong)" % counts)
    for line in wrong:
        print("  wrong: " + line)


if __name__ == "__main__":
    main()
