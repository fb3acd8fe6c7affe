#!/usr/bin/env bash
# A Debian package of gr-rfseek, for /usr:
#
#   bash scripts/package_deb.sh            # -> build-deb/gr-rfseek_<version>-1_amd64.deb
#   sudo apt install ./build-deb/gr-rfseek_*.deb
#
# The package holds the library, headers, CMake package and pkg-config file, the Python
# package, the GRC blocks, the programs, the examples and the docs. Its dependencies on
# shared libraries are found by dpkg-shlibdeps, the Python ones are declared in
# cmake/RfseekPackaging.cmake. Needs the build packages of scripts/setup.sh (plus dpkg-dev).
# Environment: RFSEEK_DEB_BUILD_DIR (default ./build-deb), RFSEEK_JOBS (default: cores).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${RFSEEK_DEB_BUILD_DIR:-$here/build-deb}
jobs=${RFSEEK_JOBS:-$(nproc)}

echo "==> configuring and building for /usr in $build ($jobs jobs)"
mkdir -p "$build"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
    -DBUILD_TESTING=OFF >"$build/configure.log" 2>&1 ||
    {
        cat "$build/configure.log"
        exit 1
    }
cmake --build "$build" -j "$jobs"

echo "==> cpack -G DEB"
rm -f "$build"/gr-rfseek_*.deb
(cd "$build" && cpack -G DEB >cpack.log 2>&1) || {
    cat "$build/cpack.log"
    exit 1
}
deb=$(ls "$build"/gr-rfseek_*.deb)
dpkg-deb --info "$deb" | sed -n '/Package:/,/Description:/p'
echo "==> $deb"
