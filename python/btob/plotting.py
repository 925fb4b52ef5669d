"""Figures of btob results, drawn by the command line's own scripts (analyses/plot/*.py, shipped in btob/data/plot):
each script has draw(f) -> matplotlib Figure for an h5py-like f, which a Result stands in for here."""
import importlib
import os
import sys

import numpy as np

PLOT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "plot")


class H5View:
    """A Result seen as an h5py.File by the plot scripts: f[name][...], name in f, f.keys(), f.attrs."""

    def __init__(self, res):
        self._res = res
        self.attrs = res.attrs

    def __getitem__(self, name):
        if name not in self._res.arrays:
            raise KeyError(name)
        return getattr(self._res, name)

    def __contains__(self, name):
        return name in self._res.arrays

    def keys(self):
        return list(self._res.arrays)


def script(name):
    """The plot module analyses/plot/<name> (imported from the package's copy)."""
    if PLOT_DIR not in sys.path:
        sys.path.insert(0, PLOT_DIR)
    return importlib.import_module(os.path.splitext(name)[0])


def plot(res):
    """The command line's figure of this result (a matplotlib Figure, not saved)."""
    if not res.plot_script or not hasattr(script(res.plot_script), "draw"):
        raise NotImplementedError(f"btob.{res.function}: the command line draws no figure from this result alone")
    return script(res.plot_script).draw(H5View(res))


def savefig(res, path, dpi=None):
    """Saves the figure of this result to `path` (PNG, PDF, ...)."""
    fig = plot(res)
    fig.savefig(path, **({"dpi": dpi} if dpi else {}))
    return path


def save(res, out, name=None, title="", plot=True):
    """Writes the result as the command line does, into the folder `out`: NAME.h5 (the arrays with units, axes and
    descriptions; the attributes), NAME.json (the attributes and the request: `btob run out/NAME.json` reproduces
    the numbers) and NAME.png (the command line's figure), all together or none.  The command line's CSV tables
    are not written.  Returns the paths written."""
    return res._save(str(out), name or res.attrs["name"], title, bool(plot))


__all__ = ["plot", "save", "savefig", "script", "H5View", "np"]
