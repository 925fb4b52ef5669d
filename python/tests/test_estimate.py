"""btob.estimate(): a sweep's predicted time from a ~0.2 s sample of its own items lies within a factor 2 of the
run it predicts (a sweep of long orbits over r and one of certified window bounds, whose items cost more as n
grows); it names the sweeps and refuses other functions and unknown keywords.  Timing on a shared machine: a
prediction outside the factor is measured once more before the test fails."""
import time

import pytest

import btob

RUNS = {
    "bifurcation": dict(r_min=0.08, r_max=0.4, r_count=100, iterations=1000000, tail=40, bins=200, threads=1),
    "windows_bounds": dict(n="1..80", certify=True, digits=15, threads=1),
}


def ratio(name, kw):
    e = btob.estimate(name, **kw)
    assert e["items"] > 0 and 0 < e["sampled"] <= e["items"] and e["bytes"] > 0
    t0 = time.perf_counter()
    getattr(btob, name)(**kw)
    return e["predicted_seconds"] / (time.perf_counter() - t0)


@pytest.mark.parametrize("name", sorted(RUNS))
def test_prediction_within_a_factor_2(name):
    r = ratio(name, RUNS[name])
    if not 0.5 <= r <= 2:
        r = ratio(name, RUNS[name])
    assert 0.5 <= r <= 2, f"{name}: predicted / measured = {r:.2f}"


def test_refuses_what_is_not_a_sweep():
    with pytest.raises(ValueError, match="estimate: got 'lyapunov', expected one of .*bifurcation"):
        btob.estimate("lyapunov", r=0.2, point="1,-0.5,-1.1")
    with pytest.raises(TypeError, match="unexpected keyword argument 'nosuch'"):
        btob.estimate("bifurcation", nosuch=1)
    assert btob.estimate(btob.bifurcation, r_count=4, iterations=100, tail=10)["items"] == 4
