#!/usr/bin/env bash
# `urbanvec shape-metrics`: metric fields on a copy of any polygon layer, units, CRS rules and bad
# input (issue 7).
set -e
source "$(dirname "$0")/lib.sh"

# A circle (ratio 1, D = 1) and the thesis's 200 m x 4 km village (ratio 0.0635) in UTM 33N, with an
# attribute that must survive the copy.
python3 - "$WORK/shapes.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("name,WKT\n")
    pts = [(455000 + 1000 * math.cos(2 * math.pi * i / 2000), 5550000 + 1000 * math.sin(2 * math.pi * i / 2000)) for i in range(2000)]
    pts.append(pts[0])
    f.write('circle,"POLYGON((' + ",".join("%.3f %.3f" % p for p in pts) + '))"\n')
    f.write('village,"POLYGON((460000 5550000,464000 5550000,464000 5550200,460000 5550200,460000 5550000))"\n')
PY
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln shapes -nlt POLYGON "$WORK/shapes.gpkg" "$WORK/shapes.csv"

run_cmd shape-metrics -q "$WORK/shapes.gpkg" "$WORK/out.gpkg"
expect_status 0
# The 4-corner village has l0 = its mean side: the chords outgrow it at once, so no dimension.
expect_stderr "Warning: 1 polygon has too few vertices for the chord lengths (fewer than 3 chords at the third scale): fractal_dimension is empty; try a smaller -step or fewer -scales"
info=$(ogrinfo -ro -so "$WORK/out.gpkg" shapes)
for f in name fractal_dimension slope_a sigma enclosed_area_ratio base_chord valid; do
  case "$info" in *"$f: "*) ;; *) fail "field $f missing";; esac
done
case "$info" in *'ID["EPSG",32633]'*) ;; *) fail "CRS not kept";; esac
expect_eq "$(feature_count "$WORK/out.gpkg" shapes)" "2" "feature count"
vals=$(ogrinfo -ro -q "$WORK/out.gpkg" shapes)
circle=$(echo "$vals" | awk '/name \(String\) = circle/{c=1} c && /enclosed_area_ratio/{print $4; exit}')
village=$(echo "$vals" | awk '/name \(String\) = village/{c=1} c && /enclosed_area_ratio/{print $4; exit}')
dimension=$(echo "$vals" | awk '/name \(String\) = circle/{c=1} c && /fractal_dimension/{print $4; exit}')
awk -v c="$circle" -v v="$village" -v d="$dimension" \
    'BEGIN { exit !(c > 0.999 && c <= 1.0 && v > 0.0634 && v < 0.0636 && d > 0.99 && d < 1.01) }' ||
  fail "circle ratio $circle / dimension $dimension or village ratio $village wrong"
# Both are far too smooth to be city boundaries.
expect_eq "$(echo "$vals" | grep -c 'valid (Integer64) = 0')" "2" "smooth shapes are not realistic"

# A generated boundary measured again: fields are replaced, not duplicated; -eval-at 13.06 reads D_R
# where the generator does.
run_cmd boundary -q -seed 11 -cellsize 1 "$WORK/city.gpkg"
run_cmd shape-metrics -q -eval-at 13.06 "$WORK/city.gpkg" "$WORK/city_metrics.gpkg"
expect_status 0
expect_stderr "Warning: layer 'boundary' has no CRS: lengths are in its coordinate units"
expect_eq "$(ogrinfo -ro -so "$WORK/city_metrics.gpkg" boundary | grep -c '^fractal_dimension:')" "1" "replaced field"
d=$(ogrinfo -ro -q "$WORK/city_metrics.gpkg" boundary | sed -n 's/^  fractal_dimension (Real) = //p')
awk -v d="$d" 'BEGIN { exit !(d > 1.1 && d < 1.4) }' || fail "generated boundary measures D_R $d"

# Real parcels (Bubenec plots, in the repository so never skipped): every polygon gets a ratio in (0, 1].
PLOTS="$SAMPLE_DIR/sources/bubenec.gpkg"
run_cmd shape-metrics -q -layer plots -skip 1 "$PLOTS" "$WORK/plots.gpkg"
expect_status 0
n=$(feature_count "$PLOTS" plots)
[ "${n:-0}" -gt 200 ] || fail "only '$n' plots in $PLOTS"
expect_eq "$(feature_count "$WORK/plots.gpkg" plots)" "$n" "plots copied"
bad=$(ogrinfo -ro -q -sql "SELECT COUNT(*) AS n FROM plots WHERE enclosed_area_ratio <= 0 OR enclosed_area_ratio > 1 OR enclosed_area_ratio IS NULL" "$WORK/plots.gpkg" | sed -n 's/^  n (Integer.*) = //p')
expect_eq "$bad" "0" "plots with a ratio outside (0, 1]"

# Geographic input needs -t_srs, and the error suggests the UTM zone; -t_srs then works.
ogr2ogr -q -t_srs EPSG:4326 "$WORK/geo.gpkg" "$WORK/shapes.gpkg"
run_cmd shape-metrics -q "$WORK/geo.gpkg" "$WORK/geo_out.gpkg"
expect_status 1
expect_stderr "ERROR: layer 'shapes' of '$WORK/geo.gpkg' is in a geographic CRS (EPSG:4326); lengths and areas need metres: give -t_srs, e.g. -t_srs EPSG:32633"
expect_missing "$WORK/geo_out.gpkg"
run_cmd shape-metrics -q -t_srs EPSG:32633 "$WORK/geo.gpkg" "$WORK/geo_out.gpkg"
expect_status 0

# Bad input.
run_cmd shape-metrics -q "$WORK/nothing.gpkg" "$WORK/x.gpkg"
expect_status 1
expect_stderr_contains "nothing.gpkg"
run_cmd shape-metrics -q -layer roads "$WORK/shapes.gpkg" "$WORK/x.gpkg"
expect_status 1
expect_stderr "ERROR: input '$WORK/shapes.gpkg' has no layer 'roads'"
printf 'id,WKT\n1,"LINESTRING(0 0,1 1)"\n' > "$WORK/lines.csv"
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln lines -nlt LINESTRING "$WORK/lines.gpkg" "$WORK/lines.csv"
run_cmd shape-metrics -q "$WORK/lines.gpkg" "$WORK/x.gpkg"
expect_status 1
expect_stderr "ERROR: layer 'lines' of '$WORK/lines.gpkg' does not hold polygons; shape-metrics measures polygon outlines"
run_cmd shape-metrics -q "$WORK/shapes.gpkg" "$WORK/out.gpkg"
expect_status 1
expect_stderr "ERROR: output file '$WORK/out.gpkg' already exists; use -overwrite to replace it"
run_cmd shape-metrics -q -skip 0 "$WORK/shapes.gpkg" "$WORK/x.gpkg"
expect_status 2
expect_missing "$WORK/x.gpkg"
expect_no_temp "$WORK"

finish
