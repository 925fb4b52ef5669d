# SPDX-License-Identifier: GPL-3.0-or-later
# `cpack -G DEB` in a build folder (after `cmake --build`): btob_<version>_amd64.deb, one package with everything
# `cmake --install` installs under /usr (the command, its plot scripts and reference tables, the library, its
# headers, CMake and pkg-config packages) and the Python package in Debian's /usr/lib/python3/dist-packages.
#
# Depends: the shared libraries the command and the Python module load, as dpkg-shlibdeps finds them (libhdf5,
# libfftw3, libmpfr, libgomp, Open MPI when built with it...), and the Python modules the package and the plot
# scripts import.  Suggests: the -dev packages a C++ program that uses the installed library also needs (its headers
# include Eigen, Boost, fmt...; btobConfig.cmake finds them): the command and the Python package do not.
#
# The package carries the kernel the build was configured with: configure with -DBTOB_KERNEL_ARCH=generic (the
# generic preset) for a package that runs on any x86-64, the default (native) only on machines like the build host.
set(BTOB_DEB_MAINTAINER "btob maintainers <btob-maintainers@example.org>"
    CACHE STRING "Maintainer field of the Debian package (cpack -G DEB): the packager's name and address")

set(CPACK_PACKAGE_NAME btob)
# The licence (LICENSE, docs/licence.md says why): GPL-3.0-or-later, as FFTW (GPL-2.0-or-later) is linked into every
# binary.  A Debian control file has no licence field: the package states it in /usr/share/doc/btob/copyright
# (cmake/debian/copyright, machine-readable DEP-5, pointing at /usr/share/common-licenses/GPL-3); the SPDX
# identifier is kept here for CPack's other generators (tests/metadata_check.py checks every place agrees).
set(BTOB_LICENSE "GPL-3.0-or-later")
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)
set(CPACK_RPM_PACKAGE_LICENSE ${BTOB_LICENSE})
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "statistics lab for the b-to-b map of four 1-D inelastic hard spheres")
# The extended description: CPack puts the summary first, indents every line and marks the empty one (" .").
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "btob iterates the b-to-b map P_r of four one-dimensional inelastic hard
spheres (the spherical billiard reduction of Castorrini and Dolmaire) in float,
double, long double, float128 or MPFR precision, and runs its analyses:
bifurcation diagrams, Lyapunov exponents, attractors and their basins, periodic
patterns, stability windows, correlations and the transfer operator.

The package holds the command btob, its plot scripts, the Python package btob,
and the C++ library with its headers and its CMake and pkg-config packages.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # <name>_<version>_<architecture>.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${BTOB_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy, python3-matplotlib, python3-h5py")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "g++, cmake, pkg-config, libeigen3-dev, libspectra-dev, libboost-dev, libfmt-dev, \
nlohmann-json3-dev, libtomlplusplus-dev, libhdf5-dev, libfftw3-dev, libmpfr-dev, libgmp-dev")
set(CPACK_STRIP_FILES ON)

# Components: the Python package is installed twice, into the prefix's site-packages by `cmake --install`
# (component python) and into Debian's dist-packages for the package only (python_deb, python/CMakeLists.txt); the
# Debian documentation files likewise (deb_doc).  Everything else is the component Unspecified.  One package
# holds the listed components.
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_COMPONENTS_ALL Unspecified deb_doc)
if(TARGET _btob)
  list(APPEND CPACK_COMPONENTS_ALL python_deb)
endif()

# /usr/share/doc/btob: the copyright file (DEP-5, cmake/debian/copyright), the Debian changelog (one entry per
# version, dated as CHANGELOG.md's entry of this version) and CHANGELOG.md, both gzipped with no timestamp (Debian
# policy 12.5, 12.7).
file(STRINGS ${CMAKE_SOURCE_DIR}/CHANGELOG.md entry REGEX "^## \\[${PROJECT_VERSION}\\] - [0-9-]+")
string(REGEX MATCH "[0-9]+-[0-9]+-[0-9]+" BTOB_DEB_DAY "${entry}")
if(NOT BTOB_DEB_DAY)
  message(WARNING "CHANGELOG.md has no entry '## [${PROJECT_VERSION}] - YYYY-MM-DD': the Debian changelog is dated today")
  string(TIMESTAMP BTOB_DEB_DAY "%Y-%m-%d" UTC)
endif()
execute_process(COMMAND date -u -R -d "${BTOB_DEB_DAY} 12:00" OUTPUT_VARIABLE BTOB_DEB_DATE
                OUTPUT_STRIP_TRAILING_WHITESPACE COMMAND_ERROR_IS_FATAL ANY)
configure_file(${CMAKE_SOURCE_DIR}/cmake/debian/changelog.in ${CMAKE_BINARY_DIR}/debian/changelog @ONLY)
# The copyright file's year (lintian wants one in the notice) is the year of this version's CHANGELOG entry.
string(SUBSTRING "${BTOB_DEB_DAY}" 0 4 BTOB_DEB_YEAR)
configure_file(${CMAKE_SOURCE_DIR}/cmake/debian/copyright ${CMAKE_BINARY_DIR}/debian/copyright @ONLY)
set(BTOB_DEB_DOCS "")
foreach(doc ${CMAKE_BINARY_DIR}/debian/changelog ${CMAKE_SOURCE_DIR}/CHANGELOG.md)
  get_filename_component(name ${doc} NAME)
  set(gz ${CMAKE_BINARY_DIR}/debian/${name}.gz)
  add_custom_command(OUTPUT ${gz} COMMAND sh -c "gzip -9n -c '${doc}' > '${gz}'" DEPENDS ${doc} VERBATIM)
  list(APPEND BTOB_DEB_DOCS ${gz})
endforeach()
add_custom_target(btob_deb_doc ALL DEPENDS ${BTOB_DEB_DOCS})
install(FILES ${CMAKE_BINARY_DIR}/debian/copyright ${BTOB_DEB_DOCS}
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT deb_doc EXCLUDE_FROM_ALL)

include(CPack)
