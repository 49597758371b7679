#!/usr/bin/env bash
# `urbanvec boundary`: layer, fields, CRS when georeferenced, determinism, and bad input (issue 7).
set -e
source "$(dirname "$0")/lib.sh"

field() {  # field <dataset> <name>: the value of a field of the single boundary feature
  ogrinfo -ro -q "$1" boundary 2>/dev/null | sed -n "s/^  $2 ([A-Za-z0-9]*) = //p"
}

# Default run: pixel units, no CRS, a warning; one realistic polygon with every metric field.
run_cmd boundary -q -seed 11 "$WORK/pixels.gpkg"
expect_status 0
expect_stderr_contains "Warning: no -a_srs: the boundary is written without a CRS, in pixel units"
info=$(ogrinfo -ro -so "$WORK/pixels.gpkg" boundary)
case "$info" in *"Geometry: Polygon"*) ;; *) fail "boundary layer is not a Polygon layer: $info";; esac
expect_eq "$(feature_count "$WORK/pixels.gpkg" boundary)" "1" "feature count"
for f in fractal_dimension slope_a sigma enclosed_area_ratio fill_ratio valid seed tries; do
  case "$info" in *"$f: "*) ;; *) fail "field $f missing";; esac
done
expect_eq "$(field "$WORK/pixels.gpkg" valid)" "1" "valid"
expect_eq "$(field "$WORK/pixels.gpkg" seed)" "11" "seed of the first try"
awk -v d="$(field "$WORK/pixels.gpkg" fractal_dimension)" -v r="$(field "$WORK/pixels.gpkg" enclosed_area_ratio)" \
    -v f="$(field "$WORK/pixels.gpkg" fill_ratio)" \
    'BEGIN { exit !(d > 1.18 && d < 1.28 && r >= 0.0635 && f >= 0.2799 && f < 0.29) }' ||
  fail "realistic boundary metrics out of range"
# The polygon is valid and lies inside the 512-pixel image, away from its rim.
valid=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT ST_IsValid(geom) AS ok, ST_MinX(geom) > 0 AND ST_MaxX(geom) < 512 AS inside FROM boundary" "$WORK/pixels.gpkg" | sed -n 's/^  \(ok\|inside\) (Integer) = //p' | tr -d '\n')
expect_eq "$valid" "11" "valid polygon inside the image"

# Same seed, same boundary.
run_cmd boundary -q -seed 11 "$WORK/again.gpkg"
a=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT ST_AsText(geom) FROM boundary" "$WORK/pixels.gpkg" | md5sum)
b=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT ST_AsText(geom) FROM boundary" "$WORK/again.gpkg" | md5sum)
expect_eq "$a" "$b" "same seed gives the same polygon"

# Georeferenced: CRS, cell size and centre place it; area scales with the cell size squared.
run_cmd boundary -q -seed 11 -cellsize 10 -center 455000 5550000 -a_srs EPSG:32633 "$WORK/geo.gpkg"
expect_status 0
expect_eq "$ERR" "" "no warning when georeferenced"
srs=$(ogrinfo -ro -so "$WORK/geo.gpkg" boundary)
case "$srs" in *'ID["EPSG",32633]'*) ;; *) fail "output CRS is not EPSG:32633";; esac
areas=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT ST_Area(geom) AS a FROM boundary" "$WORK/pixels.gpkg" | sed -n 's/^  a (Real) = //p')
geo=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT ST_Area(geom) AS a, ST_MinX(geom) AS x0, ST_MaxX(geom) AS x1 FROM boundary" "$WORK/geo.gpkg")
garea=$(echo "$geo" | sed -n 's/^  a (Real) = //p')
x0=$(echo "$geo" | sed -n 's/^  x0 (Real) = //p')
x1=$(echo "$geo" | sed -n 's/^  x1 (Real) = //p')
awk -v a="$areas" -v g="$garea" -v x0="$x0" -v x1="$x1" \
    'BEGIN { exit !(g == 100 * a && x0 > 455000 - 2560 && x1 < 455000 + 2560) }' ||
  fail "georeferenced area $garea is not 100 x $areas or extent $x0..$x1 is off the centre"

# Suburbs: a MultiPolygon layer.
run_cmd boundary -q -seed 5 -suburbs 200 "$WORK/suburbs.gpkg"
expect_status 0
case "$(ogrinfo -ro -so "$WORK/suburbs.gpkg" boundary)" in *"Geometry: Multi Polygon"*) ;; *) fail "-suburbs is not a MultiPolygon";; esac

# Bad input: one-line error, exit 1 (2 for usage), nothing written.
run_cmd boundary -fill 1.5 "$WORK/bad.gpkg"
expect_status 2
expect_stderr "ERROR: -fill must lie strictly between 0 and 1, got 1.5"
expect_missing "$WORK/bad.gpkg"
run_cmd boundary -fill 0 "$WORK/bad.gpkg"
expect_status 2
expect_stderr "ERROR: -fill must lie strictly between 0 and 1, got 0"
run_cmd boundary -layers 3-10 "$WORK/bad.gpkg"
expect_status 2
expect_stderr "ERROR: -layers must be <start>-<end> with 0 <= start <= end <= 9 (log2 of -size 512), got '3-10'"
run_cmd boundary -size 64 -layers 2-7 "$WORK/bad.gpkg"
expect_status 2
expect_stderr "ERROR: -layers must be <start>-<end> with 0 <= start <= end <= 6 (log2 of -size 64), got '2-7'"
run_cmd boundary -layers nine "$WORK/bad.gpkg"
expect_status 2
expect_stderr_contains "got 'nine'"
run_cmd boundary -slope 3 "$WORK/bad.gpkg"
expect_status 2
run_cmd boundary -seed 4294967296 "$WORK/bad.gpkg"
expect_status 2
expect_stderr_contains "-seed must be at most"
run_cmd boundary -fill 0.9 -max-tries 2 "$WORK/bad.gpkg"
expect_status 1
expect_stderr_contains "ERROR: no boundary in 2 tries: the fill-ratio threshold always fell below the highest rim value"
expect_missing "$WORK/bad.gpkg"
expect_no_temp "$WORK"
run_cmd boundary -q "$WORK/pixels.gpkg"
expect_status 1
expect_stderr "ERROR: output file '$WORK/pixels.gpkg' already exists; use -overwrite to replace it"
run_cmd boundary -q "$WORK/no/such/folder/out.gpkg"
expect_status 1
expect_stderr_contains "does not exist"
run_cmd boundary -q "$WORK/pixels.gpkg/out.gpkg"
expect_status 1
expect_stderr_contains "cannot write output file"
mkdir "$WORK/readonly" && chmod 555 "$WORK/readonly"
run_unprivileged boundary -q "$WORK/readonly/out.gpkg"  # as nobody when the tests run as root
expect_status 1
expect_stderr "ERROR: cannot write output file '$WORK/readonly/out.gpkg': folder '$WORK/readonly' is not writable"
expect_eq "$(ls -A "$WORK/readonly")" "" "a read-only folder stays empty"
run_cmd boundary -q -a_srs EPSG:4326 -cellsize 10 "$WORK/bad.gpkg"
expect_status 2
expect_stderr_contains "is geographic"

finish
