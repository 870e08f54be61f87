#!/usr/bin/env python3
"""Speed of glintlab.eval from Python against the C++ batch underneath, as JSON.

On N rows of C-ordered (N, 3) float64 directions (numpy's usual layout), the median of several
repeats of:

  cpp_eval_batch          simd::eval_batch alone on one thread, the same rows laid out beforehand as
                          contiguous columns (glintlab._glintlab.eval_batch_seconds): the reference
  python_eval_c_1thread   glintlab.eval("smooth_ggx", wi, wo, threads=1)
  python_eval_c           the same on all cores
  python_eval_f_1thread   Fortran-ordered (N, 3) input, one thread (read in place)
  python_eval_per_row_*   params={"alpha_x": (N,) array}, one thread: 16 distinct values in
                          random order, and every row its own value
  numpy_model_direct      a numpy Lambertian's eval and pdf called on all N rows at once, on the
                          columns of the (N, 3) arrays (strided views)
  numpy_model_direct_contiguous  the same on contiguous copies of the columns, made beforehand
  numpy_model_eval        the same model registered (glintlab.register_model) and run by
                          glintlab.eval in chunks, one thread

and, in "numpy_model_cases" (beside "cases", whose names the smoke test fixes):

  numpy_model_direct_copying     the direct call on contiguous copies of the columns made in the
                                 timed call (np.ascontiguousarray of each column view)
  numpy_model_eval_f_1thread     glintlab.eval of the registered model on Fortran-ordered input
                                 (its columns passed to the functions where they lie), one thread
  numpy_model_eval_all_cores     glintlab.eval of it on the C-ordered input, all cores
  numpy_model_identity_eval_1thread  glintlab.eval of a numpy model whose eval and pdf return
                                 their wo_z column as it is (no numpy work): the route's own cost,
                                 C-ordered input, one thread

and, in "model_rules_cases", a model with query rules of its own (podee: a disk light of radius
above 0 and its centre above the surface, checked by the chunk check's pass over the columns):

  podee_eval_1thread             glintlab.eval("podee", ...) on the same rows, Fortran-ordered,
                                 with a per-row footprint, its four corner reflection vectors
                                 near wo and a per-row light, one thread
  podee_entry_copy_eval_1thread  the same with podee's registry entry copied without its static
                                 model (_glintlab._register_entry_copy: its rules known only
                                 through the entry, as a plug-in's, and its batches the loop over
                                 its thunks); absent with a module without that function

and the ratios of interest (Python eval over eval_batch; the numpy model's chunked calls over
its direct calls; "numpy_model_ratios" those of the numpy_model_cases), on wall seconds; every
case also has its CPU seconds (the C++ reference its thread's, measured by the module; None from
a module that does not), "cpu_ratios" the one-thread eval cases over the reference and
"numpy_model_cpu_ratios" the numpy model's one-thread ratios on them (on a loaded machine a
longer call waits longer for a core, so wall-time ratios of a short and a long call grow with
the load). Each case's timer starts after the previous case's result is freed. --malloc fixed fixes glibc malloc's thresholds first (fix_malloc), so that the 8 MB
arrays of every case reuse freed memory instead of page-faulting depending on what ran before. The cases take turns in each repeat, so that a shared machine's changing load
reaches them alike. Speed is measured here, never asserted: tests/python runs this in its smoke
mode (--rows 1000 --repeats 1) and checks the JSON's shape only. docs/python.md "Speed of eval
from Python" holds the numbers.

Run with Debian's interpreter and the build tree's module:
  PYTHONPATH=build/release/python /usr/bin/python3 experiments/bench/python_eval.py \
      --out out/bench/python_eval.json
"""

import argparse
import json
import os
import platform
import statistics
import sys
import time

import numpy as np

import glintlab
from glintlab import _glintlab


def unit_rows(rng, n):
    """n C-ordered (n, 3) float64 unit vectors of the upper hemisphere."""
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 1e-3
    return np.ascontiguousarray(v / np.linalg.norm(v, axis=1)[:, None])


def round_robin(cases, repeats):
    """Wall and CPU seconds of each of `repeats` calls of every case, the cases taking turns in
    each round (so that a change of load on a shared machine reaches every case alike); one
    untimed call of each first (first-touch, caches). `cases`: name -> callable, or -> callable
    returning its own wall and CPU seconds (a list [wall, cpu]; cpu None where not measured). CPU seconds
    (time.process_time: this process's user and system time, page faults included) are what a
    loaded machine changes least for a one-thread case: its wall time also counts the waits for a
    core, which grow with the length of the call."""
    for f in cases.values():
        f()
    seconds = {name: [] for name in cases}
    cpu = {name: [] for name in cases}
    for _ in range(repeats):
        for name, f in cases.items():
            # The previous case's result freed before the timer starts: freeing it (glibc unmaps a
            # large array) is not this case's cost.
            r = None
            c0, t0 = time.process_time(), time.perf_counter()
            r = f()
            elapsed, used = time.perf_counter() - t0, time.process_time() - c0
            seconds[name].append(r[0] if isinstance(r, list) else elapsed)
            cpu[name].append(r[1] if isinstance(r, list) else used)
    return seconds, cpu


def fix_malloc():
    """glibc's malloc with fixed thresholds: blocks up to 256 MiB from the heap and freed memory
    kept, so that an array of 10^6 rows reuses freed pages rather than mapping fresh ones. By
    default the thresholds move with what was freed before (a freed mapped block raises them),
    so whether a case's 8 MB arrays page-fault depends on the cases before it."""
    import ctypes
    libc = ctypes.CDLL("libc.so.6")
    m_trim_threshold, m_mmap_threshold = -1, -3
    ok = libc.mallopt(m_mmap_threshold, 256 << 20) == 1 and \
        libc.mallopt(m_trim_threshold, 1 << 30) == 1
    return {"mmap_threshold": 256 << 20, "trim_threshold": 1 << 30} if ok else None


def lambert_eval(q, p):
    return p["albedo"] * np.maximum(q["wo_z"], 0) / np.pi


def lambert_pdf(q, p):
    return np.maximum(q["wo_z"], 0) / np.pi


def lambert_sample(q, u, p):
    r = np.sqrt(u[:, 0])
    phi = 2 * np.pi * u[:, 1]
    z = np.sqrt(np.maximum(0.0, 1 - u[:, 0]))
    wo = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
    return {"wo": wo, "pdf": z / np.pi, "weight": np.full(len(z), p["albedo"])}


def podee_columns(rng, wo):
    """podee's footprint (uv, its Jacobian, the corner reflection vectors: wo perturbed by 1e-3,
    normalised) and light (a cone of cos 0.999), an (N,) float64 array each."""
    n = len(wo)
    footprint = {"u": rng.uniform(0, 1, n), "v": rng.uniform(0, 1, n),
                 "dudx": np.full(n, 2e-3), "dvdx": np.zeros(n),
                 "dudy": np.zeros(n), "dvdy": np.full(n, 2e-3)}
    for k in range(4):
        r = wo + rng.normal(scale=1e-3, size=(n, 3))
        r /= np.linalg.norm(r, axis=1, keepdims=True)
        for a, axis in enumerate("xyz"):
            footprint[f"r{k}_{axis}"] = np.ascontiguousarray(r[:, a])
    light = {"light_cos_half_angle": np.full(n, 0.999), "light_intensity": np.ones(n)}
    return footprint, light


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rows", type=int, default=1_000_000, help="N (default 10^6)")
    ap.add_argument("--repeats", type=int, default=7, help="timed repeats per case (default 7)")
    ap.add_argument("--isa", default=None, help="scalar, sse4.2, avx2, avx512 (default: widest)")
    ap.add_argument("--out", required=True, help="the JSON file to write")
    ap.add_argument("--malloc", choices=("default", "fixed"), default="default",
                    help="glibc malloc's thresholds: as they are, or fixed so that freed memory "
                         "is reused (fix_malloc; default: default)")
    a = ap.parse_args()
    for option, value in (("--rows", a.rows), ("--repeats", a.repeats)):
        if value < 1:
            print(f"python_eval.py: error: {option}: {value} is out of range (valid: >= 1)",
                  file=sys.stderr)
            return 2

    malloc = {"mode": a.malloc}
    if a.malloc == "fixed":
        malloc["thresholds"] = fix_malloc()
        if malloc["thresholds"] is None:
            print("python_eval.py: error: --malloc fixed: mallopt failed (valid: glibc)",
                  file=sys.stderr)
            return 2
    rng = np.random.default_rng(20260405)
    n = a.rows
    wi, wo = unit_rows(rng, n), unit_rows(rng, n)
    wi_f, wo_f = np.asfortranarray(wi), np.asfortranarray(wo)
    alpha16 = rng.choice(np.linspace(0.1, 0.9, 16), size=n)
    alpha_distinct = rng.uniform(0.1, 0.9, size=n)
    model = "smooth_ggx"

    isa = _glintlab.eval_batch_seconds(model, wi[:1], wo[:1], isa=a.isa, repeats=1)["isa"]

    def cpp_eval_batch():
        # Its wall seconds and, where the module measures it, its thread's CPU seconds.
        r = _glintlab.eval_batch_seconds(model, wi, wo, isa=a.isa, repeats=1)
        return [r["seconds"][0], r["cpu_seconds"][0] if "cpu_seconds" in r else None]

    def py_eval(wi_, wo_, threads=1, params=None):
        return lambda: glintlab.eval(model, wi_, wo_, params=params, isa=a.isa, threads=threads)

    name = "bench_numpy_lambert"
    if name not in [m["name"] for m in glintlab.models()]:
        glintlab.register_model(name, lambert_eval, lambert_pdf, lambert_sample,
                                params=[{"name": "albedo", "default": 0.8, "lo": 0, "hi": 1}],
                                description="Lambertian in numpy (benchmark)")
    identity = "bench_numpy_identity"
    if identity not in [m["name"] for m in glintlab.models()]:
        glintlab.register_model(identity, lambda q, p: q["wo_z"], lambda q, p: q["wo_z"],
                                lambert_sample, description="wo_z as value and pdf (benchmark)")
    entry_copy = "bench_podee_entry_copy"
    if hasattr(_glintlab, "_register_entry_copy") and \
            entry_copy not in [m["name"] for m in glintlab.models()]:
        _glintlab._register_entry_copy("podee", entry_copy)
    p = {"albedo": 0.8}

    def direct():
        q = {"wi_x": wi[:, 0], "wi_y": wi[:, 1], "wi_z": wi[:, 2],
             "wo_x": wo[:, 0], "wo_y": wo[:, 1], "wo_z": wo[:, 2]}
        return lambert_eval(q, p), lambert_pdf(q, p)

    columns = {"wi_x": wi[:, 0].copy(), "wi_y": wi[:, 1].copy(), "wi_z": wi[:, 2].copy(),
               "wo_x": wo[:, 0].copy(), "wo_y": wo[:, 1].copy(), "wo_z": wo[:, 2].copy()}

    def direct_contiguous():
        return lambert_eval(columns, p), lambert_pdf(columns, p)

    def direct_copying():
        q = {"wi_x": np.ascontiguousarray(wi[:, 0]), "wi_y": np.ascontiguousarray(wi[:, 1]),
             "wi_z": np.ascontiguousarray(wi[:, 2]), "wo_x": np.ascontiguousarray(wo[:, 0]),
             "wo_y": np.ascontiguousarray(wo[:, 1]), "wo_z": np.ascontiguousarray(wo[:, 2])}
        return lambert_eval(q, p), lambert_pdf(q, p)

    podee_footprint, podee_light = podee_columns(rng, wo)

    rules_cases = {
        "podee_eval_1thread": lambda: glintlab.eval("podee", wi_f, wo_f, footprint=podee_footprint,
                                                    light=podee_light, isa=a.isa, threads=1)}
    if entry_copy in [m["name"] for m in glintlab.models()]:
        rules_cases["podee_entry_copy_eval_1thread"] = lambda: glintlab.eval(
            entry_copy, wi_f, wo_f, footprint=podee_footprint, light=podee_light, isa=a.isa,
            threads=1)
    cases, cpu = round_robin({
        "cpp_eval_batch": cpp_eval_batch,
        "python_eval_c_1thread": py_eval(wi, wo),
        "python_eval_c": py_eval(wi, wo, threads=None),
        "python_eval_f_1thread": py_eval(wi_f, wo_f),
        "python_eval_per_row_16_values_1thread": py_eval(wi, wo, params={"alpha_x": alpha16}),
        "python_eval_per_row_distinct_1thread":
            py_eval(wi, wo, params={"alpha_x": alpha_distinct}),
        "numpy_model_direct": direct,
        "numpy_model_direct_contiguous": direct_contiguous,
        "numpy_model_eval_1thread": lambda: glintlab.eval(name, wi, wo, threads=1),
        "numpy_model_direct_copying": direct_copying,
        "numpy_model_eval_f_1thread": lambda: glintlab.eval(name, wi_f, wo_f, threads=1),
        "numpy_model_eval_all_cores": lambda: glintlab.eval(name, wi, wo, threads=None),
        "numpy_model_identity_eval_1thread": lambda: glintlab.eval(identity, wi, wo, threads=1),
        **rules_cases,
    }, a.repeats)
    numpy_model_cases = {k: cases.pop(k) for k in ("numpy_model_direct_copying",
                                                    "numpy_model_eval_f_1thread",
                                                    "numpy_model_eval_all_cores",
                                                    "numpy_model_identity_eval_1thread")}
    model_rules_cases = {k: cases.pop(k) for k in rules_cases}

    median = {k: statistics.median(v)
              for k, v in {**cases, **numpy_model_cases, **model_rules_cases}.items()}
    median_cpu = {k: None if None in v else statistics.median(v) for k, v in cpu.items()}
    ref = median["cpp_eval_batch"]

    def timed(group):
        return {k: {"seconds": v, "median_s": median[k], "us_per_1e6_rows": median[k] / n * 1e12,
                    "cpu_seconds": cpu[k], "median_cpu_s": median_cpu[k]}
                for k, v in group.items()}

    def cpu_ratio(a_case, b_case):
        return median_cpu[a_case] / median_cpu[b_case]

    result = {
        "benchmark": "python_eval",
        "machine": {"cpu": cpu_name(), "cores": os.cpu_count(), "python": platform.python_version(),
                    "numpy": np.__version__},
        "isa": isa,
        "malloc": malloc,
        "load_average": list(os.getloadavg()),
        # The result arrays' memory pool's counters at the end (None for a module without one).
        "result_pool": glintlab.result_pool() if hasattr(glintlab, "result_pool") else None,
        "precision": "double",
        "model": model,
        "rows": n,
        "repeats": a.repeats,
        "cases": timed(cases),
        "numpy_model_cases": timed(numpy_model_cases),
        "model_rules_cases": timed(model_rules_cases),
        "ratios": {
            "python_eval_c_1thread_over_cpp": median["python_eval_c_1thread"] / ref,
            "python_eval_c_over_cpp": median["python_eval_c"] / ref,
            "python_eval_f_1thread_over_cpp": median["python_eval_f_1thread"] / ref,
            "per_row_16_values_over_cpp": median["python_eval_per_row_16_values_1thread"] / ref,
            "per_row_distinct_over_cpp": median["python_eval_per_row_distinct_1thread"] / ref,
            "numpy_model_chunked_over_direct":
                median["numpy_model_eval_1thread"] / median["numpy_model_direct"],
            "numpy_model_chunked_over_direct_contiguous":
                median["numpy_model_eval_1thread"] / median["numpy_model_direct_contiguous"],
        },
        "numpy_model_ratios": {
            "chunked_over_direct_copying":
                median["numpy_model_eval_1thread"] / median["numpy_model_direct_copying"],
            "chunked_f_over_direct_contiguous":
                median["numpy_model_eval_f_1thread"] / median["numpy_model_direct_contiguous"],
            "chunked_all_cores_over_direct_contiguous":
                median["numpy_model_eval_all_cores"] / median["numpy_model_direct_contiguous"],
            "identity_over_direct_contiguous":
                median["numpy_model_identity_eval_1thread"] /
                median["numpy_model_direct_contiguous"],
        },
        # The one-thread ratios over the C++ reference on CPU seconds (None where the module does
        # not measure the reference's): on a loaded machine wall times wait for a core.
        "cpu_ratios": {k: (None if median_cpu["cpp_eval_batch"] is None else
                           median_cpu[case] / median_cpu["cpp_eval_batch"])
                       for k, case in (("python_eval_c_1thread_over_cpp", "python_eval_c_1thread"),
                                       ("python_eval_f_1thread_over_cpp", "python_eval_f_1thread"),
                                       ("per_row_16_values_over_cpp",
                                        "python_eval_per_row_16_values_1thread"),
                                       ("per_row_distinct_over_cpp",
                                        "python_eval_per_row_distinct_1thread"))},
        # The same ratios of one-thread cases on CPU seconds.
        "numpy_model_cpu_ratios": {
            "chunked_over_direct": cpu_ratio("numpy_model_eval_1thread", "numpy_model_direct"),
            "chunked_over_direct_contiguous":
                cpu_ratio("numpy_model_eval_1thread", "numpy_model_direct_contiguous"),
            "chunked_over_direct_copying":
                cpu_ratio("numpy_model_eval_1thread", "numpy_model_direct_copying"),
            "chunked_f_over_direct_contiguous":
                cpu_ratio("numpy_model_eval_f_1thread", "numpy_model_direct_contiguous"),
            "identity_over_direct_contiguous":
                cpu_ratio("numpy_model_identity_eval_1thread", "numpy_model_direct_contiguous"),
        },
    }
    with open(a.out, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    for k, v in {**result["ratios"], **result["numpy_model_ratios"]}.items():
        print(f"{k}: {v:.2f}")
    for k, v in {**result["cpu_ratios"], **result["numpy_model_cpu_ratios"]}.items():
        if v is not None:
            print(f"{k} (CPU): {v:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
