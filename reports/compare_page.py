"""The page of `glintlab compare`: reads DIR/compare.json (written by experiments/compare/) and
draws the equal-time chart (DIR/equal_time.png) and the page (DIR/index.html). make_report.py
uses the same functions for the report's comparison section.

Usage: /usr/bin/python3 compare_page.py --dir DIR
"""

import argparse
import html
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import charts  # noqa: E402


def load(directory):
    with open(os.path.join(directory, "compare.json"), encoding="utf-8") as f:
        return json.load(f)


def fmt(x, spec=".3g"):
    return "–" if x is None else format(x, spec)


def draw_equal_time(data, path, relpath="equal_time.png", manifest=None):
    """Relative RMS error of each model's sampler estimate against wall time, log-log."""
    plt = charts.pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5))
    drawn = 0
    for m in data["models"]:
        pts = [p for p in m["equal_time"]["points"]
               if p["relative_rmse"] is not None and p["relative_rmse"] > 0 and p["seconds"] > 0]
        if not pts:
            continue
        xs = [p["seconds"] * 1e6 for p in pts]
        line, = ax.loglog(xs, [p["relative_rmse"] for p in pts],
                          marker="o", markersize=3, label=m["name"])
        # The reference's own error: the curve cannot be resolved below it.
        floor = m["equal_time"].get("reference_relative_error")
        if floor:
            ax.plot([min(xs), max(xs)], [floor, floor], linestyle=":", linewidth=1,
                    color=line.get_color())
        drawn += 1
    s = data["settings"]
    ax.set_title("Equal-time error: albedo estimate with each model's sampler\n"
                 f"{data['machine']}; budget {s['budget']}", fontsize=9)
    ax.set_xlabel("wall time per estimate (µs, this machine)")
    ax.set_ylabel("relative RMS error against the model's reference")
    if drawn:
        ax.plot([], [], linestyle=":", color="grey", label="reference's own error (each model)")
    ax.grid(True, which="both", alpha=0.3)
    if drawn == 0:
        ax.plot([], [], label="no model has a curve")
    ax.legend(fontsize=7)
    fig.tight_layout()
    if manifest is not None:
        charts.save(fig, path, relpath, manifest)
    else:
        fig.savefig(path, dpi=110, format="png", metadata={"Software": None})
        plt.close(fig)


# Verdicts this run measured (here, or in the run whose claims.json was read) and those it did not:
# the recorded ones are copied from glintlab's source, so they get a column of their own.
RUN_ORIGINS = ("measured", "read")
RECORDED_SOURCE = "verify/conformance/conformance.cpp"
NOT_RUN_HEADER = (f"conformance not measured in this run (recorded: copied from {RECORDED_SOURCE}; "
                  "declared: not claimed by the model)")


def conformance_cell(m, this_run):
    """The verdicts of one model measured in this run (this_run) or not (recorded, declared, not
    measured), each labelled with its origin; "—" when there is none."""
    out = []
    for v in m["conformance"]:
        if (v["origin"] in RUN_ORIGINS) != this_run:
            continue
        mark = "" if v["origin"] == "measured" else f" ({v['origin']})"
        out.append(f"<span title=\"{html.escape(v['detail'])}\">{html.escape(v['property'])}: "
                   f"<b>{html.escape(v['verdict'])}</b>{html.escape(mark)}</span>")
    return "<br>".join(out) or "—"


def reference_cell(m):
    out = []
    for r in m["reference"]:
        if not r["converged"]:
            out.append(f"θi {r['theta_deg']:g}°: <b>{r['method']} did not converge</b> (not used)")
        else:
            out.append(f"θi {r['theta_deg']:g}°: {fmt(r['albedo'], '.5g')} ± {fmt(r['error'])} "
                       f"({r['method']})")
    return "<br>".join(out)


def error_cell(m):
    e = m["equal_time"]
    if e["not_shown"]:
        return f"not shown: {html.escape(e['not_shown'])}"
    last = e["points"][-1]
    return (f"{fmt(last['relative_rmse'])} at N = {last['samples']} (reference's own error "
            f"{fmt(e.get('reference_relative_error'), '.2g')}); bias "
            f"{fmt(e['relative_bias'], '+.2g')} ± {fmt(e['relative_bias_se'], '.2g')}")


def stability_cell(m):
    return "<br>".join(
        f"{html.escape(s['sampler'])}: <b>{html.escape(s['verdict'])}</b> ({s['origin']}) "
        f"{html.escape(s['failure_region'])}" for s in m["stability"])


def intro_html(data):
    s = data["settings"]
    scenes = ", ".join(f"{t:g}°" for t in s["theta_deg"])
    return f"""<p>Every model at its default parameters on the same scenes: θi ∈ {{{scenes}}}, a
footprint of side {s['footprint_side_uv']:g} in uv, a 1° light cone for area-light models and a
delta light otherwise. Quantity: {html.escape(s['quantity'])}. Reference: the conformance
suite's integral (the truth of sampler-covers-value): cubature for models without a footprint;
for footprint models Monte Carlo over a fixed mixture about the mirror direction, blocks of
{s['reference_monte_carlo_block']} draws, as many (at most {s['reference_monte_carlo_max_blocks']})
as reach a relative error of {s['reference_monte_carlo_target_relative_error']:g}. A reference whose relative error exceeds {s['cubature_converged_relative_error']:g}
(cubature) or {s['monte_carlo_converged_relative_error']:g} (Monte Carlo, one standard error) is
flagged as not converged and not used. Times are measurements of this run's machine
({html.escape(data['machine'])}). Conformance verdicts are in two columns: those of this run
(marked "read" when they come from {html.escape(str(s['claims_from']))}) and those not measured in
this run: "recorded" ones are copied from the verdicts recorded for this budget in glintlab's
source ({RECORDED_SOURCE}), "declared" ones are properties the model does not claim.</p>"""


def table_html(data):
    rows = []
    for m in data["models"]:
        t = m["timing"]
        rows.append(
            "<tr>" + "".join(f"<td>{c}</td>" for c in [
                f"<b>{html.escape(m['name'])}</b>",
                conformance_cell(m, True), conformance_cell(m, False),
                f"{fmt(t['scalar_ns_per_eval'], '.1f')} → {fmt(t['best_ns_per_eval'], '.1f')} "
                f"({html.escape(t['best_isa'])}{'' if t['batched'] else ', not batched'})",
                reference_cell(m), error_cell(m), stability_cell(m)]) + "</tr>")
    return ("<table><thead><tr><th>model</th><th>conformance, this run</th>"
            f"<th>{html.escape(NOT_RUN_HEADER)}</th>"
            "<th>ns/eval scalar → best ISA</th><th>reference albedo per scene</th>"
            "<th>sampler error against it</th><th>stability</th></tr></thead><tbody>\n" +
            "\n".join(rows) + "\n</tbody></table>\n")


def section_html(data, png_rel):
    return (f"<h1>Models compared ({html.escape(data['settings']['budget'])} budget)</h1>\n" +
            intro_html(data) + f'\n<p><img src="{html.escape(png_rel)}" '
            'alt="equal-time error curves" width="680"></p>\n' + table_html(data))


def table_markdown(data):
    lines = [f"| model | conformance, this run | {NOT_RUN_HEADER} | ns/eval scalar → best | "
             "sampler error | stability |",
             "|---|---|---|---|---|---|"]
    for m in data["models"]:
        counts = [{}, {}]  # this run, not
        for v in m["conformance"]:
            key = v["verdict"] + ("" if v["origin"] == "measured" else f" ({v['origin']})")
            c = counts[0 if v["origin"] in RUN_ORIGINS else 1]
            c[key] = c.get(key, 0) + 1
        t = m["timing"]
        e = m["equal_time"]
        err = (f"not shown: {e['not_shown']}" if e["not_shown"] else
               f"{fmt(e['points'][-1]['relative_rmse'])} at N = {e['points'][-1]['samples']}")
        lines.append(
            f"| {m['name']} | "
            + " | ".join(", ".join(f"{k} {n}" for k, n in c.items()) or "—" for c in counts) +
            " | "
            f"{fmt(t['scalar_ns_per_eval'], '.1f')} → {fmt(t['best_ns_per_eval'], '.1f')} "
            f"({t['best_isa']}) | {err} | "
            f"{'; '.join(s['sampler'] + ': ' + s['verdict'] for s in m['stability'])} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    a = ap.parse_args()
    try:
        data = load(a.dir)
    except (OSError, ValueError, KeyError) as e:
        print(f"glintlab: error: compare.json in {a.dir} is unreadable ({e})", file=sys.stderr)
        return 2
    draw_equal_time(data, os.path.join(a.dir, "equal_time.png"))
    page = ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>glintlab compare"
            "</title></head><body>\n" + section_html(data, "equal_time.png") +
            "<p>Data: <a href=\"compare.json\">compare.json</a>, <a href=\"compare.csv\">"
            "compare.csv</a>, <a href=\"equal_time.csv\">equal_time.csv</a>.</p>\n</body></html>\n")
    tmp = os.path.join(a.dir, f".index.html.tmp.{os.getpid()}")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(tmp, os.path.join(a.dir, "index.html"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
