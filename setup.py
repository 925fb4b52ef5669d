# SPDX-License-Identifier: GPL-3.0-or-later
"""pip install . : the Python package btob (python/btob) with its compiled module btob._btob, the plot scripts and
the paper's reference tables (btob/data/), built by CMake: the same CMakeLists.txt, compilers and flags as the
command line, so the package computes what `btob` computes.

    python3 -m venv --system-site-packages ENV && ENV/bin/pip install --no-build-isolation .

The backend is setuptools (Debian's python3-setuptools, python3-wheel: no network), its build_ext step replaced by
CMake: setuptools knows the package, its metadata and the wheel; CMake knows how to compile the module.
--no-build-isolation uses the installed setuptools instead of downloading one.

Where the module comes from:
  BTOB_CMAKE_BUILD_DIR=<folder>  an existing, built CMake build of this source tree (e.g. build/release, for
                                 packagers and the tests): its module is copied as it is, never rebuilt (a rebuild
                                 would relink it with a newer git commit than the build's command line, and under
                                 a running test suite replace the module its tests import); its version and Python
                                 ABI must match this source and interpreter.
  unset                          a fresh CMake build in build/python/cmake of the module alone (tests, benchmarks
                                 and MPI off; the module libraries it links compiled once, several minutes).
  BTOB_CMAKE_ARGS="-D..."        more arguments for that configure (e.g. -DBTOB_KERNEL_ARCH=generic).
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_BASE = os.path.join("build", "python")  # setuptools' folders, next to CMake's build/<preset>


def cmake_version():
    """The one version of btob: CMakeLists.txt's project(btob VERSION x.y.z)."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"project\(btob\s+VERSION\s+([0-9][0-9.]*)", f.read())
    if not m:
        sys.exit("setup.py: no project(btob VERSION ...) in CMakeLists.txt")
    return m.group(1)


def built_version(build_dir):
    """The version a CMake build folder was configured with (its generated/btob/build_info.hpp)."""
    path = os.path.join(build_dir, "generated", "btob", "build_info.hpp")
    try:
        with open(path, encoding="utf-8") as f:
            m = re.search(r'version = "([^"]*)"', f.read())
    except OSError:
        m = None
    return m.group(1) if m else None


class CMakeBuild(build_ext):
    """build_ext by CMake: the target _btob of a CMake build, then the assembled package folder
    (<build>/python/btob: _btob*.so and data/) copied into setuptools' build folder."""

    def build_extension(self, ext):
        build_dir = os.environ.get("BTOB_CMAKE_BUILD_DIR")
        if build_dir:
            build_dir = os.path.abspath(build_dir)
            if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
                sys.exit(f"setup.py: BTOB_CMAKE_BUILD_DIR={build_dir} is not a CMake build folder (no CMakeCache.txt)")
        else:
            build_dir = os.path.join(ROOT, BUILD_BASE, "cmake")
            self.configure(build_dir)
            subprocess.check_call(["cmake", "--build", build_dir, "--target", "_btob"])
        version = built_version(build_dir)
        if version != cmake_version():
            sys.exit(f"setup.py: the CMake build {build_dir} is version {version}, this source {cmake_version()}: "
                     "reconfigure it (cmake -S . -B <build>) or unset BTOB_CMAKE_BUILD_DIR")
        self.copy_package(os.path.join(build_dir, "python", "btob"), os.path.dirname(self.get_ext_fullpath(ext.name)))

    def configure(self, build_dir):
        args = ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DBTOB_BUILD_TESTS=OFF",
                "-DBTOB_BUILD_BENCHMARKS=OFF", "-DBTOB_MPI=OFF", "-DBTOB_PYTHON=ON",
                f"-DPython3_EXECUTABLE={sys.executable}", f"-DPYTHON_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        if os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            args = [a for a in args if a not in ("-G", "Ninja")]  # an existing folder keeps its generator
        subprocess.check_call(args + shlex.split(os.environ.get("BTOB_CMAKE_ARGS", "")))

    def copy_package(self, src, dst):
        """The compiled module for this interpreter and the data files, from CMake's package folder."""
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        module = os.path.join(src, "_btob" + suffix)
        if not os.path.exists(module):
            found = [os.path.basename(p) for p in glob.glob(os.path.join(src, "_btob*"))]
            if not found:
                sys.exit(f"setup.py: no compiled module in {src}: build it first (cmake --build <build> --target _btob)")
            sys.exit(f"setup.py: no {os.path.basename(module)} in {src} (found {found}): the CMake build was made "
                     f"for another Python; configure it with -DPython3_EXECUTABLE={sys.executable}")
        os.makedirs(dst, exist_ok=True)
        shutil.copy2(module, os.path.join(dst, os.path.basename(module)))
        shutil.copytree(os.path.join(src, "data"), os.path.join(dst, "data"), dirs_exist_ok=True)


os.makedirs(os.path.join(ROOT, BUILD_BASE), exist_ok=True)
setup(
    name="btob",
    version=cmake_version(),
    description="Statistics lab for the b-to-b map of four one-dimensional inelastic hard spheres",
    long_description=open(os.path.join(ROOT, "README.md"), encoding="utf-8").read(),
    long_description_content_type="text/markdown",
    # GPL-3.0-or-later: FFTW (GPL-2.0-or-later) is linked into the module (docs/licence.md).  An SPDX expression in
    # License (setuptools 65 has no License-Expression field yet) and the matching trove classifier; LICENSE goes
    # into the wheel's .dist-info (setuptools' default license_files).
    license="GPL-3.0-or-later",
    license_files=["LICENSE"],
    classifiers=["License :: OSI Approved :: GNU General Public License v3 or later (GPLv3+)",
                 "Programming Language :: C++", "Programming Language :: Python :: 3",
                 "Topic :: Scientific/Engineering :: Mathematics", "Topic :: Scientific/Engineering :: Physics"],
    python_requires=">=3.9",
    packages=["btob"],
    package_dir={"": "python"},
    ext_modules=[Extension("btob._btob", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # h5py (the plot scripts import it) is an extra: Debian's python3-h5py registers itself as the distribution
    # "h5py.-debian-h5py-serial", so a requirement "h5py" is never satisfied by it and pip would look for h5py on
    # the network.  In a --system-site-packages environment on Debian it is present; elsewhere: pip install .[hdf5]
    install_requires=["numpy", "matplotlib"],
    extras_require={"hdf5": ["h5py"], "progress": ["tqdm"]},
    zip_safe=False,  # the plot scripts are run from the package's folder
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
)
