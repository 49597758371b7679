#!/usr/bin/env bash
# `urbanvec gridify` on the real sources: georeferenced rasters, truth layers, and every bad input
# (exact message, exit status, nothing written).
set -e
source "$(dirname "$0")/lib.sh"
SRC="$SAMPLE_DIR/sources"

# Bubenec (GeoPackage with real plots): small and fast.
run_cmd gridify -q -tr 6 -t_srs EPSG:32633 -roads-layer streets -buildings-layer buildings -parcels-layer plots \
  "$SRC/bubenec.gpkg" "$WORK/bub"
expect_status 0
for f in landuse.tif density.tif parcels.tif parcels.csv truth.gpkg; do expect_exists "$WORK/bub/$f"; done
info=$(gdalinfo "$WORK/bub/landuse.tif")
case "$info" in *'ID["EPSG",32633]]'*) ;; *) fail "landuse.tif lacks EPSG:32633";; esac
case "$info" in *"Pixel Size = (6.000000000000000,-6.000000000000000)"*) ;; *) fail "landuse.tif pixel size is not 6 m";; esac
case "$info" in *"Type=Byte"*) ;; *) fail "landuse.tif is not Byte";; esac
case "$(gdalinfo "$WORK/bub/density.tif")" in *"Type=Float32"*) ;; *) fail "density.tif is not Float32";; esac
case "$(gdalinfo "$WORK/bub/parcels.tif")" in *"Type=Int32"*) ;; *) fail "parcels.tif is not Int32";; esac
expect_eq "$(head -1 "$WORK/bub/parcels.csv")" "parcel_id,land_use,population,cells" "parcels.csv header"
for layer in roads blocks parcels grid_info; do
  ogrinfo -ro -so "$WORK/bub/truth.gpkg" "$layer" >/dev/null 2>&1 || fail "truth.gpkg has no layer $layer"
done
case "$(ogrinfo -ro -so "$WORK/bub/truth.gpkg" roads)" in *"road_class: String"*) ;; *) fail "truth roads lack road_class";; esac
case "$(ogrinfo -ro -so "$WORK/bub/truth.gpkg" parcels)" in *"land_use: String"*) ;; *) fail "truth parcels lack land_use";; esac
# The real plots are the parcels: hundreds of them.
[ "$(feature_count "$WORK/bub/truth.gpkg" parcels)" -gt 200 ] || fail "too few truth parcels"

# Monaco (OSM .pbf, geographic): the grid gets the UTM zone of the data, 32N.
run_cmd gridify -q -tr 12 "$SRC/monaco.osm.pbf" "$WORK/mon"
expect_status 0
case "$(gdalinfo "$WORK/mon/landuse.tif")" in *'ID["EPSG",32632]]'*) ;; *) fail "Monaco grid is not EPSG:32632";; esac
classes=$(ogrinfo -ro -q "$WORK/mon/truth.gpkg" -sql "SELECT DISTINCT road_class FROM roads" | sed -n 's/^ *road_class (String) = //p' | sort | tr '\n' ' ')
expect_eq "$classes" "primary secondary " "Monaco road classes"

# Bad input: one ERROR line, exit status, nothing written.
run_cmd gridify "$WORK/none.pbf" "$WORK/out1"
expect_status 1
expect_stderr_contains "ERROR: "
expect_stderr_contains "$WORK/none.pbf"
expect_missing "$WORK/out1"

printf 'not a city' > "$WORK/corrupt.gpkg"
run_cmd gridify "$WORK/corrupt.gpkg" "$WORK/out2"
expect_status 1
expect_stderr_contains "$WORK/corrupt.gpkg"
expect_missing "$WORK/out2"

run_cmd gridify -tr 0 "$SRC/monaco.osm.pbf" "$WORK/out3"
expect_status 1
expect_stderr "ERROR: -tr: the cell size must be a positive number of metres, got 0"
expect_missing "$WORK/out3"

run_cmd gridify -tr -5 "$SRC/monaco.osm.pbf" "$WORK/out3"
expect_status 1
expect_missing "$WORK/out3"

run_cmd gridify -te 500 500 500 600 "$SRC/monaco.osm.pbf" "$WORK/out4"
expect_status 1
expect_stderr_contains "-te"
expect_missing "$WORK/out4"

run_cmd gridify -bogus "$SRC/monaco.osm.pbf" "$WORK/out5"
expect_status 2
expect_stderr "ERROR: unknown option '-bogus' (see 'urbanvec gridify --help')"

run_cmd gridify "$WORK/bub/landuse.tif" "$WORK/out6"
expect_status 1
expect_stderr_contains "$WORK/bub/landuse.tif"
expect_missing "$WORK/out6"

run_cmd gridify "$SRC/monaco.osm.pbf" "$WORK/no/such/dir/out7"
expect_status 1
expect_stderr_contains "does not exist"

# Input without CRS: demands -a_srs.
mkdir -p "$WORK/nocrs"
ogr2ogr -f "ESRI Shapefile" "$WORK/nocrs" "$SRC/bubenec.gpkg" streets buildings
rm -f "$WORK"/nocrs/*.prj
run_cmd gridify -roads-layer streets -buildings-layer buildings "$WORK/nocrs" "$WORK/out8"
expect_status 1
expect_stderr_contains "-a_srs"
expect_missing "$WORK/out8"
run_cmd gridify -q -a_srs EPSG:3857 -t_srs EPSG:32633 -tr 6 -roads-layer streets -buildings-layer buildings "$WORK/nocrs" "$WORK/out9"
expect_status 0

# Existing output without -overwrite stays untouched.
before=$(md5sum "$WORK/bub/landuse.tif")
run_cmd gridify -tr 6 -t_srs EPSG:32633 -roads-layer streets -buildings-layer buildings "$SRC/bubenec.gpkg" "$WORK/bub"
expect_status 1
expect_stderr "ERROR: output folder '$WORK/bub' already holds landuse.tif, density.tif, parcels.tif, parcels.csv, truth.gpkg; use -overwrite to replace them (other files in the folder are kept)"
expect_eq "$(md5sum "$WORK/bub/landuse.tif")" "$before" "untouched output"
expect_no_temp "$WORK"
finish
