"""Keyframes: the Python API keeps a frame, and a test sequence's image, only once its view has changed
enough since the last keyframe (min_appearance_change), as the node does."""

import numpy as np
import pytest

import mrs_vpr
from conftest import ROUTE_PARAMETERS, truth_of

FIRST, COUNT = 100, 150


def repeated(images, times):
    """Every image `times` times in a row: a camera that stops at every place."""
    return np.repeat(images, times, axis=0)


def test_a_frame_too_similar_to_the_last_keyframe_is_not_kept(route, recognizer):
    assert recognizer.add_frame(route["reference"][0])
    assert not recognizer.add_frame(route["reference"][0])  # the same view again: no keyframe
    assert recognizer.add_frame(route["reference"][1])
    assert len(recognizer) == 2
    assert recognizer.add_frames(repeated(route["reference"][2:5], 3)) == 3


def test_zero_keeps_every_frame(route):
    recognizer = mrs_vpr.PlaceRecognizer(min_appearance_change=0, **ROUTE_PARAMETERS)
    assert recognizer.parameters["min_appearance_change"] == 0.0
    assert recognizer.add_frames(repeated(route["reference"][:4], 3)) == 12
    assert len(recognizer) == 12


def test_min_appearance_change_is_a_keyword_with_the_cores_range(route):
    assert mrs_vpr.PlaceRecognizer().parameters["min_appearance_change"] == 0.4
    with pytest.raises(ValueError) as error:
        mrs_vpr.PlaceRecognizer(min_appearance_change=1.5)
    assert "min_appearance_change" in str(error.value)


def test_a_test_sequence_is_keyframed_as_the_map(route, mapped):
    stretch = route["query"][FIRST:FIRST + COUNT]
    stopping = repeated(stretch, 3)
    assert mapped.keyframes_of(stopping) == list(range(0, 3 * COUNT, 3))  # the first view of every stop
    answer = mapped.match(stopping)
    assert answer.query_length == COUNT
    assert repr(answer) == repr(mapped.match(stretch))
    assert abs(answer.reference_index - truth_of(route, FIRST, COUNT)) <= 3


def test_a_test_sequence_with_one_keyframe_is_refused(route, mapped):
    with pytest.raises(ValueError) as error:
        mapped.match(repeated(route["query"][FIRST:FIRST + 1], 20))
    assert str(error.value) == ("the test sequence's 20 images hold fewer than 2 keyframes: the view hardly "
                                "changes across them (min_appearance_change 0.4)")


def test_keyframing_the_test_sequence_leaves_the_map_as_it_was(route, mapped):
    mapped.keyframes_of(route["query"][:50])
    mapped.match(route["query"][:50])
    assert len(mapped) == 600
    # The map's last keyframe is still the one the next frame is compared with.
    assert not mapped.add_frame(route["reference"][599])
