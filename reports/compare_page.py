"""The page of `glintlab compare`: reads DIR/compare.json (written by experiments/compare/) and
draws the equal-time chart (DIR/equal_time.png) and the page (DIR/index.html, from
templates/compare_page.html.j2). make_report.py uses the same chart, templates and Markdown table
for the report's comparison section.

Usage: /usr/bin/python3 compare_page.py --dir DIR
"""

import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import charts  # noqa: E402
import templating  # noqa: E402


def load(directory):
    with open(os.path.join(directory, "compare.json"), encoding="utf-8") as f:
        return json.load(f)


fmt = templating.fmt


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


def template_values(data, png_rel):
    """What the compare templates read: compare.json and the names of the verdicts' origins."""
    return {"compare": data, "png": png_rel, "run_origins": RUN_ORIGINS,
            "recorded_source": RECORDED_SOURCE, "not_run_header": NOT_RUN_HEADER}


def table_html(data):
    """The table of the models (HTML), as the page and the report show it."""
    return templating.render("compare_table.html.j2", data=template_values(data, None))


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
    page = templating.render("compare_page.html.j2", title="glintlab compare", lang=None,
                             stylesheet=None, data=template_values(data, "equal_time.png"))
    tmp = os.path.join(a.dir, f".index.html.tmp.{os.getpid()}")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(tmp, os.path.join(a.dir, "index.html"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
