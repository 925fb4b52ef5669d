# SPDX-License-Identifier: GPL-3.0-or-later
# What `cmake --install <build> --prefix P` puts under P, besides the Python package (python/CMakeLists.txt):
#   bin/btob                                 the command line
#   share/btob/{plot,reference}/             its plot scripts and the paper's reference tables (io::data_file)
#   include/btob/<module>/*.hpp              the public headers, the source tree's src/ layout kept
#   include/btob/btob.hpp                    the umbrella header (every header declaring a request), btob::version()
#   include/btob/build_info.hpp              the generated provenance header
#   lib/libbtob_<module>.a                   the module libraries (static, position-independent)
#   lib/cmake/btob/btob{Config,ConfigVersion,Targets}.cmake   find_package(btob): the target btob::btob
#   lib/pkgconfig/btob.pc                    the same for pkg-config
#
# Include layout.  The headers include each other by their module path ("lyapunov/requests.hpp", "core/map.hpp") and
# the generated header as "btob/build_info.hpp".  Installed under P/include/btob/ they keep working unchanged when the
# target's include directories are P/include/btob (the module paths) and P/include (<btob/btob.hpp>,
# <btob/build_info.hpp>): no header is rewritten at install time, so the installed headers are byte for byte the ones
# the library was compiled with, and every other folder under P/include stays off the consumer's path.  The cost: the
# module folders (core/, io/, stats/...) sit on that path, so <core/map.hpp> of another library installed with the
# same name would be ambiguous; a consumer's "..."-includes of its own files are unaffected (the including file's
# folder is searched first).

# ---- the command line and its data files ---------------------------------------------------------------------
install(TARGETS btob RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${BTOB_PLOT_SCRIPTS} DESTINATION ${CMAKE_INSTALL_DATADIR}/btob/plot)
install(FILES ${BTOB_REFERENCE_TABLES} DESTINATION ${CMAKE_INSTALL_DATADIR}/btob/reference)

# ---- headers --------------------------------------------------------------------------------------------------
set(BTOB_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/btob)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/btob
        FILES_MATCHING PATTERN "*.hpp" PATTERN "cli" EXCLUDE)
install(FILES ${CMAKE_BINARY_DIR}/generated/btob/build_info.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/btob)

# The umbrella header, generated from the module folders (a new analysis is a new folder, with no edit here): every
# header of a module library that declares a request (a line "struct <Name>Request"), each with its result and run().
get_target_property(BTOB_MODULE_LIBRARIES btob_all INTERFACE_LINK_LIBRARIES)
set(BTOB_UMBRELLA_INCLUDES "#include \"core/version.hpp\"\n")
foreach(lib ${BTOB_MODULE_LIBRARIES})
  string(REGEX REPLACE "^btob_" "" module ${lib})
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/${module}/*.hpp)
  foreach(h ${headers})
    file(STRINGS ${h} requests REGEX "^struct [A-Za-z_]*Request( |{|$)")
    if(requests)
      get_filename_component(name ${h} NAME)
      string(APPEND BTOB_UMBRELLA_INCLUDES "#include \"${module}/${name}\"\n")
    endif()
  endforeach()
endforeach()
configure_file(${CMAKE_SOURCE_DIR}/cmake/btob.hpp.in ${CMAKE_BINARY_DIR}/generated/btob/btob.hpp @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/generated/btob/btob.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/btob)

# ---- the libraries and the CMake package ----------------------------------------------------------------------
# btob_all (btob::btob in this build too) is exported as btob::btob; each module library as btob::<module>.
set_target_properties(btob_all PROPERTIES EXPORT_NAME btob)
target_compile_features(btob_all INTERFACE cxx_std_20)  # the headers need C++20 (gnu++20: the float128 type)
foreach(lib ${BTOB_MODULE_LIBRARIES})
  string(REGEX REPLACE "^btob_" "" module ${lib})
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${module})
endforeach()
install(TARGETS btob_all ${BTOB_MODULE_LIBRARIES} EXPORT btobTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT btobTargets NAMESPACE btob:: DESTINATION ${BTOB_INSTALL_CMAKEDIR})
include(CMakePackageConfigHelpers)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/btobConfig.cmake.in ${CMAKE_BINARY_DIR}/btobConfig.cmake
                              INSTALL_DESTINATION ${BTOB_INSTALL_CMAKEDIR})
# 0.x: a new minor version may change the requests' fields, so only the same MAJOR.MINOR satisfies a request.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/btobConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/btobConfig.cmake ${CMAKE_BINARY_DIR}/btobConfigVersion.cmake
        DESTINATION ${BTOB_INSTALL_CMAKEDIR})

# ---- pkg-config ------------------------------------------------------------------------------------------------
# The module libraries are static and depend on each other: one linker group resolves them in any order.  The
# third-party flags come from the dependencies' own .pc files (Requires); Boost and Spectra are header-only in
# /usr/include, HDF5's C++ library has no .pc of its own (-lhdf5_cpp, found through hdf5.pc's -L).
set(BTOB_PC_LIBS "")
foreach(lib ${BTOB_MODULE_LIBRARIES})
  string(APPEND BTOB_PC_LIBS " -l${lib}")
endforeach()
file(RELATIVE_PATH BTOB_PC_PREFIX_FROM_PCDIR /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" BTOB_PC_PREFIX_FROM_PCDIR "${BTOB_PC_PREFIX_FROM_PCDIR}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/btob.pc.in ${CMAKE_BINARY_DIR}/btob.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/btob.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
