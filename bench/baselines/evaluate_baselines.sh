#!/usr/bin/env bash
# Runs both naive baselines of issue 2 §3 on a city's land-use raster and evaluates them against its
# truth: GRASS r.thin + r.to.vect centrelines as the roads, gdal_polygonize.py developed patches
# (DN >= 4) as blocks and parcels. Prints the evaluator's table and leaves the JSON report and the
# baseline layers in <work_dir>.
# Usage: evaluate_baselines.sh <city_dir with landuse.tif and truth.gpkg> <work_dir> [urbanvec]
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "Usage: $(basename "$0") <city_dir> <work_dir> [path to urbanvec]" >&2
  exit 2
fi
city=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
urbanvec=${3:-$here/../../build/bin/urbanvec}
mkdir -p "$work"
"$here/grass_centrelines.sh" -overwrite "$city/landuse.tif" "$work/grass_centrelines.gpkg"
"$here/polygonize.sh" -overwrite "$city/landuse.tif" "$work/polygonized.gpkg"
"$urbanvec" evaluate -q -overwrite -json "$work/baseline_report.json" \
  -roads-from "$work/grass_centrelines.gpkg" \
  -blocks-layer out -blocks-where "DN >= 4" -parcels-layer out -parcels-where "DN >= 4" -landuse-field DN \
  "$work/polygonized.gpkg" "$city/truth.gpkg"
