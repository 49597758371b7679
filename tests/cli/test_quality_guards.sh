#!/usr/bin/env bash
# Quality guards (issue 23): `urbanvec vectorize` with default options on both samples, compared with
# the truth by `urbanvec evaluate` and with the input grids, each figure held in a band around the
# value measured when the guard was written. A change that makes the city worse (fewer matched blocks,
# wrong parcel counts, a larger land-use error, costlier parcels, lost people, lost or extra output)
# fails here.
#
# Bands: counts within +-10 % of today's value -- wide enough for a small deliberate change of the
# algorithms (a tie broken differently, a parameter tuned) to pass without editing this file, narrow
# enough that losing or duplicating a tenth of a layer does not. Quality figures use the same +-10 %
# (at least one unit of the last matched/unmatched step on the small Bubenec sample). The bands are
# two-sided on purpose: a figure that jumps far *better* usually means the measurement broke (an
# evaluate fault can make every block "match"), so an honest improvement moves the band in the same
# commit, with the new value noted below. Today's values (seed 1, default options; both samples are
# gridify grids, so -road-removals auto keeps every road the grid shows since issue 20's road-removal
# default: Monaco before it 792/561 roads/nodes, 196/1178 blocks/parcels, 54 of 88 matched,
# IoU 0.682, L1 0.1181, cost 93.03, p95 1.259 / 0.732, turning 1.021; Bubenec unchanged):
#
#                                   monaco     bubenec
#   roads / road_nodes              1061/776      95/68
#   blocks / parcels / spines   221/1201/57    13/164/0
#   blocks matched (IoU >= 0.7)   55 of 88    7 of 9
#   mean best block IoU             0.691      0.751
#   parcel count ratio (mean)       1.021      1.000
#   land-use L1 error               0.1181     0.2401   (bubenec 0.2557 before B7, 0.1771 after it; 0.1952 since parcel seed streams are keyed by the block's first cell (issue 22): seeds 1-5 give 0.195-0.269)
#                                                       (issue 22, block outlines start at their smallest vertex, a re-draw like another seed: seeds 1-5
#                                                        monaco 0.1209/0.1060/0.1139/0.1075/0.1094 (before 0.1106/0.1205/0.1049/0.1071/0.1083),
#                                                        bubenec 0.2733/0.2853/0.2196/0.2503/0.2320 (before 0.1952/0.2695/0.2282/0.2668/0.2427))
#                                                       (issue 20, curves drawn as curves and B7 approaches straight only where their cells are,
#                                                        a re-draw of the block outlines: bubenec band recentred on 0.2401; seeds 1-5
#                                                        bubenec 0.2401/0.2492/0.2983/0.2541/0.2751, monaco 0.1181/0.0996/0.1056/0.1048/0.0985)
#                                                       (issue 20, B7 arms fitted beyond the window, another re-draw: bubenec band recentred on 0.2013;
#                                                        now 0.2061, monaco 0.1176)
#                                                       (issue 21 round 6, pavement as a coverage, a re-draw: monaco band recentred on 0.0959;
#                                                        seeds 1-5 monaco 0.0959/0.0950/0.0997/0.0929/0.0940 (main 0.0998/0.0979/0.0964/0.0928/0.0933),
#                                                        bubenec 0.1893/0.2751/0.2489/0.2425/0.2232 (main 0.1907/0.2240/0.2701/0.2548/0.3192))
#                                                       (merge of issue 20 round 5 and issue 21 round 6: monaco L1 0.0961, band recentred on it)
#   land-use L1 error (monaco, every road kept)  0.1103
#   mean parcel cost per block     78.86      75.80    (vectorize_report.cost; bubenec 68.78 before issue 20's B7 arms fitted beyond the window)
#   road p95 truth->result cells    0.993      0.512
#   road p95 result->truth cells    0.733      0.482
#   turning ratio                   1.004      1.285    (1.014 / 1.455 before B7 fitted straight arms beyond its window)
#                                                       (issue 20, B7 junction clusters: monaco 1.006, bubenec 1.206; roads/nodes
#                                                        1012/734 and 94/67, monaco blocks/parcels 216/1197, 56 of 88 matched,
#                                                        p95 0.994 / 0.748; stage rows B7, F, C-E copied)
#                                                       (issue 20, a cluster rebuild's links cut to the longest link before:
#                                                        monaco 1.001, bubenec 1.206, monaco blocks/parcels 217/1198;
#                                                        stage rows B7, F, C-E copied: more approaches on the cut links)
#                                                       (issue 20, approaches hooked through another road's band drawn straight:
#                                                        monaco 0.982 / 1.731 bends >= 20, p95 0.993 / 0.751, 56 of 72 matchable; bubenec
#                                                        unchanged; monaco stage rows B7, F, C-E copied: 7 more nodes placed)
#                                                       (issue 20, cluster rebuilds nudged to cover: figures unchanged; B7 rows
#                                                        gain the "nudged to cover" count, B7 and F rows copied)
#                                                       (issue 20 round 5, B7 straight roads on any digital line: monaco turning
#                                                        0.950 / 1.66 bends >= 20, p95 0.998 / 0.749, 56 of 72 matchable, L1 0.0990
#                                                        (band recentred); bubenec unchanged but 3 more straight roads; B7 and F rows copied)    (1.139 / 1.455 before B7, 1.045 / 1.394 before curves drawn as curves, straight roads between ends off their line and approaches straight only where their cells are, issue 20)
#   people in / kept            54197.8 / 54177.7 (20.0 ignored)   3236.36 / 3236.36
#   misplaced people share          0.762      0.699
set -e
source "$(dirname "$0")/lib.sh"

# band <what> <value> <low> <high>: low <= value <= high.
band() {
  echo "$1 = $2 [$3, $4]"
  awk -v v="$2" -v lo="$3" -v hi="$4" 'BEGIN { exit !(v != "" && v + 0 >= lo + 0 && v + 0 <= hi + 0) }' ||
    fail "$1 = '$2', outside its band [$3, $4] (see the table at the top of this test)"
}
jqv() { jq -r "$1" "$2"; }

# Stage activity: every number of the -timings table (nodes and links after each stage and the
# counts of its summary: patches removed, pairs snapped, cycles cut, dead ends removed, bends rounded,
# ...; not seconds or memory) within +-10 % of today's, or +-2 for small counts. A stage that is skipped
# or does much more or less than it did changes its row even when the final figures barely move (e.g.
# B6 no longer rounding the sharpest bends). After a deliberate change, copy the printed rows here.
STAGES_TODAY='
monaco A2 0 0 274 204
monaco A3 0 0
monaco A4 6925 6861 0 2 2 0 77 18
monaco A4.8 9457 9322 73 19
monaco A5 9457 9322 1160 41 0
monaco B1 9457 9322 271 68
monaco B2 9457 9322 6179 153
monaco B3 9474 9946 461 0 17 146 0
monaco B4 9429 9714 5 191 2 27
monaco B5 9029 9314 0 340 1 60
monaco B6 11732 12017 1143 2703 8
monaco B7 11613 11891 132 20 40 0 555 82 67 0 245 194 14 32
monaco F 11559 11837 0 1014 0 2 119 715 1
monaco C-E 0 0 218 1199 1 1 17 38
bubenec A2 0 0 13 7
bubenec A3 0 0
bubenec A4 769 775 0 2 2 0 8 2
bubenec A4.8 1031 1016 21 5
bubenec A5 1031 1016 390 210 0
bubenec B1 1031 1016 15 13
bubenec B2 1031 1016 743 10
bubenec B3 1031 1058 0 0 0 42 0
bubenec B4 1031 1058 0 0 0 0
bubenec B5 1031 1058 0 0 0 0
bubenec B6 1045 1072 7 14 8
bubenec B7 1045 1072 8 1 1 0 56 13 8 0 29 22 2 0
bubenec F 1044 1071 0 94 0 0 4 21 0
bubenec C-E 0 0 13 164 0 0 0 0'
stage_guard() {
  /usr/bin/python3 - "$1" "$2" "$STAGES_TODAY" <<'PY' || fail "$1: stage activity moved out of its bands (see above)"
import re, sys
city, table, today = sys.argv[1], sys.argv[2], sys.argv[3]
rows = {}
for line in table.splitlines():
    # stage, name, seconds, peak MB, nodes, links, summary
    m = re.match(r"^(\S+)\s+(.+?)\s+(\d+\.\d+)\s+(\d+\.\d+)\s+(\d+)\s+(\d+)\s+(.*)$", line)
    if m:
        rows[m.group(1)] = [int(m.group(5)), int(m.group(6))] + [int(x) for x in re.findall(r"\d+", m.group(7))]
ok = True
for line in today.split("\n"):
    parts = line.split()
    if len(parts) < 2 or parts[0] != city:
        continue
    want, got = [int(x) for x in parts[2:]], rows.pop(parts[1], None)
    bad = got is None or len(got) != len(want) or any(abs(g - w) > max(0.1 * w, 2) for g, w in zip(got, want))
    if bad:
        ok = False
        print(f"{city} stage {parts[1]}: today {want}, now {got}")
if rows:
    ok = False
    print(f"{city}: stages not in the table: {sorted(rows)}")
if not ok:
    print("rows now:")
    for line in table.splitlines():
        m = re.match(r"^(\S+)\s+(.+?)\s+(\d+\.\d+)\s+(\d+\.\d+)\s+(\d+)\s+(\d+)\s+(.*)$", line)
        if m:
            print(city, m.group(1), m.group(5), m.group(6), *re.findall(r"\d+", m.group(7)))
sys.exit(0 if ok else 1)
PY
}

# guard <city> <roads> <nodes> <blocks> <parcels> <spines> then the quality bands as lo:hi pairs:
# matched_share iou count_ratio landuse_l1 mean_cost p95_t2r p95_r2t turning misplaced.
guard() {
  local city=$1 g="$SAMPLE_DIR/$1" out="$WORK/$1.gpkg" json="$WORK/$1.json"
  shift
  [ -f "$g/landuse.tif" ] || { fail "missing sample grid $g"; return; }
  run_cmd vectorize -q -timings -density "$g/density.tif" -parcels "$g/parcels.tif" -parcel-table "$g/parcels.csv" \
    "$g/landuse.tif" "$out"
  expect_status 0
  stage_guard "$city" "$OUT"
  run_cmd evaluate -q -json "$json" "$out" "$g/truth.gpkg"
  expect_status 0
  [ -f "$json" ] || { fail "$city: no evaluate report"; return; }

  # Counts, +-10 %.
  local layer i=0 today lo hi n
  for layer in roads road_nodes blocks parcels spines; do
    today=$1; shift
    lo=$(awk -v t="$today" 'BEGIN { printf "%d", t * 0.9 + 0.999 }')
    hi=$(awk -v t="$today" 'BEGIN { printf "%d", t * 1.1 }')
    n=$(feature_count "$out" "$layer")
    band "$city: $layer count (today $today)" "$n" "$lo" "$hi"
  done
  # evaluate must read the same layers: its counts agree with ogrinfo's, and the truth's are fixed.
  expect_eq "$(jqv .blocks.result_count "$json")" "$(feature_count "$out" blocks)" "$city: evaluate's result block count"
  expect_eq "$(jqv .parcels.result_count "$json")" "$(feature_count "$out" parcels)" "$city: evaluate's result parcel count"
  expect_eq "$(jqv '.blocks.truth_count + .blocks.truth_small_count' "$json")" "$(feature_count "$g/truth.gpkg" blocks)" \
    "$city: evaluate's truth block count (counted and too small)"
  expect_eq "$(jqv .parcels.truth_count "$json")" "$(feature_count "$g/truth.gpkg" parcels)" "$city: evaluate's truth parcel count"

  # Against the truth.
  band "$city: block match share" "$(jqv .blocks.matched_share "$json")" ${1%:*} ${1#*:}; shift
  band "$city: mean best block IoU" "$(jqv .blocks.mean_best_iou "$json")" ${1%:*} ${1#*:}; shift
  band "$city: parcel count ratio per matched block (mean)" "$(jqv .parcels.count_ratio_mean "$json")" ${1%:*} ${1#*:}; shift
  band "$city: land-use share error L1" "$(jqv .parcels.landuse_share_error_mean "$json")" ${1%:*} ${1#*:}; shift
  local cost
  cost=$(ogrinfo -ro -q "$out" -dialect SQLite -sql "SELECT AVG(cost) AS n FROM vectorize_report" | sed -n 's/^ *n (Real) = //p')
  band "$city: mean parcel cost per block" "$cost" ${1%:*} ${1#*:}; shift
  band "$city: road p95 distance truth->result (cells)" "$(jqv .roads.distance_truth_to_result.p95_cells "$json")" ${1%:*} ${1#*:}; shift
  band "$city: road p95 distance result->truth (cells)" "$(jqv .roads.distance_result_to_truth.p95_cells "$json")" ${1%:*} ${1#*:}; shift
  band "$city: road turning ratio" "$(jqv .roads.turning_ratio "$json")" ${1%:*} ${1#*:}; shift
  # The parcels tile the blocks exactly and are valid: no gap, no overlap, nothing invalid.
  band "$city: parcel gap share" "$(jqv .parcels.gap_share "$json")" 0 1e-6
  band "$city: parcel overlap share" "$(jqv .parcels.overlap_share "$json")" 0 1e-6
  expect_eq "$(jqv .parcels.invalid_count "$json")" "0" "$city: invalid parcels"
  expect_eq "$(jqv .blocks.result_invalid_count "$json")" "0" "$city: invalid blocks"

  # Population conserved: the people of the input parcels (parcels.csv) are the simulated population
  # of the blocks (the input parcels outside every block hold nobody on both samples), and the parcels
  # layer keeps them all but the ignored people (spec E6), who are at most 0.1 %. The density field is
  # population / area.
  local input
  input=$(awk -F, 'NR > 1 { s += $3 } END { printf "%.6f", s }' "$g/parcels.csv")
  /usr/bin/python3 - "$out" "$input" "$city" <<'PY' || fail "$city: population not conserved (see above)"
import sqlite3, sys
db = sqlite3.connect(sys.argv[1])
inp, city = float(sys.argv[2]), sys.argv[3]
sim, ign = db.execute("SELECT SUM(sim_population), SUM(ignored_population) FROM vectorize_report").fetchone()
kept = db.execute("SELECT SUM(population) FROM parcels").fetchone()[0]
dens = db.execute("SELECT MAX(ABS(density * area - population)) FROM parcels").fetchone()[0]
print(f"{city}: people in {inp:.1f}, simulated {sim:.1f}, kept {kept:.1f}, ignored {ign:.1f}, density*area off by {dens:.3g}")
ok = inp > 0 and abs(sim - inp) <= 1e-3 * inp and abs(kept + ign - sim) <= 1e-6 * sim and ign <= 1e-3 * sim \
    and dens <= 1e-6 * max(1.0, kept)
sys.exit(0 if ok else 1)
PY
  # People where the grid puts them: sum over the parcels of |parcel population - the people of
  # density.tif inside it| / all people. The vector parcels are not the simulated ones, so this is far
  # from 0 (people of a simulated parcel go to the vector parcels of its use, by area), but it grows
  # when people are spread badly (equally instead of by area, to the wrong use, ...).
  local misplaced
  misplaced=$(/usr/bin/python3 - "$out" "$g" <<'PY'
import sys
import numpy as np
from osgeo import gdal, ogr
gdal.UseExceptions()
out, grid = sys.argv[1], sys.argv[2]
dens = gdal.Open(f"{grid}/density.tif")
people = dens.ReadAsArray().astype(np.float64)
ids = gdal.GetDriverByName("MEM").Create("", dens.RasterXSize, dens.RasterYSize, 1, gdal.GDT_Int32)
ids.SetGeoTransform(dens.GetGeoTransform())
ids.SetProjection(dens.GetProjection())
vectors = ogr.Open(out)
gdal.RasterizeLayer(ids, [1], vectors.GetLayerByName("parcels"), options=["ATTRIBUTE=parcel_id"])
inside = np.bincount(ids.ReadAsArray().ravel(), weights=people.ravel())
error = total = 0.0
for f in vectors.GetLayerByName("parcels"):
    k = f.GetField("parcel_id")
    error += abs(f.GetField("population") - (inside[k] if k < len(inside) else 0.0))
    total += f.GetField("population")
print(error / total if total > 0 else "none")
PY
)
  band "$city: misplaced people share" "$misplaced" ${1%:*} ${1#*:}; shift
}

# Boundary suburbs (-suburbs N keeps the islands of at least N pixels): seed 5 gives the city and two
# suburbs of 427 and 587 pixels today.
run_cmd boundary -q -seed 5 -suburbs 200 "$WORK/suburbs.gpkg"
expect_status 0
parts=$(/usr/bin/python3 - "$WORK/suburbs.gpkg" <<'PY'
import sys
from osgeo import ogr
ds = ogr.Open(sys.argv[1])
feature = ds.GetLayer(0).GetNextFeature()
g = feature.GetGeometryRef()
print(" ".join(str(round(g.GetGeometryRef(i).GetArea())) for i in range(g.GetGeometryCount())))
PY
)
echo "boundary -seed 5 -suburbs 200: part areas $parts"
expect_eq "$(wc -w <<<"$parts")" "3" "boundary -suburbs 200: city and suburbs"
for a in $parts; do [ "$a" -ge 200 ] || fail "boundary -suburbs 200: a part of $a pixels"; done

#     city    roads nodes blocks parcels spines  match      iou        ratio      L1           cost         p95 t->r   p95 r->t   turning    misplaced
guard monaco  1061  776   221    1201    57      0.56:0.69  0.62:0.76  0.95:1.10  0.086:0.106  69.6:85.0    0.89:1.09  0.66:0.81  0.94:1.15  0.686:0.838
guard bubenec 95    68    13     164     0       0.70:0.86  0.68:0.83  0.95:1.05  0.181:0.221  68.2:83.4    0.46:0.56  0.43:0.53  1.16:1.41  0.629:0.769

finish
