"""Saving and loading the SQLite map database."""

import sqlite3

import pytest

import mrs_vpr
from conftest import ROUTE_PARAMETERS

STRETCH = slice(100, 250)


def test_a_saved_map_loads_with_the_same_frames_stamps_and_answers(route, mapped, tmp_path):
    path = tmp_path / "map.db"
    assert mapped.save(path) == 600
    loaded = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
    assert loaded.load(str(path)) == 600
    assert len(loaded) == 600
    assert repr(loaded.match(route["query"][STRETCH])) == repr(mapped.match(route["query"][STRETCH]))


def test_from_map_takes_the_front_end_the_map_was_written_with(route, mapped, tmp_path):
    path = tmp_path / "map.db"
    mapped.save(path)
    loaded = mrs_vpr.PlaceRecognizer.from_map(path, velocity_step=0.02, alignment="causal")
    assert loaded.parameters["descriptor/type"] == "thumbnail"  # not the default front end, hog
    assert len(loaded) == 600
    assert repr(loaded.match(route["query"][STRETCH])) == repr(mapped.match(route["query"][STRETCH]))


def test_a_map_of_another_front_end_is_refused_and_the_map_kept(route, mapped, tmp_path):
    path = tmp_path / "map.db"
    mapped.save(path)
    hog = mrs_vpr.PlaceRecognizer(min_appearance_change=0)
    hog.add_frames(route["reference"][:5])
    with pytest.raises(mrs_vpr.MapDatabaseError) as error:
        hog.load(path)
    assert "thumbnail" in str(error.value) and "hog" in str(error.value)
    assert len(hog) == 5  # The frames it had, not an emptied map.


def test_match_recent_never_joins_a_loaded_map_to_the_frames_added_since(route, mapped, tmp_path):
    path = tmp_path / "map.db"
    mapped.save(path)
    loaded = mrs_vpr.PlaceRecognizer.from_map(path)
    assert loaded.drive_starts == [600]  # the frames offered next are another drive's
    assert loaded.match_recent(10).reference_index >= 0  # the map's own last drive
    assert loaded.add_frames(route["reference"][:6]) == 6
    with pytest.raises(ValueError) as refused:
        loaded.match_recent(10)
    assert str(refused.value) == (
        "a test sequence of map frames [596, 606) runs across the start of a drive at frame 600 (a map was loaded, "
        "as by a node started on its database or ~load_map, or a visit appended, before it): the junction of two "
        "drives is no place; ask about at most 6 frames, or about 10 once the drive holds that many")
    assert loaded.match_recent(10, end=600).reference_index >= 0  # before the junction
    assert loaded.match_recent(6).reference_index >= 0
    loaded.add_frames(route["reference"][6:10])
    assert 0 <= loaded.match_recent(10).reference_index < 10  # the map's first frames, seen again
    loaded.save(tmp_path / "two_drives.db")
    assert mrs_vpr.PlaceRecognizer.from_map(tmp_path / "two_drives.db").drive_starts == [600, 610]
    loaded.reset()
    assert loaded.drive_starts == []


def test_a_map_is_never_overwritten(mapped, tmp_path):
    path = tmp_path / "map.db"
    path.write_text("a user's file")
    with pytest.raises(ValueError) as error:
        mapped.save(path)
    assert str(path) in str(error.value)
    assert path.read_text() == "a user's file"


@pytest.mark.parametrize("name", ["missing/folder/map.db", ""])
def test_a_bad_save_path_raises_value_error(mapped, tmp_path, name):
    with pytest.raises(ValueError):
        mapped.save(tmp_path / name if name else name)


def test_a_bad_map_raises_value_error_and_keeps_the_map(route, mapped, tmp_path):
    not_a_map = tmp_path / "notes.db"
    not_a_map.write_text("not SQLite")
    for path in [tmp_path / "missing.db", not_a_map]:
        with pytest.raises(ValueError) as error:
            mapped.load(path)
        assert str(path) in str(error.value)
        assert len(mapped) == 600
    with pytest.raises(mrs_vpr.MapDatabaseError):
        mrs_vpr.PlaceRecognizer.from_map(tmp_path / "missing.db")


def test_a_save_target_is_checked_in_the_words_save_would_use(mapped, tmp_path):
    (tmp_path / "taken.db").write_text("")
    for path, problem in ((tmp_path / "taken.db", "the file exists"),
                          (tmp_path / "no" / "map.db", "there is no folder"), (tmp_path, "it is a folder")):
        with pytest.raises(mrs_vpr.MapDatabaseError) as checked:
            mrs_vpr.PlaceRecognizer.check_save_target(path)
        assert problem in str(checked.value)
        with pytest.raises(mrs_vpr.MapDatabaseError) as saved:
            mapped.save(path)
        assert str(saved.value) == str(checked.value)
    mrs_vpr.PlaceRecognizer.check_save_target(tmp_path / "new.db")  # A new file in a folder: no error.
    assert not (tmp_path / "new.db").exists()


def test_a_saved_map_keeps_each_frames_place_among_the_frames_offered(route, tmp_path):
    # As build_map numbers a traversal's frames: mrs_vpr_eval's ground truth names the frames offered,
    # not the keyframes a map kept of them.
    recognizer = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
    recognizer.add_frames(route["reference"][:50])
    assert recognizer.add_frame(route["reference"][49]) is False  # Offered as frame 50, and left out.
    assert recognizer.add_frame(route["reference"][51]) is True
    assert recognizer.add_frame(route["reference"][51]) is False  # Frame 52, the last offered, left out.
    kept = len(recognizer)
    assert recognizer.frame_number(kept - 1) == 51
    numbers = [recognizer.frame_number(index) for index in range(kept)]
    assert numbers == sorted(set(numbers)) and numbers[0] == 0
    path = tmp_path / "map.db"
    recognizer.save(path)
    # As build_map records its traversal: a ground truth may name frames after the last keyframe.
    with sqlite3.connect(path) as database:
        assert database.execute("SELECT value FROM metadata WHERE key = 'traversal_frames'").fetchall() == [("53",)]
    database.close()
    loaded = mrs_vpr.PlaceRecognizer(**ROUTE_PARAMETERS)
    loaded.load(str(path))
    assert [loaded.frame_number(index) for index in range(kept)] == numbers
    assert loaded.add_frame(route["reference"][60]) is True  # Numbered on after the 53 frames offered.
    assert loaded.frame_number(kept) == 53
    with pytest.raises(IndexError, match=r"no map frame 99: the map holds 52 frames \(0\.\.51\)"):
        loaded.frame_number(99)
    with pytest.raises(IndexError, match="no map frame 2147483648"):
        loaded.frame_number(2**31)
    loaded.reset()
    loaded.add_frames(route["reference"][:3])
    assert loaded.frame_number(0) == 0


def test_a_map_saved_without_frame_numbers_is_numbered_on_after_its_frames(route, tmp_path):
    path = tmp_path / "map.db"
    mapped = mrs_vpr.PlaceRecognizer(min_appearance_change=0, **ROUTE_PARAMETERS)
    mapped.add_frames(route["reference"][:20])
    mapped.save(path)
    with sqlite3.connect(path) as database:  # As maps saved from Python before frames were numbered.
        database.execute("UPDATE frames SET sequence = -1")
    database.close()
    loaded = mrs_vpr.PlaceRecognizer(min_appearance_change=0, **ROUTE_PARAMETERS)
    loaded.load(str(path))
    assert loaded.frame_number(19) == -1
    loaded.add_frame(route["reference"][20])
    assert loaded.frame_number(20) == 20


def test_a_map_records_the_appearance_change_its_keyframes_were_kept_at(route, tmp_path):
    # from_map keyframes at it (test sequences on the map's scale); a map whose keyframing is not
    # known (loaded from a map kept at another) records none.
    kept_at_03 = mrs_vpr.PlaceRecognizer(min_appearance_change=0.3, **ROUTE_PARAMETERS)
    kept_at_03.add_frames(route["reference"][:40])
    kept_at_03.save(tmp_path / "at_03.db")
    loaded = mrs_vpr.PlaceRecognizer.from_map(tmp_path / "at_03.db", velocity_step=0.02, alignment="causal")
    assert loaded.parameters["min_appearance_change"] == 0.3
    chosen = mrs_vpr.PlaceRecognizer.from_map(tmp_path / "at_03.db", min_appearance_change=0.5)
    assert chosen.parameters["min_appearance_change"] == 0.5
    chosen.save(tmp_path / "unknown.db")
    with sqlite3.connect(tmp_path / "unknown.db") as database:
        keys = [key for (key,) in database.execute("SELECT key FROM metadata WHERE key LIKE 'traversal%'")]
    database.close()
    assert sorted(keys) == ["traversal_frames", "traversal_last_frame"]
