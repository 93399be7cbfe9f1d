#!/usr/bin/python3
"""Rounded or blended trajectory crossings: which gives better per-frame answers?

A straight trajectory of velocity v crosses the row k frames before its anchor at column
anchor + v * k, which mostly falls between two reference frames. OpenSeqSLAM and the core round it
to the nearest column. The alternative is to read the linear blend of the two columns around it.

This reuses reference_bias.py's NumPy copy of the core's per-frame path (its "rounded" rows equal
`mrs_vpr_eval --protocol per-frame --tolerance 2` before the velocity-bound rule, see there) and
changes only the crossings. For the sequence
lengths 10 and 50 it prints, on Nordland (winter against summer) and the corridor: top-1, PR-AUC and
the accepted answers at the core's threshold (3); and for out-of-map queries (the winter frames of
one half of the Nordland route against the summer frames of the other) how many were accepted and
their largest and 99th-percentile confidence, i.e. the margin the threshold keeps on new ground.

The search patched to blend is doc/experiments/blended_crossings.patch (`git apply` it to measure
the C++ benchmarks; its unit tests are not updated).

  doc/experiments/blended_crossings.py DATA_DIR    (DATA_DIR holds nordland/ and corridor/)

Needs python3-numpy and python3-opencv. Takes about five minutes.
"""

import argparse
import csv
import os

import numpy as np

import reference_bias as pipeline


def crossing(velocity, rows_from_anchor):
    """Column offset of a crossing and the weight of the next column (0 on a column)."""
    position = velocity * rows_from_anchor
    if abs(position - round(position)) < 1e-6:  # 0.9 * -10 is -9.000000000000002.
        return int(round(position)), 0.0
    below = int(np.floor(position))
    return below, position - below


def blended_end_costs(enhanced, last, length):
    """As pipeline.end_costs, but each crossing reads the blend of the two columns around it."""
    columns = enhanced.shape[1]
    best = np.full(columns, np.inf)
    rows = range(last - length + 1, last + 1)
    for velocity in pipeline.VELOCITIES:
        crossings = [crossing(velocity, t - last) for t in rows]
        begin = -crossings[0][0]
        total = np.zeros(columns - begin)
        for t, (offset, weight) in zip(rows, crossings):
            cells = enhanced[t, begin + offset:columns + offset]
            if weight > 0:  # Causal: offset < 0 here, so the next column is inside the row.
                cells = (1 - weight) * cells + weight * enhanced[t, begin + offset + 1:columns + offset + 1]
            total += cells
        best[begin:] = np.minimum(best[begin:], total / length)
    return best


def answers(differences, is_correct, length, blended):
    """Per-frame answers of every complete sequence: last frames, correctness and confidence."""
    enhanced = pipeline.enhance(differences)  # Per row, so it does not depend on the sequence.
    last_frames = np.arange(length - 1, differences.shape[0])
    correct, confidence = [], []
    for last in last_frames:
        rows = enhanced[last - length + 1:last + 1]
        if blended:
            costs = blended_end_costs(rows, length - 1, length)
        else:
            pipeline.SEQUENCE_LENGTH = length
            costs = pipeline.end_costs(rows, length - 1)
        winner, conf = pipeline.answer(costs)
        correct.append(is_correct(last, winner))
        confidence.append(conf)
    return last_frames, np.array(correct), np.array(confidence)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="the shared data folder")
    args = parser.parse_args()
    data = args.data
    nordland = pipeline.difference_matrix(os.path.join(data, "nordland/winter"),
                                          os.path.join(data, "nordland/summer"), "*.png")
    corridor = pipeline.difference_matrix(os.path.join(data, "corridor/query"),
                                          os.path.join(data, "corridor/ref"), "*.jpg")
    with open(os.path.join(data, "corridor/ground_truth.csv"), encoding="utf-8") as file:
        truth = {int(row["query_index"]): [int(i) for i in row["matching_ref_indices"].split()]
                 for row in csv.DictReader(file)}
    tolerance = pipeline.TOLERANCE

    for length in (10, 50):
        print(f"ds = {length}, tolerance {tolerance}")
        for blended in (False, True):
            name = "blended" if blended else "rounded"
            pipeline.print_halves(name, *answers(nordland, lambda q, r: abs(q - r) <= tolerance, length, blended))
            for part_name, part in pipeline.out_of_map_parts(nordland):
                _, _, confidence = answers(part, lambda q, r: False, length, blended)
                print(f"  {'':10} out of the map ({part_name}): {(confidence >= pipeline.ACCEPT_THRESHOLD).sum()} of "
                      f"{len(confidence)} accepted, confidence largest {confidence.max():.2f}, "
                      f"99th percentile {np.percentile(confidence, 99):.2f}")
            _, correct, confidence = answers(
                corridor, lambda q, r: any(abs(r - t) <= tolerance for t in truth.get(q, [])), length, blended)
            print(f"  {'':10} corridor {pipeline.summary(correct, confidence)}")


if __name__ == "__main__":
    main()
