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
#: correct: within the tolerance of a true frame, as mrs_vpr_eval's records; time_ms, as there, leaves
#: out describing the images); summary: a dict of the figures (top1, pr_auc, recall_at_100_precision,
#: accepted, accepted_precision, ...; None where a figure does not exist, as mrs_vpr_eval's null);
#: pr_curve: NumPy arrays threshold, precision and recall.
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


def _numbering_warning(recognizer):
    """Why query frame i may not show map frame i (the identity ground truth), or None."""
    if recognizer.frames_left_out > 0:
        return ("the map left out %d of the frames offered to it (keyframes by min_appearance_change): its frame "
                "i is not the i-th image" % recognizer.frames_left_out)
    frames = len(recognizer)
    if frames == 0:
        return None
    # A loaded map numbers its keyframes by the traversal they were kept from: gaps between its first and
    # last number are frames left out (numbers that merely start later, as a camera's counter, are not).
    first, last = recognizer.frame_number(0), recognizer.frame_number(frames - 1)
    if first >= 0 and last - first > frames - 1:
        return ("the map's %d frames are keyframes of %d frames of a traversal (frames %d to %d, by the numbers the "
                "map records)" % (frames, last - first + 1, first, last))
    return None


def _warn_of_too_few_rivals(matches, map_keyframes):
    """Warns, as mrs_vpr_eval says on stderr, of answers in a map too small for the acceptance rule."""
    note = _bindings.too_few_rivals_note(matches, map_keyframes)
    if note:
        warnings.warn(note, UserWarning, stacklevel=3)


def _check_one_size(query_images):
    """ValueError unless every query image has one size, as mrs_vpr_eval requires of a folder."""
    # What is no image at all is left to the describing, which names it.
    sizes = [(index, np.shape(image)[:2]) for index, image in enumerate(query_images) if np.ndim(image) >= 2]
    for index, size in sizes[1:]:
        if size != sizes[0][1]:
            raise ValueError("all query images must have one size (one camera): image %d is %d x %d, image %d is "
                             "%d x %d" % (sizes[0][0], sizes[0][1][1], sizes[0][1][0], index, size[1], size[0]))


def evaluate(recognizer, query_images, ground_truth=None, tolerance=_bindings.DEFAULT_TOLERANCE, protocol="per-frame",
             method="", queries=_bindings.DEFAULT_GLOBAL_QUERIES, seed=_bindings.DEFAULT_SEED, channel_order="bgr"):
    """Localises a query traversal in the recognizer's map and scores the answers, as mrs_vpr_eval does.

    The query is keyframed first, as the map's frames are (keyframes_of: every image when
    min_appearance_change is 0), and both protocols run on its keyframes. protocol "per-frame": every
    keyframe with a full sequence of sequence_length keyframes (OpenSeqSLAM's protocol); "global":
    `queries` test sequences of sequence_length keyframes at random positions drawn with `seed`. A
    record names the query image its answer localises; one without a truth is skipped. ground_truth:
    None (query image i shows map frame i), a dict {query image: [map frames]} or a sequence of one map
    frame per query image. Map frames are those the recognizer holds (its keyframes; build the map with
    min_appearance_change=0 to keep every frame). An answer is correct within `tolerance` frames of a
    true one. Returns an Evaluation (records, summary, pr_curve).

    Every argument is checked before any query is matched: a bad one raises ValueError naming it and
    what it may be (tolerance 0..2147483647, queries 1..100000 and seed 0..2**64-1, whole numbers; query
    images of one size, at least sequence_length of them keyframes). The defaults are mrs_vpr_eval's:
    tolerance 2, queries 200, seed 42.
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
    _check_one_size(query_images)
    if ground_truth is None:
        numbering = _numbering_warning(recognizer)
        if numbering:
            warnings.warn("without ground_truth, query image i is taken to show map frame i, but %s. Give "
                          "ground_truth in map frames, or build the map with min_appearance_change=0" % numbering,
                          UserWarning, stacklevel=2)
    truths = _bindings.truths(_ground_truth_dict(ground_truth, frames, len(recognizer)), frames, len(recognizer))
    # Describes every image (a bad one raises ValueError naming it) and keyframes them once.
    traversal = recognizer._keyframed_traversal(query_images, channel_order)
    keyframes = len(traversal)
    if keyframes < length:
        raise ValueError("the query's %d images hold %d keyframes, fewer than the sequence length %d: its view "
                         "hardly changes (a stop), or min_appearance_change (%g) is too high for these images; 0 "
                         "keeps every image" % (frames, keyframes, length,
                                                parameters["min_appearance_change"]))
    chosen = traversal.chosen
    records = []
    matched = []  # the Match of each record
    if protocol == "per-frame":
        evaluated = _bindings.per_frame_queries(keyframes, length, alignment)
        start = time.perf_counter()
        matches = recognizer._match_every_keyframe(traversal, method)
        per_query_ms = 1000.0 * (time.perf_counter() - start) / max(len(evaluated), 1)
        for keyframe in evaluated:
            query = chosen[keyframe]
            if truths[query] is not None:
                matched.append(matches[keyframe])
                records.append(_bindings.query_record(query, truths[query], matches[keyframe], per_query_ms))
    else:  # "global"
        repeated = _bindings.repeated_global_queries(keyframes, length, queries)
        if repeated:
            warnings.warn(repeated, UserWarning, stacklevel=2)
        for first, count, keyframe in _bindings.global_queries(keyframes, length, queries, seed, alignment):
            query = chosen[keyframe]
            if truths[query] is None:
                continue
            start = time.perf_counter()
            match = recognizer._match_keyframes(traversal, first, count, method)
            matched.append(match)
            records.append(_bindings.query_record(query, truths[query], match, 1000.0 * (time.perf_counter() - start)))
    _warn_of_too_few_rivals(matched, len(recognizer))
    for record in records:
        record["correct"] = _bindings.is_correct(record, tolerance)
    return Evaluation(records, summarise(records, tolerance), precision_recall_curve(records, tolerance))
