"""eval's input paths over several chunks: a model's own query rules (podee's) tested by the
chunk check's pass over the columns, and C-ordered (N, 3) and other strided direction arrays read
where they lie by the batches (core/simd/model_batch.h gathers them block by block). Each result
is compared bit for bit with the same rows as contiguous columns."""

import numpy as np
import pytest

import glintlab

ROWS = 10_000  # three of the CLI's 4096-row chunks


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def podee_queries(rows=ROWS, seed=3):
    rng = np.random.default_rng(seed)
    wi = unit(rng.normal(size=(rows, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wo = unit(rng.normal(size=(rows, 3)) * [1, 1, 0.5] + [0, 0, 1])
    wi[:, 2], wo[:, 2] = np.abs(wi[:, 2]), np.abs(wo[:, 2])
    footprint = {"u": rng.uniform(0, 1, rows), "v": rng.uniform(0, 1, rows),
                 "dudx": np.full(rows, 2e-3), "dvdx": np.zeros(rows),
                 "dudy": np.zeros(rows), "dvdy": np.full(rows, 2e-3)}
    for k in range(4):
        r = unit(wo + rng.normal(scale=1e-3, size=(rows, 3)))
        for a, axis in enumerate("xyz"):
            footprint[f"r{k}_{axis}"] = r[:, a]
    light = {"light_cos_half_angle": np.full(rows, 0.999), "light_intensity": np.ones(rows)}
    return wi, wo, footprint, light


def error_of(*args, **kwargs):
    with pytest.raises(ValueError) as e:
        glintlab.eval(*args, **kwargs)
    return str(e.value)


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("threads", [1, 2])
def test_a_models_own_rules_name_the_first_bad_row_of_any_chunk(precision, threads):
    wi, wo, footprint, light = podee_queries()
    kw = dict(footprint=footprint, light=light, precision=precision, threads=threads)
    got = glintlab.eval("podee", wi, wo, **kw)  # every row valid: no row refused
    assert np.all(np.isfinite(got["value"]))
    wo[7000] = unit(np.array([0.5, 0.0, -0.1]))  # its centre below the surface (wo_z > 0)
    light["light_cos_half_angle"][5000] = 1.0  # a disk of radius 0 (< 1)
    message = error_of("podee", wi, wo, **kw)
    assert message.startswith("row 5000") and "light_cos_half_angle" in message, message
    assert "< 1, a disk of radius > 0" in message, message
    light["light_cos_half_angle"][5000] = 0.999
    for layout in (wo, np.asfortranarray(wo)):
        message = error_of("podee", wi, layout, **kw)
        assert message.startswith("row 7000") and "wo_z" in message, message
        assert "> 0, the disk's centre above the surface" in message, message
    # The message is the one the row alone gets, with its index.
    alone = error_of("podee", wi[7000:7001], wo[7000:7001], precision=precision,
                     footprint={k: v[7000:7001] for k, v in footprint.items()},
                     light={k: v[7000:7001] for k, v in light.items()})
    assert message == alone.replace("row 0", "row 7000", 1)


def test_podee_over_several_chunks_is_each_piece_alone():
    wi, wo, footprint, light = podee_queries(seed=5)
    whole = glintlab.eval("podee", wi, wo, footprint=footprint, light=light)
    for a, b in ((0, 4095), (4095, 4097), (8191, ROWS)):
        piece = glintlab.eval("podee", wi[a:b], wo[a:b],
                              footprint={k: v[a:b] for k, v in footprint.items()},
                              light={k: v[a:b] for k, v in light.items()})
        for key, column in piece.items():
            assert np.array_equal(whole[key][a:b], column, equal_nan=True), key


def directions(rows=ROWS, seed=7):
    rng = np.random.default_rng(seed)
    wi = unit(rng.normal(size=(rows, 3)) + [0, 0, 1.5])
    wo = unit(rng.normal(size=(rows, 3)) + [0, 0, 1.5])
    return wi, wo


@pytest.mark.parametrize("precision", ["double", "float"])
def test_strided_direction_arrays_are_the_contiguous_columns_bit_for_bit(precision):
    wi, wo = directions()
    alpha = np.random.default_rng(8).uniform(0.05, 0.9, ROWS)
    for params in (None, {"alpha_x": alpha}):
        ref = glintlab.eval("smooth_ggx", np.asfortranarray(wi), np.asfortranarray(wo),
                            params=params, precision=precision)
        wide = np.zeros((ROWS, 5))
        wide[:, 1:4] = wo
        layouts = {
            "C-ordered (N, 3)": (wi, wo),
            "columns of an (N, 5) array (stride 5)": (wi, wide[:, 1:4]),
            "reversed rows (negative stride)": (wi[::-1][::-1], wo[::-1].copy()[::-1]),
            "float32 C-ordered": (wi.astype(np.float32), wo.astype(np.float32)),
        }
        for name, (a, b) in layouts.items():
            got = glintlab.eval("smooth_ggx", a, b, params=params, precision=precision, threads=2)
            want = ref
            if "float32" in name:  # the same rounded inputs as contiguous columns
                want = glintlab.eval("smooth_ggx", np.asfortranarray(a), np.asfortranarray(b),
                                     params=params, precision=precision)
            for key in want:
                assert np.array_equal(got[key], want[key], equal_nan=True), (name, key)


def test_a_bad_row_of_a_strided_array_in_a_later_chunk_is_named():
    wi, wo = directions()
    wide = np.zeros((ROWS, 5))
    wide[:, 1:4] = wo
    wide[9000, 1:4] *= 1.01  # not unit
    message = error_of("smooth_ggx", wi, wide[:, 1:4])
    assert message.startswith("row 9000") and "wo" in message, message


def test_the_check_catches_a_changed_row():
    # The comparisons above can fail: one changed direction changes its row's value.
    wi, wo = directions()
    ref = glintlab.eval("smooth_ggx", wi, wo)
    wo2 = wo.copy()
    wo2[5000] = unit(wo2[5000] + [0.01, 0, 0])
    got = glintlab.eval("smooth_ggx", wi, wo2)
    differ = np.flatnonzero(got["value"] != ref["value"])
    assert list(differ) == [5000]


def numpy_lambert():
    import numpy_models as nm
    name = "py_chunk_check_lambert"
    if name not in [m["name"] for m in glintlab.models()]:
        nm.register_lambert(glintlab, name)
    return name


def test_a_numpy_models_c_ordered_rows_are_checked_by_the_gather():
    # A numpy model's chunk (16384 rows) gathers a C-ordered (N, 3) array and tests its rows'
    # lengths in the same pass: a row beyond the unit tolerance in the second chunk is named, one
    # within it (but outside the pass's bounds, a little inside the tolerance) passes, and the
    # values are those of the Fortran-ordered call.
    name = numpy_lambert()
    rows = 40_000
    wi, wo = directions(rows, seed=11)
    ref = glintlab.eval(name, np.asfortranarray(wi), np.asfortranarray(wo), threads=1)
    got = glintlab.eval(name, wi, wo, threads=2)
    for key in ref:
        assert np.array_equal(got[key], ref[key]), key
    near = wo.copy()
    near[20_000] *= 1 + 0.9e-6  # |length - 1| = 0.9e-6 <= 1e-6: valid
    glintlab.eval(name, wi, near)
    far = wo.copy()
    far[30_000] *= 1 + 1.1e-6  # beyond the tolerance
    far[35_000] *= 1.5
    for layout in (far, np.asfortranarray(far)):
        message = error_of(name, wi, layout)
        assert message.startswith("row 30000") and "wo" in message, message
    bad_wi = wi.copy()
    bad_wi[17_000] = [0.0, 0.0, np.nan]
    message = error_of(name, bad_wi, wo)
    assert message.startswith("row 17000") and "wi" in message, message


def podee_by_entry():
    # podee's registry entry under another name without its static model: the module knows its
    # own rules only through the entry's validate function, as it knows a plug-in's (no column
    # form of them in python/batch_call.cpp), and its batches are the loop over its thunks.
    name = "podee_by_entry"
    if name not in [m["name"] for m in glintlab.models()]:
        glintlab._glintlab._register_entry_copy("podee", name)
    return name


@pytest.mark.parametrize("threads", [1, 2])
def test_rules_known_only_through_the_entry_name_the_first_bad_row_of_any_chunk(threads):
    """The chunk check's pass calls such a model's validate on each row's query: every row valid
    passes, and a refused row anywhere (first, last, either side of a chunk boundary) is named
    with the message podee itself gets; of two refused rows the lower one."""
    name = podee_by_entry()
    wi, wo, footprint, light = podee_queries()
    kw = dict(footprint=footprint, light=light, threads=threads)
    got = glintlab.eval(name, wi, wo, **kw)
    assert np.all(np.isfinite(got["value"])) and np.all(np.isfinite(got["pdf"]))
    cos = light["light_cos_half_angle"]
    for row in (0, 4095, 4096, 8191, 8192, ROWS - 1):
        cos[row] = 1.0  # a disk of radius 0
        message = error_of(name, wi, wo, **kw)
        assert message.startswith(f"row {row}") and "light_cos_half_angle" in message, message
        assert message == error_of("podee", wi, wo, **kw)
        cos[row] = 0.999
    wo[7000] = unit(np.array([0.5, 0.0, -0.1]))  # its centre below the surface
    cos[9000] = 1.0
    message = error_of(name, wi, wo, **kw)
    assert message.startswith("row 7000") and "> 0, the disk's centre above the surface" in message
    assert message == error_of("podee", wi, wo, **kw)


def test_an_entry_copy_needs_a_new_name():
    with pytest.raises(ValueError, match="podee"):
        glintlab._glintlab._register_entry_copy("podee", "podee")
