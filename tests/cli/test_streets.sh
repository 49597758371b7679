#!/usr/bin/env bash
# `urbanvec streets` (issue 18): layers, fields, styles and CRS; the field raster; validity (inside the
# boundary, out of the water); determinism for any -threads; the chain streets -> gridify ->
# vectorize ending in parcels; and each bad input of the issue: one ERROR line, exit status, nothing
# written.
set -e
source "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3

# A 2 x 2 km boundary in UTM 33N with a lake, a grid element and a radial element.
cat >"$WORK/boundary.csv" <<'CSV'
id,WKT
1,"POLYGON((450000 5550000,452000 5550000,452000 5552000,450000 5552000,450000 5550000))"
CSV
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln boundary "$WORK/boundary.gpkg" "$WORK/boundary.csv"
cat >"$WORK/lake.csv" <<'CSV'
id,WKT
1,"POLYGON((450800 5550800,451200 5550800,451200 5551100,450800 5551100,450800 5550800))"
CSV
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln lake "$WORK/lake.gpkg" "$WORK/lake.csv"
cat >"$WORK/design.csv" <<'CSV'
kind,angle,size,decay,WKT
grid,20,1,,"POINT(450500 5550500)"
radial,,150,,"POINT(451500 5551500)"
CSV
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln design -oo AUTODETECT_TYPE=YES "$WORK/design.gpkg" "$WORK/design.csv"

run_cmd streets -q -boundary "$WORK/boundary.gpkg" -design "$WORK/design.gpkg" -water "$WORK/lake.gpkg" \
  -dsep-major 250 -field "$WORK/field.tif" "$WORK/out.gpkg"
expect_status 0
expect_eq "$ERR" "" "stderr of a good run"
for layer in streets street_nodes blocks water; do
  n=$(feature_count "$WORK/out.gpkg" "$layer")
  [ "${n:-0}" -gt 0 ] || fail "layer $layer is empty"
done
info=$(ogrinfo -ro -so "$WORK/out.gpkg" streets)
for f in street_id class highway length; do case "$info" in *"$f: "*) ;; *) fail "streets lacks field $f";; esac; done
case "$info" in *'ID["EPSG",32633]'*) ;; *) fail "CRS not kept";; esac
q() { ogrinfo -ro -q -sql "$2" "$1" | sed -n 's/^  [a-z_]* ([A-Za-z0-9]*) = //p' | head -1; }
expect_eq "$(q "$WORK/out.gpkg" "SELECT COUNT(*) AS n FROM streets WHERE class NOT IN ('major','minor') OR length <= 0")" "0" "bad class/length"
[ "$(q "$WORK/out.gpkg" "SELECT COUNT(*) AS n FROM streets WHERE class = 'minor'")" -gt 10 ] || fail "too few minor streets"
expect_eq "$(q "$WORK/out.gpkg" "SELECT COUNT(*) AS n FROM streets WHERE (class = 'major') != (highway = 'primary')")" "0" "highway field"
expect_eq "$(q "$WORK/out.gpkg" "SELECT COUNT(*) AS n FROM layer_styles WHERE f_table_name IN ('streets','street_nodes','blocks')")" "3" "embedded styles"
expect_eq "$(q "$WORK/out.gpkg" "SELECT COUNT(*) AS n FROM blocks WHERE land_use != 'residential'")" "0" "block land use"
# Validity: nothing in the lake, everything inside the boundary (to the noding tolerance).
expect_eq "$(ogrinfo -ro -q -dialect sqlite -sql "SELECT COUNT(*) AS n FROM streets WHERE ST_Length(ST_Intersection(geom, ST_Buffer(ST_GeomFromText('POLYGON((450800 5550800,451200 5550800,451200 5551100,450800 5551100,450800 5550800))'), -0.1))) > 0" "$WORK/out.gpkg" | sed -n 's/^  n (Integer.*) = //p')" "0" "streets in the lake"
expect_eq "$(ogrinfo -ro -q -dialect sqlite -sql "SELECT COUNT(*) AS n FROM streets WHERE MbrMinX(geom) < 449999.99 OR MbrMaxX(geom) > 452000.01 OR MbrMinY(geom) < 5549999.99 OR MbrMaxY(geom) > 5552000.01" "$WORK/out.gpkg" | sed -n 's/^  n (Integer.*) = //p')" "0" "streets outside the boundary"
# Every crossing is a node: measuring the output finds as many nodes as it wrote (degree != 2).
run_cmd street-metrics -q -layer streets -json "$WORK/m.json" "$WORK/out.gpkg"
expect_status 0
expect_eq "$(jq .nodes "$WORK/m.json")" "$(q "$WORK/out.gpkg" "SELECT COUNT(*) AS n FROM street_nodes WHERE degree != 2")" "nodes re-measured"
# The field raster: two bands in the same CRS, angles in (-90, 90].
expect_eq "$(gdalinfo "$WORK/field.tif" | grep -c '^Band ')" "2" "field bands"
gdalinfo -stats "$WORK/field.tif" 2>/dev/null | grep -q 'STATISTICS_MINIMUM=-9[0-9]\|STATISTICS_MINIMUM=-8' || fail "field angles do not span the directions"
gdalsrsinfo -o epsg "$WORK/field.tif" | grep -q 32633 || fail "field raster CRS"

# Determinism: the same layers for -threads 1 and 2, and from the same design given as JSON.
run_cmd streets -q -threads 1 -boundary "$WORK/boundary.gpkg" -design "$WORK/design.gpkg" -water "$WORK/lake.gpkg" -dsep-major 250 "$WORK/t1.gpkg"
run_cmd streets -q -threads 2 -boundary "$WORK/boundary.gpkg" -design "$WORK/design.gpkg" -water "$WORK/lake.gpkg" -dsep-major 250 "$WORK/t2.gpkg"
printf '{"elements": [{"kind": "grid", "x": 450500, "y": 5550500, "angle": 20, "size": 1},\n {"kind": "radial", "x": 451500, "y": 5551500, "size": 150}]}\n' >"$WORK/design.json"
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -water "$WORK/lake.gpkg" -dsep-major 250 "$WORK/t3.gpkg"
dump() { ogrinfo -ro -al -q "$1" streets street_nodes blocks | grep -v '^INFO\|^Layer name'; }
[ "$(dump "$WORK/t1.gpkg" | md5sum)" = "$(dump "$WORK/t2.gpkg" | md5sum)" ] || fail "output depends on -threads"
[ "$(dump "$WORK/t1.gpkg" | md5sum)" = "$(dump "$WORK/t3.gpkg" | md5sum)" ] || fail "JSON design differs from the point layer"
run_cmd streets -q -seed 9 -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -water "$WORK/lake.gpkg" -dsep-major 250 "$WORK/t4.gpkg"
[ "$(dump "$WORK/t1.gpkg" | md5sum)" != "$(dump "$WORK/t4.gpkg" | md5sum)" ] || fail "-seed changes nothing"

# The chain: streets -> gridify (roads from the streets layer, land use from blocks) -> vectorize.
run_cmd gridify -q -tr 8 -landuse-layer blocks -landuse-field land_use "$WORK/out.gpkg" "$WORK/grid"
expect_status 0
run_cmd vectorize -q "$WORK/grid/landuse.tif" "$WORK/city.gpkg"
expect_status 0
n=$(feature_count "$WORK/city.gpkg" parcels)
[ "${n:-0}" -gt 20 ] || fail "the chain gave only '$n' parcels"

# Terrain and density: a DEM alone is a design (a round hill: major roads ring it, §4.4), and a density
# raster widens the spacing where it is low (fewer streets than at full density).
$PY - "$WORK/hill.tif" "$WORK/density.tif" <<'PY'
import sys
import numpy as np
from osgeo import gdal, osr
srs = osr.SpatialReference(); srs.ImportFromEPSG(32633)
y, x = np.mgrid[0:110, 0:110]
for path, data in ((sys.argv[1], 100.0 - 0.05 * np.hypot(x * 20 - 1100.0, y * 20 - 1100.0)),
                   (sys.argv[2], np.where(x < 55, 0.0, 5000.0))):
    ds = gdal.GetDriverByName("GTiff").Create(path, 110, 110, 1, gdal.GDT_Float32)
    ds.SetGeoTransform((449900, 20, 0, 5552100, 0, -20)); ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(data.astype("float32")); ds = None
PY
# (-bow 0: the check is on the field's directions, which bows leave by up to 32 degrees on purpose.)
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -dem "$WORK/hill.tif" -dsep-major 250 -no-minor -bow 0 "$WORK/hill.gpkg"
expect_status 0
# Streets follow the contours (rings) or climb the gradient (rays): measured per segment, the angle
# to the summit's radial direction is near 90 or near 0 degrees for most of the length.
$PY - "$WORK/hill.gpkg" <<'PY' || fail "terrain streets follow neither contours nor gradient"
import math, sys
from osgeo import ogr
ds = ogr.Open(sys.argv[1]); lyr = ds.GetLayer("streets")
good = total = 0.0
for f in lyr:
    pts = f.GetGeometryRef().GetPoints()
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        mx, my = (x0 + x1) / 2 - 451000, (y0 + y1) / 2 - 5551000
        r, l = math.hypot(mx, my), math.hypot(x1 - x0, y1 - y0)
        if r < 150 or r > 900 or l == 0: continue
        c = abs((mx * (x1 - x0) + my * (y1 - y0)) / (r * l))
        a = math.degrees(math.acos(min(1.0, c)))
        total += l
        good += l if (a < 10 or a > 80) else 0
assert total > 2000 and good > 0.8 * total, (good, total)
PY
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -dsep-major 250 -density "$WORK/density.tif" "$WORK/dense.gpkg"
expect_status 0
west=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT SUM(ST_Length(geom)) AS l FROM streets WHERE MbrMaxX(geom) < 450950" "$WORK/dense.gpkg" | sed -n 's/^  l (Real) = //p')
east=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT SUM(ST_Length(geom)) AS l FROM streets WHERE MbrMinX(geom) > 451050" "$WORK/dense.gpkg" | sed -n 's/^  l (Real) = //p')
awk -v w="${west:-0}" -v e="${east:-0}" 'BEGIN { exit !(e > 1.5 * w) }' || fail "street length west $west, east $east: density does not widen the spacing"
[ "$(q "$WORK/dense.gpkg" "SELECT COUNT(*) AS n FROM blocks WHERE land_use = 'unused'")" -gt 0 ] || fail "no unused block where the density is 0"

# -keep-roads (spec §14): the given roads stay in the network, clipped to the boundary (this one runs
# 500 m out of it), and the traced roads grow around them.
cat >"$WORK/roads.csv" <<'CSV'
id,WKT
1,"LINESTRING(449500 5551000,450700 5551040,451300 5551040,452000 5551100)"
2,"LINESTRING(451000 5550000,451000 5550700)"
CSV
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln roads "$WORK/roads.gpkg" "$WORK/roads.csv"
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -roads "$WORK/roads.gpkg" -keep-roads -dsep-major 300 "$WORK/kept.gpkg"
expect_status 0
kept=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT SUM(ST_Length(geom)) AS l FROM streets WHERE source = 'existing'" "$WORK/kept.gpkg" | sed -n 's/^  l (Real) = //p')
awk -v k="${kept:-0}" 'BEGIN { exit !(k > 2702.94 && k < 2702.97) }' || fail "kept roads are $kept m long, not the 2702.96 m inside the boundary"
traced=$(ogrinfo -ro -q -dialect sqlite -sql "SELECT COUNT(*) AS n FROM streets WHERE source = 'traced'" "$WORK/kept.gpkg" | sed -n 's/^  n (Integer.*) = //p')
[ "${traced:-0}" -gt 100 ] || fail "only ${traced:-0} traced streets around the kept roads"
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -roads "$WORK/roads.gpkg" -dsep-major 300 "$WORK/notkept.gpkg"
expect_eq "$(ogrinfo -ro -q -sql "SELECT COUNT(*) AS n FROM streets WHERE source = 'existing'" "$WORK/notkept.gpkg" | sed -n 's/^  n (Integer.*) = //p')" "0" "roads kept without -keep-roads"
# Without -dsep-major the major spacing is that of the -roads (2 A / L, at most 360 m, at least
# -dsep-floor), printed on stdout: a grid of roads every 250 m over the 2 km square gives 250 m (the
# network is denser than the fixed 360 m's; 270 against 165 streets when written).
grid_roads() {  # grid_roads <spacing> <name>: roads every <spacing> m both ways over the boundary
  $PY - "$WORK/$2.csv" "$1" <<'PY'
import sys
s = float(sys.argv[2])
with open(sys.argv[1], "w") as f:
    f.write("id,WKT\n")
    for i in range(int(2000 / s)):
        c = s / 2 + s * i
        f.write(f'{2 * i},"LINESTRING({450000 + c} 5550000,{450000 + c} 5552000)"\n')
        f.write(f'{2 * i + 1},"LINESTRING(450000 {5550000 + c},452000 {5550000 + c})"\n')
PY
  ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln roads "$WORK/$2.gpkg" "$WORK/$2.csv"
}
grid_roads 250 grid_roads
run_cmd streets -progress none -boundary "$WORK/boundary.gpkg" -roads "$WORK/grid_roads.gpkg" "$WORK/spaced.gpkg"
expect_status 0
expect_stdout_contains "dsep-major: 250 m (from the -roads spacing), dsep-minor: 125 m"
run_cmd streets -progress none -boundary "$WORK/boundary.gpkg" -roads "$WORK/grid_roads.gpkg" -dsep-major 360 "$WORK/fixed.gpkg"
expect_status 0
expect_stdout_contains "dsep-major: 360 m (given), dsep-minor: 180 m"
spaced=$(feature_count "$WORK/spaced.gpkg" streets) fixed=$(feature_count "$WORK/fixed.gpkg" streets)
[ "${spaced:-0}" -gt "${fixed:-0}" ] || fail "-roads every 250 m give $spaced streets, the fixed 360 m $fixed"
# Roads finer than -dsep-floor (default 100 m; a full mapped network given as -roads) are traced at
# the floor, with a warning: every 20 m would otherwise give some 25,000 streets on these 4 km².
grid_roads 20 fine_roads
run_cmd streets -progress none -boundary "$WORK/boundary.gpkg" -roads "$WORK/fine_roads.gpkg" "$WORK/floored.gpkg"
expect_status 0
expect_stdout_contains "dsep-major: 100 m (the -roads spacing 20 m raised to -dsep-floor), dsep-minor: 50 m"
expect_stderr_contains "the -roads are 20 m apart, closer than -dsep-floor 100 m"
# -major-clearance-ratio reaches the tracer: at d_sep_minor = d_sep_major / 2, keeping d_test from the
# major roads fills the regions between them with minor roads (far more streets than the default 1).
printf '{"elements": [{"kind": "grid", "x": 451000, "y": 5551000, "angle": 20}]}\n' >"$WORK/grid_design.json"
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -design "$WORK/grid_design.json" -dsep-major 200 "$WORK/clear1.gpkg"
expect_status 0
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -design "$WORK/grid_design.json" -dsep-major 200 \
  -major-clearance-ratio 0.5 "$WORK/clear05.gpkg"
expect_status 0
clear1=$(feature_count "$WORK/clear1.gpkg" streets) clear05=$(feature_count "$WORK/clear05.gpkg" streets)
[ "${clear05:-0}" -gt $((4 * ${clear1:-0} / 3)) ] || fail "-major-clearance-ratio 0.5 gives $clear05 streets, 1 gives $clear1"

# Bad input: one ERROR line, exit status, nothing written.
bad() {  # bad <status> <expected stderr substring> <args...>
  local status=$1 msg=$2
  shift 2
  rm -f "$WORK/bad.gpkg"
  run_cmd streets -q "$@" "$WORK/bad.gpkg"
  expect_status "$status"
  expect_stderr_contains "$msg"
  [ "$(printf '%s\n' "$ERR" | wc -l)" -eq 1 ] || fail "more than one line on stderr: $ERR"
  expect_missing "$WORK/bad.gpkg"
  expect_no_temp "$WORK"
}
bad 1 "ERROR: the street design is empty" -boundary "$WORK/boundary.gpkg"
bad 2 "ERROR: -keep-roads needs -roads" -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -keep-roads
printf '{"elements": []}\n' >"$WORK/empty.json"
bad 1 "ERROR: -design '$WORK/empty.json' holds no design element" -boundary "$WORK/boundary.gpkg" -design "$WORK/empty.json"
bad 1 "ERROR: -design '$WORK/missing.json' cannot be read" -boundary "$WORK/boundary.gpkg" -design "$WORK/missing.json"
printf '{"elements": [{"kind": "grid", "x": 460000, "y": 5550500}]}\n' >"$WORK/outside.json"
bad 1 "lies outside the boundary" -boundary "$WORK/boundary.gpkg" -design "$WORK/outside.json"
bad 1 "holds no polygon" -boundary "$WORK/design.gpkg" -design "$WORK/design.json"
ogr2ogr -q -f GPKG -nln boundary "$WORK/nocrs.gpkg" "$WORK/boundary.csv"
bad 1 "has no CRS; streets needs a projected CRS in metres" -boundary "$WORK/nocrs.gpkg" -design "$WORK/design.json"
bad 2 "ERROR: -dsep-major" -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -dsep-major 0
bad 2 "d_test must be > 0 and at most d_sep" -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -dtest-ratio 1.5
# -dsep-minor over a given -dsep-major fails before any input is read (the missing DEM is not
# reached); over one derived from the -roads spacing, the message names where it came from.
bad 2 "ERROR: -dsep-minor 120 exceeds -dsep-major 100" -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" \
  -dsep-major 100 -dsep-minor 120 -dem "$WORK/missing.tif"
grid_roads 100 grid100
bad 2 "ERROR: the -dsep-major derived from the -roads spacing, 100 m, is below -dsep-minor 120; give -dsep-major" \
  -boundary "$WORK/boundary.gpkg" -roads "$WORK/grid100.gpkg" -dsep-minor 120
gdal_create -q -of GTiff -outsize 50 50 -bands 1 -burn 10 -a_srs EPSG:32632 -a_ullr 450000 5552000 452000 5550000 "$WORK/dem_other.tif" 2>/dev/null ||
  gdal_translate -q -a_srs EPSG:32632 -a_ullr 450000 5552000 452000 5550000 "$WORK/field.tif" -b 1 "$WORK/dem_other.tif"
bad 1 "not the output CRS EPSG:32633" -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -dem "$WORK/dem_other.tif"
gdal_translate -q -a_srs EPSG:32633 -a_ullr 450000 5551000 451000 5550000 "$WORK/dem_other.tif" "$WORK/dem_small.tif"
bad 1 "does not cover the boundary" -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -dem "$WORK/dem_small.tif"
$PY -c "
import json
print(json.dumps({'elements': [{'kind': 'grid', 'x': 451000, 'y': 5551000, 'angle': i % 90} for i in range(1000000)]}))" >"$WORK/huge.json"
bad 1 "the design has 1000000 elements; at most 100000 are accepted" -boundary "$WORK/boundary.gpkg" -design "$WORK/huge.json"
rm -f "$WORK/huge.json"
# Water over everything: valid empty layers and a warning.
run_cmd streets -q -boundary "$WORK/boundary.gpkg" -design "$WORK/design.json" -water "$WORK/boundary.gpkg" "$WORK/drowned.gpkg"
expect_status 0
expect_stderr_contains "Warning: no street could be traced"
expect_eq "$(feature_count "$WORK/drowned.gpkg" streets)" "0" "streets under water"
expect_eq "$(feature_count "$WORK/drowned.gpkg" blocks)" "0" "blocks under water"
# A geographic boundary is grown in its UTM zone.
ogr2ogr -q -f GPKG -t_srs EPSG:4326 "$WORK/geo.gpkg" "$WORK/boundary.gpkg"
run_cmd streets -q -boundary "$WORK/geo.gpkg" -design "$WORK/design.json" -dsep-major 250 -no-minor "$WORK/geo_out.gpkg"
expect_status 0
ogrinfo -ro -so "$WORK/geo_out.gpkg" streets | grep -q 'ID\["EPSG",32633\]' || fail "geographic boundary not grown in UTM 33N"
finish
