#!/usr/bin/env bash
# Land use where the map has none (issue 20): gridify gives blocks of the street network with no
# land-use polygon the use of their buildings, else of their streets, else -default-use.
#  1. A synthetic grid city (bench/vectorize/grid_city.py) with its residential polygon dropped: the
#     residential streets make the blocks residential again; -no-infer-use leaves them unused.
#  2. Monaco with its land-use polygons dropped (streets and buildings kept, as a GeoPackage): the
#     share of the full-tag grid's developed cells (classes 4-8) recovered with their class, and the
#     land-use L1 of the class shares over land cells.
set -e
source "$(dirname "$0")/lib.sh"
recover() {  # recover <full landuse.tif> <sparse landuse.tif>: "share L1"
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys
import numpy as np
from osgeo import gdal
full = gdal.Open(sys.argv[1]).ReadAsArray()
sparse = gdal.Open(sys.argv[2]).ReadAsArray()
dev = np.isin(full, [4, 5, 6, 7, 8])
land = ~np.isin(full, [1, 2, 3]) & ~np.isin(sparse, [1, 2, 3])
share = lambda a: np.array([np.sum(a[land] == k) for k in (0, 4, 5, 6, 7, 8)]) / max(land.sum(), 1)
print(f"{np.sum(dev & (sparse == full)) / max(dev.sum(), 1):.4f} {np.abs(share(full) - share(sparse)).sum():.4f}")
PY
}
in_band() { awk -v v="$2" -v lo="$3" -v hi="$4" 'BEGIN { exit !(v >= lo && v <= hi) }' || fail "$1 = $2, outside [$3, $4]"; echo "$1 = $2 [$3, $4]"; }

# 1. The synthetic grid.
/usr/bin/python3 "$URBANVEC_SOURCE_DIR/bench/vectorize/grid_city.py" "$WORK/grid.gpkg" 15
ogr2ogr -f GPKG "$WORK/streets.gpkg" "$WORK/grid.gpkg" roads
run_cmd gridify -q -tr 8 "$WORK/grid.gpkg" "$WORK/full"
expect_status 0
gte=$(/usr/bin/python3 -c "
import sys; from osgeo import gdal
d = gdal.Open(sys.argv[1]); g = d.GetGeoTransform()
print(g[0], g[3] + g[5] * d.RasterYSize, g[0] + g[1] * d.RasterXSize, g[3])" "$WORK/full/landuse.tif")
run_cmd gridify -tr 8 -te $gte "$WORK/streets.gpkg" "$WORK/inferred"
expect_status 0
expect_stdout_contains "by their streets"
run_cmd gridify -q -tr 8 -te $gte -no-infer-use "$WORK/streets.gpkg" "$WORK/empty"
expect_status 0
read -r share l1 <<<"$(recover "$WORK/full/landuse.tif" "$WORK/inferred/landuse.tif")"
# The residential polygon reaches 60 m beyond the outer streets (at +-240 m, the street ends at
# +-260 m) on every side; that fringe is outside the street network and stays unused. Every block
# inside comes back residential: 0.357 of the polygon's developed cells.
in_band "grid, streets only: developed cells recovered" "$share" 0.33 0.40
read -r share0 l10 <<<"$(recover "$WORK/full/landuse.tif" "$WORK/empty/landuse.tif")"
in_band "grid, streets only, -no-infer-use: developed cells recovered" "$share0" 0 0.01
run_cmd gridify -q -tr 8 -te $gte -default-use park -street-use living_street=residential "$WORK/streets.gpkg" \
  "$WORK/park"
expect_status 0
read -r sharep l1p <<<"$(recover "$WORK/full/landuse.tif" "$WORK/park/landuse.tif")"
in_band "grid, streets not in -street-use, -default-use park: residential cells recovered" "$sharep" 0 0.01
run_cmd gridify -q -tr 8 -street-use "residential" "$WORK/streets.gpkg" "$WORK/bad"
expect_status 2
expect_stderr_contains "-street-use takes highway=class pairs"

# 2. Monaco without land-use polygons, on the frame of the sample grid (which -no-infer-use reproduces).
src="$SAMPLE_DIR/sources/monaco.osm.pbf"
ogr2ogr -f GPKG "$WORK/m.gpkg" "$src" -sql "SELECT highway, name FROM lines WHERE highway IS NOT NULL" \
  -nln roads -nlt LINESTRING
ogr2ogr -update -f GPKG "$WORK/m.gpkg" "$src" -sql "SELECT building FROM multipolygons WHERE building IS NOT NULL" \
  -nln buildings -nlt MULTIPOLYGON
run_cmd gridify -q -tr 8 -no-infer-use "$src" "$WORK/mfull"
expect_status 0
cmp -s "$WORK/mfull/landuse.tif" "$SAMPLE_DIR/monaco/landuse.tif" || fail "-no-infer-use does not reproduce the sample grid"
te="371576 4842352 374360 4845656"
run_cmd gridify -q -tr 8 -t_srs EPSG:32632 -te $te -landuse-field building "$WORK/m.gpkg" "$WORK/msparse"
expect_status 0
read -r share l1 <<<"$(recover "$SAMPLE_DIR/monaco/landuse.tif" "$WORK/msparse/landuse.tif")"
in_band "monaco, streets and buildings only: developed cells recovered" "$share" 0.80 0.90
in_band "monaco, streets and buildings only: land-use L1" "$l1" 0 0.10

# 3. A land-cover raster as another source (-landcover, -landcover-table). There is no land-cover
#    product of Monaco in the repository, so one is made the way CORINE Land Cover is: Monaco's OSM
#    land-use polygons as CORINE level-3 codes (112 discontinuous urban fabric, 121 commercial units,
#    141 green urban areas, 142 sport and leisure, 0 everything else) in CORINE's CRS (EPSG:3035),
#    rasterized at 10 m and aggregated to CORINE's 100 m pixels by the majority class (gdalwarp -r mode).
#    A 100 m pixel holds 156 cells of 8 m, so most small parks and gardens are lost and residential
#    land spills over streets; gridify warps it back onto its 8 m grid in EPSG:32632.
ogr2ogr -f GPKG "$WORK/clc.gpkg" "$src" -t_srs EPSG:3035 -nln clc -nlt MULTIPOLYGON -dialect sqlite -sql "
  SELECT geometry, ST_Area(geometry) AS a, CASE
    WHEN landuse = 'residential' THEN 112 WHEN landuse IN ('retail', 'commercial', 'industrial') THEN 121
    WHEN leisure IN ('pitch', 'sports_centre', 'stadium', 'miniature_golf') THEN 142
    WHEN landuse IN ('forest', 'grass', 'cemetery') OR leisure IN ('park', 'garden', 'dog_park', 'playground')
    THEN 141 END AS code
  FROM multipolygons WHERE code IS NOT NULL ORDER BY a DESC"
gdal_rasterize -q -a code -tr 10 10 -tap -init 0 -ot Int16 "$WORK/clc.gpkg" "$WORK/clc10.tif"
gdalwarp -q -r mode -tr 100 100 -tap "$WORK/clc10.tif" "$WORK/clc100.tif"
printf 'value,class_name\n# CORINE Land Cover level 3\n0,unused\n111,residential\n112,residential\n121,commercial\n141,park\n142,park\n' \
  >"$WORK/clc.csv"
run_cmd gridify -tr 8 -t_srs EPSG:32632 -te $te -landuse-field building -landcover "$WORK/clc100.tif" \
  -landcover-table "$WORK/clc.csv" "$WORK/m.gpkg" "$WORK/mcover"
expect_status 0
expect_stdout_contains "took their class from"
read -r sharec l1c <<<"$(recover "$SAMPLE_DIR/monaco/landuse.tif" "$WORK/mcover/landuse.tif")"
in_band "monaco, streets, buildings and a 100 m land cover: developed cells recovered" "$sharec" 0.85 0.90
in_band "monaco, streets, buildings and a 100 m land cover: land-use L1" "$l1c" 0 0.05
awk -v a="$sharec" -v b="$share" 'BEGIN { exit !(a > b) }' || fail "the land cover recovers $sharec, not more than $share"
# Bad input: nothing written, one line naming the file.
grep -v '^142' "$WORK/clc.csv" >"$WORK/clc_short.csv"
run_cmd gridify -q -tr 8 -t_srs EPSG:32632 -te $te -landuse-field building -landcover "$WORK/clc100.tif" \
  -landcover-table "$WORK/clc_short.csv" "$WORK/m.gpkg" "$WORK/bad1"
expect_status 1
expect_stderr_contains "holds value 142"
expect_stderr_contains "does not map (add a line '142,<class name>')"
expect_missing "$WORK/bad1"
gdal_translate -q -a_ullr 0 1000 2500 -2200 "$WORK/clc100.tif" "$WORK/far.tif"
run_cmd gridify -q -tr 8 -t_srs EPSG:32632 -te $te -landcover "$WORK/far.tif" -landcover-table "$WORK/clc.csv" \
  "$WORK/m.gpkg" "$WORK/bad2"
expect_status 1
expect_stderr_contains "covers no cell of the grid"
expect_missing "$WORK/bad2"
/usr/bin/python3 -c "
import sys; from osgeo import gdal
gdal.Translate(sys.argv[2], sys.argv[1])
d = gdal.Open(sys.argv[2], 1); d.SetProjection(''); d = None" "$WORK/clc100.tif" "$WORK/nocrs.tif"
run_cmd gridify -q -tr 8 -t_srs EPSG:32632 -te $te -landcover "$WORK/nocrs.tif" -landcover-table "$WORK/clc.csv" \
  "$WORK/m.gpkg" "$WORK/bad3"
expect_status 1
expect_stderr_contains "has no CRS"
expect_missing "$WORK/bad3"
run_cmd gridify -q -tr 8 -landcover "$WORK/clc100.tif" "$WORK/m.gpkg" "$WORK/bad4"
expect_status 2
expect_stderr_contains "-landcover needs -landcover-table"

finish
