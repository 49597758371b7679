#!/usr/bin/env bash
# The naive polygon baseline of issue 2 §3: gdal_polygonize.py turns every 4-connected patch of one
# land-use class of landuse.tif into a polygon (layer `out`, field DN = class code). Evaluate its
# developed patches as blocks and parcels with
#   urbanvec evaluate -blocks-layer out -blocks-where "DN >= 4" -parcels-layer out \
#     -parcels-where "DN >= 4" -landuse-field DN <out.gpkg> <truth.gpkg>
# Usage: polygonize.sh [-overwrite] <landuse.tif> <out.gpkg>
set -euo pipefail

overwrite=0
if [ "${1:-}" = "-overwrite" ]; then overwrite=1; shift; fi
if [ $# -ne 2 ]; then
  echo "Usage: $(basename "$0") [-overwrite] <landuse.tif> <out.gpkg>" >&2
  exit 2
fi
input=$1
output=$2
if ! gdalinfo "$input" >/dev/null 2>&1; then echo "ERROR: '$input' is not a raster GDAL can read" >&2; exit 1; fi
if [ -e "$output" ] && [ "$overwrite" -eq 0 ]; then
  echo "ERROR: output file '$output' already exists; use -overwrite to replace it" >&2
  exit 1
fi
tmp_output="$(dirname "$output")/.$(basename "$output" .gpkg).tmp-$$.gpkg"
rm -f "$tmp_output"
trap 'rm -f "$tmp_output"' EXIT
gdal_polygonize.py -q "$input" -f GPKG "$tmp_output" out DN
mv -f "$tmp_output" "$output"
