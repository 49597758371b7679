#!/usr/bin/env bash
# Speed of `urbanvec streets` (issue 18 "Speed"): synthetic square cities of 25 km² and 400 km² (one
# grid and one radial element, major d_sep 200 m, minor 100 m, default noise and graph noise), wall
# time, CPU time (user + sys: the machine is shared, so CPU is the figure to compare) and peak memory
# under /usr/bin/time, and the network's size from street-metrics. Targets:
# 25 km² (about 5k intersections) <= 0.5 s, 400 km² <= 10 s, time linear in area.
# usage: bench/streets/speed.sh [THREADS] [streets options...]   (default 2; extra options go to
# `urbanvec streets`, e.g. -major-clearance-ratio 0.5); URBANVEC overrides build/bin/urbanvec
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
URBANVEC=${URBANVEC:-$ROOT/build/bin/urbanvec}
THREADS=${1:-2}
shift || true
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
echo "| area | threads | wall (s) | CPU user+sys (s) | peak RSS (MB) | streets | nodes | 3-way share | 4-way share |"
echo "|---|---|---|---|---|---|---|---|---|"
for side in 5000 10000 20000; do
  x1=$((400000 + side)) y1=$((5500000 + side))
  printf 'id,WKT\n1,"POLYGON((400000 5500000,%d 5500000,%d %d,400000 %d,400000 5500000))"\n' "$x1" "$x1" "$y1" "$y1" >"$WORK/b.csv"
  ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln boundary "$WORK/b$side.gpkg" "$WORK/b.csv"
  printf '{"elements": [{"kind": "grid", "x": %d, "y": %d, "angle": 15},
    {"kind": "radial", "x": %d, "y": %d, "size": 300}]}\n' $((400000 + side / 3)) $((5500000 + side / 3)) \
    $((400000 + 2 * side / 3)) $((5500000 + 2 * side / 3)) >"$WORK/d$side.json"
  /usr/bin/time -f "%e %U %S %M" -o "$WORK/time" "$URBANVEC" streets -q -threads "$THREADS" -boundary "$WORK/b$side.gpkg" \
    -design "$WORK/d$side.json" -dsep-major 200 "$@" "$WORK/s$side.gpkg"
  read -r wall usr sys rss <"$WORK/time"
  "$URBANVEC" street-metrics -q -overwrite -layer streets -json "$WORK/m.json" "$WORK/s$side.gpkg"
  streets=$(ogrinfo -ro -so "$WORK/s$side.gpkg" streets | sed -n 's/^Feature Count: //p')
  printf '| %d km² | %s | %s | %.2f | %.0f | %s | %s | %.2f | %.2f |\n' $((side * side / 1000000)) "$THREADS" "$wall" "$(echo "$usr + $sys" | bc -l)" \
    "$(echo "$rss / 1024" | bc -l)" "$streets" "$(jq .nodes "$WORK/m.json")" "$(jq .share_3way "$WORK/m.json")" \
    "$(jq .share_4way "$WORK/m.json")"
done
