"""The charts of a figure's folder, drawn with matplotlib from the chart specs the C++ figure wrote.

A figure writes its data (CSV) and, beside each chart it wants, NAME.chart.json
(experiments/figures/chart_spec.h): which CSV, which columns go on which axis, one panel per
subset of rows, the series, their labels and colours, reference lines. `glintlab figure` runs
`/usr/bin/python3 reports/figure_charts.py --dir STAGING` before the figure's folder is swapped in;
this script draws every spec into NAME.png with charts.py's labelling rules (a title, axis labels
with their units, a legend) and stores what the chart shows (charts.describe: titles, labels,
legend; and a map's colour-bar label) in the PNG itself, as the text chunk "glintlab:chart",
which the report and the tests read back (chart_manifest). The PNG has no date or software
version in it: same data, same bytes. `glintlab sweep` runs it once for all its targets' folders
of stability maps (`--dir` repeated, `--root STAGING` naming a failing spec by its
model/sampler/ path; experiments/sweeps/stability_maps.h): one Python start per sweep.

A spec naming a missing CSV or column, an axis label without its unit ("[...]"), a series without
a label or a panel with nothing to draw is one line on stderr ("glintlab: error: ..."), exit 2,
and no PNG.

Spec (JSON): {"title", "csv", "panels": [{"title", "where": {column: value}, "x": {"column",
"label", "log", "range"}, "y": {"label", "log", "range"}, "series": [{"label", "where", "y",
"yerr", "yerr_scale", "color": [r, g, b], "line": "solid"|"dashed"|"dotted"|"none", "marker",
"point_label" (a str.format template over the row's cells), "mark" (a 0/1 column: those rows
ringed and joined, dashed, in x order), "mark_label"}], "hlines": [{"y", "label"}],
"slope_guide": {"slope", "label"} (a power law through the first series' first point)}]}.
With "kind": "categories" (a map of categories, e.g. the level chosen per cell), a panel is
{"title", "where", "x": {"column", "label", "log"} (its distinct values, one column each, in
order), "y": {"columns", "format", "label"} (one row per distinct tuple, in the CSV's order,
bottom to top; "format" is a str.format template over the row's cells, a number's format spec
such as "{alpha:.3g}" formats the cell as a number; "x": {"ticks": n} sets the number of x
ticks), "value": {"column", "label"}, "categories": [{"value", "label", "color"}],
"marker": {"column", "label"} (per row, an x value drawn as a bar between the columns),
"y": {"invert": true} for an image's pixel rows}; the categories are its colour bar. With "kind": "heatmap" (a number over a grid: parameters, or the
pixels of an image with "y": {"invert": true}), "value": {"column", "label", "log", "range",
"cmap"} is drawn on a colour bar, and "flags": [{"column", "value", "label", "color", "style":
"outline"|"fill"}] mark cells (outlined and hatched, or filled with the colour), named in the
legend with their counts; cells without a value are grey and named ("empty_label"). A panel's
own "kind" overrides the chart's (e.g. a heat map beside a map of categories).
A value in "where" matches a cell equal to it as text or, when both are numbers, as a number.
"""

import argparse
import csv
import glob
import json
import math
import os
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import charts  # noqa: E402

SPEC_SUFFIX = ".chart.json"
TEXT_KEY = "glintlab:chart"
LINES = {"solid": "-", "dashed": "--", "dotted": ":", "none": "none"}


class ChartError(Exception):
    pass


def _number(cell):
    try:
        return float(cell)
    except (TypeError, ValueError):
        return None


def _matches(row, where):
    for col, want in (where or {}).items():
        cell = row[col]
        b = _number(want)
        a = _number(cell) if b is not None else None  # a text value: no number to parse
        if a is not None and b is not None:
            if a != b:
                return False
        elif str(cell) != str(want):
            return False
    return True


def _matcher(where):
    """_matches(row, where) as a function of the row that decides each distinct cell of a column
    once: a figure's pixel CSV (10^5 rows) repeats a few names and values in its `where` columns,
    and each panel filters every row."""
    tests = [(col, want, _number(want), {}) for col, want in (where or {}).items()]

    def match(row):
        for col, want, b, seen in tests:
            cell = row[col]
            hit = seen.get(cell)
            if hit is None:
                hit = seen[cell] = _matches({col: cell}, {col: want})
            if not hit:
                return False
        return True
    return match


_column_groups = {"rows": None, "column": None, "groups": None}


def _rows_where(rows, where):
    """The rows that match `where`, in their order: list(filter(_matcher(where), rows)). A
    one-column `where` (a sheet's panel: one scene of its pixel CSV) is decided once per distinct
    cell of the column, the rows grouped by it once per CSV and column, not every row per panel."""
    if not where or len(where) != 1:
        return list(filter(_matcher(where), rows))
    (column, _), = where.items()
    cache = _column_groups
    if cache["rows"] is not rows or cache["column"] != column:
        groups = {}
        for k, r in enumerate(rows):
            groups.setdefault(r[column], []).append(k)
        cache.update(rows=rows, column=column, groups=groups)
    match = _matcher(where)
    hits = [ks for ks in cache["groups"].values() if match(rows[ks[0]])]
    if len(hits) == 1:
        return [rows[k] for k in hits[0]]
    return [rows[k] for k in sorted(k for ks in hits for k in ks)]


def _need(spec_name, csv_name, header, columns):
    for c in columns:
        if c and c not in header:
            raise ChartError(f"{spec_name}: {csv_name} has no column '{c}' (columns: "
                             f"{', '.join(header)})")


def _text(spec_name, what, value):
    if not isinstance(value, str) or not value.strip():
        raise ChartError(f"{spec_name}: {what} is missing (every chart has a title, labelled "
                         "axes and named series)")
    return value


def _axis_label(spec_name, what, value):
    _text(spec_name, what, value)
    if "[" not in value or "]" not in value:
        raise ChartError(f"{spec_name}: {what} '{value}' has no unit (valid: a label with its "
                         "unit in brackets, e.g. 'time [ns]' or 'ratio [1]')")
    return value


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ChartError(f"{os.path.basename(path)} is empty")
    header = rows[0]
    return header, [dict(zip(header, r)) for r in rows[1:] if r]


def _usable(v, log):
    return v is not None and math.isfinite(v) and (v > 0 or not log)


def draw_panel(ax, spec_name, csv_name, header, rows, panel):
    """One axes of a chart; returns the number of points drawn."""
    x, y = panel.get("x") or {}, panel.get("y") or {}
    _axis_label(spec_name, "x label", x.get("label"))
    _axis_label(spec_name, "y label", y.get("label"))
    _text(spec_name, "panel title", panel.get("title"))
    _need(spec_name, csv_name, header, [x.get("column"), *(panel.get("where") or {})])
    xlog, ylog = bool(x.get("log")), bool(y.get("log"))
    mine = list(filter(_matcher(panel.get("where")), rows))
    drawn, marks, firsts, x_max = 0, set(), [], -math.inf
    for s in panel.get("series") or []:
        label = _text(spec_name, "series label", s.get("label"))
        _need(spec_name, csv_name, header,
              [s.get("y"), s.get("yerr"), s.get("mark"), *(s.get("where") or {})])
        pts = []
        in_series = _matcher(s.get("where"))
        for r in mine:
            if not in_series(r):
                continue
            px, py = _number(r[x["column"]]), _number(r[s["y"]])
            if _usable(px, xlog) and _usable(py, ylog):
                pts.append((px, py, r))
        pts.sort(key=lambda p: p[0])
        if not pts:
            continue
        color = tuple(s.get("color") or (0, 0, 0))
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        firsts.append((xs[0], ys[0]))
        x_max = max(x_max, xs[-1])
        line = LINES.get(s.get("line", "solid"))
        if line is None:
            raise ChartError(f"{spec_name}: series '{label}' has line '{s.get('line')}' (valid: "
                             f"{', '.join(LINES)})")
        marker = s.get("marker", "o")
        if s.get("yerr"):
            k = float(s.get("yerr_scale", 1))
            err = [k * (_number(p[2][s["yerr"]]) or 0.0) for p in pts]
            ax.errorbar(xs, ys, yerr=err, color=color, ls=line, marker=marker, ms=3, lw=1,
                        capsize=2, label=label)
        else:
            ax.plot(xs, ys, color=color, ls=line, marker=marker, ms=4, lw=1, label=label)
        if s.get("mark"):
            front = [p for p in pts if _number(p[2][s["mark"]]) == 1]
            if front:
                what = s.get("mark_label") or s["mark"]
                ax.plot([p[0] for p in front], [p[1] for p in front], color=color, ls="--",
                        lw=1, marker="o", ms=9, mfc="none", mec="black",
                        label="_nolegend_" if what in marks else f"{what} (ringed, dashed)")
                marks.add(what)
        if s.get("point_label"):
            for px, py, r in pts:
                try:
                    text = s["point_label"].format(**r)
                except (KeyError, ValueError, IndexError) as e:
                    raise ChartError(f"{spec_name}: series '{label}' point_label "
                                     f"'{s['point_label']}' does not fit {csv_name}'s rows "
                                     f"({e})") from None
                ax.annotate(text, (px, py), textcoords="offset points", xytext=(4, 4),
                            fontsize=6, color=color)
        drawn += len(pts)
    guide = panel.get("slope_guide")
    if guide and drawn:
        # A power law of the given slope through the first series' first point, over the x range.
        first = firsts[0]
        x1 = x_max
        k = float(guide["slope"])
        ax.plot([first[0], x1], [first[1], first[1] * (x1 / first[0]) ** k], color="gray",
                ls="--", lw=0.8, label=_text(spec_name, "slope guide label", guide.get("label")))
    for h in panel.get("hlines") or []:
        ax.axhline(float(h["y"]), color="gray", lw=0.8, ls=":",
                   label=_text(spec_name, "reference line label", h.get("label")))
    if drawn == 0:
        raise ChartError(f"{spec_name}: panel '{panel.get('title')}' has no point to draw "
                         f"(no row of {csv_name} matches its series with usable values)")
    if xlog:
        ax.set_xscale("log")
    if ylog:
        ax.set_yscale("log")
    if x.get("range"):
        ax.set_xlim(*x["range"])
    if y.get("range"):
        ax.set_ylim(*y["range"])
    ax.set_xlabel(x["label"], fontsize=8)
    ax.set_ylabel(y["label"], fontsize=8)
    ax.set_title(panel["title"], fontsize=8)
    ax.grid(True, which="both" if (xlog or ylog) else "major", alpha=0.3)
    ax.tick_params(which="both", labelsize=7)
    ax.legend(fontsize=6)
    return drawn


def _category_key(cell):
    v = _number(cell)
    return f"{v:.17g}" if v is not None else str(cell)


def draw_categories(ax, fig, spec_name, csv_name, header, rows, panel):
    """One categorical map: a cell per (x value, y row) coloured by its category, the categories
    as the colour bar's ticks, and per y row an optional marker at an x value (placed between the
    columns, on a log scale where the x axis is); returns the number of cells drawn."""
    import numpy as np
    from matplotlib.colors import BoundaryNorm, ListedColormap
    x, y, value = panel.get("x") or {}, panel.get("y") or {}, panel.get("value") or {}
    _axis_label(spec_name, "x label", x.get("label"))
    _axis_label(spec_name, "y label", y.get("label"))
    _text(spec_name, "panel title", panel.get("title"))
    _text(spec_name, "value label", value.get("label"))
    marker = panel.get("marker") or {}
    ycols = y.get("columns") or []
    if not ycols:
        raise ChartError(f"{spec_name}: a categories panel names its y \"columns\"")
    _need(spec_name, csv_name, header, [x.get("column"), value.get("column"), marker.get("column"),
                                        *ycols, *(panel.get("where") or {})])
    cats = panel.get("categories") or []
    if not cats:
        raise ChartError(f"{spec_name}: panel '{panel['title']}' has no categories")
    index = {_category_key(c["value"]): k for k, c in enumerate(cats)}
    mine, xs, ykeys = _grid_axes(spec_name, csv_name, header, rows, panel, ycols)
    yi, xj = {k: i for i, k in enumerate(ykeys)}, {v: j for j, v in enumerate(xs)}
    grid = np.full((len(ykeys), len(xs)), np.nan)
    marks = [math.nan] * len(ykeys)
    for r in mine:
        i, j = yi[tuple(r[c] for c in ycols)], xj[_number(r[x["column"]])]
        key = _category_key(r[value["column"]])
        if key not in index:
            raise ChartError(f"{spec_name}: {csv_name} has {value['column']} = "
                             f"{r[value['column']]}, which is none of the panel's categories")
        grid[i, j] = index[key]
        if marker.get("column"):
            m = _number(r[marker["column"]])
            marks[i] = m if m is not None else math.nan
    cmap = ListedColormap([tuple(c["color"]) for c in cats])
    cmap.set_bad((0.8, 0.8, 0.8))
    norm = BoundaryNorm(np.arange(len(cats) + 1) - 0.5, len(cats))
    mesh = _cells(ax, grid, cmap, norm)
    cb = charts.colorbar(fig, mesh, ax, value["label"])
    cb.set_ticks(list(range(len(cats))))
    cb.set_ticklabels([_text(spec_name, "category label", c.get("label")) for c in cats])
    log = bool(x.get("log"))
    pos = [math.log10(v) if log else v for v in xs] if all(v > 0 for v in xs) or not log else None
    if marker.get("column") and pos and len(xs) > 1:
        label = _text(spec_name, "marker label", marker.get("label"))
        for i, m in enumerate(marks):
            if not (m > 0 or (not log and math.isfinite(m))):
                continue
            t = math.log10(m) if log else m
            col = (t - pos[0]) / (pos[-1] - pos[0]) * (len(xs) - 1)
            if -0.5 <= col <= len(xs) - 0.5:
                ax.plot([col, col], [i - 0.45, i + 0.45], color="black", lw=2.5, label=label)
                label = "_nolegend_"
        if label != "_nolegend_":  # no marker inside the map: still named, as absent
            ax.plot([], [], color="black", lw=2.5, label=f"{label} (outside the map)")
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(0, -0.14))
    _label_grid_axes(ax, spec_name, csv_name, panel, xs, ycols, ykeys, ticks=8, rotate=False)
    return int(np.isfinite(grid).sum())


def _cells(ax, grid, cmap, norm):
    """A grid of cells (row i, column j centred on (j, i)) coloured through `norm` and `cmap`,
    a cell without a value in cmap's "bad" colour: one image, not a mesh of quadrilaterals."""
    import numpy as np
    ny, nx = grid.shape
    return ax.imshow(np.ma.masked_invalid(grid), cmap=cmap, norm=norm, origin="lower",
                     extent=(-0.5, nx - 0.5, -0.5, ny - 0.5), aspect="auto",
                     interpolation="nearest")


def _grid_axes(spec_name, csv_name, header, rows, panel, ycols):
    """The panel's rows, its distinct x values (sorted) and y keys (in the CSV's order)."""
    x = panel.get("x") or {}
    mine = _rows_where(rows, panel.get("where"))
    if not mine:
        raise ChartError(f"{spec_name}: panel '{panel['title']}' has no point to draw (no row "
                         f"of {csv_name} matches it)")
    xs = sorted({_number(r[x["column"]]) for r in mine}, key=lambda v: (v is None, v))
    if None in xs:
        raise ChartError(f"{spec_name}: {csv_name} column '{x['column']}' is not numeric")
    ykeys = list(dict.fromkeys(tuple(r[c] for c in ycols) for r in mine))
    return mine, xs, ykeys


def _y_ticks(ax, spec_name, csv_name, y, ycols, ykeys):
    fmt = y.get("format")
    idx = list(range(len(ykeys)))
    if len(ykeys) > 12:  # a pixel or fine parameter grid: a few ticks
        idx = sorted({round(k * (len(ykeys) - 1) / 7) for k in range(8)})
    ax.set_yticks(idx)

    def label(key):
        cells = dict(zip(ycols, key))
        try:
            return fmt.format(**cells)
        except ValueError:  # a number's format ("{alpha:.3g}"): the cells as numbers
            return fmt.format(**{c: v if _number(v) is None else _number(v)
                                 for c, v in cells.items()})
    try:
        ax.set_yticklabels([label(ykeys[i]) if fmt else ", ".join(ykeys[i]) for i in idx],
                           fontsize=6)
    except (KeyError, ValueError, IndexError) as e:
        raise ChartError(f"{spec_name}: y format '{fmt}' does not fit {csv_name}'s rows "
                         f"({e})") from None


def _label_grid_axes(ax, spec_name, csv_name, panel, xs, ycols, ykeys, ticks, rotate):
    """A grid map's x ticks (the spec's count, else `ticks`; labels turned when more than four
    and `rotate`), y ticks, image-row order, axis labels and panel title; returns whether the x
    tick labels are turned."""
    x, y = panel["x"], panel["y"]
    xi, xl = charts._ticks(xs, n=int(x.get("ticks", ticks)))
    turned = rotate and len(xi) > 4
    ax.set_xticks(xi)
    ax.set_xticklabels(xl, fontsize=6, rotation=30 if turned else 0)
    _y_ticks(ax, spec_name, csv_name, y, ycols, ykeys)
    if y.get("invert"):  # image rows: the first at the top
        ax.invert_yaxis()
    ax.set_xlabel(x["label"], fontsize=8)
    ax.set_ylabel(y["label"], fontsize=8)
    ax.set_title(panel["title"], fontsize=8)
    return turned


def draw_heatmap(ax, fig, spec_name, csv_name, header, rows, panel):
    """One map of a number over two grid columns: a cell per (x value, y row) coloured by its
    value on a colour bar (linear or log, over a given range or the data's), and flagged cells
    (a column equal to a value) filled with their colour or outlined, named in the legend; cells
    with no value are grey and named too. Returns the number of cells drawn."""
    import numpy as np
    from matplotlib.colors import LogNorm, Normalize
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Patch, Rectangle
    x, y, value = panel.get("x") or {}, panel.get("y") or {}, panel.get("value") or {}
    _axis_label(spec_name, "x label", x.get("label"))
    _axis_label(spec_name, "y label", y.get("label"))
    _text(spec_name, "panel title", panel.get("title"))
    _axis_label(spec_name, "value label", value.get("label"))
    ycols = y.get("columns") or []
    if not ycols:
        raise ChartError(f"{spec_name}: a heatmap panel names its y \"columns\"")
    flags = panel.get("flags") or []
    _need(spec_name, csv_name, header, [x.get("column"), value.get("column"), *ycols,
                                        *(f.get("column") for f in flags),
                                        *(panel.get("where") or {})])
    mine, xs, ykeys = _grid_axes(spec_name, csv_name, header, rows, panel, ycols)
    yi, xj = {k: i for i, k in enumerate(ykeys)}, {v: j for j, v in enumerate(xs)}
    grid = np.full((len(ykeys), len(xs)), np.nan)
    flagged = [np.zeros(grid.shape, dtype=bool) for _ in flags]
    is_flagged = [_matcher({f["column"]: f["value"]}) for f in flags]
    for r in mine:
        i, j = yi[tuple(r[c] for c in ycols)], xj[_number(r[x["column"]])]
        v = _number(r[value["column"]])
        grid[i, j] = v if v is not None else np.nan
        for k, f in enumerate(flags):
            flagged[k][i, j] = is_flagged[k](r)
    filled = np.zeros(grid.shape, dtype=bool)
    for k, f in enumerate(flags):
        if f.get("style", "outline") == "fill":
            filled |= flagged[k]
    shown = np.where(filled, np.nan, grid)
    finite = shown[np.isfinite(shown)]
    log = bool(value.get("log"))
    lo, hi = value.get("range") or (None, None)
    if log:
        pos = finite[finite > 0]
        lo = float(lo) if lo is not None else (float(pos.min()) if pos.size else 1e-3)
        hi = float(hi) if hi is not None else max(float(pos.max()) if pos.size else 1.0, lo * 10)
        norm = LogNorm(vmin=lo, vmax=hi)
        shown = np.where(shown > 0, shown, np.nan)
    else:
        lo = float(lo) if lo is not None else (float(finite.min()) if finite.size else 0.0)
        hi = float(hi) if hi is not None else (float(finite.max()) if finite.size else 1.0)
        if hi <= lo:
            hi = lo + 1.0
        norm = Normalize(vmin=lo, vmax=hi)
    import matplotlib
    cmap = matplotlib.colormaps[value.get("cmap", "viridis")].copy()
    cmap.set_bad((0.8, 0.8, 0.8))
    mesh = _cells(ax, shown, cmap, norm)
    charts.colorbar(fig, mesh, ax, value["label"])
    handles = []
    for k, f in enumerate(flags):
        label = _text(spec_name, "flag label", f.get("label"))
        color = tuple(f.get("color") or (1, 0, 0))
        n = int(flagged[k].sum())
        cells = [Rectangle((j - 0.5, i - 0.5), 1, 1) for i, j in zip(*np.nonzero(flagged[k]))]
        if cells:  # one collection per flag, not an artist per cell
            if f.get("style", "outline") == "fill":
                ax.add_collection(PatchCollection(cells, facecolor=color, lw=0))
            else:
                ax.add_collection(PatchCollection(cells, facecolor="none", edgecolor=color,
                                                  lw=1.2, hatch="///"))
        handles.append(Patch(facecolor=color, label=f"{label} ({n} cells)")
                       if f.get("style", "outline") == "fill" else
                       Patch(facecolor="none", edgecolor=color, hatch="///",
                             label=f"{label} ({n} cells)"))
    empty = int((~np.isfinite(shown) & ~filled).sum())
    if empty:
        handles.append(Patch(facecolor=(0.8, 0.8, 0.8),
                             label=panel.get("empty_label") or f"no value ({empty} cells)"))
    turned = _label_grid_axes(ax, spec_name, csv_name, panel, xs, ycols, ykeys, ticks=6,
                              rotate=True)
    if handles:  # under the x label, lower where the tick labels are turned
        ax.legend(handles=handles, fontsize=6, loc="upper left",
                  bbox_to_anchor=(0, -0.22 if turned else -0.14))
    return int(np.isfinite(grid).sum())


def draw_chart(spec_path, name=None):
    """Draws one NAME.chart.json into NAME.png beside it; returns the PNG's path. `name`: how
    errors name the spec (default its file name)."""
    spec_name = name or os.path.basename(spec_path)
    try:
        with open(spec_path, encoding="utf-8") as f:
            spec = json.load(f)
    except (OSError, ValueError) as e:
        raise ChartError(f"{spec_name}: unreadable chart spec ({e})") from None
    if not isinstance(spec, dict) or not isinstance(spec.get("panels"), list) or \
            not spec["panels"]:
        raise ChartError(f"{spec_name}: expected an object with a non-empty \"panels\" list")
    title = _text(spec_name, "title", spec.get("title"))
    csv_name = _text(spec_name, "csv", spec.get("csv"))
    folder = os.path.dirname(spec_path)
    csv_path = os.path.join(folder, csv_name)
    if not os.path.isfile(csv_path):
        raise ChartError(f"{spec_name}: its CSV '{csv_name}' is not in the figure's folder")
    header, rows = read_csv(csv_path)
    plt = charts.pyplot()
    n = len(spec["panels"])
    cols = min(n, int(spec.get("columns", n)))
    nrows = (n + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(5.2 * cols, 4.2 * nrows + 0.5), squeeze=False)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    try:
        kind = spec.get("kind", "lines")
        if kind not in KINDS:
            raise ChartError(f"{spec_name}: kind '{kind}' (valid: {', '.join(KINDS)})")
        for ax, panel in zip(axes.flat, spec["panels"]):
            own = panel.get("kind", kind)  # a panel may be of another kind than the chart's
            if own not in KINDS:
                raise ChartError(f"{spec_name}: panel kind '{own}' (valid: {', '.join(KINDS)})")
            if own == "lines":
                draw_panel(ax, spec_name, csv_name, header, rows, panel)
            else:
                KINDS[own](ax, fig, spec_name, csv_name, header, rows, panel)
        fig.suptitle(f"{title}\n(from {csv_name})", fontsize=9)
        fig.tight_layout(rect=(0, 0, 1, 0.93))
        png = spec_path[:-len(SPEC_SUFFIX)] + ".png"
        save_png(fig, png)
    finally:
        plt.close(fig)
    return png


KINDS = {"lines": None, "categories": draw_categories, "heatmap": draw_heatmap}


def save_png(fig, path, dpi=100):
    """Saves a chart with what it shows (charts.describe) as the PNG's text chunk TEXT_KEY; no
    date or software name, so that the same chart is the same bytes."""
    entry = charts.describe(fig)
    # A map's colour-bar label (its value and unit) beside its axes, in describe's axes order.
    shown = [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]
    for ax, e in zip(shown, entry["axes"]):
        bars = [c for c in fig.axes if getattr(c, "_colorbar_of", None) is ax]
        if bars:
            e["colorbar_label"] = bars[0].get_ylabel()
    tmp = path + ".tmp"
    fig.savefig(tmp, dpi=dpi, format="png",
                metadata={"Software": None, TEXT_KEY: json.dumps(entry, sort_keys=True)})
    os.replace(tmp, path)


def chart_manifest(png_path):
    """What a chart PNG drawn here shows (its TEXT_KEY chunk), or None when it has none."""
    try:
        with open(png_path, "rb") as f:
            data = f.read()
    except OSError:
        return None
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    pos = 8
    while pos + 8 <= len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        key = TEXT_KEY.encode("latin-1") + b"\0"
        if kind == b"tEXt" and body.startswith(key):
            return json.loads(body[len(key):].decode("latin-1"))
        if kind == b"zTXt" and body.startswith(key):
            return json.loads(zlib.decompress(body[len(key) + 1:]).decode("latin-1"))
        if kind == b"iTXt" and body.startswith(key):
            rest = body[len(key):]
            compressed = rest[0] == 1
            rest = rest[2:]
            rest = rest[rest.index(b"\0") + 1:]  # language tag
            rest = rest[rest.index(b"\0") + 1:]  # translated keyword
            return json.loads((zlib.decompress(rest) if compressed else rest).decode("utf-8"))
    return None


def chart_specs(folder):
    """The chart specs of a figure's folder, sorted by name."""
    return sorted(glob.glob(os.path.join(glob.escape(folder), "*" + SPEC_SUFFIX)))


def draw_all(folders, root=None):
    """Draws every spec of every folder (in folder order, each folder's specs by name) in this
    one process; with `root`, a spec is named in an error by its path below it (e.g.
    "model/sampler/x.chart.json"). At the first failing spec, removes every PNG drawn and returns
    its error line; else returns None."""
    drawn = []
    try:
        for folder in folders:
            for spec in chart_specs(folder):
                drawn.append(draw_chart(spec, os.path.relpath(spec, root) if root else None))
    except ChartError as e:
        for png in drawn:  # nothing half done: the charts drawn before the error go too
            os.remove(png)
        return str(e)
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", required=True, action="append",
                    help="a figure's folder (its staging folder); repeated: every folder's "
                         "charts in one run (glintlab sweep: each target's)")
    ap.add_argument("--root", help="name a failing spec by its path below this folder")
    a = ap.parse_args(argv)
    for d in a.dir:
        if not os.path.isdir(d):
            print(f"glintlab: error: charts: --dir '{d}' is not a folder", file=sys.stderr)
            return 2
    charts.pyplot().rcParams["svg.hashsalt"] = "glintlab"
    error = draw_all(a.dir, a.root)
    if error is not None:
        print(f"glintlab: error: charts: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
