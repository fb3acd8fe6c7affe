#!/usr/bin/env bash
# gr-rfseek set-up on Debian 12, in one idempotent command.
#
#   bash scripts/setup.sh run    # command 1: packages, build, install, run the main job
#   bash scripts/setup.sh test   # command 2: packages, build, install, run the tests
#   bash scripts/setup.sh build  # packages, build, install only
#
# Environment: RFSEEK_PREFIX (install prefix, default /usr/local), RFSEEK_BUILD_DIR
# (default ./build), RFSEEK_JOBS (default: number of cores), RFSEEK_SKIP_APT=1 (trust
# that the packages are there).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
prefix=${RFSEEK_PREFIX:-/usr/local}
build=${RFSEEK_BUILD_DIR:-$here/build}
jobs=${RFSEEK_JOBS:-$(nproc)}
what=${1:-run}
shift || true

case "$what" in
run | test | build) ;;
*)
    echo "usage: bash scripts/setup.sh run|test|build" >&2
    exit 2
    ;;
esac

# Root, or a user with sudo.
if [ "$(id -u)" -eq 0 ]; then
    SUDO=()
elif command -v sudo >/dev/null 2>&1; then
    SUDO=(sudo)
else
    echo "setup.sh: needs root or sudo to install packages and the module" >&2
    exit 1
fi

# Debian 12 packages (no PyPI).
packages=(
    build-essential cmake pkg-config git
    gnuradio gnuradio-dev libvolk2-dev libfftw3-dev libuhd-dev gr-osmosdr
    pybind11-dev libgtest-dev libboost-all-dev libspdlog-dev libfmt-dev libgmp-dev
    libcli11-dev nlohmann-json3-dev libeigen3-dev
    python3-numpy python3-matplotlib python3-yaml python3-distributed
    clang clang-format libclang-rt-14-dev libssl-dev
)
# Node.js runs the test-only cross-check of the MAVLink codec against node-mavlink
# (installed below from the npm registry): Debian's, unless a node is already there.
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)
if [ "${RFSEEK_SKIP_APT:-0}" != 1 ]; then
    missing=()
    for p in "${packages[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
            missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        echo "==> installing Debian packages: ${missing[*]}"
        "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
        "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive \
            apt-get install -y -q --no-install-recommends "${missing[@]}"
    else
        echo "==> Debian packages present"
    fi
fi

# node-mavlink, pinned by lib/qa/node/package-lock.json, into $build/node (tests only).
if [ "$what" = test ]; then
    mkdir -p "$build/node"
    if ! cmp -s "$here/lib/qa/node/package-lock.json" "$build/node/package-lock.json" ||
        [ ! -f "$build/node/node_modules/node-mavlink/package.json" ]; then
        echo "==> installing the test dependency node-mavlink into $build/node (npm)"
        cp "$here/lib/qa/node/package.json" "$here/lib/qa/node/package-lock.json" "$build/node/"
        (cd "$build/node" && npm ci --no-audit --no-fund --loglevel=error)
    fi
fi

echo "==> configuring and building in $build (prefix $prefix, $jobs jobs)"
mkdir -p "$build"
# The Python interpreter is GNU Radio's (found by CMake); the format check runs with
# Debian 12's clang-format 14.
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" \
    -DRFSEEK_FORMAT_CHECK=ON >"$build/configure.log" 2>&1 ||
    {
        cat "$build/configure.log"
        exit 1
    }
cmake --build "$build" -j "$jobs"

echo "==> installing into $prefix"
if [ -w "$prefix" ] || [ "$(id -u)" -eq 0 ]; then
    cmake --install "$build" >/dev/null
else
    "${SUDO[@]}" cmake --install "$build" >/dev/null
fi
if [ "$(id -u)" -eq 0 ]; then ldconfig; else "${SUDO[@]}" ldconfig; fi

# PYTHONPATH, LD_LIBRARY_PATH and GRC_BLOCKS_PATH for this prefix (written by CMake).
# shellcheck disable=SC1091
source "$build/rfseek-env.sh"

case "$what" in
run)
    echo "==> running the main job: $prefix/bin/rfseek-sim $*"
    "$prefix/bin/rfseek-sim" "$@"
    ;;
test)
    echo "==> running the test suite (ctest, from the build tree)"
    cd "$build"
    ctest --output-on-failure -j "$jobs" "$@"
    ;;
build) ;;
esac
