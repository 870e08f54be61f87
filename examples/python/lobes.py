"""glintlab from Python, notebook style: evaluate two models on the plane of incidence, check the
sampler's density against pdf with a histogram, and plot both with matplotlib.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/lobes.py out.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import glintlab  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "lobes.png"

# Directions in the plane of incidence: wi at 40 degrees, wo swept over [-89, 89] degrees.
theta_i = np.radians(40.0)
theta_o = np.radians(np.linspace(-89, 89, 357))
wi = np.array([np.sin(theta_i), 0.0, np.cos(theta_i)])
wo = np.stack([-np.sin(theta_o), np.zeros_like(theta_o), np.cos(theta_o)], axis=1)

fig, (lobe, hist) = plt.subplots(1, 2, figsize=(11, 4.2))
for name, params in [("smooth_ggx", {"alpha_x": 0.3, "alpha_y": 0.3}),
                     ("smooth_beckmann", {"alpha_x": 0.3, "alpha_y": 0.3})]:
    r = glintlab.eval(name, wi, wo, params=params)
    lobe.plot(np.degrees(theta_o), r["value"], label=f"{name} value")
    lobe.plot(np.degrees(theta_o), r["pdf"], "--", label=f"{name} pdf")
lobe.set_title("smooth_ggx and smooth_beckmann, alpha = 0.3, theta_i = 40 deg")
lobe.set_xlabel("theta_o in the plane of incidence (degrees)")
lobe.set_ylabel("value f cos (1/sr), pdf (1/sr)")
lobe.legend()

# The sampler against its pdf: the counter-based stream of `glintlab sample --n --seed`.
s = glintlab.sample("smooth_ggx", wi, n=200000, seed=1, params={"alpha_x": 0.3, "alpha_y": 0.3})
kept = ~s["rejected"]
cos_o = s["wo"][kept, 2]
edges = np.linspace(0, 1, 41)
counts, _ = np.histogram(cos_o, bins=edges)
# Density in cos(theta_o), integrated over azimuth: counts / (n * bin width).
hist.stairs(counts / (len(s["pdf"]) * np.diff(edges)), edges, label="samples")
mid = 0.5 * (edges[1:] + edges[:-1])
phi = np.linspace(-np.pi, np.pi, 256, endpoint=False)
ct, ph = np.meshgrid(mid, phi, indexing="ij")
st = np.sqrt(1 - ct**2)
grid = np.stack([st * np.cos(ph), st * np.sin(ph), ct], axis=-1).reshape(-1, 3)
pdf = glintlab.eval("smooth_ggx", wi, grid, params={"alpha_x": 0.3, "alpha_y": 0.3})["pdf"]
hist.plot(mid, pdf.reshape(ct.shape).mean(axis=1) * 2 * np.pi, label="pdf integrated over phi")
hist.set_title("smooth_ggx sampler (vndf) against its pdf, 2e5 samples")
hist.set_xlabel("cos theta_o (unitless)")
hist.set_ylabel("density per unit cos theta_o")
hist.legend()
fig.tight_layout()
fig.savefig(out, dpi=100)
print(f"lobes: wrote {out}")
