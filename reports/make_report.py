"""The glintlab report: index.html and its Markdown twin report.md from a folder
of results, with the plots drawn here from the results' CSVs.

Run by /usr/bin/python3 (Debian's, with matplotlib and Jinja2); `glintlab report` calls it on its
staging folder DIR, which holds:
  run.json                 machine, budget, date and status of each part (written by glintlab report)
  verify/claims.json       glintlab verify's results (a list of claim objects)
  conformance/claims.json  the same for the models' conformance suites (model.<name>.<property>)
  schemas/claims.schema.json  the JSON Schema of claims.json the program prints (glintlab schema
                           claims.json): both claims.json files are checked against it
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

The page's HTML comes from the Jinja2 templates in reports/templates/ (templating.py,
autoescape on): this file loads, validates and computes, and Doc records the page as plain blocks
(dicts) for report.html.j2 while it writes the Markdown twin. The page: a summary first (claims,
findings vs regressions, controls), a table of contents, the compact verdict table (evidence,
control and regime folded in <details>), the figures (renders folded in a grid), speed vs
accuracy, the stability planes. Every chart is drawn with matplotlib
and listed in plots/plots.json (charts.py: title, axis labels, legend, colour scale read back from
the figure); tests/reports/browser_test.py fails on a chart that lacks them.

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
import json
import math
import os
import re
import shutil
import sys
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import charts  # noqa: E402
import speed_accuracy as sa  # noqa: E402
import compare_page  # noqa: E402
import figure_charts  # noqa: E402
import json_schema  # noqa: E402
import templating  # noqa: E402

PARTS = ["claims", "conformance", "figures", "bench", "stability", "compare", "gpu"]
PART_TITLES = {"claims": "Claims (glintlab verify)",
               "conformance": "Models' conformance (glintlab verify --claims 'model.<name>.*')",
               "figures": "Figures (glintlab figure)",
               "bench": "Benchmarks (glintlab_bench_kernels, glintlab_accuracy)",
               "stability": "Stability maps (glintlab sweep)",
               "compare": "Models compared (glintlab compare)",
               "gpu": "Models on a GPU (glintlab_gpu_check, --gpu-from)"}
PARAM_COLUMNS = {"density", "microroughness", "reference_spp", "model", "sampler", "light"}
TABLE_ROW_LIMIT = 80


class ReportError(Exception):
    """A malformed input: becomes the one-line error."""


def rel(path, root):
    return os.path.relpath(os.path.realpath(path), os.path.realpath(root)).replace(os.sep, "/")


def url(relpath):
    return urllib.parse.quote(relpath)



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


# Where glintlab report writes the schema of claims.json the program prints (glintlab schema
# claims.json); the report checks every claims.json against it instead of a copy of the format.
CLAIMS_SCHEMA = "schemas/claims.schema.json"


def load_claims_schema(root):
    if not os.path.exists(os.path.join(root, CLAIMS_SCHEMA)):
        raise ReportError(f"{CLAIMS_SCHEMA} is missing: the schema of claims.json the program "
                          "prints (glintlab schema claims.json), written by glintlab report")
    schema = load_json(root, CLAIMS_SCHEMA)
    try:
        json_schema.check_schema(schema, CLAIMS_SCHEMA)
    except ValueError as e:
        raise ReportError(str(e))
    if schema.get("type") != "array" or not isinstance(schema.get("items"), dict):
        raise ReportError(f"{CLAIMS_SCHEMA} is not the schema of a list of claim objects")
    return schema


def load_claims(root, relpath="verify/claims.json"):
    schema = load_claims_schema(root)
    data = load_json(root, relpath)
    if not isinstance(data, list):
        raise ReportError(f"{relpath} is malformed: expected a list of claim objects")
    for i, c in enumerate(data):
        label = f"entry {i}"
        if isinstance(c, dict) and isinstance(c.get("id"), str):
            label += f" ({c['id']})"
        try:
            json_schema.validate(c, schema["items"], label)
        except json_schema.SchemaError as e:
            raise ReportError(f"{relpath} does not follow the schema of claims.json "
                              f"({CLAIMS_SCHEMA}): {e}")
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
            header, rows = load_csv(root, rel(mp["csv_path"], root))
            plane = mp.get("axis")
            if plane is None:  # older stability.json: the plane is the CSV's name
                plane = os.path.splitext(os.path.basename(mp["csv_path"]))[0]
            missing = [c for c in (*charts.STABILITY_NEEDED, plane) if c not in header]
            if missing:
                raise ReportError(f"{rel(mp['csv_path'], root)} is malformed: missing column(s) "
                                  f"{', '.join(missing)} (model {m['model']} map {mp['quantity']})")
            mp["plane"] = plane
            mp["table"] = (header, rows)
    return data


def load_conformance(root):
    """The conformance part's rows: claim objects whose ids are model.<name>.<property>."""
    relpath = "conformance/claims.json"
    data = load_claims(root, relpath)
    for i, c in enumerate(data):
        parts = c["id"].split(".", 2)
        if len(parts) != 3 or parts[0] != "model" or not parts[1] or not parts[2]:
            raise ReportError(f"{relpath} is malformed: entry {i} ('{c['id']}') is not a "
                              "model.<name>.<property> id")
    return data


def load_compare(root):
    data = load_json(root, "compare/compare.json")
    if not isinstance(data, dict) or not isinstance(data.get("models"), list):
        raise ReportError("compare/compare.json is malformed: no \"models\" list")
    return data


# The device check's results.json (gpu/results_format.cpp writes it): the fields the GPU section
# reads, each with its type; a missing or mistyped one is a malformed input.
GPU_FIELDS = {"device": str, "compute_capability": str, "cuda_version": str, "rows": int,
              "timing_rows": int, "repetitions": int, "runs": list, "table3": list}
GPU_RUN_FIELDS = {"model": str, "precision": str, "function": str, "median_ms": (int, float),
                  "min_ms": (int, float), "rows_per_second": (int, float)}
GPU_FRAME_FIELDS = {"cell": str, "median_ms": (int, float), "min_ms": (int, float),
                    "pixels_per_second": (int, float)}


def load_gpu(root):
    data = load_json(root, "gpu/results.json")

    def need(obj, fields, where):
        if not isinstance(obj, dict):
            raise ReportError(f"gpu/results.json is malformed: {where} is not an object")
        for name, kind in fields.items():
            if not isinstance(obj.get(name), kind) or isinstance(obj.get(name), bool):
                raise ReportError(f"gpu/results.json is malformed: {where} has no valid "
                                  f"\"{name}\"")
    need(data, GPU_FIELDS, "the top level")
    for i, r in enumerate(data["runs"]):
        need(r, GPU_RUN_FIELDS, f"runs[{i}]")
    for i, f in enumerate(data["table3"]):
        need(f, GPU_FRAME_FIELDS, f"table3[{i}]")
    return data


def load_all(root):
    run = load_run(root)
    parts = run.get("parts", {})
    got = {}
    loaders = {"claims": ("verify/claims.json", load_claims),
               "conformance": ("conformance/claims.json", load_conformance),
               "figures": ("figures/figures.json", load_figures),
               "bench": ("bench/bench.json", load_bench),
               "stability": ("stability/stability.json", load_stability),
               "compare": ("compare/compare.json", load_compare),
               "gpu": ("gpu/results.json", load_gpu)}
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


def convergence_plot(fig_id, csv_name, header, rows, path, machine, budget, relpath, manifest):
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
    charts.save(fig, path, relpath, manifest)
    return True


def speed_accuracy_plot(bench, plots, machine, budget, manifest):
    """speed_accuracy.csv and .png: reports/speed_accuracy.py's join and fronts, drawn as one
    small panel per kernel family."""
    rows = [dict(r) for r in bench["accuracy"]]
    timed = sa.join(rows, bench["speeds"], "max")
    if not timed:
        return None
    sa.write_csv(rows, os.path.join(plots, "speed_accuracy.csv"))
    date = str(bench["context"].get("date", ""))[:10]
    sa.plot_families(timed, os.path.join(plots, "speed_accuracy.png"), "max",
                     f"{machine}; budget {budget}", date,
                     record=lambda fig: manifest.append({**charts.describe(fig),
                                                         "file": "plots/speed_accuracy.png"}))
    return timed


# ----------------------------------------------------------------------------------------------
# Writing

MD_TABLE_RULE = re.compile(r"^\s*\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)+\|?\s*$")


def md_row(line):
    """The cells of a Markdown table row (a \\| in a cell is a literal pipe)."""
    s = line.strip()
    s = s[1:] if s.startswith("|") else s
    s = s[:-1] if s.endswith("|") and not s.endswith("\\|") else s
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", s)]


def markdown_parts(text):
    """A figure's summary.md read into the parts the report shows (templates/blocks.html.j2,
    markdown): tables, headings, list items and paragraphs; nothing else of Markdown is needed by
    the summaries the figures write. Each line of text is rendered by the md_inline filter."""
    lines = text.splitlines()
    out, para, items = [], [], []

    def flush():
        if para:
            out.append({"kind": "paragraph", "lines": list(para)})
            para.clear()
        if items:
            out.append({"kind": "list", "entries": list(items)})
            items.clear()

    i = 0
    while i < len(lines):
        line = lines[i].strip()
        if line.startswith("|") and i + 1 < len(lines) and MD_TABLE_RULE.match(lines[i + 1]):
            flush()
            head = md_row(line)
            rows = []
            i += 2
            while i < len(lines) and lines[i].strip().startswith("|"):
                rows.append(md_row(lines[i]))
                i += 1
            out.append({"kind": "table", "head": head, "rows": rows})
            continue
        if not line:
            flush()
        elif line.startswith("#"):
            flush()
            out.append({"kind": "heading", "text": line.lstrip('#').strip()})
        elif line.startswith(("- ", "* ")):
            if para:
                flush()
            items.append(line[2:])
        elif items and lines[i].startswith("  "):  # a list item continued
            items[-1] += " " + line
        else:
            if items:
                flush()
            para.append(line)
        i += 1
    flush()
    return out


def markdown_twin(text):
    """A figure's summary.md inside the Markdown twin: as it is (its tables stay tables), its
    headings made bold so they do not enter the twin's outline."""
    return "\n".join(f"**{ln.lstrip('#').strip()}**" if ln.startswith("#") else ln
                     for ln in text.splitlines()) + "\n"


class Cell:
    """A table cell other than text: what the HTML shows (a kind of templates/blocks.html.j2's
    cell macro and its values) and its Markdown text."""

    def __init__(self, md_text, kind, **values):
        self.md, self.values = md_text, {"kind": kind, **values}


def short(text, n=90):
    text = " ".join(str(text).split())
    return text if len(text) <= n else text[:n].rsplit(" ", 1)[0] + " …"


class Doc:
    """The page's blocks (rendered by templates/report.html.j2, each kind by the macro of that name
    in templates/blocks.html.j2) and the Markdown twin, built side by side; headings are kept for
    the table of contents, which goes where toc_here() was called."""

    def __init__(self):
        self.blocks, self.md = [], []
        self.headings = []
        self.toc_at = None

    def heading(self, level, text, anchor):
        self.headings.append((level, text, anchor))
        self.blocks.append({"kind": "heading", "level": level, "text": text, "anchor": anchor})
        self.md.append(f"{'#' * level} {text}\n")

    def toc_here(self):
        self.toc_at = (len(self.blocks), len(self.md))

    def toc(self):
        """(block, md) of the table of contents: the level 2 headings, each with its level 3
        ones."""
        entries, m = [], ["## Contents\n"]
        for level, text, anchor in self.headings:
            if level == 2:
                entries.append({"text": text, "anchor": anchor, "subs": []})
                m.append(f"- [{md_cell(text)}](#{anchor})")
            elif level == 3:
                sub = {"text": text, "anchor": anchor, "subs": []}
                (entries[-1]["subs"] if entries else entries).append(sub)
                m.append(f"  - [{md_cell(text)}](#{anchor})")
        return {"kind": "toc", "entries": entries}, "\n".join(m) + "\n"

    def para(self, text, md=None):
        self.blocks.append({"kind": "para", "text": text})
        self.md.append((md if md is not None else text) + "\n")

    def section(self, template, data, md_text):
        """A part of the page with a template of its own (reports/templates/), given data."""
        self.blocks.append({"kind": "section", "template": template, "data": data})
        self.md.append(md_text)

    def markdown(self, summary, text):
        """A Markdown text (a figure's summary.md) folded under summary."""
        self.blocks.append({"kind": "markdown", "summary": summary,
                            "parts": markdown_parts(text)})
        self.md.append(markdown_twin(text))

    def list(self, entries):
        self.blocks.append({"kind": "list", "entries": entries})
        self.md.append("\n".join(f"- {e}" for e in entries) + "\n")

    def table(self, header, rows, classes=None, ids=None, cls=None, fold=None):
        """rows: lists of Cell, (text, href or None) or plain text cells. fold: the table is
        folded under this summary (in the HTML; the Markdown caller writes its own line)."""
        body = []
        m = ["| " + " | ".join(md_cell(c) for c in header) + " |",
             "|" + "---|" * len(header)]
        for i, r in enumerate(rows):
            cells, mc = [], []
            for c in r:
                if isinstance(c, Cell):
                    cells.append(c.values)
                    mc.append(md_cell(c.md))
                    continue
                text, href = c if isinstance(c, tuple) else (c, None)
                cells.append({"kind": "text", "text": text, "href": href})
                mc.append(f"[{md_cell(text)}]({url(href)})" if href else md_cell(text))
            body.append({"cls": classes[i] if classes else None, "id": ids[i] if ids else None,
                         "cells": cells})
            m.append("| " + " | ".join(mc) + " |")
        self.blocks.append({"kind": "table", "header": header, "rows": body, "cls": cls,
                            "fold": fold})
        self.md.append("\n".join(m) + "\n")

    def image(self, href, alt, caption, kind="render", wide=False):
        """kind: "chart" (drawn by the report, in plots/plots.json) or "render" (a rendered
        image of a figure, small ones drawn enlarged with visible pixels). wide: in a gallery, the
        image takes a whole row (a wide one squeezed into one cell would be too low to read)."""
        self.blocks.append(self.image_block(href, alt, caption, kind, wide))
        self.md.append(f"![{md_cell(alt)}]({url(href)})\n\n*{caption}*\n")

    @staticmethod
    def image_block(href, alt, caption, kind, wide):
        return {"kind": "image", "href": href, "alt": alt, "caption": caption,
                "image_kind": kind, "wide": wide}

    def gallery(self, summary, items, root=None):
        """Rendered images side by side, folded: items [(href, alt, caption)]; with root, those
        at least twice as wide as high take a row of their own."""
        if not items:
            return
        images = []
        for href, alt, caption in items:
            size = png_size(os.path.join(root, href)) if root else None
            images.append(self.image_block(href, alt, caption, "render",
                                           bool(size and size[0] >= 2 * size[1])))
            self.md.append(f"![{md_cell(alt)}]({url(href)})\n\n*{caption}*\n")
        self.blocks.append({"kind": "gallery", "summary": summary, "images": images})

    def links(self, label, items):
        """items: [(text, href)]."""
        if not items:
            return
        self.blocks.append({"kind": "links", "label": label, "links": items})
        self.md.append(f"{label}: " + ", ".join(f"[{md_cell(t)}]({url(h)})" for t, h in items) +
                       "\n")


def png_size(path):
    """(width, height) from a PNG's header; None when the file is not a readable PNG."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


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


def claim_anchor(c):
    return "claim-" + c["id"]


def as_recorded(c):
    exp = c.get("expected_verdict")
    return not isinstance(exp, str) or exp == c["verdict"]


def control_text(c):
    """(short, long) of the control column: the control's own verdict and whether it opposes the
    claim's (control_rejected), then what the control input is."""
    if c["verdict"] == "error":
        return "control: none (the check could not run)", c["control"]
    cv = c.get("control_verdict")
    own = f"control {cv}" if cv else "control"
    if c["control_rejected"]:
        head = f"{own}: rejected" + (" (opposes)" if cv else "")
    else:
        head = f"{own}: NOT REJECTED" + (" (does not oppose)" if cv else "") + " — check broken"
    body = c["control"]
    if c.get("control_p_value") is not None:
        body += f" (control p {fmt_p(c['control_p_value'])})"
    return head, body


def finding_parts(c):
    """(label, text) pairs a finding is read by: the paper's sentence, what was measured, the
    competing causes excluded, the smallest correction."""
    parts = [("The paper", c.get("paper_quote") or "(no quote recorded)"),
             ("Measured", short(c["detail"], 400))]
    excluded = "; ".join(f"{a['cause']}: {a['how']}" for a in c.get("alternatives_excluded") or [])
    parts.append(("Causes excluded", excluded or "none recorded"))
    if c.get("correction"):
        parts.append(("Smallest correction", c["correction"]))
    return parts


def finding_list_md(findings):
    out = ""
    for c in findings:
        out += f"\n  - **{c['id']}**"
        for k, v in finding_parts(c):
            out += f"\n    - *{k}:* {v}"
    return out


def write_summary(doc, claims, run, got):
    """What a reader needs first: the counts, the failures and whether they are the recorded
    findings, regressions, the controls (templates/summary.html.j2)."""
    doc.heading(2, "Summary", "summary")
    entries, items_m = [], []

    def item(text, md=None, bold=None, bad=False, claims_linked=(), extra=lambda c: "",
             findings=()):
        """One entry: an optional bold head, a text, links to the rows of claims_linked (each
        followed by extra(c)) and the findings' details; md: its Markdown line."""
        entries.append({"bold": bold, "bad": bad, "text": text,
                        "claims": [{"id": c["id"], "anchor": claim_anchor(c), "extra": extra(c)}
                                   for c in claims_linked],
                        "findings": [{"id": c["id"], "parts": finding_parts(c)}
                                     for c in findings]})
        items_m.append(f"- {md if md is not None else text}")

    def md_links(cs, extra=lambda c: ""):
        return ", ".join(f"[{md_cell(c['id'])}](#{claim_anchor(c)}){extra(c)}" for c in cs)

    if claims is not None:
        n = len(claims)
        counts = {v: sum(c["verdict"] == v for c in claims)
                  for v in sorted({c["verdict"] for c in claims})}
        text = ", ".join(f"{k} {v}" for k, v in counts.items() if v)
        item(f"{n} claims: {text}.")
        same = [c for c in claims if as_recorded(c)]
        differ = [c for c in claims if not as_recorded(c)]
        item(f"{len(same)} of {n} as recorded (the verdict equals the one recorded in the "
             "repository).")
        # A finding: a paper's claim that fails as recorded, every competing cause excluded
        # (a "fails" with a cause open is reported inconclusive by the finding rule).
        findings = [c for c in claims if c["verdict"] == "fails" and as_recorded(c)
                    and c.get("kind", "paper's claim") == "paper's claim"]
        if findings:
            head = ("Fails, as recorded (a finding: the paper's claim was found wrong, every "
                    "competing cause excluded)")
            item(f", {len(findings)}: ",
                 f"**{head}**, {len(findings)}: {md_links(findings)}"
                 + finding_list_md(findings), bold=head, claims_linked=findings,
                 findings=findings)
        else:
            item("No paper's claim fails as recorded.")
        rules = [c for c in claims if c["verdict"] == "fails" and as_recorded(c)
                 and c.get("kind") == "glintlab rule"]
        if rules:
            head = "glintlab's own rules that fail, as recorded"
            item(f" (not a paper's claim), {len(rules)}: ",
                 f"**{head}** (not a paper's claim), {len(rules)}: {md_links(rules)}",
                 bold=head, claims_linked=rules)
        open_causes = [c for c in claims if c.get("measured_verdict") == "fails"]
        if open_causes:
            head = "Measured as failing, but a competing cause is not excluded"
            item(f" (inconclusive, not a finding), {len(open_causes)}: ",
                 f"**{head}** (inconclusive, not a finding), {len(open_causes)}: "
                 f"{md_links(open_causes)}", bold=head, claims_linked=open_causes)
        errors = [c for c in claims if c["verdict"] == "error"]
        if errors:
            cause = lambda c: f" ({c['detail']})"  # noqa: E731
            item(f", {len(errors)}: ",
                 f"**Could not be checked (error)**, {len(errors)}: {md_links(errors, cause)}",
                 bold="Could not be checked (error)", bad=True, claims_linked=errors,
                 extra=cause)
        if differ:
            recorded = lambda c: f" ({c['verdict']}, recorded {c.get('expected_verdict')})"  # noqa
            item(f", {len(differ)}: ",
                 f"**Differs from recorded (a regression)**, {len(differ)}: "
                 f"{md_links(differ, recorded)}",
                 bold="Differs from recorded (a regression)", bad=True, claims_linked=differ,
                 extra=recorded)
        else:
            item("No verdict differs from the recorded one (no regression).")
        loose = [c for c in claims if not c["control_rejected"] and c["verdict"] != "error"]
        if loose:
            head = f"{len(loose)} of {n} negative controls NOT rejected"
            item(" (those checks cannot tell a wrong input): ",
                 f"**{head}**: {md_links(loose)}", bold=head, bad=True, claims_linked=loose)
        else:
            item(f"Every negative control rejected ({n} of {n}): each check tells its "
                 "deliberately wrong input apart.")
    else:
        item("No claims in this report.")
    if "stability" in got:
        ms = got["stability"]["models"]
        name = lambda m: m["model"] + (f"/{m['sampler']}" if m.get("sampler") else "")  # noqa
        region = [name(m) for m in ms
                  if m.get("failure_region") and not m["failure_region"].startswith("none")]
        failing = [name(m) for m in ms if m.get("verdict") not in (None, "holds")]
        item(f"Stability: {len(ms)} model/sampler pairs swept; cells flagged somewhere in "
             f"the sweep for {len(region)}" + (f" ({', '.join(region)})" if region else "") +
             "; the sweep's verdict fails for " +
             (", ".join(failing) if failing else "none") + ".")
    if "figures" in got:
        item(f"Figures: {len(got['figures'])} run.")
    doc.section("summary.html.j2", {"entries": entries}, "\n".join(items_m) + "\n")


def write_claims(doc, claims, part, root):
    doc.heading(2, "Verdicts", "verdicts")
    doc.para(f"{len(claims)} claims. Budget {part.get('budget', '?')}, "
             f"{machine_text(part.get('machine'))}. Verdicts: holds, holds-within, "
             "holds-in-regime (in the parameter region the check declares), fails, inconclusive, "
             "error (the check could not compute its statistic; the evidence says why); "
             "each check's negative control (a deliberately wrong input) must get the opposite "
             "verdict from the check's own decision (rejected) for the verdict to count. Click a "
             "row's evidence or control to unfold it.")
    doc.links("Files", [("claims.json", "verify/claims.json"), ("claims.csv", "verify/claims.csv"),
                        ("claims.md", "verify/claims.md")])
    rows, classes, ids = [], [], []
    for c in claims:
        verdict = c["verdict"]
        if c.get("regime"):
            vcell = Cell(f"{verdict} (regime: {c['regime']})", "verdict", verdict=verdict,
                         regime=c["regime"])
        else:
            vcell = Cell(verdict, "verdict", verdict=verdict, regime=None)
        exp = c.get("expected_verdict")
        if as_recorded(c):
            finding = verdict == "fails" and c.get("kind", "paper's claim") == "paper's claim"
            rec = "yes — a finding" if finding else "yes"
        elif verdict == "error":
            rec = f"NO (recorded: {exp}) — the check could not run"
        else:
            rec = f"NO (recorded: {exp}) — a regression"
        head, body = control_text(c)
        ctrl = Cell(f"{head}: {body}", "details", summary=head, body=body, long=False)
        evidence = c["detail"]
        extra = []
        if c.get("paper_quote"):
            extra.append(f"the paper: {c['paper_quote']}")
        if c.get("stronger_reading"):
            extra.append(f"tested beyond the paper's sentence: {c['stronger_reading']}")
        for a in c.get("alternatives_excluded") or []:
            extra.append(f"excluded: {a['cause']} — {a['how']}")
        for a in c.get("alternatives_open") or []:
            extra.append(f"not excluded: {a['cause']} — {a['why']}")
        if c.get("statistic"):
            extra.append(f"statistic: {c['statistic']}")
        if c.get("power"):
            extra.append(f"power: {c['power']}")
        if c.get("budget_note"):
            extra.append(f"budgets: {c['budget_note']}")
        full = evidence + ("\n" + "\n".join(extra) if extra else "")
        ev = Cell(" ".join(full.split("\n")), "details", summary=short(evidence), body=full,
                  long=True)
        rows.append([Cell(c["id"], "anchor", text=c["id"], anchor=claim_anchor(c)),
                     f"{c['paper']}, {c['source']}", vcell, rec, fmt_p(c.get("p_value")), ctrl,
                     ev])
        classes.append("v-" + c["verdict"] + ("" if as_recorded(c) else " regress") +
                       ("" if c["control_rejected"] or verdict == "error" else " loose"))
        ids.append(claim_anchor(c))
    doc.table(["claim", "paper, source", "verdict", "as recorded", "p-value", "control",
               "evidence"], rows, classes, ids, cls="verdicts")


def checked_control(c):
    """Whether a row has a control to reject: not for a check that could not run, nor for a
    property the model declares not claimed (nothing is measured)."""
    return c["verdict"] not in ("error", "not-claimed")


def conformance_cell(c):
    """A model's property in the conformance matrix: its verdict, whether it is the recorded one
    and whether its control was rejected; the evidence unfolds."""
    head = c["verdict"]
    if not as_recorded(c):
        head += f" (recorded: {c.get('expected_verdict')})"
    if checked_control(c) and not c["control_rejected"]:
        head += ", control NOT REJECTED"
    ctrl, ctrl_body = control_text(c) if checked_control(c) else ("control", c["control"])
    body = f"{c['detail']}\n{ctrl}: {ctrl_body}"
    return Cell(f"{head}", "details", summary=head, body=body, long=False)


def write_conformance(doc, rows, part, root):
    """The models' conformance suites this run measured: one row per model, one column per
    property (a property that does not apply to a model is —)."""
    doc.heading(2, "Models' conformance", "conformance")
    models, props, by = [], [], {}
    for c in rows:
        _, m, prop = c["id"].split(".", 2)  # validated by load_conformance
        if m not in models:
            models.append(m)
        if prop not in props:
            props.append(prop)
        by[(m, prop)] = c
    left = part.get("note", "")
    doc.para(f"The conformance suites of {len(models)} models, measured in this run at budget "
             f"{part.get('budget', '?')}, {machine_text(part.get('machine'))}: {len(rows)} checks, "
             f"each with its negative control decided by the same function. Unfold a cell for its "
             "evidence. The comparison below shows these verdicts as measured in this run; a "
             "model not measured here shows its recorded verdicts in a column of their own"
             + (f" ({left})." if left else "."))
    doc.links("Files", [(f, f"conformance/{f}") for f in ("claims.json", "claims.csv", "claims.md")
                        if os.path.exists(os.path.join(root, "conformance", f))])
    table_rows, classes = [], []
    for m in models:
        cells = [m]
        bad = False
        for prop in props:
            c = by.get((m, prop))
            if c is None:
                cells.append("—")
                continue
            cells.append(conformance_cell(c))
            bad = bad or not as_recorded(c) or (checked_control(c) and not c["control_rejected"])
        table_rows.append(cells)
        classes.append("regress" if bad else None)
    doc.table(["model"] + props, table_rows, classes, cls="verdicts")


def figure_chart_pngs(doc, f, root, base, manifest, replaced):
    """The figure's own charts: each NAME.chart.json of its folder was drawn into NAME.png by
    reports/figure_charts.py when the figure ran, with what it shows stored in the PNG; shown
    here as charts (listed in plots/plots.json from that record). Returns the CSVs they draw, whose
    numbers need no second chart."""
    charted = set()
    for spec in [n for n in f["files"] if n.endswith(figure_charts.SPEC_SUFFIX)]:
        png = spec[:-len(figure_charts.SPEC_SUFFIX)] + ".png"
        data = load_json(root, f"{base}/{spec}")
        if not isinstance(data, dict) or not isinstance(data.get("csv"), str):
            raise ReportError(f"{base}/{spec} is malformed: expected an object with \"csv\"")
        entry = figure_charts.chart_manifest(os.path.join(f["dir"], png))
        if entry is None:
            raise ReportError(f"{base}/{spec}: its chart {png} is missing or was not drawn by "
                              "reports/figure_charts.py (no chart record in it)")
        manifest.append({**entry, "file": f"{base}/{png}"})
        replaced.add(png)
        charted.add(data["csv"])
        doc.image(f"{base}/{png}", f"{f['id']} {png}",
                  f"{f['id']}: {png}, drawn from {data['csv']} (chart spec {spec})", "chart")
    return charted


# Figures shown in the adequacy section (write_adequacy) rather than among the papers' figures.
ADEQUACY_FIGURES = ("adequacy-maps", "adequacy-scene")
# The adequacy-maps figure's index of its maps (one row per map: map, family, model, ...), and the
# families' names as the section writes them, in the order it lists them.
ADEQUACY_MAP_INDEX = "adequacy-maps-index.csv"
ADEQUACY_FAMILIES = (("binomial", "binomial"), ("kemppinen", "Kemppinen"), ("area", "area"),
                     ("chermain", "Chermain"))


def adequacy_map_families(f):
    """The adequacy-maps figure's maps per family, {family: (maps, [models])}, from its index
    CSV; None when the figure has no index (an older run)."""
    header, rows = f["csvs"].get(ADEQUACY_MAP_INDEX, (None, None))
    if not header or "family" not in header or "model" not in header:
        return None
    fam, model = header.index("family"), header.index("model")
    out = {}
    for r in rows:
        maps, models = out.setdefault(r[fam], [0, []])
        out[r[fam]][0] = maps + 1
        if r[model] not in models:
            models.append(r[model])
    return out


def write_figures(doc, figures, part, root, plots_tmp, plots_rel, made, manifest):
    figures = [f for f in figures if f["id"] not in ADEQUACY_FIGURES]
    doc.heading(2, "Figures", "figures")
    doc.para(f"{len(figures)} figures. Budget {part.get('budget', '?')} "
             f"({'quick: --budget quick images and sample counts' if part.get('budget') == 'quick' else 'full'}), "
             f"{machine_text(part.get('machine'))}. Each rendered PNG is a tonemapped preview of "
             "the EXR beside it (32-bit float, linear radiance), folded under its figure and "
             "shown enlarged with visible pixels; the CSVs hold every number plotted, and the "
             "charts here are drawn from them.")
    for f in figures:
        write_figure(doc, f, part, root, plots_tmp, plots_rel, made, manifest)


def write_adequacy(doc, figures, claims, part, root, plots_tmp, plots_rel, made, manifest):
    """Which model a pixel needs: the adequacy claims' verdicts of this run and the figures
    adequacy-maps (the chosen level over the grid) and adequacy-scene (validation scenes)."""
    shown = [f for f in figures if f["id"] in ADEQUACY_FIGURES]
    rows = [c for c in (claims or []) if c["id"].startswith("adequacy.")]
    if not shown and not rows:
        return
    doc.heading(2, "Model no more than a scene needs (adequacy)", "adequacy")
    doc.para("glintlab adequacy measures, per pixel setting, the cheapest level of a glint model "
             "that no one could tell from the most complete one (within TAU), and "
             "core/glints/adequacy.h picks that level per pixel for an engine "
             "(docs/adequacy.md). The maps show the level chosen over the adequacy grid; the "
             "scenes, which the choice was not fitted on, are rendered with each pixel's chosen "
             "level and with the most complete level everywhere (exact counting; k16_exact for "
             "Kemppinen), with their difference.")
    if rows:
        doc.list([f"{c['id']}: {c['verdict']} — {short(c['detail'], 160)}" for c in rows])
    else:
        doc.para("The adequacy claims were not run in this report (see the verdict table).")
    if not shown:
        doc.para("The adequacy figures were not run in this report.")
    for f in shown:
        if f["id"] == "adequacy-maps":
            families = adequacy_map_families(f)
            if families is None:
                doc.para(f"adequacy-maps has no index of its maps ({ADEQUACY_MAP_INDEX}): "
                         "which families it draws is not known.")
            else:
                parts = [f"{name} family {families[key][0]} (" + ", ".join(families[key][1]) + ")"
                         for key, name in ADEQUACY_FAMILIES if key in families]
                parts += [f"{key} {v[0]} (" + ", ".join(v[1]) + ")"
                          for key, v in families.items() if key not in dict(ADEQUACY_FAMILIES)]
                missing = [name for key, name in ADEQUACY_FAMILIES if key not in families]
                doc.para(f"adequacy-maps draws {sum(v[0] for v in families.values())} maps of "
                         "the chosen level, per family: " + "; ".join(parts) + ". Each map's "
                         "title names its family; summary.md lists every map with its family." +
                         (" Not drawn: the " + ", ".join(missing) + " famil" +
                          ("y." if len(missing) == 1 else "ies.") if missing else ""))
        write_figure(doc, f, part, root, plots_tmp, plots_rel, made, manifest)


def write_figure(doc, f, part, root, plots_tmp, plots_rel, made, manifest):
    """One figure under its own heading: the charts drawn from its CSVs, its montages as labelled
    panels, its other renders folded, its files linked, its summary.md and convergence plots."""
    machine, budget = machine_text(part.get("machine")), part.get("budget", "?")
    fid = f["id"]
    doc.heading(3, f"{fid} — {f.get('paper', '')}, {f.get('target', '')}", "fig-" + fid)
    if f.get("description"):
        doc.para(f["description"])
    if f.get("seconds") is not None:
        doc.para(f"Ran in {float(f['seconds']):.1f} s.")
    base = f"figures/{fid}"
    replaced = set()
    charted = figure_chart_pngs(doc, f, root, base, manifest, replaced)
    for name in [n for n in f["files"] if n.endswith(".png") and n not in replaced]:
        layout_name = name[:-4] + ".panels.json"
        if layout_name not in f["files"]:
            continue
        layout = load_json(root, f"{base}/{layout_name}")
        if not isinstance(layout, dict) or not isinstance(layout.get("labels"), list) or \
                not isinstance(layout.get("columns"), int):
            raise ReportError(f"{base}/{layout_name} is malformed: expected an object with "
                              "\"labels\" and \"columns\"")
        out = f"{fid}__{name[:-4]}_panels.png"
        if charts.panel_chart(os.path.join(f["dir"], name), layout,
                              os.path.join(plots_tmp, out), f"{plots_rel}/{out}", manifest,
                              f"{machine}; budget {budget}"):
            made.append(out)
            replaced.add(name)
            doc.image(f"{plots_rel}/{out}", f"{fid} {name} panels",
                      f"{fid}: {name} as labelled panels (the PNG itself is linked below)",
                      "chart")
    pngs = [n for n in f["files"] if n.endswith(".png") and n not in replaced]
    doc.gallery(f"{len(pngs)} rendered image(s) of {fid} (click to unfold)",
                [(f"{base}/{n}", f"{fid} {n}", f"{n} (preview of the EXR data)")
                 for n in pngs], root)
    doc.links("EXR", [(n, f"{base}/{n}") for n in f["files"] if n.endswith(".exr")])
    doc.links("CSV", [(n, f"{base}/{n}") for n in f["files"] if n.endswith(".csv")])
    doc.links("Other files", [(n, f"{base}/{n}") for n in f["files"]
                              if not n.endswith((".exr", ".csv")) and
                              (not n.endswith(".png") or n in replaced)])
    if f["summary"]:
        doc.markdown("summary.md", f["summary"].strip())
    for name, (header, rows) in f["csvs"].items():
        if "spp" not in header or "rmse" not in header or name in charted:
            continue
        stem = name[:-4]
        png = f"{fid}__{stem}_convergence.png"
        if convergence_plot(fid, name, header, rows, os.path.join(plots_tmp, png), machine,
                            budget, f"{plots_rel}/{png}", manifest):
            made.append(png)
            doc.image(f"{plots_rel}/{png}", f"{fid} {stem} convergence",
                      f"{fid}: RMSE vs spp from {name} (log-log), {machine}, budget {budget}",
                      "chart")
        doc.md.append(f"RMSE table ({name}):\n")
        doc.table(header, [[tidy(c) for c in r] for r in rows[:TABLE_ROW_LIMIT]],
                  fold=f"RMSE table ({name}, {len(rows)} rows"
                  + (f", first {TABLE_ROW_LIMIT} shown" if len(rows) > TABLE_ROW_LIMIT
                     else "") + ")")


def write_bench(doc, bench, part, root, plots_tmp, plots_rel, made, manifest):
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
    timed = speed_accuracy_plot(bench, plots_tmp, machine, budget, manifest)
    if timed is None:
        doc.para("No benchmark matches a row of the accuracy CSV: no speed-vs-accuracy chart.")
        return
    made += ["speed_accuracy.png", "speed_accuracy.csv"]
    doc.image(f"{plots_rel}/speed_accuracy.png", "speed vs accuracy",
              f"Max relative error vs ns per evaluation, one panel per kernel family, every "
              f"kernel × ISA × math, per-method Pareto fronts; {machine}, budget {budget}",
              "chart")
    doc.links("Data", [("speed_accuracy.csv", f"{plots_rel}/speed_accuracy.csv")])
    front = sorted((r for r in timed if r["on_pareto_front"] == 1),
                   key=lambda r: (r["method"], r["ns_per_eval"]))
    doc.md.append(f"Pareto fronts ({len(front)} of {len(timed)} timed points):\n")
    doc.table(["method", "kernel", "isa", "math", "ns per eval", "max rel. error",
               "p99 rel. error"],
              [[r["method"], r["kernel"], r["isa"], r["math"], f"{r['ns_per_eval']:.3g}",
                r["max_rel_error"], r["p99_rel_error"]] for r in front],
              fold=f"Pareto fronts ({len(front)} of {len(timed)} timed points)")
    write_method_fronts(doc, timed, root, plots_tmp, plots_rel, made, machine, budget,
                        str(ctx.get("date", ""))[:10], manifest)


def write_method_fronts(doc, timed, root, plots_tmp, plots_rel, made, machine, budget, date,
                        manifest):
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
                    "rms", machine, date,
                    record=lambda fig: manifest.append(
                        {**charts.describe(fig), "file": f"{plots_rel}/speed_accuracy_methods.png"}))
    made += ["speed_accuracy_methods.png"]
    doc.image(f"{plots_rel}/speed_accuracy_methods.png", "speed vs accuracy of the methods",
              f"RMS error against each method's reference vs ns per evaluation, one panel per "
              f"method family, Pareto front per method; {machine}, budget {budget}", "chart")
    front = sorted((r for r in rows if r["on_pareto_front"] == 1),
                   key=lambda r: (r["method"], r["ns_per_eval"]))
    doc.md.append(f"Method fronts ({len(front)} of {len(rows)} settings; RMS error):\n")
    doc.table(["method", "setting", "ns per eval", "RMS error", "max error", "reference"],
              [[r["method"], r["setting"], f"{r['ns_per_eval']:.3g}", r["rms_rel_error"],
                r["max_rel_error"], r["reference"]] for r in front],
              fold=f"Method fronts ({len(front)} of {len(rows)} settings; RMS error)")


def slug(text):
    return "".join(ch if ch.isalnum() or ch in "-_" else "-" for ch in text)


def write_stability(doc, st, part, root, plots_tmp, plots_rel, made, manifest):
    doc.heading(2, "Stability maps", "stability")
    machine = machine_text(st.get('machine', part.get('machine')))
    budget = st.get('budget', part.get('budget', '?'))
    doc.para(f"Budget {budget}, {machine}. {len(st['models'])} model/sampler pairs. Each map is "
             "one quantity over one plane (a swept parameter × the incidence angle θ_i) of one "
             "model and sampler: the sweep's own heat map (drawn by matplotlib when the sweep "
             "ran, from the plane's CSV), with the cells the sweep flags outlined and hatched in "
             "red (the failure region); its EXR and CSV are linked under each plane.")
    doc.links("Files", [("stability.json", "stability/stability.json")])
    for m in st["models"]:
        title = m["model"] + (f" / {m['sampler']}" if m.get("sampler") else "")
        doc.heading(3, title, "st-" + slug(title.replace(" ", "").replace("/", "-")))
        doc.para("Failure region: " + (m.get("failure_region") or "none found in the sweep"))
        planes = {}
        for mp in m["maps"]:
            planes.setdefault(mp["plane"], []).append(mp)
        for plane, maps in planes.items():
            items = []
            for mp in maps:
                png = rel(mp["png_path"], root)
                entry = figure_charts.chart_manifest(mp["png_path"])
                if entry is None:
                    raise ReportError(f"{png}: the sweep's map of {m['model']} "
                                      f"{mp['quantity']} was not drawn by "
                                      "reports/figure_charts.py (no chart record in it)")
                manifest.append({**entry, "file": png})
                name = STABILITY_MAP_NAMES.get(mp["quantity"], mp["quantity"])
                # The panel's title counts the failing cells ("nan: 3 of 132 cells fail").
                counts = "; ".join(a["title"] for a in entry["axes"] if a.get("map"))
                doc.image(png, f"{title} plane {plane} {mp['quantity']}",
                          f"{title}, plane {plane} × θ_i, {name}: {counts or 'a heat map'} "
                          f"(from {os.path.basename(rel(maps[0]['csv_path'], root))})", "chart")
                items.append((f"{name} EXR", rel(mp["exr_path"], root)))
            doc.links(f"{plane}: CSV", [("CSV", rel(maps[0]["csv_path"], root))] + items)


# The stability maps' quantities (experiments/sweeps/stability_maps.cpp) in words, for the links
# to their files: a bare "nan" beside a file reads like a missing number.
STABILITY_MAP_NAMES = {
    "nan": "NaN-fraction map", "inf": "Inf-fraction map", "negative": "negative-fraction map",
    "energy_gain": "energy-gain map", "p_gt_1": "p > 1 map", "variance": "variance map",
}


def write_compare(doc, data, plots_tmp, plots_rel, made, manifest):
    """The comparison of every registered model (glintlab compare, reports/compare_page.py)."""
    doc.heading(2, PART_TITLES["compare"], "compare")
    doc.section("compare_intro.html.j2", compare_page.template_values(data, None),
                "Every model at its default parameters on the same scenes; conformance verdicts "
                "not measured in this run (recorded: copied from "
                f"{compare_page.RECORDED_SOURCE}; declared) have a column of their own.\n")
    png = "compare_equal_time.png"
    compare_page.draw_equal_time(data, os.path.join(plots_tmp, png), f"{plots_rel}/{png}",
                                 manifest)
    made.append(png)
    doc.image(f"{plots_rel}/{png}", "equal-time error curves",
              "Relative RMS error of each model's sampler estimate of the albedo against wall "
              "time (this machine).", "chart")
    doc.section("compare_table.html.j2", compare_page.template_values(data, None),
                compare_page.table_markdown(data))
    doc.links("Files", [("compare.json", "compare/compare.json"),
                        ("compare.csv", "compare/compare.csv"),
                        ("equal_time.csv", "compare/equal_time.csv")])


# Kemppinen et al. 2025, Table 3: the paper's frame times (1080p, 3 point lights, k = 4).
PAPER_TABLE3_RANGE_MS = "1.6–3.4"
PAPER_TABLE3 = f"{PAPER_TABLE3_RANGE_MS} ms per frame on an RTX 3090 (the range of the paper's Table 3)"


def write_gpu(doc, data, part):
    """The device check's timings (docs/gpu.md): each model's rate per precision and function, and
    the Table 3 analogue's frames beside the paper's, the hardware named, nothing normalised."""
    doc.heading(2, PART_TITLES["gpu"], "gpu")
    doc.para(f"{data['device']} (compute capability {data['compute_capability']}, CUDA "
             f"{data['cuda_version']}): each launch runs {data['timing_rows']} query rows, one "
             f"thread per row, timed with CUDA events after a warm-up launch, median of "
             f"{data['repetitions']}. The CPU = GPU comparison of the first {data['rows']} rows "
             "is ctest gpu.committed_runs_match_cpu (docs/gpu.md).")
    functions = ["eval", "pdf", "sample"]
    rates = {}
    for r in data["runs"]:
        rates[(r["model"], r["precision"], r["function"])] = r
    keys = []
    for r in data["runs"]:
        if (r["model"], r["precision"]) not in keys:
            keys.append((r["model"], r["precision"]))
    rows = []
    for model, precision in keys:
        row = [model, precision]
        for fn in functions:
            r = rates.get((model, precision, fn))
            row.append(f"{r['rows_per_second'] / 1e6:.4g} ({r['median_ms']:.4g} ms)" if r else "—")
        rows.append(row)
    doc.table(["model", "precision"] + [f"{fn}: Mrows/s (median ms)" for fn in functions], rows)
    if data["table3"]:
        doc.para("The Table 3 analogue (experiments/bench/kemppinen2025_table3_scene.h) as whole "
                 "1920×1080 frames on this device, one thread per pixel running the CPU "
                 f"benchmark's own shade_pixel in double precision. The paper: {PAPER_TABLE3}, "
                 "single precision in its shader — other hardware and another precision, shown "
                 "side by side, not normalised.")
        doc.table(["cell", "median ms per frame", "min ms", "Mpixels/s",
                   "paper, ms per frame (RTX 3090, Table 3's range)"],
                  [[f["cell"], f"{f['median_ms']:.4g}", f"{f['min_ms']:.4g}",
                    f"{f['pixels_per_second'] / 1e6:.4g}", PAPER_TABLE3_RANGE_MS]
                   for f in data["table3"]])
    doc.links("Files", [("results.json", "gpu/results.json")])


def build(root, run, got, plots_tmp):
    parts = run.get("parts", {})
    doc = Doc()
    title = "glintlab report"
    doc.heading(1, title, "top")
    doc.para(f"glintlab {run.get('glintlab_version', '?')}, {run.get('date', '')}, budget "
             f"{run.get('budget', '?')}, {machine_text(run.get('machine'))}.")
    write_summary(doc, got.get("claims"), run, got)
    doc.toc_here()
    doc.heading(2, "Run", "run")
    doc.list([part_line(n, parts.get(n)) for n in PARTS])
    logs = os.path.join(root, "logs")
    doc.links("Run record", [("run.json", "run.json")] +
              [(n, f"logs/{n}") for n in (sorted(os.listdir(logs)) if os.path.isdir(logs) else [])
               if not n.startswith(".") and not n.startswith("make_report")])
    made, manifest = [], []
    plots_rel = "plots"
    if "claims" in got:
        write_claims(doc, got["claims"], parts.get("claims", {}), root)
    if "conformance" in got:
        write_conformance(doc, got["conformance"], parts.get("conformance", {}), root)
    if "figures" in got:
        write_figures(doc, got["figures"], parts.get("figures", {}), root, plots_tmp, plots_rel,
                      made, manifest)
        write_adequacy(doc, got["figures"], got.get("claims"), parts.get("figures", {}), root,
                       plots_tmp, plots_rel, made, manifest)
    if "bench" in got:
        write_bench(doc, got["bench"], parts.get("bench", {}), root, plots_tmp, plots_rel, made,
                    manifest)
    if "stability" in got:
        write_stability(doc, got["stability"], parts.get("stability", {}), root, plots_tmp,
                        plots_rel, made, manifest)
    if "compare" in got:
        write_compare(doc, got["compare"], plots_tmp, plots_rel, made, manifest)
    if "gpu" in got:
        write_gpu(doc, got["gpu"], parts.get("gpu", {}))
    for n in PARTS:
        if n not in got:
            doc.heading(2, PART_TITLES[n], "absent-" + n)
            doc.para("Not in this report: " + part_line(n, parts.get(n)))
    # The table of contents, now that every heading is known, after the summary.
    doc.headings = [h for h in doc.headings if h[2] != "top"]
    toc_block, toc_m = doc.toc()
    hi, mi = doc.toc_at
    doc.blocks.insert(hi, toc_block)
    doc.md.insert(mi, toc_m)
    with open(os.path.join(plots_tmp, "plots.json"), "w", encoding="utf-8") as f:
        json.dump({"plots": manifest}, f, indent=1, sort_keys=True)
    made.append("plots.json")
    page = templating.render("report.html.j2", title=title, lang="en", stylesheet="report.css",
                             body=doc.blocks)
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
