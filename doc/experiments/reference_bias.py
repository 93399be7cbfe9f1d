#!/usr/bin/python3
"""Does removing each reference frame's bias from the differences help the per-frame protocol?

Some reference frames differ little from every query frame (bland scenery) and so attract wrong
answers. Two ways to take that bias out before the local contrast enhancement were tried:

  sequence  subtract from each reference frame's differences their mean over the test sequence's
            own frames (stays within the per-frame protocol: only the last ds frames are used)
  history   subtract their mean over the query traversal so far (every earlier frame, or the last
            50): an answer then depends on frames before its sequence

This is a NumPy re-implementation of the core's per-frame path (descriptor, difference matrix,
contrast enhancement, causal trajectory search, confidence = gap to the best rival in robust
spreads, acceptance at 3). Its "none" rows reproduce `mrs_vpr_eval --protocol per-frame
--sequence-length 10 --tolerance 2` on the same data exactly as it was before the velocity-bound
rule (commit 32728c6; since then answers at a velocity bound get confidence 0, PR-AUC 0.8144), so
the other rows differ from the project only in the bias removal. It leaves out the 100-rival
minimum, so its corridor figures rank confidences that the core reports as 0 in a 111-frame map.

  doc/experiments/reference_bias.py DATA_DIR    (DATA_DIR holds nordland/ and corridor/)

Needs python3-numpy and python3-opencv. Takes about two minutes.
"""

import argparse
import csv
import glob
import os

import cv2
import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

SEQUENCE_LENGTH = 10
TOLERANCE = 2
ACCEPT_THRESHOLD = 3.0
CONTRAST_HALF_WINDOW = 5  # contrast_window 10: the cell and 5 reference frames either side.
EXCLUSION_HALF = 5  # match_exclusion 10.
VELOCITIES = (0.8, 0.9, 1.0, 1.1, 1.2)
TUNE_HALF_END = 891  # Nordland query frames below this are the tune half, the rest the check half.


def descriptor(path):
    """64 x 32 grey image, 8 x 8 patches normalised, stored as 128 + 32 z in one byte."""
    grey = cv2.cvtColor(cv2.imread(path, cv2.IMREAD_COLOR), cv2.COLOR_BGR2GRAY).astype(np.float32)
    small = cv2.resize(grey, (64, 32), interpolation=cv2.INTER_AREA)
    for y in range(0, 32, 8):
        for x in range(0, 64, 8):
            patch = small[y:y + 8, x:x + 8]
            spread = patch.std()
            small[y:y + 8, x:x + 8] = (patch - patch.mean()) / spread if spread > 1e-6 else 0.0
    return np.clip(np.round(small * 32 + 128), 0, 255).astype(np.int16).ravel()


def difference_matrix(query_dir, reference_dir, pattern):
    """Mean absolute difference in patch standard deviations, query frames by reference frames."""
    reference = np.array([descriptor(p) for p in sorted(glob.glob(os.path.join(reference_dir, pattern)))])
    query = np.array([descriptor(p) for p in sorted(glob.glob(os.path.join(query_dir, pattern)))])
    return np.array([np.abs(reference - q).sum(axis=1) for q in query], dtype=np.float64) / (2048 * 32)


def enhance(differences):
    """OpenSeqSLAM's local contrast enhancement along each row, shifted by its bound (n-1)/sqrt(n)."""
    half = CONTRAST_HALF_WINDOW
    windows = sliding_window_view(np.pad(differences, ((0, 0), (half, half)), constant_values=np.nan),
                                  2 * half + 1, axis=1)
    mean = np.nanmean(windows, axis=2)
    spread = np.nanstd(windows, axis=2, ddof=1)
    z = np.where(spread > 1e-6, (differences - mean) / np.maximum(spread, 1e-6), 0.0)
    samples = 2 * half + 1
    return np.maximum(0.0, z + (samples - 1) / np.sqrt(samples))


def end_costs(enhanced, last):
    """Lowest mean cost over the velocities of the trajectories ending at each reference frame."""
    columns = enhanced.shape[1]
    best = np.full(columns, np.inf)
    rows = range(last - SEQUENCE_LENGTH + 1, last + 1)
    for velocity in VELOCITIES:
        offsets = [int(np.sign(t - last) * np.floor(abs(velocity * (t - last)) + 0.5)) for t in rows]
        begin = -offsets[0]
        total = np.zeros(columns - begin)
        for t, offset in zip(rows, offsets):
            total += enhanced[t, begin + offset:columns + offset]
        best[begin:] = np.minimum(best[begin:], total / SEQUENCE_LENGTH)
    return best


def answer(costs):
    """The best end and its confidence: gap to the best rival in 1.4826 median absolute deviations."""
    winner = int(np.argmin(costs))
    rivals = np.abs(np.arange(len(costs)) - winner) > EXCLUSION_HALF
    finite = costs[np.isfinite(costs)]
    spread = 1.4826 * np.median(np.abs(finite - np.median(finite)))
    return winner, (costs[rivals].min() - costs[winner]) / spread


def remove_bias(differences, last, method):
    """The rows of the test sequence ending at `last`, each reference frame's bias removed."""
    rows = differences[last - SEQUENCE_LENGTH + 1:last + 1]
    if method == "sequence":
        return rows - rows.mean(axis=0)
    if method.startswith("history"):
        first = 0 if method == "history" else max(0, last - int(method[len("history"):]) + 1)
        return rows - differences[first:last + 1].mean(axis=0)
    return rows


def average_precision(correct, confidence):
    """Area under the precision-recall curve as mrs_vpr_eval computes it (ties form one step). Every
    query here has an answer (answer() always names an end) and a place in the map, so none has to be
    kept out of acceptance or of the recall's denominator as mrs_vpr_eval keeps them out, and the
    confidences are never all equal (where mrs_vpr_eval gives no area)."""
    order = np.argsort(-confidence, kind="stable")
    correct, confidence = correct[order], confidence[order]
    area, previous_recall, true_positives, i = 0.0, 0.0, 0, 0
    while i < len(correct):
        j = i
        while j < len(correct) and confidence[j] == confidence[i]:
            j += 1
        true_positives += correct[i:j].sum()
        recall = true_positives / len(correct)
        area += (recall - previous_recall) * (true_positives / j)
        previous_recall, i = recall, j
    return area


def out_of_map_parts(nordland):
    """The queries of one half of the route against the summer frames of the other, both ways."""
    return (("tune queries, check map", nordland[:TUNE_HALF_END, TUNE_HALF_END:]),
            ("check queries, tune map", nordland[TUNE_HALF_END:, :TUNE_HALF_END]))


def print_halves(label, frames, correct, confidence):
    """The summary of the whole Nordland route and of its tune and check halves."""
    tune = frames < TUNE_HALF_END
    print(f"  {label:10} whole {summary(correct, confidence)}\n"
          f"  {'':10} tune  {summary(correct[tune], confidence[tune])}\n"
          f"  {'':10} check {summary(correct[~tune], confidence[~tune])}")


def evaluate(differences, is_correct, method):
    last_frames = np.arange(SEQUENCE_LENGTH - 1, differences.shape[0])
    correct, confidence = [], []
    for last in last_frames:
        # With bias removal the enhanced rows depend on the sequence, so they are made per query.
        winner, conf = answer(end_costs(enhance(remove_bias(differences, last, method)), SEQUENCE_LENGTH - 1))
        correct.append(is_correct(last, winner))
        confidence.append(conf)
    return last_frames, np.array(correct), np.array(confidence)


def summary(correct, confidence):
    accepted = confidence >= ACCEPT_THRESHOLD
    return (f"top-1 {correct.mean():.3f}  PR-AUC {average_precision(correct, confidence):.4f}  "
            f"accepted {accepted.sum()} ({(accepted & ~correct).sum()} wrong)")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder")
    args = parser.parse_args()
    data = args.data
    methods = ("none", "sequence", "history", "history50")

    nordland = difference_matrix(os.path.join(data, "nordland/winter"), os.path.join(data, "nordland/summer"), "*.png")
    print(f"Nordland winter against summer, {nordland.shape[0]} frames, ds = {SEQUENCE_LENGTH}, tolerance {TOLERANCE}")
    for method in methods:
        print_halves(method, *evaluate(nordland, lambda q, r: abs(q - r) <= TOLERANCE, method))
        for name, part in out_of_map_parts(nordland):
            _, _, confidence = evaluate(part, lambda q, r: False, method)
            print(f"  {'':10} out of the map ({name}): {(confidence >= ACCEPT_THRESHOLD).sum()} of "
                  f"{len(confidence)} accepted, highest confidence {confidence.max():.2f}")

    corridor = difference_matrix(os.path.join(data, "corridor/query"), os.path.join(data, "corridor/ref"), "*.jpg")
    with open(os.path.join(data, "corridor/ground_truth.csv"), encoding="utf-8") as file:
        truth = {int(row["query_index"]): [int(i) for i in row["matching_ref_indices"].split()]
                 for row in csv.DictReader(file)}
    print(f"Corridor, {corridor.shape[0]} frames, ds = {SEQUENCE_LENGTH}, "
          f"tolerance {TOLERANCE} around the ground truth")
    for method in methods:
        _, correct, confidence = evaluate(
            corridor, lambda q, r: any(abs(r - t) <= TOLERANCE for t in truth.get(q, [])), method)
        print(f"  {method:10} {summary(correct, confidence)}")


if __name__ == "__main__":
    main()
