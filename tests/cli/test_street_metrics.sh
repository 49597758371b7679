#!/usr/bin/env bash
# `urbanvec street-metrics` (issue 18): known answers on a drawn grid, JSON keys, the nodes layer,
# -where / -area / -min-edge-length, bad input, and a cross-check against OSMnx 1.2.3 (Debian's
# python3-osmnx) on the real Bubeneč streets.
set -e
source "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3

# A 5 x 5 grid of 100 m blocks with 40 m overhangs in UTM 33N plus a diagonal path filtered out by -where.
$PY - "$WORK/grid.csv" <<'PY'
import sys
with open(sys.argv[1], "w") as f:
    f.write("kind,WKT\n")
    x0, y0 = 450000, 5550000
    for i in range(6):
        f.write('street,"LINESTRING(%d %d,%d %d)"\n' % (x0 + 100 * i, y0 - 40, x0 + 100 * i, y0 + 540))
        f.write('street,"LINESTRING(%d %d,%d %d)"\n' % (x0 - 40, y0 + 100 * i, x0 + 540, y0 + 100 * i))
    f.write('path,"LINESTRING(%d %d,%d %d)"\n' % (x0 + 10, y0 + 10, x0 + 490, y0 + 480))
PY
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln roads -nlt LINESTRING "$WORK/grid.gpkg" "$WORK/grid.csv"
run_cmd street-metrics -q -where "kind = 'street'" -json "$WORK/grid.json" "$WORK/grid.gpkg" "$WORK/nodes.gpkg"
expect_status 0
for key in orientation_entropy orientation_order share_deadend share_3way share_4way average_degree circuity \
           median_edge_length intersection_density edges nodes; do
  jq -e "has(\"$key\")" "$WORK/grid.json" >/dev/null || fail "JSON lacks $key"
done
jq -e '(.orientation_entropy - 1.3862943611) | fabs < 1e-9' "$WORK/grid.json" >/dev/null ||
  fail "grid entropy $(jq .orientation_entropy "$WORK/grid.json") is not ln 4"
jq -e '.orientation_order == 1 and .nodes == 60 and .edges == 84 and .share_4way == 0.6 and .share_deadend == 0.4' \
  "$WORK/grid.json" >/dev/null || fail "grid figures wrong: $(cat "$WORK/grid.json")"
expect_eq "$(feature_count "$WORK/nodes.gpkg" street_nodes)" "60" "node features"
expect_eq "$(ogrinfo -ro -q -sql "SELECT COUNT(*) AS n FROM street_nodes WHERE degree = 4" "$WORK/nodes.gpkg" |
  sed -n 's/^  n (Integer.*) = //p')" "36" "4-way nodes"
# The diagonal path, when kept, crosses the grid and breaks the ln 4.
run_cmd street-metrics -q -json "$WORK/all.json" "$WORK/grid.gpkg"
expect_status 0
jq -e '.orientation_entropy > 1.45' "$WORK/all.json" >/dev/null || fail "diagonal path did not change H"
# -area: the inner 3 x 3 crossings only, all 4-way, 9 per 0.09 km^2.
printf 'id,WKT\n1,"POLYGON((450050 5550050,450350 5550050,450350 5550350,450050 5550350,450050 5550050))"\n' >"$WORK/area.csv"
ogr2ogr -q -f GPKG -a_srs EPSG:32633 -nln area "$WORK/area.gpkg" "$WORK/area.csv"
run_cmd street-metrics -q -where "kind = 'street'" -area "$WORK/area.gpkg" -json "$WORK/area.json" "$WORK/grid.gpkg"
expect_status 0
jq -e '.nodes == 9 and .share_4way == 1 and (.intersection_density - 100 | fabs) < 1e-6' "$WORK/area.json" >/dev/null ||
  fail "area figures wrong: $(cat "$WORK/area.json")"

# Bad input: one ERROR line, exit status, nothing written.
run_cmd street-metrics -q -min-edge-length -1 "$WORK/grid.gpkg" "$WORK/bad1.gpkg"
expect_status 2
expect_missing "$WORK/bad1.gpkg"
run_cmd street-metrics -q -where "kind = 'nothing'" "$WORK/grid.gpkg" "$WORK/bad2.gpkg"
expect_status 1
expect_stderr "ERROR: layer 'roads' of '$WORK/grid.gpkg' holds no line where kind = 'nothing'"
expect_missing "$WORK/bad2.gpkg"
run_cmd street-metrics -q -where "no_such_field = 1" "$WORK/grid.gpkg"
expect_status 2
expect_stderr_contains "ERROR: -where: layer 'roads' of input '$WORK/grid.gpkg' does not accept the filter 'no_such_field = 1'"
run_cmd street-metrics -q "$WORK/missing.gpkg"
expect_status 1
[ "$(echo "$ERR" | wc -l)" -eq 1 ] || fail "more than one error line: $ERR"
run_cmd street-metrics -q -area "$WORK/grid.gpkg" "$WORK/grid.gpkg"
expect_status 1
expect_stderr_contains "holds no polygon"

# Cross-check against OSMnx on the real Bubeneč streets (UTM 33N).
STREETS="$SAMPLE_DIR/sources/bubenec.gpkg"
ogr2ogr -q -t_srs EPSG:32633 "$WORK/bub.gpkg" "$STREETS" streets
run_cmd street-metrics -q -json "$WORK/bub.json" "$WORK/bub.gpkg"
expect_status 0
if ! $PY -c "import osmnx" 2>/dev/null; then
  echo "SKIP: python3-osmnx is missing (apt-get install python3-osmnx): OSMnx cross-check not run"
else
  $PY - "$WORK/bub.gpkg" "$WORK/osmnx.json" <<'PY' || fail "OSMnx cross-check script failed"
# The same network through OSMnx 1.2.3: noded with shapely (GEOS), nodes in lon/lat, edge lengths in
# metres from UTM, simplified and measured with OSMnx's own functions.
import json, sys, statistics, warnings
warnings.filterwarnings("ignore")
import geopandas as gpd, osmnx as ox, shapely.ops
from shapely.geometry import LineString, Point
from pyproj import Transformer
lines = gpd.read_file(sys.argv[1])
noded = shapely.ops.unary_union(list(lines.geometry))
to_ll = Transformer.from_crs(32633, 4326, always_xy=True)
ids, nodes, edges, keys = {}, [], [], {}
def node(p):
    if p not in ids:
        ids[p] = len(ids)
        lon, lat = to_ll.transform(*p)
        nodes.append({"osmid": ids[p], "x": lon, "y": lat, "geometry": Point(lon, lat)})
    return ids[p]
for part in noded.geoms:
    c = list(part.coords)
    u, v = node(c[0]), node(c[-1])
    geom = LineString([to_ll.transform(*q) for q in c])
    for a, b, g in ((u, v, geom), (v, u, LineString(list(geom.coords)[::-1]))):
        keys[(a, b)] = keys.get((a, b), -1) + 1
        edges.append({"u": a, "v": b, "key": keys[(a, b)], "osmid": 0, "length": part.length, "geometry": g})
gn = gpd.GeoDataFrame(nodes, crs=4326).set_index("osmid")
ge = gpd.GeoDataFrame(edges, crs=4326).set_index(["u", "v", "key"])
G = ox.graph_from_gdfs(gn, ge)
for _, _, d in G.edges(data=True):
    del d["geometry"]  # simplify_graph merges attributes and cannot hash geometries
G = ox.simplify_graph(G)
Gu = ox.get_undirected(G)
Gu = ox.add_edge_bearings(Gu)
H = ox.bearing.orientation_entropy(Gu, num_bins=36)
spn = ox.stats.count_streets_per_node(G)
n = len(spn)
share = lambda k: sum(1 for d in spn.values() if d == k) / n
json.dump({"orientation_entropy": H, "share_deadend": share(1), "share_3way": share(3), "share_4way": share(4),
           "circuity": ox.stats.circuity_avg(Gu), "nodes": n, "edges": len(Gu.edges),
           "average_degree": 2 * len(Gu.edges) / n,
           "median_edge_length": statistics.median(d["length"] for _, _, d in Gu.edges(data=True))},
          open(sys.argv[2], "w"))
PY
  cat "$WORK/osmnx.json"; echo
  for key in nodes edges share_deadend share_3way share_4way average_degree; do
    a=$(jq ".$key" "$WORK/bub.json"); b=$(jq ".$key" "$WORK/osmnx.json")
    awk -v a="$a" -v b="$b" 'BEGIN { exit !((a - b) ^ 2 < 1e-12) }' || fail "$key: urbanvec $a, OSMnx $b"
  done
  for spec in "orientation_entropy 0.03" "circuity 0.002" "median_edge_length 0.01"; do
    set -- $spec
    a=$(jq ".$1" "$WORK/bub.json"); b=$(jq ".$1" "$WORK/osmnx.json")
    awk -v a="$a" -v b="$b" -v t="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t * (b > 1 ? b : 1)) }' ||
      fail "$1: urbanvec $a, OSMnx $b (tolerance $2)"
  done
fi
finish
