#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The C++ library as a dependency: `cmake --install BUILD --prefix P`, then examples/cpp configured as a separate
# project with CMAKE_PREFIX_PATH=P (find_package(btob), btob::btob), built and run; the same main built a second time
# with the flags of P's btob.pc (pkg-config) must print the same lines.  Nothing of the source or build tree may be
# on the example's compile line: it sees only P.
# Usage: install_cpp.sh BUILD_DIR SOURCE_DIR WORK_DIR VERSION
set -euo pipefail
build=$1 src=$2 work=$3 version=$4
rm -rf "$work" && mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in bin/btob share/btob/plot/bifurcation.py include/btob/btob.hpp include/btob/build_info.hpp \
         include/btob/lyapunov/requests.hpp include/btob/core/version.hpp lib/libbtob_core.a \
         lib/cmake/btob/btobConfig.cmake lib/cmake/btob/btobConfigVersion.cmake lib/cmake/btob/btobTargets.cmake \
         lib/pkgconfig/btob.pc; do
  [ -f "$prefix/$f" ] || { echo "install_cpp: $f missing under the prefix"; exit 1; }
done
# As before: the Python package in the prefix's site-packages (when the build has it), its data files inside.
if [ -f "$build/python/btob/__init__.py" ]; then
  ls "$prefix"/lib/python3*/site-packages/btob/data/plot/plotlib.py > /dev/null \
    || { echo "install_cpp: no Python package in the prefix's site-packages"; exit 1; }
fi

# CMake: the example as its own project.
cmake -S "$src/examples/cpp" -B "$work/cmake" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$work/configure.log"
cmake --build "$work/cmake" > "$work/build.log" || { cat "$work/build.log"; exit 1; }
# Its compile and link lines name the prefix only: no header folder of the source or build tree, no library of the
# build tree, not the build's BTOB_SOURCE_DIR.
for tree in "$src/src" "$build/generated" "$build/src/" "BTOB_SOURCE_DIR"; do
  if grep -q -- "$tree" "$work/cmake/compile_commands.json" "$work/cmake/build.ninja"; then
    echo "install_cpp: the example's build names $tree (it must see the installed tree only):"
    grep -- "$tree" "$work/cmake/compile_commands.json" "$work/cmake/build.ninja"
    exit 1
  fi
done
(cd "$work" && "$work/cmake/btob_example") > "$work/cmake.out"
cat "$work/cmake.out"
head -n 1 "$work/cmake.out" | grep -qx "btob $version" || { echo "install_cpp: btob::version() is not $version"; exit 1; }
grep -q "^lyapunov .*lambda1 = " "$work/cmake.out" && grep -q "^basins .* attractors" "$work/cmake.out" \
  || { echo "install_cpp: the example printed no Lyapunov or basins result"; exit 1; }

# pkg-config: the same main, compiled and linked with btob.pc's flags only.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
[ "$(pkg-config --modversion btob)" = "$version" ] || { echo "install_cpp: btob.pc's version is not $version"; exit 1; }
# shellcheck disable=SC2046  # the flags are words
${CXX:-c++} -O2 "$src/examples/cpp/main.cpp" -o "$work/example_pc" $(pkg-config --cflags --libs btob)
(cd "$work" && "$work/example_pc") > "$work/pkgconfig.out"
diff "$work/cmake.out" "$work/pkgconfig.out" || { echo "install_cpp: the pkg-config build printed other lines"; exit 1; }
echo "install_cpp: the installed library builds and runs through find_package(btob) and pkg-config"
