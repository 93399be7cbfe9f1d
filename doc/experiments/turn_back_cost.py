#!/usr/bin/python3
"""What the turn-back rule costs an accepted answer of continuous mode.

  doc/experiments/turn_back_cost.py DATA

The map is Nordland summer frames 0..1782 and then winter 0..1782, keyframed at the defaults (about 3050
keyframes; the winter pass revisits the summer one). Each of the last 151 keyframes is asked about once,
as continuous mode asks (match_recent with the sequence ending there), with recent_frames 20 and 300 and
recent_exclusion 100 (the default) and 1000. The rule judges only accepted answers (turn_back.hpp), so
the same questions are asked of a second recognizer whose accept_threshold (1000) accepts nothing, where
it does not run: the difference of the mean times of the accepted answers is the rule's cost. Times
depend on the machine and its load; compare the two columns of one run. Needs python3-opencv.
"""

import argparse
import glob
import os
import statistics
import time

import cv2

import mrs_vpr

ASKED = 151


def recognizer(images, **parameters):
    """A recognizer whose map is `images`, keyframed at the defaults."""
    result = mrs_vpr.PlaceRecognizer(**parameters)
    for step, image in enumerate(images):
        result.add_frame(image, 1000.0 + 0.025 * step)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder (holding nordland/summer and nordland/winter)")
    args = parser.parse_args()
    images = [cv2.imread(path) for season in ("summer", "winter")
              for path in sorted(glob.glob(os.path.join(args.data, "nordland", season, "*.png")))]
    for exclusion in (100, 1000):
        judged = recognizer(images, recent_exclusion=exclusion)
        unjudged = recognizer(images, recent_exclusion=exclusion, **{"sequence/accept_threshold": 1000.0})
        for length in (20, 300):
            with_rule, without_rule = [], []
            for end in range(len(judged) - ASKED + 1, len(judged) + 1):
                start = time.perf_counter()
                answer = judged.match_recent(length, "", end)
                middle = time.perf_counter()
                unjudged.match_recent(length, "", end)
                if answer.match.accepted:
                    with_rule.append(1000.0 * (middle - start))
                    without_rule.append(1000.0 * (time.perf_counter() - middle))
            print("recent_exclusion %4d, recent_frames %3d: %d of %d accepted; accepted answers %.2f ms, the same "
                  "questions without the rule %.2f ms (means)" % (
                      exclusion, length, len(with_rule), ASKED, statistics.mean(with_rule) if with_rule else 0.0,
                      statistics.mean(without_rule) if without_rule else 0.0), flush=True)


if __name__ == "__main__":
    main()
