#!/usr/bin/env bash
# The city_from_scratch model in headless QGIS (issue 18 "Chain"): boundary -> streets -> gridify ->
# vectorize ends in parcels, and the streets and parcels are those of the same chain run directly.
set -euo pipefail
source "$(dirname "$0")/qgis_env.sh"
MODEL="$URBANVEC_SOURCE_DIR/sample_data/models/city_from_scratch.model3"
qp() { qgis_process.bin "$@" 2> >(grep -v -e 'setapi() is deprecated' -e '^$' >&2); }
count() { ogrinfo -ro -so "$1" "$2" | sed -n 's/^Feature Count: //p'; }

qp run "$MODEL" -- seed=3 dsep_major=360 streets:streets="$WORK/streets.gpkg" vectorize:city="$WORK/city.gpkg" \
  > "$WORK/model.txt" 2> "$WORK/model.err" || { tail -30 "$WORK/model.txt" "$WORK/model.err"; fail "the model failed"; }
grep -q 'Executed 4 algorithms' "$WORK/model.txt" || fail "the model did not run its 4 algorithms"
parcels="$(count "$WORK/city.gpkg" parcels)"
[ "${parcels:-0}" -ge 10 ] || fail "the model made only '$parcels' parcels"
ogrinfo -ro -so "$WORK/city.gpkg" parcels | grep -q 'ID\["EPSG",32633\]' || fail "parcels are not in EPSG:32633"

# The same chain directly.
"$URBANVEC" boundary -q -seed 3 -a_srs EPSG:32633 -cellsize 6 "$WORK/b.gpkg"
"$URBANVEC" streets -q -boundary "$WORK/b.gpkg" -boundary-field -dsep-major 360 -seed 3 "$WORK/s.gpkg"
"$URBANVEC" gridify -q -tr 8 -landuse-layer blocks -landuse-field land_use "$WORK/s.gpkg" "$WORK/grid"
"$URBANVEC" vectorize -q -seed 3 -density "$WORK/grid/density.tif" -parcels "$WORK/grid/parcels.tif" \
  -parcel-table "$WORK/grid/parcels.csv" "$WORK/grid/landuse.tif" "$WORK/direct.gpkg" 2>/dev/null
for layer in streets blocks; do
  [ "$(count "$WORK/streets.gpkg" "$layer")" = "$(count "$WORK/s.gpkg" "$layer")" ] ||
    fail "$layer: $(count "$WORK/streets.gpkg" "$layer") through the model, $(count "$WORK/s.gpkg" "$layer") directly"
done
[ "$parcels" = "$(count "$WORK/direct.gpkg" parcels)" ] || fail "parcels: $parcels through the model, $(count "$WORK/direct.gpkg" parcels) directly"
echo "model city_from_scratch: $(count "$WORK/streets.gpkg" streets) streets, $parcels parcels"
echo "PASS"
