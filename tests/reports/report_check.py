"""Checks shared by the report tests: parse index.html / report.md, and find links and images that
are absolute or do not resolve to a file inside the report folder."""
import html.parser
import os
import re
import urllib.parse


class Page(html.parser.HTMLParser):
    """Every href and src, and the rows (cell texts) of each table, of one HTML page."""

    def __init__(self):
        super().__init__()
        self.hrefs, self.srcs, self.tables = [], [], []
        self._cell = None
        self._row = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "a" and "href" in a:
            self.hrefs.append(a["href"])
        if tag == "img":
            self.srcs.append(a.get("src", ""))
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
