#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python package as a dependency: a fresh virtual environment (with the system's numpy, matplotlib, h5py),
# `pip install --no-build-isolation --no-deps .` from the source tree, then, from a folder outside it, import btob
# (which must come from the environment, with its data files), run a computation and draw its figure;
# btob.__version__ must be the version of the command line.
# The wheel's module comes from this CMake build (BTOB_CMAKE_BUILD_DIR, setup.py), copied, never rebuilt: the package
# is assembled by the same rules as a fresh `pip install .`, without compiling the libraries a second time, and the
# build tree the other tests use is left as it is.
# Usage: install_python.sh BUILD_DIR SOURCE_DIR WORK_DIR BTOB_EXE PYTHON (the interpreter the module was built for,
# Debian's /usr/bin/python3)
set -euo pipefail
build=$1 src=$2 work=$3 exe=$4 python=$5
rm -rf "$work" && mkdir -p "$work/outside"
unset PYTHONPATH BTOB_DATA_DIR
export PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_NO_INDEX=1  # no network: everything is local
module_stamp() { stat -c '%n %s %Y' "$build"/python/btob/_btob*.so; }
before=$(module_stamp)
"$python" -m venv --system-site-packages "$work/venv"
(cd "$src" && BTOB_CMAKE_BUILD_DIR="$build" "$work/venv/bin/pip" install --no-build-isolation --no-deps . \
  > "$work/pip.log" 2>&1) || { cat "$work/pip.log"; exit 1; }
tail -n 1 "$work/pip.log"
[ "$(module_stamp)" = "$before" ] || { echo "install_python: pip rebuilt the build tree's module"; exit 1; }
cd "$work/outside"
"$work/venv/bin/python" - "$work/venv" "$exe" <<'PY'
import os, subprocess, sys
venv, exe = sys.argv[1], sys.argv[2]
import btob
where = os.path.dirname(btob.__file__)
assert where.startswith(os.path.realpath(venv)) or where.startswith(venv), f"btob imported from {where}, not the venv"
for sub in ("data/plot/attractors_basins.py", "data/plot/plotlib.py", "data/reference"):
    assert os.path.exists(os.path.join(where, sub)), f"{sub} missing from the installed package"
assert os.listdir(os.path.join(where, "data/reference")), "no reference table in the installed package"
line = subprocess.run([exe, "--version"], check=True, capture_output=True, text=True).stdout.split()
assert line[1] == btob.__version__, f"btob.__version__ {btob.__version__} != btob --version {line[1]}"
lyap = btob.lyapunov(r=0.3, point=(1, 0.2, -0.5), iterations=20000)
print("lyapunov:", {k: lyap.attrs[k] for k in ("lambda1", "lambda2")})
res = btob.basins(r=0.3, grid="sphere:24x24", replicates=0)
fig = res.plot()
fig.savefig("basins.png")
assert os.path.getsize("basins.png") > 10000, "the figure is empty"
print(f"btob {btob.__version__} from {where}: lyapunov, basins and their figure ok")
PY
