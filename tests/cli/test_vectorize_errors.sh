#!/usr/bin/env bash
# `urbanvec vectorize` on bad input (issue 3 "Bad input"): degenerate grids that still vectorize give
# valid (possibly empty) layers and one exact warning line with exit 0; broken input gives one exact
# `ERROR: ...` line naming the file and what is wrong, exit 1 (2 for usage), and writes nothing, not
# even a temporary file. Every raster is built here with gdal_translate from an ASCII grid.
set -e
source "$(dirname "$0")/lib.sh"
O="$WORK/out.gpkg"

# raster <out.tif> <GDAL type> <columns> <rows> <awk expression of r (row) and c (column)> [gdal_translate
# options]: a grid of 10 m cells with its top-left corner at (500000, 5000130), EPSG:32633 unless the
# options say otherwise (-a_srs, -a_ullr, ...).
raster() {
  local out=$1 type=$2 cols=$3 rows=$4 expr=$5
  shift 5
  {
    printf 'ncols %s\nnrows %s\nxllcorner 500000\nyllcorner %s\ncellsize 10\n' "$cols" "$rows" $((5000130 - 10 * rows))
    awk -v R="$rows" -v C="$cols" "BEGIN { for (r = 0; r < R; r++) { line = \"\";
      for (c = 0; c < C; c++) line = line (c ? \" \" : \"\") ($expr); print line } }"
  } >"$WORK/grid.asc"
  gdal_translate -q -ot "$type" "$@" "$WORK/grid.asc" "$out"
  rm -f "$WORK/grid.asc" "$out.aux.xml"
}
SRS=(-a_srs EPSG:32633)
ROADS='(r == 3 || r == 9 || c == 3 || c == 9) ? 2 : 4'  # a 13x13 town: two secondary roads each way
raster "$WORK/town.tif" Byte 13 13 "$ROADS" "${SRS[@]}"
raster "$WORK/density.tif" Float32 13 13 '(r == 3 || r == 9 || c == 3 || c == 9) ? 0 : 2.5' "${SRS[@]}"
PARCEL_ID='1 + int(r / 4) * 4 + int(c / 4)'  # one parcel per block corner; 0 on roads
raster "$WORK/parcels.tif" Int32 13 13 "(r == 3 || r == 9 || c == 3 || c == 9) ? 0 : $PARCEL_ID" "${SRS[@]}"

# expect_failure <status> <exact stderr> <urbanvec vectorize arguments before the output>: also checks
# that nothing was written: no output, no temporary file, no stdout.
expect_failure() {
  local status=$1 message=$2
  shift 2
  run_cmd vectorize -q "$@" "$O"
  expect_status "$status"
  expect_stderr "$message"
  expect_eq "$OUT" "" "stdout of a failed run"
  expect_missing "$O"
  expect_no_temp "$WORK"
}

# expect_warning <exact warning line> <urbanvec vectorize arguments before the output>: exit 0, the
# warning among the stderr lines, and a GeoPackage with every output layer that GDAL can read.
expect_warning() {
  local warning=$1
  shift
  rm -f "$O"
  run_cmd vectorize -q -check "$@" "$O"
  expect_status 0
  grep -qxF -- "$warning" <<<"$ERR" || fail "stderr lacks the line '$warning': '$ERR'"
  case "$ERR" in *ERROR*) fail "a warning run printed an error: '$ERR'" ;; esac
  expect_stdout_contains " 0 crossings, 0 zero-length pieces, 0 duplicate nodes, 0 segment ends without a node"
  expect_exists "$O"
  local layers
  layers=$(ogrinfo -ro -q "$O" 2>/dev/null | sed -n 's/^[0-9]*: \([a-z_]*\).*/\1/p' | grep -v layer_styles | sort | tr '\n' ' ')
  expect_eq "$layers" "blocks parcels pavement road_nodes roads spines vectorize_report water " "layers of $*"
  case "$(ogrinfo -ro -so "$O" roads)" in *"Geometry: Line String"*) ;; *) fail "roads are not LineStrings ($*)" ;; esac
  case "$(ogrinfo -ro -so "$O" road_nodes)" in *"Geometry: Point"*) ;; *) fail "road_nodes are not Points ($*)" ;; esac
  expect_no_temp "$WORK"
}

# The sound town vectorizes cleanly, with no warning: the fixtures below differ from it in one thing.
run_cmd vectorize -q -check -density "$WORK/density.tif" -parcels "$WORK/parcels.tif" "$WORK/town.tif" "$O"
expect_status 0
expect_stderr ""
expect_stdout_contains "road cells farther than 1.5 cells from a road: 0 of 48 "
TOWN_ROADS=$(feature_count "$O" roads)
[ "$TOWN_ROADS" -gt 10 ] || fail "the town has only '$TOWN_ROADS' road segments"
rm -f "$O"

# No road cells: valid empty road layers and a warning.
raster "$WORK/noroad.tif" Byte 13 13 '4' "${SRS[@]}"
expect_warning "Warning: the land-use grid has no road cells (codes 2 and 3): the road layers are empty" \
  "$WORK/noroad.tif"
expect_eq "$(feature_count "$O" roads)" "0" "roads of a grid without road cells"
expect_eq "$(feature_count "$O" road_nodes)" "0" "road nodes of a grid without road cells"

# Every cell road (secondary, then primary): no blocks, no parcels, a collapsed but valid network.
ALL_ROAD="Warning: every cell of the land-use grid is road: there are no blocks, and the road network collapses to intersection clusters"
for code in 2 3; do
  raster "$WORK/allroad.tif" Byte 13 13 "$code" "${SRS[@]}"
  expect_warning "$ALL_ROAD" "$WORK/allroad.tif"
  expect_eq "$(feature_count "$O" blocks)" "0" "blocks of an all-road grid (code $code)"
  expect_eq "$(feature_count "$O" parcels)" "0" "parcels of an all-road grid (code $code)"
done

# 1x1 grids: one road cell, one residential cell.
raster "$WORK/one.tif" Byte 1 1 '2' "${SRS[@]}"
expect_warning "$ALL_ROAD" "$WORK/one.tif"
expect_eq "$(feature_count "$O" roads)" "0" "roads of a 1x1 road grid"
raster "$WORK/one.tif" Byte 1 1 '4' "${SRS[@]}"
expect_warning "Warning: the land-use grid has no road cells (codes 2 and 3): the road layers are empty" "$WORK/one.tif"
rm -f "$O"

# -keep-all-roads switches B4 and B5 removal off: giving their thresholds as well is refused.
expect_failure 2 "ERROR: -keep-all-roads switches the road removals off; do not give -cycle-nodes with it" \
  -keep-all-roads -cycle-nodes 12 "$WORK/town.tif"
expect_failure 2 "ERROR: -keep-all-roads switches the road removals off; do not give -dead-end-angle with it" \
  -keep-all-roads -dead-end-angle 45 "$WORK/town.tif"
expect_failure 2 "ERROR: -road-removals none switches the road removals off; do not give -cycle-nodes with it" \
  -road-removals none -cycle-nodes 12 "$WORK/town.tif"
expect_failure 2 "ERROR: -keep-all-roads is -road-removals none; do not give -road-removals paper with it" \
  -keep-all-roads -road-removals paper "$WORK/town.tif"

# A float raster whose values are not class codes is refused, pointing at -classes; with a -classes
# table it works, and a table that misses a value names it. Float cells holding whole codes are fine.
raster "$WORK/float.tif" Float32 13 13 '(r == 3 || r == 9 || c == 3 || c == 9) ? 0.25 : 0.75' "${SRS[@]}"
expect_failure 1 "ERROR: land-use raster '$WORK/float.tif' (Float32) holds value 0.75 at column 0, row 0, which is not a land-use class code (0..8, 255 = nodata); map its values to classes with -classes <csv>" \
  "$WORK/float.tif"
printf 'value,class_name\n0.25,secondary_road\n0.75,residential\n' >"$WORK/classes.csv"
run_cmd vectorize -q -classes "$WORK/classes.csv" "$WORK/float.tif" "$O"
expect_status 0
expect_eq "$(feature_count "$O" roads)" "$TOWN_ROADS" "road segments of the float town mapped with -classes"
rm -f "$O"
printf 'value,class_name\n0.25,secondary_road\n' >"$WORK/classes_short.csv"
expect_failure 1 "ERROR: land-use raster '$WORK/float.tif' holds value 0.75 at column 0, row 0, which -classes table '$WORK/classes_short.csv' does not map (add a line '0.75,<class name>')" \
  -classes "$WORK/classes_short.csv" "$WORK/float.tif"
raster "$WORK/float_codes.tif" Float32 13 13 "$ROADS" "${SRS[@]}"
run_cmd vectorize -q "$WORK/float_codes.tif" "$O"
expect_status 0
expect_stderr ""
expect_eq "$(feature_count "$O" roads)" "$TOWN_ROADS" "road segments of the town as Float32 codes"
rm -f "$O"

# Negative parcel ids. CONVENTIONS.md defines parcels.tif as "parcel (ownership) id per cell, 0 = none";
# the "negative" parcels of the spec (E3) and of the parcels layer's `undeveloped` land use are parcels
# the vectorizer makes, not input ids. So a negative id in the raster is an error naming the first one.
raster "$WORK/negative.tif" Int32 13 13 "(r == 3 || r == 9 || c == 3 || c == 9) ? 0 : -($PARCEL_ID)" "${SRS[@]}"
expect_failure 1 "ERROR: parcels raster '$WORK/negative.tif' holds negative parcel id -1 at column 0, row 0 (ids must be >= 0, 0 = no parcel)" \
  -parcels "$WORK/negative.tif" "$WORK/town.tif"

# Parcel tables: ids not in the raster are an error; raster ids missing from the table are derived
# from the rasters, with a warning.
printf 'parcel_id,land_use,population,cells\n1,residential,10,9\n99,commercial,5,3\n' >"$WORK/table_extra.csv"
expect_failure 1 "ERROR: parcel table '$WORK/table_extra.csv' line 3 names parcel id 99, which is not in the parcels raster '$WORK/parcels.tif'" \
  -parcels "$WORK/parcels.tif" -parcel-table "$WORK/table_extra.csv" "$WORK/town.tif"
printf 'parcel_id,land_use,population,cells\n1,residential,10,9\n' >"$WORK/table_short.csv"
run_cmd vectorize -q -parcels "$WORK/parcels.tif" -parcel-table "$WORK/table_short.csv" "$WORK/town.tif" "$O"
expect_status 0
expect_stderr "Warning: 15 parcel ids of parcels raster '$WORK/parcels.tif' are not in parcel table '$WORK/table_short.csv'; their use and population are derived from the rasters"
rm -f "$O"
expect_failure 1 "ERROR: -parcel-table '$WORK/table_short.csv' needs the parcel raster (-parcels) that holds the parcels' cells" \
  -parcel-table "$WORK/table_short.csv" "$WORK/town.tif"
expect_failure 1 "ERROR: parcel table '$WORK/nope.csv' does not exist" \
  -parcels "$WORK/parcels.tif" -parcel-table "$WORK/nope.csv" "$WORK/town.tif"
expect_failure 1 "ERROR: -classes table '$WORK/nope.csv' does not exist" -classes "$WORK/nope.csv" "$WORK/town.tif"

# Rasters given together must be one grid; the error names both rasters, what differs, and both values.
SAME="; rasters given together must share size, geotransform and CRS"
raster "$WORK/narrow.tif" Float32 12 13 '1' "${SRS[@]}"
expect_failure 1 "ERROR: density raster '$WORK/narrow.tif' and land-use raster '$WORK/town.tif' differ in size: 12x13 vs 13x13 cells$SAME" \
  -density "$WORK/narrow.tif" "$WORK/town.tif"
raster "$WORK/shifted.tif" Float32 13 13 '1' "${SRS[@]}" -a_ullr 500010 5000130 500140 5000000
expect_failure 1 "ERROR: density raster '$WORK/shifted.tif' and land-use raster '$WORK/town.tif' differ in geotransform origin: (500010, 5000130) vs (500000, 5000130)$SAME" \
  -density "$WORK/shifted.tif" "$WORK/town.tif"
raster "$WORK/coarse.tif" Int32 13 13 '0' "${SRS[@]}" -a_ullr 500000 5000130 500260 4999870
expect_failure 1 "ERROR: parcels raster '$WORK/coarse.tif' and land-use raster '$WORK/town.tif' differ in geotransform pixel size: (20, -20) vs (10, -10)$SAME" \
  -parcels "$WORK/coarse.tif" "$WORK/town.tif"
raster "$WORK/utm32.tif" Int32 13 13 '0' -a_srs EPSG:32632
expect_failure 1 "ERROR: parcels raster '$WORK/utm32.tif' and land-use raster '$WORK/town.tif' differ in CRS: EPSG:32632 vs EPSG:32633$SAME" \
  -parcels "$WORK/utm32.tif" "$WORK/town.tif"
raster "$WORK/nocrs.tif" Float32 13 13 '1'
expect_failure 1 "ERROR: density raster '$WORK/nocrs.tif' and land-use raster '$WORK/town.tif' differ in CRS: no CRS vs EPSG:32633$SAME" \
  -density "$WORK/nocrs.tif" "$WORK/town.tif"

# Missing and non-raster files.
expect_failure 1 "ERROR: land-use raster '$WORK/nope.tif' does not exist" "$WORK/nope.tif"
expect_failure 1 "ERROR: density raster '$WORK/nope.tif' does not exist" -density "$WORK/nope.tif" "$WORK/town.tif"
echo "not a raster" >"$WORK/text.tif"
expect_failure 1 "ERROR: land-use raster '$WORK/text.tif' is not a raster GDAL can read" "$WORK/text.tif"
expect_failure 1 "ERROR: parcels raster '$WORK/text.tif' is not a raster GDAL can read" \
  -parcels "$WORK/text.tif" "$WORK/town.tif"
# Usage errors.
expect_failure 2 "ERROR: unknown option '-bogus' (see 'urbanvec vectorize --help')" -bogus "$WORK/town.tif"
run_cmd vectorize -q "$WORK/town.tif"
expect_status 2
expect_stderr "ERROR: 'urbanvec vectorize' expects <landuse> <output>, got 1 argument"

# A failed run with -debug-stages leaves no debug folder behind either.
expect_failure 1 "ERROR: land-use raster '$WORK/nope.tif' does not exist" -debug-stages "$WORK/debug/stages" "$WORK/nope.tif"
expect_missing "$WORK/debug"

# Unwritable outputs: a folder that does not exist, a folder in the output's place, and (when not
# root, who may write anywhere) a read-only folder.
run_cmd vectorize -q "$WORK/town.tif" "$WORK/no/such/folder/out.gpkg"
expect_status 1
expect_stderr "ERROR: cannot write output file '$WORK/no/such/folder/out.gpkg': folder '$WORK/no/such/folder' does not exist"
mkdir "$WORK/folder.gpkg"
run_cmd vectorize -q -overwrite "$WORK/town.tif" "$WORK/folder.gpkg"
expect_status 1
expect_stderr "ERROR: output file '$WORK/folder.gpkg' exists and is a folder"
expect_eq "$(ls -A "$WORK/folder.gpkg")" "" "a folder in the output's place stays empty"
# A read-only folder, also when the tests run as root (run_unprivileged).
mkdir "$WORK/readonly"
chmod 555 "$WORK/readonly"
run_unprivileged vectorize -q "$WORK/town.tif" "$WORK/readonly/out.gpkg"
expect_status 1
expect_stderr "ERROR: cannot write output file '$WORK/readonly/out.gpkg': folder '$WORK/readonly' is not writable"
expect_eq "$(ls -A "$WORK/readonly")" "" "a read-only folder stays empty"
chmod u+w "$WORK/readonly"

# An existing output without -overwrite is an error and stays untouched; with -overwrite it is replaced.
echo "keep me" >"$O"
run_cmd vectorize -q "$WORK/town.tif" "$O"
expect_status 1
expect_stderr "ERROR: output file '$O' already exists; use -overwrite to replace it"
expect_eq "$(cat "$O")" "keep me" "an existing output without -overwrite"
expect_no_temp "$WORK"
run_cmd vectorize -q -overwrite "$WORK/town.tif" "$O"
expect_status 0
expect_eq "$(feature_count "$O" roads)" "$TOWN_ROADS" "road segments after -overwrite"
expect_no_temp "$WORK"

finish
