#!/usr/bin/python3
"""A map built offline, visit by visit, with build_map: the place links it makes, and whether they are right.

  doc/experiments/build_map_visits.py DATA [--visits N] [--unlinked V [--link-places]]

The visits are those of repeated_traversals.py, each written as an image folder and appended to one map
by `build_map --append` at its defaults: Nordland summer 0..799 (the map), winter 300..699, then winter
300..699 again with another camera's noise on each later visit (a simulation of another winter day, which
the shared data does not hold), and last winter 1000..1299, which the map does not hold. After each
visit it prints the place links build_map made (its accepted closures) and how many are right:
the linked keyframe's place within 5 places of the place it is linked to, where route frames at which
the recording train stood count as one place. On the last visit every link is wrong. With
--unlinked V, visit V is appended with --no-place-links, as maps were built before build_map closed
loops; with --link-places as well, `build_map --link-places` then links the map's drives afterwards. Needs python3-numpy, python3-opencv and build_map on the ROS package path.
"""

import argparse
import glob
import os
import sqlite3
import subprocess
import tempfile

import cv2

from repeated_traversals import TOLERANCE, another_day, route_places


def write_visit(folder, images):
    """Writes `images` (paths, or arrays to save) into `folder` in order."""
    os.makedirs(folder)
    for index, image in enumerate(images):
        name = os.path.join(folder, "%05d.png" % index)
        if isinstance(image, str):
            os.symlink(image, name)
        else:
            cv2.imwrite(name, image)


def links_and_frames(database):
    """The map's place links, and each map frame's index in the visits appended (build_map's numbers)."""
    with sqlite3.connect(database) as connection:
        frames = [row[0] for row in connection.execute("SELECT sequence FROM frames ORDER BY id")]
        links = connection.execute("SELECT frame, reference FROM place_links ORDER BY id").fetchall()
    return links, frames


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    parser.add_argument("--visits", type=int, default=4,
                        help="visits of the stretch, the summer map's included (the visit to new ground follows them)")
    parser.add_argument("--unlinked", type=int, default=0, help="append this visit with --no-place-links")
    parser.add_argument("--link-places", action="store_true",
                        help="after the unlinked visit, link the map's drives with build_map --link-places")
    args = parser.parse_args()
    if args.visits < 2:
        parser.error("--visits: at least 2 (the summer map and the winter visit)")
    if args.unlinked and not 2 <= args.unlinked <= args.visits + 1:
        parser.error("--unlinked: a visit appended to the map, 2 to %d" % (args.visits + 1))
    if args.link_places and not args.unlinked:
        parser.error("--link-places: links the visit of --unlinked afterwards")
    summer = sorted(glob.glob(os.path.join(args.data, "nordland", "summer", "*.png")))
    winter = sorted(glob.glob(os.path.join(args.data, "nordland", "winter", "*.png")))
    place = route_places(summer, winter, len(summer))
    visits = [("summer 0..799", [summer[f] for f in range(0, 800)], range(0, 800))]
    visits.append(("winter 300..699", [winter[f] for f in range(300, 700)], range(300, 700)))
    for visit in range(3, args.visits + 1):
        images = [another_day(cv2.imread(winter[f], cv2.IMREAD_GRAYSCALE), visit) for f in range(300, 700)]
        visits.append(("winter 300..699, another day", images, range(300, 700)))
    visits.append(("winter 1000..1299, not in the map", [winter[f] for f in range(1000, 1300)], range(1000, 1300)))

    scratch = tempfile.TemporaryDirectory()
    database = os.path.join(scratch.name, "map.db")
    route_frame = []  # the route frame of each frame of the visits, in build_map's numbering
    links_before = 0
    for number, (name, images, frames) in enumerate(visits, start=1):
        folder = os.path.join(scratch.name, "visit_%d" % number)
        write_visit(folder, images)
        command = ["rosrun", "mrs_vpr", "build_map", "--images", folder, "--output", database]
        if number > 1:
            command.append("--append")
        if number == args.unlinked:
            command.append("--no-place-links")
        subprocess.run(command, check=True, stderr=subprocess.DEVNULL)
        route_frame.extend(frames)
        steps = [(name, number < len(visits))]
        if number == args.unlinked and args.link_places:
            steps.append(("build_map --link-places", True))
        for step, judged in steps:
            if step == "build_map --link-places":
                subprocess.run(["rosrun", "mrs_vpr", "build_map", "--link-places", "--output", database], check=True,
                               stderr=subprocess.DEVNULL)
            links, sequence = links_and_frames(database)
            new = links[links_before:]
            links_before = len(links)
            right = sum(abs(place[route_frame[sequence[f]]] - place[route_frame[sequence[r]]]) <= TOLERANCE
                        for f, r in new) if judged else 0
            print("visit %d (%s): %d keyframes in the map, %d closures linked (%d right, %d wrong)"
                  % (number, step, len(sequence), len(new), right, len(new) - right))


if __name__ == "__main__":
    main()
