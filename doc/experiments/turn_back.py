#!/usr/bin/python3
"""A robot that turns back within a test sequence: what continuous mode accepts on the way back.

  doc/experiments/turn_back.py DATA [--resume-elsewhere] [--backwards-only] [--forward-again N] [--halves]

The map is Nordland summer frames 0..399 and then 400..799 (with --resume-elsewhere 1000..1399: two
stretches that follow each other in the map, as where a recording resumed elsewhere), keyframed at the
defaults. The revisit is winter frames 300..399 and then 399 back to 300, as a robot that drives on and
turns back over its path sees them (with --backwards-only: winter 799 back to 100, a robot backing up
over a mapped stretch from its start; with --forward-again N: winter 300..399, back N frames, and forward
again to 549, a robot that backs up and drives on). After each new keyframe it asks as continuous mode does
(match_recent with the default 20 keyframes) and prints each accepted answer that is wrong (the
answer's keyframe more than 5 route frames from the place of the localised keyframe), the answers not
accepted because the sequence returns to a place it passed (turn_back.hpp), and the totals.
--halves also prints, for every accepted answer, how far each half of the test sequence (the keyframes
before the localised one, and from it on) stands out at the answer: its cost along the answer's
trajectory against the same half's costs at every other end at the same velocity, in standard
deviations from their median (differences contrast-enhanced over 11 map frames, as an approximation
of the search's own). Needs python3-numpy and python3-opencv.
"""

import argparse
import glob
import os

import cv2
import numpy as np

import mrs_vpr

TOLERANCE = 5
LENGTH = 20  # continuous mode's default sequence length, in keyframes


def enhanced(query, reference, window=10):
    """Differences of query x reference descriptors, each normalised over `window` + 1 map frames."""
    raw = np.abs(query[:, None, :] - reference[None, :, :]).mean(axis=2)
    result = np.zeros_like(raw)
    for column in range(raw.shape[1]):
        near = raw[:, max(0, column - window // 2):column + window // 2 + 1]
        result[:, column] = (raw[:, column] - near.mean(axis=1)) / (near.std(axis=1) + 1e-6)
    return result


def half_scores(matrix, answer):
    """How far each half of the test sequence stands out at the answer (see the module's text)."""
    anchor, end, velocity = answer.localised_row, answer.match.reference_index, answer.match.velocity
    scores = []
    for rows in (range(0, anchor), range(anchor, LENGTH)):
        costs = np.full(matrix.shape[1], np.nan)
        for candidate in range(matrix.shape[1]):
            columns = [candidate + int(round(velocity * (row - anchor))) for row in rows]
            if min(columns) >= 0 and max(columns) < matrix.shape[1]:
                costs[candidate] = np.mean([matrix[row, column] for row, column in zip(rows, columns)])
        others = costs[np.abs(np.arange(len(costs)) - end) > TOLERANCE * 2]
        others = others[np.isfinite(others)]
        scores.append((np.median(others) - costs[end]) / others.std())
    return scores


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    parser.add_argument("--resume-elsewhere", action="store_true", help="map summer 1000..1399 after 0..399")
    parser.add_argument("--backwards-only", action="store_true", help="revisit winter 799 back to 100 only")
    parser.add_argument("--forward-again", type=int, metavar="N",
                        help="revisit winter 300..399, back N frames, then forward again to 549")
    parser.add_argument("--halves", action="store_true", help="print how far each half stands out")
    args = parser.parse_args()
    summer = sorted(glob.glob(os.path.join(args.data, "nordland", "summer", "*.png")))
    winter = sorted(glob.glob(os.path.join(args.data, "nordland", "winter", "*.png")))
    recognizer = mrs_vpr.PlaceRecognizer()
    places, descriptors = [], []  # the route frame and the descriptor of each map keyframe

    def offer(path, frame, stamp):
        image = cv2.imread(path)
        if recognizer.add_frame(image, stamp):
            places.append(frame)
            descriptors.append(recognizer.describe(image).astype(np.int16))

    second = range(1000, 1400) if args.resume_elsewhere else range(400, 800)
    for step, frame in enumerate(list(range(0, 400)) + list(second)):
        offer(summer[frame], frame, 1000.0 + 0.025 * step)
    if args.backwards_only:
        revisit = list(range(799, 99, -1))
    elif args.forward_again:
        revisit = list(range(300, 400)) + list(range(399, 399 - args.forward_again, -1)) + list(
            range(399 - args.forward_again, 550))
    else:
        revisit = list(range(300, 400)) + list(range(399, 299, -1))
    right = wrong = 0
    refused = {True: 0, False: 0}  # answers not accepted as turning back, by whether they were right
    exclusion = recognizer.parameters["recent_exclusion"]
    for step, frame in enumerate(revisit):
        before = len(recognizer)
        offer(winter[frame], frame, 3000.0 + 0.025 * step)
        if len(recognizer) == before or len(recognizer) < 2 * LENGTH:
            continue
        answer = recognizer.match_recent(LENGTH)
        size = len(recognizer)
        way = "back" if step >= 100 or args.backwards_only else "out"
        if args.forward_again and step >= 100 + args.forward_again:
            way = "forward again"
        truth = places[size - LENGTH + answer.localised_row]
        found = places[answer.match.reference_index]
        correct = abs(found - truth) <= TOLERANCE
        if answer.match.turned_back:
            refused[correct] += 1
            print("revisit frame %3d (%s): winter %d placed at summer %d, confidence %.2f, %s, not accepted: turns "
                  "back" % (step, way, truth, found, answer.match.confidence, "right" if correct else "WRONG"))
        if not answer.match.accepted:
            continue
        right += correct
        wrong += not correct
        line = "revisit frame %3d (%s): winter %d placed at summer %d, confidence %.2f, %s" % (
            step, way, truth, found, answer.match.confidence, "right" if correct else "WRONG")
        if args.halves:
            matrix = enhanced(np.array(descriptors[size - LENGTH:size]),
                              np.array(descriptors[:size - LENGTH - exclusion]))
            line += "; halves stand out %.2f and %.2f" % tuple(half_scores(matrix, answer))
        if args.halves or not correct:
            print(line)
    print("accepted: %d right, %d wrong; not accepted as turning back: %d right, %d wrong" % (
        right, wrong, refused[True], refused[False]))


if __name__ == "__main__":
    main()
