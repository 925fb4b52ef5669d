# SPDX-License-Identifier: GPL-3.0-or-later
"""Figures of btob results, drawn by the command line's own scripts (analyses/plot/*.py, shipped in btob/data/plot).
Most scripts have draw(f) -> matplotlib Figure for an h5py-like f, which a Result stands in for here.  The scripts
of strip_orbits, pattern_curves and pattern_atlas read the saved HDF5 file, as the command line runs them:
for those, plot() saves the result to a temporary folder exactly as the command line writes it, runs the script as
the command line does and returns a figure showing the PNGs it wrote, pixel for pixel."""
import importlib
import os
import sys
import tempfile

import numpy as np

PLOT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "plot")


class H5View:
    """A Result seen as an h5py.File by the plot scripts: f[name][...], name in f, f.keys(), f.attrs.  Its string
    datasets (res.texts: word names, methods) are numpy arrays of str here, where h5py gives byte strings."""

    def __init__(self, res):
        self._res = res
        self.attrs = res.attrs

    def __getitem__(self, name):
        if name not in self:
            raise KeyError(name)
        v = getattr(self._res, name)
        return np.array(v, dtype=object) if name in self._res.texts else v

    def __contains__(self, name):
        return name in self._res.arrays or name in self._res.texts

    def keys(self):
        return list(self._res.arrays) + list(self._res.texts)


def script(name):
    """The plot module analyses/plot/<name> (imported from the package's copy)."""
    if PLOT_DIR not in sys.path:
        sys.path.insert(0, PLOT_DIR)
    return importlib.import_module(os.path.splitext(name)[0])


def plot(res):
    """The command line's figure of this result (a matplotlib Figure, not saved)."""
    if not res.plot_script:
        raise NotImplementedError(f"btob.{res.function}: the command line draws no figure from this result alone")
    if res.plots_from_files:
        return figure_of_files(res)
    return script(res.plot_script).draw(H5View(res))


def figure_of_files(res):
    """The PNGs the command line's script writes for this result, stacked in one Figure at their own pixel size."""
    import matplotlib.image
    import matplotlib.pyplot as plt

    with tempfile.TemporaryDirectory(prefix="btob-plot-") as d:
        written = res._save(d, res.attrs.get("name") or "result", "", True)
        images = [matplotlib.image.imread(p) for p in sorted(written) if p.endswith(".png")]
    if not images:
        raise RuntimeError(f"btob.{res.function}: {res.plot_script} wrote no figure")
    dpi = 100
    width = max(im.shape[1] for im in images)
    height = sum(im.shape[0] for im in images)
    fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    top = 1.0
    for im in images:
        h = im.shape[0] / height
        ax = fig.add_axes([0, top - h, im.shape[1] / width, h])
        ax.imshow(im, interpolation="none")
        ax.set_axis_off()
        top -= h
    fig.btob_images = images  # the command line's pixels, for comparison
    return fig


def savefig(res, path, dpi=None):
    """Saves the figure of this result to `path` (PNG, PDF, ...)."""
    fig = plot(res)
    fig.savefig(path, **({"dpi": dpi} if dpi else {}))
    return path


def save(res, out, name=None, title="", plot=True):
    """Writes the result as the command line does, into the folder `out`: NAME.h5 (the arrays with units, axes and
    descriptions; the attributes), NAME.json (the attributes and the request: `btob run out/NAME.json` reproduces
    the numbers), the CSV tables of results that have them in the library (res.tables: strip_orbits,
    pattern_curves, pattern_atlas) and the command line's figure(s), all together or none.  Returns the paths
    written."""
    return res._save(str(out), name or res.attrs["name"], title, bool(plot))


__all__ = ["plot", "save", "savefig", "script", "H5View", "np"]
