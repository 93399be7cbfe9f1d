"""Offline evaluation with the core's protocols and metrics (mrs_vpr/evaluation/evaluation.hpp): the
figures mrs_vpr_eval prints, from NumPy images.
"""

import collections
import time

from mrs_vpr import _bindings

#: records: one dict per evaluated query (query_index, true_indices, predicted_index, score,
#: confidence, accepted, rival_places, at_velocity_bound, repeated_view, time_ms); summary: a dict of
#: the figures (top1, pr_auc, recall_at_100_precision, accepted, accepted_precision, ...); pr_curve:
#: NumPy arrays threshold, precision and recall.
Evaluation = collections.namedtuple("Evaluation", "records summary pr_curve")

summarise = _bindings.summarise
precision_recall_curve = _bindings.precision_recall_curve


def _ground_truth_dict(ground_truth):
    """None, a dict {query frame: [map frames]} or a sequence of one map frame per query frame (< 0:
    none) as the core's ground truth."""
    if ground_truth is None or isinstance(ground_truth, dict):
        return ground_truth
    return {query: [int(reference)] if reference >= 0 else [] for query, reference in enumerate(ground_truth)}


def evaluate(recognizer, query_images, ground_truth=None, tolerance=2, protocol="per-frame", method="",
             queries=100, seed=0, channel_order="bgr"):
    """Localises a query traversal in the recognizer's map and scores the answers.

    protocol "per-frame": every query frame with a full sequence of sequence_length frames (OpenSeqSLAM's
    protocol); "global": `queries` test sequences of sequence_length frames at random positions drawn
    with `seed`. ground_truth: None (query frame i shows map frame i), a dict {query frame: [map
    frames]} or a sequence of one map frame per query frame. Map frames are those the recognizer holds
    (its keyframes; build the map with min_appearance_change=0 to keep every frame). The per-frame
    protocol matches every query frame; a global test sequence is keyframed by match(). An answer is
    correct within `tolerance` frames of a true one. Returns an Evaluation (records, summary, pr_curve).
    """
    parameters = recognizer.parameters
    length = parameters["sequence/sequence_length"]
    alignment = parameters["sequence/alignment"]
    frames = len(query_images)
    truths = _bindings.truths(_ground_truth_dict(ground_truth), frames, len(recognizer))
    records = []
    if protocol == "per-frame":
        evaluated = _bindings.per_frame_queries(frames, length, alignment)
        start = time.perf_counter()
        matches = recognizer.match_every_frame(query_images, method, channel_order)
        per_query_ms = 1000.0 * (time.perf_counter() - start) / max(len(evaluated), 1)
        for query in evaluated:
            if truths[query] is not None:
                records.append(_bindings.query_record(query, truths[query], matches[query], per_query_ms))
    elif protocol == "global":
        for first, count, query in _bindings.global_queries(frames, length, queries, seed, alignment):
            if truths[query] is None:
                continue
            start = time.perf_counter()
            answer = recognizer.match(query_images[first:first + count], method, channel_order)
            elapsed_ms = 1000.0 * (time.perf_counter() - start)
            records.append(_bindings.query_record(query, truths[query], answer.match, elapsed_ms))
    else:
        raise ValueError("protocol must be 'per-frame' or 'global', got '%s'" % protocol)
    return Evaluation(records, summarise(records, tolerance), precision_recall_curve(records, tolerance))
