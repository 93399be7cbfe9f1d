"""Stamps: float seconds in Python, whole nanoseconds in the core, converted to the nearest one."""

import math

import pytest

import mrs_vpr
from conftest import ROUTE_PARAMETERS


@pytest.fixture
def every_frame():
    # Each frame below must enter the map whatever its view, to read its stamp back.
    return mrs_vpr.PlaceRecognizer(min_appearance_change=0, **ROUTE_PARAMETERS)


@pytest.mark.parametrize("seconds", [0.0, 1e-9, 100.25, 1700000000.123456789, 4294967295.0])
def test_a_stamp_comes_back_as_the_float_it_was(route, every_frame, seconds):
    every_frame.add_frames(route["reference"][:20], stamps=[seconds] * 20)
    answer = every_frame.match(route["reference"][:20], method="seqslam")
    assert answer.reference_stamp == seconds


@pytest.mark.parametrize("seconds, message", [
    (-1.0, "stamp -1 s is outside"),
    (math.nan, "a stamp of NaN seconds is outside"),
    (5e9, "stamp 5000000000 s is outside"),
])
def test_a_stamp_out_of_range_raises_value_error_and_adds_nothing(route, every_frame, seconds, message):
    with pytest.raises(ValueError) as error:
        every_frame.add_frame(route["reference"][0], stamp=seconds)
    assert message in str(error.value)
    with pytest.raises(ValueError) as error:
        every_frame.add_frames(route["reference"][:3], stamps=[1.0, seconds, 2.0])
    assert str(error.value).startswith("stamp 1 of stamps: ")
    assert len(every_frame) == 0
