"""Speed vs accuracy (issue 9 item 5): joins glintlab_accuracy's CSV with the Google Benchmark JSON
of scripts/bench.sh, marks the Pareto front, writes speed_accuracy.csv and speed_accuracy.png.

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
               "on_pareto_front", "p99_rel_error", "nonfinite_mismatch", "reference"]
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
    timed = [r for r in rows if r["ns_per_eval"] is not None]
    by_method = {}
    for r in timed:
        by_method.setdefault(r["method"], []).append(r)
    for group in by_method.values():
        pts = [(r["ns_per_eval"], float(r[key])) for r in group]
        for i in pareto_front(pts):
            group[i]["on_pareto_front"] = 1
    return timed


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
                              r["p99_rel_error"], r["nonfinite_mismatch"], r["reference"]])
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


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--accuracy", default="out/bench/accuracy.csv")
    p.add_argument("--bench", default="out/bench/bench.json")
    p.add_argument("--out-dir", default="out/bench")
    p.add_argument("--metric", default="max", help="max or rms relative error")
    p.add_argument("--date", default=None, help="date in the title (default: the bench JSON's)")
    a = p.parse_args(argv)
    if a.metric not in ("max", "rms"):
        fail(f"--metric must be max or rms (got '{a.metric}')")
    rows = load_accuracy(a.accuracy)
    speeds, context = load_bench(a.bench)
    timed = join(rows, speeds, a.metric)
    if not timed:
        fail(f"--bench: {a.bench} has no benchmark matching a row of {a.accuracy}")
    os.makedirs(a.out_dir, exist_ok=True)
    write_csv(rows, os.path.join(a.out_dir, "speed_accuracy.csv"))
    machine = context.get("cpu_model") or cpu_model()
    date = a.date or context.get("date", "")[:10]
    plot(timed, os.path.join(a.out_dir, "speed_accuracy.png"), a.metric, machine, date)
    untimed = len(rows) - len(timed)
    print(f"speed_accuracy: {len(timed)} points ({untimed} without a benchmark), "
          f"{sum(r['on_pareto_front'] for r in timed)} on their method's front "
          "-> "
          f"{a.out_dir}/speed_accuracy.csv, speed_accuracy.png")


if __name__ == "__main__":
    main()
