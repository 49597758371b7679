#!/usr/bin/env bash
# The naive baselines of issue 2 §3 through bench/baselines: GRASS r.thin + r.to.vect centrelines of
# the road cells and gdal_polygonize.py patches, evaluated against the truth of the hand-made city of
# test_evaluate.sh. The road cells lie under the truth centrelines, so the thinned centrelines must
# lie within a cell of them both ways.
set -e
EVALUATE_FIXTURE_ONLY=1 source "$(dirname "${BASH_SOURCE[0]}")/test_evaluate.sh"
make_evaluate_fixture "$WORK" >/dev/null
BASE="$URBANVEC_SOURCE_DIR/bench/baselines"

"$BASE/grass_centrelines.sh" "$WORK/landuse.tif" "$WORK/grass.gpkg" || fail "grass_centrelines.sh failed"
expect_exists "$WORK/grass.gpkg"
[ "$(feature_count "$WORK/grass.gpkg" roads)" -gt 0 ] || fail "GRASS traced no centrelines"
# The scripts refuse to clobber, like urbanvec.
set +e
ERR=$("$BASE/grass_centrelines.sh" "$WORK/landuse.tif" "$WORK/grass.gpkg" 2>&1)
STATUS=$?
set -e
expect_status 1
expect_stderr "ERROR: output file '$WORK/grass.gpkg' already exists; use -overwrite to replace it"
"$BASE/polygonize.sh" "$WORK/landuse.tif" "$WORK/poly.gpkg" || fail "polygonize.sh failed"

run_cmd evaluate -q -json "$WORK/base.json" -roads-from "$WORK/grass.gpkg" -blocks-layer out \
  -blocks-where "DN >= 4" -parcels-layer out -parcels-where "DN >= 4" -landuse-field DN "$WORK/poly.gpkg" "$WORK/truth.gpkg"
expect_status 0
expect_stderr ""
expect_stdout_contains "result roads                            'roads' of '$WORK/grass.gpkg'"
expect_eq "$(jq '.roads.distance_truth_to_result.p95_cells <= 1 and .roads.distance_result_to_truth.p95_cells <= 1' "$WORK/base.json")" \
  "true" "thinned road cells lie within a cell of the truth"
expect_eq "$(jq '.roads.turning_ratio >= 1' "$WORK/base.json")" "true" "thinning adds turns, never removes them"
expect_eq "$(jq '.blocks.result_count' "$WORK/base.json")" "6" "polygonized developed patches"
expect_eq "$(jq '.parcels.invalid_share' "$WORK/base.json")" "0" "gdal_polygonize.py writes valid polygons"
finish
