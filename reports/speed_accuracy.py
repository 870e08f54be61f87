"""Speed vs accuracy: joins glintlab_accuracy's CSV with the Google Benchmark JSON
of scripts/bench.sh, marks the Pareto front, writes speed_accuracy.csv and speed_accuracy.png.
With --methods, also the method rows `method/<method>/<setting>` of the method benchmarks
(experiments/bench/METHOD_BENCHMARKS.md) into the same CSV (source=method) and a chart of every
method family with each method's front, speed_accuracy_methods.png. A method's front is among
the rows of its method id only (one reference, one error unit), on its RMS error by default
(--method-metric max|rms|p99; the kernel rows keep --metric).

Run by /usr/bin/python3 (Debian's, with matplotlib): scripts/speed_accuracy.sh calls it.
Time per evaluation = 1 / items_per_second of the benchmark `kernel/isa/math` (median aggregate
when the JSON has repetitions). Error = max (default) or RMS relative error against the scalar
double exact reference, as defined in experiments/bench/accuracy.cpp. A point is on the Pareto
front when no other point of the same method (the quantity computed, i.e. the reference kernel) is
at least as fast and at least as accurate and strictly better in one of the two.
"""

import argparse
import csv
import json
import math
import os
import statistics
import sys
import tempfile

OUT_COLUMNS = ["method", "kernel", "isa", "math", "ns_per_eval", "max_rel_error", "rms_rel_error",
               "on_pareto_front", "p99_rel_error", "nonfinite_mismatch", "reference",
               # method rows (and the kernel rows' equivalents): where the row comes from, the
               # setting (key=value,...), the benchmark's label, err_n, the binary
               "source", "setting", "label", "err_n", "binary"]
METHOD_COUNTERS = ("err_max", "err_rms", "err_p99", "err_n")
ZERO_FLOOR = 1e-17  # where an error of exactly 0 is drawn on the log axis


def dominates(a, b):
    """a = (time, error) dominates b: no worse in both, strictly better in one."""
    return a[0] <= b[0] and a[1] <= b[1] and (a[0] < b[0] or a[1] < b[1])


def pareto_front(points):
    """Indices of the non-dominated points of a list of (time, error), in input order.
    Equal points are both kept. O(n log n): sweep by time, then error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front = set()
    best = math.inf  # lowest error among strictly faster points
    k = 0
    while k < len(order):
        # Points with the same time form a group: only the group's minimum error can survive.
        j = k
        while j < len(order) and points[order[j]][0] == points[order[k]][0]:
            j += 1
        group = order[k:j]
        low = min(points[i][1] for i in group)
        if low < best:
            front.update(i for i in group if points[i][1] == low)
            best = low
        k = j
    return [i for i in range(len(points)) if i in front]


def is_pareto_front(points, indices):
    """True when `indices` is exactly the set of non-dominated points (the brute-force check)."""
    chosen = set(indices)
    for i, p in enumerate(points):
        dominated = any(dominates(q, p) for q in points)
        if dominated == (i in chosen):
            return False
    return True


def fail(msg):
    print(f"glintlab: error: {msg}", file=sys.stderr)
    sys.exit(2)


def load_bench(path):
    """{'kernel/isa/math': items_per_second}: the median aggregate, else the median of the runs."""
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"--bench: cannot read benchmark JSON {path}: {e}")
    medians, runs = {}, {}
    for b in data.get("benchmarks", []):
        if "items_per_second" not in b:
            continue
        name = b.get("run_name", b["name"])
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                medians[name] = b["items_per_second"]
        else:
            runs.setdefault(name, []).append(b["items_per_second"])
    for name, v in runs.items():
        medians.setdefault(name, statistics.median(v))
    return medians, data.get("context", {})


def load_accuracy(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"--accuracy: cannot read {path}: {e}")
    need = {"method", "kernel", "isa", "math", "reference", "max_rel_error", "rms_rel_error",
            "p99_rel_error", "nonfinite_mismatch"}
    if not rows or not need.issubset(rows[0].keys()):
        fail(f"--accuracy: {path} is not a glintlab_accuracy CSV (needs columns {sorted(need)})")
    return rows


def join(rows, speeds, metric):
    """Adds ns_per_eval and the front flags; rows without a benchmark get no time and no flag."""
    key = "max_rel_error" if metric == "max" else "rms_rel_error"
    for r in rows:
        ips = speeds.get(f"{r['kernel']}/{r['isa']}/{r['math']}")
        r["ns_per_eval"] = 1e9 / ips if ips else None
        r["on_pareto_front"] = 0
        r.update(source="kernel", setting=f"kernel={r['kernel']},isa={r['isa']},math={r['math']}",
                 label="", err_n=r.get("compared", ""), binary="glintlab_accuracy")
    timed = [r for r in rows if r["ns_per_eval"] is not None]
    by_method = {}
    for r in timed:
        by_method.setdefault(r["method"], []).append(r)
    for group in by_method.values():
        pts = [(r["ns_per_eval"], float(r[key])) for r in group]
        for i in pareto_front(pts):
            group[i]["on_pareto_front"] = 1
    return timed


def parse_method_name(name, path):
    """'method/<method>/<setting>' -> (method, setting); fails on anything else."""
    parts = name.split("/")
    if len(parts) != 3 or parts[0] != "method" or not parts[1] or not parts[2] or \
            any(" " in p for p in parts):
        fail(f"--methods: {path}: benchmark '{name}' is not method/<method>/<setting> "
             "(no '/' or spaces inside the parts)")
    return parts[1], parts[2]


def load_methods(paths):
    """The method rows of every JSON (one per method/setting): time from the median aggregate (else
    the median of the runs), counters and label from the same entry. An empty file or an empty
    benchmark list is a binary without method rows."""
    rows = []
    seen = {}
    for path in paths:
        try:
            with open(path) as f:
                text = f.read()
            data = json.loads(text) if text.strip() else {"benchmarks": []}
        except (OSError, ValueError) as e:
            fail(f"--methods: cannot read benchmark JSON {path}: {e}")
        binary = os.path.splitext(os.path.basename(path))[0]
        entries = {}
        for b in data.get("benchmarks", []):
            name = b.get("run_name", b.get("name", ""))
            if not name.startswith("method/") or b.get("error_occurred"):
                continue
            e = entries.setdefault(name, {"median": None, "runs": [], "label": ""})
            e["label"] = e["label"] or b.get("label", "")
            if b.get("run_type") == "aggregate":
                if b.get("aggregate_name") == "median":
                    e["median"] = b
            else:
                e["runs"].append(b)
        for name, e in entries.items():
            method, setting = parse_method_name(name, path)
            if name in seen:
                fail(f"--methods: '{name}' appears in both {seen[name]} and {path}")
            seen[name] = path
            runs = [e["median"]] if e["median"] else e["runs"]
            if not runs or any("items_per_second" not in b for b in runs):
                fail(f"--methods: {path}: '{name}' has no items_per_second (SetItemsProcessed)")
            missing = [c for c in METHOD_COUNTERS if c not in runs[0]]
            if missing:
                fail(f"--methods: {path}: '{name}' lacks the counters {missing}")
            ips = statistics.median(b["items_per_second"] for b in runs)
            err = {c: float(runs[0][c]) for c in METHOD_COUNTERS}
            if not all(math.isfinite(v) and v >= 0 for v in err.values()) or not ips > 0:
                fail(f"--methods: {path}: '{name}' has a negative or non-finite error or time "
                     f"({err}, items/s {ips})")
            label = e["label"]
            rows.append({"method": method, "kernel": "", "isa": "", "math": "",
                         "ns_per_eval": 1e9 / ips, "max_rel_error": f"{err['err_max']:.6g}",
                         "rms_rel_error": f"{err['err_rms']:.6g}",
                         "p99_rel_error": f"{err['err_p99']:.6g}", "nonfinite_mismatch": "",
                         "reference": label.split(";")[0].strip(), "on_pareto_front": 0,
                         "source": "method", "setting": setting, "label": label,
                         "err_n": f"{err['err_n']:.0f}", "binary": binary})
    return rows


METHOD_METRIC_COLUMN = {"max": "max_rel_error", "rms": "rms_rel_error", "p99": "p99_rel_error"}


def mark_fronts(rows, metric):
    """Sets on_pareto_front per method id (rows of one method share a reference and a unit)."""
    key = METHOD_METRIC_COLUMN[metric]
    by_method = {}
    for r in rows:
        by_method.setdefault(r["method"], []).append(r)
    for group in by_method.values():
        pts = [(r["ns_per_eval"], float(r[key])) for r in group]
        for i in pareto_front(pts):
            group[i]["on_pareto_front"] = 1
    return by_method


def write_atomic(path, write):
    d = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(prefix=".tmp.", dir=d)
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_csv(rows, path):
    def w(tmp):
        with open(tmp, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(OUT_COLUMNS)
            for r in rows:
                ns = "" if r["ns_per_eval"] is None else f"{r['ns_per_eval']:.6g}"
                out.writerow([r["method"], r["kernel"], r["isa"], r["math"], ns,
                              r["max_rel_error"], r["rms_rel_error"], r["on_pareto_front"],
                              r["p99_rel_error"], r["nonfinite_mismatch"], r["reference"],
                              r["source"], r["setting"], r["label"], r["err_n"], r["binary"]])
    write_atomic(path, w)


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def plot(timed, path, metric, machine, date):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    key = "max_rel_error" if metric == "max" else "rms_rel_error"
    colors = {"float_exact": "tab:blue", "float_fast": "tab:orange", "double_exact": "tab:green"}
    markers = {"scalar": "o", "sse4.2": "s", "avx2": "^", "avx512": "D"}
    fig, ax = plt.subplots(figsize=(12, 8))
    for r in timed:
        e = max(float(r[key]), ZERO_FLOOR)
        front = r["on_pareto_front"] == 1
        formula = r["kernel"] != r["method"]
        ax.scatter(r["ns_per_eval"], e, s=34 if front else 14,
                   marker=markers.get(r["isa"], "x"), c=colors.get(r["math"], "gray"),
                   alpha=0.95 if front else 0.25,
                   edgecolors="red" if formula else ("black" if front else "none"),
                   linewidths=0.8)
    # Each method's front as a thin step line through its front points, fastest first.
    fronts = {}
    for r in timed:
        if r["on_pareto_front"] == 1:
            fronts.setdefault(r["method"], []).append(r)
    for group in fronts.values():
        group.sort(key=lambda r: r["ns_per_eval"])
        ax.step([r["ns_per_eval"] for r in group],
                [max(float(r[key]), ZERO_FLOOR) for r in group], where="post", color="black",
                lw=0.5, alpha=0.5, zorder=0)
    ax.axhline(ZERO_FLOOR, color="gray", ls=":", lw=0.8)
    ax.text(0.005, ZERO_FLOOR * 1.6, "error exactly 0 drawn here", fontsize=7, color="gray",
            transform=ax.get_yaxis_transform())
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per evaluation [ns] (1 / items per second, one thread, 4096-row batches)")
    ax.set_ylabel(f"{metric} relative error vs scalar double exact reference [1]")
    ax.set_title(f"glintlab speed vs accuracy: every kernel × ISA × math ({len(timed)} points; fronts per method)\n"
                 f"{machine}, {date}", fontsize=10)
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], ls="", marker="o", color=c, label=m) for m, c in colors.items()]
    handles += [Line2D([], [], ls="", marker=mk, color="gray", label=i)
                for i, mk in markers.items() if any(r["isa"] == i for r in timed)]
    handles += [Line2D([], [], ls="", marker="o", color="gray", markeredgecolor="black",
                       label="on its method's Pareto front (opaque)"),
                Line2D([], [], ls="", marker="o", color="white", markeredgecolor="red",
                       label="printed / approximate formula vs the exact one"),
                Line2D([], [], color="black", lw=0.5, label="Pareto front of one method")]
    ax.legend(handles=handles, fontsize=7, loc="upper right")
    ax.grid(True, which="major", alpha=0.3)
    fig.tight_layout()
    write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=130, format="png"))
    plt.close(fig)


def family(method):
    return method.split(".", 1)[0]


def plot_methods(kernel_rows, method_rows, path, metric, method_metric, machine, date,
                 record=None):
    """One panel per method family (the method id's first dotted part) and one for the kernels'
    exact vs fast math; colour per method, its front as filled points joined by a staircase with
    the settings written beside them; dominated settings hollow."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    kernel_key = "max_rel_error" if metric == "max" else "rms_rel_error"
    method_key = METHOD_METRIC_COLUMN[method_metric]
    families = sorted({family(r["method"]) for r in method_rows})
    panels = [("kernels", None)] if kernel_rows else []
    panels += [(f, f) for f in families]
    cols = 2 if len(panels) > 1 else 1
    nrows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(8.5 * cols, 6.2 * nrows), squeeze=False)
    cmap = plt.get_cmap("tab10")
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    for ax, (title, fam) in zip(axes.flat, panels):
        mine = kernel_rows if fam is None else [r for r in method_rows
                                                if family(r["method"]) == fam]
        key = kernel_key if fam is None else method_key
        nonzero = [float(r[key]) for r in mine if float(r[key]) > 0]
        # Errors of exactly 0 (references) drawn a decade below the panel's smallest error.
        floor = ZERO_FLOOR if fam is None or not nonzero else \
            10 ** (math.floor(math.log10(min(nonzero))) - 1)
        if fam is None:  # kernels: each kernel method's front, coloured by math flavour
            colors = {"float_exact": "tab:blue", "float_fast": "tab:orange",
                      "double_exact": "tab:green"}
            for r in kernel_rows:
                front = r["on_pareto_front"] == 1
                ax.scatter(r["ns_per_eval"], max(float(r[key]), ZERO_FLOOR),
                           s=16 if front else 5, c=colors.get(r["math"], "gray"),
                           alpha=0.9 if front else 0.15, linewidths=0)
            handles = [Line2D([], [], ls="", marker="o", color=c, label=m)
                       for m, c in colors.items()]
            ax.legend(handles=handles, fontsize=7, loc="upper right",
                      title="opaque: on its kernel's front", title_fontsize=7)
            ax.set_title("kernels × ISA: exact vs fast math (vs scalar double exact; "
                         "relative error)", fontsize=9)
        else:
            methods = sorted({r["method"] for r in method_rows if family(r["method"]) == fam})
            handles = []
            for mi, m in enumerate(methods):
                c = cmap(mi % 10)
                group = [r for r in method_rows if r["method"] == m]
                for r in group:
                    front = r["on_pareto_front"] == 1
                    ax.scatter(r["ns_per_eval"], max(float(r[key]), floor),
                               s=38 if front else 22, marker="o",
                               facecolors=c if front else "none", edgecolors=c, linewidths=1.0,
                               zorder=3)
                front = sorted((r for r in group if r["on_pareto_front"] == 1),
                               key=lambda r: r["ns_per_eval"])
                ax.step([r["ns_per_eval"] for r in front],
                        [max(float(r[key]), floor) for r in front], where="post", color=c,
                        lw=0.9, alpha=0.7, zorder=2)
                for k, r in enumerate(front):  # alternate above / below against overlaps
                    ax.annotate(r["setting"], (r["ns_per_eval"], max(float(r[key]), floor)),
                                textcoords="offset points", xytext=(4, 4 if k % 2 == 0 else -8),
                                fontsize=5.5, color=c)
                label = group[0]["label"].replace(" (reference)", "")
                kind = label.split(";", 1)[-1].strip() if label else ""
                short = m[len(fam) + 1:] if m.startswith(fam + ".") else m
                handles.append(Line2D([], [], color=c, marker="o", lw=0.9,
                                      label=f"{short}: {kind}"[:95]))
            ax.legend(handles=handles, fontsize=6, loc="upper center",
                      bbox_to_anchor=(0.5, -0.11), ncol=1, frameon=False)
            ax.set_title(f"{fam}: {len(methods)} method(s); filled = on its front, hollow = "
                         "dominated", fontsize=9)
        ax.axhline(floor, color="gray", ls=":", lw=0.8)
        ax.text(0.005, floor * 1.3, "error 0 (reference) drawn here", fontsize=6,
                color="gray", transform=ax.get_yaxis_transform())
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("time per evaluation [ns], one thread", fontsize=8)
        ax.set_ylabel(f"{metric if fam is None else method_metric} error vs the "
                      "method's reference (unit: legend)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", alpha=0.3)
    fig.suptitle(f"glintlab speed vs accuracy of every method and setting, Pareto front per "
                 f"method ({len(method_rows)} method rows, {len(kernel_rows)} kernel rows)\n"
                 f"{machine}, {date}", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    if record:
        record(fig)
    write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=120, format="png"))
    plt.close(fig)


def kernel_family(method):
    """The quantity a kernel method computes, grouped: d, g1, g2, lambda, brdf, map, area, vndf,
    pdf, sample (the model, ggx or beckmann, is drawn in the colour)."""
    head, _, rest = method.partition(".")
    if head in ("pdf", "sample") or not rest:
        return head
    name = rest.split("/", 1)[0]
    for prefix, fam in (("brdf", "brdf"), ("map_", "map"), ("projected_area", "area"),
                        ("total_area", "area"), ("g2", "g2")):
        if name.startswith(prefix):
            return fam
    return name


def plot_families(timed, path, metric, machine, date, record=None):
    """One small panel per kernel family (kernel_family): every kernel x ISA x math point of the
    family, colour per method, marker per math flavour, each method's Pareto front a staircase.
    record(fig), when given, is called before the figure is saved (the report's manifest)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    key = "max_rel_error" if metric == "max" else "rms_rel_error"
    markers = {"float_exact": "o", "float_fast": "^", "double_exact": "s"}
    fams = sorted({kernel_family(r["method"]) for r in timed})
    cols = min(4, len(fams))
    nrows = (len(fams) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(4.4 * cols, 3.9 * nrows), squeeze=False)
    for ax in axes.flat[len(fams):]:
        ax.set_visible(False)
    cmap = plt.get_cmap("tab10")
    for ax, fam in zip(axes.flat, fams):
        mine = [r for r in timed if kernel_family(r["method"]) == fam]
        methods = sorted({r["method"] for r in mine})
        handles = []
        for mi, m in enumerate(methods):
            c = cmap(mi % 10)
            group = [r for r in mine if r["method"] == m]
            for r in group:
                front = r["on_pareto_front"] == 1
                ax.scatter(r["ns_per_eval"], max(float(r[key]), ZERO_FLOOR), s=14 if front else 6,
                           marker=markers.get(r["math"], "x"), c=[c], alpha=0.95 if front else 0.3,
                           linewidths=0)
            fr = sorted((r for r in group if r["on_pareto_front"] == 1),
                        key=lambda r: r["ns_per_eval"])
            ax.step([r["ns_per_eval"] for r in fr], [max(float(r[key]), ZERO_FLOOR) for r in fr],
                    where="post", color=c, lw=0.8, alpha=0.8)
            handles.append(Line2D([], [], color=c, lw=0.8, label=m[:40]))
        handles += [Line2D([], [], ls="", marker=mk, color="gray", label=f)
                    for f, mk in markers.items()]
        ax.legend(handles=handles, fontsize=5, loc="best", ncol=1 if len(handles) < 9 else 2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{fam}: {len(methods)} method(s), {len(mine)} points", fontsize=8)
        ax.set_xlabel("time per evaluation [ns], one thread", fontsize=7)
        ax.set_ylabel(f"{metric} relative error [1] (0 drawn at {ZERO_FLOOR:g})", fontsize=7)
        ax.tick_params(labelsize=6)
        ax.grid(True, which="major", alpha=0.3)
    fig.suptitle(f"speed vs accuracy per kernel family ({len(timed)} kernel x ISA x math points; "
                 f"line: each method's Pareto front, faint: dominated)\n{machine}, {date}",
                 fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    if record:
        record(fig)
    write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=100, format="png"))
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--accuracy", default="out/bench/accuracy.csv")
    p.add_argument("--bench", default="out/bench/bench.json")
    p.add_argument("--out-dir", default="out/bench")
    p.add_argument("--metric", default="max", help="max or rms relative error")
    p.add_argument("--date", default=None, help="date in the title (default: the bench JSON's)")
    p.add_argument("--method-metric", default="rms",
                   help="error of the method rows' fronts and chart: max, rms or p99 (default "
                        "rms: pixel and P22 errors have outliers that the max alone shows)")
    p.add_argument("--methods", nargs="*", default=[],
                   help="method benchmark JSONs (out/bench/methods/<binary>.json)")
    a = p.parse_args(argv)
    if a.metric not in ("max", "rms"):
        fail(f"--metric must be max or rms (got '{a.metric}')")
    if a.method_metric not in METHOD_METRIC_COLUMN:
        fail(f"--method-metric must be max, rms or p99 (got '{a.method_metric}')")
    rows = load_accuracy(a.accuracy)
    speeds, context = load_bench(a.bench)
    timed = join(rows, speeds, a.metric)
    if not timed:
        fail(f"--bench: {a.bench} has no benchmark matching a row of {a.accuracy}")
    method_rows = load_methods(a.methods)
    mark_fronts(method_rows, a.method_metric)
    os.makedirs(a.out_dir, exist_ok=True)
    write_csv(rows + method_rows, os.path.join(a.out_dir, "speed_accuracy.csv"))
    machine = context.get("cpu_model") or cpu_model()
    date = a.date or context.get("date", "")[:10]
    plot(timed, os.path.join(a.out_dir, "speed_accuracy.png"), a.metric, machine, date)
    charts = "speed_accuracy.png"
    if method_rows:
        plot_methods(timed, method_rows, os.path.join(a.out_dir, "speed_accuracy_methods.png"),
                     a.metric, a.method_metric, machine, date)
        charts += ", speed_accuracy_methods.png"
    untimed = len(rows) - len(timed)
    print(f"speed_accuracy: {len(timed)} points ({untimed} without a benchmark), "
          f"{sum(r['on_pareto_front'] for r in timed)} on their method's front; "
          f"{len(method_rows)} method rows of {len({r['method'] for r in method_rows})} methods, "
          f"{sum(r['on_pareto_front'] for r in method_rows)} on their front -> "
          f"{a.out_dir}/speed_accuracy.csv, {charts}")


if __name__ == "__main__":
    main()
