#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of the vectorizer (issue 3 "Bad input": "run the
# stages under AddressSanitizer/UBSan in a test build at least once and keep it clean").
#
# Builds <build dir> (default build-asan) with -DURBANVEC_SANITIZE=ON, then runs under the sanitizers:
#   1. the vectorize, blocks and parcels unit tests;
#   2. `urbanvec vectorize` on sample_data/monaco and sample_data/bubenec with -density, -parcels and
#      -parcel-table as scripts/demo.sh runs it (plus -check, -timings and -debug-stages);
#   3. tests/cli/test_vectorize_errors.sh, every bad input of the issue.
# Leaks are errors (ASAN_OPTIONS=detect_leaks=1), and UBSan stops at its first finding with a stack
# (UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1). Any sanitizer report or failed step ends the run
# with a non-zero status; the logs are kept in <build dir>/sanitize-logs. Slow (the build alone takes
# 15-25 minutes on 2 cores), so it is not part of scripts/test.sh or CI.
#
# Usage: scripts/sanitize.sh [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build-asan}
LOGS="$BUILD/sanitize-logs"

cmake -S . -B "$BUILD" -G Ninja -DURBANVEC_SANITIZE=ON
cmake --build "$BUILD" -j"${JOBS:-2}" --target urbanvec_cli unit_vectorize unit_vectorize_roads unit_vectorize_pavement unit_vectorize_blocks unit_vectorize_parcels
rm -rf "$LOGS"
mkdir -p "$LOGS"

export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
URBANVEC="$PWD/$BUILD/bin/urbanvec"
failed=0

# step <name> <command...>: runs the command with its output in $LOGS/<name>.log; a non-zero status or
# any sanitizer report in the log is a failure.
step() {
  local name=$1
  shift
  local log="$LOGS/$name.log" status=0
  echo "== $name"
  "$@" >"$log" 2>&1 || status=$?
  if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: (Address|Leak|UndefinedBehavior)Sanitizer" "$log"; then
    echo "   sanitizer report (exit $status), see $log:"
    grep -E -m 10 "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY:" "$log" | sed 's/^/   /'
    failed=1
  elif [ "$status" -ne 0 ]; then
    echo "   failed (exit $status), see $log:"
    tail -n 5 "$log" | sed 's/^/   /'
    failed=1
  else
    echo "   clean"
  fi
}

for module in vectorize vectorize_roads vectorize_pavement vectorize_blocks vectorize_parcels; do
  step "unit_$module" "$BUILD/bin/unit_$module" --gtest_brief=1
done

for city in monaco bubenec; do
  g="sample_data/$city"
  step "vectorize_$city" "$URBANVEC" vectorize -overwrite -progress none -check -timings \
    -debug-stages "$LOGS/${city}_stages" -density "$g/density.tif" -parcels "$g/parcels.tif" \
    -parcel-table "$g/parcels.csv" "$g/landuse.tif" "$LOGS/$city.gpkg"
done

step cli_vectorize_errors env URBANVEC="$URBANVEC" URBANVEC_SOURCE_DIR="$PWD" URBANVEC_BUILD_DIR="$PWD/$BUILD" \
  bash tests/cli/test_vectorize_errors.sh

if [ "$failed" -ne 0 ]; then
  echo "sanitize: FAILED (logs in $LOGS)"
  exit 1
fi
echo "sanitize: clean (logs in $LOGS)"
