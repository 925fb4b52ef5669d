"""Ctrl-C (SIGINT) stops every kind of run: single orbits in every precision, transients, sweeps whose items are
long orbits, the atlas and windows certificates raise KeyboardInterrupt within a bound, and the next run is
unaffected.
Each call below would run for minutes or hours if the signal were not seen inside its inner loop.  The bound is
2 s so that a loaded machine does not fail the test; on an idle machine the latency is the binding's 50 ms poll."""
import os
import signal
import threading
import time

import pytest

import btob

ORBIT = dict(r=0.2, point="1,-0.5,-1.1")
BOUND = 2.0  # seconds from SIGINT to KeyboardInterrupt (the guarantee on an idle machine is 0.1 s)

RUNS = [
    ("lyapunov double", lambda: btob.lyapunov(**ORBIT, iterations=10**12)),
    ("lyapunov mpfr", lambda: btob.lyapunov(**ORBIT, iterations=10**9, precision="mpfr:40")),
    ("iterate", lambda: btob.iterate(0.2, [1, -0.5, -1.1], 10**11, record="final")),
    ("classify transient", lambda: btob.classify(**ORBIT, transient=10**12)),
    ("lyapunov_map", lambda: btob.lyapunov_map(r_count=2, iterations=10**11, grid="1,-0.5,-1.1")),
    ("pattern_atlas", lambda: btob.pattern_atlas(max_length=12)),
    ("windows certificate", lambda: btob.windows_bounds(n="1000", certify=True)),
    ("bifurcation mpfr", lambda: btob.bifurcation(r_count=2, iterations=10**8, tail=100, grid="1,-0.5,-1.1",
                                                  precision="mpfr:30")),
]


@pytest.mark.parametrize("name,run", RUNS, ids=[n for n, _ in RUNS])
def test_keyboard_interrupt_stops_the_run(name, run):
    sent = []

    def send():
        time.sleep(0.5)
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=send).start()
    with pytest.raises(KeyboardInterrupt):
        run()
    latency = time.monotonic() - sent[0]
    print(f"{name}: KeyboardInterrupt {latency:.3f} s after SIGINT")
    assert latency < BOUND, f"{name}: KeyboardInterrupt {latency:.3f} s after SIGINT"
    # The interrupted run left nothing behind: the same route runs again to the end.
    assert btob.lyapunov(**ORBIT, iterations=1000).attrs["lambda1"] == btob.lyapunov(**ORBIT, iterations=1000).attrs["lambda1"]
