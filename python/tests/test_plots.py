# SPDX-License-Identifier: GPL-3.0-or-later
"""res.plot() draws the command line's figure from the result itself (the plot scripts' draw(f) on the result
seen as an h5py file): every function with a figure returns a matplotlib Figure with the script's axes and title."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
import matplotlib.pyplot  # noqa: E402
import pytest  # noqa: E402

import btob  # noqa: E402

CASES = [
    ("bifurcation", dict(r_min=0.1, r_max=0.12, r_count=30, iterations=300, tail=30, overlay=["windows"])),
    ("lyapunov_map", dict(r_min=0.1, r_max=0.2, r_count=6, grid="random:3", iterations=800, transient=80)),
    ("lyapunov_strip", dict(r=0.3, grid="strip:8x5", iterations=500, transient=50)),
    ("hyperbolicity", dict(r=0.2, grid="strip:16x8")),
    ("hyperbolicity_orbits", dict(r_min=0.1, r_max=0.2, r_count=3, grid="random:3", iterations=300, transient=100,
                                  backward=100)),
    ("basins", dict(r=0.2, grid="strip:12x10", replicates=0, transient=500, iterations=300, lyap_iterations=400,
                    lyap_transient=100)),
    ("basins_r", dict(r_values=[0.2, 0.3], grid="random:8", transient=500, iterations=300, lyap_iterations=400,
                      lyap_transient=100, boundary_grid="sphere:24x20")),
    # long enough for three windows above the noise floor: the fit and its verdict are drawn
    ("correlate", dict(r=0.11, point=(1.0, -0.5, -1.1), n_max=400, iterations=1000000)),
    ("measure", dict(r=0.2, grid="random:3", iterations=2000, transient=100, bins=16)),
]


@pytest.mark.parametrize("function,kwargs", CASES, ids=[c[0] for c in CASES])
def test_plot_returns_the_scripts_figure(function, kwargs, tmp_path):
    res = getattr(btob, function)(**kwargs)
    fig = res.plot()
    assert isinstance(fig, matplotlib.figure.Figure) and fig.axes
    assert any(ax.get_title() or ax.get_xlabel() for ax in fig.axes)
    res.savefig(tmp_path / "f.png")
    assert (tmp_path / "f.png").stat().st_size > 10000


def test_results_without_a_figure_say_so():
    res = btob.windows_thresholds()
    with pytest.raises(NotImplementedError, match="draws no figure"):
        res.plot()


def test_bifurcation_figure_is_the_command_lines_pixel_for_pixel(tmp_path):
    import subprocess

    import matplotlib.image as mpimg
    import numpy as np
    from conftest import exe, flags
    kw = dict(r_min=0.1, r_max=0.13, r_count=120, iterations=600, tail=60, overlay=["thresholds", "windows"])
    p = subprocess.run([exe(), "bifurcation"] + flags(kw) + ["--out", str(tmp_path), "--quiet"], capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stderr
    btob.bifurcation(**kw).savefig(tmp_path / "py.png", dpi=150)  # the script's figure dpi
    a, b = mpimg.imread(tmp_path / "bifurcation.png"), mpimg.imread(tmp_path / "py.png")
    assert a.shape == b.shape and np.array_equal(a, b)


# Results whose scripts read the command line's files (tables, manifest): the figure is the command line's PNGs.
FILE_CASES = [
    ("strip_orbits", "strip-orbits", dict(r=0.2, orbits=3, iterations=2000, tail=200, seed=3)),
    ("pattern_curves", "pattern-curves", dict(word="132312", r_min=0.3, r_max=0.6, r_count=60)),
    ("pattern_atlas", "pattern atlas", dict(max_length=6)),
]


@pytest.mark.parametrize("function,command,kwargs", FILE_CASES, ids=[c[0] for c in FILE_CASES])
def test_figures_from_files_are_the_command_lines_pixel_for_pixel(function, command, kwargs, tmp_path):
    import subprocess

    import matplotlib.image as mpimg
    import numpy as np
    from conftest import exe, flags
    res = getattr(btob, function)(**kwargs)
    name = res.attrs["name"]
    p = subprocess.run([exe()] + command.split() + flags(kwargs) + ["--out", str(tmp_path), "--quiet"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    cli_pngs = sorted(tmp_path.glob("*.png"))
    fig = res.plot()
    assert isinstance(fig, matplotlib.figure.Figure) and len(fig.btob_images) == len(cli_pngs) >= 1
    for got, path in zip(fig.btob_images, cli_pngs):
        want = mpimg.imread(path)
        assert got.shape == want.shape and np.array_equal(got, want), path.name
    matplotlib.pyplot.close(fig)
    # save() writes the command line's tables with the same bytes.
    saved = res.save(tmp_path / "py", name=name, plot=False)
    tables = [f for f in saved if f.endswith(".csv")]
    assert tables and sorted(os.path.basename(f) for f in tables) == sorted(res.tables)
    for f in tables:
        assert open(f).read() == (tmp_path / os.path.basename(f)).read_text(), f


# Scripts that once needed a CSV or the manifest beside the HDF5 file: each runs alone on the HDF5 file, in a folder
# holding nothing else, as `python3 analyses/plot/SCRIPT.py NAME.h5 OUT` (OUT a PNG, or a folder for pattern_curves' figures).
ALONE = [
    ("strip-orbits", "strip_orbits.py", ["--r", "0.2", "--orbits", "3", "--iterations", "1500", "--tail", "200"]),
    ("pattern-curves", "pattern_curves.py", ["--word", "132312", "--r-min", "0.3", "--r-max", "0.6", "--r-count", "60"]),
    ("transfer", "transfer.py", ["--r", "0.21", "--boxes", "16x16", "--samples", "4", "--eigenvalues", "4",
                                 "--measure-orbits", "2", "--measure-iterations", "200", "--tv-bins", "8"]),
    ("transfer", "transfer.py", ["--r", "0.21", "--boxes", "16x16", "--samples", "4", "--eigenvalues", "0",
                                 "--tv-bins", "8", "--cycle", "1322"]),
    ("lyapunov-map", "orbit_attractors.py", ["--r-min", "0.1", "--r-max", "0.2", "--r-count", "6", "--grid", "random:4",
                                             "--iterations", "600", "--transient", "100", "--attractors"]),
    ("transfer-r", "transfer_r.py", ["--r-min", "0.15", "--r-max", "0.3", "--r-count", "3", "--boxes", "12x12",
                                     "--samples", "2", "--eigenvalues", "4"]),
    ("pattern atlas", "patterns_atlas.py", ["--max-length", "5", "--ics", "20", "--iterations", "400", "--tail", "100",
                                            "--max-period", "50"]),
    ("pattern atlas", "patterns_feasible.py", ["--feasible", "--max-length", "3"]),
    ("windows precision", "windows_precision.py", ["--n", "2..6"]),
    ("particles", "particles.py", ["1133", "--r", "0.15", "--periods", "3"]),
    ("basins", "attractors_basins.py", ["--r", "0.2", "--grid", "strip:12x10", "--replicates", "0", "--transient", "300",
                                        "--iterations", "300", "--lyap-iterations", "400", "--lyap-transient", "50"]),
]


@pytest.mark.parametrize("command,script,args", ALONE, ids=[f"{a[1]}-{i}" for i, a in enumerate(ALONE)])
def test_plot_script_runs_alone_on_its_hdf5(command, script, args, tmp_path):
    import glob
    import shutil
    import subprocess
    import sys

    from conftest import ROOT, exe
    p = subprocess.run([exe()] + command.split() + args + ["--out", str(tmp_path / "run"), "--name", "x", "--no-plot",
                                                   "--quiet"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    alone = tmp_path / "alone"
    alone.mkdir()
    shutil.copy(tmp_path / "run" / "x.h5", alone / "x.h5")  # the HDF5 file and nothing else
    many = script in ("pattern_curves.py", "particles.py")  # scripts that write several figures into a folder
    out = alone / "figures" if many else alone / "x.png"
    if many:
        out.mkdir()
    p = subprocess.run([sys.executable, os.path.join(ROOT, "analyses", "plot", script), str(alone / "x.h5"), str(out)],
                       capture_output=True, text=True, cwd=alone)
    assert p.returncode == 0, p.stderr
    pngs = glob.glob(str(out / "*.png")) if many else [str(out)]
    assert pngs and all(os.path.getsize(f) > 10000 for f in pngs)
