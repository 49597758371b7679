#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on sample_data/: gridify the Monaco
# OpenStreetMap extract into a simulation grid, vectorize the grid into a vector city, evaluate the
# city against the vectors the grid was made from, and print an ogrinfo summary of what was written.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
URBANVEC=build/bin/urbanvec
OUT=demo_output
mkdir -p "$OUT"

echo "== gridify: sample_data/sources/monaco.osm.pbf -> $OUT/monaco_grid (8 m cells)"
"$URBANVEC" gridify -overwrite -tr 8 sample_data/sources/monaco.osm.pbf "$OUT/monaco_grid"
gdalinfo "$OUT/monaco_grid/landuse.tif" | grep -E '^Size is|^Pixel Size|ID\["EPSG",[0-9]+\]\]$' | tail -3

echo "== vectorize: $OUT/monaco_grid -> $OUT/monaco_city.gpkg"
G="$OUT/monaco_grid"
"$URBANVEC" vectorize -overwrite -density "$G/density.tif" -parcels "$G/parcels.tif" -parcel-table "$G/parcels.csv" \
  "$G/landuse.tif" "$OUT/monaco_city.gpkg"

echo "== summary of $OUT/monaco_city.gpkg"
ogrinfo -ro -so -al "$OUT/monaco_city.gpkg" | grep -E '^Layer name|^Geometry|^Feature Count'

echo "== evaluate against $G/truth.gpkg"
"$URBANVEC" evaluate -q -overwrite -json "$OUT/monaco_evaluation.json" "$OUT/monaco_city.gpkg" "$G/truth.gpkg"
