"""Bad input raises ValueError with the core's message, and the recognizer stays as it was."""

import numpy as np
import pytest

from conftest import truth_of


def message_of(call):
    with pytest.raises(ValueError) as error:
        call()
    return str(error.value)


# The image types the core takes, as its messages list them.
SUPPORTED_TYPES = "(supported: 8UC1, 16UC1, 8UC3, 16UC3, 8UC4, 16UC4)"


@pytest.mark.parametrize(
    "image, message",
    [
        (np.zeros((32, 64), np.float32), "unsupported image dtype float32 (supported: uint8 or uint16 grey, BGR or "
         "BGRA); scale an image of floats in 0..1 first: (image * 255).round().astype(np.uint8)"),
        (np.zeros((32, 64), np.int8), "unsupported image dtype int8 (supported: uint8 or uint16 grey, BGR or BGRA)"),
        (np.zeros((32, 64, 2), np.uint8), "unsupported image type CV_8UC2 " + SUPPORTED_TYPES),
        (np.zeros((32, 64), np.int64), "unsupported image dtype int64 (supported: uint8 or uint16 grey, BGR or BGRA)"),
        (np.zeros((32, 64), bool), "unsupported image dtype bool (supported: uint8 or uint16 grey, BGR or BGRA)"),
        (np.zeros((2, 32, 64, 3), np.uint8),
         "an image must be H x W (grey) or H x W x C (BGR, BGRA), got an array of 4 dimensions, shape (2, 32, 64, 3)"),
        (np.zeros(64, np.uint8),
         "an image must be H x W (grey) or H x W x C (BGR, BGRA), got an array of 1 dimensions, shape (64,)"),
        (np.zeros((0, 64), np.uint8), "image is empty: an array of shape (0, 64)"),
        (np.zeros((32, 0, 3), np.uint8), "image is empty: an array of shape (32, 0, 3)"),
        ([[1, 2], [3, 4]], "an image must be a NumPy array, got list"),
        (None, "an image must be a NumPy array, got NoneType"),
    ],
)
def test_a_bad_image_raises_value_error_and_adds_nothing(mapped, image, message):
    assert message_of(lambda: mapped.add_frame(image)) == message
    assert message_of(lambda: mapped.describe(image)) == message
    assert len(mapped) == 600


def test_a_bad_image_in_a_batch_adds_none_of_the_batch(route, mapped):
    images = list(route["query"][:5])
    images[3] = np.zeros((32, 64, 2), np.uint8)
    assert message_of(lambda: mapped.add_frames(images)) == (
        "image 3 of images: unsupported image type CV_8UC2 " + SUPPORTED_TYPES)
    assert len(mapped) == 600


def test_stamps_must_match_the_images(route, mapped):
    assert message_of(lambda: mapped.add_frames(route["query"][:5], stamps=[1.0, 2.0])) == (
        "stamps has 2 entries for 5 images")
    assert len(mapped) == 600


def test_a_bad_test_sequence_raises_value_error_naming_the_image(route, mapped):
    test = list(route["query"][:10])
    test[4] = np.zeros((1, 2, 3, 4), np.uint8)
    assert message_of(lambda: mapped.match(test)) == (
        "image 4 of the test sequence: an image must be H x W (grey) or H x W x C (BGR, BGRA), got an array of "
        "4 dimensions, shape (1, 2, 3, 4)")
    test[4] = np.zeros((32, 64), np.int8)
    assert message_of(lambda: mapped.match(test)) == (
        "image 4 of the test sequence: unsupported image dtype int8 (supported: uint8 or uint16 grey, BGR or BGRA)")


def test_one_image_is_not_a_test_sequence(route, mapped):
    assert message_of(lambda: mapped.match(route["query"][0])) == (
        "the test sequence must be a sequence of images (a list, or an N x H x W or N x H x W x C array), got one "
        "array of shape (64, 128, 3)")
    assert message_of(lambda: mapped.match("images")) == "the test sequence must be a sequence of images, got str"
    assert message_of(lambda: mapped.match(route["query"][:1])) == "a test sequence needs at least 2 images, got 1"
    assert message_of(lambda: mapped.match([])) == "a test sequence needs at least 2 images, got 0"


def test_an_unknown_method_raises_the_cores_message(route, mapped):
    assert message_of(lambda: mapped.match(route["query"][:20], method="fast")) == (
        "unknown method 'fast': use 'mrs' or 'seqslam'")
    assert message_of(lambda: mapped.match_recent(20, method="fast")) == "unknown method 'fast': use 'mrs' or 'seqslam'"


def test_an_unknown_channel_order_raises_value_error(route, mapped):
    assert message_of(lambda: mapped.add_frame(route["query"][0], channel_order="hsv")) == (
        "channel_order must be 'bgr' or 'rgb', got 'hsv'")


def test_queries_the_map_cannot_answer(route, recognizer, mapped):
    assert message_of(lambda: recognizer.match(route["query"][:20])) == "the reference map is empty: add frames first"
    assert message_of(lambda: mapped.match_recent(1)) == "recent_frames must be at least 2, got 1"
    assert message_of(lambda: mapped.match_recent(700)) == (
        "recent_frames 700 is more than the 600 frames in the reference map")


def test_the_recognizer_answers_as_before_after_every_error(route, mapped):
    for call in [lambda: mapped.add_frame(np.zeros((2, 2, 2, 2), np.uint8)),
                 lambda: mapped.match(route["query"][:20], method="fast"),
                 lambda: mapped.load("/nonexistent/map.db")]:
        with pytest.raises(ValueError):
            call()
    answer = mapped.match(route["query"][100:250])
    assert abs(answer.reference_index - truth_of(route, 100, 150)) <= 3
