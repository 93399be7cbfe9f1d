#!/usr/bin/python3
"""The summary of an mrs_vpr_eval JSON (--output) over its query frames below and from a split.

  doc/experiments/eval_halves.py EVALUATION.json [SPLIT]

Prints top-1, PR-AUC (average precision, as mrs_vpr_eval computes it), and the precision and recall of
accepted answers over every record (top-1 and recall over those about places in the map), and with
SPLIT also over the records whose query_index is below SPLIT ("tune") and from SPLIT on ("check"). For
the Nordland halves the split is 891. Needs python3-numpy.
"""

import argparse
import json

import numpy as np


def average_precision(correct, confidence, answered, in_map):
    """Area under the precision-recall curve as mrs_vpr_eval computes it (precisionRecallCurve and
    averagePrecision in src/evaluation/evaluation.cpp): records without an answer are never accepted
    but count in the recall's denominator, which holds the records about places in the map; ties form
    one step, and a curve of one step ranks nothing (NaN)."""
    if in_map == 0:
        return float("nan")
    correct, confidence = correct[answered], confidence[answered]
    if len(np.unique(confidence)) < 2:
        return float("nan")
    order = np.argsort(-confidence, kind="stable")
    correct, confidence = correct[order], confidence[order]
    area, previous_recall, true_positives, i = 0.0, 0.0, 0, 0
    while i < len(correct):
        j = i
        while j < len(correct) and confidence[j] == confidence[i]:
            j += 1
        true_positives += correct[i:j].sum()
        recall = true_positives / in_map
        area += (recall - previous_recall) * (true_positives / j)
        previous_recall, i = recall, j
    return area


def summary(records):
    if not records:
        return "no records"
    correct = np.array([r["correct"] for r in records])
    confidence = np.array([r["confidence"] for r in records])
    accepted = np.array([r["accepted"] for r in records])
    answered = np.array([r["predicted_index"] >= 0 for r in records])
    in_map = sum(1 for r in records if r["true_indices"])
    precision = (accepted & correct).sum() / accepted.sum() if accepted.any() else float("nan")
    pr_auc = average_precision(correct, confidence, answered, in_map)
    top1 = correct.sum() / in_map if in_map else float("nan")
    recall = (accepted & correct).sum() / in_map if in_map else float("nan")
    return (f"queries {len(records):5d} ({in_map} in the map)  top-1 {top1:.3f}  PR-AUC {pr_auc:.3f}  "
            f"accepted {accepted.sum():5d}  precision {precision:.3f}  recall {recall:.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("evaluation", type=argparse.FileType("r", encoding="utf-8"), help="an mrs_vpr_eval JSON (--output)")
    parser.add_argument("split", type=int, nargs="?", help="the first query_index of the check part")
    args = parser.parse_args()
    with args.evaluation as file:
        records = json.load(file)["records"]
    print(f"all    {summary(records)}")
    if args.split is not None:
        split = args.split
        print(f"tune   {summary([r for r in records if r['query_index'] < split])}")
        print(f"check  {summary([r for r in records if r['query_index'] >= split])}")


if __name__ == "__main__":
    main()
