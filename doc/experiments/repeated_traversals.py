#!/usr/bin/python3
"""A map that holds a stretch of route more than once: what continuous mode accepts on the next visit.

  doc/experiments/repeated_traversals.py DATA [--visits N] [--first F] [--last L] [--restart]

A robot that maps as it drives appends every visit to its map (the node with ~database, day after day).
Here the first visit is Nordland summer frames 0..799, the second winter frames F..L (default 300..699),
and each later visit winter F..L again, each time with its own camera noise (a shift of a pixel, a gain
of 0.85 and an offset of 10 grey levels, and sensor noise of 3 grey levels, seeded by the visit): a
simulation standing in for driving the same stretch on another winter day, which the shared data does
not hold. Every visit is keyframed at the defaults and asked about after each new keyframe as continuous
mode asks (match_recent with the default 20 keyframes, which searches every earlier visit). Visits
follow one another directly, as if the robot were carried back to the stretch's start, so the first
questions of a visit hold the end of the one before. It prints, per visit, the answers, those accepted
(right: the answer's place within 5 places of the localised keyframe's, where route frames at which the
recording train stood count as one place, as the real-data benchmark counts them), the answers not
accepted that named the right place, and their median confidence. A last visit drives on into winter
1000..1299, which the map does not hold: every answer accepted about a keyframe there is wrong (at the
centred alignment the first answers of that visit localise the last keyframes of the one before, and are
judged as that visit's). With --restart, the map is saved after each visit and loaded into a new
recognizer, as a node restarted on its ~database reads it (frames, place links and drive starts, in one
file), and, as such a node asks, the visit's keyframes are asked about once the visit holds a whole
test sequence of them.
Needs python3-numpy and python3-opencv.
"""

import argparse
import glob
import os
import statistics
import tempfile

import cv2
import numpy as np

import mrs_vpr

TOLERANCE = 5
LENGTH = 20  # continuous mode's default sequence length, in keyframes


def another_day(image, seed):
    """The same view through a camera of another day: shifted a pixel, another gain, sensor noise."""
    rng = np.random.default_rng(seed)
    shifted = np.roll(image.astype(np.float32), 1, axis=1)
    noisy = 0.85 * shifted + 10.0 + rng.normal(0.0, 3.0, image.shape)
    return np.clip(noisy, 0, 255).astype(np.uint8)


def route_places(summer, winter, frames):
    """The place of each route frame: a step that changes the view by under a tenth of the route's median
    step in both seasons is the recording train standing, and stays at the same place (as
    include/mrs_vpr/evaluation/route_places.hpp counts them)."""
    standing = None
    for season in (summer, winter):
        images = [cv2.imread(season[frame], cv2.IMREAD_GRAYSCALE).astype(np.float32) for frame in range(frames)]
        steps = np.array([np.abs(b - a).mean() for a, b in zip(images, images[1:])])
        still = steps < 0.1 * np.median(steps)
        standing = still if standing is None else standing & still
    return np.concatenate([[0], np.cumsum(~standing)])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    parser.add_argument("--visits", type=int, default=4, help="visits in all, the summer map's included")
    parser.add_argument("--first", type=int, default=300, help="first winter frame of the revisits")
    parser.add_argument("--last", type=int, default=699, help="last winter frame of the revisits")
    parser.add_argument("--restart", action="store_true",
                        help="save the map after each visit and go on with a new recognizer that loads it")
    args = parser.parse_args()
    summer = sorted(glob.glob(os.path.join(args.data, "nordland", "summer", "*.png")))
    winter = sorted(glob.glob(os.path.join(args.data, "nordland", "winter", "*.png")))
    place = route_places(summer, winter, len(summer))
    recognizer = mrs_vpr.PlaceRecognizer()
    places = []  # the route frame of each map keyframe
    for step, frame in enumerate(range(0, 800)):
        if recognizer.add_frame(cv2.imread(summer[frame], cv2.IMREAD_GRAYSCALE), 1000.0 + 0.1 * step):
            places.append(frame)
    print("visit 1 (the map): summer 0..799, %d keyframes" % len(recognizer))
    scratch = tempfile.TemporaryDirectory()
    for visit in range(2, args.visits + 2):
        if args.restart:
            saved = os.path.join(scratch.name, "before_visit_%d.db" % visit)
            recognizer.save(saved)
            recognizer = mrs_vpr.PlaceRecognizer()
            recognizer.load(saved)
        new_ground = visit == args.visits + 1
        frames = range(1000, 1300) if new_ground else range(args.first, args.last + 1)
        answers = accepted = right = 0
        refused_right = []  # confidences of answers not accepted that named the right place
        added = 0  # the visit's keyframes
        for step, frame in enumerate(frames):
            image = cv2.imread(winter[frame], cv2.IMREAD_GRAYSCALE)
            if visit > 2:
                image = another_day(image, visit)
            if not recognizer.add_frame(image, 100000.0 * visit + 0.1 * step):
                continue
            places.append(frame)
            added += 1
            if args.restart and added < LENGTH:
                continue  # as a node asks after a load: about its own run's keyframes only
            answer = recognizer.match_recent(LENGTH)
            if answer.match.reference_index < 0:
                continue
            truth = places[len(recognizer) - LENGTH + answer.localised_row]
            if new_ground and truth < frames[0]:
                continue  # a keyframe of the visit before
            answers += 1
            correct = abs(place[places[answer.match.reference_index]] - place[truth]) <= TOLERANCE
            if answer.match.accepted:
                accepted += 1
                right += correct and not new_ground
            elif correct:
                refused_right.append(answer.match.confidence)
        if new_ground:
            print("visit %d (winter 1000..1299, not in the map): %d answers, %d accepted" % (visit, answers, accepted))
            break
        median = statistics.median(refused_right) if refused_right else float("nan")
        print("visit %d (%s %d..%d): %d answers, %d accepted (%d right, %d wrong); %d not accepted named the "
              "right place, median confidence %.2f" % (visit, "winter" if visit == 2 else "winter, another day",
                                                       args.first, args.last, answers, accepted, right,
                                                       accepted - right, len(refused_right), median))


if __name__ == "__main__":
    main()
