"""The README's example script, on two folders of generated frames."""

import pathlib
import subprocess
import sys

import numpy as np
import pytest

import mrs_vpr

Image = pytest.importorskip("PIL.Image")

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "doc" / "examples" / "map_and_localise.py"


def write_folder(folder, frames):
    folder.mkdir()
    for i, frame in enumerate(frames):
        Image.fromarray(np.ascontiguousarray(frame[..., ::-1])).save(folder / ("%05d.png" % i))  # BGR -> RGB


def test_the_example_maps_a_folder_and_localises_the_last_stretch(tmp_path):
    # At a constant speed of one place per frame, query frame i shows map frame i, as in the Nordland set.
    route = mrs_vpr.synthetic_route(reference_frames=300, query_frames=300, speed_min=1.0, speed_max=1.0)
    assert list(route["query_to_reference"]) == list(range(300))
    write_folder(tmp_path / "map", route["reference"])
    write_folder(tmp_path / "query", route["query"])
    result = subprocess.run(
        [sys.executable, str(SCRIPT), str(tmp_path / "map"), str(tmp_path / "query"), "--evaluate", "10",
         "--save", str(tmp_path / "map.db"), "--parameter", "descriptor_type=thumbnail",
         "--parameter", "velocity_step=0.02"],
        capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("map: 300 frames of 128 x 64 px, 300 keyframes, mapped in ")
    assert lines[1].startswith("stretch: query frames 250..299 (50 keyframes) -> map keyframe ")
    # The middle keyframe of the stretch is the one localised (alignment centred, the default).
    assert lines[1].endswith("query frame 275 localised: error 0 frames (correct)")
    assert lines[3].startswith("10 stretches of 50 frames at random positions: top-1 1.000 (within 3 frames)")
    assert lines[4] == "saved 300 frames to %s" % (tmp_path / "map.db")
    assert len(mrs_vpr.PlaceRecognizer.from_map(tmp_path / "map.db")) == 300


def test_the_example_keyframes_a_camera_that_stops_and_scores_the_frames_a_keyframe_stands_for(tmp_path):
    # Both traversals stop for a second frame at every place: frame i of either shows place i // 2.
    route = mrs_vpr.synthetic_route(reference_frames=150, query_frames=150, speed_min=1.0, speed_max=1.0)
    write_folder(tmp_path / "map", np.repeat(route["reference"], 2, axis=0))
    write_folder(tmp_path / "query", np.repeat(route["query"], 2, axis=0))
    result = subprocess.run(
        [sys.executable, str(SCRIPT), str(tmp_path / "map"), str(tmp_path / "query"), "--evaluate", "10",
         "--tolerance", "0", "--parameter", "descriptor_type=thumbnail", "--parameter", "velocity_step=0.02"],
        capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("map: 300 frames of 128 x 64 px, 150 keyframes, mapped in ")
    # The stretch's last keyframe is frame 298 (299 repeats it); map keyframe 149 stands for frames 298..299.
    assert lines[1].startswith("stretch: query frames 250..299 (25 keyframes) -> map keyframe 137 (frames 274..275), "
                               "query frame 274 localised: error 0 frames (correct)")
    assert lines[3].startswith("10 stretches of 50 frames at random positions: top-1 1.000 (within 0 frames)")


def test_the_example_run_as_documented_prints_its_help_without_a_prompt_or_a_warning():
    result = subprocess.run([str(SCRIPT), "--help"], stdin=subprocess.DEVNULL, capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0
    assert result.stdout.startswith("usage: map_and_localise.py [-h]")
    assert "map_folder" in result.stdout and "--parameter NAME=VALUE" in result.stdout
    assert result.stderr == ""


def test_the_example_reports_a_bad_parameter(tmp_path):
    result = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), str(tmp_path), "--parameter", "tau=0"],
                            capture_output=True, text=True)
    assert result.returncode == 2  # A bad argument, as the documentation says.
    assert "bad parameter: mrs/tau must be in 1..16, got 0" in result.stderr
    unknown = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), str(tmp_path), "--parameter", "foo=1"],
                             capture_output=True, text=True)
    assert unknown.returncode == 2
    assert "bad parameter: unknown parameter 'foo'" in unknown.stderr


def test_the_example_refuses_a_sequence_length_other_than_its_length_option(tmp_path):
    for name in ("sequence_length", "sequence/sequence_length"):
        result = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), str(tmp_path), "--parameter",
                                 name + "=30"], capture_output=True, text=True)
        assert result.returncode == 2
        assert result.stderr.splitlines()[-1] == ("map_and_localise.py: error: --parameter %s: the sequence length "
                                                  "is the stretch's, set it with --length" % name)
        assert "Traceback" not in result.stderr


def test_the_example_refuses_bad_numbers_and_an_existing_save_target_before_any_work(tmp_path):
    (tmp_path / "taken.db").write_text("")
    (tmp_path / "left.db-wal").write_text("")
    for arguments, message in ((["--tolerance", "-1"], "--tolerance must be >= 0, got -1"),
                               (["--evaluate", "-1"], "--evaluate must be >= 0, got -1"),
                               (["--seed", "-1"], "--seed must be >= 0, got -1"),
                               (["--length", "1"], "--length must be >= 2, got 1"),
                               # The map database's own words: the check is the one save() makes.
                               (["--save", ""], "--save: cannot save the map to '': no path given"),
                               (["--save", str(tmp_path / "taken.db")],
                                "--save: cannot save the map to '%s': the file exists" % (tmp_path / "taken.db")),
                               (["--save", str(tmp_path)],
                                "--save: cannot save the map to '%s': it is a folder" % tmp_path),
                               (["--save", str(tmp_path / "nowhere" / "map.db")],
                                "there is no folder %s" % (tmp_path / "nowhere")),
                               (["--save", str(tmp_path / "left.db")],
                                "'%s-wal' is left beside it by an earlier map of that name" % (tmp_path / "left.db"))):
        # The folders hold no image: an argument checked only after reading them would say so instead.
        result = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path), str(tmp_path)] + arguments,
                                capture_output=True, text=True)
        assert result.returncode == 2, arguments
        assert message in result.stderr.splitlines()[-1], result.stderr


def test_the_example_refuses_a_stretch_outside_the_query_and_counts_stretches_it_cannot_ask(tmp_path):
    route = mrs_vpr.synthetic_route(reference_frames=120, query_frames=120, speed_min=1.0, speed_max=1.0)
    write_folder(tmp_path / "map", route["reference"])
    # The query stands still for its first 40 frames: a stretch within them keyframes to one frame.
    write_folder(tmp_path / "query", np.concatenate([np.repeat(route["query"][:1], 40, axis=0), route["query"][40:]]))
    common = [sys.executable, str(SCRIPT), str(tmp_path / "map"), str(tmp_path / "query"), "--parameter",
              "descriptor_type=thumbnail", "--length", "20"]
    for first in ("-1", "101"):
        result = subprocess.run(common + ["--first", first], capture_output=True, text=True)
        assert result.returncode == 1
        assert result.stderr.strip() == "--first must be in 0..100 (120 query frames, stretches of 20), got " + first
    result = subprocess.run(common + ["--evaluate", "101"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    lines = result.stdout.splitlines()
    assert lines[3].startswith("101 stretches of 20 frames at random positions: top-1 ")
    # The 21 stretches starting at frames 0..20 lie within the stop (frames 0..39).
    assert lines[4] == "21 of them held too few keyframes to be asked (counted as not correct)"
