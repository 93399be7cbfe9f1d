"""scripts/mrs_vpr_plot on input files that are not what mrs_vpr_eval writes: one line that names the file
(doc/robustness.md), never a traceback. Its drawings are tested with mrs_vpr_eval in test/tools/plots_test.cpp."""

import importlib.machinery
import importlib.util
import json
import pathlib
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib")
pytest.importorskip("PIL")

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "mrs_vpr_plot"

#: What mrs_vpr_eval --output writes, cut to the fields the PR curve reads.
EVALUATION = {"method": "mrs", "protocol": "per-frame", "reference_frames": 100,
              "parameters": {"sequence_length": 10},
              "summary": {"tolerance": 2, "pr_auc": 1.0, "recall_at_100_precision": 1.0},
              "pr_curve": [{"threshold": 1.0, "precision": 1.0, "recall": 1.0}], "records": []}


@pytest.fixture(scope="module")
def plot_tool():
    """The script as a module (it has no .py name), run in this process: fast, and an exception that
    escapes main() fails the test as its traceback would have been printed."""
    loader = importlib.machinery.SourceFileLoader("mrs_vpr_plot", str(SCRIPT))
    spec = importlib.util.spec_from_loader("mrs_vpr_plot", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def error_of(plot_tool, capsys, argv):
    """What main(argv) prints on stderr; it must fail."""
    assert plot_tool.main(argv) == 1
    captured = capsys.readouterr()
    assert captured.out == ""
    return captured.err


@pytest.mark.parametrize(
    "content, problem",
    [
        # Before: a RecursionError's traceback.
        ("[" * 100000 + "]" * 100000, " is not JSON this tool reads: its arrays or objects nest too deeply"),
        ('{"summary": ' * 100000 + "1" + "}" * 100000,
         " is not JSON this tool reads: its arrays or objects nest too deeply"),
        # Before, none of these named the file.
        ("", " is empty, not the JSON that mrs_vpr_eval --output or mrs_vpr_real_benchmark --json writes"),
        ("not json", " is not JSON: Expecting value: line 1 column 1 (char 0)"),
        ('{"summary": ', " is not JSON: Expecting value: line 1 column 13 (char 12)"),
        (b"\xff\xfe{}", " is not JSON: not UTF-8 text ('utf-8' codec can't decode byte 0xff in position 0: "
                        "invalid start byte)"),
        ('{"summary": %s}' % ("1" * 5000), " is not JSON this tool reads: Exceeds the limit (4300 digits)"),
    ],
    ids=["deep arrays", "deep objects", "empty", "not JSON", "cut short", "not UTF-8", "a 5000-digit number"],
)
def test_a_file_that_is_not_json_is_one_line_naming_it(plot_tool, capsys, tmp_path, content, problem):
    path = tmp_path / "evaluation.json"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    for argv in (["pr", str(path), "-o", str(tmp_path / "x.png")], ["error", str(path), "-o", str(tmp_path / "x.png")],
                 ["eval", str(path)], ["benchmark", str(path)]):
        err = error_of(plot_tool, capsys, argv)
        assert err.startswith("mrs_vpr_plot: error: %s%s" % (path, problem)), err
        assert err.count("\n") == 1, err
    assert not (tmp_path / "x.png").exists()


def test_a_missing_field_names_the_file(plot_tool, capsys, tmp_path):
    path = tmp_path / "evaluation.json"
    path.write_text("{}")
    err = error_of(plot_tool, capsys, ["pr", str(path), "-o", str(tmp_path / "x.png")])
    assert err == "mrs_vpr_plot: error: missing field 'summary' in %s\n" % path


def test_of_several_files_the_error_names_the_bad_one(plot_tool, capsys, tmp_path):
    good, bad = tmp_path / "good.json", tmp_path / "bad.json"
    good.write_text(json.dumps(EVALUATION))
    bad.write_text(json.dumps(dict(EVALUATION, parameters=[])))
    err = error_of(plot_tool, capsys, ["pr", str(good), str(bad), "-o", str(tmp_path / "x.png")])
    assert err.startswith("mrs_vpr_plot: error: %s: not the JSON that mrs_vpr_eval or mrs_vpr_real_benchmark writes "
                          "(TypeError: " % bad), err
    assert err.count("\n") == 1, err
    assert not (tmp_path / "x.png").exists()
    assert plot_tool.main(["pr", str(good), "-o", str(tmp_path / "x.png")]) == 0
    assert capsys.readouterr().out == "wrote %s\n" % (tmp_path / "x.png")


def test_an_output_matplotlib_cannot_write_is_not_blamed_on_the_input(plot_tool, capsys, tmp_path):
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(EVALUATION))
    err = error_of(plot_tool, capsys, ["pr", str(path), "-o", str(tmp_path / "x.foo")])
    assert err.startswith("mrs_vpr_plot: error: -o %s: matplotlib writes no .foo files (it writes " % (
        tmp_path / "x.foo")), err
    assert err.count("\n") == 1


def test_the_tool_prints_no_traceback_for_deeply_nested_json(tmp_path):
    # The audit's case, as a user runs it.
    path = tmp_path / "deep.json"
    path.write_text("[" * 100000 + "]" * 100000)
    result = subprocess.run([sys.executable, str(SCRIPT), "pr", str(path), "-o", str(tmp_path / "x.png")],
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 1
    assert result.stderr == ("mrs_vpr_plot: error: %s is not JSON this tool reads: its arrays or objects nest too "
                             "deeply\n" % path)
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(
    "argv, problem",
    [
        (["pr", "e.json", "-o", "x.png", "--dpi", "0"], "--dpi and --size must be positive"),
        (["pr", "e.json", "-o", "x.png", "--colours", "1"], "--colours must be in 2..256"),
        (["pr", "e.json", "-o", "x.png", "--size", "1e6", "1e6"],
         "--size and --dpi make a picture over 65535 pixels a side"),
        # Within the limit a side, but 14 GB to draw: refused at once, not killed without a word.
        (["pr", "e.json", "-o", "x.png", "--size", "600", "600", "--dpi", "100"],
         "--size and --dpi make a picture of 3600 megapixels, more than the 100 it draws, at 4 bytes each in memory"),
        (["pr", "e.json"], "the following arguments are required: -o/--output"),
    ],
    ids=["dpi", "colours", "huge", "huge area", "no output"],
)
def test_bad_arguments_are_one_line_and_exit_code_one(plot_tool, capsys, argv, problem):
    with pytest.raises(SystemExit) as stop:
        plot_tool.main(argv)
    assert stop.value.code == 1
    err = capsys.readouterr().err
    assert err == "mrs_vpr_plot: error: %s (see --help)\n" % problem


def test_a_mistyped_output_folder_is_refused_not_created(plot_tool, capsys, tmp_path):
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(EVALUATION))
    typo = tmp_path / "typo1" / "typo2" / "out"
    err = error_of(plot_tool, capsys, ["eval", str(path), "-d", str(typo)])
    assert err == "mrs_vpr_plot: error: -d %s: there is no folder %s\n" % (typo, typo.parent)
    assert not (tmp_path / "typo1").exists()


@pytest.mark.parametrize(
    "argv, problem",
    [
        (["pr", "{json}", "-o", ""], "-o was given an empty path"),
        (["eval", "{json}", "-d", ""], "-d was given an empty path"),
        (["pr", "{json}", "-o", "{folder}/c.jpg", "--colours", "16"],
         "--colours makes a PNG of a few colours; -o {folder}/c.jpg is no .png file"),
        (["pr", "{json}", "-o", "{folder}/nowhere/pr.png"],
         "-o {folder}/nowhere/pr.png: there is no folder {folder}/nowhere"),
    ],
    ids=["empty -o", "empty -d", "colours of a JPEG", "no folder for -o"],
)
def test_outputs_it_cannot_write_as_asked_are_refused_before_drawing(plot_tool, capsys, tmp_path, argv, problem):
    path = tmp_path / "evaluation.json"
    path.write_text(json.dumps(EVALUATION))
    argv = [a.format(json=path, folder=tmp_path) for a in argv]
    err = error_of(plot_tool, capsys, argv)
    assert err == "mrs_vpr_plot: error: %s\n" % problem.format(folder=tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["evaluation.json"]


def test_the_benchmark_curves_join_only_the_plain_global_rows(plot_tool, tmp_path, monkeypatch):
    def row(setting, length, top1):
        return {"setting": setting, "method": "mrs", "protocol": "global", "out_of_map": False,
                "reference_frames": 1783, "sequence_length": length,
                "summary": {"top1": top1, "median_time_ms": 1.0}}
    bench = {"rows": [row("global N=100 M=1783", 100, 0.9), row("global winter backwards N=100 M=1783", 100, 0.0),
                      row("global N=200 M=1783", 200, 1.0), row("global winter with stops N=200 M=1783", 200, 0.0)],
             "tolerance": 2, "queries": 10, "part": "check", "threads": 1}
    path = tmp_path / "bench.json"
    path.write_text(json.dumps(bench))
    drawn = []
    original_plot = plot_tool.plt.Axes.plot

    def record(axes, xs, ys, *rest, **options):
        drawn.append((list(xs), list(ys)))
        return original_plot(axes, xs, ys, *rest, **options)
    monkeypatch.setattr(plot_tool.plt.Axes, "plot", record)
    assert plot_tool.main(["benchmark", str(path)]) == 0
    # Success against N: one line through the plain rows; time against M: one point for each N.
    assert drawn == [([100, 200], [0.9, 1.0]), ([1783], [1.0]), ([1783], [1.0])]
