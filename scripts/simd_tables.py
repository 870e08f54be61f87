#!/usr/bin/python3
"""The benchmark JSON of scripts/bench.sh, annotated and turned into docs/simd.md's speed tables.

  simd_tables.py annotate BENCH.json [--uarch-counts COUNTS.json]
      Adds to BENCH.json (in place):
      - per kernel row (kernel/<isa>/<flavour>, every working set): peak_gflops, the FLOP peak of
        one core for the row's ISA and precision measured in the same run (the uarch/peak/<isa>/
        <precision> row of bench_uarch.cpp: an FMA-bound loop, mul + add where the ISA's build
        has no FMA), and roofline_fraction = counted FLOPs per item x items/s / that peak;
      - the same-FLOPs check, per median (or single-run) chunk row of a batched ISA (not scalar):
        the rows of the same ISA and flavour whose counted FLOPs per item are within a factor 1.25
        of this row's (0.8x to 1.25x) are its peers; same_flops_slow = 1 when the row runs at less than half the items/s
        of its fastest peer (same_flops_peer, same_flops_rate_ratio name it), else 0; the row's
        label says SLOW when flagged; the flagged rows also go to the top-level same_flops_flags;
      - a top-level targets list (docs/simd.md "Targets"): each target's row, measured value,
        threshold and whether it is met, with the instructions and loads per item of its rows
        and of the rows it is read against (COMPARE) from COUNTS.json
        (experiments/bench/uarch_counts.py) where given.
  simd_tables.py tables BENCH.json [--update DOC.md]
      Prints the Markdown tables (every row named with its ISA and the machine of the JSON
      context); with --update, replaces the text between the markers
      <!-- simd_tables.py begin --> and <!-- simd_tables.py end --> of DOC.md with them.

Standard library only (run with /usr/bin/python3). Never rewrites numbers it did not compute.
"""
import argparse
import collections
import json
import sys

BEGIN = "<!-- simd_tables.py begin -->"
END = "<!-- simd_tables.py end -->"
ISAS = ["scalar", "sse4.2", "avx2", "avx512"]
FLAVOURS = ["float_exact", "float_fast", "double_exact"]
# Peers: counted FLOPs per item within a factor 1.25 either way. 10 % would miss the case the
# check exists for: the VNDF pdf (39 FLOPs) runs at a fifth of ggx.vndf (32 FLOPs) on AVX2.
SAME_FLOPS_FACTOR = 1.25
SLOW_RATIO = 0.5  # flagged below half the rate of the fastest peer

# (id, what, numerator row, denominator row or None, threshold): items/s ≥ threshold, or the
# ratio numerator / denominator ≥ threshold. Issue 39 item 4, one core of this machine class.
TARGETS = [
    ("heitz_sample_avx2", "batched GGX VNDF sample + reflect + pdf, AVX2 float, Mitem/s",
     "sample.heitz_vndf/ggx/avx2/float_exact", None, 110e6),
    ("heitz_sample_avx512", "batched GGX VNDF sample + reflect + pdf, AVX-512 float, Mitem/s",
     "sample.heitz_vndf/ggx/avx512/float_exact", None, 200e6),
    ("vndf_pdf_avx2", "batched VNDF pdf of a reflected direction, AVX2 float, Mitem/s",
     "pdf.heitz_vndf/ggx/avx2/float_exact", None, 800e6),
    ("deliot_belcour_avx2", "deliot_belcour eval, AVX2 float over scalar float",
     "model/deliot_belcour/avx2/eval_float", "model/deliot_belcour/scalar/eval_float", 4.0),
    ("deliot_belcour_avx512", "deliot_belcour eval, AVX-512 float over scalar float",
     "model/deliot_belcour/avx512/eval_float", "model/deliot_belcour/scalar/eval_float", 6.0),
    ("kneiphof_klein_avx2", "kneiphof_klein eval, AVX2 float over scalar float",
     "model/kneiphof_klein/avx2/eval_float", "model/kneiphof_klein/scalar/eval_float", 4.0),
    ("kneiphof_klein_avx512", "kneiphof_klein eval, AVX-512 float over scalar float",
     "model/kneiphof_klein/avx512/eval_float", "model/kneiphof_klein/scalar/eval_float", 6.0),
]


# Rows counted beside a target's own (experiments/bench/uarch_counts.py): what it is read against.
COMPARE = {
    "sample.heitz_vndf/ggx/avx2/float_exact": ["sample.heitz_vndf/ggx/scalar/float_exact"],
    "sample.heitz_vndf/ggx/avx512/float_exact": ["sample.heitz_vndf/ggx/scalar/float_exact"],
    "pdf.heitz_vndf/ggx/avx2/float_exact": ["ggx.vndf/avx2/float_exact",
                                            "pdf.heitz_vndf/ggx/scalar/float_exact"],
}


def rows_by_name(d):
    """run_name -> the row the tables read: the median aggregate, else the single run."""
    out = collections.OrderedDict()
    for b in d["benchmarks"]:
        name = b.get("run_name", b["name"])
        agg = b.get("aggregate_name")
        if agg == "median" or (agg is None and b.get("run_type", "iteration") == "iteration"
                               and name not in out):
            out[name] = b
    return out


def kernel_key(name):
    """(working set prefix, kernel, isa, flavour) of a kernel row, or None."""
    if name.startswith(("model/", "uarch/", "chi_square")):
        return None
    prefix = ""
    for p in ("l1/", "stream/"):
        if name.startswith(p):
            prefix, name = p, name[len(p):]
    parts = name.rsplit("/", 2)
    if len(parts) != 3 or parts[1] not in ISAS or parts[2] not in FLAVOURS:
        return None
    return prefix, parts[0], parts[1], parts[2]


def peaks(rows):
    """(isa, 'float' | 'double') -> measured FLOP/s of uarch/peak/<isa>/<precision>."""
    out = {}
    for name, b in rows.items():
        parts = name.split("/")
        if len(parts) == 4 and parts[:2] == ["uarch", "peak"]:
            out[(parts[2], parts[3])] = b["flops_per_second"]
    return out


def annotate(d, counts=None):
    # Idempotent: a second run replaces the first's fields and SLOW labels.
    for b in d["benchmarks"]:
        for k in ("same_flops_peers", "same_flops_slow", "same_flops_peer",
                  "same_flops_rate_ratio"):
            b.pop(k, None)
        if "SLOW: " in b.get("label", ""):
            b["label"] = b["label"][:b["label"].index("SLOW: ")].rstrip()
            if not b["label"]:
                del b["label"]
    rows = rows_by_name(d)
    peak = peaks(rows)
    # Roofline on every kernel entry (each aggregate: its own FLOP rate over the median peak).
    for b in d["benchmarks"]:
        key = kernel_key(b.get("run_name", b["name"]))
        if key is None or "flops_per_item" not in b or "items_per_second" not in b:
            continue
        p = peak.get((key[2], "double" if key[3].startswith("double") else "float"))
        if p:
            b["peak_gflops"] = p * 1e-9
            b["roofline_fraction"] = b["items_per_second"] * b["flops_per_item"] / p
    # The same-FLOPs check on the chunk rows of the batched ISAs.
    groups = collections.defaultdict(list)
    for name, b in rows.items():
        key = kernel_key(name)
        if key and key[0] == "" and key[2] != "scalar" and "flops_per_item" in b:
            groups[(key[2], key[3])].append((name, b))
    flags = []
    for members in groups.values():
        for name, b in members:
            f = b["flops_per_item"]
            peers = [(n, o) for n, o in members if n != name and
                     f / SAME_FLOPS_FACTOR <= o["flops_per_item"] <= f * SAME_FLOPS_FACTOR]
            b["same_flops_peers"] = len(peers)
            if not peers:
                b["same_flops_slow"] = 0
                continue
            peer_name, peer = max(peers, key=lambda p: p[1]["items_per_second"])
            ratio = b["items_per_second"] / peer["items_per_second"]
            b["same_flops_peer"] = peer_name
            b["same_flops_rate_ratio"] = ratio
            b["same_flops_slow"] = 1 if ratio < SLOW_RATIO else 0
            if ratio < SLOW_RATIO:
                b["label"] = (b.get("label", "") + " " if b.get("label") else "") + \
                    f"SLOW: {ratio:.2f}x of same-FLOPs {peer_name}"
                flags.append({"row": name, "peer": peer_name, "rate_ratio": ratio,
                              "flops_per_item": f, "peer_flops_per_item": peer["flops_per_item"]})
    d["same_flops_check"] = (
        f"batched chunk rows (not scalar) of one ISA and flavour whose counted FLOPs per item are "
        f"within a factor {SAME_FLOPS_FACTOR} of each other are peers; a row below {SLOW_RATIO} of "
        f"its fastest peer's items/s is flagged (same_flops_slow = 1)")
    d["same_flops_flags"] = flags
    # Targets.
    counts = counts or {}
    targets = []
    for tid, what, num, den, threshold in TARGETS:
        t = {"id": tid, "what": what, "row": num, "threshold": threshold}
        if den:
            t["over_row"] = den
        a, b = rows.get(num), rows.get(den) if den else None
        if a is None or (den and b is None):
            t["measured"] = None
            t["met"] = None  # the row is not in this run (e.g. the CPU lacks the ISA)
        else:
            value = a["items_per_second"] / b["items_per_second"] if den else a["items_per_second"]
            t["measured"] = value
            t["met"] = value >= threshold
        for r in [num] + ([den] if den else []) + COMPARE.get(num, []):
            if r in counts:
                t.setdefault("uarch", {})[r] = counts[r]
        targets.append(t)
    d["targets"] = targets
    return d


def machine(d):
    ctx = d.get("context", {})
    model = ctx.get("cpu_model") or "unknown CPU"
    return f"{model}, {ctx.get('num_cpus', '?')} CPUs"


def fmt_rate(v):
    return f"{v / 1e6:.1f}" if v is not None else "—"


def tables(d):
    rows = rows_by_name(d)
    ctx = d.get("context", {})
    mach = machine(d)
    lines = [
        f"Machine: {mach} ({ctx.get('mhz_per_cpu', '?')} MHz per Google Benchmark), run "
        f"{ctx.get('date', '?')}; median of the repetitions where repeated; single thread, CPU "
        f"time.", ""]
    # Peaks.
    peak = peaks(rows)
    if peak:
        lines += ["**Peak** (`uarch/peak/<isa>/<precision>`, measured in the same run): FLOP/s of "
                  "one core.", "",
                  "| ISA | machine | float GFLOP/s | double GFLOP/s |", "|---|---|---|---|"]
        for isa in ISAS:
            if (isa, "float") in peak:
                lines.append(f"| {isa} | {mach} | {peak[(isa, 'float')] / 1e9:.1f} | "
                             f"{peak.get((isa, 'double'), 0) / 1e9:.1f} |")
        lines.append("")
    # Kernels, chunk working set.
    kern = collections.OrderedDict()
    for name, b in rows.items():
        key = kernel_key(name)
        if key and key[0] == "":
            kern.setdefault(key[1], {})[(key[2], key[3])] = b
    if kern:
        lines += ["**Kernels** (4096 rows per call): Mitem/s per flavour, speed-up of float exact "
                  "over scalar float exact, counted FLOPs per item, roofline = fraction of the "
                  "ISA's measured peak (float exact), and the same-FLOPs check (SLOW: below half "
                  "the rate of a kernel of the same ISA and flavour within a factor 1.25 of its "
                  "FLOPs; "
                  "the fastest such peer named).", "",
                  "| kernel | ISA | machine | float exact Mitem/s | float fast Mitem/s | "
                  "double Mitem/s | × scalar | FLOP/item | roofline | same FLOPs |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for kernel, r in kern.items():
            base = r.get(("scalar", "float_exact"))
            for isa in ISAS:
                if not any((isa, f) in r for f in FLAVOURS):
                    continue
                cells = [fmt_rate(r[(isa, f)]["items_per_second"]) if (isa, f) in r else "—"
                         for f in FLAVOURS]
                fe = r.get((isa, "float_exact"))
                speed = (f"{fe['items_per_second'] / base['items_per_second']:.1f}"
                         if fe and base else "—")
                flops = f"{fe['flops_per_item']:.0f}" if fe and "flops_per_item" in fe else "—"
                roof = (f"{100 * fe['roofline_fraction']:.1f} %"
                        if fe and "roofline_fraction" in fe else "—")
                flag = "—"
                if fe and "same_flops_slow" in fe:
                    flag = (f"SLOW {fe['same_flops_rate_ratio']:.2f}× of "
                            f"{fe['same_flops_peer'].rsplit('/', 2)[0]}"
                            if fe["same_flops_slow"] else "ok")
                lines.append(f"| {kernel} | {isa} | {mach} | " + " | ".join(cells) +
                             f" | {speed} | {flops} | {roof} | {flag} |")
        lines.append("")
    # Working sets: the l1/ and stream/ rows beside the chunk rows of the same variant.
    sets = collections.OrderedDict()
    for name, b in rows.items():
        key = kernel_key(name)
        if key and key[0] in ("l1/", "stream/"):
            sets.setdefault((key[1], key[2], key[3]), {})[key[0]] = b
    if sets:
        lines += ["**Working sets**: Mitem/s of 4096-row calls on the same rows (chunk, L2), of "
                  "calls whose columns fit 16 KiB (L1) and of 4096-row calls streaming through "
                  "2^20 rows (memory).", "",
                  "| kernel | ISA | flavour | machine | chunk Mitem/s | L1 Mitem/s | "
                  "stream Mitem/s |", "|---|---|---|---|---|---|---|"]
        for (kernel, isa, flavour), r in sets.items():
            chunk = kern.get(kernel, {}).get((isa, flavour))
            lines.append(f"| {kernel} | {isa} | {flavour} | {mach} | "
                         f"{fmt_rate(chunk['items_per_second']) if chunk else '—'} | "
                         f"{fmt_rate(r['l1/']['items_per_second']) if 'l1/' in r else '—'} | "
                         f"{fmt_rate(r['stream/']['items_per_second']) if 'stream/' in r else '—'} |")
        lines.append("")
    chi = [(n, b) for n, b in rows.items() if n.startswith("chi_square")]
    if chi:
        lines += [f"- `{n}` on {mach}: {b['real_time']:.0f} ms wall for 10^7 samples (sampling + "
                  "binning + expected counts + statistic)" for n, b in chi]
        lines.append("")
    # Models.
    models = collections.OrderedDict()
    for name, b in rows.items():
        if name.startswith("model/"):
            parts = name.split("/")
            model = "/".join(parts[1:-2])
            models.setdefault(model, {})[(parts[-2], parts[-1])] = b
    if models:
        lines += ["**Models** (registry-level batch API, 4096 queries, default parameters): "
                  "Mitem/s; the entry row is the scalar double thunk loop (eval, pdf, sample); "
                  "the batch API's pdf is eval_batch's pdf column, so the batched eval rows carry "
                  "it; × entry: the batch over the entry's loop of the same op; double-only "
                  "models compute in double whatever the column type.", "",
                  "| model | op | ISA | machine | float Mitem/s | double Mitem/s | × entry | "
                  "batched | double-only |", "|---|---|---|---|---|---|---|---|---|"]
        for model, r in models.items():
            any_row = next(iter(r.values()))
            batched = "yes" if any_row.get("batched") else "no"
            donly = "yes" if any_row.get("double_only") else "no"
            for op in ["eval", "pdf", "sample"]:
                e = r.get(("entry", op))
                if e:
                    lines.append(f"| {model} | {op} | entry (scalar double thunks) | {mach} | — | "
                                 f"{fmt_rate(e['items_per_second'])} | 1.0 | {batched} | "
                                 f"{donly} |")
                for isa in ISAS:
                    fl, db = r.get((isa, f"{op}_float")), r.get((isa, f"{op}_double"))
                    if not (fl or db):
                        continue
                    best = db if donly == "yes" or not fl else fl
                    speed = (f"{best['items_per_second'] / e['items_per_second']:.1f}"
                             if e else "—")
                    lines.append(
                        f"| {model} | {op} | {isa} | {mach} | "
                        f"{fmt_rate(fl['items_per_second']) if fl else '—'} | "
                        f"{fmt_rate(db['items_per_second']) if db else '—'} | {speed} | "
                        f"{batched} | {donly} |")
        lines.append("")
    # Targets.
    if d.get("targets"):
        lines += ["**Targets** (one core; `targets` in the JSON): measured against threshold; "
                  "instructions and loads per item of the target's rows (and of the rows it is read "
                  "against) where counted (experiments/bench/uarch_counts.py: valgrind callgrind; "
                  "this VM has no PMU counters; valgrind emulates no AVX-512).", "",
                  "| target | row | machine | measured | target | met | instructions/item | "
                  "loads/item |", "|---|---|---|---|---|---|---|---|"]
        for t in d["targets"]:
            ratio = "over_row" in t
            m = t["measured"]
            shown = "—" if m is None else (f"{m:.2f}×" if ratio else f"{m / 1e6:.0f} Mitem/s")
            thr = f"≥ {t['threshold']:g}×" if ratio else f"≥ {t['threshold'] / 1e6:.0f} Mitem/s"
            met = {True: "yes", False: "**no**", None: "not run"}[t["met"]]
            ua = t.get("uarch", {})

            def per_item(key):
                return "; ".join(f"{r}: {ua[r][key]:.0f}" if ua[r].get("counted")
                                 else f"{r}: not counted" for r in ua) or "—"
            ins, lds = per_item("instructions_per_item"), per_item("loads_per_item")
            lines.append(f"| {t['what']} | `{t['row']}`" +
                         (f" / `{t['over_row']}`" if ratio else "") +
                         f" | {mach} | {shown} | {thr} | {met} | {ins} | {lds} |")
        lines.append("")
    # uarch ceilings.
    ua = [(n, b) for n, b in rows.items() if n.startswith("uarch/") and "/peak/" not in n]
    if ua:
        lines += [f"Division and multiplication throughput on {mach} (bench_uarch.cpp, 8 "
                  "independent chains): " +
                  "; ".join(f"{n[6:]}: {1e9 / b['items_per_second']:.2f} ns/instruction, "
                            f"{1e9 / b['lane_ops_per_second']:.3f} ns/lane" for n, b in ua), ""]
    return "\n".join(lines).rstrip("\n") + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("annotate")
    a.add_argument("json")
    a.add_argument("--uarch-counts")
    t = sub.add_parser("tables")
    t.add_argument("json")
    t.add_argument("--update")
    args = ap.parse_args()
    d = json.load(open(args.json))
    if args.cmd == "annotate":
        counts = json.load(open(args.uarch_counts)) if args.uarch_counts else None
        annotate(d, counts)
        with open(args.json, "w") as f:
            json.dump(d, f, indent=1)
        return 0
    text = tables(d)
    if not args.update:
        sys.stdout.write(text)
        return 0
    doc = open(args.update).read()
    if doc.count(BEGIN) != 1 or doc.count(END) != 1 or doc.index(BEGIN) > doc.index(END):
        print(f"simd_tables.py: error: {args.update} needs one {BEGIN} ... {END} block",
              file=sys.stderr)
        return 2
    head, rest = doc.split(BEGIN)
    _, tail = rest.split(END)
    with open(args.update, "w") as f:
        f.write(head + BEGIN + "\n" + text + END + tail)
    return 0


if __name__ == "__main__":
    sys.exit(main())
