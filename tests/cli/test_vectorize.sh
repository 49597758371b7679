#!/usr/bin/env bash
# `urbanvec vectorize` on real-derived grids: layers, counts, geometry types, CRS, fields, topology,
# debug stages, progress lines, and the output contract (no clobbering without -overwrite).
set -e
source "$(dirname "$0")/lib.sh"

# The sample grids (in the repository, so never skipped) and today's road/node counts with default
# options (issue 23): the counts must stay within +-10 % (see test_quality_guards.sh for why).
grids=("$SAMPLE_DIR/monaco" "$SAMPLE_DIR/bubenec")
declare -A today_roads=([monaco]=785 [bubenec]=95) today_nodes=([monaco]=555 [bubenec]=68)
for g in "${grids[@]}"; do [ -f "$g/landuse.tif" ] || fail "missing sample grid $g"; done

for g in "${grids[@]}"; do
  name=$(basename "$g")
  out="$WORK/$name.gpkg"
  run_cmd vectorize -check -density "$g/density.tif" -parcels "$g/parcels.tif" -parcel-table "$g/parcels.csv" \
    "$g/landuse.tif" "$out"
  expect_status 0
  expect_stdout_contains "0 crossings, 0 zero-length pieces, 0 duplicate nodes, 0 segment ends without a node"
  # Road-cell coverage (issue 3): every road cell of the grid lies within 1.5 cells of a result road,
  # except the cells the pipeline removes on purpose (A3 extraneous patches, A4.3 2x2 squares, B4 short
  # cycles, B5 dead ends). The road cells are counted here independently of the program.
  road_cells=$(/usr/bin/python3 -c "import sys; from osgeo import gdal; a = gdal.Open(sys.argv[1]).ReadAsArray(); print(int(((a == 2) | (a == 3)).sum()))" "$g/landuse.tif")
  coverage=$(grep "^road cells farther than 1.5 cells from a road: " <<<"$OUT" || true)
  far=$(sed -n "s/^road cells farther than 1.5 cells from a road: \([0-9]*\) of $road_cells (.*/\1/p" <<<"$coverage")
  [ -n "$far" ] || fail "$name: road coverage line missing or counts other than $road_cells road cells: '$coverage'"
  [ "$far" = 0 ] || fail "$name: $far of $road_cells road cells are farther than 1.5 cells from a road"
  expect_exists "$out"
  info=$(ogrinfo -ro -so "$out" roads)
  case "$info" in *"Geometry: Line String"*) ;; *) fail "$name: roads are not LineStrings";; esac
  for f in "road_id: Integer" "road_class: String" "from_node: Integer" "to_node: Integer" "length: Real"; do
    case "$info" in *"$f"*) ;; *) fail "$name: roads lack field '$f'";; esac
  done
  ninfo=$(ogrinfo -ro -so "$out" road_nodes)
  case "$ninfo" in *"Geometry: Point"*) ;; *) fail "$name: road_nodes are not Points";; esac
  for f in "node_id: Integer" "kind: String" "degree: Integer"; do
    case "$ninfo" in *"$f"*) ;; *) fail "$name: road_nodes lack field '$f'";; esac
  done
  # CRS: the land-use raster's.
  srs_out=$(ogrinfo -ro -so "$out" roads | sed -n 's/^.*ID\["EPSG",\([0-9]*\)\]\]$/\1/p' | tail -1)
  srs_in=$(gdalinfo "$g/landuse.tif" | sed -n 's/^.*ID\["EPSG",\([0-9]*\)\]\]$/\1/p' | tail -1)
  expect_eq "$srs_out" "$srs_in" "$name: output CRS"
  roads=$(feature_count "$out" roads)
  nodes=$(feature_count "$out" road_nodes)
  awk -v n="${roads:-0}" -v t="${today_roads[$name]}" 'BEGIN { exit !(n >= 0.9 * t && n <= 1.1 * t) }' ||
    fail "$name: ${roads} road segments, not within 10 % of today's ${today_roads[$name]}"
  awk -v n="${nodes:-0}" -v t="${today_nodes[$name]}" 'BEGIN { exit !(n >= 0.9 * t && n <= 1.1 * t) }' ||
    fail "$name: ${nodes} road nodes, not within 10 % of today's ${today_nodes[$name]}"
  # Classes present, and no zero-length segment.
  classes=$(ogrinfo -ro -q "$out" -sql "SELECT DISTINCT road_class FROM roads ORDER BY road_class" | sed -n 's/^ *road_class (String) = //p' | tr '\n' ' ')
  case "$classes" in *secondary*) ;; *) fail "$name: no secondary roads ($classes)";; esac
  zero=$(ogrinfo -ro -q "$out" -sql "SELECT COUNT(*) AS n FROM roads WHERE length <= 0" | sed -n 's/^ *n (Integer) = //p')
  expect_eq "$zero" "0" "$name: zero-length roads"
  # Segment ends are road nodes: from_node/to_node name existing nodes.
  dangling=$(ogrinfo -ro -q "$out" -dialect SQLite -sql "SELECT COUNT(*) AS n FROM roads WHERE from_node NOT IN (SELECT node_id FROM road_nodes) OR to_node NOT IN (SELECT node_id FROM road_nodes)" | sed -n 's/^ *n (Integer) = //p')
  expect_eq "$dangling" "0" "$name: roads naming missing nodes"
done

# -keep-all-roads (no A3, B4, B5 removals) on the first real grid: it keeps every road cell covered
# with nothing excused for those stages (A4.3 still opens 2x2 road squares), and on Monaco it brings
# the truth->result 95th percentile within the issue's 1 cell (1.26 with the spec's removals;
# docs/vectorize.md "Keeping every road").
g=${grids[0]}
if [ -f "$g/truth.gpkg" ]; then
  run_cmd vectorize -q -check -timings -roads-only -keep-all-roads "$g/landuse.tif" "$WORK/keep.gpkg"
  expect_status 0
  expect_stdout_contains "road cells farther than 1.5 cells from a road: 0 of "
  expect_stdout_contains " 0 short-cycle roads (B4), 0 dead ends (B5))"
  expect_stdout_contains "A3     patch cleaning"
  expect_stdout_contains "skipped (every secondary patch kept)"
  run_cmd evaluate -q -json "$WORK/keep.json" "$WORK/keep.gpkg" "$g/truth.gpkg"
  expect_status 0
  /usr/bin/python3 - "$WORK/keep.json" <<'PY' || fail "-keep-all-roads: centreline distance or turning out of the issue's bounds"
import json, sys
r = json.load(open(sys.argv[1]))["roads"]
vals = (r["distance_truth_to_result"]["median_cells"], r["distance_truth_to_result"]["p95_cells"],
        r["distance_result_to_truth"]["median_cells"], r["distance_result_to_truth"]["p95_cells"], r["turning_ratio"])
print("keep-all-roads:", vals)
sys.exit(0 if vals[0] <= 0.3 and vals[1] <= 1.0 and vals[2] <= 0.3 and vals[3] <= 1.0 and vals[4] <= 1.5 else 1)
PY
fi

# An existing output is an error without -overwrite, and stays untouched.
before=$(md5sum "$WORK/$(basename "$g").gpkg")
run_cmd vectorize "$g/landuse.tif" "$WORK/$(basename "$g").gpkg"
expect_status 1
expect_stderr_contains "ERROR: "
expect_eq "$(md5sum "$WORK/$(basename "$g").gpkg")" "$before" "untouched output"

# -progress lines names every stage; -debug-stages writes one links/nodes layer pair per graph stage.
run_cmd vectorize -progress lines -timings -debug-stages "$WORK/stages" "$g/landuse.tif" "$WORK/p.gpkg"
expect_status 0
for stage in "raw blocks" "patch cleaning" "road graph" "perimeters" "parcels" "intersection straightening" \
  "road smoothing" "primary/secondary connection" "cycle removal" "intersection simplification" "curve smoothing" \
  "through roads"; do
  case "$OUT" in *"PROGRESS "*" $stage"*) ;; *) fail "no progress line for stage '$stage'";; esac
done
expect_stdout_contains "PROGRESS 100"
expect_stdout_contains "peak_MB"
layers=$(ogrinfo -ro -q "$WORK/stages/stages.gpkg" | grep -c "_links (Line String)" || true)
# One links/nodes pair per graph stage: A4, A4.8, B1-B7.
expect_eq "$layers" "9" "debug stage layers"
expect_no_temp "$WORK"

finish
