"""The glintlab report: index.html and its Markdown twin report.md from a folder
of results, with the plots drawn here from the results' CSVs.

Run by /usr/bin/python3 (Debian's, with matplotlib); `glintlab report` calls it on its staging
folder DIR, which holds:
  run.json                 machine, budget, date and status of each part (written by glintlab report)
  verify/claims.json       glintlab verify's results (a list of claim objects)
  figures/figures.json     the figures run ([{id, paper, target, description, ...}]) and
  figures/<id>/            each figure's PNG, EXR, CSV (and summary.md) files
  bench/bench.json         Google Benchmark JSON of glintlab_bench_kernels, and
  bench/accuracy.csv       glintlab_accuracy's errors: joined into the speed-vs-accuracy chart
  stability/stability.json glintlab sweep's maps: {machine, budget, models: [{model, sampler,
                           maps: [{quantity, png, exr, csv}], failure_region}]}
A part may be absent (skipped, or not available in this build): the report says so. Every input
is validated before anything is written; a malformed one is a one-line error
("glintlab: error: ..."), exit 2, and no output. Outputs (plots/, index.html, report.md) are written
to temporary names and renamed into place last.

Plots: for every figure CSV with an `spp` and an `rmse` column, an RMSE table, and where a series
has two or more spp values, a log-log convergence plot (RMSE vs spp, one line per series, with the
slope -1/2 of an unbiased Monte Carlo estimator for reference). Series are the rows sharing the
CSV's text columns and its parameter columns (alpha*, theta*, density, microroughness, spp of the
reference). The speed-vs-accuracy chart with per-method Pareto fronts is reports/speed_accuracy.py's.
Every plot names the machine (CPU model, cores) and the budget its data came from.
"""

import argparse
import csv
import glob
import html
import json
import math
import os
import shutil
import sys
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import speed_accuracy as sa  # noqa: E402

PARTS = ["claims", "figures", "bench", "stability"]
PART_TITLES = {"claims": "Claims (glintlab verify)", "figures": "Figures (glintlab figure)",
               "bench": "Benchmarks (glintlab_bench_kernels, glintlab_accuracy)",
               "stability": "Stability maps (glintlab sweep)"}
CLAIM_KEYS = {"id": str, "paper": str, "source": str, "verdict": str, "detail": str,
              "control": str, "control_rejected": bool}
VERDICTS = {"holds", "holds-within", "holds-in-regime", "fails", "inconclusive"}
PARAM_COLUMNS = {"density", "microroughness", "reference_spp", "model", "sampler", "light"}
TABLE_ROW_LIMIT = 80


class ReportError(Exception):
    """A malformed input: becomes the one-line error."""


def rel(path, root):
    return os.path.relpath(os.path.realpath(path), os.path.realpath(root)).replace(os.sep, "/")


def url(relpath):
    return urllib.parse.quote(relpath)


def esc(text):
    return html.escape(str(text), quote=True)


def md_cell(text):
    return str(text).replace("\\", "\\\\").replace("|", "\\|").replace("\n", " ")


def load_json(root, relpath):
    path = os.path.join(root, relpath)
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise ReportError(f"cannot read {relpath}: {e.strerror}")
    except ValueError as e:
        raise ReportError(f"{relpath} is not valid JSON ({e})")


def load_csv(root, relpath):
    """(header, rows) of a CSV; every row must have the header's number of cells."""
    path = os.path.join(root, relpath)
    try:
        with open(path, newline="", encoding="utf-8") as f:
            table = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise ReportError(f"cannot read {relpath} as CSV ({e})")
    table = [r for r in table if r]
    if not table or not all(c.strip() for c in table[0]):
        raise ReportError(f"{relpath} is malformed: no header row of column names")
    header = table[0]
    for i, r in enumerate(table[1:], start=2):
        if len(r) != len(header):
            raise ReportError(f"{relpath} is malformed: line {i} has {len(r)} cells, the header "
                              f"{len(header)}")
    return header, table[1:]


def number(cell):
    try:
        v = float(cell)
    except ValueError:
        return None
    return v


def tidy(cell):
    """A long decimal (0.20000000000000001) shown to 6 significant digits; integers and text as is."""
    if len(cell) <= 9 or number(cell) is None or cell.lstrip("-").isdigit():
        return cell
    return f"{float(cell):.6g}"


def machine_text(m):
    if isinstance(m, dict):
        cores = m.get("cores")
        threads = m.get("threads")
        s = str(m.get("cpu_model", "unknown CPU"))
        if cores:
            s += f", {cores} cores"
        if threads:
            s += f" ({threads} threads used)"
        return s
    return str(m) if m else "unknown machine"


# ----------------------------------------------------------------------------------------------
# Loading and validation (nothing is written until all of it passed)

def load_run(root):
    if not os.path.exists(os.path.join(root, "run.json")):
        return {"parts": {}}
    run = load_json(root, "run.json")
    if not isinstance(run, dict) or not isinstance(run.get("parts", {}), dict):
        raise ReportError("run.json is malformed: expected an object with a \"parts\" object")
    for name, part in run.get("parts", {}).items():
        if not isinstance(part, dict) or not isinstance(part.get("status", ""), str):
            raise ReportError(f"run.json is malformed: part \"{name}\" is not an object with a "
                              "status")
    return run


def load_claims(root):
    relpath = "verify/claims.json"
    data = load_json(root, relpath)
    if not isinstance(data, list):
        raise ReportError(f"{relpath} is malformed: expected a list of claim objects")
    for i, c in enumerate(data):
        if not isinstance(c, dict):
            raise ReportError(f"{relpath} is malformed: entry {i} is not an object")
        for k, t in CLAIM_KEYS.items():
            if not isinstance(c.get(k), t):
                raise ReportError(f"{relpath} is malformed: entry {i} lacks \"{k}\" "
                                  f"({t.__name__})")
        if c["verdict"] not in VERDICTS:
            raise ReportError(f"{relpath} is malformed: entry {i} ({c['id']}) has verdict "
                              f"'{c['verdict']}' (valid: {', '.join(sorted(VERDICTS))})")
        for k in ("p_value", "control_p_value"):
            v = c.get(k)
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float))):
                raise ReportError(f"{relpath} is malformed: entry {i} ({c['id']}) has a "
                                  f"non-numeric \"{k}\"")
    return data


def load_figures(root):
    relpath = "figures/figures.json"
    data = load_json(root, relpath)
    if not isinstance(data, list):
        raise ReportError(f"{relpath} is malformed: expected a list of figure objects")
    figures = []
    for i, f in enumerate(data):
        if not isinstance(f, dict) or not isinstance(f.get("id"), str) or not f["id"]:
            raise ReportError(f"{relpath} is malformed: entry {i} has no \"id\"")
        fid = f["id"]
        d = os.path.join(root, "figures", fid)
        if "/" in fid or fid.startswith(".") or not os.path.isdir(d):
            raise ReportError(f"{relpath} names figure '{fid}' but figures/{fid}/ is missing")
        files = sorted(n for n in os.listdir(d) if not n.startswith("."))
        csvs = {}
        for n in files:
            if n.endswith(".csv"):
                csvs[n] = load_csv(root, f"figures/{fid}/{n}")
        summary = None
        if "summary.md" in files:
            with open(os.path.join(d, "summary.md"), encoding="utf-8", errors="replace") as fh:
                summary = fh.read()
        figures.append({**f, "dir": d, "files": files, "csvs": csvs, "summary": summary})
    return figures


def load_bench(root):
    data = load_json(root, "bench/bench.json")
    if not isinstance(data, dict) or not isinstance(data.get("benchmarks"), list):
        raise ReportError("bench/bench.json is malformed: expected Google Benchmark JSON with a "
                          "\"benchmarks\" list")
    for i, b in enumerate(data["benchmarks"]):
        if not isinstance(b, dict) or not isinstance(b.get("name"), str):
            raise ReportError(f"bench/bench.json is malformed: benchmark {i} has no name")
        ips = b.get("items_per_second")
        if ips is not None and (not isinstance(ips, (int, float)) or ips <= 0):
            raise ReportError(f"bench/bench.json is malformed: {b['name']} has items_per_second "
                              f"{ips!r} (a positive number is expected)")
    speeds, context = sa.load_bench(os.path.join(root, "bench/bench.json"))
    acc = None
    if os.path.exists(os.path.join(root, "bench/accuracy.csv")):
        header, rows = load_csv(root, "bench/accuracy.csv")
        need = ["method", "kernel", "isa", "math", "reference", "max_rel_error", "rms_rel_error",
                "p99_rel_error", "nonfinite_mismatch"]
        missing = [c for c in need if c not in header]
        if missing:
            raise ReportError(f"bench/accuracy.csv is malformed: missing column(s) "
                              f"{', '.join(missing)}")
        acc = [dict(zip(header, r)) for r in rows]
        for i, r in enumerate(acc, start=2):
            for c in ("max_rel_error", "rms_rel_error", "p99_rel_error"):
                if number(r[c]) is None:
                    raise ReportError(f"bench/accuracy.csv is malformed: line {i} column {c} is "
                                      f"'{r[c]}', not a number")
    return {"json": data, "speeds": speeds, "context": context, "accuracy": acc}


def stability_file(root, relpath, what):
    """A map file named by stability.json: relative to stability/ (or to the report folder, or an
    absolute path), and in either case an existing file inside stability/."""
    if not isinstance(relpath, str) or not relpath:
        raise ReportError(f"stability/stability.json is malformed: {what} is not a file name")
    base = os.path.realpath(os.path.join(root, "stability"))
    for p in (os.path.join(base, relpath), os.path.join(root, relpath)):
        p = os.path.realpath(p)
        if os.path.commonpath([base, p]) == base and os.path.isfile(p):
            return p
    raise ReportError(f"stability/stability.json names {what} '{relpath}', which is not a file "
                      "in stability/")


def load_stability(root):
    relpath = "stability/stability.json"
    data = load_json(root, relpath)
    if not isinstance(data, dict) or not isinstance(data.get("models"), list):
        raise ReportError(f"{relpath} is malformed: expected an object with a \"models\" list")
    for i, m in enumerate(data["models"]):
        if not isinstance(m, dict) or not isinstance(m.get("model"), str) or \
                not isinstance(m.get("maps"), list):
            raise ReportError(f"{relpath} is malformed: model {i} needs \"model\" and \"maps\"")
        if not isinstance(m.get("failure_region", ""), str):
            raise ReportError(f"{relpath} is malformed: model {i} has a non-text failure_region")
        for j, mp in enumerate(m["maps"]):
            if not isinstance(mp, dict) or not isinstance(mp.get("quantity"), str):
                raise ReportError(f"{relpath} is malformed: model {i} map {j} has no quantity")
            for k in ("png", "exr", "csv"):
                where = f"model {m['model']} map {mp['quantity']} {k}"
                mp[k + "_path"] = stability_file(root, mp.get(k), where)
            load_csv(root, rel(mp["csv_path"], root))
    return data


def load_all(root):
    run = load_run(root)
    parts = run.get("parts", {})
    got = {}
    loaders = {"claims": ("verify/claims.json", load_claims),
               "figures": ("figures/figures.json", load_figures),
               "bench": ("bench/bench.json", load_bench),
               "stability": ("stability/stability.json", load_stability)}
    for name, (index, loader) in loaders.items():
        if os.path.exists(os.path.join(root, index)):
            got[name] = loader(root)
        elif parts.get(name, {}).get("status") in ("ran", "reused", "read"):
            raise ReportError(f"run.json says part {name} was {parts[name]['status']} but {index} "
                              "is missing")
    return run, got


# ----------------------------------------------------------------------------------------------
# Plots

def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def is_param_column(name):
    return name in PARAM_COLUMNS or name.startswith("alpha") or name.startswith("theta")


def series_of(header, rows):
    """{series label: [(spp, rmse)]} for a CSV with spp and rmse columns."""
    i_spp, i_rmse = header.index("spp"), header.index("rmse")
    keys = []
    for k, name in enumerate(header):
        if k in (i_spp, i_rmse) or name == "seed":
            continue
        text = any(number(r[k]) is None for r in rows)
        if text or is_param_column(name):
            keys.append(k)
    out = {}
    for r in rows:
        spp, e = number(r[i_spp]), number(r[i_rmse])
        if spp is None or e is None or spp <= 0 or not math.isfinite(e) or e <= 0:
            continue
        label = ", ".join(f"{header[k]}={tidy(r[k])}" for k in keys) or "all rows"
        out.setdefault(label, []).append((spp, e))
    return out


def convergence_plot(fig_id, csv_name, header, rows, path, machine, budget):
    """Log-log RMSE vs spp; returns False when no series has two spp values."""
    series = {k: sorted(v) for k, v in series_of(header, rows).items()
              if len({s for s, _ in v}) >= 2}
    if not series:
        return False
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for label, pts in series.items():
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, lw=1, label=label)
    # Slope -1/2 through the first point of the first series: an unbiased estimator's rate.
    s0, e0 = next(iter(series.values()))[0]
    smax = max(p[0] for v in series.values() for p in v)
    ax.plot([s0, smax], [e0, e0 * math.sqrt(s0 / smax)], color="gray", ls="--", lw=0.8,
            label="slope -1/2 (unbiased Monte Carlo)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("samples per pixel [spp]")
    ax.set_ylabel("RMSE against the reference [linear radiance]")
    ax.set_title(f"{fig_id}: {csv_name} convergence\n{machine}; budget {budget}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110, format="png")
    plt.close(fig)
    return True


def speed_accuracy_plot(bench, plots, machine, budget):
    """speed_accuracy.csv and .png (reports/speed_accuracy.py's join, fronts and chart)."""
    rows = [dict(r) for r in bench["accuracy"]]
    timed = sa.join(rows, bench["speeds"], "max")
    if not timed:
        return None
    sa.write_csv(rows, os.path.join(plots, "speed_accuracy.csv"))
    date = str(bench["context"].get("date", ""))[:10]
    sa.plot(timed, os.path.join(plots, "speed_accuracy.png"), "max", f"{machine}; budget {budget}",
            date)
    return timed


# ----------------------------------------------------------------------------------------------
# Writing

class Doc:
    """The HTML body and the Markdown twin, built side by side."""

    def __init__(self):
        self.html, self.md = [], []

    def heading(self, level, text, anchor):
        self.html.append(f'<h{level} id="{esc(anchor)}">{esc(text)}</h{level}>')
        self.md.append(f"{'#' * level} {text}\n")

    def para(self, text, md=None):
        self.html.append(f"<p>{esc(text)}</p>")
        self.md.append((md if md is not None else text) + "\n")

    def raw(self, html_text, md_text):
        self.html.append(html_text)
        self.md.append(md_text)

    def table(self, header, rows, classes=None):
        """rows: lists of (text, href or None) or plain text cells."""
        h = ["<table><thead><tr>" + "".join(f"<th>{esc(c)}</th>" for c in header) +
             "</tr></thead><tbody>"]
        m = ["| " + " | ".join(md_cell(c) for c in header) + " |",
             "|" + "---|" * len(header)]
        for i, r in enumerate(rows):
            cls = f' class="{esc(classes[i])}"' if classes and classes[i] else ""
            hc, mc = [], []
            for c in r:
                text, href = c if isinstance(c, tuple) else (c, None)
                if href:
                    hc.append(f'<td><a href="{esc(url(href))}">{esc(text)}</a></td>')
                    mc.append(f"[{md_cell(text)}]({url(href)})")
                else:
                    hc.append(f"<td>{esc(text)}</td>")
                    mc.append(md_cell(text))
            h.append(f"<tr{cls}>" + "".join(hc) + "</tr>")
            m.append("| " + " | ".join(mc) + " |")
        h.append("</tbody></table>")
        self.html.append("\n".join(h))
        self.md.append("\n".join(m) + "\n")

    def image(self, href, alt, caption, preview=False):
        """preview: a small rendered image, drawn enlarged with visible pixels."""
        cls = ' class="preview"' if preview else ""
        self.html.append(f'<figure><a href="{esc(url(href))}"><img{cls} src="{esc(url(href))}" '
                         f'alt="{esc(alt)}"></a><figcaption>{esc(caption)}</figcaption></figure>')
        self.md.append(f"![{md_cell(alt)}]({url(href)})\n\n*{caption}*\n")

    def links(self, label, items):
        """items: [(text, href)]."""
        if not items:
            return
        self.html.append(f"<p>{esc(label)}: " + ", ".join(
            f'<a href="{esc(url(h))}">{esc(t)}</a>' for t, h in items) + "</p>")
        self.md.append(f"{label}: " + ", ".join(f"[{md_cell(t)}]({url(h)})" for t, h in items) +
                       "\n")

    def pre(self, text):
        self.html.append(f"<pre>{esc(text)}</pre>")
        self.md.append("\n".join("    " + line for line in text.splitlines()) + "\n")


def fmt_p(v):
    if v is None:
        return "—"
    return f"{v:.3g}"


def part_line(name, part):
    status = part.get("status", "absent") if part else "absent"
    s = f"{PART_TITLES[name]}: {status}"
    if part and status in ("ran", "reused", "read"):
        if part.get("budget"):
            s += f", budget {part['budget']}"
        if part.get("machine"):
            s += f", {machine_text(part['machine'])}"
        if part.get("date"):
            s += f", {part['date']}"
        if part.get("seconds") is not None:
            s += f", {float(part['seconds']):.1f} s"
    if part and part.get("note"):
        s += f" — {part['note']}"
    return s


def write_claims(doc, claims, part, root):
    doc.heading(2, "Verdicts", "verdicts")
    doc.para(f"{len(claims)} claims. Budget {part.get('budget', '?')}, "
             f"{machine_text(part.get('machine'))}. Verdicts: holds, holds-within, "
             "holds-in-regime, fails, inconclusive; each check's negative control (a "
             "deliberately wrong input) must be rejected for the verdict to count.")
    doc.links("Files", [("claims.json", "verify/claims.json"), ("claims.csv", "verify/claims.csv"),
                        ("claims.md", "verify/claims.md")])
    rows, classes = [], []
    for c in claims:
        verdict = c["verdict"]
        exp = c.get("expected_verdict")
        if isinstance(exp, str) and exp != verdict:
            verdict += f" (recorded: {exp})"
        evidence = c["detail"]
        control = c["control"] + (" — rejected" if c["control_rejected"]
                                  else " — NOT REJECTED (the check is broken)")
        if c.get("control_p_value") is not None:
            control += f" (p {fmt_p(c['control_p_value'])})"
        rows.append([c["id"], c["paper"], c["source"], verdict, evidence, fmt_p(c.get("p_value")),
                     control])
        classes.append("v-" + c["verdict"])
    doc.table(["claim", "paper", "source", "verdict", "evidence", "p-value", "control"], rows,
              classes)


def write_figures(doc, figures, part, root, plots_tmp, plots_rel, made):
    doc.heading(2, "Figures", "figures")
    doc.para(f"{len(figures)} figures. Budget {part.get('budget', '?')} "
             f"({'quick: --quick images and sample counts' if part.get('budget') == 'quick' else 'full'}), "
             f"{machine_text(part.get('machine'))}. Each PNG is a tonemapped preview of the EXR "
             "beside it (32-bit float, linear radiance); the CSVs hold every number plotted.")
    machine, budget = machine_text(part.get("machine")), part.get("budget", "?")
    for f in figures:
        fid = f["id"]
        doc.heading(3, f"{fid} — {f.get('paper', '')}, {f.get('target', '')}", "fig-" + fid)
        if f.get("description"):
            doc.para(f["description"])
        if f.get("seconds") is not None:
            doc.para(f"Ran in {float(f['seconds']):.1f} s.")
        base = f"figures/{fid}"
        for n in f["files"]:
            if n.endswith(".png"):
                doc.image(f"{base}/{n}", f"{fid} {n}", f"{fid}: {n} (preview of the EXR data)",
                          preview=True)
        doc.links("EXR", [(n, f"{base}/{n}") for n in f["files"] if n.endswith(".exr")])
        doc.links("CSV", [(n, f"{base}/{n}") for n in f["files"] if n.endswith(".csv")])
        doc.links("Other files", [(n, f"{base}/{n}") for n in f["files"]
                                  if not n.endswith((".png", ".exr", ".csv"))])
        if f["summary"]:
            doc.pre(f["summary"].strip())
        for name, (header, rows) in f["csvs"].items():
            if "spp" not in header or "rmse" not in header:
                continue
            stem = name[:-4]
            png = f"{fid}__{stem}_convergence.png"
            if convergence_plot(fid, name, header, rows, os.path.join(plots_tmp, png), machine,
                                budget):
                made.append(png)
                doc.image(f"{plots_rel}/{png}", f"{fid} {stem} convergence",
                          f"{fid}: RMSE vs spp from {name} (log-log), {machine}, budget {budget}")
            doc.para(f"RMSE table ({name}" + (f", first {TABLE_ROW_LIMIT} of {len(rows)} rows"
                                              if len(rows) > TABLE_ROW_LIMIT else "") + "):")
            doc.table(header, [[tidy(c) for c in r] for r in rows[:TABLE_ROW_LIMIT]])


def write_bench(doc, bench, part, root, plots_tmp, plots_rel, made):
    doc.heading(2, "Speed vs accuracy", "speed")
    machine, budget = machine_text(part.get("machine")), part.get("budget", "?")
    ctx = bench["context"]
    if ctx.get("cpu_model") and isinstance(part.get("machine"), dict) and \
            part["machine"].get("cpu_model") != ctx.get("cpu_model"):
        machine = f"{ctx.get('cpu_model')}, {ctx.get('num_cpus', '?')} cores"
    doc.para(f"Budget {budget} ({part.get('settings', '')}), {machine}. Time per evaluation is "
             "1 / items per second of one thread on 4096-row batches; error is relative to the "
             "scalar double exact instantiation. A point is on its method's Pareto front when no "
             "other setting of the same quantity is at least as fast and as accurate. Timings "
             "on a shared machine are noisy.")
    doc.links("Files", [("bench.json", "bench/bench.json")] +
              ([("accuracy.csv", "bench/accuracy.csv")] if bench["accuracy"] else []))
    if not bench["accuracy"]:
        doc.para("No accuracy CSV (bench/accuracy.csv): no speed-vs-accuracy chart.")
        return
    timed = speed_accuracy_plot(bench, plots_tmp, machine, budget)
    if timed is None:
        doc.para("No benchmark matches a row of the accuracy CSV: no speed-vs-accuracy chart.")
        return
    made += ["speed_accuracy.png", "speed_accuracy.csv"]
    doc.image(f"{plots_rel}/speed_accuracy.png", "speed vs accuracy",
              f"Max relative error vs ns per evaluation, every kernel × ISA × math, per-method "
              f"Pareto fronts; {machine}, budget {budget}")
    doc.links("Data", [("speed_accuracy.csv", f"{plots_rel}/speed_accuracy.csv")])
    front = sorted((r for r in timed if r["on_pareto_front"] == 1),
                   key=lambda r: (r["method"], r["ns_per_eval"]))
    doc.para(f"Pareto fronts ({len(front)} of {len(timed)} timed points):")
    doc.table(["method", "kernel", "isa", "math", "ns per eval", "max rel. error",
               "p99 rel. error"],
              [[r["method"], r["kernel"], r["isa"], r["math"], f"{r['ns_per_eval']:.3g}",
                r["max_rel_error"], r["p99_rel_error"]] for r in front])
    write_method_fronts(doc, timed, root, plots_tmp, plots_rel, made, machine, budget,
                        str(ctx.get("date", ""))[:10])


def write_method_fronts(doc, timed, root, plots_tmp, plots_rel, made, machine, budget, date):
    """The method rows (bench/methods/*.json, METHOD_BENCHMARKS.md): chart and fronts on RMS."""
    paths = sorted(glob.glob(os.path.join(root, "bench/methods/*.json")))
    if not paths:
        doc.para("No method benchmarks (bench/methods/*.json; `bash scripts/speed_accuracy.sh` "
                 "writes them): no method chart.")
        return
    try:
        rows = sa.load_methods(paths)
    except SystemExit as e:
        raise ReportError(f"bench/methods: {e}") from None
    if not rows:
        doc.para("The method benchmark JSONs have no method/ rows: no method chart.")
        return
    sa.mark_fronts(rows, "rms")
    sa.plot_methods(timed, rows, os.path.join(plots_tmp, "speed_accuracy_methods.png"), "max",
                    "rms", machine, date)
    made += ["speed_accuracy_methods.png"]
    doc.image(f"{plots_rel}/speed_accuracy_methods.png", "speed vs accuracy of the methods",
              f"RMS error against each method's reference vs ns per evaluation, one panel per "
              f"method family, Pareto front per method; {machine}, budget {budget}")
    front = sorted((r for r in rows if r["on_pareto_front"] == 1),
                   key=lambda r: (r["method"], r["ns_per_eval"]))
    doc.para(f"Method fronts ({len(front)} of {len(rows)} settings; RMS error):")
    doc.table(["method", "setting", "ns per eval", "RMS error", "max error", "reference"],
              [[r["method"], r["setting"], f"{r['ns_per_eval']:.3g}", r["rms_rel_error"],
                r["max_rel_error"], r["reference"]] for r in front])


def write_stability(doc, st, part, root):
    doc.heading(2, "Stability maps", "stability")
    doc.para(f"Budget {st.get('budget', part.get('budget', '?'))}, "
             f"{machine_text(st.get('machine', part.get('machine')))}. {len(st['models'])} "
             "model/sampler pairs.")
    doc.links("Files", [("stability.json", "stability/stability.json")])
    for m in st["models"]:
        title = m["model"] + (f" / {m['sampler']}" if m.get("sampler") else "")
        doc.heading(3, title, "st-" + title.replace(" ", "").replace("/", "-"))
        doc.para("Failure region: " + (m.get("failure_region") or "none found in the sweep"))
        for mp in m["maps"]:
            doc.image(rel(mp["png_path"], root), f"{title} {mp['quantity']}",
                      f"{title}: {mp['quantity']}", preview=True)
            doc.links(mp["quantity"], [("EXR", rel(mp["exr_path"], root)),
                                       ("CSV", rel(mp["csv_path"], root))])


CSS = """body{font-family:sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;font-size:12px;margin:0.5em 0}
td,th{border:1px solid #ccc;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#eee}img{max-width:100%;border:1px solid #ddd}figure{margin:0.8em 0}
figcaption{font-size:12px;color:#555}
img.preview{min-width:360px;image-rendering:pixelated}pre{background:#f6f6f6;padding:0.5em;overflow:auto}
tr.v-holds td:nth-child(4),tr.v-holds-within td:nth-child(4){background:#d9f2d9}
tr.v-holds-in-regime td:nth-child(4){background:#eef6cc}
tr.v-fails td:nth-child(4){background:#f6d0d0}tr.v-inconclusive td:nth-child(4){background:#eee}"""


def build(root, run, got, plots_tmp):
    parts = run.get("parts", {})
    doc = Doc()
    title = "glintlab report"
    doc.heading(1, title, "top")
    doc.para(f"glintlab {run.get('glintlab_version', '?')}, {run.get('date', '')}, budget "
             f"{run.get('budget', '?')}, {machine_text(run.get('machine'))}.")
    doc.raw("<ul>" + "".join(f"<li>{esc(part_line(n, parts.get(n)))}</li>" for n in PARTS) +
            "</ul>", "\n".join(f"- {part_line(n, parts.get(n))}" for n in PARTS) + "\n")
    logs = os.path.join(root, "logs")
    doc.links("Run record", [("run.json", "run.json")] +
              [(n, f"logs/{n}") for n in (sorted(os.listdir(logs)) if os.path.isdir(logs) else [])
               if not n.startswith(".") and not n.startswith("make_report")])
    made = []
    plots_rel = "plots"
    if "claims" in got:
        write_claims(doc, got["claims"], parts.get("claims", {}), root)
    if "figures" in got:
        write_figures(doc, got["figures"], parts.get("figures", {}), root, plots_tmp, plots_rel,
                      made)
    if "bench" in got:
        write_bench(doc, got["bench"], parts.get("bench", {}), root, plots_tmp, plots_rel, made)
    if "stability" in got:
        write_stability(doc, got["stability"], parts.get("stability", {}), root)
    for n in PARTS:
        if n not in got:
            doc.heading(2, PART_TITLES[n], "absent-" + n)
            doc.para("Not in this report: " + part_line(n, parts.get(n)))
    page = ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{esc(title)}</title><style>{CSS}</style></head><body>\n" +
            "\n".join(doc.html) + "\n</body></html>\n")
    return page, "\n".join(doc.md), made


def write_text_atomic(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def make_report(root):
    run, got = load_all(root)
    plots_tmp = os.path.join(root, ".plots.tmp")
    shutil.rmtree(plots_tmp, ignore_errors=True)
    os.makedirs(plots_tmp)
    try:
        page, md, made = build(root, run, got, plots_tmp)
        html_tmp, md_tmp = os.path.join(root, ".index.html.tmp"), os.path.join(root, ".report.md.tmp")
        with open(html_tmp, "w", encoding="utf-8") as f:
            f.write(page)
        with open(md_tmp, "w", encoding="utf-8") as f:
            f.write(md)
        plots = os.path.join(root, "plots")
        shutil.rmtree(plots, ignore_errors=True)
        os.replace(plots_tmp, plots)
        os.replace(html_tmp, os.path.join(root, "index.html"))
        os.replace(md_tmp, os.path.join(root, "report.md"))
    finally:
        shutil.rmtree(plots_tmp, ignore_errors=True)
        for n in (".index.html.tmp", ".report.md.tmp"):
            if os.path.exists(os.path.join(root, n)):
                os.unlink(os.path.join(root, n))
    return got, made


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dir", required=True, help="the results folder (glintlab report's staging "
                                                "folder); index.html and report.md go there")
    a = p.parse_args(argv)
    if not os.path.isdir(a.dir):
        print(f"glintlab: error: --dir: '{a.dir}' is not a folder", file=sys.stderr)
        return 2
    try:
        got, made = make_report(a.dir)
    except ReportError as e:
        print(f"glintlab: error: report: {e}", file=sys.stderr)
        return 2
    print(f"make_report: {', '.join(sorted(got)) or 'no parts'}; {len(made)} plot files -> "
          f"{os.path.join(a.dir, 'index.html')}, report.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
