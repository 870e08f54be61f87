"""Checks shared by the report tests: parse index.html / report.md, find links and images that
are absolute or do not resolve to a file inside the report folder, and what a reader would see
that no run measured (a nan in a table, NOT FOUND, a Markdown table left as raw text, an empty cell
where a number belongs), and render panels too small to judge."""
import html.parser
import json
import os
import re
import urllib.parse


class Page(html.parser.HTMLParser):
    """Every href and src, and the rows (cell texts) of each table, of one HTML page."""

    def __init__(self):
        super().__init__()
        self.hrefs, self.srcs, self.tables = [], [], []
        self.imgs = []  # (src, class) of every <img>
        self._cell = None
        self._row = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "a" and "href" in a:
            self.hrefs.append(a["href"])
        if tag == "img":
            self.srcs.append(a.get("src", ""))
            self.imgs.append((a.get("src", ""), a.get("class", "") or ""))
        if tag == "table":
            self.tables.append([])
        if tag == "tr":
            self._row = []
        if tag in ("td", "th"):
            self._cell = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._row is not None:
            self._row.append(self._cell.strip())
            self._cell = None
        if tag == "tr" and self._row is not None:
            self.tables[-1].append(self._row)
            self._row = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data


def parse_html(path):
    p = Page()
    with open(path, encoding="utf-8") as f:
        p.feed(f.read())
    return p


MD_LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)\)")


def markdown_targets(path):
    """(links, images) of a Markdown file."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    links, images = [], []
    for m in MD_LINK.finditer(text):
        (images if m.group(0).startswith("!") else links).append(m.group(1))
    return links, images, text


def bad_targets(root, targets):
    """Targets that are absolute (a scheme, a leading /) or do not name an existing file (or
    folder) inside root."""
    bad = []
    real_root = os.path.realpath(root)
    for t in targets:
        u = urllib.parse.urlsplit(t)
        if u.scheme or u.netloc or t.startswith("/"):
            bad.append(f"{t} (absolute)")
            continue
        if not u.path:  # a same-page anchor
            continue
        p = os.path.realpath(os.path.join(root, urllib.parse.unquote(u.path)))
        if os.path.commonpath([real_root, p]) != real_root:
            bad.append(f"{t} (outside the report)")
        elif not os.path.exists(p):
            bad.append(f"{t} (missing)")
    return bad


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n"


def distinct_colours(path, limit=64):
    """How many distinct RGB(A) colours a PNG has (counting stops at limit)."""
    import matplotlib.image
    import numpy as np
    img = matplotlib.image.imread(path)
    flat = img.reshape(-1, img.shape[-1]) if img.ndim == 3 else img.reshape(-1, 1)
    step = max(1, flat.shape[0] // 200000)
    return min(limit, len(np.unique(flat[::step], axis=0)))


def plot_problems(root, page):
    """What makes a picture of the report unreadable: a chart (<img class="chart">) without an
    entry in plots/plots.json, or whose source data (that manifest, read back from the matplotlib
    figure) lacks a title, an axis label, a legend or, for a map, its colour scale; an image that
    is neither a chart nor a rendered figure image (<img class="render"> under figures/), i.e. a
    data map shown raw; an image that is a bare block (fewer than 4 distinct colours)."""
    problems = []
    try:
        with open(os.path.join(root, "plots", "plots.json"), encoding="utf-8") as f:
            manifest = {p["file"]: p for p in json.load(f)["plots"]}
    except (OSError, ValueError, KeyError) as e:
        return [f"plots/plots.json unreadable ({e})"]
    for src, cls in page.imgs:
        path = urllib.parse.unquote(src)
        if "chart" in cls.split():
            entry = manifest.get(path)
            if entry is None:
                problems.append(f"{src}: a chart not in plots/plots.json")
                continue
            if not entry.get("title"):
                problems.append(f"{src}: chart without a title")
            if not entry.get("axes"):
                problems.append(f"{src}: chart without axes")
            for i, ax in enumerate(entry.get("axes", [])):
                for k in ("xlabel", "ylabel", "title"):
                    if not str(ax.get(k, "")).strip():
                        problems.append(f"{src}: axes {i} has no {k}")
                # A rendered panel is named by its title; a map's colour bar is its legend.
                if not ax.get("legend") and not ax.get("render") and \
                        not (ax.get("map") and ax.get("colorbar")):
                    problems.append(f"{src}: axes {i} has no legend")
                if ax.get("map") and not ax.get("colorbar"):
                    problems.append(f"{src}: map {i} has no colour scale")
        elif "render" in cls.split():
            if not path.startswith("figures/"):
                problems.append(f"{src}: shown as a rendered image but not a figure's render "
                                "(a data map must be a chart with axes and colour scale)")
        else:
            problems.append(f"{src}: neither a chart nor a rendered figure image")
        full = os.path.join(root, path)
        if os.path.isfile(full) and is_png(full) and distinct_colours(full) < 4:
            problems.append(f"{src}: a bare block (fewer than 4 colours)")
    return problems


class Text(html.parser.HTMLParser):
    """The text a reader sees on a page (folded <details> included, <style> and <title> not), one
    string per text node, and the cells of every table."""

    def __init__(self):
        super().__init__()
        self.chunks, self.cells = [], []
        self._skip = 0
        self._cell = None

    def handle_starttag(self, tag, attrs):
        if tag in ("style", "script", "title"):
            self._skip += 1
        if tag in ("td", "th"):
            self._cell = ""

    def handle_endtag(self, tag):
        if tag in ("style", "script", "title"):
            self._skip -= 1
        if tag in ("td", "th") and self._cell is not None:
            self.cells.append(" ".join(self._cell.split()))
            self._cell = None

    def handle_data(self, data):
        if self._skip:
            return
        self.chunks.append(data)
        if self._cell is not None:
            self._cell += data


NAN_TOKEN = re.compile(r"^[-+]?nan$", re.IGNORECASE)
WORD = re.compile(r"[A-Za-z]{3,}")
MD_RULE = re.compile(r"^\s*\|?\s*:?-{3,}:?\s*(\|\s*:?-{3,}:?\s*)+\|?\s*$")


def nan_as_value(cell):
    """A cell that shows nan as a number: a token nan (alone, or among numbers and separators),
    not the word NaN in a sentence ("NaN for alpha below 1e-3")."""
    tokens = re.split(r"[\s/,;()=|]+", cell)
    if not any(NAN_TOKEN.match(t) for t in tokens):
        return False
    return not any(WORD.search(t) and not NAN_TOKEN.match(t) for t in tokens)


def visible_problems(page_html):
    """What a reader of the page sees that no run measured: a table cell showing nan, "NOT FOUND"
    anywhere, and Markdown tables left as raw text (a row of pipes over a |---| rule) instead of
    HTML tables."""
    t = Text()
    t.feed(page_html)
    problems = [f"table cell shows nan: {c!r}" for c in t.cells if nan_as_value(c)]
    text = "\n".join(t.chunks)
    for line in text.splitlines():
        if "NOT FOUND" in line:
            problems.append(f"visible NOT FOUND: {line.strip()[:120]!r}")
    lines = text.splitlines()
    for i in range(1, len(lines)):
        if MD_RULE.match(lines[i]) and lines[i - 1].strip().startswith("|"):
            problems.append(f"raw Markdown table: {lines[i - 1].strip()[:120]!r}")
    return problems


NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*(%|×|x|s|ms|µs|ns)?$")


def empty_number_cells(page):
    """Cells left empty in a table column whose other cells hold numbers: a number that a run
    should have written and did not (a column of words or links may have blanks)."""
    problems = []
    for t, rows in enumerate(page.tables):
        if len(rows) < 2:
            continue
        header, body = rows[0], rows[1:]
        for j, name in enumerate(header):
            cells = [r[j] for r in body if j < len(r)]
            numbers = sum(1 for c in cells if NUMBER.match(c))
            empty = sum(1 for c in cells if not c)
            if numbers and empty:
                problems.append(f"table {t + 1} ({' | '.join(header[:3])} ...): column "
                                f"{name!r} has {empty} empty cell(s) among {numbers} numbers")
    return problems


# A reader judges a glint method by its sparkle: a rendered panel needs this many pixels, rendered
# (not enlarged from fewer) and as displayed.
MIN_RENDER_PX = 128


def small_renders(root, shown):
    """Rendered images a reader sees under MIN_RENDER_PX pixels. shown: per <img>, as the browser
    laid it out (details unfolded): {src, cls, nw, nh (natural size), w, h (displayed size)}. A
    chart's rendered panels are read from plots/plots.json: each panel's image pixels and the size
    it is drawn at in the chart, scaled as the browser shows the chart; any other render (a
    figure's PNG in the gallery) by its own natural and displayed size."""
    try:
        with open(os.path.join(root, "plots", "plots.json"), encoding="utf-8") as f:
            manifest = {p["file"]: p for p in json.load(f)["plots"]}
    except (OSError, ValueError, KeyError) as e:
        return [f"plots/plots.json unreadable ({e})"]
    n = MIN_RENDER_PX
    problems = []
    for im in shown:
        src, cls = urllib.parse.unquote(im["src"]), im["cls"].split()
        if "chart" in cls:
            scale = im["w"] / im["nw"] if im["nw"] else 0
            for i, ax in enumerate(manifest.get(src, {}).get("axes", [])):
                if not ax.get("render"):
                    continue
                if "image_px" not in ax or "drawn_px" not in ax:
                    problems.append(f"{src}: panel {i} ({ax.get('title')!r}) has no recorded size")
                    continue
                pw, ph = ax["image_px"]
                dw, dh = (scale * v for v in ax["drawn_px"])
                if min(pw, ph) < n:
                    problems.append(f"{src}: panel {i} ({ax.get('title')!r}) is rendered at "
                                    f"{pw} x {ph} pixels (under {n})")
                if min(dw, dh) < n:
                    problems.append(f"{src}: panel {i} ({ax.get('title')!r}) is displayed at "
                                    f"{dw:.0f} x {dh:.0f} pixels (under {n})")
        elif "render" in cls:
            if min(im["nw"], im["nh"]) < n:
                problems.append(f"{src}: a render of {im['nw']} x {im['nh']} pixels (under {n})")
            if min(im["w"], im["h"]) < n:
                problems.append(f"{src}: displayed at {im['w']:.0f} x {im['h']:.0f} pixels "
                                f"(under {n})")
    return problems
