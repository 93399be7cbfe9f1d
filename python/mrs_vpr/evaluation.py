"""Offline evaluation with the core's protocols and metrics (mrs_vpr/evaluation/evaluation.hpp): the
figures mrs_vpr_eval prints, from NumPy images.
"""

import collections
import collections.abc
import operator
import reprlib
import time
import warnings

import numpy as np

from mrs_vpr import _bindings

#: records: one dict per evaluated query (query_index, true_index, true_indices, predicted_index,
#: predicted_last, score, confidence, accepted, rival_places, at_velocity_bound, repeated_view, time_ms,
#: correct: within the tolerance of a true frame, as mrs_vpr_eval's records; time_ms includes describing
#: the images, which mrs_vpr_eval does before it times the queries); summary: a dict of
#: the figures (top1, pr_auc, recall_at_100_precision, accepted, accepted_precision, ...); pr_curve:
#: NumPy arrays threshold, precision and recall.
Evaluation = collections.namedtuple("Evaluation", "records summary pr_curve")

summarise = _bindings.summarise
precision_recall_curve = _bindings.precision_recall_curve


#: The range of the core's int (tolerance, map frames) and of the global protocol's std::uint64_t seed.
_INT_MAX = 2**31 - 1
_SEED_MAX = 2**64 - 1
_METHODS = ("mrs", "seqslam", "")
_PROTOCOLS = ("per-frame", "global")
_CHANNEL_ORDERS = ("bgr", "rgb")


def _is_integer(value):
    """An int or a NumPy integer, but not a bool; a float is not one, even 2.0 (the parameters' rule)."""
    return not isinstance(value, (bool, np.bool_)) and hasattr(type(value), "__index__")


def _whole_number(name, value, low, high):
    """`value` as an int in low..high, or ValueError naming `name` and the range."""
    if not _is_integer(value):
        raise ValueError("%s must be in %d..%d, got %s (not an integer)" % (name, low, high, reprlib.repr(value)))
    number = operator.index(value)
    if not low <= number <= high:
        raise ValueError("%s must be in %d..%d, got %d" % (name, low, high, number))
    return number


def _one_of(name, value, allowed):
    """ValueError naming `name` unless `value` is one of the strings `allowed`."""
    if not isinstance(value, str) or value not in allowed:
        raise ValueError("%s must be %s, got %s" % (name, " or ".join(map(repr, allowed)), reprlib.repr(value)))


def _ground_truth_dict(ground_truth, query_frames, reference_frames):
    """None, a dict {query frame: [map frames]} or a sequence of one map frame per query frame (< 0:
    none) as the core's ground truth. Anything else raises ValueError naming the bad entry (the core
    checks a dict's entries and the range of every frame)."""
    if ground_truth is None or isinstance(ground_truth, dict):
        return ground_truth
    if isinstance(ground_truth, np.ndarray) and ground_truth.ndim != 1:
        raise ValueError("ground_truth as an array must have one dimension (one map frame per query frame), got "
                         "shape %s" % (ground_truth.shape,))
    if not isinstance(ground_truth, (collections.abc.Sequence, np.ndarray)) or isinstance(
            ground_truth, (str, bytes, bytearray)):
        raise ValueError("ground_truth must be None, a dict {query frame: [map frames]} or a sequence of one map "
                         "frame per query frame, got %s" % type(ground_truth).__name__)
    truth = {}
    for query, reference in enumerate(ground_truth):
        if not _is_integer(reference):
            raise ValueError("a ground truth sequence holds one map frame per query frame, an integer (< 0: none); "
                             "got %s for query frame %d" % (reprlib.repr(reference), query))
        reference = operator.index(reference)
        if reference >= reference_frames:  # The core's message, before a number beyond its int is narrowed.
            raise ValueError("ground truth row of query frame %d lists reference frame %d, but the reference has %d "
                             "frames" % (query, reference, reference_frames))
        truth[query] = [reference] if reference >= 0 else []
    if len(truth) != query_frames:  # A shorter one would drop the frames it misses without a word.
        raise ValueError("a ground truth sequence holds one map frame per query frame: %d for %d query frames"
                         % (len(truth), query_frames))
    return truth


def evaluate(recognizer, query_images, ground_truth=None, tolerance=_bindings.DEFAULT_TOLERANCE, protocol="per-frame",
             method="", queries=_bindings.DEFAULT_GLOBAL_QUERIES, seed=_bindings.DEFAULT_SEED, channel_order="bgr"):
    """Localises a query traversal in the recognizer's map and scores the answers.

    protocol "per-frame": every query frame with a full sequence of sequence_length frames (OpenSeqSLAM's
    protocol); "global": `queries` test sequences of sequence_length frames at random positions drawn
    with `seed`. ground_truth: None (query frame i shows map frame i), a dict {query frame: [map
    frames]} or a sequence of one map frame per query frame. Map frames are those the recognizer holds
    (its keyframes; build the map with min_appearance_change=0 to keep every frame). The per-frame
    protocol matches every query frame; a global test sequence is keyframed by match(), and its record
    names the image the answer localises (the middle or newest keyframe kept, not always the window's
    middle or newest image); a test sequence whose localised image has no truth is skipped. An answer is
    correct within `tolerance` frames of a true one. Returns an Evaluation (records, summary, pr_curve).

    Every argument is checked before any query is matched: a bad one raises ValueError naming it and
    what it may be (tolerance 0..2147483647, queries 1..100000 and seed 0..2**64-1, whole numbers). The
    defaults are mrs_vpr_eval's: tolerance 2, queries 200, seed 42.
    """
    if not isinstance(recognizer, _bindings.PlaceRecognizer):
        raise ValueError("recognizer must be a mrs_vpr.PlaceRecognizer, got %s" % type(recognizer).__name__)
    if isinstance(query_images, (str, bytes, bytearray)) or not hasattr(query_images, "__len__"):
        raise ValueError("query_images must be a sequence of images (a list, or an N x H x W or N x H x W x C "
                         "array), got %s" % type(query_images).__name__)
    tolerance = _whole_number("tolerance", tolerance, 0, _INT_MAX)
    _one_of("protocol", protocol, _PROTOCOLS)
    if not isinstance(method, str) or method not in _METHODS:
        raise ValueError("method must be 'mrs', 'seqslam' or '' (the recognizer's default_method), got %s"
                         % reprlib.repr(method))
    queries = _whole_number("queries", queries, 1, _bindings.MAX_GLOBAL_QUERIES)
    seed = _whole_number("seed", seed, 0, _SEED_MAX)
    _one_of("channel_order", channel_order, _CHANNEL_ORDERS)
    parameters = recognizer.parameters
    length = parameters["sequence/sequence_length"]
    alignment = parameters["sequence/alignment"]
    frames = len(query_images)
    if frames < length:  # Else no query would be matched, and every figure would be NaN.
        raise ValueError("the query has %d images, fewer than the sequence length %d" % (frames, length))
    if ground_truth is None and recognizer.frames_left_out > 0:
        warnings.warn("without ground_truth, query frame i is taken to show map frame i, but the map left out %d "
                      "of the frames offered to it (keyframes by min_appearance_change): its frame i is not the "
                      "i-th image. Give ground_truth in map frames, or build the map with "
                      "min_appearance_change=0" % recognizer.frames_left_out, UserWarning, stacklevel=2)
    truths = _bindings.truths(_ground_truth_dict(ground_truth, frames, len(recognizer)), frames, len(recognizer))
    records = []
    if protocol == "per-frame":
        evaluated = _bindings.per_frame_queries(frames, length, alignment)
        start = time.perf_counter()
        matches = recognizer.match_every_frame(query_images, method, channel_order)
        per_query_ms = 1000.0 * (time.perf_counter() - start) / max(len(evaluated), 1)
        for query in evaluated:
            if truths[query] is not None:
                records.append(_bindings.query_record(query, truths[query], matches[query], per_query_ms))
    else:  # "global"
        # Every image first, as match_every_frame checks them: a window meets a bad one only if it covers it.
        recognizer._check_images(query_images, channel_order, "the traversal")
        repeated = _bindings.repeated_global_queries(frames, length, queries)
        if repeated:
            warnings.warn(repeated, UserWarning, stacklevel=2)
        for first, count, _ in _bindings.global_queries(frames, length, queries, seed, alignment):
            start = time.perf_counter()
            answer = recognizer.match(query_images[first:first + count], method, channel_order)
            elapsed_ms = 1000.0 * (time.perf_counter() - start)
            # match() keyframes the window, so the image it localises is not always the window's anchor
            # (a stop drops images): judge the answer at that image, and skip the window when it has no
            # truth, as mrs_vpr_eval does.
            query = first + answer.localised_row
            if truths[query] is None:
                continue
            records.append(_bindings.query_record(query, truths[query], answer.match, elapsed_ms))
    for record in records:
        record["correct"] = _bindings.is_correct(record, tolerance)
    return Evaluation(records, summarise(records, tolerance), precision_recall_curve(records, tolerance))
