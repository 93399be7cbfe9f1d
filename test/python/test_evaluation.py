"""Offline evaluation with the core's protocols and metrics."""

import inspect
import pathlib
import warnings

import numpy as np
import pytest

import mrs_vpr
import mrs_vpr.evaluation
from conftest import ROUTE_PARAMETERS


class MatchesNothing(mrs_vpr.PlaceRecognizer):
    """Fails the test when evaluate() matches a query: a bad argument must be refused before that."""

    def match(self, *args, **kwargs):
        raise AssertionError("evaluate() matched a query before it checked its arguments")

    match_every_frame = _match_every_keyframe = _match_keyframes = match


@pytest.fixture
def short_sequences(route):
    recognizer = mrs_vpr.PlaceRecognizer(sequence_length=20, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"])
    return recognizer


def test_per_frame_records_every_query_frame_with_a_full_sequence(route, short_sequences):
    evaluation = mrs_vpr.evaluate(short_sequences, route["query"], ground_truth=route["query_to_reference"],
                                  tolerance=3)
    queries = [record["query_index"] for record in evaluation.records]
    assert queries == list(range(19, 400))  # causal: the sequence ends at the frame localised
    record = evaluation.records[0]
    assert record["true_indices"] == [int(route["query_to_reference"][19])]
    assert set(record) == {"query_index", "true_index", "true_indices", "predicted_index", "predicted_last",
                           "score", "confidence", "accepted", "rival_places", "at_velocity_bound", "repeated_view",
                           "time_ms", "correct"}
    assert record["true_index"] == record["true_indices"][0]
    assert record["predicted_last"] == record["predicted_index"]  # A map frame stands for itself here.
    # As mrs_vpr_eval counts them: the summary's top-1 is the share of correct records.
    correct = [r["correct"] for r in evaluation.records]
    assert correct == [r["predicted_index"] >= 0 and min(abs(r["predicted_index"] - t) for t in r["true_indices"]) <= 3
                       for r in evaluation.records]
    assert evaluation.summary["top1"] == pytest.approx(sum(correct) / len(correct))
    summary = evaluation.summary
    assert summary["queries"] == 381
    assert summary["tolerance"] == 3
    assert summary["top1"] > 0.9
    assert summary["accepted_precision"] == 1.0
    assert summary["largest_wrong_accepted_error"] is None  # no accepted answer is wrong: null, as in mrs_vpr_eval
    curve = evaluation.pr_curve
    assert len(curve["threshold"]) == len(curve["precision"]) == len(curve["recall"]) > 0
    assert np.all(np.diff(curve["recall"]) >= 0)


def test_the_records_answer_as_match_every_frame_does(route, short_sequences):
    matches = short_sequences.match_every_frame(route["query"])
    assert len(matches) == 400
    assert matches[10].reference_index == -1  # no full sequence yet
    evaluation = mrs_vpr.evaluate(short_sequences, route["query"], ground_truth=route["query_to_reference"])
    for record in evaluation.records:
        assert record["predicted_index"] == matches[record["query_index"]].reference_index
        assert record["accepted"] == matches[record["query_index"]].accepted


def test_ground_truth_as_a_dict_evaluates_only_its_frames(route, short_sequences):
    truth = {100: [int(route["query_to_reference"][100])], 200: []}
    evaluation = mrs_vpr.evaluate(short_sequences, route["query"], ground_truth=truth)
    assert [record["query_index"] for record in evaluation.records] == [100, 200]
    assert evaluation.records[1]["true_indices"] == []


def test_the_defaults_are_mrs_vpr_evals():
    # One place for them (the core's evaluation library); before, Python drew 100 sequences with seed 0
    # and mrs_vpr_eval 200 with seed 42. The default seed is the recognizer's mrs/seed.
    defaults = {name: parameter.default for name, parameter in inspect.signature(mrs_vpr.evaluate).parameters.items()}
    mrs_seed = next(entry["default"] for entry in mrs_vpr.parameter_reference() if entry["name"] == "mrs/seed")
    assert (defaults["tolerance"], defaults["queries"], defaults["seed"]) == (2, 200, mrs_seed) == (2, 200, 42)


def test_the_global_protocol_draws_the_same_sequences_for_the_same_seed(route, short_sequences):
    first = mrs_vpr.evaluate(short_sequences, route["query"], ground_truth=route["query_to_reference"],
                             protocol="global", queries=15, seed=3, method="seqslam")
    again = mrs_vpr.evaluate(short_sequences, route["query"], ground_truth=route["query_to_reference"],
                             protocol="global", queries=15, seed=3, method="seqslam")
    indices = [record["query_index"] for record in first.records]
    assert len(indices) == 15
    assert indices == [record["query_index"] for record in again.records]
    assert [r["predicted_index"] for r in first.records] == [r["predicted_index"] for r in again.records]
    assert first.summary["top1"] > 0.8
    # More test sequences than the query has positions for (6 of 20 frames in 25): said, as repeats count.
    with pytest.warns(UserWarning, match="10 test sequences, but the query has 6 positions for one"):
        more = mrs_vpr.evaluate(short_sequences, route["query"][:25], protocol="global", queries=10, seed=3,
                                method="seqslam")
    assert len(more.records) <= 10


def test_bad_evaluation_input_raises_value_error(route, short_sequences):
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, route["query"], protocol="sideways")
    assert str(error.value) == "protocol must be 'per-frame' or 'global', got 'sideways'"
    for protocol in ("per-frame", "global"):  # Not 0 queries and NaN figures, as mrs_vpr_eval refuses it.
        with pytest.raises(ValueError) as error:
            mrs_vpr.evaluate(MatchesNothing(sequence_length=20, **ROUTE_PARAMETERS), route["query"][:19],
                             protocol=protocol)
        assert str(error.value) == "the query has 19 images, fewer than the sequence length 20"
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, route["query"], ground_truth={5000: [1]})
    assert "5000" in str(error.value)
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, route["query"], ground_truth={5: ["one"]})
    assert str(error.value) == (
        "ground truth maps a query frame to a list of map frames, all integers; got 5: ['one']")
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluation.summarise([{"query_index": "one"}], 2)
    assert str(error.value) == "a query record holds a value of the wrong type: {'query_index': 'one'}"
    record = {"query_index": 0, "true_indices": [0], "predicted_index": 0, "score": 0.5, "accepted": True,
              "at_velocity_bound": False, "time_ms": 1.0}
    with pytest.raises(ValueError) as error:  # Before, the curve grew until memory ran out.
        mrs_vpr.evaluation.summarise([dict(record, confidence=float("nan")), dict(record, confidence=1.0)], 2)
    assert str(error.value) == "the record of query 0 has a confidence that is not a number"
    with pytest.raises(ValueError) as error:
        mrs_vpr._bindings.per_frame_queries(100, 0, "causal")
    assert "sequence/sequence_length must be in 2..10000, got 0" in str(error.value)


@pytest.mark.parametrize(
    "keywords, message",
    [
        # Before, every query was matched and summarise() then raised a TypeError dumping every record.
        ({"tolerance": 2.5}, "tolerance must be in 0..2147483647, got 2.5 (not an integer)"),
        ({"tolerance": float("nan")}, "tolerance must be in 0..2147483647, got nan (not an integer)"),
        ({"tolerance": "2"}, "tolerance must be in 0..2147483647, got '2' (not an integer)"),
        ({"tolerance": True}, "tolerance must be in 0..2147483647, got True (not an integer)"),
        ({"tolerance": -1}, "tolerance must be in 0..2147483647, got -1"),
        ({"tolerance": 2**31}, "tolerance must be in 0..2147483647, got 2147483648"),
        # As mrs_vpr_eval's --seed and --queries; before, a TypeError of global_queries().
        ({"protocol": "global", "seed": -1}, "seed must be in 0..18446744073709551615, got -1"),
        ({"protocol": "global", "seed": 2**64}, "seed must be in 0..18446744073709551615, got 18446744073709551616"),
        ({"protocol": "global", "seed": 1.0}, "seed must be in 0..18446744073709551615, got 1.0 (not an integer)"),
        ({"protocol": "global", "queries": 10**12}, "queries must be in 1..100000, got 1000000000000"),
        ({"protocol": "global", "queries": 0}, "queries must be in 1..100000, got 0"),
        ({"queries": "10"}, "queries must be in 1..100000, got '10' (not an integer)"),
        ({"protocol": None}, "protocol must be 'per-frame' or 'global', got None"),
        ({"method": "fast"}, "method must be 'mrs', 'seqslam' or '' (the recognizer's default_method), got 'fast'"),
        ({"protocol": "global", "method": 5},
         "method must be 'mrs', 'seqslam' or '' (the recognizer's default_method), got 5"),
        ({"channel_order": "hsv"}, "channel_order must be 'bgr' or 'rgb', got 'hsv'"),
        ({"protocol": "global", "channel_order": None}, "channel_order must be 'bgr' or 'rgb', got None"),
    ],
)
def test_a_bad_argument_is_refused_before_any_query_is_matched(route, keywords, message):
    recognizer = MatchesNothing(sequence_length=20, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"][:100])
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(recognizer, route["query"][:100], **keywords)
    assert str(error.value) == message


@pytest.mark.parametrize(
    "ground_truth, message",
    [
        # Before, TypeError: '>=' not supported between instances of 'list' and 'int'.
        ([[i] for i in range(100)],
         "a ground truth sequence holds one map frame per query frame, an integer (< 0: none); got [0] for query "
         "frame 0"),
        ([None] * 100,
         "a ground truth sequence holds one map frame per query frame, an integer (< 0: none); got None for query "
         "frame 0"),
        ([0, 1, 2.5, 3],  # Before, int() truncated it to map frame 2.
         "a ground truth sequence holds one map frame per query frame, an integer (< 0: none); got 2.5 for query "
         "frame 2"),
        (np.arange(100.0),
         "a ground truth sequence holds one map frame per query frame, an integer (< 0: none); got 0.0 for query "
         "frame 0"),
        ([0, 1, 2**40], "ground truth row of query frame 2 lists reference frame 1099511627776, but the reference has "
                        "100 frames"),
        (np.zeros((100, 2), int),
         "ground_truth as an array must have one dimension (one map frame per query frame), got shape (100, 2)"),
        ("0123", "ground_truth must be None, a dict {query frame: [map frames]} or a sequence of one map frame per "
                 "query frame, got str"),
        ({1, 2}, "ground_truth must be None, a dict {query frame: [map frames]} or a sequence of one map frame per "
                 "query frame, got set"),
        ({5: 3}, "ground truth maps a query frame to a list of map frames, all integers; got 5: 3"),
        # Before, the query frames it missed were dropped without a word.
        (list(range(40)), "a ground truth sequence holds one map frame per query frame: 40 for 100 query frames"),
        ([0] * 101, "a ground truth sequence holds one map frame per query frame: 101 for 100 query frames"),
    ],
)
def test_ground_truth_of_another_shape_is_refused_naming_the_entry(route, ground_truth, message):
    recognizer = MatchesNothing(sequence_length=20, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"][:100])
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(recognizer, route["query"][:100], ground_truth=ground_truth)
    assert str(error.value) == message


def test_a_recognizer_and_images_are_checked_first(route, short_sequences):
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(None, route["query"])
    assert str(error.value) == "recognizer must be a mrs_vpr.PlaceRecognizer, got NoneType"
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, 5, protocol="global")
    assert str(error.value) == (
        "query_images must be a sequence of images (a list, or an N x H x W or N x H x W x C array), got int")


@pytest.mark.parametrize("protocol", ["per-frame", "global"])
def test_every_image_is_checked_before_any_query_is_matched(route, protocol):
    # Before, the global protocol met a bad image only in a window that covered it, after matching others.
    # The per-frame protocol's match_every_frame checks them itself, before it matches.
    recognizer = (MatchesNothing if protocol == "global" else mrs_vpr.PlaceRecognizer)(sequence_length=20,
                                                                                        **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"][:100])
    images = list(route["query"][:100])
    images[99] = None
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(recognizer, images, protocol=protocol, queries=5)
    assert str(error.value).startswith("image 99 of the traversal: ")
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(recognizer, route["query"][0], protocol=protocol)  # One image, not a sequence.
    assert str(error.value).startswith("the traversal must be a sequence of images")
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(recognizer, dict(enumerate(route["query"][:100])), protocol=protocol)
    assert str(error.value) == "the traversal must be a sequence of images, got dict"


def test_without_ground_truth_a_map_that_left_frames_out_is_warned_about(route):
    # Query frame i is then taken to show map frame i, which is no longer the i-th image offered (on
    # Nordland at sequence_length 10: top-1 0.024, against 0.863 with every frame kept).
    recognizer = mrs_vpr.PlaceRecognizer(sequence_length=20, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"][:100])
    assert recognizer.add_frame(route["reference"][99]) is False  # The same view again: left out.
    assert recognizer.frames_left_out >= 1
    with pytest.warns(UserWarning, match="query image i is taken to show map frame i"):
        mrs_vpr.evaluate(recognizer, route["query"][:100])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # 100 map frames are too few for the acceptance rule, which it says
        warnings.filterwarnings("error", message="without ground_truth")
        truth = [min(i, len(recognizer) - 1) for i in range(100)]
        mrs_vpr.evaluate(recognizer, route["query"][:100], ground_truth=truth)
    recognizer.reset()
    assert recognizer.frames_left_out == 0


def test_arguments_at_the_ends_of_their_ranges_evaluate(route, short_sequences):
    truth = [int(frame) for frame in route["query_to_reference"]]
    truth[:200] = [-1] * 200  # < 0: a query frame outside the map
    evaluation = mrs_vpr.evaluate(short_sequences, route["query"], ground_truth=np.array(truth, np.int16),
                                  tolerance=np.int64(0), protocol="global", queries=np.int32(3), seed=2**64 - 1)
    assert len(evaluation.records) == 3
    assert evaluation.summary["tolerance"] == 0
    for record in evaluation.records:
        assert record["true_indices"] == ([] if record["query_index"] < 200 else [truth[record["query_index"]]])


def _with_a_stop(route, held):
    """The query with image 150 held for `held` images with pixel noise (a stop), and its ground truth."""
    stop = 150
    noise = np.random.default_rng(0).integers(-2, 3, (held,) + route["query"].shape[1:])
    still = np.clip(route["query"][stop].astype(np.int16) + noise, 0, 255).astype(np.uint8)
    images = np.concatenate([route["query"][:stop], still, route["query"][stop + 1:]])
    truth = [int(frame) for frame in route["query_to_reference"]]
    return images, truth[:stop] + [truth[stop]] * held + truth[stop + 1:]


@pytest.mark.parametrize("protocol", ["per-frame", "global"])
def test_both_protocols_run_on_the_querys_keyframes_as_mrs_vpr_eval_does(route, protocol):
    # A stop of 60 images, longer than a sequence: the query's keyframes hold one of them, so no test
    # sequence is mostly one view, and a window inside the stop is not a query (it was: "fewer than 2
    # keyframes" ended the whole global evaluation).
    images, truth = _with_a_stop(route, held=60)
    recognizer = mrs_vpr.PlaceRecognizer(sequence_length=20, **dict(ROUTE_PARAMETERS, alignment="centred"))
    recognizer.add_frames(route["reference"])
    chosen = recognizer.keyframes_of(images)
    assert len([i for i in chosen if 150 <= i < 210]) <= 2  # The stop keeps its first image, at most one more.
    evaluation = mrs_vpr.evaluate(recognizer, images, ground_truth=truth, protocol=protocol, queries=300)
    localised = [record["query_index"] for record in evaluation.records]
    assert set(localised) <= set(chosen)
    if protocol == "per-frame":  # Each keyframe with a full sequence of keyframes, answered as its own keyframes.
        keyframes = images[chosen]
        assert localised == sorted(localised) and len(localised) == len(chosen) - 19
        matches = recognizer.match_every_frame(keyframes)
        for record in evaluation.records:
            assert record["predicted_index"] == matches[chosen.index(record["query_index"])].reference_index
    assert evaluation.summary["top1"] > 0.9
    assert evaluation.summary["accepted_precision"] == 1.0

def test_query_images_of_other_sizes_are_refused(route, short_sequences):
    images = list(route["query"][:100])
    images[40] = images[40][:, :-8]  # another camera, or a cropped file among the others
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, images)
    height, width = route["query"].shape[1:3]
    assert str(error.value) == ("all query images must have one size (one camera): image 0 is %d x %d, image 40 is "
                                "%d x %d" % (width, height, width - 8, height))


def test_a_query_that_hardly_changes_names_its_keyframes(route, short_sequences):
    images, _ = _with_a_stop(route, held=60)
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, images[150:210])
    assert str(error.value).startswith("the query's 60 images hold 1 keyframes, fewer than the sequence length 20: "
                                       "its view hardly changes (a stop)")


def test_without_ground_truth_a_loaded_map_of_keyframes_is_warned_about(route, tmp_path):
    # Its frames keep the numbers of the frames they were kept from: map frame i is not query image i.
    images, _ = _with_a_stop(route, held=30)
    recognizer = mrs_vpr.PlaceRecognizer(sequence_length=20, **ROUTE_PARAMETERS)
    recognizer.add_frames(images)
    assert recognizer.frames_left_out > 0
    recognizer.save(str(tmp_path / "map.db"))
    loaded = mrs_vpr.PlaceRecognizer.from_map(str(tmp_path / "map.db"), sequence_length=20, **ROUTE_PARAMETERS)
    assert loaded.frames_left_out == 0
    with pytest.warns(UserWarning, match=r"the map.s %d frames are keyframes of \d+ frames of a traversal"
                      % len(loaded)):
        mrs_vpr.evaluate(loaded, route["query"][:100])


def test_image_files_are_listed_in_the_tools_order(tmp_path):
    for name in ("10.png", "2.png", "1.png", "notes.txt", "0.jpg"):
        (tmp_path / name).write_bytes(b"")
    assert [pathlib.Path(path).name for path in mrs_vpr.image_files(str(tmp_path))] == ["0.jpg", "1.png", "2.png",
                                                                                         "10.png"]
    with pytest.raises(RuntimeError) as error:
        mrs_vpr.image_files(str(tmp_path / "missing"))
    assert "does not exist" in str(error.value)


def test_image_files_say_where_digits_after_a_point_read_as_a_fraction(tmp_path):
    # As the tools print it: an id digit, a point and an unpadded counter are not read as counters.
    for name in ("cam1.9.png", "cam1.10.png"):
        (tmp_path / name).write_bytes(b"")
    with pytest.warns(UserWarning, match=r"read 'cam1.10.png' before 'cam1.9.png', the digits after a point as a "
                      r"decimal fraction"):
        names = [pathlib.Path(path).name for path in mrs_vpr.image_files(str(tmp_path))]
    assert names == ["cam1.10.png", "cam1.9.png"]
    agreeing = tmp_path / "agreeing"  # both readings order these alike: nothing to say
    agreeing.mkdir()
    for name in ("1.5.png", "2.25.png"):
        (agreeing / name).write_bytes(b"")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert [pathlib.Path(path).name for path in mrs_vpr.image_files(str(agreeing))] == ["1.5.png", "2.25.png"]


def test_a_map_too_small_for_the_acceptance_rule_is_named(route):
    # As mrs_vpr_eval says on stderr: confidences of 0 and no PR curve, not a method that fails.
    recognizer = mrs_vpr.PlaceRecognizer(sequence_length=20, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"][:60])
    with pytest.warns(UserWarning, match="answers found fewer than 100 trajectory ends outside their window in the "
                                         "map of 60 keyframes.*every confidence is equal, so there is no PR curve"):
        evaluation = mrs_vpr.evaluate(recognizer, route["query"][:80])
    assert evaluation.summary["accepted"] == 0
    assert evaluation.summary["pr_auc"] is None
