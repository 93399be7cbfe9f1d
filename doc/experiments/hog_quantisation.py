#!/usr/bin/python3
"""What storing HOG descriptors in one byte a value costs: the per-frame protocol with OpenCV's HOG
values as floats against the same values quantised as the core stores them (round(510 v), saturated at
255, so that 0.5 is 255).

The front end is the core's default (grey image resized to 128 x 64 by area interpolation, cells of
16 px, 9 bins, blocks of 2 x 2 cells, L2-Hys), compared by the mean absolute difference. The search is
the NumPy copy of the per-frame path in reference_bias.py (contrast enhancement, causal straight
trajectories at 0.8..1.2, confidence = gap to the best rival in robust spreads), without the core's
velocity-bound rule and 100-rival minimum: both rows share it, so their difference is the quantisation's.

  doc/experiments/hog_quantisation.py DATA_DIR    (DATA_DIR holds nordland/ and corridor/)

Needs python3-numpy and python3-opencv. Takes a few minutes.
"""

import argparse
import csv
import glob
import os

import cv2
import numpy as np

import reference_bias as per_frame

LEVELS_PER_UNIT = 510.0
HOG = cv2.HOGDescriptor((128, 64), (32, 32), (16, 16), (16, 16), 9)


def hog(path):
    grey = cv2.cvtColor(cv2.imread(path, cv2.IMREAD_COLOR), cv2.COLOR_BGR2GRAY)
    return HOG.compute(cv2.resize(grey, (128, 64), interpolation=cv2.INTER_AREA)).ravel().astype(np.float64)


def differences(query_dir, reference_dir, pattern, quantised):
    describe = (lambda p: np.clip(np.round(hog(p) * LEVELS_PER_UNIT), 0, 255)) if quantised else hog
    reference = np.array([describe(p) for p in sorted(glob.glob(os.path.join(reference_dir, pattern)))])
    query = np.array([describe(p) for p in sorted(glob.glob(os.path.join(query_dir, pattern)))])
    return np.array([np.abs(reference - q).mean(axis=1) for q in query])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder")
    args = parser.parse_args()
    data = args.data
    with open(os.path.join(data, "corridor/ground_truth.csv"), encoding="utf-8") as file:
        truth = {int(row["query_index"]): [int(i) for i in row["matching_ref_indices"].split()]
                 for row in csv.DictReader(file)}
    for quantised in (False, True):
        label = "8-bit" if quantised else "float"
        nordland = differences(os.path.join(data, "nordland/winter"), os.path.join(data, "nordland/summer"), "*.png",
                               quantised)
        corridor = differences(os.path.join(data, "corridor/query"), os.path.join(data, "corridor/ref"), "*.jpg",
                               quantised)
        for length in (10, 30):
            per_frame.SEQUENCE_LENGTH = length
            frames, correct, confidence = per_frame.evaluate(
                nordland, lambda q, r: abs(q - r) <= per_frame.TOLERANCE, "none")
            tune = frames < per_frame.TUNE_HALF_END
            print(f"{label:6} ds = {length:2}  Nordland tune  {per_frame.summary(correct[tune], confidence[tune])}")
            print(f"{label:6} ds = {length:2}  Nordland check {per_frame.summary(correct[~tune], confidence[~tune])}")
            _, correct, confidence = per_frame.evaluate(
                corridor, lambda q, r: any(abs(r - t) <= per_frame.TOLERANCE for t in truth.get(q, [])), "none")
            print(f"{label:6} ds = {length:2}  corridor       {per_frame.summary(correct, confidence)}")


if __name__ == "__main__":
    main()
