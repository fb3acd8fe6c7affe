# A Debian package of the module: scripts/package_deb.sh configures a build for the /usr
# prefix and runs `cpack -G DEB` on it (gr-rfseek_<version>-1_<arch>.deb). The shared
# library dependencies are found by dpkg-shlibdeps; the Python ones are declared here.
set(CPACK_PACKAGE_NAME "gr-rfseek")
set(CPACK_PACKAGE_VENDOR "gr-rfseek authors")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "GNU Radio blocks to home in on an RF beacon from its frequency (Doppler) alone")
set(CPACK_PACKAGE_DESCRIPTION
    "gr-rfseek lets a UAV with one omnidirectional antenna and no GPS home in on a distant
RF beacon using only the beacon's measured frequency and its own heading. It holds
the GNU Radio blocks channel_source (simulated emitter, multipath, carrier offset and
UAV), doppler_estimator and seeking_controller, their Python bindings and GRC blocks,
the C++ library and CMake package for other projects, and the programs rfseek-sim,
rfseek-live and rfseek-montecarlo.")
set(CPACK_RESOURCE_FILE_LICENSE "${PROJECT_SOURCE_DIR}/COPYING")
set(CPACK_PACKAGING_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")
set(CPACK_STRIP_FILES ON)

set(CPACK_DEBIAN_PACKAGE_MAINTAINER "gr-rfseek authors <gr-rfseek@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION "comm")
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
# The Python package and programs: GNU Radio's Python modules, numpy, matplotlib (the
# figures of rfseek-sim and rfseek-plot-montecarlo).
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "gnuradio (>= ${Gnuradio_VERSION_MAJOR}.${Gnuradio_VERSION_MINOR}), python3-numpy, python3-matplotlib")
# Building against the module (headers, CMake package) needs GNU Radio's development
# files; Dask studies need python3-distributed.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "gnuradio-dev, libvolk2-dev, python3-distributed, gr-osmosdr")

set(CPACK_SOURCE_GENERATOR "TGZ")
set(CPACK_SOURCE_IGNORE_FILES "/build[^/]*/;/\\\\.git/;~$")
include(CPack)
