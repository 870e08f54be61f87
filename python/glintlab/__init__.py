"""glintlab from Python: the registered microfacet and glint models on numpy arrays.

Every call runs glintlab's C++ batch path (structure-of-arrays SIMD batches, chunks of 4096 rows
on worker threads, the GIL released), with the same input checks and the same results as the
``glintlab`` command line: ``eval`` matches ``glintlab eval --model`` and ``sample(n=, seed=)``
matches ``glintlab sample --model`` bit for bit in double precision.

Functions: models, eval, sample, load_plugin, register_model (a model prototyped in numpy),
verify (the claims and the models' conformance checks), and figure, sweep, compare and adequacy
(the CLI's subcommands of those names, run in this process: they write the CLI's files and return
their paths with the data parsed). Bad input raises ValueError with the CLI's one-line message
naming the parameter (or row and column) and its valid range.

Directions are unit vectors in the local shading frame (z the normal): ``wi`` toward the viewer,
``wo`` toward the light. ``value`` is the cosine-weighted BRDF f(wi, wo) max(wo_z, 0), ``pdf``
the density of wo (per steradian) under the model's own sampler.
"""

import csv as _csv
import json as _json
import os as _os

import numpy as _np

from . import _glintlab

# An installed package carries the report scripts that figure, sweep and compare run to draw their
# charts and pages (python/CMakeLists.txt): they are used unless GLINTLAB_REPORTS_DIR names
# others. The build tree's package has none, and the source tree's reports/ is used.
_REPORTS = _os.path.join(_os.path.dirname(_os.path.abspath(__file__)), "reports")
if not _os.environ.get("GLINTLAB_REPORTS_DIR") and _os.path.isfile(
        _os.path.join(_REPORTS, "figure_charts.py")):
    _os.environ["GLINTLAB_REPORTS_DIR"] = _REPORTS

__all__ = ["models", "eval", "sample", "load_plugin", "register_model", "verify", "figure",
           "sweep", "compare", "adequacy", "read_csv", "result_pool"]

_PRECISIONS = "precision: 'double' (float64 in, float64 out) or 'float' (float32)"


def models():
    """The registered models (built-in, then plug-ins), as a list of dicts.

    Each dict has: ``name``, ``description``, ``source`` (the paper and equations),
    ``needs`` (a list of the query parts it reads besides the directions: "footprint",
    "point light", "area light", "pixel corners"), ``params`` (a list of dicts: ``name``,
    ``default``, ``range`` in words, ``description``, and either ``lo``, ``hi``, ``lo_open``,
    ``hi_open``, ``integral`` for a number or ``choices`` for a named choice), ``intermediates``
    (the names eval returns besides value and pdf), ``smooth_limit`` (the model a footprint model
    tends to, or None) and ``batched`` (whether it runs on SIMD batches; otherwise row by row in
    double).
    """
    return _glintlab.models()


def eval(model, wi, wo, params=None, footprint=None, light=None, precision="double", isa=None,
         math="exact", threads=None):
    """Evaluates `model` on N queries; returns a dict of (N,) arrays.

    model      a name of models().
    wi, wo     (N, 3) arrays of unit directions, or (3,) for one direction on every row.
    params     dict parameter name -> value: a number (or a choice's name) for every row, or an
               (N,) array varying per row (a choice by its index). Unset: the model's defaults.
    footprint  dict of the pixel footprint columns u, v, dudx, dvdx, dudy, dvdy (and
               r0_x .. r3_z, the corner reflection vectors, for models needing pixel corners):
               scalars or (N,) arrays. Required for models that need a footprint.
    light      dict of light_cos_half_angle (in [-1, 1], 1 = a delta light) and
               light_intensity (>= 0). Required for models that need a light.
    precision  'double' or 'float': the float type the model is evaluated in; the results
               have that dtype (float64 or float32).
    isa        'scalar', 'sse4.2', 'avx2' or 'avx512'; None: GLINTLAB_ISA if set, else the
               widest this CPU has.
    math       'exact', or 'fast' (fast exp/erf/rsqrt; needs precision='float').
    threads    worker threads, an integer in [0, 1024]; None or 0: all cores. The results
               do not depend on it.

    Returns {'value': ..., 'pdf': ..., <each intermediate of the model>: ...}.

    Arrays are read where they lie when they already are contiguous columns of the precision's
    dtype (an (N,) float64 array, or a Fortran-ordered (N, 3) one, for precision='double');
    other layouts and dtypes are converted chunk by chunk, never all at once. Every row is checked
    before it is evaluated, as ``glintlab eval --model`` checks its --in rows: finite values,
    unit wi and wo, the light's range and the model's own rules; the first bad row raises
    ValueError.
    """
    return _glintlab.eval(model, wi, wo, params=params, footprint=footprint, light=light,
                          precision=precision, isa=isa, math=math, threads=threads)


def sample(model, wi, u=None, params=None, footprint=None, light=None, n=None, seed=None,
           precision="double", isa=None, math="exact", threads=None):
    """Samples `model`'s own sampler: one wo per row; returns a dict of arrays.

    model, params, footprint, light, precision, isa, math, threads: as for eval.
    wi     (N, 3) unit directions, or (3,) for every row.
    u      (N, 2) uniforms in [0, 1), one pair per row; or instead
    n      the number of samples (an integer in [1, 1e9]) and
    seed   an integer in [0, 2**64 - 1] (default 0): sample i uses the CLI's counter-based
           uniforms (counter_uniform(seed, i, 0), counter_uniform(seed, i, 1)), so the result is
           bit-identical to ``glintlab sample --model M --wi x,y,z --n N --seed S`` in double.

    Returns {'wo': (N, 3) (Fortran-ordered), 'pdf': (N,), 'weight': (N,) value / pdf (0 if
    rejected), 'rejected': (N,) bool}.
    """
    return _glintlab.sample(model, wi, u=u, params=params, footprint=footprint, light=light,
                            n=n, seed=seed, precision=precision, isa=isa, math=math,
                            threads=threads)


def result_pool(idle_limit=None):
    """The memory of the arrays eval and sample return: counters of its pool, after setting the
    pool's bound on idle memory when idle_limit (bytes, >= 0) is given.

    An array of at least min_block_bytes takes a block the pool keeps mapped after an earlier
    result was freed (so its pages need not be faulted in again), else a freshly mapped one; the
    arrays are ordinary numpy arrays owning their memory, which numpy gives back to the pool when
    the last reference (or view) goes. Freed blocks stay mapped while their bytes together are
    within idle_limit (default 256 MiB; the oldest are unmapped first); 0 unmaps every freed
    block. Returns {'idle_bytes', 'idle_blocks' (kept for reuse), 'live_bytes', 'live_blocks'
    (held by arrays now), 'reused', 'mapped', 'unmapped' (blocks so far), 'idle_limit',
    'min_block_bytes'}.
    """
    return _glintlab.result_pool(idle_limit=idle_limit)


def load_plugin(path):
    """Loads a model plug-in (a module built with glintlab_add_model_plugin) and registers its
    models; returns their names. They are then listed by models() and usable by eval and sample.
    Raises ValueError for a file that is not a usable plug-in (the reason in the message)."""
    return _glintlab.load_plugin(str(path))


def register_model(name, eval, pdf, sample, params=None, needs=None, smooth_limit=None,
                   description="", source="", not_claimed=None, chunked=True):
    """Registers a model written as three vectorised numpy functions; returns None.

    The model is then listed by models(), usable by eval() and sample() (one call of its
    functions per chunk of 4096 rows) and has the conformance checks model.<name>.* of verify().

    name         letters, digits and '_'; not a registered model's name.
    eval(q, p)   q: dict of (N,) float64 arrays keyed by the query layout's column names
                 (wi_x, wi_y, wi_z, wo_x, wo_y, wo_z; with needs 'footprint': u, v, dudx,
                 dvdx, dudy, dvdy; with a light: light_cos_half_angle, light_intensity; with
                 'pixel corners': r0_x .. r3_z); p: dict parameter name -> float (the same
                 for every row of a call). Returns the cosine-weighted value f(wi, wo) max(wo_z, 0)
                 as a float64 (N,) array.
    pdf(q, p)    the density of wo under the model's sampler (per steradian), float64 (N,).
    sample(q, u, p)  u: (N, 2) float64 uniforms in [0, 1). Returns a dict: 'wo' (N, 3),
                 'pdf' (N,), 'weight' (N,) = value / pdf, all float64, and optionally
                 'rejected' (N,) bool.
    params       list of dicts: name, default, lo, hi, and optionally lo_open, hi_open,
                 integral, description (checked like a built-in model's parameters).
    needs        list of the query parts read besides the directions: 'footprint',
                 'point light', 'area light', 'pixel corners'.
    smooth_limit the registered model a footprint model tends to (converges-to-smooth).
    not_claimed  dict conformance property -> the reason the model does not claim it.
    chunked      True: the conformance suite calls the functions once per chunk of queries where
                 it has many (a few thousand rows per call); False: once per query (much slower;
                 for checking that the model's results do not depend on the chunking).

    A function that raises, or returns another type, dtype or shape, or NaN, makes the call that
    used it raise RuntimeError naming the model and the function. Raises ValueError for bad
    arguments here.
    """
    _glintlab.register_model(name, eval, pdf, sample, params=params, needs=needs,
                             smooth_limit=smooth_limit, description=description, source=source,
                             not_claimed=not_claimed, chunked=chunked)


def verify(claims, budget="quick", threads=None):
    """Runs the checks whose ids match `claims`; returns a list of dicts, claims.json's rows.

    claims   comma-separated globs over the claim ids (glintlab verify --list), e.g. 'eto.*'. As
             in the CLI, a model's conformance checks (model.<name>.<property>) are selected only
             by a pattern naming 'model.', e.g. 'model.my_model.*'; they include the models
             registered so far, plug-ins and register_model ones.
    budget   'quick' or 'full'.
    threads  worker threads, an integer in [0, 1024]; None or 0: all cores.

    Each dict has claims.json's fields: id, verdict, detail, statistic, value, bound, p_value,
    control, control_verdict, control_rejected, expected_verdict, seconds, ... Raises ValueError
    for a bad argument (the CLI's message). A registered Python model's function that fails during
    a check makes that check's verdict 'error', its message (naming the model and the function)
    in the detail; the other checks still run.
    """
    rows = _json.loads(_glintlab.verify(claims, budget=budget, threads=threads))
    return rows["claims"] if isinstance(rows, dict) else rows


def read_csv(path):
    """A CSV file the suite writes, as a numpy structured array: one field per column, named by
    the header; a column whose every value parses as a number is float64 (inf and nan included),
    any other column a str column. One row gives a (1,) array, a header alone a (0,) one. A
    name the header repeats gets the suffix _1, _2, ... from its second column on, as in
    numpy.genfromtxt (a sweep of a model with a parameter named `albedo` has the swept value's
    column and the furnace albedo's)."""
    with open(path, newline="") as f:
        rows = list(_csv.reader(f))
    header, body = [], [r for r in rows[1:] if r]
    for name in rows[0]:
        unique, k = name, 0
        while unique in header:
            k += 1
            unique = f"{name}_{k}"
        header.append(unique)
    columns = []
    for k in range(len(header)):
        values = [r[k] for r in body]
        try:
            columns.append(_np.array([float(v) for v in values], dtype=_np.float64))
        except ValueError:
            columns.append(_np.array(values, dtype=str))
    table = _np.empty(len(body), dtype=[(name, c.dtype) for name, c in zip(header, columns)])
    for name, c in zip(header, columns):
        table[name] = c
    return table


def _read_json(path):
    with open(path) as f:
        return _json.load(f)


def _files(folder):
    """Every file below the absolute `folder`: its relative path -> its path (sorted)."""
    found = {}
    for root, _, names in _os.walk(folder):
        for name in names:
            full = _os.path.join(root, name)
            found[_os.path.relpath(full, folder)] = full
    return dict(sorted(found.items()))


def _parsed(files):
    """The CSV files as structured arrays and the JSON files as dicts/lists, by relative path."""
    data = {}
    for rel, full in files.items():
        if rel.endswith(".csv"):
            data[rel] = read_csv(full)
        elif rel.endswith(".json"):
            data[rel] = _read_json(full)
    return data


def _text(value):
    """An option's value as the CLI's text: lists joined by commas, None as 0 (threads)."""
    if value is None:
        return "0"
    if isinstance(value, (list, tuple)):
        return ",".join(str(v) for v in value)
    return str(value)


def figure(id, out, budget="quick", threads=None, env=None, bench_from=None):
    """Runs the figure experiment `id` as ``glintlab figure ID --out OUT`` does, in this process.

    id          an id of ``glintlab figure --list``.
    out         the output folder: the figure's files go to out/<id>/ (replaced as a whole).
    budget      'quick' (the CLI's --budget quick: smaller images, seconds) or 'full'.
    threads     worker threads, an integer in [0, 1024]; None or 0: all cores. The files do not
                depend on it.
    env         a lat-long EXR environment map lighting the experiments that use one.
    bench_from  a folder of Google Benchmark JSON for the timing figures (None: no benchmark data).

    Returns a dict: ``dir`` (out/<id>), ``files`` (relative path -> path of every file written),
    ``data`` (each CSV as a structured array, see read_csv, and each JSON as dicts, by relative
    path). The experiments that draw every registered model (models-hemisphere) include the
    models registered from Python. Raises ValueError with the CLI's message for bad input.
    """
    folder = _glintlab.figure(str(id), str(out), budget=str(budget), threads=_text(threads),
                              env="" if env is None else str(env),
                              bench_from=None if bench_from is None else str(bench_from))
    folder = _os.path.abspath(folder)
    files = _files(folder)
    return {"dir": folder, "files": files, "data": _parsed(files)}


def sweep(out, models="*", budget="quick", threads=None):
    """The stability maps of the selected models × samplers, as ``glintlab sweep`` writes them.

    out      the output folder (out/<model>/<sampler>/<plane>.csv, .exr, .png; stability.json).
    models   comma-separated globs over model names (or a list of them); every glob must match.
             Models registered from Python are swept like any other.
    budget   'quick' (coarser grids) or 'full' (the CLI's default).
    threads  as for figure.

    Returns a dict: ``dir``, ``json`` (the path of stability.json), ``stability`` (its content),
    ``targets`` (the number of model × sampler targets), ``files`` and ``data`` (every CSV as a
    structured array, by path relative to out).
    """
    s = _glintlab.sweep(str(out), budget=str(budget), models=_text(models), threads=_text(threads))
    folder, path = _os.path.abspath(str(out)), _os.path.abspath(s["json"])
    files = _files(folder)
    return {"dir": folder, "json": path, "stability": _read_json(path),
            "targets": s["targets"], "files": files, "data": _parsed(files)}


def compare(out, models="*", budget="quick", threads=None, claims_from=None, sweeps_from=None):
    """The models side by side, as ``glintlab compare`` writes them (index.html drawn by
    reports/compare_page.py with /usr/bin/python3, as the CLI does).

    out          the output folder: compare.json, compare.csv, equal_time.csv, equal_time.png,
                 index.html.
    models       comma-separated globs over model names (or a list); models registered from
                 Python included.
    budget       'quick' or 'full'.
    threads      as for figure.
    claims_from  a ``glintlab verify --out`` folder whose claims.json gives the conformance
                 verdicts; None: each model's conformance checks run here (minutes per glint
                 model).
    sweeps_from  a ``glintlab sweep --out`` folder (or sweep()'s out) whose stability.json gives
                 the failure regions; None: swept here.

    Returns a dict: ``dir``, ``models`` (how many), ``files`` (name -> path), ``compare``
    (compare.json), ``table`` (compare.csv) and ``equal_time`` (equal_time.csv), the CSVs as
    structured arrays (read_csv).
    """
    s = _glintlab.compare(str(out), budget=str(budget), models=_text(models),
                          threads=_text(threads),
                          claims_from="" if claims_from is None else str(claims_from),
                          sweeps_from="" if sweeps_from is None else str(sweeps_from))
    folder = _os.path.abspath(s["dir"])
    files = _files(folder)
    return {"dir": folder, "models": s["models"], "files": files,
            "compare": _read_json(files["compare.json"]),
            "table": read_csv(files["compare.csv"]),
            "equal_time": read_csv(files["equal_time.csv"])}


def adequacy(out, models="*", threshold=0.02, budget="quick", threads=None, calibrate=False,
             runs=None, tables=None, bench_from=None, positions=None):
    """Where each cheaper level of a glint model family (binomial counting, Kemppinen's levels,
    kneiphof_klein_area under square lights) is indistinguishable from its most complete level, as
    ``glintlab adequacy`` writes it (docs/adequacy.md); with calibrate=True the decision
    rule's false-adequate rate on synthetic cells instead (``glintlab adequacy --calibrate``).

    out        the output folder.
    models     comma-separated globs over the measured models (deliot_belcour, kneiphof_klein,
               kemppinen_ggx, kemppinen_beckmann, kneiphof_klein_area).
    threshold  TAU, a number in (0, 1].
    budget     'quick' or 'full'.
    threads    as for figure.
    calibrate  measure the decision rule instead of the table.
    runs       with calibrate: synthetic cells per case and delta, an integer in [1, 1000000]
               (None: 2000).
    tables     with calibrate: whole tables per family-wise delta, an integer in [0, 100000]
               (None: 20).
    bench_from a folder holding glints.json of glintlab_bench_glints (its adequacy/ rows): each
               level priced by the benchmark (``cheapest_by_benchmark``, the time saved).
    positions  surface positions per cell, an integer in [100, 1000000] (None: the budget's,
               quick 8000, full 32000).

    Returns a dict: ``json`` and ``csv`` (the paths of adequacy.json / adequacy.csv, or
    adequacy-calibration.json / .csv), ``summary`` (the JSON's content), ``table`` (the CSV as a
    structured array), ``seconds``; without calibrate also ``maps`` (the PNG maps, relative to
    out), ``cells``, ``chosen`` and ``cheapest_measured`` (cells per level), ``chooser_matches``,
    ``chooser_refuted``, ``undecided``, ``exact_ns``, ``chosen_ns``, ``cheapest_ns`` (the
    summary the CLI prints).
    """
    s = _glintlab.adequacy(str(out), budget=str(budget), models=_text(models),
                           threshold=str(threshold), threads=_text(threads),
                           calibrate=bool(calibrate), runs=None if runs is None else str(runs),
                           tables=None if tables is None else str(tables),
                           bench_from=None if bench_from is None else str(bench_from),
                           positions=None if positions is None else str(positions))
    s["json"], s["csv"] = _os.path.abspath(s["json"]), _os.path.abspath(s["csv"])
    s["summary"] = _read_json(s["json"])
    s["table"] = read_csv(s["csv"])
    return s
