#!/usr/bin/env bash
# Inputs that used to give silently wrong output (issue 15): each is now refused with one exact
# `ERROR: ...` line naming the file, option or value, writing nothing, or read correctly, or (evaluate
# on layers that do not overlap) reported with a warning. A grid in degrees or feet, negative or
# non-finite densities, parcel tables separated by semicolons or tabs, result and truth far apart,
# non-finite or absurd `boundary` placement options, and a truncated OpenStreetMap extract.
set -e
# lib.sh, and make_evaluate_fixture for the evaluate case.
EVALUATE_FIXTURE_ONLY=1 source "$(dirname "${BASH_SOURCE[0]}")/test_evaluate.sh"
O="$WORK/out.gpkg"

# grid <out.tif> <GDAL type> <python expression of r (row) and c (column)> [gdal_translate options]: a
# 13 x 13 grid of 10 m cells with its top-left corner at (500000, 5000130) in EPSG:32633 unless the
# options say otherwise, written as raw floats first (ASCII grids cannot hold NaN).
grid() {
  local out=$1 type=$2 expr=$3
  shift 3
  /usr/bin/python3 -c "import struct,sys
vals=[float($expr) for r in range(13) for c in range(13)]
open(sys.argv[1],'wb').write(struct.pack('<%df' % len(vals), *vals))" "$WORK/raw.bin"
  printf 'ENVI\nsamples = 13\nlines = 13\nbands = 1\nheader offset = 0\ndata type = 4\ninterleave = bsq\nbyte order = 0\n' \
    >"$WORK/raw.hdr"
  gdal_translate -q -of GTiff -ot "$type" -a_srs EPSG:32633 -a_ullr 500000 5000130 500130 5000000 "$@" \
    "$WORK/raw.bin" "$out"
  rm -f "$WORK/raw.bin" "$WORK/raw.hdr" "$out.aux.xml"
}

# expect_failure <status> <exact stderr> <urbanvec arguments, output last>: nothing on stdout, the
# output (last argument) not written, no temporary file left.
expect_failure() {
  local status=$1 message=$2
  shift 2
  local output="${*: -1}"
  run_cmd "$@"
  expect_status "$status"
  expect_stderr "$message"
  expect_eq "$OUT" "" "stdout of a failed run"
  expect_missing "$output"
  expect_no_temp "$(dirname "$output")"
}

ROADS='(r in (3, 9) or c in (3, 9))'  # a town of two secondary roads each way
grid "$WORK/town.tif" Byte "2 if $ROADS else 4"
grid "$WORK/parcels.tif" Int32 "0 if $ROADS else 1 + r // 4 * 4 + c // 4"  # one parcel per block corner

# 1. A land-use grid in degrees (or feet) gave areas of 1e-9 "m²" and lengths in degrees: refused,
# with the gdalwarp command to the UTM zone of the grid's centre, as gridify picks it.
grid "$WORK/degrees.tif" Byte "2 if $ROADS else 4" -a_srs EPSG:4326 -a_ullr 7.40 43.75 7.4013 43.7487
expect_failure 1 "ERROR: land-use raster '$WORK/degrees.tif' is in EPSG:4326; vectorize needs a projected CRS in metres (the grid is in degrees); reproject it with gdalwarp -t_srs EPSG:32632" \
  vectorize -q "$WORK/degrees.tif" "$O"
# South of the equator and west of Greenwich: Rio de Janeiro is in zone 23 south.
grid "$WORK/rio.tif" Byte "2 if $ROADS else 4" -a_srs EPSG:4326 -a_ullr -43.20 -22.90 -43.1987 -22.9013
expect_failure 1 "ERROR: land-use raster '$WORK/rio.tif' is in EPSG:4326; vectorize needs a projected CRS in metres (the grid is in degrees); reproject it with gdalwarp -t_srs EPSG:32723" \
  vectorize -q "$WORK/rio.tif" "$O"
# The Monaco sample warped to degrees, as a user would get it from a web portal.
gdalwarp -q -t_srs EPSG:4326 "$SAMPLE_DIR/monaco/landuse.tif" "$WORK/monaco_degrees.tif"
expect_failure 1 "ERROR: land-use raster '$WORK/monaco_degrees.tif' is in EPSG:4326; vectorize needs a projected CRS in metres (the grid is in degrees); reproject it with gdalwarp -t_srs EPSG:32632" \
  vectorize -q "$WORK/monaco_degrees.tif" "$O"
# New York Long Island state plane, in US survey feet (Manhattan: zone 18 north).
grid "$WORK/feet.tif" Byte "2 if $ROADS else 4" -a_srs EPSG:2263 -a_ullr 985000 203000 985130 202870
expect_failure 1 "ERROR: land-use raster '$WORK/feet.tif' is in EPSG:2263; vectorize needs a projected CRS in metres (the grid is in US survey feet); reproject it with gdalwarp -t_srs EPSG:32618" \
  vectorize -q "$WORK/feet.tif" "$O"
# The density raster shares the land-use grid, so its CRS is checked with it: the town in metres runs.
run_cmd vectorize -q "$WORK/town.tif" "$O"
expect_status 0
expect_stderr ""
rm -f "$O"

# 2. Densities: a negative or non-finite population gave negative or lost populations; refused with
# the cell. Nodata cells (a -9999 or a NaN nodata value) count as 0.
DENSITY="0 if $ROADS else 2.5"
for bad in "-4:-4" "float('nan'):nan" "float('inf'):inf" "-float('inf'):-inf"; do
  value=${bad%%:*} shown=${bad#*:}
  grid "$WORK/bad_density.tif" Float32 "$value if (r, c) == (5, 7) else ($DENSITY)"
  expect_failure 1 "ERROR: density raster '$WORK/bad_density.tif' holds value $shown at column 7, row 5, which is not a population per cell (a finite number >= 0; only nodata cells count as 0)" \
    vectorize -q -density "$WORK/bad_density.tif" "$WORK/town.tif" "$O"
done
grid "$WORK/nodata_density.tif" Float32 "-9999 if (r, c) == (5, 7) else ($DENSITY)" -a_nodata -9999
grid "$WORK/nan_nodata_density.tif" Float32 "float('nan') if (r, c) == (5, 7) else ($DENSITY)" -a_nodata nan
grid "$WORK/zero_density.tif" Float32 "0 if (r, c) == (5, 7) else ($DENSITY)"
run_cmd vectorize -q -density "$WORK/zero_density.tif" -parcels "$WORK/parcels.tif" "$WORK/town.tif" "$WORK/zero.gpkg"
expect_status 0
for d in nodata nan_nodata; do
  run_cmd vectorize -q -density "$WORK/${d}_density.tif" -parcels "$WORK/parcels.tif" "$WORK/town.tif" "$WORK/$d.gpkg"
  expect_status 0
  expect_stderr ""
  expect_eq "$(ogr2ogr -f CSV /vsistdout/ "$WORK/$d.gpkg" parcels)" "$(ogr2ogr -f CSV /vsistdout/ "$WORK/zero.gpkg" parcels)" \
    "parcels with a $d cell (as with a 0 cell)"
done

# 3. Parcel tables separated by semicolons or tabs (as spreadsheets save them) were refused as having
# no column 'parcel_id': the separator is detected and the parcels are those of the comma table.
awk 'BEGIN { print "parcel_id,land_use,population,cells";
  for (i = 1; i <= 16; i++) print i "," (i % 2 ? "residential" : "commercial") "," (i * 1.5) ",4" }' >"$WORK/comma.csv"
tr ',' ';' <"$WORK/comma.csv" | sed 's/\.5;/,5;/' >"$WORK/semicolon.csv"  # decimal commas too
tr ',' '\t' <"$WORK/comma.csv" >"$WORK/tab.csv"
grep -q '^1;residential;1,5;4$' "$WORK/semicolon.csv" || fail "semicolon fixture lacks a decimal comma"
PARCELS_OF() { ogr2ogr -f CSV /vsistdout/ "$1" parcels -select parcel_id,land_use,population; }
run_cmd vectorize -q -parcels "$WORK/parcels.tif" -parcel-table "$WORK/comma.csv" "$WORK/town.tif" "$WORK/comma.gpkg"
expect_status 0
COMMA_ERR=$ERR
case "$ERR" in *ERROR*) fail "the comma table failed: $ERR" ;; esac
for t in semicolon tab; do
  run_cmd vectorize -q -parcels "$WORK/parcels.tif" -parcel-table "$WORK/$t.csv" "$WORK/town.tif" "$WORK/$t.gpkg"
  expect_status 0
  expect_stderr "$COMMA_ERR"
  expect_eq "$(PARCELS_OF "$WORK/$t.gpkg")" "$(PARCELS_OF "$WORK/comma.gpkg")" "parcels from the $t table"
done
# A header separated by semicolons but rows by commas: the line says which separator each uses.
{ head -1 "$WORK/semicolon.csv"; tail -n +2 "$WORK/comma.csv"; } >"$WORK/mixed.csv"
expect_failure 1 "ERROR: parcel table '$WORK/mixed.csv' line 2 has too few columns (the header separates columns with semicolons, this line seems to use commas)" \
  vectorize -q -parcels "$WORK/parcels.tif" -parcel-table "$WORK/mixed.csv" "$WORK/town.tif" "$O"
printf 'id;use;population;cells\n1;residential;1;4\n' >"$WORK/renamed.csv"
expect_failure 1 "ERROR: parcel table '$WORK/renamed.csv' has no column 'parcel_id' (expected parcel_id,land_use,population,cells, separated by semicolons)" \
  vectorize -q -parcels "$WORK/parcels.tif" -parcel-table "$WORK/renamed.csv" "$WORK/town.tif" "$O"
# A -classes table separated by semicolons, with a decimal comma.
grid "$WORK/float.tif" Float32 "0.5 if $ROADS else 1.5"
printf 'value;class_name\n0,5;secondary_road\n1,5;residential\n' >"$WORK/classes.csv"
run_cmd vectorize -q -classes "$WORK/classes.csv" "$WORK/float.tif" "$WORK/classes.gpkg"
expect_status 0
expect_eq "$(feature_count "$WORK/classes.gpkg" roads)" "$(feature_count "$WORK/zero.gpkg" roads)" "roads through a ';' -classes table"

# 4. evaluate with a result that lies elsewhere (here: labelled EPSG:32633 while it is in the truth's
# EPSG:32632) reported distances of thousands of cells as if measured: it warns, naming both files
# and extents, and the JSON report says so.
mkdir "$WORK/eval"
make_evaluate_fixture "$WORK/eval" >/dev/null
T="$WORK/eval/truth.gpkg"
json() { /usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"; }
ogr2ogr -f GPKG -a_srs EPSG:32633 "$WORK/eval/elsewhere.gpkg" "$T" roads blocks parcels
run_cmd evaluate -q -json "$WORK/eval/elsewhere.json" "$WORK/eval/elsewhere.gpkg" "$T"
expect_status 0
RX=$(json "$WORK/eval/elsewhere.json" '"x %.10g to %.10g, y %.10g to %.10g" % tuple(d["extent"]["result"][k] for k in ("min_x", "max_x", "min_y", "max_y"))')
expect_stderr "Warning: the result '$WORK/eval/elsewhere.gpkg' ($RX) and the truth '$T' (x 300000 to 300400, y 5000000 to 5000400) do not overlap in EPSG:32632: the distances and matches measure how far apart they lie, not the result; check that both carry the right CRS"
case "$RX" in "x 300000 "*) fail "the result was not moved by its other CRS: $RX" ;; esac
expect_eq "$(json "$WORK/eval/elsewhere.json" 'd["extent"]["overlap"]')" "False" "JSON overlap of layers far apart"
expect_eq "$(json "$WORK/eval/elsewhere.json" 'd["extent"]["truth"]')" \
  "{'min_x': 300000.0, 'min_y': 5000000.0, 'max_x': 300400.0, 'max_y': 5000400.0}" "JSON truth extent"
# The truth against itself overlaps: no warning.
run_cmd evaluate -q -json "$WORK/eval/self.json" "$T" "$T"
expect_status 0
expect_stderr ""
expect_eq "$(json "$WORK/eval/self.json" 'd["extent"]["overlap"]')" "True" "JSON overlap of the truth with itself"

# 5. boundary: -cellsize nan gave a raw SQLite error, -cellsize 1e300 coordinates of 1e302. Every
# real option is finite (the parser) and in a sensible range (the option declarations).
B="$WORK/boundary.gpkg"
expect_failure 2 "ERROR: -cellsize expects a finite number, got 'nan'" boundary -q -cellsize nan "$B"
expect_failure 2 "ERROR: -cellsize must be at most 10000, got 1e300" boundary -q -cellsize 1e300 "$B"
expect_failure 2 "ERROR: -cellsize must be at least 0.001, got 1e-300" boundary -q -cellsize 1e-300 "$B"
expect_failure 2 "ERROR: -center must be at most 1e+08, got 1e300" boundary -q -center 0 1e300 "$B"
expect_failure 2 "ERROR: -center must be at least -1e+08, got -1e300" boundary -q -center -1e300 0 "$B"
expect_failure 2 "ERROR: -center expects a finite number, got 'inf'" boundary -q -center inf 0 "$B"
expect_failure 2 "ERROR: -suburbs expects a finite number, got 'nan'" boundary -q -suburbs nan "$B"
expect_failure 2 "ERROR: -suburbs must be at most 1e+16, got 1e300" boundary -q -suburbs 1e300 "$B"
expect_failure 2 "ERROR: -c2 expects a finite number, got 'nan'" boundary -q -c2 nan "$B"
expect_failure 2 "ERROR: -persistence expects a finite number, got '-inf'" boundary -q -persistence -inf "$B"
expect_failure 2 "ERROR: -fill must lie strictly between 0 and 1, got 1" boundary -q -fill 1 "$B"
# The largest accepted values still give finite coordinates where they were asked for.
run_cmd boundary -q -size 16 -layers 0-4 -no-validate -max-tries 50 -cellsize 10000 -center 1e8 -1e8 \
  -a_srs EPSG:32633 "$B"
expect_status 0
# Within the 16 x 16 pixels of 10 km around the centre.
EXTENT=$(ogrinfo -ro -so "$B" boundary | sed -n 's/^Extent: //p' | tr -d '(),-' | tr -s ' ')
awk -v e="$EXTENT" 'BEGIN { split(e, v, " "); exit !(v[1] >= 99920000 && v[3] <= 100080000 && v[2] >= 99920000 && v[4] <= 100080000 && v[1] < v[3]) }' ||
  fail "extent of the boundary at the largest placement: $EXTENT"
# --help names the units the options take: map units (those of -a_srs, pixels by default), not metres.
run_cmd boundary --help
expect_status 0
HELP_CELLSIZE=$(grep -A1 '^  -cellsize' <<<"$OUT" | tail -1)
HELP_SUBURBS=$(grep -A1 '^  -suburbs' <<<"$OUT" | tail -1)
case "$HELP_CELLSIZE" in *"Unit: map units."*) ;; *) fail "-cellsize help: $HELP_CELLSIZE" ;; esac
case "$HELP_SUBURBS" in *"Unit: square map units."*) ;; *) fail "-suburbs help: $HELP_SUBURBS" ;; esac
case "$HELP_CELLSIZE$HELP_SUBURBS" in *"Unit: m."* | *"Unit: m2."*) fail "metres in the boundary help" ;; esac
# -suburbs really is in square -cellsize units: 200 pixels² at -cellsize 10 are 20000, and keep the
# same suburbs as -suburbs 200 without -cellsize.
run_cmd boundary -q -seed 5 -suburbs 200 "$WORK/sub_pixels.gpkg"
expect_status 0
run_cmd boundary -q -seed 5 -cellsize 10 -suburbs 20000 "$WORK/sub_metres.gpkg"
expect_status 0
PARTS_PIXELS=$(ogrinfo -ro -q -dialect SQLite -sql "SELECT ST_NumGeometries(geom) AS n FROM boundary" "$WORK/sub_pixels.gpkg" | sed -n 's/.*n (Integer) = //p')
PARTS_METRES=$(ogrinfo -ro -q -dialect SQLite -sql "SELECT ST_NumGeometries(geom) AS n FROM boundary" "$WORK/sub_metres.gpkg" | sed -n 's/.*n (Integer) = //p')
[ "${PARTS_PIXELS:-0}" -gt 1 ] || fail "-suburbs 200 kept no suburb ('$PARTS_PIXELS' parts)"
expect_eq "$PARTS_METRES" "$PARTS_PIXELS" "parts with -suburbs in square map units"

# 6. A truncated .pbf was read as far as it went and reported as holding no road: GDAL's read
# failure now names the file as not read completely.
PBF="$SAMPLE_DIR/sources/monaco.osm.pbf"
head -c $(($(stat -c %s "$PBF") / 2)) "$PBF" >"$WORK/half.osm.pbf"
expect_failure 1 "ERROR: input '$WORK/half.osm.pbf' could not be read completely: GDAL failed while reading layer 'lines' (An error occurred during the parsing of data around byte 278144); the file may be truncated or damaged, so download or export it again" \
  gridify -q -tr 8 "$WORK/half.osm.pbf" "$WORK/grid_half"
head -c 1000 "$PBF" >"$WORK/start.osm.pbf"
expect_failure 1 "ERROR: input '$WORK/start.osm.pbf' could not be read completely: GDAL failed while reading layer 'lines' (An error occurred during the parsing of data around byte 187); the file may be truncated or damaged, so download or export it again" \
  gridify -q -tr 8 "$WORK/start.osm.pbf" "$WORK/grid_start"

finish
