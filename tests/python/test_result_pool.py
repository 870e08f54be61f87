"""The memory of eval's and sample's result arrays (python/result_pool.h, glintlab.result_pool):
ordinary writable numpy arrays owning their memory (kept, written, sliced, pickled, resized,
deleted), a block handed out again only after every array and view of it is gone, the pool's
idle memory bounded by its limit, and no block left behind over many calls (counted)."""

import gc
import pickle
import threading

import numpy as np
import pytest

import glintlab
import numpy_models as nm

ROWS = 40000  # 320 000-byte arrays: above the pool's smallest block


def directions(rows, seed):
    v = np.random.default_rng(seed).normal(size=(rows, 3))
    v[:, 2] = np.abs(v[:, 2]) + 1e-3
    return v / np.linalg.norm(v, axis=1, keepdims=True)


WI, WO = directions(ROWS, 1), directions(ROWS, 2)


def stats():
    gc.collect()
    return glintlab.result_pool()


@pytest.fixture
def pool_limit():
    """Restores the pool's limit after a test that changes it."""
    limit = glintlab.result_pool()["idle_limit"]
    yield
    glintlab.result_pool(idle_limit=limit)


def test_results_are_ordinary_arrays():
    before = stats()
    r = glintlab.eval("smooth_ggx", WI, WO)
    expect = {k: v.copy() for k, v in r.items()}
    v = r["value"]
    assert v.nbytes >= before["min_block_bytes"]
    assert v.flags.owndata and v.flags.writeable and v.flags.c_contiguous and v.base is None
    assert np.core.multiarray.get_handler_name(v) == "glintlab_result_pool"
    assert stats()["live_blocks"] == before["live_blocks"] + len(r)
    # Written, sliced, pickled.
    v[:10] = 7.0
    assert (v[:10] == 7.0).all()
    view = v[100:200:2]
    back = pickle.loads(pickle.dumps(r))
    np.testing.assert_array_equal(back["value"], v)
    np.testing.assert_array_equal(back["pdf"], expect["pdf"])
    # A view keeps its block: dropping the array and the dict leaves the view's values intact
    # while other calls take blocks.
    del r, v
    assert stats()["live_blocks"] == before["live_blocks"] + 1  # the view's block
    for _ in range(3):
        glintlab.eval("smooth_ggx", WO, WI)
    np.testing.assert_array_equal(view, expect["value"][100:200:2])
    del view
    assert stats()["live_blocks"] == before["live_blocks"]
    # Resized in place (numpy reallocates through the pool's handler) and given back after.
    r = glintlab.eval("smooth_ggx", WI, WO)
    p = r.pop("pdf")
    p.resize(2 * ROWS, refcheck=False)
    np.testing.assert_array_equal(p[:ROWS], expect["pdf"])
    del r, p
    assert stats()["live_blocks"] == before["live_blocks"]


def test_sample_results():
    before = stats()
    s = glintlab.sample("smooth_ggx", WI, n=ROWS, seed=3)
    assert s["wo"].flags.f_contiguous and s["wo"].flags.owndata and s["rejected"].dtype == bool
    for k in ("wo", "pdf", "weight", "rejected"):
        assert np.core.multiarray.get_handler_name(s[k]) == "glintlab_result_pool", k
    again = glintlab.sample("smooth_ggx", WI, n=ROWS, seed=3)
    for k in s:
        np.testing.assert_array_equal(s[k], again[k])
    del s, again
    assert stats()["live_blocks"] == before["live_blocks"]


def test_kept_results_are_never_reused():
    """Results kept by the caller are not handed out again: each keeps its values while later calls
    run (a pool that gave back a block still in use would overwrite them)."""
    kept = []
    for k in range(6):
        wi, wo = (WI, WO) if k % 2 == 0 else (WO, WI)
        r = glintlab.eval("smooth_ggx", wi, wo)
        kept.append((r, {name: a.copy() for name, a in r.items()}))
    addresses = [a.__array_interface__["data"][0] for r, _ in kept for a in r.values()]
    assert len(set(addresses)) == len(addresses)
    for r, copies in kept:
        for name, a in r.items():
            np.testing.assert_array_equal(a, copies[name])


def test_memory_is_reused_and_nothing_leaks():
    """Many calls that drop their results: the blocks of the first are taken again by the others
    (counted), and none is left held after them."""
    glintlab.eval("smooth_ggx", WI, WO)  # the pool's blocks for this size, left idle
    before = stats()
    calls = 200
    arrays = 0
    for k in range(calls):
        r = glintlab.eval("smooth_ggx", WI, WO, threads=1 + k % 2)
        arrays += len(r)
        del r
    after = stats()
    assert after["live_blocks"] == before["live_blocks"]
    assert after["live_bytes"] == before["live_bytes"]
    assert after["reused"] - before["reused"] == arrays
    assert after["mapped"] == before["mapped"]
    assert after["idle_bytes"] <= after["idle_limit"]


def test_failed_calls_give_their_blocks_back():
    before = stats()
    bad = WO.copy()
    bad[ROWS - 5] *= 1.1
    for _ in range(20):
        with pytest.raises(ValueError, match=f"row {ROWS - 5}"):
            glintlab.eval("smooth_ggx", WI, bad)
    assert stats()["live_blocks"] == before["live_blocks"]


def test_idle_memory_is_bounded(pool_limit):
    with pytest.raises(ValueError, match="idle_limit: -1 is out of range"):
        glintlab.result_pool(idle_limit=-1)
    one_mib = 1 << 20
    s = glintlab.result_pool(idle_limit=one_mib)
    assert s["idle_limit"] == one_mib and s["idle_bytes"] <= one_mib
    r = glintlab.eval("smooth_ggx", WI, WO)  # nine arrays of 320 000 bytes
    arrays = len(r)
    held = stats()
    del r
    s = stats()
    assert s["idle_bytes"] <= one_mib
    assert s["live_blocks"] == held["live_blocks"] - arrays
    assert s["unmapped"] > held["unmapped"]
    # No idle memory: every freed block unmapped, every result mapped fresh.
    s = glintlab.result_pool(idle_limit=0)
    assert s["idle_bytes"] == 0 and s["idle_blocks"] == 0
    for _ in range(2):
        glintlab.eval("smooth_ggx", WI, WO)
    s2 = stats()
    assert s2["idle_blocks"] == 0 and s2["mapped"] - s["mapped"] == 2 * arrays
    assert s2["reused"] == s["reused"]
    # With room again, the second call takes the first one's blocks.
    glintlab.result_pool(idle_limit=64 << 20)
    for _ in range(2):
        glintlab.eval("smooth_ggx", WI, WO)
    s3 = stats()
    assert s3["mapped"] - s2["mapped"] == arrays and s3["reused"] - s2["reused"] == arrays


def test_threads_free_concurrently():
    """Arrays made and dropped on several Python threads at once (the pool is locked)."""
    before = stats()
    failures = []

    def work(seed):
        try:
            wo = directions(ROWS, seed)
            expect = glintlab.eval("smooth_ggx", WI, wo)["value"].copy()
            for _ in range(20):
                np.testing.assert_array_equal(glintlab.eval("smooth_ggx", WI, wo)["value"], expect)
        except Exception as e:  # noqa: BLE001 (reported below)
            failures.append(e)

    threads = [threading.Thread(target=work, args=(10 + k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not failures, failures
    assert stats()["live_blocks"] == before["live_blocks"]


def test_numpy_model_arrays_it_keeps():
    """A numpy model's functions run with the pool's handler (their chunk-sized temporaries reuse
    blocks): an array a function keeps is never handed out again, and the results are its values."""
    kept = []

    def ev(q, p):
        v = nm.lambert_eval(q, p)
        kept.append((v, v.copy()))
        return v

    glintlab.register_model("py_pool_keeper", ev, nm.lambert_pdf, nm.lambert_sample,
                            params=[nm.ALBEDO])
    wo = directions(100000, 4)
    for _ in range(3):
        r = glintlab.eval("py_pool_keeper", WI[0], wo, threads=2)
        np.testing.assert_array_equal(r["value"], 0.8 * wo[:, 2] / np.pi)
    assert any(np.core.multiarray.get_handler_name(v) == "glintlab_result_pool" for v, _ in kept)
    for v, copy in kept:
        np.testing.assert_array_equal(v, copy)
    before = stats()
    kept.clear()
    assert stats()["live_blocks"] < before["live_blocks"]


def test_numpy_model_results_do_not_depend_on_where_the_pool_puts_blocks():
    """numpy's loops take another path (other rounding) when an input and an output array lie
    exactly end to end in memory (it then treats them as overlapping: log1p on float64, numpy
    1.24), which two of the pool's blocks would do wherever the system maps them next to each
    other. A numpy model's results through eval are therefore those of the same functions called
    directly, every time and on any thread count (the 2 MiB temporaries of a chunk of 16384 rows
    here, as the example model's (N, 16) arrays)."""
    def ev(q, p):
        x = -0.5 * np.repeat(q["wo_z"][:, None], 16, axis=1)
        return np.log1p(x).sum(axis=1)

    name = "py_log1p"
    if name not in [m["name"] for m in glintlab.models()]:
        glintlab.register_model(name, ev, ev, nm.lambert_sample, params=[nm.ALBEDO])
    want = np.concatenate([ev({"wo_z": np.ascontiguousarray(WO[b:b + 16384, 2])}, {})
                           for b in range(0, ROWS, 16384)])
    for threads in (1, 2, 1, 2):
        got = glintlab.eval(name, WI, WO, threads=threads)["value"]
        np.testing.assert_array_equal(got, want)
