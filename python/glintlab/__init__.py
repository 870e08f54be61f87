"""glintlab from Python: the registered microfacet and glint models on numpy arrays.

Every call runs glintlab's C++ batch path (structure-of-arrays SIMD batches, chunks of 4096 rows
on worker threads, the GIL released), with the same input checks and the same results as the
``glintlab`` command line: ``eval`` matches ``glintlab eval --model`` and ``sample(n=, seed=)``
matches ``glintlab sample --model`` bit for bit in double precision.

Functions: models, eval, sample, load_plugin, register_model (a model prototyped in numpy) and
verify (the claims and the models' conformance checks). Bad input raises ValueError with the CLI's
one-line message naming the parameter (or row and column) and its valid range.

Directions are unit vectors in the local shading frame (z the normal): ``wi`` toward the viewer,
``wo`` toward the light. ``value`` is the cosine-weighted BRDF f(wi, wo) max(wo_z, 0), ``pdf``
the density of wo (per steradian) under the model's own sampler.
"""

import json as _json

from . import _glintlab

__all__ = ["models", "eval", "sample", "load_plugin", "register_model", "verify"]

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
