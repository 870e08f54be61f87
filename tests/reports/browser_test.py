"""The HTML report in a real browser: headless Debian chromium loads a copy of
index.html with a script that records, after the load event, every <img> that did not decode
(complete and naturalWidth > 0) and every relative link that a file:// request cannot read; the
result is read back with --dump-dom. A screenshot of the report is saved. Negative control: the
same check on a page with one image and one link pointing at missing files must report exactly
those two.

Usage: browser_test.py SCREENSHOT.png [--report DIR]  (default: a report made from
tests/reports/fixtures/ by reports/make_report.py). Exit 0 pass, 1 fail, 77 skip (ctest
SKIP_RETURN_CODE) when /usr/bin/chromium is not installed."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import report_check as rc  # noqa: E402

CHROMIUM = "/usr/bin/chromium"
SCRIPT = os.path.join(HERE, "..", "..", "reports", "make_report.py")

# Runs after load: broken images, and relative links read with synchronous file:// requests
# (allowed by --allow-file-access-from-files); the verdict goes into a <pre id>.
PROBE = """<script>
window.addEventListener('load', function () {
  var broken = [], dead = [], shown = [], imgs = document.images, links = document.links;
  // Unfold every <details>, as a reader would, so that folded images have a displayed size.
  var folds = document.getElementsByTagName('details');
  for (var k = 0; k < folds.length; k++) folds[k].open = true;
  for (var i = 0; i < imgs.length; i++) {
    if (!imgs[i].complete || imgs[i].naturalWidth === 0) broken.push(imgs[i].getAttribute('src'));
    var r = imgs[i].getBoundingClientRect();
    shown.push({src: imgs[i].getAttribute('src'), cls: imgs[i].className,
                nw: imgs[i].naturalWidth, nh: imgs[i].naturalHeight, w: r.width, h: r.height});
  }
  for (var j = 0; j < links.length; j++) {
    var h = links[j].getAttribute('href');
    if (/^[a-z]+:|^\\/|^#/i.test(h)) continue;
    try {
      var x = new XMLHttpRequest();
      x.open('GET', links[j].href, false);
      x.send();
      if (x.status !== 0 && x.status !== 200) dead.push(h);
    } catch (e) { dead.push(h); }
  }
  var pre = document.createElement('pre');
  pre.id = 'glintlab-browser-check';
  pre.textContent = JSON.stringify({images: imgs.length, links: links.length,
                                    broken: broken, dead: dead, shown: shown});
  document.body.appendChild(pre);
});
</script>"""

# The window width fixes the layout, so the displayed sizes measured are those of a 1280-pixel-wide
# browser window.
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run",
         "--allow-file-access-from-files", "--virtual-time-budget=15000", "--window-size=1280,3000"]


def chromium(args, profile):
    return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *args],
                          capture_output=True, text=True, timeout=180)


def probe(page_path, profile):
    """The probe's result for one page (a copy with the script, beside it)."""
    src = open(page_path, encoding="utf-8").read()
    probe_path = os.path.join(os.path.dirname(page_path), ".browser_probe.html")
    with open(probe_path, "w", encoding="utf-8") as f:
        f.write(src.replace("</body>", PROBE + "</body>"))
    try:
        r = chromium(["--dump-dom", "file://" + os.path.abspath(probe_path)], profile)
    finally:
        os.unlink(probe_path)
    m = re.search(r'<pre id="glintlab-browser-check">(.*?)</pre>', r.stdout, re.S)
    if not m:
        return None, r.stderr[-2000:]
    return json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&")), ""


def broken_plots(broken, page):
    """Breaks a copy of the report three ways (a chart's y label removed from plots.json, a raw
    stability PNG and a one-colour PNG shown as images); True when plot_problems names each."""
    mpath = os.path.join(broken, "plots", "plots.json")
    manifest = json.load(open(mpath, encoding="utf-8"))
    charts = [s for s, c in page.imgs if c == "chart"]
    if not manifest["plots"] or not charts:
        return "the report has no chart to break"
    victim = manifest["plots"][0]
    victim["axes"][0]["ylabel"] = ""
    json.dump(manifest, open(mpath, "w", encoding="utf-8"))
    raw = [os.path.relpath(p, broken) for p in
           sorted(__import__("glob").glob(os.path.join(broken, "stability", "**", "*.png"),
                                          recursive=True))]
    import matplotlib.image
    import numpy as np
    matplotlib.image.imsave(os.path.join(broken, "figures", "block.png"),
                            np.zeros((64, 64, 3)) + 0.4)
    extra = [("figures/block.png", "render")] + [(r, "render") for r in raw[:1]]
    page.imgs = list(page.imgs) + extra
    got = rc.plot_problems(broken, page)
    page.imgs = page.imgs[:-len(extra)]
    want = [f"{victim['file']}: axes 0 has no ylabel", "figures/block.png: a bare block"]
    want += [f"{r}: shown as a rendered image but not a figure's render" for r in raw[:1]]
    missing = [w for w in want if not any(g.startswith(w) for g in got)]
    return True if not missing and len(got) == len(want) else f"wanted {want}, got {got}"


def shrunk_panels(tmp, profile):
    """Negative control: the fixtures with their two-panel montage cut to 48-pixel panels (the old
    quick renders, enlarged in the page); True when small_renders names both panels."""
    import matplotlib.image
    d = os.path.join(tmp, "small")
    shutil.copytree(os.path.join(HERE, "fixtures"), d)
    png = os.path.join(d, "figures", "fixture2026-fig1", "renders.png")
    img = matplotlib.image.imread(png)
    matplotlib.image.imsave(png, img[::8, ::8][:, :, :3].repeat(3, 0).repeat(3, 1)[:48, :96])
    r = subprocess.run([sys.executable, SCRIPT, "--dir", d], capture_output=True, text=True)
    if r.returncode != 0:
        return f"make_report.py on the shrunk fixtures: {r.stderr.strip()}"
    res, err = probe(os.path.join(d, "index.html"), profile)
    if res is None:
        return f"chromium did not run the probe: {err}"
    got = rc.small_renders(d, res["shown"])
    want = [f"plots/fixture2026-fig1__renders_panels.png: panel {i} " for i in (0, 1)]
    ok = all(any(g.startswith(w) and "rendered at 48 x 48 pixels" in g for g in got)
             for w in want)
    return True if ok and len(got) == 2 else f"wanted both panels at 48 x 48, got {got}"


def main():
    if len(sys.argv) < 2:
        print("usage: browser_test.py SCREENSHOT.png [--report DIR]")
        return 2
    if not os.path.exists(CHROMIUM):
        print(f"SKIP: {CHROMIUM} is not installed, so the HTML report was not opened in a browser "
              "(Debian: apt-get install chromium; scripts/setup.sh installs it)")
        return 77
    shot = os.path.abspath(sys.argv[1])
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        profile = os.path.join(tmp, "profile")
        if "--report" in sys.argv:
            report = sys.argv[sys.argv.index("--report") + 1]
        else:
            report = os.path.join(tmp, "report")
            shutil.copytree(os.path.join(HERE, "fixtures"), report)
            r = subprocess.run([sys.executable, SCRIPT, "--dir", report], capture_output=True,
                               text=True)
            if r.returncode != 0:
                print(f"FAIL: make_report.py on the fixtures: {r.stderr.strip()}")
                return 1
        index = os.path.join(report, "index.html")
        page = rc.parse_html(index)
        res, err = probe(index, profile)
        if res is None:
            print(f"FAIL: chromium did not run the probe: {err}")
            return 1
        print(f"chromium: {res['images']} images, {res['links']} links in {index}")
        if res["images"] != len(page.srcs) or res["images"] == 0:
            failures.append(f"chromium saw {res['images']} images, the HTML has {len(page.srcs)}")
        if res["broken"]:
            failures.append(f"images that did not load: {res['broken']}")
        if res["dead"]:
            failures.append(f"links that do not resolve: {res['dead']}")
        bad = rc.bad_targets(report, page.hrefs + page.srcs)
        if bad:
            failures.append(f"absolute or missing targets: {bad}")
        # Negative control: one image and one relative link pointed at missing files must be
        # caught (the first relative link: a report made without claims has no verify/).
        control = os.path.join(report, ".control.html")
        text = open(index, encoding="utf-8").read()
        first = page.srcs[0] if page.srcs else ""
        link = next((h for h in page.hrefs if not re.match(r"^[a-z]+:|^/|^#", h, re.I)), "")
        with open(control, "w", encoding="utf-8") as f:
            text = text.replace(f'src="{first}"', 'src="missing-image.png"', 1)
            f.write(text.replace(f'href="{link}"', 'href="missing-file.json"', 1))
        cres, err = probe(control, profile)
        os.unlink(control)
        if cres is None or cres["broken"] != ["missing-image.png"] or \
                cres["dead"] != ["missing-file.json"]:
            failures.append(f"negative control: a missing image and a dangling link were not "
                            f"both reported ({cres}, {err})")
        # Every render is large enough to judge, rendered and as displayed.
        small = rc.small_renders(report, res["shown"])
        if small:
            failures.append(f"renders too small: {small[:10]}" +
                            (f" and {len(small) - 10} more" if len(small) > 10 else ""))
        caught = shrunk_panels(tmp, profile)
        if caught is not True:
            failures.append(f"negative control: 48-pixel panels not reported ({caught})")
        # Every picture is readable: charts with title, labelled axes, legend, colour scale.
        problems = rc.plot_problems(report, page)
        if problems:
            failures.append(f"unreadable pictures: {problems[:10]}" +
                            (f" and {len(problems) - 10} more" if len(problems) > 10 else ""))
        # Nothing shown that no run measured: a nan in a table, NOT FOUND, raw Markdown tables (the
        # page is static, so its text is the HTML's; the negative controls are in
        # report_writer_test.py).
        shown = rc.visible_problems(open(index, encoding="utf-8").read())
        shown += rc.empty_number_cells(page)
        if shown:
            failures.append(f"shown but not measured: {shown[:10]}" +
                            (f" and {len(shown) - 10} more" if len(shown) > 10 else ""))
        # Negative control: a chart whose axis label is gone, a raw data map shown as an image
        # and a one-colour block must all be caught.
        broken = os.path.join(tmp, "broken")
        shutil.copytree(report, broken, symlinks=True)
        caught = broken_plots(broken, page)
        if caught is not True:
            failures.append(f"negative control: broken pictures not all reported ({caught})")
        r = chromium([f"--screenshot={shot}",
                      "file://" + os.path.abspath(index)], profile)
        if not os.path.exists(shot) or not rc.is_png(shot):
            failures.append(f"no screenshot written to {shot}: {r.stderr[-500:]}")
        else:
            print(f"screenshot: {shot}")
    for f in failures:
        print(f"FAIL: {f}")
    if failures:
        return 1
    print("browser test passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
