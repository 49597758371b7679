#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on sample_data/: gridify each sample city
# (Monaco from OpenStreetMap, Prague-Bubeneč from cadastral data) into a simulation grid, vectorize the
# grid into a vector city, print an ogrinfo summary of it, and evaluate it against the vectors the grid
# was made from.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
URBANVEC=build/bin/urbanvec
OUT=demo_output
mkdir -p "$OUT"

# One city: gridify its source, vectorize the grid, summarize the GeoPackage, evaluate against the truth.
run_city() {
  local city=$1 cell=$2
  shift 2
  local G="$OUT/${city}_grid" C="$OUT/${city}_city.gpkg"
  echo "== gridify: $city -> $G (${cell} m cells)"
  "$URBANVEC" gridify -q -overwrite -tr "$cell" "$@" "$G"
  gdalinfo "$G/landuse.tif" | grep -E '^Size is|^Pixel Size|ID\["EPSG",[0-9]+\]\]$' | tail -3
  echo "== vectorize: $G -> $C"
  "$URBANVEC" vectorize -overwrite -density "$G/density.tif" -parcels "$G/parcels.tif" -parcel-table "$G/parcels.csv" \
    "$G/landuse.tif" "$C"
  echo "== summary of $C"
  ogrinfo -ro -so -al "$C" | grep -E '^Layer name|^Geometry|^Feature Count'
  echo "== evaluate $C against $G/truth.gpkg"
  "$URBANVEC" evaluate -q -overwrite -json "$OUT/${city}_evaluation.json" "$C" "$G/truth.gpkg"
}

run_city monaco 8 sample_data/sources/monaco.osm.pbf
run_city bubenec 6 -t_srs EPSG:32633 -roads-layer streets -buildings-layer buildings -parcels-layer plots \
  sample_data/sources/bubenec.gpkg
