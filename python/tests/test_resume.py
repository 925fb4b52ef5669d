# SPDX-License-Identifier: GPL-3.0-or-later
"""resume= on every sweep (the command line's --resume, one code: io/checkpoint.hpp): the finished items are kept in
the file while the run goes on; a run killed with SIGKILL, or stopped by Ctrl-C (KeyboardInterrupt keeps the file),
and then resumed gives arrays bitwise equal to one uninterrupted run, and removes the file; a file made by another
request is refused with one line naming the field that differs, and left as it was."""
import signal
import subprocess
import sys
import time

import pytest

import btob
from test_round_trip import CASES, same_arrays

# A sweep of 64 r values in 32 rounds of 2 (one thread), about 2.5 s in all: a part is appended every ~0.08 s.
KW = dict(r_min=0.1, r_max=0.5, r_count=64, grid="paper", iterations=1000000, transient=100, threads=1)
CHILD = """
import os, sys, btob
print("started", flush=True)
try:
    btob.lyapunov_map(resume=sys.argv[1], **{kw!r})
except KeyboardInterrupt:
    sys.exit(42 if os.path.exists(sys.argv[1]) else 1)
sys.exit(0)
"""


@pytest.fixture(scope="module")
def uninterrupted():
    return btob.lyapunov_map(**KW)


def stop_after_parts(path, sig):
    """Runs the sweep in a child interpreter with resume=path, sends `sig` once the file holds a few finished parts
    (it grew twice past its header), and returns the child's exit status."""
    child = subprocess.Popen([sys.executable, "-c", CHILD.format(kw=KW), str(path)], stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "started"
    sizes = set()
    deadline = time.monotonic() + 60
    while len(sizes) < 3 and time.monotonic() < deadline:
        assert child.poll() is None, "the sweep finished before it was stopped"
        if path.exists():
            sizes.add(path.stat().st_size)
        time.sleep(0.01)
    child.send_signal(sig)
    return child.wait(timeout=30)


def test_a_killed_run_resumes_bitwise(tmp_path, uninterrupted):
    cp = tmp_path / "map.checkpoint"
    assert stop_after_parts(cp, signal.SIGKILL) == -signal.SIGKILL
    assert cp.exists()
    same_arrays(btob.lyapunov_map(resume=cp, **KW), uninterrupted)
    assert not cp.exists(), "the checkpoint outlived the complete result"


def test_keyboard_interrupt_keeps_the_checkpoint_and_resumes_bitwise(tmp_path, uninterrupted):
    cp = tmp_path / "map.checkpoint"
    assert stop_after_parts(cp, signal.SIGINT) == 42, "KeyboardInterrupt did not leave the checkpoint"
    same_arrays(btob.lyapunov_map(resume=str(cp), **KW), uninterrupted)
    assert not cp.exists()


def test_another_request_is_refused_in_one_line(tmp_path):
    cp = tmp_path / "map.checkpoint"
    assert stop_after_parts(cp, signal.SIGKILL) == -signal.SIGKILL
    before = cp.read_bytes()
    with pytest.raises(ValueError) as e:
        btob.lyapunov_map(resume=cp, **dict(KW, iterations=KW["iterations"] + 1))
    message = str(e.value)
    assert "\n" not in message and "iterations" in message and "another request" in message, message
    assert cp.read_bytes() == before


SWEEPS = sorted(f for f in btob._btob._sweeps if f in CASES)


def test_every_sweep_takes_resume():
    assert set(SWEEPS) == set(btob._btob._sweeps), "a sweep without a small case in test_round_trip.CASES"
    assert set(btob._btob._sweeps) < set(btob._btob._estimators), "the sweeps are some of the estimated functions"


@pytest.mark.parametrize("function", SWEEPS)
def test_resume_gives_the_run_and_removes_its_file(function, tmp_path):
    cp = tmp_path / f"{function}.checkpoint"
    fn = getattr(btob, function)
    same_arrays(fn(threads=1, resume=cp, **CASES[function]), fn(threads=1, **CASES[function]))
    assert not cp.exists()


def test_resume_is_only_for_sweeps():
    with pytest.raises(TypeError, match="resume"):
        btob.lyapunov(r=0.2, point="1,-0.5,-1.1", iterations=100, resume="x.checkpoint")
