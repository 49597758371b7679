#!/usr/bin/env python3
"""How far the result's block edges are from the truth's, per unmatched matchable truth block (issue 20,
"Monaco's matchable blocks: the frontier"). Matchable and matched as `urbanvec evaluate` counts them:
internal truth blocks of >= 4 cells with >= 0.7 of their area on land cells (4 x 4 samples per cell),
matched at IoU >= 0.7 with their best result block. For each unmatched one, the best IoU

  result      the result blocks as written;
  grown d     every result block grown by d cells (mitred; d > 0 is pavement 2d cells narrower,
              d < 0 wider), d in -0.25 .. 0.5: whether a narrower or wider pavement would match it;
  truth edges the result's faces (polygons of its road centrelines and perimeters) minus the truth's
              road surfaces (truth centrelines buffered by the curb half widths, 1 / 0.5 cell): block
              edges on the truth's surfaces, the result's topology kept;
  truth edges for one class only  the faces minus the truth's surfaces of that class and the result's
              centrelines of the other buffered by the same half widths: what each class's position is worth;
  result lines buffered  the same faces minus the result's centrelines buffered by the same half
              widths (round, no curb corners): the result's centrelines with the truth's construction,
              and with other half widths per class (WIDTHS);
  land cells  the grid's land cells of its raw block (what the cells alone give);
  offset      mean distance (cells) from the truth centrelines within 1.5 cells of the block, every
              quarter cell, to the result's centrelines.

It also prints the pavement width per road class: the area of the union of the result's pavement /
the length of its centrelines, against the truth's surfaces / centreline length (both count the
overlap at intersections once).

usage: block_edge_frontier.py <grid dir with landuse.tif and truth.gpkg> <result.gpkg>
"""
import sys

import numpy as np
from osgeo import gdal, ogr
from scipy import ndimage
from shapely import wkb
from shapely.geometry import box
from shapely.ops import polygonize, unary_union

GROW = (-0.25, -0.1, 0.1, 0.25, 0.5)
# (secondary, primary) half widths in cells for the per-class sweep of "result lines buffered"
WIDTHS = ((0.5, 1.0), (0.4, 1.0), (0.6, 1.0), (0.5, 0.8), (0.5, 0.9), (0.5, 1.1), (0.5, 1.2), (0.4, 0.8))
gdal.PushErrorHandler("CPLQuietErrorHandler")
grid, result = sys.argv[1:3]
ds = gdal.Open(f"{grid}/landuse.tif")
codes = ds.ReadAsArray()
gt = ds.GetGeoTransform()
cs = abs(gt[1])
land = ~np.isin(codes, [1, 2, 3])


def layer(path, name, where=None):
    src = ogr.Open(path)
    lyr = src.GetLayerByName(name)
    if where:
        lyr.SetAttributeFilter(where)
    return [(wkb.loads(bytes(f.GetGeometryRef().ExportToWkb())), f.items()) for f in lyr]


# Land share with 4 x 4 samples per cell, as evaluate's featureLandShare.
sub = 4
fine = np.repeat(np.repeat(land, sub, 0), sub, 1)
mem = gdal.GetDriverByName("MEM")


def land_share(poly):
    r = mem.Create("", fine.shape[1], fine.shape[0], 1, gdal.GDT_Byte)
    r.SetGeoTransform((gt[0], gt[1] / sub, 0, gt[3], 0, gt[5] / sub))
    src = ogr.GetDriverByName("Memory").CreateDataSource("")
    lyr = src.CreateLayer("p")
    f = ogr.Feature(lyr.GetLayerDefn())
    f.SetGeometry(ogr.CreateGeometryFromWkb(poly.wkb))
    lyr.CreateFeature(f)
    gdal.RasterizeLayer(r, [1], lyr, burn_values=[1])
    del lyr, src
    m = r.ReadAsArray().astype(bool)
    return fine[m].mean() if m.any() else 0.0


def best_iou(t, polys):
    best = 0.0
    for p in polys:
        if not p.intersects(t):
            continue
        inter = p.intersection(t).area
        best = max(best, inter / (p.area + t.area - inter))
    return best


truth_roads = layer(f"{grid}/truth.gpkg", "roads")
res_roads = layer(result, "roads")
half = {"primary": 1.0, "secondary": 0.5}
surface = unary_union([g.buffer(half[a["road_class"]] * cs, 8) for g, a in truth_roads if a["road_class"] in half])
for name in ("secondary", "primary"):
    tl = [g for g, a in truth_roads if a["road_class"] == name]
    rl = [g for g, a in res_roads if a["road_class"] == name]
    pav = unary_union([g for g, a in layer(result, "pavement") if a["road_class"] == name])
    ts = unary_union([g.buffer(half[name] * cs, 8) for g in tl])
    tlen, rlen = sum(g.length for g in tl), sum(g.length for g in rl)
    if not tlen or not rlen:
        continue
    print(f"{name}: pavement {pav.area / rlen / cs:.3f} cells wide ({pav.area:.0f} m2 / {rlen:.0f} m), "
          f"truth surfaces {ts.area / tlen / cs:.3f} ({ts.area:.0f} m2 / {tlen:.0f} m), nominal {2 * half[name]}")

res_blocks = [g for g, a in layer(result, "blocks")]
h, w = codes.shape
frame = box(gt[0], gt[3] + h * gt[5], gt[0] + w * gt[1], gt[3])
faces = list(polygonize(unary_union([g for g, a in res_roads] + [frame.exterior])))
raw, _ = ndimage.label(land)
r = mem.Create("", w, h, 1, gdal.GDT_Int32)
r.SetGeoTransform(gt)
tsrc = ogr.Open(f"{grid}/truth.gpkg")
gdal.RasterizeLayer(r, [1], tsrc.GetLayerByName("blocks"), options=["ATTRIBUTE=block_id"])
tb = r.ReadAsArray()

print("block\tcells\tresult\t" + "\t".join(f"grown {d:+g}" for d in GROW) + "\tresult lines buffered\ttruth edges\tland cells\toffset")
rows = []
res_lines = unary_union([g for g, a in res_roads if a["road_class"] in half])
matched = matchable = edges_matched = own_matched = 0
res_surfaces = [unary_union([g.buffer((sw if a["road_class"] == "secondary" else pw) * cs, 8)
                             for g, a in res_roads if a["road_class"] in half]) for sw, pw in WIDTHS]
res_surface = res_surfaces[0]


def class_surface(roads, name):
    return unary_union([g.buffer(half[name] * cs, 8) for g, a in roads if a["road_class"] == name])


# one class's edges on the truth's surfaces, the other's on the result's lines (buffered 0.5 / 1 cell)
mixed_surfaces = {"secondary": class_surface(truth_roads, "secondary").union(class_surface(res_roads, "primary")),
                  "primary": class_surface(res_roads, "secondary").union(class_surface(truth_roads, "primary"))}
mixed_matched = dict.fromkeys(mixed_surfaces, 0)
width_matched = [0] * len(WIDTHS)
grown_matched = [0] * len(GROW)
matched_offsets = []
for t, a in layer(f"{grid}/truth.gpkg", "blocks"):
    if a.get("kind") == "external" or t.area < 4 * cs * cs or land_share(t) < 0.7:
        continue
    matchable += 1
    iou = best_iou(t, res_blocks)
    fs = [f for f in faces if f.intersects(t)]
    edges = best_iou(t, [f.difference(surface) for f in fs])
    own = best_iou(t, [f.difference(res_surface) for f in fs])
    edges_matched += edges >= 0.7
    for name, surf in mixed_surfaces.items():
        mixed_matched[name] += best_iou(t, [f.difference(surf) for f in fs]) >= 0.7
    own_matched += own >= 0.7
    for k, surf in enumerate(res_surfaces):
        width_matched[k] += best_iou(t, [f.difference(surf) for f in fs]) >= 0.7
    grown = [best_iou(t, [b.buffer(d * cs, join_style=2) for b in res_blocks if b.distance(t) < cs]) for d in GROW]
    for k in range(len(GROW)):
        grown_matched[k] += grown[k] >= 0.7
    # centreline offset: truth centrelines within 1.5 cells of the block, sampled every quarter cell,
    # their mean distance to the result's centrelines (cells)
    near = t.buffer(1.5 * cs)
    pts = []
    for g, _ in truth_roads:
        if g.intersects(near):
            piece = g.intersection(near)
            for part in getattr(piece, "geoms", [piece]):
                if part.length > 0:
                    pts += [part.interpolate(x) for x in np.arange(0, part.length, cs / 4)]
    off = np.mean([res_lines.distance(p) for p in pts]) / cs if pts else float("nan")
    if iou >= 0.7:
        matched += 1
        matched_offsets.append(off)
        continue
    cells = tb == a["block_id"]
    comp = np.bincount(raw[cells & land]).argmax() if (cells & land).any() else 0
    ys, xs = np.nonzero(raw == comp)
    cellpolys = unary_union([box(gt[0] + x * cs, gt[3] - (y + 1) * cs, gt[0] + (x + 1) * cs, gt[3] - y * cs)
                             for y, x in zip(ys, xs)]) if comp else None
    lc = best_iou(t, [cellpolys]) if cellpolys is not None else 0.0
    rows.append((a["block_id"], t.area / cs / cs, iou, grown, edges, lc, off))
    print(f"{a['block_id']}\t{t.area / cs / cs:.0f}\t{iou:.3f}\t" + "\t".join(f"{g:.3f}" for g in grown) +
          f"\t{own:.3f}\t{edges:.3f}\t{lc:.3f}\t{off:.2f}")
print(f"matched {matched} of {matchable} matchable; centreline offset median {np.median(matched_offsets):.2f} "
      f"cells on the matched, {np.median([r[-1] for r in rows]) if rows else float('nan'):.2f} on the unmatched")
for k, d in enumerate(GROW):
    print(f"grown {d:+g}: {grown_matched[k]} of {matchable} matched ({sum(r[3][k] >= 0.7 for r in rows)} "
          f"of the unmatched)")
print(f"result lines buffered: {own_matched} of {matchable}; truth edges: {edges_matched} of {matchable}")
print(f"truth edges for secondaries only: {mixed_matched['secondary']} of {matchable}; "
      f"for primaries only: {mixed_matched['primary']} of {matchable}")
for (sw, pw), n in zip(WIDTHS, width_matched):
    print(f"result lines buffered by {sw:g} / {pw:g} cell (secondary / primary): {n} of {matchable}")
print(f"of the unmatched, matched with truth edges: {sum(r[4] >= 0.7 for r in rows)}; "
      f"as land cells: {sum(r[5] >= 0.7 for r in rows)}")
