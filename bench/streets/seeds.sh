#!/usr/bin/env bash
# The realism comparison of bench/streets/compare.sh over seeds 1-8: for each area and mode (generated,
# main roads kept), the mean number of the 7 figures that match the real network and of the 6 of
# Boeing's plausibility ranges that hold, per figure how many seeds match, and the median values;
# then per figure on how many seeds it lies inside Boeing's range.
# Run compare.sh first (it prepares the areas in OUTDIR). Extra arguments go to `urbanvec streets`,
# e.g. `-bend-share 0 -edge-seed-ratio 0` to measure without the corner and edge-seed rules.
# usage: bench/streets/seeds.sh [OUTDIR] [streets options...]   (default OUTDIR /tmp/streets_compare)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
URBANVEC=${URBANVEC:-$ROOT/build/bin/urbanvec}
OUT=${1:-/tmp/streets_compare}
shift || true
PY=/usr/bin/python3
AREAS="monaco bubenec monaco_west monaco_east"
for c in $AREAS; do
  d="$OUT/$c"
  [ -f "$d/run.txt" ] || { echo "ERROR: $d/run.txt missing: run bench/streets/compare.sh $OUT first" >&2; exit 1; }
  water=()
  [ -f "$d/water.gpkg" ] && water=(-water "$d/water.gpkg")
  mkdir -p "$d/seeds"
  for mode in generated kept; do
    keep=()
    [ "$mode" = kept ] && keep=(-keep-roads)
    for s in 1 2 3 4 5 6 7 8; do
      "$URBANVEC" streets -q -overwrite -boundary "$d/boundary.gpkg" "${water[@]}" -roads "$d/main.gpkg" "${keep[@]}" \
        -seed "$s" "$@" "$d/seeds/$mode-$s.gpkg"
      "$URBANVEC" street-metrics -q -overwrite -layer streets -area "$d/interior.gpkg" -json "$d/seeds/$mode-$s.json" \
        "$d/seeds/$mode-$s.gpkg"
    done
  done
done
$PY - "$OUT" $AREAS <<'PY'
import json, statistics as st, sys
out, areas = sys.argv[1], sys.argv[2:]
tol = {"orientation_entropy": ("abs", .25), "share_3way": ("abs", .10), "share_4way": ("abs", .10),
       "share_deadend": ("abs", .08), "circuity": ("abs", .03), "median_edge_length": ("rel", .30),
       "intersection_density": ("rel", .30)}
plausible = {"orientation_entropy": (2.86, 3.57), "share_3way": (0.45, 1.0), "share_4way": (0.06, 0.42),
             "share_deadend": (0.05, 0.30), "circuity": (1.02, 1.10), "median_edge_length": (52, 283)}
print("| area | mode | matches of 7 | plausible of 6 | " + " | ".join(f"{k} (seeds matching; median)" for k in tol) + " |")
print("|---" * (4 + len(tol)) + "|")
for c in areas:
    real = json.load(open(f"{out}/{c}/real.json"))
    for mode in ("generated", "kept"):
        runs = [json.load(open(f"{out}/{c}/seeds/{mode}-{s}.json")) for s in range(1, 9)]
        def ok(g, k):
            kind, v = tol[k]
            return abs(g[k] - real[k]) <= (v if kind == "abs" else v * real[k])
        matches = st.mean(sum(ok(g, k) for k in tol) for g in runs)
        plaus = st.mean(sum(lo <= g[k] <= hi for k, (lo, hi) in plausible.items()) for g in runs)
        cells = [f"{sum(ok(g, k) for g in runs)}; {st.median(g[k] for g in runs):.3f}" for k in tol]
        print(f"| {c} | {mode} | {matches:.2f} | {plaus:.2f} | " + " | ".join(cells) + " |")
# Per figure: on how many seeds it lies inside Boeing's range (the plausibility the generated mode is
# judged by), and its median.
print("\n| area | mode | " + " | ".join(f"{k} in {lo}-{hi} (seeds; median)" for k, (lo, hi) in plausible.items()) + " |")
print("|---" * (2 + len(plausible)) + "|")
for c in areas:
    for mode in ("generated", "kept"):
        runs = [json.load(open(f"{out}/{c}/seeds/{mode}-{s}.json")) for s in range(1, 9)]
        cells = [f"{sum(lo <= g[k] <= hi for g in runs)}; {st.median(g[k] for g in runs):.3f}"
                 for k, (lo, hi) in plausible.items()]
        print(f"| {c} | {mode} | " + " | ".join(cells) + " |")
PY
