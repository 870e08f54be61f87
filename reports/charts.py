"""Charts the report draws itself with matplotlib, and the manifest of every chart it drew.

Every chart is saved through `save`, which reads back from the matplotlib figure what a reader
needs (figure and axes titles, axis labels, legend, colour scale of a map) into a manifest entry;
make_report.py writes the entries to plots/plots.json and the browser test
(tests/reports/browser_test.py) fails on a chart whose axes lack labels, title, legend or, for a
map, its colour scale.

A figure's or a sweep's own charts and heat maps are drawn once, when the figure or sweep runs
(figure_charts.py, from the chart specs beside its CSVs); the report shows those PNGs and reads
what they show from their "glintlab:chart" chunk. What is left here: the montages of renders as
labelled panels (panel_chart), and the helpers figure_charts.py shares.
"""


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

# The columns every plane CSV of a sweep has (the report checks them; the maps themselves are the
# sweep's PNGs, drawn by figure_charts.py).
STABILITY_NEEDED = ("row_index", "column_index", "theta_i_deg")


def _ticks(values, n=6):
    """Tick positions (cell indices) and labels (the parameter values) of a grid map's axis
    (figure_charts.py)."""
    if len(values) <= n:
        idx = list(range(len(values)))
    else:
        idx = sorted({round(k * (len(values) - 1) / (n - 1)) for k in range(n)})
    return idx, [f"{values[i]:.5g}" for i in idx]


# ----------------------------------------------------------------------------------------------
# Montage PNGs of a figure, drawn as labelled panels from their NAME.panels.json
# (experiments/figures/panel_layout.h)

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
    """A figure's montage of renders as one labelled panel per tile, each enlarged (nearest
    pixel) with pixel axes (a map of numbers is a heat map of its own, drawn from its CSV by
    figure_charts.py). Returns False when the layout does not fit the image."""
    import matplotlib.image
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
    for ax, tile, label in zip(axes.flat, tiles, layout["labels"]):
        ax.set_title(label, fontsize=7)
        ax.tick_params(labelsize=6)
        ax.imshow(tile[..., :3], interpolation="nearest")
        ax._render_panel = True
        ax.set_xlabel("x [pixel]", fontsize=7)
        ax.set_ylabel("y [pixel]", fontsize=7)
    fig.suptitle(f"{layout.get('title', '')}\n{subtitle}", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    save(fig, path, relpath, manifest)
    return True
