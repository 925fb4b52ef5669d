# SPDX-License-Identifier: GPL-3.0-or-later
"""btob in Python: the b-to-b map P_r of four one-dimensional inelastic hard spheres (Castorrini & Dolmaire).

Every analysis of the command line is a function with the same inputs (keyword arguments named as the flags, '-'
turned into '_', the same defaults and validation: bad input raises ValueError with the command line's message):

    import btob
    res = btob.bifurcation(r_min=0.0717, r_max=0.1717, r_count=500, iterations=5000, tail=100)
    res.density          # numpy array viewing the C++ result (no copy), shape (r_count, bins)
    res.attrs            # provenance and summary, the attributes the command line writes to HDF5
    res.plot()           # the command line's figure (matplotlib), returned

Building blocks: btob.Map(r).step(points), btob.iterate(r, points, iterations, record=...).
Each function also takes threads= (0: all cores) and progress= (False, True for a tqdm bar, or a callable(done,
total)); the computation runs with the GIL released and stops on Ctrl-C (KeyboardInterrupt) within 0.1 s.
"""
import functools
import os

# The plot scripts and reference tables travel inside the package (io::data_file reads BTOB_DATA_DIR first).
DATA_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
os.environ.setdefault("BTOB_DATA_DIR", DATA_DIR)

from . import _btob  # noqa: E402
from ._btob import Map, Result  # noqa: E402,F401
from . import plotting, progress as _progress  # noqa: E402

__version__ = _btob.__version__
git_commit = _btob.git_commit


def cite(format="bibtex"):
    """How to cite btob, as ``btob cite --format FORMAT`` prints it: the software at this build's version and git
    commit, and the paper whose b-to-b map it implements (R. Castorrini and T. Dolmaire, "Four collapsing
    one-dimensional particles: a dynamical system approach of the spherical billiard reduction").

    format: "bibtex" (BibTeX entries, the default), "cff" (Citation File Format, as CITATION.cff) or "text".
    Returns the text (print it); another format raises ValueError naming the accepted ones."""
    return _btob.cite(format)

# The analyses, one function per command of the command line, in the order of its declarations (the compiled
# module lists them: commands/commands.hpp declares every command once).
FUNCTIONS = list(_btob._functions)


def _default(annotation, texts):
    """A field's default as a Python value, from its text form(s) (what the command line shows): a number for a
    number, a list for a list, the text itself where the text is the value (a decimal whose text is not a float's
    shortest form keeps its text, as the field does)."""
    def one(t):
        if annotation.startswith("int"):
            return int(t)
        if "float" in annotation and annotation != "str":
            try:
                x = float(t)
            except ValueError:
                return t
            return x if repr(x) == t or repr(x) == t + ".0" else t
        return t
    if annotation.startswith("list"):
        return [one(t) for t in texts]
    if annotation == "bool":
        return texts == ["true"]
    return one(texts[0]) if texts else ""


def _signature(name):
    """inspect.Signature of a function, from the binding's fields (name, annotation, default, required): every
    keyword is keyword-only, a required one without a default; then threads, progress (and resume for a sweep)."""
    import inspect
    fields, sweep = _btob._signatures[name]
    kw = inspect.Parameter.KEYWORD_ONLY
    params = [inspect.Parameter(k, kw, annotation=a, default=inspect.Parameter.empty if req else _default(a, texts))
              for k, a, texts, req in fields]
    params += [inspect.Parameter("threads", kw, annotation="int", default=0),
               inspect.Parameter("progress", kw, annotation="bool | Callable[[int, int], None]", default=False)]
    if sweep:
        params.append(inspect.Parameter("resume", kw, annotation="str | None", default=None))
    return inspect.Signature(params, return_annotation="btob.Result")


def _wrap(name):
    fn = getattr(_btob, name)

    @functools.wraps(fn)
    def call(**kwargs):
        with _progress.sink(kwargs.pop("progress", False), name) as cb:
            return fn(progress=cb, **kwargs)

    # help(), IDE completion and Jupyter's shift-tab read __signature__ (the compiled function only says **kwargs).
    call.__signature__ = _signature(name)
    return call


for _name in FUNCTIONS:
    globals()[_name] = _wrap(_name)
del _name

def estimate(function, **kwargs):
    """The cost of a request before it runs: ``btob.estimate("bifurcation", r_count=10**6, ...)`` or
    ``btob.estimate(btob.lyapunov, r=0.2, point="1,-0.5,-1.1", iterations=10**10)`` takes the function (or its name)
    and its keywords and returns a dict; nothing is written.

    A sweep runs a sample of the request's own items (spread over the sweep; 32 items and 0.2 s, or 1 s) and
    returns: items, sampled, sample_seconds, predicted_seconds (the whole request on this machine with these
    threads), bytes (the result's data) and peak_bytes.

    Any other request counts its work from its keywords and prices it with a rate per route (map steps of the
    double derivative cocycle, particle collisions in MPFR at D digits, ...), measured once by a ~0.1 s fixed probe
    run and cached in $XDG_CACHE_HOME/btob/rates.json (~/.cache/btob/rates.json), keyed by btob version and commit,
    CPU model, threads and route.  It returns: terms (a list of dicts: route, units, what, units_per_second, cached),
    predicted_seconds, threads, upper_bound (why the count is an upper bound, or ""), bytes (the data the result
    writes, figures excluded) and peak_bytes.  The functions: ``sorted(btob._btob._estimators)``; others raise
    ValueError."""
    name = getattr(function, "__name__", function)
    if name not in _btob._estimators:
        raise ValueError(f"estimate: got {name!r}, expected one of {', '.join(sorted(_btob._estimators))}")
    return _btob._estimators[name](**kwargs)


Result.plot = plotting.plot
Result.save = plotting.save
Result.savefig = plotting.savefig


def iterate(r, points, iterations, record="tail", coord="theta", tail=None, precision="double", threads=0,
            progress=False):
    """Iterate every point at every r with the batched kernel (src/iterate) and keep what `record` says.

    r: one value in (0, 1) or a sequence of them; points: (N, 3) array of directions x,y,z (x*z <= 0), or one (3,).

    - record="tail": the coordinate `coord` (theta, log10-theta, phi, w1, w2; radians) of the last `tail` states,
      shape (N, tail) (or (R, N, tail) for a sequence of r), float64;
    - record="symbols": the branch 1/2/3 of the last `tail` steps, same shape, uint8;
    - record="final": the final direction (unit vector), shape (N, 3) (or (R, N, 3));
    - record="orbit": the whole orbit over the last `tail` steps from ONE kernel run, a dict of arrays of the tail's
      shape: "x", "y", "z" the state after each step normalised to a unit vector (float64; the last column is
      record="final" bit for bit), "branch" the branch 1/2/3 that step took (uint8; record="symbols"), "theta" and
      "phi" its angles in radians (record="tail" with coord="theta" / "phi", bit for bit).

    tail defaults to min(100, iterations).  precision: float, double or long-double.  threads: OpenMP threads (0:
    all cores); progress: False, True (a tqdm bar) or a callable(done, total).  The arrays own their data (no copy
    was made from the kernel's buffers).
    """
    if tail is None:
        tail = min(100, int(iterations))
    threads = _btob._check_threads(threads)  # the compiled functions' check and wording
    with _progress.sink(progress, "iterate") as cb:
        return _btob._iterate(r, points, int(iterations), record, coord, int(tail), precision, threads, cb)
