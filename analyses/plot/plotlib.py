# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared helpers of the plot scripts: Agg backend, HDF5 attributes as str, atomic PNG writes, and main(draw), the
command line `SCRIPT.py DATA.h5 OUT.png` every single-file script shares."""
import os
import sys

import matplotlib

# Agg when a plot script runs as a program (the command line); a Python session that imports the scripts (a
# notebook, btob.Result.plot) keeps its own backend.
if os.path.dirname(os.path.abspath(sys.argv[0] or ".")) == os.path.dirname(os.path.abspath(__file__)):
    matplotlib.use("Agg")


def attrs(h5obj):
    """The attributes of an h5py file or dataset, bytes decoded to str."""
    return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in h5obj.attrs.items()}


def texts(f, name):
    """A string dataset as a list of str: an h5py file gives byte strings, a btob Result (plotting.H5View) str."""
    d = f[name]
    return [t.decode() if isinstance(t, bytes) else str(t) for t in (d[()] if hasattr(d, "dtype") else d)]


def save_atomic(fig, dst, **savefig_kw):
    """Writes the figure to a temporary file beside dst (savefig_kw: matplotlib's, e.g. dpi), then renames it (no
    partial PNG)."""
    tmp = f"{dst}.tmp-{os.getpid()}.png"
    fig.savefig(tmp, **savefig_kw)
    os.replace(tmp, dst)


def main(draw, usage=None, require=None, **savefig_kw):
    """The command line every plot script shares: `SCRIPT.py DATA.h5 OUT.png` draws draw(f) of the HDF5 file and
    writes OUT.png atomically (savefig_kw: matplotlib's, e.g. dpi).  Wrong arguments exit with `usage` (else a usage
    line naming the script); a file without the dataset `require` exits naming it."""
    import h5py
    script = os.path.basename(sys.argv[0])
    if len(sys.argv) != 3:
        sys.exit(usage or f"usage: {script} DATA.h5 OUT.png")
    with h5py.File(sys.argv[1], "r") as f:
        if require and require not in f:
            sys.exit(f"{script}: {sys.argv[1]} has no dataset {require} (see the script's docstring)")
        fig = draw(f)
    save_atomic(fig, sys.argv[2], **savefig_kw)
