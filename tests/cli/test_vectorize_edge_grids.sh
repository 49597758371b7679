#!/usr/bin/env bash
# `urbanvec vectorize` on degenerate grids (issue 15): all developed land without a road, one road
# across developed land, all water, all unused, 1x1 grids of every class. None may crash, every
# warning must be true, and the population of -density must reach the parcels or its loss be
# reported. Also the wording of the sample runs' warnings about parcels outside every block and about
# population the parcels layer does not hold.
set -e
source "$(dirname "$0")/lib.sh"

# 50 x 50 cells of 10 m in EPSG:32633: land-use grids, 2.5 people per cell, 25 parcels of 10 x 10.
/usr/bin/python3 - "$WORK" <<'PY'
import sys
from osgeo import gdal, osr
import numpy as np
d = sys.argv[1]
def write(name, a, dtype):
    h, w = a.shape
    ds = gdal.GetDriverByName("GTiff").Create(f"{d}/{name}.tif", w, h, 1, dtype)
    ds.SetGeoTransform((500000, 10, 0, 5000000 + 10 * h, 0, -10))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32633)
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(a)
n = 50
r, c = np.mgrid[0:n, 0:n]
write("residential", np.full((n, n), 4, np.uint8), gdal.GDT_Byte)
write("road", np.where(c == 25, 2, 4).astype(np.uint8), gdal.GDT_Byte)  # one secondary road, north-south
write("water", np.full((n, n), 1, np.uint8), gdal.GDT_Byte)
write("unused", np.full((n, n), 0, np.uint8), gdal.GDT_Byte)
write("density", np.full((n, n), 2.5, np.float32), gdal.GDT_Float32)
write("parcels", (1 + (r // 10) * 5 + c // 10).astype(np.int32), gdal.GDT_Int32)
for code in range(9):
    write(f"one_{code}", np.full((1, 1), code, np.uint8), gdal.GDT_Byte)
write("one_density", np.full((1, 1), 3.0, np.float32), gdal.GDT_Float32)
write("one_parcels", np.full((1, 1), 1, np.int32), gdal.GDT_Int32)
PY

NO_ROADS="Warning: the land-use grid has no road cells (codes 2 and 3): the road layers are empty"
ISLAND="Warning: 1 closed boundary between undeveloped land and external blocks meets no road and got no perimeter line (islands become blocks of their own outline)"
NO_PARCELS="Warning: the density grid holds 6250 people, but without a parcels grid (-parcels) there are no input parcels to carry them:"

# sql <dataset> <query with one column named n>
sql() { ogrinfo -ro -q "$1" -dialect SQLite -sql "$2" | sed -n 's/^ *n ([A-Za-z0-9]*) = //p'; }
# check <name> <blocks> <parcels> <population of the parcels layer>: counts in $WORK/<name>.gpkg.
check() {
  local out="$WORK/$1.gpkg"
  expect_exists "$out"
  expect_eq "$(feature_count "$out" blocks)" "$2" "$1: blocks"
  expect_eq "$(feature_count "$out" parcels)" "$3" "$1: parcels"
  expect_eq "$(sql "$out" "SELECT printf('%.3f', COALESCE(SUM(population), 0)) AS n FROM parcels")" "$4" "$1: population"
}
vec() { local name=$1; shift; run_cmd vectorize -q "$@" "$WORK/$name.gpkg"; }

# All developed land, no road: the island rule makes it one external block, split into its 25
# parcels with all 6250 people.
vec residential -density "$WORK/density.tif" -parcels "$WORK/parcels.tif" "$WORK/residential.tif"
expect_status 0
expect_stderr "$NO_ROADS
$ISLAND"
check residential 1 25 6250.000
expect_eq "$(sql "$WORK/residential.gpkg" "SELECT kind AS n FROM blocks")" "external" "residential: block kind"
expect_eq "$(sql "$WORK/residential.gpkg" "SELECT COUNT(*) AS n FROM parcels WHERE land_use <> 'residential'")" "0" \
  "residential: parcels of another use"
expect_eq "$(sql "$WORK/residential.gpkg" "SELECT COUNT(*) AS n FROM vectorize_report WHERE shortfall <> ''")" "0" \
  "residential: blocks short of their parcels"
# The block covers the grid but for its smoothed corners (2500 cells of 100 m2).
area=$(sql "$WORK/residential.gpkg" "SELECT CAST(ROUND(SUM(area)) AS INTEGER) AS n FROM blocks")
[ "${area:-0}" -gt 249000 ] && [ "${area:-0}" -le 250000 ] || fail "residential: block area $area m2"

# The same without a parcels grid: one undeveloped parcel, and the warning says where the people went.
vec residential_np -density "$WORK/density.tif" "$WORK/residential.tif"
expect_status 0
expect_stderr "$NO_ROADS
$ISLAND
$NO_PARCELS each block is one undeveloped parcel with population 0"
check residential_np 1 1 0.000

# One secondary road across developed land: two external blocks, nothing to warn about.
vec road -density "$WORK/density.tif" -parcels "$WORK/parcels.tif" "$WORK/road.tif"
expect_status 0
expect_stderr ""
check road 2 25 6250.000
[ "$(feature_count "$WORK/road.gpkg" roads)" -gt 0 ] || fail "road: no road segment"

# All water / all unused: no block; the parcels lie outside every block with their people, and say so.
vec water -density "$WORK/density.tif" -parcels "$WORK/parcels.tif" "$WORK/water.tif"
expect_status 0
expect_stderr "$NO_ROADS
Warning: 25 input parcels (6250 people) lie mostly on water outside every block: no block takes them, so they are left out of the parcels layer with their 6250 people"
check water 0 0 0.000
expect_eq "$(feature_count "$WORK/water.gpkg" water)" "1" "water: water polygons"
vec unused -density "$WORK/density.tif" -parcels "$WORK/parcels.tif" "$WORK/unused.tif"
expect_status 0
expect_stderr "$NO_ROADS
Warning: 25 input parcels (6250 people) lie mostly on open land (unused cells) outside every block: no block takes them, so they are left out of the parcels layer with their 6250 people"
check unused 0 0 0.000
vec unused_np -density "$WORK/density.tif" "$WORK/unused.tif"
expect_status 0
expect_stderr "$NO_ROADS
$NO_PARCELS the parcels layer is empty (the grid has no blocks)"
check unused_np 0 0 0.000

# 1x1 grids: a residential cell is one block and one parcel with its 3 people; no class crashes.
vec one -density "$WORK/one_density.tif" -parcels "$WORK/one_parcels.tif" "$WORK/one_4.tif"
expect_status 0
expect_stderr "$NO_ROADS
$ISLAND"
check one 1 1 3.000
for code in 0 1 2 3 4 5 6 7 8; do
  vec "one_$code" "$WORK/one_$code.tif"
  expect_status 0
  case "$ERR" in Warning:*) ;; *) fail "1x1 grid of code $code: stderr '$ERR'";; esac
  ogrinfo -ro -so "$WORK/one_$code.gpkg" parcels >/dev/null 2>&1 || fail "1x1 grid of code $code: no parcels layer"
done

# Bubeneč: its 210 open-land plots hold no one, and the warning says so; the people of the table all
# reach the parcels layer.
g="$SAMPLE_DIR/bubenec"
run_cmd vectorize -q -density "$g/density.tif" -parcels "$g/parcels.tif" -parcel-table "$g/parcels.csv" \
  "$g/landuse.tif" "$WORK/bubenec.gpkg"
expect_status 0
expect_stderr_contains "Warning: 210 input parcels (0 people) lie mostly on open land (unused cells) outside every block: no block takes them, so they are left out of the parcels layer and no population is lost"
case "$ERR" in *"the parcels layer holds"*) fail "bubenec: population reported lost: $ERR";; esac
table=$(awk -F, 'NR > 1 { s += $3 } END { printf "%.3f", s }' "$g/parcels.csv")
kept=$(sql "$WORK/bubenec.gpkg" "SELECT printf('%.3f', SUM(population)) AS n FROM parcels")
expect_eq "$kept" "$table" "bubenec: people of the parcels layer vs the parcel table"

# Monaco: the people E6 cannot place are named in a warning whose numbers are the output's.
g="$SAMPLE_DIR/monaco"
run_cmd vectorize -q -density "$g/density.tif" -parcels "$g/parcels.tif" -parcel-table "$g/parcels.csv" \
  "$g/landuse.tif" "$WORK/monaco.gpkg"
expect_status 0
expect_stderr_contains "Warning: 41 input parcels (0 people) lie mostly on reserved land outside every block: no block takes them, so they are left out of the parcels layer and no population is lost"
kept=$(sql "$WORK/monaco.gpkg" "SELECT printf('%.1f', SUM(population)) AS n FROM parcels" | sed 's/\.0$//')
sim=$(sql "$WORK/monaco.gpkg" "SELECT printf('%.1f', SUM(sim_population)) AS n FROM vectorize_report" | sed 's/\.0$//')
ignored=$(sql "$WORK/monaco.gpkg" "SELECT printf('%.1f', SUM(ignored_population)) AS n FROM vectorize_report" | sed 's/\.0$//')
expect_stderr_contains "Warning: the parcels layer holds $kept of the $sim people of the input parcels inside blocks; the others are $ignored people of land uses that no parcel of their block gets (vectorize_report ignored_population)"
finish
