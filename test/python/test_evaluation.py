"""Offline evaluation with the core's protocols and metrics."""

import numpy as np
import pytest

import mrs_vpr
import mrs_vpr.evaluation
from conftest import ROUTE_PARAMETERS


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
    assert set(record) == {"query_index", "true_indices", "predicted_index", "score", "confidence", "accepted",
                           "rival_places", "at_velocity_bound", "repeated_view", "time_ms"}
    summary = evaluation.summary
    assert summary["queries"] == 381
    assert summary["tolerance"] == 3
    assert summary["top1"] > 0.9
    assert summary["accepted_precision"] == 1.0
    assert np.isnan(summary["largest_wrong_accepted_error"])  # no accepted answer is wrong
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


def test_bad_evaluation_input_raises_value_error(route, short_sequences):
    with pytest.raises(ValueError) as error:
        mrs_vpr.evaluate(short_sequences, route["query"], protocol="sideways")
    assert str(error.value) == "protocol must be 'per-frame' or 'global', got 'sideways'"
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
