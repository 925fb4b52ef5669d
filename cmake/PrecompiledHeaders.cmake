# SPDX-License-Identifier: GPL-3.0-or-later
# Precompiled headers: the third-party and standard headers that nearly every translation unit parses through
# core/scalar.hpp (Boost.Multiprecision float128 + MPFR, ~840 headers), core/map.hpp and core/coords.hpp (Eigen),
# core/request.hpp (fmt), parsed once per group of targets instead of once per unit (4-6 s a unit).
#
# GCC uses a precompiled header only when the unit is compiled with compatible flags and macros, so the targets are
# grouped by their flags, one header per group (REUSE_FROM shares it within a group):
#   libraries   -fPIC -fopenmp          every btob_<module> library but core and io (no -fopenmp)
#   tests       -fPIE -fopenmp + gtest   every tests/test_*.cpp executable
#   cli         -fPIE -fopenmp + CLI11   the btob executable (-O1 in Release)
# Not the Python module (3 units, its own flags: the header costs 16 s, it saves 12), nor core and io (7 units),
# the benchmarks (7 units, Release only) or fuzz_replay: too few units each to pay for a header of their own.
# The units compiled with the kernel flags (btob_kernel_sources: -march=native, -fno-math-errno, ...) define other
# macros and never use one (SKIP_PRECOMPILE_HEADERS, set in cmake/KernelFlags.cmake).  CMake adds -Winvalid-pch, so
# a header GCC rejects is reported by every unit that skips it.
#
# Only headers from outside the project, which no unit configures with a macro of its own before including them;
# the project's headers stay out, so an edit to one recompiles only its users.  A unit's object is the one GCC makes
# with these headers included as text in front of it (checked byte for byte on windows/polynomial.cpp); a unit that
# did not include some of them only sees more declarations, and no unit outside the kernel is compiled with FMA or
# any value-changing floating-point option, so no result changes.  Through a precompiled header GCC 12 prints a few
# -Wstringop-overflow/-Wstringop-overread false positives inside <bits/char_traits.h> and <bits/stl_algobase.h>
# (attractors.cpp, patterns/atlas.cpp, transfer/output.cpp, windows/polynomial.cpp, Release) that it keeps quiet
# when it reads the same system header as text.
#
# With ccache: CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime.
option(BTOB_PCH "Precompiled headers for the libraries, the tests and the command line" ON)

set(BTOB_PCH_COMMON
    <boost/multiprecision/float128.hpp>
    <boost/multiprecision/mpfr.hpp>
    <Eigen/Core>
    <Eigen/Geometry>
    <fmt/format.h>
    <algorithm>
    <array>
    <atomic>
    <chrono>
    <cmath>
    <concepts>
    <cstddef>
    <cstdint>
    <cstdlib>
    <cstring>
    <functional>
    <limits>
    <map>
    <memory>
    <numbers>
    <optional>
    <stdexcept>
    <string>
    <string_view>
    <type_traits>
    <utility>
    <variant>
    <vector>)

# btob_pch_group(<owner> <reusers> <headers>...): <owner> compiles the header, the targets in the list <reusers> use it.
function(btob_pch_group owner reusers)
  target_precompile_headers(${owner} PRIVATE ${ARGN})
  foreach(t ${reusers})
    target_precompile_headers(${t} REUSE_FROM ${owner})
  endforeach()
endfunction()

function(btob_setup_pch)
  if(NOT BTOB_PCH)
    return()
  endif()
  # Libraries: btob_iterate compiles it (its two non-kernel units), every other -fopenmp library reuses it.
  set(libs)
  foreach(dir ${BTOB_MODULE_DIRS})
    get_filename_component(module ${dir} NAME)
    if(TARGET btob_${module} AND NOT module MATCHES "^(core|io|iterate)$")
      list(APPEND libs btob_${module})
    endif()
  endforeach()
  btob_pch_group(btob_iterate "${libs}" ${BTOB_PCH_COMMON})

  if(TARGET test_core)
    get_property(tests DIRECTORY ${CMAKE_SOURCE_DIR}/tests PROPERTY BUILDSYSTEM_TARGETS)
    list(FILTER tests INCLUDE REGEX "^test_")
    list(REMOVE_ITEM tests test_core)
    btob_pch_group(test_core "${tests}" <gtest/gtest.h> ${BTOB_PCH_COMMON})
  endif()

  btob_pch_group(btob "" <CLI/CLI.hpp> ${BTOB_PCH_COMMON})
endfunction()
