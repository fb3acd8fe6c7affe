#!/usr/bin/env bash
# Fuzzing: libFuzzer harnesses of the C++ parsers of outside data (lib/fuzz/) and the
# Python mutation fuzzer (scripts/fuzz_python.py).
#
#   bash scripts/fuzz.sh            # 30 s per harness (what CI runs)
#   bash scripts/fuzz.sh 3600       # longer: seconds per harness
#
# Builds lib/fuzz/ with clang (Debian clang, libFuzzer + ASan + UBSan) in build-fuzz/
# (RFSEEK_FUZZ_BUILD), runs each harness from its seed corpus (lib/fuzz/corpus/<name>/,
# copied: new inputs go to build-fuzz/corpus/), prints the executions reached, and exits
# non-zero if any harness found a crash (the input is in build-fuzz/findings/).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RFSEEK_FUZZ_BUILD:-$here/build-fuzz}"
jobs="${RFSEEK_JOBS:-$(nproc)}"
seconds="${1:-30}"
case "$seconds" in '' | *[!0-9]*) echo "usage: fuzz.sh [SECONDS per harness]" >&2; exit 2 ;; esac

echo "==> fuzzing build (clang, libFuzzer + ASan + UBSan) in $build"
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DRFSEEK_FUZZ=ON >"$build/configure.log" 2>&1 ||
    {
        cat "$build/configure.log"
        exit 1
    }
cmake --build "$build" -j "$jobs" --target rfseek-fuzzers

status=0
mkdir -p "$build/findings" "$build/corpus"
summary=""
for f in fuzz_channel_source_cmd fuzz_seeking_controller fuzz_tone_estimator \
    fuzz_burst_detector fuzz_burst_acquirer fuzz_estimator_tags fuzz_mavlink_parser; do
    corpus="$build/corpus/$f"
    mkdir -p "$corpus"
    [ -d "$here/lib/fuzz/corpus/$f" ] && cp -n "$here/lib/fuzz/corpus/$f"/* "$corpus/" 2>/dev/null || true
    echo "==> $f, $seconds s"
    log="$build/$f.log"
    # The MAVLink parser reads outside data from an autopilot link: at least 10^6
    # executions, whatever SECONDS is (a second round, from the same corpus, makes up
    # what the first did not reach).
    min_execs=0
    [ "$f" = fuzz_mavlink_parser ] && min_execs=1000000
    result="0 crashes"
    execs=0
    elapsed=$seconds
    for round in 1 2; do
        if [ "$round" = 1 ]; then
            limit=(-max_total_time="$seconds")
        else
            [ "$execs" -ge "$min_execs" ] && break
            limit=(-runs=$((min_execs - execs)) -max_total_time=1200)
        fi
        start=$SECONDS
        if ! "$build/lib/fuzz/$f" "${limit[@]}" -rss_limit_mb=2048 -timeout=10 \
            -print_final_stats=1 -artifact_prefix="$build/findings/$f-" "$corpus" >"$log" 2>&1; then
            result="FOUND A CRASH (see $log and $build/findings/)"
            status=1
            tail -40 "$log"
            break
        fi
        [ "$round" = 2 ] && elapsed=$((seconds + SECONDS - start))
        n=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
        execs=$((execs + ${n:-0}))
    done
    line="$f: $execs executions in $elapsed s, $result"
    echo "$line"
    summary+="$line"$'\n'
done

echo "==> Python parsers (scripts/fuzz_python.py), $seconds s each"
python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
if ! PYTHONPATH="$here/build/python:${PYTHONPATH:-}" "${python:-/usr/bin/python3}" \
    "$here/scripts/fuzz_python.py" --seconds "$seconds" --out "$build/findings" \
    >"$build/fuzz_python.log" 2>&1; then
    status=1
fi
cat "$build/fuzz_python.log"
summary+="$(grep '^fuzz_python' "$build/fuzz_python.log")"$'\n'
echo "==> fuzzing summary"
printf '%s' "$summary"
exit $status
