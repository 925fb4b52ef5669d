# SPDX-License-Identifier: GPL-3.0-or-later
# Parallel HDF5 for the MPI build of the btob executable.
#
# Debian installs the serial HDF5 (libhdf5-dev: /usr/include/hdf5/serial, libhdf5_serial*) and the Open MPI one
# (libhdf5-openmpi-dev: /usr/include/hdf5/openmpi, libhdf5_openmpi*) side by side.  One process must load only one of
# them (they export the same symbols), so the choice is per executable:
#   - btob_io links the serial library for every consumer (the library, Python, tests, benchmarks) ...
#   - ... but the parallel one for a target whose property BTOB_PARALLEL_HDF5 is ON (btob_use_parallel_hdf5): the MPI
#     build's btob, whose rank writer (src/cli/rows.cpp, its own object library) calls H5Pset_fapl_mpio.
# The two 1.10.8 builds share every header but H5pubconf.h, where the parallel one only adds declarations (the MPI-IO
# driver) and drops thread safety; io's units, compiled against the serial headers, link against either.  The
# parallel library is not thread-safe: btob calls HDF5 from one thread at a time (the main thread, or the explorer's
# export behind its lock).
option(BTOB_PARALLEL_HDF5_WANTED "Use parallel HDF5 for the MPI build's btob when libhdf5-openmpi-dev is installed" ON)
set(BTOB_PARALLEL_HDF5 OFF)
if(BTOB_MPI AND BTOB_PARALLEL_HDF5_WANTED)
  find_path(BTOB_HDF5_MPI_INCLUDE H5FDmpio.h PATHS /usr/include/hdf5/openmpi NO_DEFAULT_PATH)
  foreach(lib hdf5_openmpi hdf5_openmpi_hl hdf5_openmpi_cpp hdf5_openmpi_hl_cpp)
    find_library(BTOB_LIB_${lib} ${lib})
  endforeach()
  if(BTOB_HDF5_MPI_INCLUDE AND BTOB_LIB_hdf5_openmpi AND BTOB_LIB_hdf5_openmpi_hl AND BTOB_LIB_hdf5_openmpi_cpp)
    set(BTOB_PARALLEL_HDF5 ON)
  else()
    message(STATUS "btob: no parallel HDF5 (apt-get install libhdf5-openmpi-dev): MPI ranks send their rows to rank 0")
  endif()
endif()

# btob_link_hdf5(target): the serial HDF5 (C++ and high-level libraries), or the parallel one for consumers with
# BTOB_PARALLEL_HDF5 set (evaluated on the executable being linked).
function(btob_link_hdf5 target)
  if(NOT BTOB_PARALLEL_HDF5)
    target_link_libraries(${target} PUBLIC HDF5::HDF5 ${HDF5_HL_LIBRARIES})
    return()
  endif()
  set(parallel "$<BOOL:$<TARGET_PROPERTY:BTOB_PARALLEL_HDF5>>")
  target_include_directories(${target} PRIVATE ${HDF5_INCLUDE_DIRS})
  target_link_libraries(${target} PUBLIC "$<$<NOT:${parallel}>:HDF5::HDF5>")
  foreach(l ${HDF5_HL_LIBRARIES})
    target_link_libraries(${target} PUBLIC "$<$<NOT:${parallel}>:${l}>")
  endforeach()
  foreach(l ${BTOB_LIB_hdf5_openmpi_hl_cpp} ${BTOB_LIB_hdf5_openmpi_cpp} ${BTOB_LIB_hdf5_openmpi_hl}
            ${BTOB_LIB_hdf5_openmpi})
    target_link_libraries(${target} PUBLIC "$<${parallel}:${l}>")
  endforeach()
endfunction()

# btob_use_parallel_hdf5(exe): links `exe` against the parallel HDF5 and adds the rank writer (src/cli/rows.cpp,
# compiled against the parallel headers, which define BTOB_PARALLEL_HDF5).
function(btob_use_parallel_hdf5 exe)
  set_target_properties(${exe} PROPERTIES BTOB_PARALLEL_HDF5 ON)
  add_library(btob_rows OBJECT ${CMAKE_SOURCE_DIR}/src/cli/rows.cpp)
  target_include_directories(btob_rows PRIVATE ${BTOB_HDF5_MPI_INCLUDE} ${CMAKE_SOURCE_DIR}/src)
  target_compile_definitions(btob_rows PRIVATE BTOB_PARALLEL_HDF5=1)
  target_link_libraries(btob_rows PRIVATE MPI::MPI_CXX fmt::fmt)
  target_link_libraries(${exe} PRIVATE btob_rows)
  target_compile_definitions(${exe} PRIVATE BTOB_PARALLEL_HDF5=1)
endfunction()
