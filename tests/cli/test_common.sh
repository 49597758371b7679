#!/usr/bin/env bash
# Behaviour every subcommand shares: version, help, usage errors, exit codes.
set -e
source "$(dirname "$0")/lib.sh"

run_cmd --version
expect_status 0
case "$OUT" in "urbanvec "[0-9]*.[0-9]*.[0-9]*) ;; *) fail "bad --version output '$OUT'";; esac

run_cmd --help
expect_status 0
expect_stdout_contains "Subcommands:"

run_cmd
expect_status 2

run_cmd frobnicate
expect_status 2
expect_stderr "ERROR: unknown subcommand 'frobnicate' (see 'urbanvec --help')"

run_cmd --json-usage
expect_status 0
echo "$OUT" | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["program"]=="urbanvec"' || fail "--json-usage is not JSON"

# Every registered subcommand has --help and --json-usage, and rejects an unknown option with exit 2.
for sub in $(echo "$OUT" | python3 -c 'import json,sys; print(" ".join(c["name"] for c in json.load(sys.stdin)["commands"]))'); do
  run_cmd "$sub" --help
  expect_status 0
  expect_stdout_contains "Usage: urbanvec $sub"
  run_cmd "$sub" --json-usage
  expect_status 0
  run_cmd "$sub" -no-such-option x y
  expect_status 2
  expect_stderr "ERROR: unknown option '-no-such-option' (see 'urbanvec $sub --help')"
done
finish
