# SPDX-License-Identifier: GPL-3.0-or-later
"""The package as a citizen of the interpreter: errors as the command line words them, zero-copy arrays, no memory
growth over 100 calls, the GIL released during a run, Ctrl-C within half a second, progress."""
import gc
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import btob
from conftest import exe

SMALL = dict(r_min=0.1, r_max=0.12, r_count=20, iterations=200, tail=20, bins=32)
# The Figure 4.1 workload (5000 r x 32 orbits x 5000 iterations, 8e8 map iterations).
FIG41 = dict(r_min=0.0717, r_max=0.1717, r_count=5000, iterations=5000, tail=100, bins=700)


def cli_error(args):
    p = subprocess.run([exe()] + args, capture_output=True, text=True)
    assert p.returncode == 2, p.stderr
    return p.stderr.strip().removeprefix("btob: error: ")


@pytest.mark.parametrize("function,command,kwargs", [
    ("bifurcation", "bifurcation", dict(r_min=1.5)),
    ("bifurcation", "bifurcation", dict(precision="quad")),
    ("bifurcation", "bifurcation", dict(grid="strip:0x5")),
    ("bifurcation", "bifurcation", dict(overlay=["nosuch"])),
    ("lyapunov", "lyapunov", dict(r=0.2, point="1,2")),
    ("lyapunov", "lyapunov", dict(r=0.2, point="1,0.5,1")),
    ("lyapunov_map", "lyapunov-map", dict(r_count=0)),
    ("windows_bounds", "windows bounds", dict(n="0..3")),
    ("basins", "basins", dict(r=0.2, grid="strip:0x0")),
])
def test_value_error_has_the_command_line_message(function, command, kwargs, tmp_path):
    from conftest import flags
    want = cli_error(command.split() + flags(kwargs) + (["--out", str(tmp_path / "x")] if command not in
                                                        ("lyapunov", "windows bounds") else []))
    with pytest.raises(ValueError) as e:
        getattr(btob, function)(**kwargs)
    assert str(e.value) == want
    assert not os.path.exists(tmp_path / "x")  # nothing written


def test_point_as_tuple_with_wrong_length_names_the_argument():
    with pytest.raises(ValueError, match=r"^point: got '1,0.5', expected three finite numbers"):
        btob.lyapunov(r=0.2, point=(1, 0.5))


def test_unknown_keyword_and_missing_required_raise_type_error():
    with pytest.raises(TypeError, match="unexpected keyword argument 'r_mni'"):
        btob.bifurcation(r_mni=0.1)
    with pytest.raises(TypeError, match="missing required keyword argument 'point'"):
        btob.lyapunov(r=0.2)
    with pytest.raises(TypeError):
        btob.bifurcation(0.1)  # keywords only
    with pytest.raises(ValueError, match=r"^threads: got -1, expected 0 \(all cores\) or 1\.\.1024$"):
        btob.bifurcation(threads=-1, **SMALL)
    # Not an int: core's wording, and that it must be one; beyond a long: out of range.  btob.iterate checks alike.
    not_int = r"^threads: got 2\.5, expected 0 \(all cores\) or 1\.\.1024, an int$"
    with pytest.raises(ValueError, match=not_int):
        btob.bifurcation(threads=2.5, **SMALL)
    with pytest.raises(ValueError, match=not_int):
        btob.iterate(0.2, [[1, -0.5, -1.1]], 10, threads=2.5)
    too_many = r"^threads: got 1180591620717411303424, expected 0 \(all cores\) or 1\.\.1024$"
    with pytest.raises(ValueError, match=too_many):
        btob.bifurcation(threads=2**70, **SMALL)
    with pytest.raises(ValueError, match="^log: got 1, expected True or False"):
        btob.bifurcation(log=1, **SMALL)


def test_arrays_are_views_of_the_result():
    res = btob.bifurcation(**SMALL)
    d = res.density
    assert d.flags.owndata is False and d.flags.writeable is False
    assert d.base is res  # the numpy array's base is the Python result, which holds the C++ result
    assert d.shape == (20, 32) and d.dtype == np.uint32
    # Two views share the buffer: no copy either time.
    assert np.shares_memory(d, res.density)
    del res
    gc.collect()
    assert int(d.sum()) == 20 * 32 * 20  # the view keeps the result alive
    with pytest.raises(ValueError):
        d[0, 0] = 1  # read-only


def rss_kib():
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS")


def test_100_calls_do_not_grow_memory():
    kw = dict(SMALL, r_count=200, bins=256)  # 200 x 256 x 4 bytes = 200 KiB per result
    for _ in range(10):
        btob.bifurcation(**kw).density.sum()
    gc.collect()
    before = rss_kib()
    for _ in range(100):
        res = btob.bifurcation(**kw)
        res.density.sum()
        res.attrs
    del res
    gc.collect()
    grown = rss_kib() - before
    # 100 leaked results would be 20 MiB; allocator noise is well under 4 MiB.
    assert grown < 4096, f"resident memory grew by {grown} KiB over 100 calls"


def test_fig41_density_is_not_copied():
    """The Figure 4.1 workload: its density (5000 x 700 uint32, 14 MB) is a view, and the peak resident memory
    after reading it through numpy does not grow by a copy."""
    res = btob.bifurcation(**FIG41)
    before = rss_kib()
    d = res.density
    total = int(d.sum(dtype=np.uint64))
    assert d.flags.owndata is False and d.base is res
    assert total == 5000 * 32 * 100 - int(res.points_below_range) - int(res.points_above_range)
    assert rss_kib() - before < 0.25 * d.nbytes / 1024


def test_a_second_thread_advances_during_a_run():
    """Another Python thread keeps running while btob computes (the GIL is released).  The workload doubles until a
    run lasts at least 0.3 s, so a fast machine cannot make the check vacuous (a 2000 x 5000 Figure 4.1 run took
    0.07 s on one CI machine, too short to count ticks of 10 ms)."""

    def run_while_ticking(iterations):
        ticks = []
        stop = threading.Event()

        def count():
            while not stop.is_set():
                ticks.append(time.monotonic())
                time.sleep(0.01)

        t = threading.Thread(target=count)
        t.start()
        time.sleep(0.02)
        t0 = time.monotonic()
        btob.bifurcation(**dict(FIG41, r_count=2000, iterations=iterations))
        t1 = time.monotonic()
        stop.set()
        t.join()
        return t1 - t0, [x for x in ticks if t0 < x < t1]

    iterations = 5000
    elapsed, during = run_while_ticking(iterations)
    while elapsed < 0.3 and iterations < 5000 * 2**8:
        iterations *= 2
        elapsed, during = run_while_ticking(iterations)
    assert elapsed >= 0.3, f"even {iterations} iterations ran in {elapsed:.3f} s"
    # The other thread ticks every ~10 ms while the run holds no GIL (it would not tick at all otherwise); a tenth of
    # the ticks leaves room for a machine loaded several times over, where the ticking thread waits for a core.
    assert len(during) >= 0.1 * elapsed / 0.01, (elapsed, len(during))


def test_keyboard_interrupt_within_seconds():
    """SIGINT during the Figure 4.1 run (the signal a terminal's Ctrl-C sends): KeyboardInterrupt within 5 s (a
    margin for a loaded machine; the run would take many seconds more unpolled, and the idle machine's 0.1 s is
    benchmarks/bm_cancel.cpp's measurement)."""
    sent = []

    def send():
        time.sleep(0.3)
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    kw = dict(FIG41, iterations=50000)  # 8e9 iterations: many seconds unless interrupted
    threading.Thread(target=send).start()
    with pytest.raises(KeyboardInterrupt):
        btob.bifurcation(**kw)
    latency = time.monotonic() - sent[0]
    assert latency < 5, f"KeyboardInterrupt {latency:.3f} s after SIGINT"


def test_keyboard_interrupt_by_itimer():
    def handler(signum, frame):
        raise KeyboardInterrupt

    old = signal.signal(signal.SIGALRM, handler)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.2)
        t0 = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            btob.bifurcation(**dict(FIG41, iterations=50000))
        assert time.monotonic() - t0 < 0.2 + 5  # the timer's 0.2 s, then seconds of margin for a loaded machine
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    # The next run is unaffected.
    assert btob.bifurcation(**SMALL).density.sum() > 0


def test_progress_callback_sees_the_run_to_its_end():
    seen = []
    btob.bifurcation(progress=lambda done, total: seen.append((done, total)), **dict(FIG41, r_count=1000))
    assert seen and seen[-1][0] == seen[-1][1]
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))


def test_progress_callback_exception_stops_the_run():
    def fail(done, total):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        btob.bifurcation(progress=fail, **dict(FIG41, iterations=20000))


def test_progress_true_uses_tqdm(capsys):
    pytest.importorskip("tqdm")
    res = btob.bifurcation(progress=True, **SMALL)
    assert res.density.sum() > 0


def test_threads_do_not_change_numbers():
    a = btob.bifurcation(threads=1, **dict(SMALL, grid="random:9"))
    b = btob.bifurcation(threads=2, **dict(SMALL, grid="random:9"))
    assert a.density.tobytes() == b.density.tobytes()
    assert a.attrs["threads"] == 1 and b.attrs["threads"] == 2


def test_sequences_and_numpy_values_set_vector_and_point_fields():
    res = btob.bifurcation(vline=np.array([0.11, 0.115]), range=(0.0, 1.0), **SMALL)
    assert res.vlines.tolist() == [0.11, 0.115] and (res.range_lo, res.range_hi) == (0.0, 1.0)
    grid = np.array([[1.0, -0.5, -1.1], [1.0, 0.8, -1.0]])
    a = btob.bifurcation(grid=grid, **SMALL)
    b = btob.bifurcation(grid="1,-0.5,-1.1;1,0.8,-1", **SMALL)
    assert a.density.tobytes() == b.density.tobytes() and a.initial_conditions == 2
    assert btob.lyapunov(r=np.float64(0.15), point=np.array([1, -0.5, -1.1]), iterations=2000).lambda1 < 0
    assert a.request["grid"] == ["1,-0.5,-1.1;1,0.8,-1"]  # what the manifest would record
