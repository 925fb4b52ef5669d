#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian package: `cpack -G DEB` makes btob_<version>_amd64.deb; unpacked with dpkg-deb -x into a folder, its
# command runs, its Python package imports from there (with its data files), its headers, library and CMake package
# are in place; lintian reports no error (its warnings are printed).  The Python package is Debian's python3's
# (/usr/bin/python3, which reads /usr/lib/python3/dist-packages).
# Usage: install_deb.sh BUILD_DIR WORK_DIR VERSION WITH_PYTHON (1 when the build has the Python package)
set -euo pipefail
build=$1 work=$2 version=$3 with_python=$4
rm -rf "$work" && mkdir -p "$work/outside"
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/cpack" > "$work/cpack.log" 2>&1) \
  || { cat "$work/cpack.log"; exit 1; }
deb=$work/cpack/btob_${version}_amd64.deb
[ -f "$deb" ] || { echo "install_deb: no $deb"; ls "$work/cpack"; exit 1; }
dpkg-deb --field "$deb" Package Version Architecture Depends
root=$work/root
dpkg-deb -x "$deb" "$root"
for f in usr/bin/btob usr/share/btob/plot/bifurcation.py usr/include/btob/btob.hpp usr/lib/libbtob_core.a \
         usr/lib/cmake/btob/btobConfig.cmake usr/lib/pkgconfig/btob.pc usr/share/doc/btob/copyright; do
  [ -f "$root/$f" ] || { echo "install_deb: $f missing from the package"; exit 1; }
done
cd "$work/outside"
[ "$("$root/usr/bin/btob" --version | cut -d' ' -f2)" = "$version" ] || { echo "install_deb: btob --version"; exit 1; }
"$root/usr/bin/btob" lyapunov --r 0.3 --point 1,0.2,-0.5 --iterations 20000
if [ "$with_python" = 1 ]; then
  site=$root/usr/lib/python3/dist-packages
  for f in btob/__init__.py btob/data/plot/plotlib.py btob/data/plot/attractors_basins.py; do
    [ -f "$site/$f" ] || { echo "install_deb: $f missing from the package's dist-packages"; exit 1; }
  done
  PYTHONPATH=$site /usr/bin/python3 - "$root" "$version" <<'PY'
import os, sys
import btob
root, version = sys.argv[1], sys.argv[2]
assert btob.__file__.startswith(root), f"btob imported from {btob.__file__}"
assert btob.__version__ == version, f"btob.__version__ {btob.__version__} != {version}"
print("python:", btob.__version__, btob.lyapunov(r=0.3, point=(1, 0.2, -0.5), iterations=20000).attrs["lambda1"])
PY
fi
command -v lintian > /dev/null || { echo "install_deb: lintian is not installed (apt-get install lintian)"; exit 1; }
lintian --fail-on error --tag-display-limit 0 "$deb"
echo "install_deb: $(basename "$deb") unpacks, runs and passes lintian with no error"
