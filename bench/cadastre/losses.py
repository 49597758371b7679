#!/usr/bin/python3
"""Why building parts are missed (issue 17): classifies every truth building part that no output element
matches at IoU >= 0.9, and computes the ceiling of any planar partition of the truth's own lines.

  losses.py OUTPUT.gpkg TRUTH.gpkg [--json] [--parts]

Planar ceiling: the faces of the arrangement of every truth boundary (blocks, parcels, building parts)
are what a perfect structuring of a perfect drawing gives; a truth part no face matches at IoU >= 0.9
cannot be output by any planar partition (overlapping or split parts).

Classes of a missed part t, with o the output element of best IoU:
  planar-impossible  no face of the truth arrangement matches t (overlaps another part, split by lines);
  no output          no output element overlaps t;
  placement          o's vertices moved to their nearest truth vertex (within 0.8 m) match t: the
                     topology is right, the vertices' positions put the IoU under 0.9
                     (split by area: under 5 m2 / 5 m2 and over);
  missing edge       (topology) snapped o covers t and more (>= 1.1 times its area): t merged with a
                     neighbour;
  extra edge         (topology) snapped o lies inside t and is smaller (<= 0.9 times): t cut in pieces;
  wrong circuit      (topology) anything else (o partly inside, partly outside t).
Per missed part also: `fine`, true when t has two vertices closer than 0.75 m (the default Collapsing
Threshold) or a mean width 2 area / perimeter under 0.75 m (detail below the noise of the drawing), and
`cover`, the share of t covered by any output element (under 1: pieces dropped as slivers).
"""
import json
import sys
import warnings

import numpy as np
from osgeo import ogr
from scipy.spatial import cKDTree
from shapely import wkb
from shapely.geometry import Polygon
from shapely.ops import polygonize, unary_union
from shapely.strtree import STRtree

warnings.filterwarnings("ignore")
ogr.UseExceptions()

SNAP = 0.8      # m: an output vertex within this of a truth vertex is moved onto it
FINE = 0.75     # m: the default Collapsing Threshold
SMALL = 5.0     # m2


def load(path, layer):
    ds = ogr.Open(path)
    out = []
    for f in ds.GetLayerByName(layer):
        g = f.GetGeometryRef()
        if g is None or g.IsEmpty():
            continue
        s = wkb.loads(bytes(g.ExportToWkb()))
        out.append(s if s.is_valid else s.buffer(0))
    return out


def iou(a, b):
    i = a.intersection(b).area
    u = a.area + b.area - i
    return i / u if u > 0 else 0.0


def parts_of(g):
    return [g] if g.geom_type == "Polygon" else [p for p in getattr(g, "geoms", []) if p.geom_type == "Polygon"]


class Index:
    def __init__(self, geoms):
        self.geoms = geoms
        self.tree = STRtree(geoms)
        self.ids = {id(g): k for k, g in enumerate(geoms)}

    def near(self, g):
        hits = self.tree.query(g)
        return sorted(int(h) if isinstance(h, (int, np.integer)) else self.ids[id(h)] for h in hits)

    def best(self, g):
        b, bj = 0.0, -1
        for j in self.near(g):
            v = iou(g, self.geoms[j])
            if v > b:
                b, bj = v, j
        return b, bj


def classify(output, truth_path):
    truth = load(truth_path, "building_parts")
    lines = unary_union([g.boundary for layer in ("building_parts", "parcels", "blocks")
                         for g in load(truth_path, layer)])
    faces = Index(list(polygonize(lines)))
    verts = []
    for layer in ("building_parts", "parcels", "blocks"):
        for g in load(truth_path, layer):
            for p in parts_of(g):
                for r in [p.exterior] + list(p.interiors):
                    verts += list(r.coords)
    verts = np.unique(np.round(np.array(verts), 6), axis=0)
    vtree = cKDTree(verts)
    out = Index(load(output, "buildings"))

    def snapped(g):
        def ring(coords):
            a = np.array(coords)
            d, k = vtree.query(a)
            return np.where((d < SNAP)[:, None], verts[k], a)
        polys = []
        for p in parts_of(g):
            q = Polygon(ring(p.exterior.coords), [ring(h.coords) for h in p.interiors])
            polys.append(q if q.is_valid else q.buffer(0))
        return unary_union(polys)

    planar_ok, rows = 0, []
    for i, t in enumerate(truth):
        if faces.best(t)[0] >= 0.9:
            planar_ok += 1
            planar = True
        else:
            planar = False
        b, j = out.best(t)
        if b >= 0.9:
            continue
        near = out.near(t)
        cover = unary_union([out.geoms[k] for k in near]).intersection(t).area / t.area if near else 0.0
        ring = np.array(max(parts_of(t), key=lambda p: p.area).exterior.coords)[:-1]
        dm = np.sqrt(((ring[:, None] - ring[None]) ** 2).sum(-1))
        np.fill_diagonal(dm, np.inf)
        fine = bool(dm.min() < FINE or 2 * t.area / t.length < FINE)
        if not planar:
            c = "planar-impossible"
        elif j < 0:
            c = "no output"
        else:
            so = snapped(out.geoms[j])
            inter = t.intersection(so).area
            if iou(t, so) >= 0.9:
                c = "placement, small" if t.area < SMALL else "placement, large"
            elif so.area >= 1.1 * t.area and inter >= 0.9 * t.area:
                c = "missing edge"
            elif so.area <= 0.9 * t.area and inter >= 0.9 * so.area:
                c = "extra edge"
            else:
                c = "wrong circuit"
        rows.append(dict(part=i, cls=c, iou=round(b, 3), area=round(t.area, 2), fine=fine, cover=round(cover, 2)))
    classes = {}
    for r in rows:
        classes[r["cls"]] = classes.get(r["cls"], 0) + 1
    topo = [r for r in rows if r["cls"] in ("missing edge", "extra edge", "wrong circuit", "no output")]
    return dict(truth=len(truth), planar_ceiling=planar_ok / max(1, len(truth)), missed=len(rows),
                classes=classes, topology_fine=sum(r["fine"] for r in topo),
                topology_uncovered=sum(r["cover"] < 0.9 for r in topo), parts=rows)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        sys.exit(__doc__)
    r = classify(*args)
    if "--parts" not in sys.argv:
        r.pop("parts")
    print(json.dumps(r) if "--json" in sys.argv else json.dumps(r, indent=1))


if __name__ == "__main__":
    main()
