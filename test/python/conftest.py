"""Fixtures of the Python API's tests: the core's generated route, as NumPy arrays.

The route's frames are textures made for OpenSeqSLAM's thumbnail, and its neighbouring frames do not
look alike, so long test sequences search a finer velocity step (as the core's tests do).
"""

import pytest

import mrs_vpr

#: The parameters the route is searched with, as keywords.
# The route's tests check the answer at the newest frame of a test sequence (alignment causal).
ROUTE_PARAMETERS = {"descriptor_type": "thumbnail", "velocity_step": 0.02, "alignment": "causal"}


@pytest.fixture(scope="session")
def route():
    """600 map frames and 400 query frames of one generated route, BGR uint8, with the alignment."""
    return mrs_vpr.synthetic_route(reference_frames=600, query_frames=400)


@pytest.fixture
def recognizer():
    """A recognizer with an empty map."""
    return mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)


@pytest.fixture
def mapped(route):
    """A recognizer whose map is the route's first traversal, stamped 100 + frame / 10 seconds. Its
    neighbouring frames do not look alike: at the default min_appearance_change each is a keyframe."""
    recognizer = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
    stamps = [100.0 + i / 10.0 for i in range(len(route["reference"]))]
    assert recognizer.add_frames(route["reference"], stamps) == len(route["reference"])
    return recognizer


def truth_of(route, first, count):
    """The map frame that shows the place of the newest frame of query frames [first, first + count)."""
    return int(route["query_to_reference"][first + count - 1])
