#!/usr/bin/env bash
# Speed of `urbanvec cadastre` (issue 17): the L2 drawing of the real sample replicated k x k times
# (~7k, ~115k and ~1M segments); wall time and peak memory (GNU time). Usage:
# [THREADS=n] bench_speed.sh [workdir]   (THREADS is passed as -threads, default 1)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
U="${URBANVEC:-$root/build/bin/urbanvec}"
work="${1:-$(mktemp -d /tmp/cadastre_speed.XXXX)}"
mkdir -p "$work"
echo "| replicas | segments | wall s | peak MB | blocks | building elements |"
echo "|---|---|---|---|---|---|"
for k in 1 4 12; do
  d="$work/r$k"
  [ -f "$d.dxf" ] || /usr/bin/python3 "$root/tests/cadastre/make_cad.py" --level L2 --seed 1 --replicate $k "$d" > "$d.log"
  segs=$(sed -n 's/.*seed 1: \([0-9]*\) segments.*/\1/p' "$d.log")
  /usr/bin/time -f "%e %M" -o "$d.time" "$U" cadastre -q -threads "${THREADS:-1}" -overwrite -block-layer BLOCKS -lot-layer PARCELS \
    -building-layer BUILDINGS -label-layer FLOORS -a_srs EPSG:32628 "$d.dxf" "$d.gpkg"
  read -r wall kb < "$d.time"
  blocks=$(ogrinfo -ro -so "$d.gpkg" blocks | sed -n 's/^Feature Count: //p')
  elems=$(ogrinfo -ro -so "$d.gpkg" buildings | sed -n 's/^Feature Count: //p')
  echo "| ${k}x$k | $segs | $wall | $((kb / 1024)) | $blocks | $elems |"
done
