#!/usr/bin/env bash
# The README's example chain (the sh block under "## The command") runs as written from a fresh
# clone (issue 15). The block is read from README.md itself, so this test follows the README: each
# line runs in a scratch folder holding only the git-tracked sample_data/ (at the same relative
# paths), with the leading `urbanvec` replaced by the built program. Every step must exit 0, every
# subcommand of the README's table must appear, each output must hold the files/layers the README
# names with about the feature counts the Monaco sample gives, and everything the chain writes must
# be git-ignored.
set -e
source "$(dirname "$0")/lib.sh"
README="$URBANVEC_SOURCE_DIR/README.md"
RUN="$WORK/clone"
mkdir -p "$RUN"

# A fresh clone's sample_data/: the tracked files only (all of it when the source is no git checkout).
if git -C "$URBANVEC_SOURCE_DIR" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  IN_GIT=1
  (cd "$URBANVEC_SOURCE_DIR" && git ls-files -z sample_data | xargs -0 cp --parents -t "$RUN")
else
  IN_GIT=0
  cp -r "$SAMPLE_DIR" "$RUN/sample_data"
fi
sample_before=$(cd "$RUN" && find sample_data -type f | sort)

# The block: first ```sh fence after the heading, before the next heading; `\` continuations joined.
block=$(awk '/^## The command[[:space:]]*$/ { h = 1; next }
             h && /^## / { exit }
             h && !c && /^```sh[[:space:]]*$/ { c = 1; next }
             c && /^```[[:space:]]*$/ { exit }
             c' "$README" | sed -e ':a' -e '/\\$/{N;s/\\\n[[:space:]]*/ /;ba' -e '}')
[ -n "$block" ] || { fail "no sh block under '## The command' in README.md"; finish; }

# The subcommands the README's table lists (rows starting with | `name` |) and what they make.
table_row() { grep -E "^\| \`$1\` \|" "$README" | head -n 1; }
subcommands=$(grep -oE '^\| `[a-z-]+` \|' "$README" | sed -E 's/^\| `([a-z-]+)` \|/\1/')
[ -n "$subcommands" ] || fail "README.md has no subcommand table"
# Backticked names right of the arrow in a table row: the files/layers the README says it writes.
made_by() { table_row "$1" | awk -F'|' '{ print $3 }' | sed 's/.*→//' | grep -oE '`[^`]+`' | tr -d '`'; }

declare -A OUTPUT INPUT OPT
steps=0
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  steps=$((steps + 1))
  cmd=$line
  case "$cmd" in urbanvec|urbanvec\ *) cmd="\"\$URBANVEC\"${cmd#urbanvec}" ;; esac
  set +e
  (cd "$RUN" && eval "$cmd") </dev/null >"$WORK/step$steps.out" 2>"$WORK/step$steps.err"
  status=$?
  set -e
  [ "$status" -eq 0 ] || fail "README step exited $status: $line
  stderr: $(cat "$WORK/step$steps.err")"
  # Remember each subcommand's output (last word), input (the word before) and option values.
  line=${line%%#*}
  read -r -a words <<< "$line"
  if [ "${words[0]}" = urbanvec ] && [ "${#words[@]}" -ge 3 ] && [ "${words[1]:0:1}" != - ] &&
     [ "${words[-1]}" != --help ]; then
    sub=${words[1]}
    OUTPUT[$sub]=${words[-1]}
    INPUT[$sub]=${words[-2]}
    for ((i = 2; i < ${#words[@]} - 1; i++)); do
      case "${words[i]}" in -*) OPT[$sub${words[i]}]=${words[i + 1]} ;; esac
    done
  fi
done <<< "$block"
[ "$steps" -ge 1 ] || fail "the README block has no command"

for sub in $subcommands; do
  [ -n "${OUTPUT[$sub]:-}" ] || fail "the README example chain never runs '$sub' (it is in the README's table)"
done
[ "$FAILURES" -eq 0 ] || finish

# Everything the chain wrote is git-ignored; sample_data/ gained and lost nothing.
if [ "$IN_GIT" -eq 1 ]; then
  written=$(cd "$RUN" && find . -path ./sample_data -prune -o -type f -print | sed 's|^\./||')
  [ -n "$written" ] || fail "the README chain wrote no file"
  for f in $written; do
    git -C "$URBANVEC_SOURCE_DIR" check-ignore -q --no-index "$f" ||
      fail "README output '$f' is not git-ignored (see .gitignore)"
  done
fi
expect_eq "$(cd "$RUN" && find sample_data -type f | sort)" "$sample_before" "sample_data/ after the chain"

# count_above <dataset> <layer> <minimum>: the layer exists and has more than <minimum> features.
count_above() {
  local n; n=$(feature_count "$RUN/$1" "$2")
  [ -n "$n" ] || { fail "'$1' has no layer '$2'"; return; }
  [ "$n" -gt "$3" ] || fail "'$1' layer '$2' has $n features, expected more than $3"
}

# gridify: the files of the table's gridify row; the Monaco grid is 348 x 413 cells of 8 m.
grid=${OUTPUT[gridify]}
for f in $(made_by gridify); do expect_exists "$RUN/$grid/$f"; done
[ -n "$(made_by gridify)" ] || fail "README's gridify row names no output file"
size=$(gdalinfo "$RUN/$grid/landuse.tif" 2>/dev/null | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)$/\1 \2/p')
read -r width height <<< "${size:-0 0}"
[ $((width * height)) -gt 120000 ] || fail "landuse.tif is ${width} x ${height}, expected over 120000 cells"
count_above "$grid/truth.gpkg" roads 600      # 714
count_above "$grid/truth.gpkg" blocks 75      # 88
count_above "$grid/truth.gpkg" parcels 1000   # 1160

# vectorize: every layer of the table's vectorize row, with about the counts Monaco gives.
city=${OUTPUT[vectorize]}
for layer in $(made_by vectorize); do
  ogrinfo -ro -so "$RUN/$city" "$layer" >/dev/null 2>&1 || fail "'$city' lacks layer '$layer'"
done
[ -n "$(made_by vectorize)" ] || fail "README's vectorize row names no layer"
count_above "$city" roads 650        # 785
count_above "$city" road_nodes 450   # 555
count_above "$city" pavement 2700    # 3253
count_above "$city" blocks 160       # 194
count_above "$city" water 10         # 19
count_above "$city" spines 35        # 52
count_above "$city" parcels 1000     # 1175
count_above "$city" vectorize_report 160

# evaluate: the -json report compares the two files named and matches over half the truth blocks.
report=${OPT[evaluate-json]:-}
[ -n "$report" ] || fail "the README's evaluate step gives no -json report"
if [ -n "$report" ]; then
  python3 - "$RUN/$report" "$city" "$grid/truth.gpkg" <<'PY' || fail "evaluate's report '$report' is wrong"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["result"] == sys.argv[2] and d["truth"] == sys.argv[3], (d["result"], d["truth"])
assert d["roads"]["result_lines"] > 600, d["roads"]["result_lines"]
assert d["blocks"]["matched_share"] > 0.5, d["blocks"]["matched_share"]     # 0.61
assert d["parcels"]["result_count"] > 1000, d["parcels"]["result_count"]
PY
fi

# boundary: one realistic boundary (the table says "a realistic city boundary").
bnd=${OUTPUT[boundary]}
expect_eq "$(feature_count "$RUN/$bnd" boundary)" 1 "boundary features"
valid=$(ogrinfo -ro -q -geom=NO "$RUN/$bnd" boundary 2>/dev/null | sed -n 's/^  valid (Integer64) = //p')
expect_eq "$valid" 1 "boundary 'valid'"

# shape-metrics: a copy of the measured layer, every feature with its metric fields.
metrics=${OUTPUT[shape-metrics]}
layer=${OPT[shape-metrics-layer]:-$(ogrinfo -ro -q "$RUN/${INPUT[shape-metrics]}" 2>/dev/null | sed -n '1s/^1: \([^ ]*\).*/\1/p')}
n_in=$(feature_count "$RUN/${INPUT[shape-metrics]}" "$layer")
count_above "$metrics" "$layer" 0
expect_eq "$(feature_count "$RUN/$metrics" "$layer")" "$n_in" "shape-metrics features"
measured=$(ogrinfo -ro -q -sql "SELECT COUNT(*) AS n FROM \"$layer\" WHERE enclosed_area_ratio > 0 AND enclosed_area_ratio <= 1" \
  "$RUN/$metrics" 2>/dev/null | sed -n 's/^  n (Integer.*) = //p')
expect_eq "$measured" "$n_in" "features with an enclosed-area ratio in (0, 1]"

finish
