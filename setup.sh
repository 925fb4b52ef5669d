#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Debian packages btob needs (only the missing ones).  Why each: docs/install.md, "Dependencies and why each".
set -euo pipefail
packages=(
  g++ cmake ninja-build pkg-config git        # toolchain
  libeigen3-dev                               # small fixed-size matrices, QR (core, references, Lyapunov)
  libboost-dev                                # Multiprecision (gmp_rational, mpfr_float, float128), Math (root finders, intervals)
  libgmp-dev libmpfr-dev                      # exact rationals and arbitrary precision behind Boost.Multiprecision
  libfftw3-dev                                # correlation functions C_N by FFT
  libspectra-dev                              # sparse eigensolvers (Arnoldi) on Eigen for the transfer operator
  libhdf5-dev                                 # result files with their provenance attributes
  libcli11-dev libtomlplusplus-dev libfmt-dev # command line, scene files, formatting
  nlohmann-json3-dev                          # manifests: a result records its request, `btob run NAME.json` reads it back
  libgtest-dev libbenchmark-dev               # tests and benchmarks
  python3 python3-matplotlib python3-numpy python3-h5py  # plots
  python3-mpmath                              # tests: an independent 50-digit eigensolver for pattern-curves
  clang-14 libfuzzer-14-dev                   # fuzzing the parsers of user input (tests/fuzz, libFuzzer; .ci/run)
  clang-format-14                             # the C++ house style (.clang-format, tools/format.sh, the test format_check)
  python3-dev pybind11-dev python3-pybind11   # the Python package `btob` (python/), built with the library
  python3-pytest python3-nbconvert python3-ipykernel python3-tqdm  # its tests, the notebooks run as tests, progress bars
  openmpi-bin libopenmpi-dev                  # sweeps split over ranks with `mpirun` (optional at build time)
  libhdf5-openmpi-dev                         # parallel HDF5 (MPI-IO): each rank writes its own rows of NAME.h5
  python3-sphinx python3-myst-parser          # the documentation site (docs/, target `docs`): Sphinx, pages in Markdown
  python3-nbsphinx pandoc                     # the tutorials: notebooks executed in the site (pandoc renders their Markdown)
  furo                                        # the site's theme (responsive, with search)
  libjs-mathjax                               # the site's formulas: MathJax, the field's standard, copied into the site (offline)
  doxygen python3-breathe                     # the site's C++ API reference: Doxygen reads the installed headers, Breathe makes Sphinx pages of it
  chromium chromium-driver python3-selenium   # tests in a real browser (headless): the built site (label docs), the explorer's page
  libcpp-httplib-dev                          # `btob explore`: a maintained one-header HTTP server (Debian builds it as a library)
  libpng-dev                                  # `btob explore`: PNG images of the density (the reference PNG library)
  python3-setuptools python3-wheel python3-venv  # `pip install .` (setup.py: setuptools drives CMake, no network) and its test's venv
  dpkg-dev file                               # `cpack -G DEB`: dpkg-shlibdeps (and file) compute the package's Depends
  lintian                                     # the Debian package's test: lintian must report no error
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
