#!/usr/bin/env bash
# `urbanvec evaluate` on bad input (issue 2 §3): each case prints one exact `ERROR: ...` line naming
# the file or option, exits 1 (2 for usage), and writes no -json report, not even a temporary one.
set -e
EVALUATE_FIXTURE_ONLY=1 source "$(dirname "${BASH_SOURCE[0]}")/test_evaluate.sh"
make_evaluate_fixture "$WORK" >/dev/null
T="$WORK/truth.gpkg"
R="$WORK/report.json"

# expect_failure <status> <exact stderr> <urbanvec evaluate arguments...>: also checks that no report
# and no temporary file were written.
expect_failure() {
  local status=$1 message=$2
  shift 2
  run_cmd evaluate -q -json "$R" "$@"
  expect_status "$status"
  expect_stderr "$message"
  expect_eq "$OUT" "" "stdout of a failed run"
  expect_missing "$R"
  expect_no_temp "$WORK"
}

# Missing, corrupt and wrongly typed files.
expect_failure 1 "ERROR: result '$WORK/nope.gpkg' does not exist" "$WORK/nope.gpkg" "$T"
expect_failure 1 "ERROR: truth '$WORK/nope.gpkg' does not exist" "$T" "$WORK/nope.gpkg"
echo "not a geopackage" >"$WORK/garbage.gpkg"
expect_failure 1 "ERROR: result '$WORK/garbage.gpkg' is not a vector dataset GDAL can read" "$WORK/garbage.gpkg" "$T"
head -c 20000 "$T" >"$WORK/truncated.gpkg"
expect_failure 1 "ERROR: truth '$WORK/truncated.gpkg' is not a vector dataset GDAL can read (database disk image is malformed)" \
  "$T" "$WORK/truncated.gpkg"
expect_failure 1 "ERROR: result '$WORK/landuse.tif' is a raster, not a vector dataset" "$WORK/landuse.tif" "$T"
expect_failure 1 "ERROR: truth '$WORK/landuse.tif' is a raster, not a vector dataset" "$T" "$WORK/landuse.tif"
expect_failure 1 "ERROR: result roads '$WORK/nope.gpkg' does not exist" -roads-from "$WORK/nope.gpkg" "$T" "$T"
expect_failure 1 "ERROR: result roads: layer 'blocks' of '$T' holds polygons; it must hold lines" \
  -roads-layer blocks "$T" "$T"
expect_failure 1 "ERROR: result parcels: layer 'roads' of '$T' holds lines; it must hold polygons" \
  -parcels-layer roads "$T" "$T"
expect_failure 1 "ERROR: result blocks: layer 'grid_info' of '$T' has no geometry; it must hold polygons" \
  -blocks-layer grid_info "$T" "$T"
gdal_polygonize.py -q "$WORK/landuse.tif" -f GPKG "$WORK/poly.gpkg" >/dev/null
expect_failure 1 "ERROR: truth '$WORK/poly.gpkg' has none of the layers roads, blocks, parcels (its layers: out)" \
  "$T" "$WORK/poly.gpkg" -cell-size 10

# CRS: a layer without one is an error; another projected CRS is reprojected to the truth's; a truth
# in degrees cannot give distances in metres.
ogr2ogr -f GPKG "$WORK/nocrs.gpkg" "$WORK/roads.csv" -oo GEOM_POSSIBLE_NAMES=WKT -oo KEEP_GEOM_COLUMNS=NO -nln roads
expect_failure 1 "ERROR: result roads: layer 'roads' of '$WORK/nocrs.gpkg' has no CRS; assign one with ogr2ogr -a_srs EPSG:32632" \
  "$WORK/nocrs.gpkg" "$T"
expect_failure 1 "ERROR: truth roads: layer 'roads' of '$WORK/nocrs.gpkg' has no CRS; assign one with ogr2ogr -a_srs" \
  "$T" "$WORK/nocrs.gpkg" -cell-size 10
ogr2ogr -f GPKG -t_srs EPSG:4326 "$WORK/degrees.gpkg" "$T" roads blocks parcels
expect_failure 1 "ERROR: truth '$WORK/degrees.gpkg' is in EPSG:4326, not a projected CRS in metres; reproject it with ogr2ogr -t_srs" \
  "$T" "$WORK/degrees.gpkg" -cell-size 10
ogr2ogr -f GPKG -t_srs EPSG:3857 "$WORK/mercator.gpkg" "$T" roads blocks parcels
run_cmd evaluate -q -json "$R" "$WORK/mercator.gpkg" "$T"
expect_status 0
expect_eq "$(jq '.roads.distance_result_to_truth.p95_cells < 0.001' "$R")" "true" "reprojected roads lie on the truth"
expect_eq "$(jq '.blocks.matched_share' "$R")" "1" "reprojected blocks match"
rm -f "$R"

# Cell size: from grid_info, else -cell-size, else an error.
ogr2ogr -f GPKG "$WORK/nogrid.gpkg" "$T" roads blocks parcels
expect_failure 1 "ERROR: truth '$WORK/nogrid.gpkg' has no grid_info table giving the cell size; give -cell-size <metres>" \
  "$T" "$WORK/nogrid.gpkg"
run_cmd evaluate -q -cell-size 20 -json "$R" "$T" "$WORK/nogrid.gpkg"
expect_status 0
expect_eq "$(jq '.cell_size_m' "$R")" "20" "-cell-size"
rm -f "$R"

# Options.
expect_failure 2 "ERROR: unknown option '-bogus' (see 'urbanvec evaluate --help')" -bogus "$T" "$T"
expect_failure 2 "ERROR: 'urbanvec evaluate' expects <result> <truth>, got 1 argument" "$T"
expect_failure 2 "ERROR: -cell-size must be at least 1e-06, got 0" -cell-size 0 "$T" "$T"
expect_failure 2 "ERROR: -min-iou expects a number, got 'high'" -min-iou high "$T" "$T"
expect_failure 2 "ERROR: -blocks-where 'NOPE > 1' cannot select features of layer 'blocks' of '$T' (failed to prepare SQL: SELECT m.\"fid\", m.\"geom\", m.\"block_id\", m.\"kind\" FROM \"blocks\" m WHERE NOPE > 1)" \
  -blocks-where "NOPE > 1" "$T" "$T"

# The -json output: an unwritable place, or an existing file without -overwrite.
run_cmd evaluate -q -json "$WORK/no/such/folder/report.json" "$T" "$T"
expect_status 1
expect_stderr "ERROR: cannot write output file '$WORK/no/such/folder/report.json': folder '$WORK/no/such/folder' does not exist"
expect_eq "$OUT" "" "stdout of a failed run"
echo "keep me" >"$R"
run_cmd evaluate -q -json "$R" "$T" "$T"
expect_status 1
expect_stderr "ERROR: output file '$R' already exists; use -overwrite to replace it"
expect_eq "$(cat "$R")" "keep me" "an existing report without -overwrite"
run_cmd evaluate -q -overwrite -json "$R" "$T" "$T"
expect_status 0
expect_eq "$(jq '.roads.turning_ratio' "$R")" "1" "an existing report with -overwrite"
expect_no_temp "$WORK"

finish
