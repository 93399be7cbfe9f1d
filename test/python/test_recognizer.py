"""Mapping and localising with NumPy images: the core's answers, stamps and image layouts."""

import numpy as np
import pytest

import mrs_vpr
from conftest import ROUTE_PARAMETERS, truth_of

FIRST, COUNT = 100, 150  # A stretch of the second traversal long enough for one coarser MRS level.


def grey(images):
    """Grey versions of BGR frames (the mean of the channels)."""
    return np.mean(images, axis=-1).round().astype(np.uint8)


@pytest.mark.parametrize("method", ["", "mrs", "seqslam"])
def test_a_stretch_of_the_route_is_found_within_3_frames_and_accepted(route, mapped, method):
    assert len(mapped) == 600
    answer = mapped.match(route["query"][FIRST:FIRST + COUNT], method=method)
    assert abs(answer.reference_index - truth_of(route, FIRST, COUNT)) <= 3
    assert answer.accepted
    assert answer.confidence >= 3.0
    assert 0.0 <= answer.score <= 1.0
    assert answer.reference_stamp == pytest.approx(100.0 + answer.reference_index / 10.0)
    assert answer.query_length == COUNT
    assert answer.method == (method or "mrs")
    assert answer.match.reference_index == answer.reference_index
    assert answer.verdict == "accepted"


def test_an_answer_not_accepted_says_why_as_the_node_does(route):
    strict = mrs_vpr.PlaceRecognizer(**dict(ROUTE_PARAMETERS, accept_threshold=1000))
    strict.add_frames(route["reference"])
    answer = strict.match(route["query"][FIRST:FIRST + COUNT])
    assert not answer.accepted
    assert answer.verdict == "not accepted: confidence below sequence/accept_threshold"


def test_frames_added_one_by_one_give_the_same_map_as_a_batch(route, mapped):
    single = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
    for i, image in enumerate(route["reference"]):
        assert single.add_frame(image, stamp=100.0 + i / 10.0)
    test = list(route["query"][FIRST:FIRST + COUNT])  # a list of arrays as well as one array
    assert repr(single.match(test)) == repr(mapped.match(route["query"][FIRST:FIRST + COUNT]))


def test_match_recent_finds_the_newest_frames_among_the_older_ones(route):
    recognizer = mrs_vpr.PlaceRecognizer(recent_exclusion=50, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"])
    # The second traversal's frames 100..249 follow the first: they are the map's newest 150 frames.
    recognizer.add_frames(route["query"][100:250], stamps=[1000.0 + i for i in range(100, 250)])
    answer = recognizer.match_recent(150, method="seqslam")
    assert abs(answer.reference_index - truth_of(route, 100, 150)) <= 3
    assert answer.reference_index < 750 - 150 - 50  # only [0, 550) is searched
    assert answer.newest_stamp == 1249.0


def test_the_places_match_recent_links_are_saved_and_loaded_with_the_map(route, tmp_path):
    recognizer = mrs_vpr.PlaceRecognizer(recent_exclusion=50, **ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"])
    assert recognizer.linked_frames == 0
    accepted = 0
    last_accepted = None
    for i in range(100, 250):  # the second traversal, asked about after each frame as continuous mode asks
        recognizer.add_frame(route["query"][i], stamp=1000.0 + i)
        answer = recognizer.match_recent(20)
        accepted += answer.accepted
        last_accepted = answer if answer.accepted else last_accepted
    assert accepted >= 10
    assert recognizer.linked_frames == accepted  # each accepted answer linked a new keyframe
    recognizer.save(str(tmp_path / "linked.db"))
    loaded = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
    loaded.load(str(tmp_path / "linked.db"))
    assert loaded.linked_frames == accepted
    # A closure found wrong afterwards: its link goes, in the saved map too, and asking again is an error.
    assert loaded.reject_closure(last_accepted.localised_frame, last_accepted.reference_index) == 1
    assert loaded.linked_frames == accepted - 1
    with pytest.raises(ValueError, match="forgotten already"):
        loaded.reject_closure(last_accepted.localised_frame, last_accepted.reference_index)
    loaded.save(str(tmp_path / "rejected.db"))
    assert mrs_vpr.PlaceRecognizer.from_map(str(tmp_path / "rejected.db")).linked_frames == accepted - 1


def test_a_fixed_map_localises_the_trail_of_the_camera_and_stays_as_it_was(route, mapped):
    accepted = right = 0
    for i in range(100, 250):  # the second traversal, asked about after each keyframe as continuous mode asks
        if not mapped.add_to_trail(route["query"][i], stamp=1000.0 + i) or mapped.trail_size < 20:
            continue
        answer = mapped.match_trail(20)
        accepted += answer.accepted
        right += answer.accepted and abs(answer.reference_index - truth_of(route, i - 19, 20)) <= 3
    assert mapped.trail_size == 150  # every frame of the route's second traversal is a keyframe
    assert accepted >= 8  # 11: the route's 20-frame sequences stand out little (17 for match_recent)
    assert right == accepted
    assert len(mapped) == 600  # the map holds the first traversal only
    assert mapped.linked_frames == 0  # and links nothing
    with pytest.raises(ValueError, match="is more than the 150 keyframes the camera has given"):
        mapped.match_trail(200)


def test_match_recent_ending_at_an_older_frame_and_a_centred_answer_name_the_frame_localised(route):
    parameters = dict(ROUTE_PARAMETERS, alignment="centred")
    recognizer = mrs_vpr.PlaceRecognizer(recent_exclusion=50, **parameters)
    recognizer.add_frames(route["reference"])
    recognizer.add_frames(route["query"][100:250], stamps=[1000.0 + i for i in range(100, 250)])
    # Map frames 600..699 are the second traversal's 100..199; the middle of them, 150, is localised.
    answer = recognizer.match_recent(100, method="seqslam", end=700)
    assert answer.localised_row == 50
    assert answer.localised_stamp == 1150.0
    assert abs(answer.reference_index - route["query_to_reference"][150]) <= 3
    assert answer.reference_index < 700 - 100 - 50
    with pytest.raises(ValueError, match="the map holds 750 frames"):
        recognizer.match_recent(100, end=751)


def test_grey_uint8_and_uint16_images_localise_like_colour_ones(route):
    for scale, dtype in [(1, np.uint8), (257, np.uint16)]:
        recognizer = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
        recognizer.add_frames(grey(route["reference"]).astype(dtype) * dtype(scale))
        answer = recognizer.match(grey(route["query"][FIRST:FIRST + COUNT]).astype(dtype) * dtype(scale))
        assert abs(answer.reference_index - truth_of(route, FIRST, COUNT)) <= 3, dtype


def test_strided_and_padded_images_are_described_as_their_contiguous_copies(route, recognizer):
    frame = route["reference"][10]
    padded = np.zeros((frame.shape[0], frame.shape[1] + 7, 3), np.uint8)
    padded[:, :frame.shape[1]] = frame
    views = [
        padded[:, :frame.shape[1]],  # rows further apart than a row's pixels: read in place
        np.repeat(np.repeat(frame, 2, axis=0), 2, axis=1)[::2, ::2],  # every other pixel: copied
        frame[::-1],  # rows in reverse: copied
        np.asfortranarray(frame),  # column-major
        grey(route["reference"][10:11])[0][:, ::3],  # grey, every third column
    ]
    for view in views:
        assert not view.flags["C_CONTIGUOUS"]
        np.testing.assert_array_equal(recognizer.describe(view), recognizer.describe(np.ascontiguousarray(view)))


def test_rgb_images_with_their_channel_order(route, recognizer):
    bgr = route["reference"][10]
    rgb = bgr[..., ::-1]
    np.testing.assert_array_equal(recognizer.describe(rgb, channel_order="rgb"), recognizer.describe(bgr))
    assert not np.array_equal(recognizer.describe(rgb), recognizer.describe(bgr))


def test_big_endian_uint16_is_read_by_value(route, recognizer):
    image = grey(route["reference"][10:11])[0].astype(np.uint16) * np.uint16(257)
    np.testing.assert_array_equal(recognizer.describe(image.astype(">u2")), recognizer.describe(image))


def test_the_descriptor_is_a_row_of_bytes(route, recognizer):
    descriptor = recognizer.describe(route["reference"][0])
    assert descriptor.dtype == np.uint8
    assert descriptor.shape == (recognizer.descriptor_size,) == (64 * 32,)
    assert len(recognizer) == 0  # describing does not touch the map


def test_a_full_map_drops_frames_and_says_so(route):
    recognizer = mrs_vpr.PlaceRecognizer(max_frames=5, **ROUTE_PARAMETERS)
    assert recognizer.add_frames(route["reference"][:4]) == 4
    assert recognizer.add_frame(route["reference"][4])
    assert not recognizer.add_frame(route["reference"][5])
    assert recognizer.add_frames(route["reference"][:3]) == 0
    assert len(recognizer) == 5


def test_reset_empties_the_map(mapped):
    assert mapped.reset() == 600
    assert len(mapped) == 0


def test_the_answer_and_the_recognizer_print_what_they_hold(route, mapped):
    answer = mapped.match(route["query"][FIRST:FIRST + COUNT])
    assert repr(answer).startswith("Answer(reference_index=%d, confidence=" % answer.reference_index)
    assert repr(mapped) == "PlaceRecognizer(frames=600, front_end='thumbnail (64 x 32, patches of 8 px)', " \
                           "default_method='mrs')"
