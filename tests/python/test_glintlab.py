"""The glintlab Python module against the glintlab CLI (GLINTLAB_EXE): eval and sample bit-identical
in double for every registered model, the no-copy path, per-row parameters, thread independence
and the errors. Run by ctest as `/usr/bin/python3 -m pytest tests/python`."""

import csv
import os
import subprocess
import sys

import numpy as np
import pytest

import glintlab

EXE = os.environ.get("GLINTLAB_EXE", "glintlab")
ROWS = 64


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def queries(model, rows=ROWS, seed=1):
    """Valid query rows for `model`: upper-hemisphere directions and, where needed, a footprint,
    a light and the corner reflection vectors (a small cone around wo, as podee requires)."""
    rng = np.random.default_rng(seed)
    wi = unit(rng.normal(size=(rows, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wo = unit(rng.normal(size=(rows, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wi[:, 2], wo[:, 2] = np.abs(wi[:, 2]), np.abs(wo[:, 2])
    footprint, light = None, None
    if "footprint" in model["needs"]:
        footprint = {"u": rng.uniform(0, 1, rows), "v": rng.uniform(0, 1, rows),
                     "dudx": np.full(rows, 2e-3), "dvdx": np.zeros(rows),
                     "dudy": np.zeros(rows), "dvdy": np.full(rows, 2e-3)}
    if "pixel corners" in model["needs"]:
        for k in range(4):
            r = unit(wo + rng.normal(scale=1e-3, size=(rows, 3)))
            for a, axis in enumerate("xyz"):
                footprint[f"r{k}_{axis}"] = r[:, a]
    if "point light" in model["needs"] or "area light" in model["needs"]:
        light = {"light_cos_half_angle": np.full(rows, 0.999), "light_intensity": np.ones(rows)}
    return wi, wo, footprint, light


def run_cli(args, tmp_path, name="out.csv"):
    out = tmp_path / name
    subprocess.run([EXE, *args, "--out", str(out)], check=True, capture_output=True)
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def write_queries(path, wi, wo, footprint, light):
    cols = {"wi_x": wi[:, 0], "wi_y": wi[:, 1], "wi_z": wi[:, 2],
            "wo_x": wo[:, 0], "wo_y": wo[:, 1], "wo_z": wo[:, 2]}
    cols.update(footprint or {})
    cols.update(light or {})
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for i in range(len(wi)):
            w.writerow([repr(float(c[i])) for c in cols.values()])


MODELS = [m["name"] for m in glintlab.models()]


def model_info(name):
    return next(m for m in glintlab.models() if m["name"] == name)


def test_models_lists_every_registered_model_with_its_parameters():
    assert "smooth_ggx" in MODELS and len(MODELS) >= 9
    ggx = model_info("smooth_ggx")
    names = [p["name"] for p in ggx["params"]]
    assert names[:2] == ["alpha_x", "alpha_y"]
    assert ggx["params"][0]["range"] == "[0.0001, 100]"
    assert "D" in ggx["intermediates"]


@pytest.mark.parametrize("name", MODELS)
def test_eval_is_bit_identical_to_the_cli(name, tmp_path):
    wi, wo, footprint, light = queries(model_info(name))
    write_queries(tmp_path / "in.csv", wi, wo, footprint, light)
    cli = run_cli(["eval", "--model", name, "--in", str(tmp_path / "in.csv")], tmp_path)
    got = glintlab.eval(name, wi, wo, footprint=footprint, light=light)
    assert set(got) == {"value", "pdf", *model_info(name)["intermediates"]}
    for key, column in got.items():
        assert column.dtype == np.float64
        np.testing.assert_array_equal(column, cli[key], err_msg=f"{name} {key}")


@pytest.mark.parametrize("name", ["smooth_ggx", "chermain"])
def test_sample_with_n_and_seed_is_bit_identical_to_the_cli(name, tmp_path):
    model = model_info(name)
    wi = unit(np.array([0.3, -0.2, 0.9]))
    _, _, footprint, light = queries(model, rows=1)
    args = ["sample", "--model", name, "--wi", ",".join(repr(float(x)) for x in wi),
            "--n", "500", "--seed", "11"]
    one_row = {k: float(v[0]) for k, v in (footprint or {}).items()}
    if one_row:
        args += ["--query", ",".join(f"{k}={v!r}" for k, v in one_row.items())]
    cli = run_cli(args, tmp_path)
    got = glintlab.sample(name, wi, n=500, seed=11, footprint=one_row or None, light=light)
    for a, key in enumerate(["wo_x", "wo_y", "wo_z"]):
        np.testing.assert_array_equal(got["wo"][:, a], cli[key])
    np.testing.assert_array_equal(got["pdf"], cli["pdf"])
    np.testing.assert_array_equal(got["weight"], cli["weight"])
    np.testing.assert_array_equal(got["rejected"], cli["rejected"] != 0)


def test_sample_with_explicit_uniforms_matches_the_stream_it_replaces():
    wi = np.array([0.0, 0.0, 1.0])
    a = glintlab.sample("smooth_ggx", wi, n=100, seed=3)
    b = glintlab.sample("smooth_ggx", wi, n=100, seed=4)
    assert not np.array_equal(a["wo"], b["wo"])  # the seed is used
    rng = np.random.default_rng(0)
    u = rng.uniform(size=(100, 2))
    s = glintlab.sample("smooth_ggx", np.tile(wi, (100, 1)), u=u)
    assert s["wo"].shape == (100, 3)
    np.testing.assert_allclose(np.linalg.norm(s["wo"], axis=1), 1, atol=1e-12)


def test_arrays_of_the_right_dtype_and_layout_are_read_in_place():
    wi, wo, _, _ = queries(model_info("smooth_ggx"))
    f_order = np.asfortranarray(wi)
    at = glintlab._glintlab.column_addresses("smooth_ggx", f_order, wo)
    assert at["wi_x"] == f_order[:, 0].ctypes.data
    assert at["wi_z"] == f_order[:, 2].ctypes.data
    # C order: each column strided, not a contiguous column (the batches gather it block by
    # block, a numpy model's chunk gathers it); float32 gathered for double precision.
    assert at["wo_x"] is None
    f32 = np.asfortranarray(wi, dtype=np.float32)
    assert glintlab._glintlab.column_addresses("smooth_ggx", f32, wo)["wi_x"] is None
    at32 = glintlab._glintlab.column_addresses("smooth_ggx", f32, wo, precision="float")
    assert at32["wi_x"] == f32[:, 0].ctypes.data
    fp = {"u": np.linspace(0, 1, ROWS), "v": 0.5, "dudx": 1e-3, "dvdx": 0.0, "dudy": 0.0,
          "dvdy": 1e-3}
    at = glintlab._glintlab.column_addresses("chermain", wi, wo, footprint=fp)
    assert at["u"] == fp["u"].ctypes.data and at["v"] is None


def test_layout_and_dtype_do_not_change_the_result():
    wi, wo, _, _ = queries(model_info("smooth_ggx"))
    ref = glintlab.eval("smooth_ggx", wi, wo)["value"]
    for w in (np.asfortranarray(wi), wi[::-1][::-1], np.repeat(wi, 2, axis=0)[::2]):
        np.testing.assert_array_equal(glintlab.eval("smooth_ggx", w, wo)["value"], ref)
    f = glintlab.eval("smooth_ggx", wi.astype(np.float32), wo, precision="float")
    assert f["value"].dtype == np.float32
    np.testing.assert_allclose(f["value"], ref, rtol=1e-4)


def test_one_direction_broadcasts_to_every_row():
    _, wo, _, _ = queries(model_info("smooth_ggx"))
    wi = unit(np.array([0.2, 0.1, 1.0]))
    got = glintlab.eval("smooth_ggx", wi, wo)["value"]
    np.testing.assert_array_equal(got, glintlab.eval("smooth_ggx", np.tile(wi, (ROWS, 1)), wo)["value"])


def test_per_row_parameters_equal_one_call_per_value():
    wi, wo, _, _ = queries(model_info("smooth_ggx"))
    alpha = np.where(np.arange(ROWS) % 3 == 0, 0.2, 0.7)
    got = glintlab.eval("smooth_ggx", wi, wo, params={"alpha_x": alpha, "sampler": "ndf"})["pdf"]
    for a in (0.2, 0.7):
        rows = alpha == a
        one = glintlab.eval("smooth_ggx", wi[rows], wo[rows],
                            params={"alpha_x": a, "sampler": "ndf"})["pdf"]
        np.testing.assert_array_equal(got[rows], one)
    # A choice per row by its index.
    idx = np.arange(ROWS) % 2
    mixed = glintlab.eval("smooth_ggx", wi, wo, params={"sampler": idx})["pdf"]
    vndf = glintlab.eval("smooth_ggx", wi, wo, params={"sampler": "vndf"})["pdf"]
    np.testing.assert_array_equal(mixed[idx == 1], vndf[idx == 1])
    assert not np.array_equal(mixed[idx == 0], vndf[idx == 0])


def test_per_row_parameters_match_the_per_row_route_bit_for_bit():
    # Several chunks of 4096 rows; the rows of equal values are scattered, adjacent or all
    # different (lanes of one batch with different values, a per-row choice splitting a batch).
    # Each row must equal that row evaluated alone with its values as scalars, in both
    # precisions, eval and sample.
    rng = np.random.default_rng(11)
    n = 9000
    wi = unit(rng.normal(size=(n, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wo = unit(rng.normal(size=(n, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wi[:, 2] = np.abs(wi[:, 2])
    u = rng.uniform(0, 1, (n, 2))
    scattered = rng.choice([0.1, 0.3, 0.55, 0.9], size=n)
    adjacent = np.repeat([0.2, 0.6, 0.4], n // 3)
    distinct = rng.uniform(0.05, 1.5, size=n)
    sampler = rng.integers(0, 4, size=n)
    rows = np.concatenate([rng.choice(n, 40, replace=False), [0, 4095, 4096, n - 1]])
    for precision in ("double", "float"):
        for alpha in (scattered, adjacent, distinct):
            params = {"alpha_x": alpha, "alpha_y": scattered, "sampler": sampler}
            got = glintlab.eval("smooth_ggx", wi, wo, params=params, precision=precision)
            sam = glintlab.sample("smooth_ggx", wi, u=u, params=params, precision=precision)
            for i in rows:
                one = {"alpha_x": alpha[i], "alpha_y": scattered[i],
                       "sampler": ["ndf", "vndf", "spherical_caps", "bounded_caps"][sampler[i]]}
                ref = glintlab.eval("smooth_ggx", wi[i:i + 1], wo[i:i + 1], params=one,
                                    precision=precision)
                for k, v in ref.items():
                    assert got[k][i].tobytes() == v[0].tobytes(), (precision, k, i)
                ref = glintlab.sample("smooth_ggx", wi[i:i + 1], u=u[i:i + 1], params=one,
                                      precision=precision)
                for k, v in ref.items():
                    assert sam[k][i].tobytes() == v[0].tobytes(), (precision, k, i)


def test_the_input_check_over_the_batch_keeps_the_row_rules():
    # The check runs over each chunk's columns; a row on either side of the unit tolerance
    # (|length - 1| <= 1e-6), a non-finite value or a bad light in a later chunk, in C-ordered,
    # Fortran-ordered and float32 input, gives the row-by-row rule's verdict and message.
    rng = np.random.default_rng(12)
    n = 10000
    wi = unit(rng.normal(size=(n, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wo = unit(rng.normal(size=(n, 3)) * [1, 1, 0.5] + [0, 0, 1])
    inside = wo.copy()
    inside[5000] *= 1 + 0.9999e-6
    inside[6000] *= 1 - 0.9999e-6
    for w in (inside, np.asfortranarray(inside)):
        glintlab.eval("smooth_ggx", wi, w)  # no error
    outside = inside.copy()
    outside[8000] *= 1 + 1.0002e-6
    outside[9000, 2] = np.inf
    for w in (outside, np.asfortranarray(outside)):
        msg = error_of(glintlab.eval, "smooth_ggx", wi, w)
        assert msg.startswith("row 8000, columns wo_x,wo_y,wo_z (wo): direction") and \
            "not unit" in msg, msg
    outside[8000] = inside[8000]
    msg = error_of(glintlab.eval, "smooth_ggx", wi, outside.astype(np.float32), precision="float")
    assert msg.startswith("row 9000, wo[:, 2]: wo_z = inf is not finite"), msg
    model = next(m for m in glintlab.models() if "point light" in m["needs"])
    wi_, wo_, footprint, light = queries(model, rows=n, seed=3)
    light["light_cos_half_angle"] = light["light_cos_half_angle"].copy()
    light["light_cos_half_angle"][7001] = 1.5
    msg = error_of(glintlab.eval, model["name"], wi_, wo_, footprint=footprint, light=light)
    assert msg.startswith("row 7001, light['light_cos_half_angle']: 1.5 is out of range"), msg


def test_given_uniforms_are_checked_over_the_batch_with_the_row_rule():
    # sample(u=...): [0, 1) tested by a pass over each chunk; the row rule names the first bad row
    # (in a later chunk here), and the interval's ends are kept exactly (0 and the largest double
    # below 1 pass, 1 and NaN do not).
    rng = np.random.default_rng(13)
    n = 10000
    wi = unit(rng.normal(size=(n, 3)) * [1, 1, 0.5] + [0, 0, 1])
    u = rng.uniform(0, 1, (n, 2))
    u[4500, 0] = 0.0
    u[4600, 1] = np.nextafter(1.0, 0.0)
    for given in (u, np.asfortranarray(u)):
        glintlab.sample("smooth_ggx", wi, u=given)  # no error
    bad = u.copy()
    bad[8000, 1] = 1.0
    bad[9000, 0] = np.nan
    for given in (bad, np.asfortranarray(bad)):
        msg = error_of(glintlab.sample, "smooth_ggx", wi, u=given)
        assert msg.startswith("row 8000, ") and "1 is out of range (valid: [0, 1))" in msg, msg
    bad[8000, 1] = u[8000, 1]
    assert error_of(glintlab.sample, "smooth_ggx", wi, u=bad).startswith("row 9000, ")


def test_results_do_not_depend_on_the_thread_count():
    rng = np.random.default_rng(5)
    n = 20000  # several chunks of 4096 rows
    wi = unit(rng.normal(size=(n, 3)) * [1, 1, 0.3] + [0, 0, 1])
    wo = unit(rng.normal(size=(n, 3)) * [1, 1, 0.3] + [0, 0, 1])
    one = glintlab.eval("smooth_beckmann", wi, wo, threads=1)
    two = glintlab.eval("smooth_beckmann", wi, wo, threads=2)
    np.testing.assert_array_equal(one["value"], two["value"])
    s1 = glintlab.sample("smooth_ggx", wi[0], n=n, seed=2, threads=1)
    s2 = glintlab.sample("smooth_ggx", wi[0], n=n, seed=2, threads=2)
    np.testing.assert_array_equal(s1["wo"], s2["wo"])


def error_of(f, *args, **kwargs):
    with pytest.raises(ValueError) as e:
        f(*args, **kwargs)
    return str(e.value)


def test_bad_input_raises_value_error_naming_it_and_its_range():
    wi, wo, _, _ = queries(model_info("smooth_ggx"))
    ev = glintlab.eval
    assert "(valid: (N, 3) or (3,))" in error_of(ev, "smooth_ggx", wi[:, :2], wo)
    assert "the same row count" in error_of(ev, "smooth_ggx", wi[:5], wo)
    bad = wo.copy()
    bad[7, 0] = np.nan
    msg = error_of(ev, "smooth_ggx", wi, bad)
    assert "row 7" in msg and "wo_x = nan is not finite" in msg
    msg = error_of(ev, "smooth_ggx", wi, 2 * wo)
    assert "row 0" in msg and "not unit" in msg
    assert "no parameter 'alpha'" in error_of(ev, "smooth_ggx", wi, wo, params={"alpha": 0.1})
    assert "[0.0001, 100]" in error_of(ev, "smooth_ggx", wi, wo, params={"alpha_x": -1})
    per_row = np.full(ROWS, 0.5)
    per_row[9] = 1e3
    msg = error_of(ev, "smooth_ggx", wi, wo, params={"alpha_x": per_row})
    assert "params['alpha_x'] row 9" in msg and "out of range" in msg
    assert "one of: ndf" in error_of(ev, "smooth_ggx", wi, wo, params={"sampler": "nope"})
    assert "valid: smooth_ggx" in error_of(ev, "no_such_model", wi, wo) or \
        "smooth_ggx" in error_of(ev, "no_such_model", wi, wo)
    assert "missing query column(s) u" in error_of(ev, "chermain", wi, wo)
    assert "unknown column 'w'" in error_of(ev, "chermain", wi, wo, footprint={"w": 0.0})
    assert "--isa" in error_of(ev, "smooth_ggx", wi, wo, isa="mmx")
    assert "--precision" in error_of(ev, "smooth_ggx", wi, wo, precision="half")
    assert "--threads" in error_of(ev, "smooth_ggx", wi, wo, threads=-1)
    assert "dtype" in error_of(ev, "smooth_ggx", wi.astype(complex), wo)
    sm = glintlab.sample
    assert "give exactly one" in error_of(sm, "smooth_ggx", wi)
    assert "[0, 1)" in error_of(sm, "smooth_ggx", wi, u=np.full((ROWS, 2), 1.0))
    assert "n:" in error_of(sm, "smooth_ggx", wi[0], n=0)


def test_the_models_own_rules_are_checked():
    wi, wo, footprint, light = queries(model_info("podee"))
    wo[3] = unit(np.array([0.5, 0.0, -0.1]))
    assert "row 3" in error_of(glintlab.eval, "podee", wi, wo, footprint=footprint, light=light)


def test_no_silent_nan_for_valid_queries():
    for name in MODELS:
        wi, wo, footprint, light = queries(model_info(name), seed=9)
        got = glintlab.eval(name, wi, wo, footprint=footprint, light=light)
        assert np.all(np.isfinite(got["value"])) and np.all(np.isfinite(got["pdf"])), name


def test_help_documents_every_argument():
    doc = glintlab.eval.__doc__
    for word in ("wi, wo", "params", "footprint", "light", "precision", "isa", "threads"):
        assert word in doc
    assert "bit-identical" in glintlab.sample.__doc__


def test_the_example_script_runs_and_writes_its_figure(tmp_path):
    script = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python", "lobes.py")
    out = tmp_path / "lobes.png"
    subprocess.run([sys.executable, script, str(out)], check=True, capture_output=True)
    assert out.stat().st_size > 10000


def test_load_plugin_registers_its_models_and_refuses_a_non_plugin():
    bad = os.environ.get("GLINTLAB_TEST_NOT_A_PLUGIN")
    good = os.environ.get("GLINTLAB_TEST_PLUGIN")
    if not (bad and good):
        pytest.skip("GLINTLAB_TEST_PLUGIN / GLINTLAB_TEST_NOT_A_PLUGIN not set (ctest sets them)")
    assert "load_plugin" in error_of(glintlab.load_plugin, bad)
    names = glintlab.load_plugin(good)
    assert names and all(n in [m["name"] for m in glintlab.models()] for n in names)
    model = model_info(names[0])
    wi, wo, footprint, light = queries(model)
    got = glintlab.eval(names[0], wi, wo, footprint=footprint, light=light)
    assert np.all(np.isfinite(got["value"]))
