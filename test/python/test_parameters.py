"""Parameters by keyword: every entry of the core's tables, validated by the core."""

import pytest

import mrs_vpr


def test_every_parameter_of_the_reference_is_accepted_by_its_exact_name_at_its_default():
    reference = mrs_vpr.parameter_reference()
    names = [row["name"] for row in reference]
    assert "sequence/sequence_length" in names and "mrs/tau" in names and "max_frames" in names
    recognizer = mrs_vpr.PlaceRecognizer(**{row["name"]: row["default"] for row in reference})
    assert recognizer.parameters == {row["name"]: row["default"] for row in reference}


def test_every_parameter_has_a_keyword_that_is_a_python_identifier():
    for row in mrs_vpr.parameter_reference():
        assert any(keyword.isidentifier() for keyword in row["keywords"]), row


def test_exact_short_and_group_names_set_the_same_parameter():
    by_exact = mrs_vpr.PlaceRecognizer(**{"sequence/sequence_length": 30, "mrs/tau": 2.5, "descriptor/type": "thumbnail"})
    by_short = mrs_vpr.PlaceRecognizer(sequence_length=30, tau=2.5, type="thumbnail")
    by_group = mrs_vpr.PlaceRecognizer(sequence_length=30, mrs_tau=2.5, descriptor_type="thumbnail")
    assert by_exact.parameters == by_short.parameters == by_group.parameters
    assert by_exact.parameters["sequence/sequence_length"] == 30
    assert by_exact.parameters["mrs/tau"] == 2.5
    assert by_exact.parameters["descriptor/type"] == "thumbnail"
    assert by_exact.descriptor_size == 64 * 32


def test_nested_names_join_their_groups():
    recognizer = mrs_vpr.PlaceRecognizer(hog_cell_size=8, alignment="centred", default_method="seqslam", seed=2**63)
    assert recognizer.parameters["descriptor/hog/cell_size"] == 8
    assert recognizer.parameters["sequence/alignment"] == "centred"
    assert recognizer.parameters["default_method"] == "seqslam"
    assert recognizer.parameters["mrs/seed"] == 2**63


def test_numpy_numbers_are_numbers():
    np = pytest.importorskip("numpy")
    recognizer = mrs_vpr.PlaceRecognizer(sequence_length=np.int64(20), tau=np.float32(3.0))
    assert recognizer.parameters["sequence/sequence_length"] == 20
    assert recognizer.parameters["mrs/tau"] == 3.0


@pytest.mark.parametrize(
    "parameters, message",
    [
        ({"sequence_length": 1}, "sequence/sequence_length must be in 2..10000, got 1"),
        ({"tau": 0.5}, "mrs/tau must be in 1..16, got 0.5"),
        ({"descriptor_type": "sift"}, "descriptor/type must be one of hog, thumbnail, got 'sift'"),
        ({"alignment": "sideways"}, "sequence/alignment must be one of causal, centred, got 'sideways'"),
        ({"default_method": "fast"}, "default_method must be one of mrs, seqslam, got 'fast'"),
        ({"seed": -1}, "mrs/seed must be >= 0, got -1"),
        ({"velocity_min": 1.5, "velocity_max": 1.2},
         "sequence/velocity_min 1.5 is above sequence/velocity_max 1.2"),
        ({"descriptor_type": "thumbnail", "patch_size": 5}, "descriptor/patch_size must be in 2..1024"),
    ],
)
def test_a_value_out_of_range_raises_the_cores_message(parameters, message):
    with pytest.raises(ValueError) as error:
        mrs_vpr.PlaceRecognizer(**parameters)
    assert str(error.value).startswith(message)


@pytest.mark.parametrize(
    "parameters, message",
    [
        ({"sequence_length": 2.5}, "sequence/sequence_length must be in 2..10000, got 2.5 (not an integer)"),
        ({"sequence_length": True}, "sequence/sequence_length must be in 2..10000, got True (not an integer)"),
        ({"tau": "2"}, "mrs/tau must be in 1..16, got '2' (not a number)"),
        ({"descriptor_type": 1}, "descriptor/type must be one of hog, thumbnail, got 1 (not a string)"),
        ({"levels": 10**30}, "mrs/levels must be in 0..8, got 1000000000000000000000000000000"),
        ({"max_frames": 10**12}, "max_frames must be 0 (unbounded) or >= 2, got 1000000000000 (beyond 2147483647)"),
        ({"seed": 2**64}, "mrs/seed must be >= 0, got 18446744073709551616 (beyond 18446744073709551615)"),
    ],
)
def test_a_value_of_the_wrong_type_or_size_raises_value_error_naming_the_parameter(parameters, message):
    with pytest.raises(ValueError) as error:
        mrs_vpr.PlaceRecognizer(**parameters)
    assert str(error.value) == message


def test_an_unknown_parameter_raises_value_error_with_a_suggestion():
    with pytest.raises(ValueError) as error:
        mrs_vpr.PlaceRecognizer(sequence_lenght=30)
    assert str(error.value).startswith("unknown parameter 'sequence_lenght' (did you mean 'sequence_length'?)")


def test_a_parameter_of_the_other_front_end_is_refused_unless_at_its_default():
    for parameters, message in (({"hog_bins": 12, "descriptor_type": "thumbnail"},
                                 "'hog_bins' is a parameter of the hog front end, and the front end is thumbnail "
                                 "(add descriptor_type='hog')"),
                                ({"image_width": 100},
                                 "'image_width' is a parameter of the thumbnail front end, and the front end is hog "
                                 "(add descriptor_type='thumbnail')")):
        with pytest.raises(ValueError) as error:
            mrs_vpr.PlaceRecognizer(**parameters)
        assert str(error.value) == message
    # At its default it changes nothing: a recognizer's settings copy into another.
    thumbnail = mrs_vpr.PlaceRecognizer(descriptor_type="thumbnail", image_width=128, image_height=64)
    assert mrs_vpr.PlaceRecognizer(**thumbnail.parameters).parameters == thumbnail.parameters
    assert mrs_vpr.PlaceRecognizer(hog_bins=12).parameters["descriptor/hog/bins"] == 12


def test_a_parameter_given_twice_raises_value_error():
    with pytest.raises(ValueError) as error:
        mrs_vpr.PlaceRecognizer(**{"tau": 2.0, "mrs/tau": 3.0})
    assert str(error.value) == "mrs/tau is given twice, as 'tau' and 'mrs/tau'"


def test_the_reference_describes_each_parameter():
    row = next(row for row in mrs_vpr.parameter_reference() if row["name"] == "mrs/tau")
    assert row["type"] == "float"
    assert row["default"] == 2.0
    assert row["allowed"] == "1..16"
    assert row["keywords"] == ["mrs/tau", "tau", "mrs_tau"]
    assert "Particle overlap" in row["meaning"]
    assert row["front_end"] is None
    fronts = {row["name"]: row["front_end"] for row in mrs_vpr.parameter_reference()}
    assert fronts["descriptor/hog/bins"] == "hog" and fronts["descriptor/patch_size"] == "thumbnail"
    assert fronts["descriptor/type"] is None
