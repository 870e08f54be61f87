"""Charts the report draws itself with matplotlib, and the manifest of every chart it drew.

Every chart is saved through `save`, which reads back from the matplotlib figure what a reader
needs (figure and axes titles, axis labels, legend, colour scale of a map) into a manifest entry;
make_report.py writes the entries to plots/plots.json and the browser test
(tests/reports/browser_test.py) fails on a chart whose axes lack labels, title, legend or, for a
map, its colour scale.

Stability maps: one chart per model / sampler / plane (a swept parameter x the incidence angle),
one heatmap panel per quantity drawn from the plane's CSV (every number per cell, written by
`glintlab sweep`), its cells flagged as failing outlined in red, a colour bar per panel and the
parameter values on both axes.
"""

import math

ZERO = 1e-300


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def describe(fig):
    """The manifest's view of a figure: its title and, per visible data axes, title, labels,
    whether it has a legend (its own or the figure's) and, for a map, a colour bar."""
    suptitle = fig._suptitle.get_text() if getattr(fig, "_suptitle", None) else ""
    colorbars = [a for a in fig.axes if a.get_label() == "<colorbar>"]
    axes = []
    for ax in fig.axes:
        if not ax.get_visible() or ax.get_label() == "<colorbar>":
            continue
        is_map = bool(ax.images) or any(type(c).__name__ == "QuadMesh" for c in ax.collections)
        render = bool(getattr(ax, "_render_panel", False))
        axes.append({"title": ax.get_title() or suptitle, "xlabel": ax.get_xlabel(),
                     "ylabel": ax.get_ylabel(),
                     "legend": ax.get_legend() is not None or bool(fig.legends),
                     # a rendered image (a figure's panel), not a map of data: no colour scale
                     "render": render,
                     "map": is_map and not render,
                     # a colour bar beside this map (matplotlib makes it an axes of its own)
                     "colorbar": is_map and any(getattr(c, "_colorbar_of", None) is ax
                                                for c in colorbars)})
    return {"title": suptitle or (axes[0]["title"] if axes else ""), "axes": axes}


def colorbar(fig, mappable, ax, label):
    cb = fig.colorbar(mappable, ax=ax, fraction=0.05, pad=0.02)
    cb.set_label(label, fontsize=7)
    cb.ax.tick_params(labelsize=6)
    cb.ax._colorbar_of = ax
    return cb


def save(fig, path, relpath, manifest, dpi=110):
    """Saves a chart, records it in the manifest (relpath: its path in the report) with, per
    rendered panel, the pixels of its image and the size it is drawn at in the saved chart, so
    that the browser test can tell how large a reader sees it."""
    entry = describe(fig)
    entry["file"] = relpath
    fig.savefig(path, dpi=dpi, format="png", metadata={"Software": None})
    # After drawing: the axes' box is the one the image's aspect made (a fraction of the figure,
    # which savefig writes at figsize x dpi pixels).
    w_in, h_in = fig.get_size_inches()
    visible = [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]
    for ax, a in zip(visible, entry["axes"]):
        if a["render"] and ax.images:
            shape = ax.images[0].get_array().shape
            box = ax.get_position()
            a["image_px"] = [int(shape[1]), int(shape[0])]
            a["drawn_px"] = [round(box.width * w_in * dpi, 1), round(box.height * h_in * dpi, 1)]
    pyplot().close(fig)
    manifest.append(entry)


# ----------------------------------------------------------------------------------------------
# Stability maps

# quantity -> (label of the colour, value of a cell from its CSV row, whether the cell fails,
#              logarithmic colour scale)
def _max_prefixed(prefix):
    def get(row):
        vals = [v for k, v in row.items() if k.startswith(prefix) and k.endswith("_fraction")]
        return max(vals) if vals else 0.0
    return get


STABILITY_QUANTITIES = {
    "nan": ("NaN fraction of calls (max over value, pdf, sample; double, float) [1]",
            _max_prefixed("nan_"), lambda r: _max_prefixed("nan_")(r) > 0, False),
    "inf": ("Inf fraction of calls (max over value, pdf, sample; double, float) [1]",
            _max_prefixed("inf_"), lambda r: _max_prefixed("inf_")(r) > 0, False),
    "negative": ("negative fraction of calls (max over value, pdf, sample) [1]",
                 _max_prefixed("negative_"), lambda r: _max_prefixed("negative_")(r) > 0, False),
    "energy_gain": ("white-furnace albedo [1] (fails: gain > 1 beyond 4 s.e.)",
                    lambda r: r.get("albedo", math.nan), lambda r: r.get("energy_gain", 0) > 0,
                    False),
    "p_gt_1": ("largest probability p seen [1] (fails: p > 1)", lambda r: r.get("p_max", math.nan),
               lambda r: r.get("p_gt_1_fraction", 0) > 0, False),
    "variance": ("Var(w)/E(w)^2 of the sample weight at a fixed position [1] "
                 "(fails: > 81.92)",
                 lambda r: r.get("relative_variance", math.nan),
                 lambda r: r.get("variance_blowup", 0) > 0, True),
}
STABILITY_NEEDED = ("row_index", "column_index", "theta_i_deg")
AXIS_UNITS = {"alpha": "alpha (GGX/Beckmann roughness) [1]",
              "anisotropy": "anisotropy alpha_x / alpha_y [1]",
              "density": "glint density [1]", "microroughness": "microroughness [1]",
              "footprint": "footprint size [1]", "light_size": "light half-angle [deg]"}


def _num(cell):
    try:
        return float(cell)
    except ValueError:
        return math.nan


def _ticks(values, n=6):
    """Tick positions (cell indices) and labels (the parameter values) of one axis."""
    if len(values) <= n:
        idx = list(range(len(values)))
    else:
        idx = sorted({round(k * (len(values) - 1) / (n - 1)) for k in range(n)})
    return idx, [f"{values[i]:.5g}" for i in idx]


def stability_chart(title, plane, header, rows, quantities, path, relpath, manifest, subtitle):
    """One panel per quantity of one plane: heatmap of the CSV's cells with the parameter values
    on the axes, a colour bar and the failing cells outlined. Returns the failing cell count per
    quantity."""
    import numpy as np
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.patches import Patch, Rectangle

    plt = pyplot()
    recs = [{h: _num(c) for h, c in zip(header, r)} for r in rows]
    nrow = int(max(r["row_index"] for r in recs)) + 1
    ncol = int(max(r["column_index"] for r in recs)) + 1
    row_vals, col_vals = [math.nan] * nrow, [math.nan] * ncol
    for r in recs:
        row_vals[int(r["row_index"])] = r.get(plane, math.nan)
        col_vals[int(r["column_index"])] = r["theta_i_deg"]
    qs = [q for q in quantities if q in STABILITY_QUANTITIES]
    cols = min(3, len(qs)) or 1
    nrows = (len(qs) + cols - 1) // cols or 1
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.3 * nrows + 0.8), squeeze=False)
    for ax in axes.flat[len(qs):]:
        ax.set_visible(False)
    failing = {}
    for ax, q in zip(axes.flat, qs):
        label, get, fails, log = STABILITY_QUANTITIES[q]
        grid = np.full((nrow, ncol), np.nan)
        bad = np.zeros((nrow, ncol), dtype=bool)
        for r in recs:
            i, j = int(r["row_index"]), int(r["column_index"])
            grid[i, j] = get(r)
            bad[i, j] = fails(r)
        finite = grid[np.isfinite(grid)]
        if log:
            pos = finite[finite > 0]
            lo = pos.min() if pos.size else 1e-3
            hi = max(pos.max() if pos.size else 1.0, lo * 10)
            norm = LogNorm(vmin=lo, vmax=hi)
            grid = np.where(grid > 0, grid, lo)
        else:
            lo = float(finite.min()) if finite.size else 0.0
            hi = float(finite.max()) if finite.size else 1.0
            if hi <= lo:
                lo, hi = lo - 0.5 if lo else 0.0, hi + 0.5 if hi else 1.0
            norm = Normalize(vmin=lo, vmax=hi)
        mesh = ax.pcolormesh(np.arange(ncol + 1) - 0.5, np.arange(nrow + 1) - 0.5,
                             np.ma.masked_invalid(grid), cmap="viridis", norm=norm,
                             shading="flat")
        for i, j in zip(*np.nonzero(bad)):
            ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, edgecolor="red",
                                   lw=1.4, hatch="///"))
        failing[q] = int(bad.sum())
        colorbar(fig, mesh, ax, label.split(" (")[0] if len(label) > 40 else label)
        xi, xl = _ticks(col_vals)
        yi, yl = _ticks(row_vals)
        ax.set_xticks(xi)
        ax.set_xticklabels(xl, fontsize=6)
        ax.set_yticks(yi)
        ax.set_yticklabels(yl, fontsize=6)
        ax.set_xlabel("incidence angle theta_i [deg]", fontsize=7)
        ax.set_ylabel(AXIS_UNITS.get(plane, f"{plane} [1]"), fontsize=7)
        ax.set_title(f"{q}: {label}\n{failing[q]} of {nrow * ncol} cells fail", fontsize=7)
    fig.suptitle(f"{title}, plane {plane} x theta_i\n{subtitle}", fontsize=9)
    fig.legend(handles=[Patch(facecolor="none", edgecolor="red", hatch="///",
                              label="failure region (cells flagged by the sweep)")],
               loc="lower center", fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, 0.04, 1, 0.95))
    save(fig, path, relpath, manifest, dpi=100)
    return failing


# ----------------------------------------------------------------------------------------------
# Montage PNGs of a figure, drawn as labelled panels from their NAME.panels.json
# (experiments/figures/panel_layout.h)

def _srgb_to_linear(v):
    import numpy as np
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def panel_tiles(image, layout):
    """The panels of a montage image (H x W x C array), row by row from the top left; None when
    the image's size does not fit the layout's grid."""
    n, cols, gap = len(layout["labels"]), int(layout["columns"]), int(layout.get("gap", 0))
    if n == 0 or cols <= 0:
        return None
    rows = (n + cols - 1) // cols
    h, w = image.shape[0], image.shape[1]
    if (w - gap * (cols - 1)) % cols or (h - gap * (rows - 1)) % rows:
        return None
    tw, th = (w - gap * (cols - 1)) // cols, (h - gap * (rows - 1)) // rows
    return [image[(k // cols) * (th + gap):(k // cols) * (th + gap) + th,
                  (k % cols) * (tw + gap):(k % cols) * (tw + gap) + tw] for k in range(n)]


def panel_chart(png, layout, path, relpath, manifest, subtitle):
    """A figure's montage as one labelled panel per tile, each enlarged (nearest pixel): renders
    with pixel axes, maps (layout "axes") with their parameter axes and a colour bar of the value
    recovered from the 8-bit preview. Returns False when the layout does not fit the image."""
    import matplotlib.image
    import numpy as np
    image = matplotlib.image.imread(png)
    tiles = panel_tiles(image, layout)
    if tiles is None:
        return False
    plt = pyplot()
    cols = min(int(layout["columns"]), len(tiles))
    th, tw = tiles[0].shape[0], tiles[0].shape[1]
    # A row of wide panels too long for its height (six 16:11 frames) is drawn in two, so that each
    # panel keeps a readable height in the page.
    while cols % 2 == 0 and cols * tw > 7 * th:
        cols //= 2
    rows = (len(tiles) + cols - 1) // cols
    aspect = min(2.0, max(0.5, th / tw))
    fig, axes = plt.subplots(rows, cols, squeeze=False,
                             figsize=(max(6.5, 2.7 * cols + 0.6), 2.7 * aspect * rows + 1.0))
    for ax in axes.flat[len(tiles):]:
        ax.set_visible(False)
    spec = layout.get("axes")
    for ax, tile, label in zip(axes.flat, tiles, layout["labels"]):
        ax.set_title(label, fontsize=7)
        ax.tick_params(labelsize=6)
        if spec:
            value = _srgb_to_linear(tile[..., 0]) / float(spec["exposure"])
            x0, x1 = spec["x_range"]
            y0, y1 = spec["y_range"]
            im = ax.imshow(value, cmap="magma", interpolation="nearest", aspect="auto",
                           extent=(x0, x1, y0, y1), vmin=0, vmax=1 / float(spec["exposure"]))
            colorbar(fig, im, ax, spec["value_label"] + " (8-bit preview, clipped at the top)")
            ax.set_xlabel(spec["x_label"], fontsize=7)
            ax.set_ylabel(spec["y_label"], fontsize=7)
        else:
            ax.imshow(tile[..., :3], interpolation="nearest")
            ax._render_panel = True
            ax.set_xlabel("x [pixel]", fontsize=7)
            ax.set_ylabel("y [pixel]", fontsize=7)
    fig.suptitle(f"{layout.get('title', '')}\n{subtitle}", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    save(fig, path, relpath, manifest)
    return True


# ----------------------------------------------------------------------------------------------
# Charts drawn from figure CSVs in place of a raster PNG the C++ experiment writes (the figures'
# line charts are their own: figure_charts.py draws them from their chart specs)

def p_map_chart(header, rows, path, relpath, manifest, subtitle):
    """kneiphof2024-fig6 p_map.csv: Eq. 20's probability p at normal incidence over the light's
    half-angle gamma (log) and sqrt(alpha), the cells with p > 1 outlined."""
    import numpy as np
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Patch, Rectangle
    if not {"sqrt_alpha", "gamma_deg", "p_eq20", "p_gt_1"} <= set(header):
        return False
    recs = [{h: _num(c) for h, c in zip(header, r)} for r in rows]
    sa = sorted({r["sqrt_alpha"] for r in recs})
    gd = sorted({r["gamma_deg"] for r in recs})
    grid = np.full((len(sa), len(gd)), np.nan)
    over = np.zeros(grid.shape, dtype=bool)
    for r in recs:
        i, j = sa.index(r["sqrt_alpha"]), gd.index(r["gamma_deg"])
        grid[i, j] = r["p_eq20"]
        over[i, j] = r["p_gt_1"] > 0
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 5))
    pos = grid[np.isfinite(grid) & (grid > 0)]
    lo = float(pos.min()) if pos.size else 1e-3
    mesh = ax.pcolormesh(np.arange(len(gd) + 1) - 0.5, np.arange(len(sa) + 1) - 0.5,
                         np.ma.masked_invalid(np.where(grid > 0, grid, lo)), cmap="viridis",
                         shading="flat",
                         norm=LogNorm(vmin=lo, vmax=max(lo * 10, float(pos.max()) if pos.size
                                                        else 1.0)))
    for i, j in zip(*np.nonzero(over)):
        ax.add_patch(Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, edgecolor="red", lw=1.2,
                               hatch="///"))
    colorbar(fig, mesh, ax, "p of Eq. 20 [1] (log scale)")
    xi, xl = _ticks(gd)
    yi, yl = _ticks(sa)
    ax.set_xticks(xi)
    ax.set_xticklabels(xl, fontsize=7)
    ax.set_yticks(yi)
    ax.set_yticklabels(yl, fontsize=7)
    ax.set_xlabel("light half-angle gamma [deg] (log spaced)", fontsize=8)
    ax.set_ylabel("sqrt(alpha) [1]", fontsize=8)
    ax.set_title(f"{int(over.sum())} of {over.size} cells have p > 1", fontsize=8)
    ax.legend(handles=[Patch(facecolor="none", edgecolor="red", hatch="///",
                             label="p > 1 (not a probability)")], fontsize=7, loc="upper right")
    fig.suptitle(f"kneiphof2024-fig6: p at normal incidence (from p_map.csv)\n{subtitle}",
                 fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    save(fig, path, relpath, manifest)
    return True


# figure id -> {csv name: function(header, rows, path, relpath, manifest, subtitle) -> bool,
#               and the C++ chart PNG it replaces}
FIGURE_CHARTS = {"kneiphof2024-fig6": {"p_map.csv": (p_map_chart, "p_map.png")}}
