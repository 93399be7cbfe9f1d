#!/usr/bin/python3
"""A fixed map (the node's map_mode fixed) on each half of Nordland: what the camera's trail localises.

  doc/experiments/fixed_map_halves.py DATA

For each half of the route (tune: frames 0..890, check: 891..1782, as the real-data benchmark splits
it), the map is that half's summer frames, keyframed at the defaults, and it stays as it is. The winter
frames of the same half then join the trail of the camera's newest keyframes, and after each keyframe
the trail's newest 20 (continuous mode's default length) are asked about as the node asks in fixed mode
(match_trail). Then the winter frames of the other half, which the map does not hold, do the same: every
answer accepted there is wrong. Right: the answer's place within 5 places of the localised keyframe's,
where route frames at which the recording train stood count as one place (as repeated_traversals.py
counts them). Nothing here was tuned: the figures are the defaults' on both halves. Needs python3-numpy
and python3-opencv.
"""

import argparse
import glob
import os

import cv2

import mrs_vpr
from repeated_traversals import LENGTH, TOLERANCE, route_places

SPLIT = 891  # the real-data benchmark's halves: route frames [0, 891) and [891, 1783)


def drive(recognizer, winter, frames, place, map_frames, new_ground):
    """Offers `frames` of winter to the trail, asking after each keyframe; returns answers, accepted, right."""
    trail = []  # the route frame of each trail keyframe
    answers = accepted = right = 0
    stamp = 100000.0 + 1000.0 * recognizer.trail_size
    for step, frame in enumerate(frames):
        if not recognizer.add_to_trail(cv2.imread(winter[frame], cv2.IMREAD_GRAYSCALE), stamp + 0.1 * step):
            continue
        trail.append(frame)
        if len(trail) < LENGTH:
            continue
        answer = recognizer.match_trail(LENGTH)
        answers += 1
        if not answer.match.accepted:
            continue
        accepted += 1
        truth = trail[len(trail) - LENGTH + answer.localised_row]
        found = map_frames[answer.match.reference_index]
        right += not new_ground and abs(place[found] - place[truth]) <= TOLERANCE
    return answers, accepted, right


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    args = parser.parse_args()
    summer = sorted(glob.glob(os.path.join(args.data, "nordland", "summer", "*.png")))
    winter = sorted(glob.glob(os.path.join(args.data, "nordland", "winter", "*.png")))
    place = route_places(summer, winter, len(summer))
    halves = {"tune": range(0, SPLIT), "check": range(SPLIT, len(summer))}
    for name, frames in halves.items():
        other = halves["check" if name == "tune" else "tune"]
        recognizer = mrs_vpr.PlaceRecognizer()
        map_frames = []  # the route frame of each map keyframe
        for step, frame in enumerate(frames):
            if recognizer.add_frame(cv2.imread(summer[frame], cv2.IMREAD_GRAYSCALE), 1000.0 + 0.1 * step):
                map_frames.append(frame)
        answers, accepted, right = drive(recognizer, winter, frames, place, map_frames, False)
        print("%s half: map summer %d..%d, %d keyframes; winter %d..%d: %d answers, %d accepted (%d right, %d wrong)"
              % (name, frames[0], frames[-1], len(recognizer), frames[0], frames[-1], answers, accepted, right,
                 accepted - right))
        answers, accepted, _ = drive(recognizer, winter, other, place, map_frames, True)
        print("  then winter %d..%d, not in the map: %d answers, %d accepted; the map still %d keyframes"
              % (other[0], other[-1], answers, accepted, len(recognizer)))


if __name__ == "__main__":
    main()
