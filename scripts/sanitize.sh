#!/usr/bin/env bash
# The whole ctest suite under AddressSanitizer + UndefinedBehaviorSanitizer.
#
#   bash scripts/sanitize.sh            # configure build-sanitize/, build, run ctest
#   bash scripts/sanitize.sh -R qa_     # extra arguments go to ctest
#
# A separate build tree (RFSEEK_SAN_BUILD, default build-sanitize) with -DRFSEEK_SANITIZE=ON:
# every C++ source of the module, its tests and programs instrumented; UBSan aborts on the
# first finding; Python QA runs /usr/bin/python3 with the ASan runtime preloaded. Needs the
# packages of scripts/setup.sh (run it first on a new machine). Exit status: ctest's.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RFSEEK_SAN_BUILD:-$here/build-sanitize}"
jobs="${RFSEEK_JOBS:-$(nproc)}"

echo "==> sanitizer build (ASan + UBSan) in $build, $jobs jobs"
mkdir -p "$build"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRFSEEK_SANITIZE=ON \
    >"$build/configure.log" 2>&1 ||
    {
        cat "$build/configure.log"
        exit 1
    }
cmake --build "$build" -j "$jobs"

echo "==> running the test suite under ASan + UBSan (ctest, from $build)"
cd "$build"
ctest --output-on-failure -j "$jobs" "$@"
