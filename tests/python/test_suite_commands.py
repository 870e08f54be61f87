"""glintlab.figure, sweep, compare and adequacy against the glintlab CLI (GLINTLAB_EXE): the same
arguments write the same files (byte for byte, but for the fields that are wall-clock timings),
the returned data is those files parsed, a numpy model that raises makes them raise, and bad
arguments raise ValueError with the CLI's error line. Small inputs only: one quick figure, one
model's sweep, one compare, a calibration of 10 runs. A numpy model swept, compared and drawn:
slow_register_model_conformance.py (seconds: the sweep calls it once per query)."""

import csv
import io
import json
import os
import subprocess

import numpy as np
import pytest

import glintlab
import numpy_models as nm
import stand_in_reports as stand_in

EXE = os.environ.get("GLINTLAB_EXE", "glintlab")
# compare's wall-clock fields (experiments/compare/compare.h kTimingFields): they differ between
# any two runs, so they are left out of the byte comparison; equal_time.png and index.html draw and
# print them and are compared by name only.
COMPARE_TIMING_FIELDS = {"scalar_ns_per_eval", "best_ns_per_eval", "seconds"}


def stand_in_reports(folder):
    """`folder` with the stand-in figure_charts.py and compare_page.py in it
    (stand_in_reports.py), for GLINTLAB_REPORTS_DIR: the runs whose files are compared, not
    drawn."""
    return stand_in.stand_in_reports(folder)


def expect_stand_in_charts(folder):
    """Every PNG below `folder` that has a chart spec is the spec's bytes and its CSV's; returns
    how many there are."""
    files, n = tree(folder), 0
    for rel, spec in files.items():
        if rel.endswith(".chart.json"):
            csv_name = json.loads(spec)["csv"]
            png = rel[:-len(".chart.json")] + ".png"
            assert files[png] == spec + files[os.path.join(os.path.dirname(rel), csv_name)], png
            n += 1
    return n


def run_cli(args, cwd):
    """The CLI on `args` in `cwd`; asserts success."""
    r = subprocess.run([EXE, *args], cwd=cwd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


def cli_error(args, cwd):
    """The message of the CLI's `glintlab: error: <message>` line for `args` (exit 2)."""
    r = subprocess.run([EXE, *args], cwd=cwd, capture_output=True, text=True)
    assert r.returncode == 2 and r.stdout == "", (r.returncode, r.stdout)
    prefix = "glintlab: error: "
    assert r.stderr.startswith(prefix) and r.stderr.count("\n") == 1, r.stderr
    return r.stderr[len(prefix):].rstrip("\n")


def tree(folder):
    """Every file below `folder`: relative path -> bytes."""
    out = {}
    for root, _, names in os.walk(folder):
        for name in names:
            full = os.path.join(root, name)
            with open(full, "rb") as f:
                out[os.path.relpath(full, folder)] = f.read()
    return out


def same_tree(a, b):
    ta, tb = tree(a), tree(b)
    assert sorted(ta) == sorted(tb)
    for rel in ta:
        assert ta[rel] == tb[rel], rel


@pytest.fixture
def two_dirs(tmp_path, monkeypatch):
    """(py, cli): two empty folders; the current directory is `py`, so the same relative --out
    gives the same paths inside the files of both runs."""
    py, cli = tmp_path / "py", tmp_path / "cli"
    py.mkdir()
    cli.mkdir()
    monkeypatch.chdir(py)
    return py, cli


def test_figure_writes_what_the_cli_writes(two_dirs, tmp_path, monkeypatch):
    py, cli = two_dirs
    # Both runs' chart (p_map) drawn by the stand-in: its spec and data compared.
    monkeypatch.setenv("GLINTLAB_REPORTS_DIR", str(stand_in_reports(tmp_path)))
    fig = glintlab.figure("kneiphof2024-fig6", "figs", budget="quick", threads=2)
    run_cli(["figure", "kneiphof2024-fig6", "--out", "figs", "--budget", "quick", "--threads", "2"],
            cli)
    same_tree(py / "figs", cli / "figs")
    assert expect_stand_in_charts(py / "figs") == 1
    assert os.path.samefile(fig["dir"], py / "figs" / "kneiphof2024-fig6")
    assert sorted(fig["files"]) == sorted(tree(py / "figs" / "kneiphof2024-fig6"))
    table = fig["data"]["fig6.csv"]
    with open(fig["files"]["fig6.csv"]) as f:
        rows = list(csv.reader(f))
    assert list(table.dtype.names) == rows[0] and len(table) == len(rows) - 1
    first_numeric = next(n for n in table.dtype.names if table.dtype[n] == np.float64)
    k = rows[0].index(first_numeric)
    assert np.array_equal(table[first_numeric], [float(r[k]) for r in rows[1:]])
    with open(fig["files"]["fig6.panels.json"]) as f:
        assert fig["data"]["fig6.panels.json"] == json.load(f)


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    """(py, cli, result): sweep(out="sw", models="smooth_ggx") run from `py` and the CLI's sweep
    on the same arguments run in `cli`; compare reads both folders."""
    py, cli = tmp_path_factory.mktemp("py"), tmp_path_factory.mktemp("cli")
    here, reports = os.getcwd(), os.environ.get("GLINTLAB_REPORTS_DIR")
    # Both sweeps' maps drawn by the stand-in: their specs and data compared.
    os.environ["GLINTLAB_REPORTS_DIR"] = str(stand_in_reports(tmp_path_factory.mktemp("reports")))
    os.chdir(py)
    try:
        result = glintlab.sweep(out="sw", models="smooth_ggx", budget="quick")
        run_cli(["sweep", "--out", "sw", "--models", "smooth_ggx", "--budget", "quick"], cli)
    finally:
        os.chdir(here)
        if reports is None:
            os.environ.pop("GLINTLAB_REPORTS_DIR", None)
        else:
            os.environ["GLINTLAB_REPORTS_DIR"] = reports
    return py, cli, result


def test_sweep_writes_what_the_cli_writes(swept):
    py, cli, s = swept
    same_tree(py / "sw", cli / "sw")
    assert expect_stand_in_charts(py / "sw") == 40  # the maps, as the stand-in drew them
    assert s["targets"] == len(s["stability"]["models"]) > 0
    assert {m["model"] for m in s["stability"]["models"]} == {"smooth_ggx"}
    assert os.path.samefile(s["json"], py / "sw" / "stability.json")
    assert sorted(s["files"]) == sorted(tree(py / "sw"))
    plane = next(rel for rel in s["data"] if rel.endswith(".csv"))
    assert len(s["data"][plane]) > 0 and "theta_i_deg" in s["data"][plane].dtype.names


def test_read_csv_names_repeated_columns_apart(tmp_path):
    (tmp_path / "t.csv").write_text("model,albedo,albedo,x\nm,0.5,1.25,inf\n")
    t = glintlab.read_csv(tmp_path / "t.csv")
    assert t.dtype.names == ("model", "albedo", "albedo_1", "x")
    assert t["model"][0] == "m" and t["albedo_1"][0] == 1.25 and np.isinf(t["x"][0])


def without_timings(value):
    """compare.json's content without its timing fields."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in COMPARE_TIMING_FIELDS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def csv_without_timings(text):
    rows = list(csv.reader(io.StringIO(text)))
    keep = [k for k, name in enumerate(rows[0]) if name not in COMPARE_TIMING_FIELDS]
    return [[r[k] for k in keep] for r in rows]


def test_compare_writes_what_the_cli_writes(swept, tmp_path, monkeypatch):
    py, cli, _ = swept
    # No conformance run here (an empty claims.json: the recorded verdicts) and the failure
    # regions read from the sweep's folder, so the comparison takes about a second per model.
    # Both pages drawn by the stand-in (their compare.json's bytes; about 0.9 s of CPU each by
    # compare_page.py): compare.json and the CSVs are compared, the pages by name only. The
    # page drawn from Python by the real script: slow_register_model_conformance.py and
    # test_example_my_glint_model.
    monkeypatch.setenv("GLINTLAB_REPORTS_DIR", str(stand_in_reports(tmp_path)))
    for d in (py, cli):
        (d / "claims").mkdir()
        (d / "claims" / "claims.json").write_text("[]\n")
    monkeypatch.chdir(py)
    c = glintlab.compare(out="cmp", models="smooth_ggx", budget="quick", threads=2,
                         claims_from="claims", sweeps_from="sw")
    run_cli(["compare", "--out", "cmp", "--models", "smooth_ggx", "--budget", "quick",
             "--threads", "2", "--claims-from", "claims", "--sweeps-from", "sw"], cli)
    mine, theirs = tree(py / "cmp"), tree(cli / "cmp")
    assert sorted(mine) == sorted(theirs) == sorted(c["files"])
    assert without_timings(json.loads(mine["compare.json"])) == \
        without_timings(json.loads(theirs["compare.json"]))
    for name in ("compare.csv", "equal_time.csv"):
        assert csv_without_timings(mine[name].decode()) == \
            csv_without_timings(theirs[name].decode()), name
    assert c["models"] == 1 and list(c["table"]["model"]) == ["smooth_ggx"]
    assert c["compare"] == json.loads(mine["compare.json"])
    assert mine["index.html"] == mine["compare.json"]  # drawn by the stand-in
    assert c["equal_time"]["samples"][0] == 1 and c["equal_time"].dtype["seconds"] == np.float64


def test_adequacy_calibration_writes_what_the_cli_writes(two_dirs):
    py, cli = two_dirs
    # At 1000 positions per synthetic cell, not the quick budget's 8000 (0.2 s of CPU a run, not
    # 0.9 s): the files are compared, whatever they hold.
    a = glintlab.adequacy(out="adq", models="kneiphof_klein", budget="quick", calibrate=True,
                          runs=10, tables=1, positions=1000)
    run_cli(["adequacy", "--out", "adq", "--models", "kneiphof_klein", "--budget", "quick",
             "--calibrate", "--runs", "10", "--tables", "1", "--positions", "1000"], cli)
    same_tree(py / "adq", cli / "adq")
    assert os.path.samefile(a["csv"], py / "adq" / "adequacy-calibration.csv")
    assert len(a["table"]) > 0 and "rate" in a["table"].dtype.names
    assert isinstance(a["summary"], dict) and a["seconds"] >= 0


# One bad argument per function: the message is the CLI's error line for the same option value.
@pytest.mark.parametrize("call, args", [
    (lambda: glintlab.figure("no-such-figure", "f", budget="quick"),
     ["figure", "no-such-figure", "--out", "f", "--budget", "quick"]),
    (lambda: glintlab.figure("kneiphof2024-fig6", "f", threads=2000),
     ["figure", "kneiphof2024-fig6", "--out", "f", "--threads", "2000"]),
    (lambda: glintlab.sweep(out="s", models="smooth_ggx", threads=-1),
     ["sweep", "--out", "s", "--models", "smooth_ggx", "--threads", "-1"]),
    (lambda: glintlab.compare(out="c", models="smooth_ggx", budget="medium"),
     ["compare", "--out", "c", "--models", "smooth_ggx", "--budget", "medium"]),
    (lambda: glintlab.adequacy(out="a", threshold=0),
     ["adequacy", "--out", "a", "--threshold", "0"]),
    (lambda: glintlab.adequacy(out="a", runs=5),
     ["adequacy", "--out", "a", "--runs", "5"]),
    (lambda: glintlab.adequacy(out="a", positions=50),
     ["adequacy", "--out", "a", "--positions", "50"]),
])
def test_bad_arguments_raise_the_cli_message(two_dirs, call, args):
    py, cli = two_dirs
    with pytest.raises(ValueError) as e:
        call()
    assert str(e.value) == cli_error(args, cli)
    assert os.listdir(py) == [] and os.listdir(cli) == []


def test_a_failing_numpy_model_raises_and_writes_nothing(two_dirs):
    py, _ = two_dirs

    def broken(q, p):
        raise ZeroDivisionError("on purpose")

    if "py_suite_broken" not in [m["name"] for m in glintlab.models()]:
        glintlab.register_model("py_suite_broken", broken, nm.lambert_pdf, nm.lambert_sample,
                                params=[nm.ALBEDO])
    with pytest.raises(RuntimeError, match="'py_suite_broken': eval raised ZeroDivisionError"):
        glintlab.sweep(out="sw", models="py_suite_broken", budget="quick")
    assert not (py / "sw").exists() or os.listdir(py / "sw") == []


def test_installed_package_uses_its_own_report_scripts(tmp_path):
    """cmake --install puts the report scripts (reports/) inside the package, and the installed
    package points GLINTLAB_REPORTS_DIR at them, so that its sweep, figure and compare do not
    depend on the source tree it was built from (the build tree's package has no copy and uses
    the source tree's reports/). The sweep is of smooth_beckmann: its 20 maps drawn by matplotlib
    with the installed scripts (smooth_ggx has 40)."""
    build = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(glintlab.__file__))))
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True,
                   capture_output=True)
    [init] = [os.path.join(d, "__init__.py") for d, _, files in os.walk(prefix)
              if d.endswith(os.sep + "glintlab") and "__init__.py" in files]
    package = os.path.dirname(init)
    for script in ("figure_charts.py", "compare_page.py", "charts.py", "templating.py",
                   os.path.join("templates", "compare_page.html.j2")):
        assert os.path.isfile(os.path.join(package, "reports", script)), script
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "GLINTLAB_REPORTS_DIR")}
    env["PYTHONPATH"] = os.path.dirname(package)
    env["MPLBACKEND"] = "Agg"
    code = ("import os, sys, glintlab; print(glintlab.__file__); "
            "print(os.environ['GLINTLAB_REPORTS_DIR']); "
            "s = glintlab.sweep(sys.argv[1], models='smooth_beckmann'); print(len(s['files']))")
    r = subprocess.run(["/usr/bin/python3", "-c", code, str(tmp_path / "sweeps")], env=env,
                       cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    where, reports, files = r.stdout.split()
    assert where == init and reports == os.path.join(package, "reports")
    assert int(files) > 0
