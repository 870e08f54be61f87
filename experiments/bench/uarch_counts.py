#!/usr/bin/python3
"""Instructions and loads per item of benchmark rows, counted by valgrind's callgrind.

  uarch_counts.py --build build/release --out out/bench/uarch_counts.json [ROW ...]

Rows default to the rows of scripts/simd_tables.py's targets (and, for each, the kernel its
same-FLOPs check compares it with). Why callgrind: this machine is a KVM guest without a virtual
PMU (`perf stat -e instructions:u` reports <not supported>), so hardware counters cannot be read;
callgrind executes the binary on a synthetic CPU and counts every guest instruction (Ir) and data
read (Dr: loads and load operands) exactly, independent of timing noise. Each row's benchmark runs
once with one iteration (--benchmark_min_time tiny), collecting only inside
glintlab::simd::eval_batch / sample_batch (callgrind --toggle-collect), so the counts are of the
batch call: 4096 rows, plus the model benchmarks' one untimed warm-up row. Valgrind emulates no
AVX-512 (its CPUID hides it, so the binaries do not register avx512 rows): those rows are recorded
as not counted, with the reason. Standard library only.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import simd_tables  # noqa: E402  (TARGETS and COMPARE: the rows to count)

ROWS_PER_CALL = 4096
NOT_COUNTABLE = ("valgrind emulates no AVX-512 and this VM exposes no PMU counters; the row is "
                 "not counted")


def default_rows():
    rows = []
    for _, _, num, den, _ in simd_tables.TARGETS:
        for r in [num, den] + simd_tables.COMPARE.get(num, []):
            if r and r not in rows:
                rows.append(r)
    return rows


def count(build, row):
    model = row.startswith("model/")
    binary = os.path.join(build, "experiments", "bench",
                          "glintlab_bench_models" if model else "glintlab_bench_kernels")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        js = os.path.join(tmp, "bench.json")
        cmd = ["valgrind", "--tool=callgrind", "--cache-sim=yes", f"--callgrind-out-file={out}",
               "--toggle-collect=glintlab::simd::eval_batch*",
               "--toggle-collect=glintlab::simd::sample_batch*",
               binary, f"--benchmark_filter=^{re.escape(row)}$", "--benchmark_min_time=1e-9",
               "--benchmark_repetitions=1", f"--benchmark_out={js}",
               "--benchmark_out_format=json"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            last = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else ""
            return {"counted": False, "why": f"valgrind exit {r.returncode}: {last}"}
        # Google Benchmark leaves the file empty when no benchmark matched the filter.
        text = open(js).read() if os.path.exists(js) else ""
        ran = json.loads(text)["benchmarks"] if text.strip() else []
        if not ran:
            return {"counted": False, "why": NOT_COUNTABLE if "avx512" in row else
                    "no benchmark of that name ran under valgrind"}
        iterations = ran[0]["iterations"]
        events, totals = None, None
        for line in open(out):
            if line.startswith("events:"):
                events = line.split()[1:]
            elif line.startswith(("summary:", "totals:")):
                totals = [int(v) for v in line.split()[1:]]
        if not events or not totals:
            return {"counted": False, "why": "no totals in callgrind's output"}
        ev = dict(zip(events, totals))
        items = iterations * ROWS_PER_CALL + (1 if model else 0)
        return {"counted": True, "tool": "valgrind callgrind (Ir, Dr)", "items": items,
                "instructions_per_item": ev["Ir"] / items, "loads_per_item": ev["Dr"] / items,
                "stores_per_item": ev.get("Dw", 0) / items}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    ap.add_argument("--out", required=True)
    ap.add_argument("rows", nargs="*")
    args = ap.parse_args()
    rows = args.rows or default_rows()
    result = {}
    for row in rows:
        result[row] = count(args.build, row)
        c = result[row]
        print(f"{row}: " + (f"{c['instructions_per_item']:.1f} instructions, "
                            f"{c['loads_per_item']:.1f} loads per item" if c["counted"]
                            else "not counted: " + c["why"]), flush=True)
    with open(args.out, "w") as f:
        json.dump(result, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
