#!/usr/bin/env bash
# The naive road-centreline baseline of issue 2 §3: GRASS thins the road cells of a land-use raster
# (classes 2 secondary and 3 primary road, CONVENTIONS.md "Gridded input") to one-cell-wide skeletons
# with r.thin, traces them into lines with r.to.vect type=line, and exports them with v.out.ogr as
# the layer `roads` of a GeoPackage, in the raster's CRS. Evaluate it with
#   urbanvec evaluate -roads-from <out.gpkg> <any result> <truth.gpkg>
# Usage: grass_centrelines.sh [-overwrite] <landuse.tif> <out.gpkg>
set -euo pipefail

overwrite=0
if [ "${1:-}" = "-overwrite" ]; then overwrite=1; shift; fi
if [ $# -ne 2 ]; then
  echo "Usage: $(basename "$0") [-overwrite] <landuse.tif> <out.gpkg>" >&2
  exit 2
fi
input=$(realpath "$1")
output=$(realpath -m "$2")
if ! gdalinfo "$input" >/dev/null 2>&1; then echo "ERROR: '$1' is not a raster GDAL can read" >&2; exit 1; fi
if [ -e "$output" ] && [ "$overwrite" -eq 0 ]; then
  echo "ERROR: output file '$2' already exists; use -overwrite to replace it" >&2
  exit 1
fi
command -v grass >/dev/null || { echo "ERROR: GRASS GIS ('grass') is not installed" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/steps.sh" <<'STEPS'
set -euo pipefail
r.in.gdal --quiet input="$BASELINE_INPUT" output=landuse
g.region --quiet raster=landuse
r.mapcalc --quiet expression="road_cells = if(landuse == 2 || landuse == 3, 1, null())"
r.thin --quiet input=road_cells output=road_thin
r.to.vect --quiet input=road_thin output=centrelines type=line
v.out.ogr --quiet input=centrelines type=line output="$BASELINE_OUTPUT" format=GPKG output_layer=roads
STEPS
# A throw-away location in the raster's CRS; the output is written beside the target and renamed,
# so a failed run leaves nothing behind.
tmp_output="$(dirname "$output")/.$(basename "$output" .gpkg).tmp-$$.gpkg"
rm -f "$tmp_output"
BASELINE_INPUT="$input" BASELINE_OUTPUT="$tmp_output" \
  grass --tmp-location "$input" --exec bash "$work/steps.sh" >"$work/grass.log" 2>&1 || {
  rm -f "$tmp_output"
  echo "ERROR: GRASS failed on '$1': $(grep -m1 -i 'error' "$work/grass.log" || tail -n1 "$work/grass.log")" >&2
  exit 1
}
mv -f "$tmp_output" "$output"
