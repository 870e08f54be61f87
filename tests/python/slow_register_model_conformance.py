"""The conformance suite on models registered from numpy (ctest python.register_model_conformance;
the suite calls the numpy functions once per chunk of queries where it has many, so a quick run of
all of a numpy Lambertian's properties takes seconds, where one call per query took minutes). A
correct Lambertian holds every property that applies to it, each control rejected; a Lambertian
whose pdf is 3 % above its sampler's density fails sampler-matches-pdf, its corrected control
holds.

The suites run on one thread: a numpy model is called with the GIL held, so a second worker
thread only waits for it (each call hands the GIL between the threads: about twice the CPU, most
of it the kernel's, for the same rows; the results are the same for any thread count). A numpy
model called from two worker threads: test_register_model.py."""

import glintlab
import numpy_models as nm


def test_correct_lambertian_holds_everything_applicable():
    nm.register_lambert(glintlab, "py_lambert_suite")
    rows = glintlab.verify("model.py_lambert_suite.*", budget="quick", threads=1)
    verdicts = {r["id"].split(".")[-1]: r["verdict"] for r in rows}
    assert verdicts == {
        "eval-pdf-consistency": "holds", "sampler-matches-pdf": "holds",
        "sampler-covers-value": "holds", "pdf-normalized": "holds", "energy": "holds",
        # No float or SIMD instantiation to compare with the double thunks.
        "float-vs-double": "not-claimed", "simd-equivalence": "not-claimed",
        "stability": "holds"}, rows
    for r in rows:
        if r["verdict"] != "not-claimed":
            assert r["control_rejected"] is True, r
    # The control of a property that holds is a model wrong near the truth: it fails.
    control = {r["id"].split(".")[-1]: r["control_verdict"] for r in rows}
    assert control["eval-pdf-consistency"] == "fails", rows


def test_pdf_three_percent_high_fails_sampler_matches_pdf():
    nm.register_wrong_pdf(glintlab, "py_lambert_wrong_pdf")
    (row,) = glintlab.verify("model.py_lambert_wrong_pdf.sampler-matches-pdf", budget="quick",
                             threads=1)
    assert row["verdict"] == "fails", row
    assert row["control_verdict"] == "holds" and row["control_rejected"] is True, row


def test_sweep_compare_and_the_registry_figure_include_a_numpy_model(tmp_path):
    """glintlab.sweep, compare and figure("models-hemisphere") run in this process, so a model
    registered from numpy is swept, compared beside a paper's model and drawn (seconds: the sweep
    calls it once per query). The
    figure draws every model registered in the process, so this file runs in its own process
    (ctest), away from the broken models of the other test files."""
    sampled_rows = []  # rows per call of the sampler

    def counted_sample(q, u, p):
        sampled_rows.append(len(u))
        return nm.lambert_sample(q, u, p)

    glintlab.register_model("py_lambert_drawn", nm.lambert_eval, nm.lambert_pdf, counted_sample,
                            params=[nm.ALBEDO], description="Lambertian in numpy",
                            source="cosine-weighted hemisphere sampling (Malley's method)")
    # Beside it a paper's model with few maps (smooth_beckmann: 20, smooth_ggx 40): matplotlib
    # draws them all, about 0.1 s a map; the paper's models' maps are checked in the CLI's tests.
    s = glintlab.sweep(out=tmp_path / "sw", models="smooth_beckmann,py_lambert_drawn",
                       budget="quick")
    assert [(m["model"], m["verdict"]) for m in s["stability"]["models"]
            if m["model"] == "py_lambert_drawn"] == [("py_lambert_drawn", "holds")], s["stability"]
    assert any(rel.startswith("py_lambert_drawn/") and rel.endswith(".csv") for rel in s["data"])
    fig = glintlab.figure("models-hemisphere", tmp_path / "figs", budget="quick")
    assert {"py_lambert_drawn.exr", "py_lambert_drawn.png"} <= set(fig["files"])
    table = fig["data"]["models_hemisphere.csv"]
    (row,) = table[table["model"] == "py_lambert_drawn"]
    # The Lambertian's albedo is its default 0.8; the estimate is a pixel sum over the hemisphere.
    assert abs(row["albedo_estimate"] - 0.8) < 0.02 and row["nonfinite_pixels"] == 0
    # Compared beside a paper's model: its recorded verdicts are none (an empty claims.json) and
    # its failure regions are read from the sweep above.
    (tmp_path / "claims").mkdir()
    sampled_rows.clear()
    (tmp_path / "claims" / "claims.json").write_text("[]\n")
    c = glintlab.compare(out=tmp_path / "cmp", models=["smooth_beckmann", "py_lambert_drawn"],
                         budget="quick", claims_from=tmp_path / "claims",
                         sweeps_from=tmp_path / "sw")
    assert list(c["table"]["model"]) == ["smooth_beckmann", "py_lambert_drawn"]
    assert set(c["equal_time"]["model"]) == {"smooth_beckmann", "py_lambert_drawn"}
    mine = c["table"][c["table"]["model"] == "py_lambert_drawn"][0]
    assert mine["reference_converged"] == "yes" and mine["stability"] == "default: holds", mine
    assert {"index.html", "equal_time.png"} <= set(c["files"])
    # The equal-time curve calls the sampler once per estimate (an untimed warm-up of 1024
    # samples, then 2 scenes × 8 repetitions of each N = 1, 4, …, 1024), never once per sample.
    assert sorted(sampled_rows) == sorted([1024] + [4**k for k in range(6) for _ in range(16)])
