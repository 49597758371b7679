#!/usr/bin/env bash
# Mutation check (issue 23; docs/testing.md "Mutation check"): applies each deliberate one-line fault of
# tests/mutants/*.patch in turn to a scratch copy of the committed sources, rebuilds the program
# incrementally, runs the CLI tests the patch names, and reports which mutants survive (every test
# passed although the code is broken). Exit status 0 when every mutant is killed, 1 when one
# survives or the unmutated build fails a test, 2 on usage errors.
#
#   scripts/mutants.sh [-all] [-tests DIR] [NAME_PATTERN...]
#
#   -all        run every test a mutant names, to list all the tests that kill it (default: stop at
#               the first failing test)
#   -tests DIR  take the CLI test scripts from DIR instead of tests/cli (e.g. an older version of the
#               tests, to see which mutants they let through)
#   NAME_PATTERN  only the mutants whose file name contains one of the patterns (e.g. parcels 07-)
#
# The scratch copy is a git worktree of HEAD in $URBANVEC_MUTANTS_DIR (default /tmp/urbanvec-mutants)
# with its own build folder: the first run builds the program from scratch (~10 minutes on 2 cores),
# later runs move the worktree to the new HEAD and rebuild what changed. Uncommitted changes to src/
# are not mutated (commit first); the test scripts and sample data are read from this working tree,
# so new tests can be checked before they are committed. Compiles and tests run under `nice`.
set -euo pipefail

usage() { sed -n '7,14p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
REPO=$(cd "$(dirname "$0")/.." && pwd)
TESTS="$REPO/tests/cli"
ALL=0
PATTERNS=()
while [ $# -gt 0 ]; do
  case $1 in
    -all) ALL=1 ;;
    -tests) [ $# -ge 2 ] || usage; TESTS=$(cd "$2" && pwd); shift ;;
    -h|--help) usage ;;
    -*) echo "ERROR: unknown option '$1'" >&2; usage ;;
    *) PATTERNS+=("$1") ;;
  esac
  shift
done

SCRATCH=${URBANVEC_MUTANTS_DIR:-/tmp/urbanvec-mutants}
SRC="$SCRATCH/src"
BUILD="$SCRATCH/build"
LOG="$SCRATCH/log"
JOBS=${URBANVEC_MUTANTS_JOBS:-2}
mkdir -p "$SCRATCH" "$LOG"
start=$(date +%s)

# The scratch worktree at this repository's HEAD, with no mutant left over from an interrupted run.
head=$(git -C "$REPO" rev-parse HEAD)
if [ ! -e "$SRC/.git" ]; then
  git -C "$REPO" worktree prune
  git -C "$REPO" worktree add -q --detach "$SRC" "$head"
else
  git -C "$SRC" reset -q --hard
  git -C "$SRC" checkout -q --detach "$head"
fi
echo "sources: $head (worktree $SRC)"

build() {
  if [ ! -f "$BUILD/build.ninja" ] && [ ! -f "$BUILD/Makefile" ]; then
    local gen=()
    command -v ninja >/dev/null && gen=(-G Ninja)
    nice cmake -S "$SRC" -B "$BUILD" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DURBANVEC_BUILD_TESTS=OFF >"$LOG/cmake.txt" 2>&1
  fi
  nice cmake --build "$BUILD" -j "$JOBS" --target urbanvec_cli >"$LOG/build.txt" 2>&1
}
export URBANVEC="$BUILD/bin/urbanvec" URBANVEC_SOURCE_DIR="$REPO"

# run_test <name> <log>: runs tests/cli/test_<name>.sh against the scratch program.
# A test missing from the test folder (an older one, with -tests) passes: it cannot kill anything.
run_test() {
  if [ ! -f "$TESTS/test_$1.sh" ]; then echo "no test_$1.sh in $TESTS" >"$2"; return 0; fi
  nice bash "$TESTS/test_$1.sh" >"$2" 2>&1
}

mutants=()
for p in "$REPO"/tests/mutants/*.patch; do
  name=$(basename "$p" .patch)
  if [ ${#PATTERNS[@]} -gt 0 ]; then
    keep=0
    for pat in "${PATTERNS[@]}"; do case $name in *"$pat"*) keep=1 ;; esac; done
    [ $keep = 1 ] || continue
  fi
  mutants+=("$p")
done
[ ${#mutants[@]} -gt 0 ] || { echo "ERROR: no mutant matches ${PATTERNS[*]}" >&2; exit 2; }
tests_of() { sed -n 's/^# tests: //p' "$1"; }

# The unmutated program must pass every test the mutants use, or a kill means nothing.
echo "building the unmutated program..."
build || { echo "ERROR: the unmutated sources do not build; see $LOG/build.txt" >&2; exit 1; }
baseline=$(for p in "${mutants[@]}"; do tests_of "$p"; done | tr ' ' '\n' | sort -u | tr '\n' ' ')
for t in $baseline; do
  t0=$(date +%s)
  if ! run_test "$t" "$LOG/baseline-$t.txt"; then
    echo "ERROR: test_$t.sh fails without any mutant; see $LOG/baseline-$t.txt" >&2
    exit 1
  fi
  echo "baseline test_$t.sh passed ($(( $(date +%s) - t0 )) s)"
done

survivors=0
report=()
for p in "${mutants[@]}"; do
  name=$(basename "$p" .patch)
  t0=$(date +%s)
  if ! patch -s -p1 -d "$SRC" --dry-run <"$p" >/dev/null 2>&1; then
    report+=("$(printf '%-40s %s' "$name" "DOES NOT APPLY (refresh the patch to today's source)")")
    survivors=$((survivors + 1))
    continue
  fi
  patch -s -p1 -d "$SRC" <"$p"
  if ! build; then
    verdict="killed by the compiler (make the mutant compile)"
    cp "$LOG/build.txt" "$LOG/$name-build.txt"
  else
    killers=()
    for t in $(tests_of "$p"); do
      if ! run_test "$t" "$LOG/$name-$t.txt"; then
        killers+=("test_$t.sh")
        [ $ALL = 1 ] || break
      fi
    done
    if [ ${#killers[@]} -gt 0 ]; then
      verdict="killed by ${killers[*]}"
    else
      verdict="SURVIVED ($(tests_of "$p"))"
      survivors=$((survivors + 1))
    fi
  fi
  patch -s -R -p1 -d "$SRC" <"$p"
  line=$(printf '%-40s %s (%d s)' "$name" "$verdict" $(( $(date +%s) - t0 )))
  echo "$line"
  report+=("$line")
done
# Leave the scratch program unmutated.
build || true

echo
echo "mutants: ${#mutants[@]}, survived: $survivors, time: $(( $(date +%s) - start )) s (logs in $LOG)"
printf '%s\n' "${report[@]}" | grep -v "killed by test" || true
[ $survivors -eq 0 ]
