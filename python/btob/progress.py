# SPDX-License-Identifier: GPL-3.0-or-later
"""Progress of a run: progress=True shows a tqdm bar (python3-tqdm; nothing when it is not installed), a callable
receives (done, total), False shows nothing.  The compiled module calls the callable from the waiting thread with
the GIL held, at most every 50 ms."""
import contextlib


@contextlib.contextmanager
def sink(progress, label):
    if progress is None or progress is False:
        yield None
        return
    if callable(progress):
        yield progress
        return
    if progress is not True:
        raise ValueError(f"progress: got {progress!r}, expected True, False or a callable(done, total)")
    try:
        from tqdm.auto import tqdm
    except ImportError:  # tqdm is optional
        yield None
        return
    bar = tqdm(total=0, desc=label, unit="", leave=False)

    def update(done, total):
        if bar.total != total:
            bar.total = total
        bar.n = done
        bar.refresh()

    try:
        yield update
    finally:
        bar.close()
