"""A glint model prototyped in numpy, registered with glintlab and judged by its conformance suite.

The model ("facet cells"): the surface is a grid of cells, each holding `facets` facets per unit
uv area; a pixel footprint of area A sees K = clamp(round(A * facets), 1, 16) of them, those of
the grid cell (sized to hold K facets) that contains the footprint's centre. Each facet's normal
is a Beckmann draw of roughness `alpha`, fixed by a hash of its cell and index, and reflects into
a narrow von Mises-Fisher lobe of concentration `kappa` around the mirror direction. The pdf is
the mixture of the K lobes; the value is albedo times the pdf above the horizon, so the sampler
(pick a facet, sample its lobe) has weight albedo there. Small footprints give a few sharp
glints, large ones a smoother, rougher lobe.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/my_glint_model.py \
        [--out my_glint_model.png] [--properties '*' | eval-pdf-consistency,stability,...] \
        [--compare-with smooth_ggx,deliot_belcour | ''] [--compare-out DIR] [--compare-papers-only]

Prints the verdicts of the conformance checks asked for (all of them by default), writes three
labelled plots, then compares the model beside the papers' models named by --compare-with with
glintlab.compare (quick budget), prints a table of its rows and the path of its index.html.
The suite calls the model's functions once per chunk of queries where it has many (samples,
integrals) and once per query elsewhere (the stability sweep: for this model 0.3 ms an
eval, 1.7 ms a sample); all properties took 131 s on a busy 2-core machine, the stability sweep
most of it (eval-pdf-consistency and stability alone: 109 s). One query per call everywhere took
over half an hour. The comparison calls the model once per chunk of directions for its reference
albedo too: the model beside smooth_ggx took 18 s (a 2-core machine shared with other work),
where one call per direction had taken about 180 s; --compare-papers-only leaves the model out of
the comparison.
"""

import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import glintlab  # noqa: E402

MAX_FACETS = 16
NAME = "facet_cells"


def hash_uniform(a, b, c, salt):
    """A uniform in [0, 1) from three integer arrays (splitmix64 of their mix)."""
    with np.errstate(over="ignore"):
        x = (a.astype(np.uint64) * np.uint64(0x9E3779B97F4A7C15)
             ^ b.astype(np.uint64) * np.uint64(0xBF58476D1CE4E5B9)
             ^ c.astype(np.uint64) * np.uint64(0x94D049BB133111EB)
             ^ np.uint64(salt))
        x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        x = x ^ (x >> np.uint64(31))
    return (x >> np.uint64(11)).astype(np.float64) / 2.0**53


def facets(q, p):
    """The footprint's facet count K (N,) and the mirror directions of its facets (N, 16, 3)."""
    area = np.abs(q["dudx"] * q["dvdy"] - q["dvdx"] * q["dudy"])
    k = np.clip(np.round(area * p["facets"]), 1, MAX_FACETS)
    cells_per_unit = np.sqrt(p["facets"] / k)
    cu = np.floor(q["u"] * cells_per_unit).astype(np.int64)[:, None]
    cv = np.floor(q["v"] * cells_per_unit).astype(np.int64)[:, None]
    index = np.arange(MAX_FACETS)[None, :]
    xi1, xi2 = hash_uniform(cu, cv, index, 1), hash_uniform(cu, cv, index, 2)
    tan_theta = p["alpha"] * np.sqrt(-np.log1p(-xi1))  # Beckmann slope magnitude
    phi = 2 * np.pi * xi2
    cos_t = 1 / np.sqrt(1 + tan_theta**2)
    sin_t = tan_theta * cos_t
    m = np.stack([sin_t * np.cos(phi), sin_t * np.sin(phi), cos_t], axis=-1)
    wi = np.stack([q["wi_x"], q["wi_y"], q["wi_z"]], axis=-1)[:, None, :]
    r = 2 * np.sum(wi * m, axis=-1, keepdims=True) * m - wi
    return k, r


def lobe_pdf(r, wo, kappa):
    """von Mises-Fisher density on the sphere around r (..., 3) at wo."""
    norm = kappa / (2 * np.pi * -np.expm1(-2 * kappa))
    return norm * np.exp(kappa * (np.sum(r * wo, axis=-1) - 1))


def pdf(q, p):
    k, r = facets(q, p)
    wo = np.stack([q["wo_x"], q["wo_y"], q["wo_z"]], axis=-1)[:, None, :]
    used = np.arange(MAX_FACETS)[None, :] < k[:, None]
    return np.sum(np.where(used, lobe_pdf(r, wo, p["kappa"]), 0.0), axis=1) / k


def value(q, p):
    return np.where(q["wo_z"] > 0, p["albedo"] * pdf(q, p), 0.0)


def sample(q, u, p):
    k, r = facets(q, p)
    chosen = np.minimum(np.floor(u[:, 0] * k), k - 1).astype(np.int64)
    u1 = np.clip(u[:, 0] * k - chosen, 0.0, 1.0)
    mu = r[np.arange(len(k)), chosen]
    kappa = p["kappa"]
    with np.errstate(divide="ignore"):
        w = 1 + np.log(u1 + (1 - u1) * np.exp(-2 * kappa)) / kappa
    w = np.clip(w, -1.0, 1.0)
    # An orthonormal frame around mu.
    helper = np.where(np.abs(mu[:, 2:3]) < 0.9, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    t = np.cross(helper, mu)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    b = np.cross(mu, t)
    phi = 2 * np.pi * u[:, 1]
    s = np.sqrt(np.maximum(0.0, 1 - w * w))[:, None]
    wo = w[:, None] * mu + s * (np.cos(phi)[:, None] * t + np.sin(phi)[:, None] * b)
    wo /= np.linalg.norm(wo, axis=1, keepdims=True)
    at = dict(q, wo_x=wo[:, 0], wo_y=wo[:, 1], wo_z=wo[:, 2])
    density = pdf(at, p)
    weight = np.where(wo[:, 2] > 0, p["albedo"], 0.0)
    return {"wo": wo, "pdf": density, "weight": weight}


def register():
    glintlab.register_model(
        NAME, value, pdf, sample, needs=["footprint"],
        params=[
            {"name": "alpha", "default": 0.3, "lo": 0.01, "hi": 1,
             "description": "Beckmann roughness of the facet normals"},
            {"name": "facets", "default": 2e5, "lo": 1, "hi": 1e9,
             "description": "facets per unit uv area"},
            {"name": "kappa", "default": 500, "lo": 1, "hi": 1e5,
             "description": "concentration of each facet's reflection lobe"},
            {"name": "albedo", "default": 0.9, "lo": 0, "hi": 1,
             "description": "reflected fraction"}],
        not_claimed={"constant-time": "a numpy prototype called one query at a time: its cost "
                                      "is Python's per call, not the model's"},
        description="facet cells: K Beckmann facets per footprint, each a vMF lobe (numpy)",
        source="examples/python/my_glint_model.py")


def footprint(side, rows):
    return {"u": np.full(rows, 0.37), "v": np.full(rows, 0.61), "dudx": side, "dvdx": 0.0,
            "dudy": 0.0, "dvdy": side}


def plots(out):
    theta_i = np.radians(30.0)
    wi = np.array([np.sin(theta_i), 0.0, np.cos(theta_i)])
    theta_o = np.radians(np.linspace(-89, 89, 713))
    wo = np.stack([-np.sin(theta_o), np.zeros_like(theta_o), np.cos(theta_o)], axis=1)
    fig, (lobe, dens, hist) = plt.subplots(1, 3, figsize=(16, 4.4))
    for side in [1e-3, 5e-3]:
        r = glintlab.eval(NAME, wi, wo, footprint=footprint(side, len(wo)))
        k = int(np.clip(round(side * side * 2e5), 1, MAX_FACETS))
        lobe.plot(np.degrees(theta_o), r["value"], label=f"{NAME}, footprint side {side:g} ({k} facets)")
        dens.plot(np.degrees(theta_o), r["pdf"], label=f"{NAME} pdf, footprint side {side:g}")
    smooth = glintlab.eval("smooth_beckmann", wi, wo, params={"alpha_x": 0.3, "alpha_y": 0.3})
    lobe.plot(np.degrees(theta_o), smooth["value"], "k--", label="smooth_beckmann, alpha 0.3")
    lobe.set_title("value in the plane of incidence, theta_i = 30 deg")
    lobe.set_xlabel("theta_o (degrees; positive: the mirror side)")
    lobe.set_ylabel("value f cos (1/sr)")
    lobe.legend(fontsize=7)
    dens.set_title("pdf in the plane of incidence")
    dens.set_xlabel("theta_o (degrees; positive: the mirror side)")
    dens.set_ylabel("pdf (1/sr)")
    dens.legend(fontsize=7)

    # The sampler against its pdf: histogram of sampled cos theta_o against the pdf integrated
    # over the same bins (uniform sphere directions weighted by pdf * 4 pi).
    n = 200000
    fp = footprint(5e-3, n)
    s = glintlab.sample(NAME, wi, n=n, seed=1, footprint=fp)
    edges = np.linspace(-1, 1, 81)
    counts, _ = np.histogram(s["wo"][:, 2], bins=edges)
    rng = np.random.default_rng(2)
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    expected, _ = np.histogram(d[:, 2], bins=edges,
                               weights=glintlab.eval(NAME, wi, d, footprint=fp)["pdf"] * 4 * np.pi / n)
    centres = 0.5 * (edges[1:] + edges[:-1])
    hist.step(centres, counts / n, where="mid", label="sampled (200000 samples)")
    hist.plot(centres, expected, "o", ms=3, label="pdf integrated over the bin (Monte Carlo)")
    hist.set_title(f"{NAME} sampler vs pdf, footprint side 0.005")
    hist.set_xlabel("cos theta_o")
    hist.set_ylabel("fraction of samples per bin")
    hist.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def compare(model_claims, papers, include_model, out):
    """The numpy model beside the papers' models `papers`, as `glintlab compare` draws them
    (quick budget). Its conformance verdicts are the rows just measured, written where compare
    reads them (claims_from); the papers' models not measured here show their recorded verdicts.
    The stability maps are swept for the papers' models only: the sweep calls a numpy model once
    per query (minutes); the numpy model's stability verdict, when measured, is among its
    conformance verdicts."""
    verdicts = out + "-verdicts"
    os.makedirs(verdicts, exist_ok=True)
    with open(os.path.join(verdicts, "claims.json"), "w") as f:
        json.dump(model_claims, f, indent=1)
    sweeps = glintlab.sweep(out + "-sweeps", models=papers, budget="quick")
    c = glintlab.compare(out, models=([NAME] if include_model else []) + papers, budget="quick",
                         claims_from=verdicts, sweeps_from=sweeps["dir"])
    print(f"\n{'model':<16} {'ns/eval':>10} {'rel. RMSE @1024':>15} {'rel. bias':>17}  "
          f"conformance; stability")
    for row in c["table"]:
        bias = f"{row['relative_bias']:+.4f}±{row['relative_bias_se']:.4f}"
        print(f"{row['model']:<16} {row['best_ns_per_eval']:>10.4g} "
              f"{row['relative_rmse_at_max_samples']:>15.4g} {bias:>17}  "
              f"{row['conformance']}; {row['stability']}")
    print(f"compare: {c['files']['index.html']}")
    return c


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="my_glint_model.png")
    parser.add_argument("--properties", default="*",
                        help="comma-separated conformance properties to run, '*' for all")
    parser.add_argument("--budget", default="quick")
    parser.add_argument("--compare-with", default="smooth_ggx,deliot_belcour",
                        help="comma-separated papers' models to compare the model with "
                             "(glintlab.models()), at the quick budget; '' skips the comparison")
    parser.add_argument("--compare-out", default=None,
                        help="compare's output folder (default: --out's name with _compare)")
    parser.add_argument("--compare-papers-only", action="store_true",
                        help="leave the numpy model out of the comparison (compares the papers' "
                             "models only)")
    args = parser.parse_args()
    register()
    claims = ",".join(f"model.{NAME}.{p}" for p in args.properties.split(","))
    rows = glintlab.verify(claims, budget=args.budget)
    for row in rows:
        print(f"{row['id']:<45} {row['verdict']:<12} control {row['control_verdict']}: {row['detail']}")
    plots(args.out)
    print(f"plots: {args.out}")
    papers = [m for m in args.compare_with.split(",") if m]
    if papers:
        compare(rows, papers, not args.compare_papers_only,
                args.compare_out or os.path.splitext(args.out)[0] + "_compare")


if __name__ == "__main__":
    main()
