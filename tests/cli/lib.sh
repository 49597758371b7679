# Shared helpers for CLI tests: source it, then call the check functions. Each failed check prints
# what was expected and exits 1.
set -u
: "${URBANVEC:?URBANVEC must point at the built program}"
: "${URBANVEC_SOURCE_DIR:?URBANVEC_SOURCE_DIR must point at the repository}"
SAMPLE_DIR="${URBANVEC_SOURCE_DIR}/sample_data"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
FAILURES=0

fail() { echo "FAIL: $*" >&2; FAILURES=$((FAILURES + 1)); }

# run_cmd: runs the program, capturing stdout, stderr and status in OUT, ERR, STATUS.
run_cmd() {
  set +e
  OUT=$("$URBANVEC" "$@" 2>"$WORK/.stderr")
  STATUS=$?
  ERR=$(cat "$WORK/.stderr")
  set -e
}

expect_status() { [ "$STATUS" -eq "$1" ] || fail "expected exit $1, got $STATUS (stderr: $ERR)"; }
expect_stderr() { [ "$ERR" = "$1" ] || fail "expected stderr '$1', got '$ERR'"; }
expect_stderr_contains() { case "$ERR" in *"$1"*) ;; *) fail "stderr lacks '$1': '$ERR'";; esac; }
expect_stdout_contains() { case "$OUT" in *"$1"*) ;; *) fail "stdout lacks '$1'";; esac; }
expect_missing() { [ ! -e "$1" ] || fail "'$1' should not exist"; }
expect_exists() { [ -e "$1" ] || fail "'$1' should exist"; }
expect_eq() { [ "$1" = "$2" ] || fail "$3: expected '$2', got '$1'"; }
# No temporary outputs may be left next to an output after a failure.
expect_no_temp() { local left; left=$(ls -a "$1" | grep -c '\.tmp-' || true); [ "$left" -eq 0 ] || fail "temporary files left in $1"; }

# feature_count <dataset> <layer>
feature_count() { ogrinfo -ro -so "$1" "$2" 2>/dev/null | sed -n 's/^Feature Count: //p'; }

finish() {
  if [ "$FAILURES" -ne 0 ]; then echo "$FAILURES check(s) failed" >&2; exit 1; fi
  echo "all checks passed"
}

# run_unprivileged <args...>: like run_cmd, but as an unprivileged user even when the tests run as root
# (CI does), so permission checks really apply: root runs a copy of the program as user nobody.
run_unprivileged() {
  local prog="$URBANVEC"
  local as=()
  if [ "$(id -u)" -eq 0 ]; then
    chmod 755 "$WORK"
    prog="$WORK/.urbanvec_unprivileged"
    [ -x "$prog" ] || { cp "$URBANVEC" "$prog" && chmod 755 "$prog"; }
    as=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  fi
  set +e
  OUT=$("${as[@]}" "$prog" "$@" 2>"$WORK/.stderr")
  STATUS=$?
  ERR=$(cat "$WORK/.stderr")
  set -e
}
