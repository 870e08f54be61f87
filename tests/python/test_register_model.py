"""glintlab.register_model: a numpy Lambertian registered from Python, listed, evaluated and sampled
in chunks; the errors of a model's functions (raise, wrong type, dtype, shape, NaN) and of
register_model's arguments; verify's arguments. The conformance suite on it (every property,
and the wrong-pdf model failing sampler-matches-pdf) is slow_register_model_conformance.py, its
own ctest test."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import glintlab
import numpy_models as nm
import stand_in_reports as stand_in

WI = np.array([0.3, 0.0, np.sqrt(1 - 0.09)])


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


@pytest.fixture(scope="module")
def lambert():
    nm.register_lambert(glintlab, "py_lambert")
    return "py_lambert"


def directions(rows, seed=3):
    wo = unit(np.random.default_rng(seed).normal(size=(rows, 3)))
    wo[:, 2] = np.abs(wo[:, 2])
    return wo


def test_listed(lambert):
    m = {m["name"]: m for m in glintlab.models()}[lambert]
    assert m["description"] == "Lambertian in numpy"
    assert m["needs"] == [] and m["batched"] is False and m["smooth_limit"] is None
    assert [p["name"] for p in m["params"]] == ["albedo"] and m["params"][0]["default"] == 0.8


def test_eval_and_sample(lambert):
    wo = directions(10000)
    r = glintlab.eval(lambert, WI, wo, params={"albedo": 0.5})
    np.testing.assert_array_equal(r["value"], 0.5 * wo[:, 2] / np.pi)
    np.testing.assert_array_equal(r["pdf"], wo[:, 2] / np.pi)
    # Per-row parameters: each run of equal values is one call with that value.
    albedo = np.where(np.arange(10000) < 5000, 0.25, 0.75)
    r = glintlab.eval(lambert, WI, wo, params={"albedo": albedo})
    np.testing.assert_array_equal(r["value"], albedo * wo[:, 2] / np.pi)
    f = glintlab.eval(lambert, WI, wo, precision="float")
    assert f["value"].dtype == np.float32
    np.testing.assert_allclose(f["value"], 0.8 * wo[:, 2] / np.pi, rtol=1e-6)
    s = glintlab.sample(lambert, WI, n=20000, seed=7)
    np.testing.assert_allclose(np.linalg.norm(s["wo"], axis=1), 1, rtol=1e-12)
    np.testing.assert_array_equal(s["weight"], 0.8)
    np.testing.assert_allclose(s["pdf"], s["wo"][:, 2] / np.pi, rtol=1e-12)
    assert not s["rejected"].any()
    # Mean cos θo of the cosine-weighted hemisphere is 2/3 (σ of the mean ≈ 0.0016).
    assert abs(s["wo"][:, 2].mean() - 2 / 3) < 0.01
    again = glintlab.sample(lambert, WI, n=20000, seed=7, threads=1)
    np.testing.assert_array_equal(s["wo"], again["wo"])


def test_called_per_chunk():
    calls = []

    def ev(q, p):
        calls.append(len(q["wo_z"]))
        return nm.lambert_eval(q, p)

    glintlab.register_model("py_counted", ev, nm.lambert_pdf, nm.lambert_sample,
                            params=[nm.ALBEDO])
    glintlab.eval("py_counted", WI, directions(40000), threads=1)
    # A numpy model's chunks of 16384 rows (four of the CLI's): one call of eval per chunk, never
    # one per row.
    assert sorted(calls) == [7232, 16384, 16384]
    calls.clear()
    glintlab.eval("py_counted", WI, directions(40000), threads=2)
    assert sorted(calls) == [7232, 16384, 16384]


def test_query_arrays_are_read_only_views():
    """The functions get the query columns as read-only arrays: views of the caller's array where a
    column lies contiguous in float64 (a Fortran-ordered (N, 3) array), else of the chunk's
    gathered columns (a C-ordered one); an array a function keeps stays valid after the call. A
    function that writes into one raises, naming the model and the function. Rows of per-row
    parameters grouped from scattered rows get copies (the same values)."""
    kept = []

    def ev(q, p):
        kept.append(q)
        return nm.lambert_eval(q, p)

    glintlab.register_model("py_kept", ev, nm.lambert_pdf, nm.lambert_sample, params=[nm.ALBEDO])
    n = 40000
    wi, wo = directions(n, seed=5), directions(n, seed=6)
    albedo = np.random.default_rng(7).choice([0.25, 0.5, 0.75], size=n)  # scattered groups
    for layout in (np.ascontiguousarray, np.asfortranarray):
        for params in (None, {"albedo": albedo}):
            kept.clear()
            r = glintlab.eval("py_kept", layout(wi), layout(wo), params=params, threads=2)
            expect = (0.8 if params is None else albedo) * wo[:, 2] / np.pi
            np.testing.assert_array_equal(r["value"], expect)
            seen = np.zeros(n, dtype=int)
            for q in kept:
                assert all(not a.flags.writeable and a.dtype == np.float64 and a.ndim == 1
                           for a in q.values()), q
                # Each call's rows: find them by value (wo_z of the kept array is the input's).
                rows = np.flatnonzero(np.isin(wo[:, 2], q["wo_z"]))
                assert len(rows) == len(q["wo_z"])
                seen[rows] += 1
                np.testing.assert_array_equal(np.sort(q["wi_x"]), np.sort(wi[rows, 0]))
            assert (seen == 1).all()
        if layout is np.asfortranarray:
            # In place: the views of one call lie in the caller's arrays.
            f = layout(wo)
            kept.clear()
            glintlab.eval("py_kept", wi, f, threads=1)
            assert np.shares_memory(kept[0]["wo_z"], f)

    def writes(q, p):
        q["wo_z"][:] = 0
        return nm.lambert_eval(q, p)

    glintlab.register_model("py_writes", writes, nm.lambert_pdf, nm.lambert_sample,
                            params=[nm.ALBEDO])
    f = np.asfortranarray(wo)
    with pytest.raises(RuntimeError, match="glintlab model 'py_writes': eval raised ValueError: "
                                           "assignment destination is read-only"):
        glintlab.eval("py_writes", wi, f)
    np.testing.assert_array_equal(f, wo)


def register_broken(name, **overrides):
    fns = {"eval": nm.lambert_eval, "pdf": nm.lambert_pdf, "sample": nm.lambert_sample}
    fns.update(overrides)
    glintlab.register_model(name, fns["eval"], fns["pdf"], fns["sample"], params=[nm.ALBEDO])
    return name


def raises_zero_division(q, p):
    return 1 / 0


BROKEN = {
    "raises": ({"eval": raises_zero_division}, "eval raised ZeroDivisionError"),
    "shape": ({"eval": lambda q, p: np.zeros((len(q["wo_z"]), 2))}, "eval returned its value of shape"),
    "dtype": ({"pdf": lambda q, p: np.zeros(len(q["wo_z"]), dtype=np.float32)},
              "pdf returned its pdf of dtype float32"),
    "byteorder": ({"pdf": lambda q, p: np.zeros(len(q["wo_z"]), dtype=">f8")},
                  "pdf returned its pdf of dtype >f8"),
    "type": ({"eval": lambda q, p: 0.5}, "eval returned its value of type float"),
    "nan": ({"eval": lambda q, p: np.full(len(q["wo_z"]), np.nan)}, "eval returned NaN"),
    "sample_keys": ({"sample": lambda q, u, p: {"wo": np.zeros((len(u), 3))}},
                    "sample returned no 'pdf'"),
    "sample_list": ({"sample": lambda q, u, p: [1, 2]}, "sample did not return a dict"),
}


@pytest.mark.parametrize("kind", sorted(BROKEN))
def test_broken_functions_raise(kind):
    overrides, message = BROKEN[kind]
    name = register_broken(f"py_broken_{kind}", **overrides)
    with pytest.raises(RuntimeError, match=f"glintlab model '{name}': {message}"):
        if kind.startswith("sample"):
            glintlab.sample(name, WI, n=5000, seed=1)
        else:
            glintlab.eval(name, WI, directions(5000))


def test_register_errors(lambert):
    f = nm.lambert_eval
    with pytest.raises(ValueError, match="already registered"):
        glintlab.register_model(lambert, f, f, f)
    with pytest.raises(ValueError, match="not a model name"):
        glintlab.register_model("bad name", f, f, f)
    with pytest.raises(ValueError, match="pdf: not callable"):
        glintlab.register_model("py_e1", f, 3, f)
    with pytest.raises(ValueError, match="needs: 'light' is not a query part"):
        glintlab.register_model("py_e2", f, f, f, needs=["light"])
    with pytest.raises(ValueError, match="smooth_limit"):
        glintlab.register_model("py_e3", f, f, f, smooth_limit="no_such_model")
    with pytest.raises(ValueError, match="params: 'a' needs a name and lo <= default <= hi"):
        glintlab.register_model("py_e4", f, f, f, params=[{"name": "a", "default": 2, "lo": 0, "hi": 1}])
    with pytest.raises(ValueError, match="energy-conservation"):
        glintlab.register_model("py_e5", f, f, f, not_claimed={"energy-conservation": "why"})
    names = [m["name"] for m in glintlab.models()]
    assert not any(n.startswith("py_e") for n in names)


def test_footprint_model_gets_its_columns():
    seen = {}

    def ev(q, p):
        seen.update({k: v.copy() for k, v in q.items()})
        return nm.lambert_eval(q, p)

    glintlab.register_model("py_footprint", ev, nm.lambert_pdf, nm.lambert_sample,
                            params=[nm.ALBEDO], needs=["footprint"], smooth_limit="smooth_ggx")
    m = {m["name"]: m for m in glintlab.models()}["py_footprint"]
    assert m["needs"] == ["footprint"] and m["smooth_limit"] == "smooth_ggx"
    fp = {"u": 0.25, "v": 0.5, "dudx": 1e-3, "dvdx": 0.0, "dudy": 0.0, "dvdy": 2e-3}
    glintlab.eval("py_footprint", WI, directions(10), footprint=fp)
    assert sorted(seen) == sorted(["u", "v", "dudx", "dvdx", "dudy", "dvdy",
                                   "wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z"])
    np.testing.assert_array_equal(seen["dvdy"], 2e-3)


def test_verify_errors():
    with pytest.raises(ValueError, match="budget: 'medium' is not a budget"):
        glintlab.verify("smooth.projected-area", budget="medium")
    with pytest.raises(ValueError, match="no.such.claim' matches nothing"):
        glintlab.verify("no.such.claim")
    with pytest.raises(ValueError, match="--threads"):
        glintlab.verify("smooth.projected-area", threads=-1)


def test_verify_a_paper_claim():
    (row,) = glintlab.verify("smooth.projected-area", threads=1)
    assert row["id"] == "smooth.projected-area"
    assert row["verdict"] == row["expected_verdict"] == "holds"
    assert row["control_rejected"] is True and row["budget"] == "quick"


def test_a_raising_model_is_an_error_row_inside_verify(lambert):
    """Inside the suite a Python function that raises is that model's `error` verdict, naming the
    model and the function; the other claims of the run still run (another model's check here:
    a paper claim through verify is test_verify_a_paper_claim's)."""
    name = register_broken("py_broken_in_suite", eval=raises_zero_division)
    rows = {r["id"]: r for r in glintlab.verify(
        f"model.{name}.eval-pdf-consistency,model.{lambert}.eval-pdf-consistency", threads=1)}
    bad = rows[f"model.{name}.eval-pdf-consistency"]
    assert bad["verdict"] == "error"
    assert f"glintlab model '{name}': eval raised ZeroDivisionError" in bad["detail"]
    assert rows[f"model.{lambert}.eval-pdf-consistency"]["verdict"] == "holds"


# Registers the numpy Lambertian as `py_route` with the given chunked flag, runs its checks and
# prints their rows without the timing field (the checks' seeds follow the claim id, so the two
# routes are compared under the same model name, in two processes).
ROUTE_SCRIPT = """
import json, sys
import glintlab, numpy_models as nm
calls = []
def pdf(q, p):
    calls.append(len(q["wo_z"]))
    return nm.lambert_pdf(q, p)
glintlab.register_model("py_route", nm.lambert_eval, pdf, nm.lambert_sample, params=[nm.ALBEDO],
                        chunked=sys.argv[1] == "chunked")
rows = glintlab.verify("model.py_route.eval-pdf-consistency", threads=2)
print(json.dumps({"rows": [{k: v for k, v in r.items() if k != "seconds"} for r in rows],
                  "pdf_calls": len(calls), "pdf_rows": sum(calls)}))
"""


def test_chunked_and_per_query_routes_agree():
    """The suite's calls per chunk of queries (one call of pdf for thousands of rows) give the same
    check results, bit for bit, as its calls per query (chunked=False)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [os.path.dirname(__file__), os.environ.get("PYTHONPATH", "")]))
    out = {}
    for route in ("chunked", "per-query"):
        r = subprocess.run([sys.executable, "-c", ROUTE_SCRIPT, route], check=True,
                           capture_output=True, text=True, env=env)
        out[route] = json.loads(r.stdout)
    chunked, per_query = out["chunked"], out["per-query"]
    assert [r["verdict"] for r in chunked["rows"]] == ["holds"], chunked["rows"]
    assert chunked["rows"][0]["control_verdict"] == "fails", chunked["rows"]
    assert chunked["rows"] == per_query["rows"]
    # The same rows asked for: 32768 rows of pdf (2 settings × 4096 samples, check and control,
    # for pdf() and for eval's pdf), in 8 calls instead of 32768.
    assert chunked["pdf_rows"] == per_query["pdf_rows"] == 32768
    assert per_query["pdf_calls"] == 32768 and chunked["pdf_calls"] == 8


def test_chunked_errors_inside_verify():
    """A function that fails on one row of a chunk is that model's `error` verdict inside the suite,
    naming the model and the function, and the run goes on to its other checks."""
    def pdf_nan_near_normal(q, p):
        v = nm.lambert_pdf(q, p)
        return np.where(q["wo_z"] > 0.999, np.nan, v)

    def sample_wrong_shape(q, u, p):
        s = nm.lambert_sample(q, u, p)
        s["wo"] = s["wo"][:, :2]
        return s

    glintlab.register_model("py_nan_row", nm.lambert_eval, pdf_nan_near_normal, nm.lambert_sample,
                            params=[nm.ALBEDO])
    glintlab.register_model("py_bad_shape", nm.lambert_eval, nm.lambert_pdf, sample_wrong_shape,
                            params=[nm.ALBEDO])
    rows = {r["id"]: r for r in glintlab.verify(
        "model.py_nan_row.sampler-matches-pdf,model.py_bad_shape.pdf-normalized,"
        "model.py_bad_shape.eval-pdf-consistency,model.py_bad_shape.energy", threads=2)}
    nan = rows["model.py_nan_row.sampler-matches-pdf"]
    assert nan["verdict"] == "error"
    assert "glintlab model 'py_nan_row': pdf returned NaN in its pdf at row" in nan["detail"], nan
    shape = rows["model.py_bad_shape.pdf-normalized"]
    assert shape["verdict"] == "error"
    assert "glintlab model 'py_bad_shape': sample returned its 'wo' of shape" in shape["detail"], shape
    assert rows["model.py_bad_shape.eval-pdf-consistency"]["verdict"] == "error"
    # energy integrates eval's value, never the sampler: the broken sampler does not touch it.
    assert rows["model.py_bad_shape.energy"]["verdict"] == "holds"


def test_example_my_glint_model(tmp_path):
    """examples/python/my_glint_model.py registers its numpy glint model, prints the verdicts of
    the conformance checks it is asked for, writes its plots and compares itself with a paper's
    model (one property and one paper's model here: all the properties take about two minutes,
    mostly the stability sweep's one call per query; compare's reference albedo calls the numpy
    model once per chunk of directions, seconds). The paper's model is smooth_beckmann, whose
    stability maps (the example sweeps it) are 20, smooth_ggx's 40. Nothing here looks at those
    maps: they are drawn by the stand-in (stand_in_reports.py; about 4 of the example's 12 s of
    CPU were matplotlib's drawing of them), compare's page by the real compare_page.py. The
    example's maps drawn by matplotlib: install.python_site_packages (tests/install/)."""
    script = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python",
                          "my_glint_model.py")
    out = tmp_path / "glint.png"
    env = dict(os.environ, GLINTLAB_REPORTS_DIR=stand_in.stand_in_reports(
        str(tmp_path / "reports"), with_pages=True))
    r = subprocess.run([sys.executable, script, "--out", str(out),
                        "--properties", "eval-pdf-consistency",
                        "--compare-with", "smooth_beckmann"],
                       check=True, capture_output=True, text=True, env=env)
    lines = r.stdout.splitlines()
    assert lines[0].startswith("model.facet_cells.eval-pdf-consistency")
    assert lines[0].split()[1] == "holds" and "control fails" in lines[0]
    assert out.stat().st_size > 10000
    index = tmp_path / "glint_compare" / "index.html"
    assert lines[-1] == f"compare: {index}"
    assert index.stat().st_size > 1000 and "smooth_beckmann" in index.read_text()
    table = lines[lines.index("plots: " + str(out)) + 1:-1]
    assert table[0] == "" and table[1].split()[:2] == ["model", "ns/eval"], table
    assert [row.split()[0] for row in table[2:]] == ["smooth_beckmann", "facet_cells"], table
    assert "holds (recorded)" in table[2], table
    # The numpy model's row: a finite time per evaluation and sampler error against its reference,
    # its one measured verdict read from the run.
    assert "holds (read) 1" in table[3] and float(table[3].split()[1]) > 0, table
