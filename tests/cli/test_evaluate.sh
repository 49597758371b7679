#!/usr/bin/env bash
# `urbanvec evaluate` (issue 2 §3): the printed table and JSON report on a hand-made 40 x 40 cell city
# (cells of 10 m, EPSG:32632): the truth against itself, a result whose roads are shifted by half a
# cell, and the naive gdal_polygonize.py output of its land-use raster.
set -e
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# make_evaluate_fixture <dir>: writes <dir>/truth.gpkg (roads, blocks, parcels, grid_info),
# <dir>/shifted.gpkg (the truth with every road moved 5 m east and 5 m north) and <dir>/landuse.tif.
make_evaluate_fixture() {
  local d=$1
  local x0=300000 y0=5000000
  # Roads: a west-east secondary road along the centres of row 19, a south-north primary road along
  # column 20, an L-shaped secondary road (one 90 degree turn) and the perimeter staircase.
  cat >"$d/roads.csv" <<CSV
WKT,road_class
"LINESTRING (300005 5000205,300395 5000205)",secondary
"LINESTRING (300205 5000005,300205 5000395)",primary
"LINESTRING (300055 5000055,300055 5000155,300155 5000155)",secondary
"LINESTRING (300000 5000000,300400 5000000,300400 5000400,300000 5000400,300000 5000000)",perimeter
CSV
  cat >"$d/blocks.csv" <<CSV
WKT,block_id,kind
"POLYGON ((300000 5000210,300200 5000210,300200 5000400,300000 5000400,300000 5000210))",1,internal
"POLYGON ((300210 5000210,300400 5000210,300400 5000400,300210 5000400,300210 5000210))",2,internal
"POLYGON ((300000 5000000,300200 5000000,300200 5000200,300000 5000200,300000 5000000))",3,internal
"POLYGON ((300210 5000000,300400 5000000,300400 5000200,300210 5000200,300210 5000000))",4,internal
CSV
  cat >"$d/parcels.csv" <<CSV
WKT,parcel_id,block_id,land_use,code
"POLYGON ((300000 5000210,300100 5000210,300100 5000400,300000 5000400,300000 5000210))",1,1,residential,4
"POLYGON ((300100 5000210,300200 5000210,300200 5000400,300100 5000400,300100 5000210))",2,1,residential,4
"POLYGON ((300210 5000210,300300 5000210,300300 5000400,300210 5000400,300210 5000210))",3,2,commercial,5
"POLYGON ((300300 5000210,300400 5000210,300400 5000400,300300 5000400,300300 5000210))",4,2,residential,4
"POLYGON ((300000 5000000,300100 5000000,300100 5000200,300000 5000200,300000 5000000))",5,3,industrial,6
"POLYGON ((300100 5000000,300200 5000000,300200 5000200,300100 5000200,300100 5000000))",6,3,park,7
"POLYGON ((300210 5000000,300300 5000000,300300 5000200,300210 5000200,300210 5000000))",7,4,residential,4
"POLYGON ((300300 5000000,300400 5000000,300400 5000200,300300 5000200,300300 5000000))",8,4,residential,4
CSV
  cat >"$d/grid_info.csv" <<CSV
cell_size,width,height,geotransform,crs
10,40,40,300000 10 0 5000400 0 -10,EPSG:32632
CSV
  local csv="-oo GEOM_POSSIBLE_NAMES=WKT -oo KEEP_GEOM_COLUMNS=NO -oo AUTODETECT_TYPE=YES"
  ogr2ogr -f GPKG -a_srs EPSG:32632 $csv -nlt LINESTRING -nln roads "$d/truth.gpkg" "$d/roads.csv"
  ogr2ogr -update -a_srs EPSG:32632 $csv -nlt POLYGON -nln blocks "$d/truth.gpkg" "$d/blocks.csv"
  ogr2ogr -update -a_srs EPSG:32632 $csv -nlt POLYGON -nln parcels "$d/truth.gpkg" "$d/parcels.csv"
  ogr2ogr -update -oo AUTODETECT_TYPE=YES -nln grid_info "$d/truth.gpkg" "$d/grid_info.csv"
  ogr2ogr -f GPKG "$d/shifted.gpkg" "$d/truth.gpkg" blocks parcels
  ogr2ogr -update -nln roads -dialect SQLite \
    -sql "SELECT ST_Translate(geom, 5, 5, 0) AS geom, road_class FROM roads" "$d/shifted.gpkg" "$d/truth.gpkg"
  # The land-use raster of the same city: parcels with their class code, then road cells (2).
  gdal_create -q -of GTiff -outsize 40 40 -bands 1 -ot Byte -burn 0 -a_srs EPSG:32632 \
    -a_ullr $x0 $((y0 + 400)) $((x0 + 400)) $y0 "$d/landuse.tif"
  gdal_rasterize -q -a code -l parcels "$d/truth.gpkg" "$d/landuse.tif"
  gdal_rasterize -q -burn 2 -where "road_class <> 'perimeter'" -l roads "$d/truth.gpkg" "$d/landuse.tif"
}

if [ "${EVALUATE_FIXTURE_ONLY:-0}" = 1 ]; then return 0; fi

make_evaluate_fixture "$WORK" >/dev/null
T="$WORK/truth.gpkg"

# json <file> <python expression over d>: prints the value of the expression.
json() { /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"; }

# 1. The truth against itself: zero distances, turning ratio 1, every block matched, no error.
run_cmd evaluate -q -json "$WORK/self.json" "$T" "$T"
expect_status 0
expect_stderr ""
expect_stdout_contains "roads: distance truth->result median    0.00 m = 0.000 cells"
expect_stdout_contains "roads: distance result->truth p95       0.00 m = 0.000 cells"
expect_stdout_contains "roads: turning ratio result/truth       1.000"
expect_stdout_contains "blocks: matched share (IoU >= 0.7)      1.0000 (4 of 4)"
expect_stdout_contains "parcels: count ratio per matched block  mean 1.000, median 1.000 (4 blocks)"
expect_stdout_contains "parcels: land-use share error (L1)      0.0000"
expect_stdout_contains "parcels: gap share                      0.0000"
expect_stdout_contains "parcels: invalid geometries             0.0000 (0 of 8)"
expect_eq "$(json "$WORK/self.json" 'd["cell_size_m"]')" "10.0" "cell size from grid_info"
expect_eq "$(json "$WORK/self.json" 'd["roads"]["truth_lines"]')" "3" "roads counted without the perimeter"
expect_eq "$(json "$WORK/self.json" 'd["roads"]["distance_truth_to_result"]["median_m"]')" "0.0" "self distance"
expect_eq "$(json "$WORK/self.json" 'd["roads"]["distance_result_to_truth"]["p95_cells"]')" "0.0" "self p95"
expect_eq "$(json "$WORK/self.json" 'd["roads"]["turning_ratio"]')" "1.0" "self turning ratio"
expect_eq "$(json "$WORK/self.json" 'd["blocks"]["matched_share"]')" "1.0" "self block matches"
expect_eq "$(json "$WORK/self.json" 'd["blocks"]["mean_best_iou"]')" "1.0" "self IoU"
expect_eq "$(json "$WORK/self.json" 'd["parcels"]["count_ratio_mean"]')" "1.0" "self count ratio"
expect_eq "$(json "$WORK/self.json" 'd["parcels"]["overlap_share"]')" "0.0" "self overlaps"
expect_eq "$(json "$WORK/self.json" 'd["parcels"]["invalid_share"]')" "0.0" "self invalid"
# 1.25 km of roads: 390 + 390 + 200 m; 90 degrees over 0.98 km.
expect_eq "$(json "$WORK/self.json" 'round(d["roads"]["truth_length_km"], 6)')" "0.98" "truth road length"
expect_eq "$(json "$WORK/self.json" 'round(d["roads"]["truth_turning_deg_per_km"], 4)')" "91.8367" "truth turning"

# 2. Roads moved half a cell both ways: the bulk of the samples lie exactly 0.5 cell away.
run_cmd evaluate -q -json "$WORK/shifted.json" "$WORK/shifted.gpkg" "$T"
expect_status 0
expect_stdout_contains "roads: distance truth->result median    5.00 m = 0.500 cells"
expect_stdout_contains "roads: distance result->truth median    5.00 m = 0.500 cells"
expect_eq "$(json "$WORK/shifted.json" 'd["roads"]["distance_truth_to_result"]["median_cells"]')" "0.5" "shifted median"
expect_eq "$(json "$WORK/shifted.json" 'd["roads"]["turning_ratio"]')" "1.0" "a shift does not turn"
# A quarter cell is 2.5 m: 980 m of road gives 392 samples.
expect_eq "$(json "$WORK/shifted.json" 'd["roads"]["distance_truth_to_result"]["samples"]')" "392" "samples"

# 3. Progress on stdout comes before the table, as GDAL prints it.
run_cmd evaluate "$T" "$T"
expect_status 0
case "$OUT" in "0...10...20...30...40...50...60...70...80...90...100 - done."*"result roads"*) ;;
  *) fail "progress should end before the table: '$OUT'";; esac

# 4. The naive approach: gdal_polygonize.py output. Without options its layer 'out' is none of
#    roads/blocks/parcels: every result metric is absent (null), never 0, and the run succeeds.
gdal_polygonize.py -q "$WORK/landuse.tif" -f GPKG "$WORK/poly.gpkg" >/dev/null
run_cmd evaluate -q -json "$WORK/poly.json" "$WORK/poly.gpkg" "$T"
expect_status 0
expect_stderr_contains "Warning: '$WORK/poly.gpkg' has no layer 'roads' (its layers: out); road metrics are absent (choose a layer with -roads-layer)"
expect_stdout_contains "result roads                            absent"
expect_stdout_contains "roads: distance truth->result median    absent"
expect_stdout_contains "blocks: matched share (IoU >= 0.7)      absent"
expect_stdout_contains "parcels: gap share                      absent"
expect_eq "$(json "$WORK/poly.json" 'd["roads"]["distance_truth_to_result"]')" "None" "absent distance is null"
expect_eq "$(json "$WORK/poly.json" 'd["roads"]["turning_ratio"]')" "None" "absent ratio is null"
expect_eq "$(json "$WORK/poly.json" 'd["blocks"]["matched_share"]')" "None" "absent blocks are null"
expect_eq "$(json "$WORK/poly.json" 'd["parcels"]["invalid_share"]')" "None" "absent parcels are null"
expect_eq "$(json "$WORK/poly.json" 'd["roads"]["truth_lines"]')" "3" "truth side still measured"

#    Pointed at its polygons without naming the land-use field, the land-use error alone is absent.
run_cmd evaluate -q -blocks-layer out -parcels-layer out "$WORK/poly.gpkg" "$T"
expect_status 0
expect_stderr_contains "Warning: the result parcels ('out' of '$WORK/poly.gpkg') have no field 'land_use'; the land-use share error is absent (choose a field with -landuse-field)"
expect_stdout_contains "parcels: land-use share error (L1)      absent"

#    Pointed at its polygons of developed land (DN >= 4) as blocks and parcels, it measures them:
#    each land-use patch is one block, so the two-parcel blocks of the truth are merged or split.
run_cmd evaluate -q -json "$WORK/poly2.json" -blocks-layer out -blocks-where "DN >= 4" -parcels-layer out \
  -parcels-where "DN >= 4" -landuse-field DN "$WORK/poly.gpkg" "$T"
expect_status 0
expect_stdout_contains "result blocks                           'out' of '$WORK/poly.gpkg' where DN >= 4"
expect_eq "$(json "$WORK/poly2.json" 'd["blocks"]["result_count"]')" "6" "polygonized patches"
# Block 1 (all residential) and block 4 (all residential) come back whole; blocks 2 and 3 are split.
expect_eq "$(json "$WORK/poly2.json" 'd["blocks"]["matched_count"]')" "2" "polygonize matches"
expect_eq "$(json "$WORK/poly2.json" 'd["parcels"]["count_ratio_mean"]')" "0.5" "one patch for two parcels"
expect_eq "$(json "$WORK/poly2.json" 'd["parcels"]["landuse_share_error_mean"]')" "0.0" "land use by DN code"
expect_eq "$(json "$WORK/poly2.json" 'd["parcels"]["gap_share"]')" "0.0" "a patch fills its block"
expect_eq "$(json "$WORK/poly2.json" 'd["roads"]["distance_truth_to_result"]')" "None" "no roads in polygons"

# 5. The real sample: Monaco's truth against itself gives zero distances, a turning ratio of 1 and
#    every block matched.
M="$SAMPLE_DIR/monaco/truth.gpkg"
run_cmd evaluate -q -json "$WORK/monaco.json" "$M" "$M"
expect_status 0
# (zero up to rounding: the samples are interpolated along segments in UTM coordinates of ~1e6 m)
expect_eq "$(jq '[.roads.distance_truth_to_result.p95_m, .roads.distance_result_to_truth.p95_m] | max < 1e-6' "$WORK/monaco.json")" \
  "true" "Monaco self distances"
expect_eq "$(jq '.roads.turning_ratio' "$WORK/monaco.json")" "1" "Monaco self turning ratio"
expect_eq "$(jq '.blocks.matched_share' "$WORK/monaco.json")" "1" "Monaco self block matches"
expect_eq "$(jq '.parcels.count_ratio_median' "$WORK/monaco.json")" "1" "Monaco self parcel counts"
expect_eq "$(jq '.parcels.landuse_share_error_mean' "$WORK/monaco.json")" "0" "Monaco self land use"
expect_eq "$(jq '.parcels.overlap_share < 1e-9' "$WORK/monaco.json")" "true" "Monaco self overlaps"

finish
