# SPDX-License-Identifier: GPL-3.0-or-later
# Flags for the hot kernel's translation units only (see DESIGN.md, perf-notes).
#  -fno-trapping-math : lets GCC 12 if-convert the branch-free matrix selection (else 15x slower)
#  -fno-math-errno    : sqrt/fabs vectorise
#  -march=native      : the build host's instruction set (BTOB_KERNEL_ARCH=native)
#  -mprefer-vector-width=512 : GCC 12 tunes Zen 4/5 as znver3 and would otherwise use 256-bit vectors
# None of these changes results: no -ffast-math, no reassociation, no contraction across statements
# beyond what the default -ffp-contract=fast of GNU C++ already allows everywhere (FMA is enabled by
# -march=native, which is why batched-vs-scalar tests compare symbols on converging orbits and
# distributions on chaotic ones).
include(CheckCXXSourceCompiles)
set(BTOB_KERNEL_FLAGS -fno-trapping-math -fno-math-errno)
if(BTOB_KERNEL_ARCH STREQUAL "native")
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag("-march=native" BTOB_HAS_MARCH_NATIVE)
  if(BTOB_HAS_MARCH_NATIVE)
    list(APPEND BTOB_KERNEL_FLAGS -march=native)
    set(CMAKE_REQUIRED_FLAGS "-march=native")
    check_cxx_source_compiles("
      #ifndef __AVX512F__
      #error no avx512
      #endif
      int main() { return 0; }" BTOB_HOST_HAS_AVX512)
    unset(CMAKE_REQUIRED_FLAGS)
    if(BTOB_HOST_HAS_AVX512)
      list(APPEND BTOB_KERNEL_FLAGS -mprefer-vector-width=512)
    endif()
  else()
    message(WARNING "compiler does not accept -march=native: kernel built for the generic target")
  endif()
elseif(NOT BTOB_KERNEL_ARCH STREQUAL "generic")
  message(FATAL_ERROR "BTOB_KERNEL_ARCH must be native or generic, got '${BTOB_KERNEL_ARCH}'")
endif()

# btob_kernel_sources(<target> <file>...): compile these files with the kernel flags (and without the target's
# precompiled header, built without them: cmake/PrecompiledHeaders.cmake).
function(btob_kernel_sources target)
  target_sources(${target} PRIVATE ${ARGN})
  set_source_files_properties(${ARGN} TARGET_DIRECTORY ${target}
                              PROPERTIES COMPILE_OPTIONS "${BTOB_KERNEL_FLAGS}" SKIP_PRECOMPILE_HEADERS ON)
endfunction()
