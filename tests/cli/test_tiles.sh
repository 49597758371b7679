#!/usr/bin/env bash
# urbanvec-tiles (issue 22, docs/scale.md): a tiled run (sequential, and on a local Dask cluster of 2
# workers) gives the features of a single run (Bubenec and Monaco, every layer); a too-small halo is
# caught; a killed worker's tile is retried; bad input is refused before any work.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
TILES="$URBANVEC_SOURCE_DIR/tools/urbanvec-tiles"
export URBANVEC
D="$SAMPLE_DIR/bubenec"
IN=(-density "$D/density.tif" -parcels "$D/parcels.tif" -parcel-table "$D/parcels.csv" "$D/landuse.tif")
run_tiles() {
  set +e
  OUT=$(/usr/bin/python3 "$TILES" "$@" 2>"$WORK/.stderr")
  STATUS=$?
  ERR=$(cat "$WORK/.stderr")
  set -e
}
# digest_of <gpkg> <layer...>: the canonical digests of those layers.
digest_of() { local f=$1; shift; local out; out=$(/usr/bin/python3 "$TILES" digest "$f"); for l in "$@"; do grep "^$l " <<<"$out"; done; }
ALL=(roads road_nodes pavement blocks water spines parcels vectorize_report)

# A single run, and the windowed read matches it: -srcwin of the whole grid gives the same bytes.
run_cmd vectorize -q "${IN[@]:0:6}" "$D/landuse.tif" "$WORK/single.gpkg"
expect_status 0
run_cmd vectorize -q -srcwin 0 0 98 107 "${IN[@]:0:6}" "$D/landuse.tif" "$WORK/whole.gpkg"
expect_status 0
expect_eq "$(digest_of "$WORK/whole.gpkg" roads parcels)" "$(digest_of "$WORK/single.gpkg" roads parcels)" "-srcwin of the whole grid"
# A window is georeferenced at its place: its extent lies inside the single run's.
run_cmd vectorize -q -roads-only -srcwin 10 20 60 50 "$D/landuse.tif" "$WORK/win.gpkg"
expect_status 0
ox=$(gdalinfo "$D/landuse.tif" | sed -n 's/^Origin = (\([0-9.]*\),.*/\1/p')
wx=$(ogrinfo -ro -so "$WORK/win.gpkg" roads | sed -n 's/^Extent: (\([0-9.]*\),.*/\1/p')
cell=$(gdalinfo "$D/landuse.tif" | sed -n 's/^Pixel Size = (\([0-9.]*\),.*/\1/p')
single_x=$(ogrinfo -ro -so "$WORK/single.gpkg" roads | sed -n 's/^Extent: (\([0-9.]*\),.*/\1/p')
awk -v o="$ox" -v w="$wx" -v c="$cell" 'BEGIN { exit !(w >= o + 10 * c && w <= o + 14 * c) }' ||
  fail "window roads start at x=$wx, the window at $ox + 10 x $cell"
awk -v s="$single_x" -v w="$wx" 'BEGIN { exit !(w > s) }' || fail "window roads start west of the single run's"
run_cmd vectorize -q -srcwin 50 50 60 60 "$D/landuse.tif" "$WORK/out.gpkg"
expect_status 2
expect_stderr_contains "-srcwin 50 50 60 60 is not inside land-use raster"
expect_missing "$WORK/out.gpkg"

# Tiled, sequential: 6 tiles of 50 cells, halo 16 (the guard raises it where a region is cut).
run_tiles run --sequential -q -tile 50 -halo 16 -max-halo 64 "${IN[@]}" "$WORK/seq.gpkg"
expect_status 0
# Every layer, parcels included: a block's stages C-E see the same numbers in any window.
expect_eq "$(digest_of "$WORK/seq.gpkg" "${ALL[@]}")" "$(digest_of "$WORK/single.gpkg" "${ALL[@]}")" "tiled (sequential) vs single"
expect_eq "$(feature_count "$WORK/seq.gpkg" parcels)" "$(feature_count "$WORK/single.gpkg" parcels)" "parcel count"
expect_eq "$(feature_count "$WORK/seq.gpkg" pavement)" "$(feature_count "$WORK/single.gpkg" pavement)" "pavement count"
expect_eq "$(feature_count "$WORK/seq.gpkg" layer_styles)" "$(feature_count "$WORK/single.gpkg" layer_styles)" "styles"
expect_no_temp "$WORK"

# Tiled on a local Dask cluster of 2 workers: the same digests.
run_tiles run --local 2 -q -tile 50 -halo 16 -max-halo 64 "${IN[@]}" "$WORK/dask.gpkg"
expect_status 0
expect_eq "$(digest_of "$WORK/dask.gpkg" "${ALL[@]}")" "$(digest_of "$WORK/seq.gpkg" "${ALL[@]}")" "local cluster vs sequential"

# Monaco (348 x 413 cells; sea and open land on three sides): 6 tiles of 200 cells, halo 64. Every
# layer equal here too: stage D1 unions the pavement in squares anchored to the raster's frame, so a
# window gets the union's vertices the whole raster gets (GEOS's cascaded union of the whole window
# gave a few intersections other near-duplicate vertices, and the blocks and parcels next to them).
M="$SAMPLE_DIR/monaco"
MIN=(-density "$M/density.tif" -parcels "$M/parcels.tif" -parcel-table "$M/parcels.csv" "$M/landuse.tif")
run_cmd vectorize -q "${MIN[@]:0:6}" "$M/landuse.tif" "$WORK/monaco.gpkg"
expect_status 0
run_tiles run --sequential -q -tile 200 -halo 64 -max-halo 256 "${MIN[@]}" "$WORK/monaco_tiled.gpkg"
expect_status 0
expect_eq "$(digest_of "$WORK/monaco_tiled.gpkg" "${ALL[@]}")" "$(digest_of "$WORK/monaco.gpkg" "${ALL[@]}")" "Monaco tiled vs single"
expect_eq "$(feature_count "$WORK/monaco_tiled.gpkg" pavement)" "$(feature_count "$WORK/monaco.gpkg" pavement)" "Monaco pavement count"
# Tiles of 256 cells: tile r000_c000's window (cells 0..326 wide) ends 2 cells east of a kept external
# block, where a perimeter road runs along the cut side and moves a junction next to the block; the
# block itself stays a cell away from the side, so only the shaped-road guard (tile.py shaped_roads)
# redoes the tile with a larger halo (without it: 1 block and its 59 parcels differ).
run_tiles run --sequential -q -tile 256 -halo 64 -max-halo 256 "${MIN[@]}" "$WORK/monaco_256.gpkg"
expect_status 0
expect_eq "$(digest_of "$WORK/monaco_256.gpkg" "${ALL[@]}")" "$(digest_of "$WORK/monaco.gpkg" "${ALL[@]}")" "Monaco tiles of 256 vs single"

# A too-small halo that may not grow is caught, naming the tile; nothing is written.
run_tiles run --sequential -q -tile 50 -halo 4 -max-halo 4 "${IN[@]}" "$WORK/small.gpkg"
expect_status 1
expect_stderr_contains "ERROR: tile r000_c000"
expect_stderr_contains "kept features reach the edge of its window with halo 4"
expect_missing "$WORK/small.gpkg"
expect_no_temp "$WORK"

# Bad input: before any work, one ERROR line.
run_tiles run --sequential -tile 50 -halo 200 "${IN[@]}" "$WORK/bad.gpkg"
expect_status 2
expect_stderr "ERROR: -halo 200 is larger than the grid (98 x 107 cells)"
run_tiles run --sequential -tile 0 -halo 4 "${IN[@]}" "$WORK/bad.gpkg"
expect_status 2
expect_stderr "ERROR: -tile must be at least 1 cell, got 0"
run_tiles run --sequential -tile 50 -halo 16 "${IN[@]}" "$WORK/seq.gpkg"
expect_status 1
expect_stderr_contains "exists; give -overwrite"
start=$(date +%s)
run_tiles run --scheduler tcp://127.0.0.1:9 --connect-timeout 3 -tile 50 -halo 16 "${IN[@]}" "$WORK/bad.gpkg"
expect_status 1
expect_stderr_contains "ERROR: scheduler 'tcp://127.0.0.1:9' does not answer"
[ $(( $(date +%s) - start )) -le 10 ] || fail "the unreachable scheduler took more than 10 s to report"
expect_missing "$WORK/bad.gpkg"
# A worker out of disk (a file size limit of 200 KB: the tile's GeoPackage cannot be written): the tile
# is named with the reason, and neither the output nor a work folder is left behind.
set +e
mkdir -p "$WORK/full"
OUT=$( (ulimit -f 200 && exec /usr/bin/python3 "$TILES" run --sequential -q -tile 50 -halo 16 -max-halo 64 \
  "${IN[@]}" "$WORK/full/out.gpkg") 2>"$WORK/.stderr")
STATUS=$?
set -e
ERR=$(cat "$WORK/.stderr")
expect_status 1
expect_stderr_contains "ERROR: tile r000_c000 (window 0 0 72 78): urbanvec vectorize failed (killed by SIGXFSZ: file size limit reached"
[ -z "$(ls -A "$WORK/full" 2>/dev/null)" ] || fail "out of disk left files behind: $(ls -A "$WORK/full")"

# A worker killed mid-run: its tile is retried elsewhere and the result is the same.
export URBANVEC_FAULT=write-delay-ms=300
/usr/bin/python3 "$TILES" run --local 2 -q -roads-only -tile 50 -halo 16 -max-halo 64 "$D/landuse.tif" "$WORK/killed.gpkg" \
  2>"$WORK/killed.err" &
driver=$!
victim=""
for _ in $(seq 1 200); do
  # The local cluster's workers are the driver's children; each runs its tile's vectorize as a child.
  # Only this run's processes are looked at (other runs on the machine may have -srcwin children),
  # and a process that ends meanwhile is simply not found.
  for w in $(pgrep -P "$driver" 2>/dev/null || true); do
    if pgrep -P "$w" -f -- "-srcwin" >/dev/null 2>&1; then victim=$w; fi
  done
  [ -n "$victim" ] && break
  sleep 0.1
done
[ -n "$victim" ] && kill -9 "$victim" || fail "found no worker running a tile"
wait "$driver" || fail "the run with a killed worker failed: $(cat "$WORK/killed.err")"
unset URBANVEC_FAULT
/usr/bin/python3 "$TILES" run --sequential -q -roads-only -tile 50 -halo 16 -max-halo 64 "$D/landuse.tif" "$WORK/roads.gpkg"
expect_eq "$(digest_of "$WORK/killed.gpkg" roads road_nodes)" "$(digest_of "$WORK/roads.gpkg" roads road_nodes)" "killed worker vs sequential"
finish
