#!/usr/bin/python3
"""Scores a structured cadastre against the truth of tests/cadastre/make_cad.py (issue 17).

Per layer: recall = share of truth polygons matched by an output polygon at IoU >= 0.9, precision =
share of output polygons matching a truth polygon at IoU >= 0.9. Layers compared:
  blocks    truth blocks (parcels dissolved by the first 5 characters of the reference, one polygon per
            part) vs the output's sub_blocks: where blocks touch, the drawn block layer makes one
            pre-block whose sub-blocks are the cadastre's blocks (an isolated block is its own sub-block);
  parcels   truth parcels vs output parcels;
  buildings truth building parts vs output buildings; precision over output elements with floors >= 1
            (elements without a label are courtyards/yards, not building parts).
Heights: share of matched building parts whose output height equals 3 + 2.5 (floors - 1) (0 for 0
floors) within 1 cm ("exact"), and the same over all truth parts.

Usage: score.py OUTPUT.gpkg TRUTH.gpkg [--json] [--result-layers blocks=sub_blocks,...]
"""
import json
import sys

from osgeo import gdal, ogr

ogr.UseExceptions()
gdal.PushErrorHandler("CPLQuietErrorHandler")


def surface(g):
    """Area of the polygonal parts of any geometry (intersections may hold lines and points)."""
    t = ogr.GT_Flatten(g.GetGeometryType())
    if t in (ogr.wkbPolygon, ogr.wkbMultiPolygon):
        return g.GetArea()
    if t == ogr.wkbGeometryCollection:
        return sum(surface(g.GetGeometryRef(i)) for i in range(g.GetGeometryCount()))
    return 0.0


def polygons(path, layer, where=None):
    ds = ogr.Open(path)
    lyr = ds.GetLayerByName(layer)
    if lyr is None:
        return []
    if where:
        lyr.SetAttributeFilter(where)
    out = []
    for f in lyr:
        g = f.GetGeometryRef()
        if g is None or g.IsEmpty():
            continue
        g = g.Clone()
        if not g.IsValid():
            g = g.MakeValid()
        attrs = {f.GetFieldDefnRef(i).GetName(): f.GetField(i) for i in range(f.GetFieldCount())}
        out.append((g, g.GetEnvelope(), g.GetArea(), attrs))
    return out


def match(truth, result, threshold=0.9):
    """best IoU per truth and per result polygon (greedy-free: each pair judged on its own)."""
    # bucket results by grid for speed
    cell = 50.0
    grid = {}
    for j, (g, e, a, _) in enumerate(result):
        for x in range(int(e[0] // cell), int(e[1] // cell) + 1):
            for y in range(int(e[2] // cell), int(e[3] // cell) + 1):
                grid.setdefault((x, y), set()).add(j)
    best_t = [0.0] * len(truth)
    best_t_j = [-1] * len(truth)
    best_r = [0.0] * len(result)
    for i, (g, e, a, _) in enumerate(truth):
        cand = set()
        for x in range(int(e[0] // cell), int(e[1] // cell) + 1):
            for y in range(int(e[2] // cell), int(e[3] // cell) + 1):
                cand |= grid.get((x, y), set())
        for j in sorted(cand):
            rg, re, ra, _ = result[j]
            if re[0] > e[1] or re[1] < e[0] or re[2] > e[3] or re[3] < e[2]:
                continue
            inter = g.Intersection(rg)
            if inter is None or inter.IsEmpty():
                continue
            ia = surface(inter)
            iou = ia / (a + ra - ia) if a + ra - ia > 0 else 0.0
            if iou > best_t[i]:
                best_t[i], best_t_j[i] = iou, j
            best_r[j] = max(best_r[j], iou)
    return best_t, best_t_j, best_r


def score(output, truth_path, layers=None):
    layers = layers or {"blocks": "sub_blocks", "parcels": "parcels", "buildings": "buildings"}
    res = {}
    for name, truth_layer in (("blocks", "blocks"), ("parcels", "parcels"), ("buildings", "building_parts")):
        truth = polygons(truth_path, truth_layer)
        result = polygons(output, layers[name])
        bt, btj, br = match(truth, result)
        recall = sum(1 for v in bt if v >= 0.9) / max(1, len(truth))
        if name == "buildings":
            claimed = [j for j, r in enumerate(result) if (r[3].get("floors") or 0) >= 1]
            precision = sum(1 for j in claimed if br[j] >= 0.9) / max(1, len(claimed))
            matched = [i for i, v in enumerate(bt) if v >= 0.9]
            exact = sum(1 for i in matched
                        if abs((result[btj[i]][3].get("height") or 0.0) - truth[i][3]["height"]) < 0.01)
            res["heights_exact_matched"] = exact / max(1, len(matched))
            res["heights_exact_all"] = exact / max(1, len(truth))
        else:
            precision = sum(1 for v in br if v >= 0.9) / max(1, len(result))
        res[name] = {"recall": recall, "precision": precision, "truth": len(truth), "output": len(result)}
    return res


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        sys.exit(__doc__)
    layers = None
    for a in sys.argv[1:]:
        if a.startswith("--result-layers="):
            layers = {"blocks": "sub_blocks", "parcels": "parcels", "buildings": "buildings"}
            for kv in a.split("=", 1)[1].split(","):
                k, v = kv.split("=")
                layers[k] = v
    r = score(args[0], args[1], layers)
    if "--json" in sys.argv:
        print(json.dumps(r))
        return
    for k in ("blocks", "parcels", "buildings"):
        print("%-9s recall %.3f precision %.3f (truth %d, output %d)" % (
            k, r[k]["recall"], r[k]["precision"], r[k]["truth"], r[k]["output"]))
    print("heights   exact %.3f of matched parts, %.3f of all parts" % (r["heights_exact_matched"], r["heights_exact_all"]))


if __name__ == "__main__":
    main()
