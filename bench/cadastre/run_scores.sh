#!/usr/bin/env bash
# Score table of issue 17: urbanvec cadastre (default, without the geometric adjustment, thesis thresholds) against the GRASS, QGIS and
# plain-clustering baselines on drawings made from the real catastro sample at defect levels L0-L3
# (L2 with 5 seeds). Usage: [BASELINES=0] bench/cadastre/run_scores.sh [workdir]  (prints a markdown table)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
U="${URBANVEC:-$root/build/bin/urbanvec}"
PY=/usr/bin/python3
work="${1:-$(mktemp -d /tmp/cadastre_scores.XXXX)}"
mkdir -p "$work"
layers=(-block-layer BLOCKS -lot-layer PARCELS -building-layer BUILDINGS -label-layer FLOORS -a_srs EPSG:32628)
echo "| level | seed | method | blocks R | blocks P | parcels R | parcels P | parts R | parts P | heights exact |"
echo "|---|---|---|---|---|---|---|---|---|---|"
row() {  # level seed method gpkg truth
  "$PY" "$here/score.py" "$4" "$5" --json | "$PY" -c "
import json,sys; r=json.load(sys.stdin)
print('| $1 | $2 | $3 | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |' % (r['blocks']['recall'], r['blocks']['precision'],
  r['parcels']['recall'], r['parcels']['precision'], r['buildings']['recall'], r['buildings']['precision'],
  r['heights_exact_matched']))"
}
for spec in L0:1 L1:1 L2:1 L2:2 L2:3 L2:4 L2:5 L3:1; do
  level=${spec%:*}; seed=${spec#*:}
  base="$work/${level}_s$seed"
  "$PY" "$root/tests/cadastre/make_cad.py" --level "$level" --seed "$seed" "$base" > /dev/null
  "$U" cadastre -q -overwrite "${layers[@]}" "$base.dxf" "$base.urbanvec.gpkg"
  row "$level" "$seed" "urbanvec" "$base.urbanvec.gpkg" "${base}_truth.gpkg"
  "$U" cadastre -q -overwrite -no-adjust "${layers[@]}" "$base.dxf" "$base.noadjust.gpkg"
  row "$level" "$seed" "urbanvec -no-adjust (mean of the copies)" "$base.noadjust.gpkg" "${base}_truth.gpkg"
  "$U" cadastre -q -overwrite -thesis-thresholds "${layers[@]}" "$base.dxf" "$base.thesis.gpkg"
  row "$level" "$seed" "urbanvec, thesis 1 m / 3 m" "$base.thesis.gpkg" "${base}_truth.gpkg"
  [ "${BASELINES:-1}" = 0 ] && continue  # BASELINES=0: urbanvec rows only (the baselines take minutes)
  for m in grass qgis plain; do
    "$PY" "$here/baselines.py" "$m" "$base.dxf" "$base.$m.gpkg"
    row "$level" "$seed" "$m" "$base.$m.gpkg" "${base}_truth.gpkg"
  done
done
