"""Renders the same input folders with the report writer of an earlier commit and with this
checkout's, and diffs the HTML after normalising what does not change the page: runs of
whitespace (a run of it is one space, none next to a block element's tag), and the spelling of
escaped quotes (html.escape writes &quot; and &#x27;, Jinja2's autoescape &#34; and &#39;: the
same characters once parsed; an apostrophe is compared unescaped). The Markdown twins report.md are
compared byte for byte. Not a ctest: it takes the input
folders as arguments (a `glintlab report` folder, a `glintlab compare` folder).

Usage: /usr/bin/python3 tests/reports/html_equivalence.py --before REV DIR...
A DIR holding compare.json (and no run.json) is rendered by compare_page.py, any other by
make_report.py. Exit 0 when every page is equivalent, 1 when one differs (the diff is printed).
"""
import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys
import tempfile

REPO = os.path.realpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


# Tags around which whitespace is not shown (the page's block elements, and the style sheet's).
BLOCK_TAG = re.compile(r"\s*(</?(?:html|head|body|title|meta|style|nav|h[1-6]|p|ul|li|table|thead|"
                       r"tbody|tr|td|th|details|summary|div|figure|figcaption|br)\b[^>]*>)\s*")


def normalised(page):
    # The page's attribute values are all in double quotes, so an apostrophe needs no escaping.
    page = page.replace("&quot;", "&#34;").replace("&#x27;", "'").replace("&#39;", "'")
    # A run of whitespace reads as one space, and as none next to a block element's tag.
    page = BLOCK_TAG.sub(r"\1", re.sub(r"\s+", " ", page))
    # One tag per line, so that a difference is shown where it is.
    return page.replace("><", ">\n<").splitlines()


def render(reports_dir, source, work):
    shutil.copytree(source, work)
    is_compare = os.path.exists(os.path.join(work, "compare.json")) and \
        not os.path.exists(os.path.join(work, "run.json"))
    script = "compare_page.py" if is_compare else "make_report.py"
    r = subprocess.run(["/usr/bin/python3", os.path.join(reports_dir, script), "--dir", work],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{script} on {source} failed ({reports_dir}): {r.stderr.strip()}")
    pages = []
    for name in ("index.html", "report.md"):
        path = os.path.join(work, name)
        pages.append(open(path, encoding="utf-8").read() if os.path.exists(path) else None)
    return pages


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, help="the commit whose reports/ is compared")
    ap.add_argument("dirs", nargs="+")
    a = ap.parse_args()
    differs = 0
    with tempfile.TemporaryDirectory() as tmp:
        old = os.path.join(tmp, "old")
        os.makedirs(old)
        archive = subprocess.run(["git", "-C", REPO, "archive", a.before, "reports"],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", old], input=archive, check=True)
        for i, d in enumerate(a.dirs):
            before, md_before = render(os.path.join(old, "reports"), d, os.path.join(tmp, f"b{i}"))
            after, md_after = render(os.path.join(REPO, "reports"), d, os.path.join(tmp, f"a{i}"))
            if md_before != md_after:
                differs += 1
                print("\n".join(difflib.unified_diff(
                    (md_before or "").splitlines(), (md_after or "").splitlines(),
                    f"{d}/report.md ({a.before})", f"{d}/report.md (this checkout)",
                    lineterm="", n=0)))
                print(f"{d}: report.md DIFFERS")
            raw_same = before == after
            diff = list(difflib.unified_diff(normalised(before), normalised(after),
                                             f"{d} ({a.before})", f"{d} (this checkout)",
                                             lineterm="", n=1))
            if diff:
                differs += 1
                print("\n".join(diff))
            print(f"{d}: {len(before)} -> {len(after)} bytes; "
                  + ("identical bytes" if raw_same else
                     "equivalent after normalising" if not diff else "DIFFERS"))
    return 1 if differs else 0


if __name__ == "__main__":
    sys.exit(main())
