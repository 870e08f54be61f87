"""Tests of reports/make_report.py on the fixture results of tests/reports/fixtures/: the verdict
table rows, relative links that resolve, images present, the Markdown twin, the absent-part note,
and that a malformed input is a one-line error (exit 2) leaving no output. The link checker itself
is shown to reject an absolute and a dangling link. Exit 0 pass, 1 fail, 77 skip (no matplotlib or
Jinja2)."""
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import report_check as rc  # noqa: E402

SCRIPT = os.path.join(HERE, "..", "..", "reports", "make_report.py")
FIXTURES = os.path.join(HERE, "fixtures")
OUTPUTS = {"index.html", "report.md", "plots"}
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


def make(d):
    return subprocess.run([sys.executable, SCRIPT, "--dir", d], capture_output=True, text=True)


def fresh(tmp, name):
    d = os.path.join(tmp, name)
    shutil.copytree(FIXTURES, d)
    return d


for module, package in (("matplotlib", "python3-matplotlib"), ("jinja2", "python3-jinja2")):
    if importlib.util.find_spec(module) is None:
        print(f"SKIP: {sys.executable} lacks {module} (Debian: apt-get install {package}, "
              "see scripts/setup.sh)")
        sys.exit(77)

with tempfile.TemporaryDirectory() as tmp:
    # --- the whole fixture ---
    d = fresh(tmp, "full")
    r = make(d)
    check(r.returncode == 0, f"fixture report: exit 0 (got {r.returncode}: {r.stderr.strip()})")
    page = rc.parse_html(os.path.join(d, "index.html"))
    claims = json.load(open(os.path.join(FIXTURES, "verify", "claims.json")))
    header = ["claim", "paper, source", "verdict", "as recorded", "p-value", "control", "evidence"]
    verdicts = [t for t in page.tables if t and t[0] == header]
    check(len(verdicts) == 1, "one verdict table with the compact columns")
    if verdicts:
        t = verdicts[0]
        check([row[0] for row in t[1:]] == [c["id"] for c in claims],
              "one verdict row per claim, in claims.json's order")
        by_id = {row[0]: row for row in t[1:]}
        check(by_id["fixture.fails"][2] == "fails" and by_id["fixture.fails"][4] == "1.5e-09",
              f"fails row: verdict and p-value (got {by_id['fixture.fails']})")
        check("a finding" in by_id["fixture.fails"][3], "a recorded failure is called a finding")
        check(by_id["fixture.holds"][4] == "—", "a deterministic check shows no p-value")
        check("recorded: holds" in by_id["fixture.inconclusive"][3] and
              "regression" in by_id["fixture.inconclusive"][3],
              "a verdict that differs from the recorded one says so (a regression)")
        check("NOT REJECTED" in by_id["fixture.inconclusive"][5],
              "a control that was not rejected is flagged")
        check("control fails: rejected" in by_id["fixture.holds"][5],
              f"the control's own verdict is shown (got {by_id['fixture.holds'][5]})")
        check("control holds: NOT REJECTED" in by_id["fixture.inconclusive"][5],
              "the control's verdict that does not oppose the claim's is shown")
        check("<tag> & | pipe" in by_id["fixture.holds"][6], "evidence text kept verbatim")
        check("regime" in by_id["fixture.regime"][2] and "alpha >= 0.1" in by_id["fixture.regime"][2],
              "a holds-in-regime verdict shows its regime")
    # The models' conformance measured in this run: a model per row, a property per column.
    conf_header = ["model", "energy", "converges-to-smooth"]
    conf = [t for t in page.tables if t and t[0] == conf_header]
    check(len(conf) == 1, f"one conformance table, a column per property (got {[t[0] for t in page.tables if t]})")
    if conf:
        rows = {r[0]: r for r in conf[0][1:]}
        check(sorted(rows) == ["fixture_model", "other_model"], f"a row per model (got {sorted(rows)})")
        check(rows["fixture_model"][1].startswith("holds") and "NOT" not in rows["fixture_model"][1],
              f"a holds with its control rejected (got {rows['fixture_model'][1]!r})")
        check(rows["fixture_model"][2].startswith("not-claimed") and
              "NOT REJECTED" not in rows["fixture_model"][2],
              f"a property not claimed has no control to reject (got {rows['fixture_model'][2]!r})")
        check(rows["other_model"][1].startswith("fails (recorded: holds), control NOT REJECTED"),
              f"a verdict that is not the recorded one, a control not rejected (got {rows['other_model'][1]!r})")
        check(rows["other_model"][2] == "—", "a property not measured for a model is —")
    text = open(os.path.join(d, "index.html"), encoding="utf-8").read()
    check("left out by --conformance): third_model" in text,
          "the models whose conformance was not measured are named")
    check(text.count("<details>") >= len(claims) * 2, "evidence and controls folded in <details>")
    # The summary comes first and names findings, regressions and loose controls.
    summary = text[text.index('id="summary"'):text.index('id="contents"')]
    check("4 claims" in summary, "summary: the number of claims")
    check("3 of 4 as recorded" in summary, "summary: how many as recorded")
    check("a finding" in summary and 'href="#claim-fixture.fails"' in summary,
          "summary: the recorded failure as a finding, linked")
    check("Smallest correction" in summary and "the fixture formula divided by 2" in summary and
          "the fixture formula is exact" in summary and "cross-checked by finite" in summary,
          "summary: a finding shows the paper's sentence, the causes excluded, the correction")
    check("a competing cause is not excluded" in summary,
          "summary: a measured failure with a cause open is listed apart, not as a finding")
    check("a regression" in summary and 'href="#claim-fixture.inconclusive"' in summary,
          "summary: the differing verdict as a regression, linked")
    check("1 of 4 negative controls NOT rejected" in summary, "summary: the control not rejected")
    check(text.index('id="summary"') < text.index('id="contents"') < text.index('id="verdicts"'),
          "summary, then contents, then the verdicts")
    anchors = {h[1:] for h in page.hrefs if h.startswith("#")}
    for want in ["summary", "verdicts", "figures", "speed", "stability", "fig-fixture2026-fig1",
                 "claim-fixture.fails"]:
        check(want in anchors, f"in-page link to #{want}")
    missing = [a for a in anchors if f'id="{a}"' not in text]
    check(not missing, f"every in-page link has its target (missing: {missing})")
    # The plot manifest: every chart with title, axis labels, legend, and colour scale for maps.
    manifest = json.load(open(os.path.join(d, "plots", "plots.json")))["plots"]
    charts = {p["file"] for p in manifest}
    check(charts == {s for s, c in page.imgs if "chart" in c.split()},
          "every chart shown is in plots/plots.json")
    # A figure's own chart (figure_charts.py drew it from its spec when the figure ran): shown
    # from the figure's folder as a chart, its labels read back from the PNG.
    curve = [p for p in manifest if p["file"] == "figures/fixture2026-fig1/curve.png"]
    check(len(curve) == 1 and curve[0]["axes"][0]["xlabel"] == "angle [deg]"
          and curve[0]["axes"][0]["legend"],
          "the figure's chart curve.png is shown with the labels it records")
    for p in manifest:
        for ax in p["axes"]:
            # A rendered panel is named by its title (no legend); its size is recorded for the
            # browser test.
            check(ax["xlabel"] and ax["ylabel"] and ax["title"] and (ax["legend"] or ax["render"]),
                  f"{p['file']}: title, axis labels and legend ({ax})")
            check(not ax["render"] or (ax.get("image_px") == [128, 128] and ax.get("drawn_px")),
                  f"{p['file']}: a rendered panel's pixels and drawn size recorded ({ax})")
            check(not ax["map"] or ax["colorbar"], f"{p['file']}: a map has a colour scale")
    # The sweep's own heat maps (figure_charts.py drew them when the sweep ran): shown from the
    # sweep's folder, one chart per quantity, their labels read back from the PNGs; the report
    # draws no map of its own.
    st = [p for p in manifest if p["file"].startswith("stability/maps/")]
    check(sorted(p["file"] for p in st) == ["stability/maps/fixture_model_energy_gain.png",
                                            "stability/maps/fixture_model_nan_fraction.png"]
          and all(len(p["axes"]) == 1 and p["axes"][0]["map"] and p["axes"][0]["colorbar"]
                  for p in st),
          "each stability map is the sweep's own heat map, with its colour bar")
    check(not any(p["file"].startswith("plots/stability__") for p in manifest),
          "no stability chart drawn again by the report")
    bad = rc.bad_targets(d, page.hrefs + page.srcs)
    check(not bad, f"every link and image is relative and resolves (bad: {bad})")
    check(all(rc.is_png(os.path.join(d, s)) for s in page.srcs), "every <img> is a PNG file")
    for want in ["figures/fixture2026-fig1/fig1.png", "plots/speed_accuracy.png",
                 "plots/fixture2026-fig1__rmse_spp_convergence.png",
                 "stability/maps/fixture_model_nan_fraction.png",
                 "stability/maps/fixture_model_energy_gain.png"]:
        check(want in page.srcs, f"image {want} shown")
    for want in ["figures/fixture2026-fig1/fig1.exr", "figures/fixture2026-fig1/rmse_spp.csv",
                 "stability/maps/fixture_model_energy_gain.exr",
                 "stability/maps/fixture_model_alpha.csv", "verify/claims.json",
                 "plots/speed_accuracy.csv"]:
        check(want in page.hrefs, f"link to {want}")
    check("NaN for alpha below 1e-3 at grazing" in text, "the failure region in words")
    check("Fixture CPU, 2 cores" in text and "budget quick" in text, "machine and budget named")
    check("&lt;tag&gt;" in text, "text is HTML-escaped")
    # A figure's summary.md: its Markdown table shown as an HTML table, and nothing on the page a
    # reader would take for a missing measurement.
    check(["quantity", "paper", "ours"] in [t[0] for t in page.tables if t] and
          ["ratio", "0.5", "0.52"] in [r for t in page.tables for r in t],
          "summary.md's Markdown table is an HTML table")
    problems = rc.visible_problems(text)
    check(not problems, f"no visible nan, NOT FOUND or raw Markdown table (got {problems})")
    # The Markdown twin: same verdict rows, same images, links resolve.
    links, images, md = rc.markdown_targets(os.path.join(d, "report.md"))
    rows = [ln for ln in md.splitlines() if ln.startswith("| fixture.")]
    check([ln.split(" | ")[0][2:] for ln in rows] == [c["id"] for c in claims],
          "Markdown twin: one verdict row per claim")
    check(sorted(images) == sorted(page.srcs), "Markdown twin shows the same images")
    check("## Summary" in md and "## Contents" in md, "Markdown twin: summary and contents")
    bad = rc.bad_targets(d, links + images)
    check(not bad, f"Markdown links resolve (bad: {bad})")
    check(r"\| pipe" in md, "a | in a Markdown cell is escaped")
    check("\n| ratio | 0.5 | 0.52 |\n" in md, "Markdown twin: summary.md's table is a table")
    # The checker can fail: an absolute link, a dangling one, one leaving the report.
    check(len(rc.bad_targets(d, ["/etc/passwd", "http://x/y.png", "nope.png", "../x.png",
                                 "#top"])) == 4, "link checker rejects bad targets")

    # --- a figure without its benchmark data, the old way: a table of nan and NOT FOUND ---
    d = fresh(tmp, "nan_table")
    with open(os.path.join(d, "figures", "fixture2026-fig1", "summary.md"), "w") as f:
        f.write("# fixture2026-fig1\n\nGoogle Benchmark JSON out/bench/glints.json (NOT FOUND: our "
                "columns are empty)\n\n| light | smooth ns | paper ms |\n|---|---|---|\n"
                "| area | nan | 1.7 |\n| none | -nan / 2 | 1.4 |\n")
    r = make(d)
    check(r.returncode == 0, f"report of the broken figure: exit 0 (got {r.returncode})")
    problems = rc.visible_problems(open(os.path.join(d, "index.html"), encoding="utf-8").read())
    check(len([p for p in problems if "shows nan" in p]) == 2 and
          any("NOT FOUND" in p for p in problems),
          f"the check fails a table of nan and a visible NOT FOUND (got {problems})")
    # ... and a summary.md shown as raw Markdown text (as the report once did, in a <pre>).
    raw = ("<details><summary>summary.md</summary><pre>" +
           open(os.path.join(FIXTURES, "figures", "fixture2026-fig1", "summary.md")).read() +
           "</pre></details>")
    check(any("raw Markdown table" in p for p in rc.visible_problems(raw)),
          "the check fails a Markdown table left as raw text")
    check(not rc.visible_problems("<table><tr><td>NaN for alpha below 1e-3</td>"
                                  "<td>nan_fraction</td></tr></table>"),
          "the word NaN in a sentence and nan_fraction are not values")

    # --- the comparison: verdicts copied from the source apart from those of this run ---
    sys.path.insert(0, os.path.join(HERE, "..", "..", "reports"))
    import compare_page  # noqa: E402
    model = {"name": "m", "timing": {"scalar_ns_per_eval": 2.0, "best_ns_per_eval": 1.0,
                                     "best_isa": "avx2", "batched": True},
             "reference": [], "equal_time": {"not_shown": "no sampler", "points": []},
             "stability": [{"sampler": "s", "verdict": "holds", "origin": "read",
                            "failure_region": "none"}],
             "conformance": [{"property": p, "verdict": v, "origin": o, "detail": ""}
                             for p, v, o in [("measured-here", "holds", "measured"),
                                             ("from-verify", "holds", "read"),
                                             ("copied", "fails", "recorded"),
                                             ("unclaimed", "not-claimed", "declared")]]}
    cpage = rc.Page()
    cpage.feed(compare_page.table_html({"models": [model]}))
    head, row = cpage.tables[0][0], cpage.tables[0][1]
    check(head[1] == "conformance, this run" and "recorded" in head[2] and
          "verify/conformance/conformance.cpp" in head[2],
          f"compare: a column for this run, one for recorded verdicts naming their source ({head})")
    check("measured-here" in row[1] and "from-verify" in row[1] and "recorded" not in row[1] and
          "copied: fails (recorded)" in row[2] and "unclaimed" in row[2] and
          "measured-here" not in row[2],
          f"compare: recorded and declared verdicts only in their own column ({row})")
    cmd = compare_page.table_markdown({"models": [model]}).splitlines()
    check(len(cmd) == 3 and cmd[2].split(" | ")[1] == "holds 1, holds (read) 1" and
          cmd[2].split(" | ")[2] == "fails (recorded) 1, not-claimed (declared) 1",
          f"compare Markdown: the same two columns ({cmd[-1]})")

    # --- the adequacy section: its claims' verdicts and its figures, not among the papers' ---
    d = fresh(tmp, "adequacy")
    os.rename(os.path.join(d, "figures", "fixture2026-fig1"),
              os.path.join(d, "figures", "adequacy-scene"))
    figs = json.load(open(os.path.join(d, "figures", "figures.json")))
    figs[0]["id"] = "adequacy-scene"
    # adequacy-maps with its index of maps: one binomial and two Kemppinen maps.
    maps_dir = os.path.join(d, "figures", "adequacy-maps")
    os.makedirs(maps_dir)
    with open(os.path.join(maps_dir, "adequacy-maps-index.csv"), "w") as fh:
        fh.write("map,family,model,theta_i_deg,light_half_angle_deg,ggaa_dh,png,exr\n"
                 "adequacy_deliot_belcour_light0_theta0,binomial,deliot_belcour,0,0,nan,a.png,a.exr\n"
                 "adequacy_kemppinen_ggx_theta0,kemppinen,kemppinen_ggx,0,nan,nan,b.png,b.exr\n"
                 "adequacy_kemppinen_beckmann_theta0,kemppinen,kemppinen_beckmann,0,nan,nan,c.png,"
                 "c.exr\n")
    with open(os.path.join(maps_dir, "summary.md"), "w") as fh:
        fh.write("# adequacy-maps\n\nthree maps\n")
    figs.append({**figs[0], "id": "adequacy-maps"})
    json.dump(figs, open(os.path.join(d, "figures", "figures.json"), "w"))
    c = json.load(open(os.path.join(d, "verify", "claims.json")))
    c.append({**c[0], "id": "adequacy.choice-is-safe", "detail": "1 of 19423 lit pixels over TAU"})
    json.dump(c, open(os.path.join(d, "verify", "claims.json"), "w"))
    r = make(d)
    check(r.returncode == 0, f"report with adequacy: exit 0 (got {r.returncode}: {r.stderr.strip()})")
    text = open(os.path.join(d, "index.html"), encoding="utf-8").read()
    check('id="adequacy"' in text and 'id="fig-adequacy-scene"' in text and
          text.index('id="adequacy"') < text.index('id="fig-adequacy-scene"'),
          "the adequacy figure is shown under the adequacy section")
    check(text.index('id="figures"') < text.index('id="adequacy"') and
          "0 figures." in text[text.index('id="figures"'):text.index('id="adequacy"')],
          "and not among the papers' figures")
    check("adequacy.choice-is-safe: holds — 1 of 19423 lit pixels over TAU" in text,
          "the adequacy claims' verdicts are listed in the section")
    section = text[text.index('id="adequacy"'):]
    check('id="fig-adequacy-maps"' in section and
          "adequacy-maps draws 3 maps of the chosen level, per family: binomial family 1 "
          "(deliot_belcour); Kemppinen family 2 (kemppinen_ggx, kemppinen_beckmann)." in section and
          "Not drawn: the area, Chermain families." in section,
          "the adequacy section names the maps' families from adequacy-maps-index.csv")

    # --- a check that could not run (verdict error): shown with its cause, no control ---
    d = fresh(tmp, "error_row")
    c = json.load(open(os.path.join(d, "verify", "claims.json")))
    c.append({**c[0], "id": "fixture.error", "paper": "Fixture 2026", "source": "Eq. 1",
              "verdict": "error", "expected_verdict": "holds",
              "detail": "model faulty: energy: exception: eval failed on purpose",
              "statistic": "none (the check could not compute its statistic)", "value": 0,
              "bound": None, "p_value": None, "suite_adjusted_p_value": None,
              "raw_p_values": [], "control": "none: the check could not run",
              "control_p_value": None, "control_rejected": False, "budget": "quick",
              "seconds": 0.1, "control_verdict": None, "regime": None})
    json.dump(c, open(os.path.join(d, "verify", "claims.json"), "w"))
    r = make(d)
    check(r.returncode == 0, f"report with an error row: exit 0 (got {r.returncode}: "
          f"{r.stderr.strip()})")
    page = rc.parse_html(os.path.join(d, "index.html"))
    rows = {row[0]: row for t in page.tables if t and t[0] == header for row in t[1:]}
    err = rows.get("fixture.error", [""] * 7)
    check(err[2] == "error" and "could not run" in err[3] and "none" in err[5] and
          "eval failed on purpose" in err[6],
          f"error row: verdict, as recorded, control and cause (got {err})")
    text = open(os.path.join(d, "index.html"), encoding="utf-8").read()
    summary = text[text.index('id="summary"'):text.index('id="contents"')]
    check("Could not be checked (error)" in summary and "eval failed on purpose" in summary and
          "1 of 5 negative controls NOT rejected" in summary,
          "summary: the error named with its cause, not counted as a control not rejected")

    # --- a part absent: the report says so ---
    d = fresh(tmp, "no_stability")
    shutil.rmtree(os.path.join(d, "stability"))
    run = json.load(open(os.path.join(d, "run.json")))
    run["parts"]["stability"] = {"status": "unavailable", "note": "no sweep subcommand"}
    json.dump(run, open(os.path.join(d, "run.json"), "w"))
    r = make(d)
    check(r.returncode == 0, "report without stability part: exit 0")
    text = open(os.path.join(d, "index.html"), encoding="utf-8").read()
    check("Not in this report" in text and "no sweep subcommand" in text,
          "an absent part is named with its reason")

    # --- malformed inputs: one line, exit 2, no output ---
    def corrupt_claims(d):
        with open(os.path.join(d, "verify", "claims.json"), "w") as f:
            f.write('[{"id": "x", ')

    def claims_wrong_type(d):
        c = json.load(open(os.path.join(d, "verify", "claims.json")))
        c[1]["p_value"] = "small"
        json.dump(c, open(os.path.join(d, "verify", "claims.json"), "w"))

    def claims_field_missing(d):
        c = json.load(open(os.path.join(d, "verify", "claims.json")))
        del c[2]["power"]
        json.dump(c, open(os.path.join(d, "verify", "claims.json"), "w"))

    def claims_field_unknown(d):
        c = json.load(open(os.path.join(d, "conformance", "claims.json")))
        c[0]["p"] = 0.5
        json.dump(c, open(os.path.join(d, "conformance", "claims.json"), "w"))

    def claims_verdict_unknown(d):
        c = json.load(open(os.path.join(d, "verify", "claims.json")))
        c[0]["verdict"] = "passes"
        json.dump(c, open(os.path.join(d, "verify", "claims.json"), "w"))

    def schema_missing(d):
        os.unlink(os.path.join(d, "schemas", "claims.schema.json"))

    def schema_unknown_rule(d):
        p = os.path.join(d, "schemas", "claims.schema.json")
        schema = json.load(open(p))
        schema["items"]["properties"]["value"]["minimum"] = 0
        json.dump(schema, open(p, "w"))

    def ragged_csv(d):
        with open(os.path.join(d, "figures", "fixture2026-fig1", "rmse_spp.csv"), "a") as f:
            f.write("0.2,a,32\n")

    def stability_csv_columns(d):
        p = os.path.join(d, "stability", "maps", "fixture_model_alpha.csv")
        s = open(p).read().replace("theta_i_deg", "theta", 1)
        open(p, "w").write(s)

    def control_verdict_number(d):
        c = json.load(open(os.path.join(d, "verify", "claims.json")))
        c[0]["control_verdict"] = 3
        json.dump(c, open(os.path.join(d, "verify", "claims.json"), "w"))

    def missing_map(d):
        os.unlink(os.path.join(d, "stability", "maps", "fixture_model_energy_gain.png"))

    def map_not_a_chart(d):  # a raster without the chart record figure_charts.py stores
        shutil.copy(os.path.join(d, "figures", "fixture2026-fig1", "fig1.png"),
                    os.path.join(d, "stability", "maps", "fixture_model_energy_gain.png"))

    def run_says_ran(d):
        os.unlink(os.path.join(d, "bench", "bench.json"))

    def bad_accuracy(d):
        p = os.path.join(d, "bench", "accuracy.csv")
        s = open(p).read().replace(",1e-07,5e-08,1e-07", ",1e-07,abc,1e-07", 1)
        open(p, "w").write(s)

    def conformance_id(d):
        p = os.path.join(d, "conformance", "claims.json")
        s = open(p).read().replace("model.other_model.energy", "other_model.energy", 1)
        open(p, "w").write(s)

    def chart_not_drawn(d):
        os.unlink(os.path.join(d, "figures", "fixture2026-fig1", "curve.png"))

    cases = [(chart_not_drawn, "curve.chart.json: its chart curve.png is missing"),
             (corrupt_claims, "verify/claims.json is not valid JSON"),
             (conformance_id, "('other_model.energy') is not a model.<name>.<property> id"),
             (claims_wrong_type, "entry 1 (fixture.fails) \"p_value\" is string 'small', the "
                                 "schema wants number or null"),
             (claims_field_missing, "entry 2 (fixture.inconclusive) lacks power"),
             (claims_field_unknown, "conformance/claims.json does not follow the schema of "
                                    "claims.json (schemas/claims.schema.json): entry 0 "
                                    "(model.fixture_model.energy) has p, which the schema does "
                                    "not name"),
             (claims_verdict_unknown, "\"verdict\" is 'passes' (valid: holds, holds-within"),
             (schema_missing, "schemas/claims.schema.json is missing"),
             (schema_unknown_rule, "uses minimum, which this checker does not implement"),
             (ragged_csv, "rmse_spp.csv is malformed: line"),
             (missing_map, "fixture_model_energy_gain.png"),
             (map_not_a_chart, "fixture_model_energy_gain.png: the sweep's map of fixture_model "
                               "energy_gain was not drawn by reports/figure_charts.py"),
             (run_says_ran, "bench/bench.json is missing"),
             (bad_accuracy, "accuracy.csv is malformed"),
             (stability_csv_columns, "missing column(s) theta_i_deg"),
             (control_verdict_number, "\"control_verdict\" is 3 (valid: holds")]
    for i, (mutate, needle) in enumerate(cases):
        d = fresh(tmp, f"bad{i}")
        mutate(d)
        before = set(os.listdir(d))
        r = make(d)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2, f"{mutate.__name__}: exit 2 (got {r.returncode})")
        check(len(lines) == 1 and lines[0].startswith("glintlab: error: ") and needle in lines[0],
              f"{mutate.__name__}: one error line naming '{needle}' (got {lines})")
        check(set(os.listdir(d)) == before and not (OUTPUTS & before),
              f"{mutate.__name__}: no output written (new: {set(os.listdir(d)) - before})")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("report writer tests passed")
