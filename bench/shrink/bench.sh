#!/usr/bin/env bash
# Speed of `urbanvec shrink` (issue 19 "Speed"): the whole pipeline on Monaco at imageSize 500 with
# 100x100 seams (a 400x500 image, the Avidan & Shamir / thesis size; target <= 0.2 s) and at imageSize
# 2000 with 400x400 seams (target <= 2 s), plus seam carving alone for 50..400 seams to show it is
# O(pixels) per seam. Prints the best of N runs of wall time and of CPU time (user+sys), and the
# pipeline's own step timings (`-timings`, the thesis's Table 2 step names). The machine is shared:
# CPU time is the steadier figure.
# Usage: bench/shrink/bench.sh [urbanvec] [repeats]
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
U=${1:-$ROOT/build/bin/urbanvec}
N=${2:-3}
OSM=$ROOT/sample_data/sources/monaco.osm.pbf
OSMI=$ROOT/sample_data/monaco/monaco.osmi
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

measure() {  # measure <label> <args...>
  local label=$1; shift
  local best_wall=999 best_cpu=999 best_pipe=999 best_sc=999
  for _ in $(seq "$N"); do
    /usr/bin/time -f "%e %U %S" -o "$OUT/time" "$U" shrink -timings -overwrite "$@" "$OSM" "$OSMI" "$OUT/o.gpkg" >"$OUT/log"
    read -r wall user sys <"$OUT/time"
    cpu=$(echo "$user + $sys" | bc -l)
    pipe=$(sed -n 's/^timing pipeline \(.*\) s$/\1/p' "$OUT/log")
    sc=$(sed -n 's/^timing step8SC \(.*\) s$/\1/p' "$OUT/log")
    best_wall=$(echo "if ($wall < $best_wall) $wall else $best_wall" | bc -l)
    best_cpu=$(echo "if ($cpu < $best_cpu) $cpu else $best_cpu" | bc -l)
    best_pipe=$(echo "if ($pipe < $best_pipe) $pipe else $best_pipe" | bc -l)
    best_sc=$(echo "if ($sc < $best_sc) $sc else $best_sc" | bc -l)
  done
  printf '%-34s command wall %6.3f s  cpu %6.3f s | pipeline %6.3f s  step8SC %6.3f s\n' \
    "$label" "$best_wall" "$best_cpu" "$best_pipe" "$best_sc"
}

echo "load: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
trap 'echo "load at the end: $(cut -d" " -f1-3 /proc/loadavg)"; rm -rf "$OUT"' EXIT
measure "imageSize 500, 100x100 seams" -image-size 500 -seams 100 100
measure "imageSize 2000, 400x400 seams" -image-size 2000 -seams 400 400
measure "imageSize 2000, 400x400, -threads 1" -image-size 2000 -seams 400 400 -threads 1
measure "imageSize 2000, 400x400, -threads 2" -image-size 2000 -seams 400 400 -threads 2
for s in 50 100 200 400; do
  measure "imageSize 2000, ${s}x0 seams" -image-size 2000 -seams "$s" 0
done
