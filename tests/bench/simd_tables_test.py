#!/usr/bin/python3
"""scripts/simd_tables.py on a checked-in sample of scripts/bench.sh's JSON (simd_tables_sample.json:
median rows of one run on an AMD EPYC): the roofline against the run's measured peak, the
same-FLOPs check flagging a slow row and not a fast one (and flagging a row slowed on purpose), the
targets, the tables' shape (every row names its ISA and machine) and the --update markers."""
import copy
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "..", "scripts", "simd_tables.py")
SAMPLE = os.path.join(HERE, "simd_tables_sample.json")


def run(*args, expect=0):
    r = subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)
    if r.returncode != expect:
        sys.exit(f"simd_tables.py {' '.join(args)}: exit {r.returncode}, wanted {expect}\n"
                 f"{r.stdout}{r.stderr}")
    return r.stdout


def annotated(d, tmp):
    path = os.path.join(tmp, "bench.json")
    json.dump(d, open(path, "w"))
    run("annotate", path)
    return json.load(open(path)), path


def by_name(d):
    return {b["run_name"]: b for b in d["benchmarks"]}


def main():
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    raw = json.load(open(SAMPLE))
    with tempfile.TemporaryDirectory() as tmp:
        d, path = annotated(copy.deepcopy(raw), tmp)
        rows = by_name(d)
        peak = rows["uarch/peak/avx2/float"]["flops_per_second"]
        vndf = rows["ggx.vndf/avx2/float_exact"]
        want = vndf["items_per_second"] * vndf["flops_per_item"] / peak
        check(abs(vndf["roofline_fraction"] - want) <= 1e-12 * want,
              "roofline_fraction = FLOPs/item x items/s / the run's uarch/peak row")
        check(abs(rows["ggx.vndf/avx2/double_exact"]["peak_gflops"] * 1e9 -
                  rows["uarch/peak/avx2/double"]["flops_per_second"]) < 1.0,
              "a double row is read against the double peak")
        # The measured case: the VNDF pdf at a fifth of ggx.vndf's rate, same FLOPs within 1.25x.
        pdf = rows["pdf.heitz_vndf/ggx/avx2/float_exact"]
        check(pdf["same_flops_slow"] == 1 and pdf["same_flops_peer"] == "ggx.vndf/avx2/float_exact",
              "pdf.heitz_vndf/ggx avx2 flagged against ggx.vndf")
        check("SLOW" in pdf.get("label", ""), "a flagged row's label says SLOW")
        check(rows["ggx.vndf/avx2/float_exact"]["same_flops_slow"] == 0, "ggx.vndf not flagged")
        check("same_flops_slow" not in rows["ggx.vndf/scalar/float_exact"],
              "scalar rows are not in the check")
        check(any(f["row"] == "pdf.heitz_vndf/ggx/avx2/float_exact" for f in d["same_flops_flags"]),
              "flagged rows listed in same_flops_flags")
        # Deliberately broken input: ggx.vndf slowed to 0.4x of pdf.walter/ggx (27 vs 32 FLOPs).
        broken = copy.deepcopy(raw)
        b = by_name(broken)
        b["ggx.vndf/avx512/float_exact"]["items_per_second"] = \
            0.4 * b["pdf.walter/ggx/avx512/float_exact"]["items_per_second"]
        b["pdf.heitz_vndf/ggx/avx512/float_exact"]["items_per_second"] = \
            0.6 * b["pdf.walter/ggx/avx512/float_exact"]["items_per_second"]
        d2, _ = annotated(broken, tmp)
        r2 = by_name(d2)
        check(r2["ggx.vndf/avx512/float_exact"]["same_flops_slow"] == 1,
              "a row slowed to 0.4x of a same-FLOPs peer is flagged")
        check(r2["pdf.heitz_vndf/ggx/avx512/float_exact"]["same_flops_slow"] == 0,
              "a row at 0.6x of its fastest peer is not flagged")
        # Targets: every item-4 target, measured where its rows ran, met decided by the threshold.
        t = {x["id"]: x for x in d["targets"]}
        check(len(t) == 7, "seven targets")
        v = t["vndf_pdf_avx2"]
        check(v["measured"] == pdf["items_per_second"] and v["met"] == (v["measured"] >= 800e6),
              "the VNDF pdf target reads its row")
        db = t["deliot_belcour_avx2"]
        want = (rows["model/deliot_belcour/avx2/eval_float"]["items_per_second"] /
                rows["model/deliot_belcour/scalar/eval_float"]["items_per_second"])
        check(abs(db["measured"] - want) < 1e-12 and db["met"] == (want >= 4.0),
              "a ratio target is the ISA row over the scalar row")
        check(t["kneiphof_klein_avx2"]["met"] is None, "a target whose rows did not run: met null")
        # Tables: header shapes, and every kernel/model row names its ISA and the machine.
        text = run("tables", path)
        machine = d["context"]["cpu_model"]
        kernel_rows = [l for l in text.splitlines() if l.startswith("| ggx.vndf |")
                       or l.startswith("| pdf.")]
        check(len(kernel_rows) == 9, f"9 kernel rows (3 kernels x 3 ISAs), got {len(kernel_rows)}")
        for line in kernel_rows:
            cells = [c.strip() for c in line.strip("|").split("|")]
            check(len(cells) == 10 and cells[1] in ("scalar", "avx2", "avx512") and
                  machine in cells[2], f"kernel row shape: {line}")
        check("| pdf.heitz_vndf/ggx | avx2 |" in text and "SLOW" in text, "flag in the table")
        model_rows = [l for l in text.splitlines() if l.startswith("| deliot_belcour |")]
        check(len(model_rows) == 5, f"5 deliot_belcour rows, got {len(model_rows)}")
        for line in model_rows:
            cells = [c.strip() for c in line.strip("|").split("|")]
            check(len(cells) == 9 and machine in cells[3], f"model row shape: {line}")
        check("| avx512 | " + machine in text, "peak table names ISA and machine")
        # --update replaces only the marked block, and refuses a document without it.
        doc = os.path.join(tmp, "doc.md")
        open(doc, "w").write("before\n<!-- simd_tables.py begin -->\nOLD BLOCK\n"
                             "<!-- simd_tables.py end -->\nafter\n")
        run("tables", path, "--update", doc)
        new = open(doc).read()
        check(new.startswith("before\n<!-- simd_tables.py begin -->\n") and
              new.endswith("<!-- simd_tables.py end -->\nafter\n") and "OLD BLOCK" not in new and
              text in new, "--update replaces the marked block")
        open(doc, "w").write("no markers\n")
        run("tables", path, "--update", doc, expect=2)
        check(open(doc).read() == "no markers\n", "a document without markers is left alone")
    for f in failures:
        print("FAIL:", f)
    print(f"simd_tables_test: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
