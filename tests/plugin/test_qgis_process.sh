#!/usr/bin/env bash
# The provider in real headless QGIS through qgis_process.bin: algorithm list, vectorize on a sample
# grid (checked with ogrinfo against the program run directly), a bad input, the program lookup
# through the Processing setting, and the city_from_osm model chaining gridify -> vectorize -> evaluate.
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
OSM="$URBANVEC_SOURCE_DIR/sample_data/sources/monaco.osm.pbf"
[ -f "$OSM" ] || OSM="$URBANVEC_SOURCE_DIR/../shared/data/real/monaco.osm.pbf"
MODEL="$URBANVEC_SOURCE_DIR/sample_data/models/city_from_osm.model3"
qp() { qgis_process.bin "$@" 2> >(grep -v -e 'setapi() is deprecated' -e '^$' >&2); }

# 1. The toolbox lists one algorithm per subcommand.
qp list > "$WORK/list.txt"
expected="$("$URBANVEC" --json-usage | "$QGIS_PYTHON" -c 'import json,sys; print("\n".join("urbanvec:"+c["name"] for c in json.load(sys.stdin)["commands"]))')"
for alg in $expected; do
  grep -q "^[[:space:]]*$alg[[:space:]]" "$WORK/list.txt" || fail "qgis_process list lacks $alg"
done
for alg in urbanvec:gridify urbanvec:vectorize urbanvec:evaluate; do
  grep -q "^[[:space:]]*$alg[[:space:]]" "$WORK/list.txt" || fail "qgis_process list lacks $alg"
done
qp help urbanvec:vectorize > "$WORK/help.txt"
grep -q '^LANDUSE: ' "$WORK/help.txt" || fail "vectorize help has no LANDUSE parameter"
grep -q 'Command-line option: -seed' "$WORK/help.txt" || fail "vectorize help does not map SEED to -seed"

# 2. vectorize on the sample grid of Monaco, through QGIS and directly: same layers, counts and CRS.
grid="$URBANVEC_SOURCE_DIR/sample_data/monaco"
if [ ! -f "$grid/landuse.tif" ]; then
  grid="$WORK/grid"
  "$URBANVEC" gridify -q -tr 12 "$OSM" "$grid"
fi
qp run urbanvec:vectorize -- LANDUSE="$grid/landuse.tif" DENSITY="$grid/density.tif" PARCELS="$grid/parcels.tif" \
  PARCEL_TABLE="$grid/parcels.csv" OUTPUT="$WORK/city.gpkg" > "$WORK/run.txt" 2> "$WORK/run.err" \
  || { cat "$WORK/run.txt" "$WORK/run.err"; fail "qgis_process run urbanvec:vectorize failed"; }
grep -q "vectorize -progress lines -density $grid/density.tif -parcels $grid/parcels.tif -parcel-table $grid/parcels.csv -overwrite $grid/landuse.tif $WORK/city.gpkg" "$WORK/run.txt" \
  || fail "the command line was not logged as expected: $(grep -m1 'vectorize -progress' "$WORK/run.txt")"
grep -q "^ROADS:[[:space:]]*$WORK/city.gpkg|layername=roads$" "$WORK/run.txt" || fail "no ROADS output in the results"
"$URBANVEC" vectorize -q -density "$grid/density.tif" -parcels "$grid/parcels.tif" -parcel-table "$grid/parcels.csv" \
  "$grid/landuse.tif" "$WORK/direct.gpkg" 2>/dev/null
layers() { ogrinfo -ro -q "$1" | sed -n 's/^[0-9]*: \([a-z_]*\).*/\1/p' | grep -v layer_styles | sort | tr '\n' ' '; }
count() { ogrinfo -ro -so "$1" "$2" | sed -n 's/^Feature Count: //p'; }
[ "$(layers "$WORK/city.gpkg")" = "$(layers "$WORK/direct.gpkg")" ] || fail "layers differ: $(layers "$WORK/city.gpkg")"
for layer in roads road_nodes; do
  layers "$WORK/city.gpkg" | grep -qw "$layer" || fail "city.gpkg has no $layer layer"
done
for layer in $(layers "$WORK/city.gpkg"); do
  [ "$(count "$WORK/city.gpkg" "$layer")" = "$(count "$WORK/direct.gpkg" "$layer")" ] \
    || fail "$layer: $(count "$WORK/city.gpkg" "$layer") features through QGIS, $(count "$WORK/direct.gpkg" "$layer") directly"
done
roads="$(count "$WORK/city.gpkg" roads)"
[ "$roads" -ge 100 ] || fail "only $roads roads in Monaco"
ogrinfo -ro -so "$WORK/city.gpkg" roads | grep -q 'ID\["EPSG",32632\]' || fail "roads are not in EPSG:32632 (UTM 32N, the grid's CRS)"
echo "vectorize through qgis_process: $roads roads, $(count "$WORK/city.gpkg" road_nodes) road nodes"

# 3. A bad input fails with the program's own message and writes nothing.
set +e
qp run urbanvec:vectorize -- LANDUSE="$grid/density.tif" OUTPUT="$WORK/bad.gpkg" > "$WORK/bad.txt" 2>&1
status=$?
set -e
[ "$status" -ne 0 ] || fail "vectorize of a density raster succeeded"
grep -q "holds value .* which is not a land-use class code" "$WORK/bad.txt" || { cat "$WORK/bad.txt"; fail "the program's error message is not shown"; }
[ ! -e "$WORK/bad.gpkg" ] || fail "a failed run left $WORK/bad.gpkg"

# 4. The model: OSM extract -> gridify -> vectorize -> evaluate.
qp run "$MODEL" -- osm="$OSM" cell_size=12 vectorize:city="$WORK/model_city.gpkg" evaluate:report="$WORK/report.json" \
  > "$WORK/model.txt" 2> "$WORK/model.err" || { tail -30 "$WORK/model.txt" "$WORK/model.err"; fail "the model failed"; }
grep -q 'Executed 3 algorithms' "$WORK/model.txt" || fail "the model did not run its 3 algorithms"
"$URBANVEC" gridify -q -tr 12 "$OSM" "$WORK/grid12"
"$URBANVEC" vectorize -q -density "$WORK/grid12/density.tif" -parcels "$WORK/grid12/parcels.tif" \
  -parcel-table "$WORK/grid12/parcels.csv" "$WORK/grid12/landuse.tif" "$WORK/direct12.gpkg" 2>/dev/null
for layer in $(layers "$WORK/direct12.gpkg"); do
  [ "$(count "$WORK/model_city.gpkg" "$layer")" = "$(count "$WORK/direct12.gpkg" "$layer")" ] \
    || fail "the model's $layer: $(count "$WORK/model_city.gpkg" "$layer") features, directly $(count "$WORK/direct12.gpkg" "$layer")"
done
# The model's report is the report of the same chain run directly, figure for figure.
"$URBANVEC" evaluate -q -json "$WORK/direct12.json" "$WORK/direct12.gpkg" "$WORK/grid12/truth.gpkg" >/dev/null
"$QGIS_PYTHON" - "$WORK/report.json" "$WORK/direct12.json" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
direct = json.load(open(sys.argv[2]))
for key in ('roads', 'blocks', 'parcels'):
    assert report[key] == direct[key], '{} of the model differs from the direct run: {} vs {}'.format(
        key, report[key], direct[key])
assert report['roads']['distance_truth_to_result']['p95_cells'] is not None, 'no road distance in the report'
assert report['blocks']['matched_share'] is not None and report['blocks']['matched_share'] > 0.3, \
    'the model matched almost no block: {}'.format(report['blocks']['matched_share'])
PY
echo "model city_from_osm: $(count "$WORK/model_city.gpkg" roads) roads, report $(wc -c < "$WORK/report.json") bytes"

# 5. The program from the Processing setting, when it is not on PATH.
PATH="$(echo "$PATH" | tr ':' '\n' | grep -vx "$(dirname "$URBANVEC")" | paste -sd: -)"
if command -v urbanvec >/dev/null; then fail "another urbanvec is on PATH: $(command -v urbanvec)"; fi
ini="$HOME/.local/share/QGIS/QGIS3/profiles/default/QGIS/QGIS3.ini"
qp list 2>/dev/null | grep -q 'urbanvec:vectorize' && fail "algorithms listed although no program can be found"
printf '\n[Processing]\nConfiguration\\URBANVEC_PROGRAM=%s\n' "$URBANVEC" >> "$ini"
qp list | grep -q 'urbanvec:vectorize' || fail "the program set in the Processing options was not used"
echo "PASS"
