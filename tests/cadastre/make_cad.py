#!/usr/bin/python3
"""Builds messy cadastral CAD drawings (DXF) and their truth from real cadastre polygons (issue 17).

Input: the Spanish cadastre sample (parcel.gpkg, cons.gpkg in sample_data/sources/catastro). Output:
  <out>.dxf        2-point LINE segments on layers BLOCKS, PARCELS, BUILDINGS and TEXT labels (number of
                   floors in Roman numerals, e.g. III, -I+III, II+TZA) on layer FLOORS;
  <out>_truth.gpkg layers blocks (parcels dissolved by the first 5 characters of the reference, one
                   polygon per part), parcels (one polygon per part), building_parts (floors,
                   floors_below, height = 3.0 + 2.5 (floors - 1), 0 for 0 floors, label).

Defect levels (cumulative, seeded, as issue 17 defines them):
  L0 clean noded linework;
  L1 + 10 % duplicated segments, 20 % split segments, jitter <= 0.05 m (one move per distinct vertex);
  L2 + jitter <= 0.3 m applied separately to each copy of a shared vertex, 15 % of ends over- or
       undershot by 0.1-0.8 m;
  L3 + 3 % of segments copied onto a wrong layer, 10 % partial-overlap duplicates, labels moved <= 1 m.

Usage: make_cad.py [--level L2] [--seed 1] [--bbox xmin ymin xmax ymax] [--data DIR] OUT_PREFIX
"""
import argparse
import math
import os
import random
import sys

from osgeo import ogr, osr

ogr.UseExceptions()

ROMAN = [(10, "X"), (9, "IX"), (5, "V"), (4, "IV"), (1, "I")]


def roman(n):
    s = ""
    for v, r in ROMAN:
        while n >= v:
            s += r
            n -= v
    return s


def label_for(above, below, rng):
    """The cadastre's floor label: -I+III for one floor below and three above; None for 0/0."""
    if above == 0 and below == 0:
        return None
    parts = []
    if below > 0:
        parts.append("-" + roman(below))
    if above > 0:
        parts.append(roman(above))
    text = "+".join(parts)
    # Some labels carry a use suffix (terrace, porch) that does not change the floor count.
    if above > 0 and rng.random() < 0.05:
        text += rng.choice(["+TZA", "+POR"])
    return text


def height_for(floors, first=3.0, upper=2.5):
    return 0.0 if floors <= 0 else first + upper * (floors - 1)


def polygons_of(geom):
    t = ogr.GT_Flatten(geom.GetGeometryType())
    if t == ogr.wkbPolygon:
        return [geom.Clone()]
    if t in (ogr.wkbMultiPolygon, ogr.wkbGeometryCollection):
        out = []
        for i in range(geom.GetGeometryCount()):
            out += polygons_of(geom.GetGeometryRef(i))
        return out
    return []


def load(data, bbox):
    filt = None
    if bbox:
        filt = ogr.CreateGeometryFromWkt(
            "POLYGON(({0} {1},{2} {1},{2} {3},{0} {3},{0} {1}))".format(*bbox))
    pds = ogr.Open(os.path.join(data, "parcel.gpkg"))
    pl = pds.GetLayer("parcel")
    srs = pl.GetSpatialRef().Clone()
    parcels, groups = [], {}
    for f in pl:
        g = f.GetGeometryRef()
        if filt and not g.Centroid().Within(filt):
            continue
        ref = f.GetField("localId")
        for p in polygons_of(g):
            parcels.append((ref, p))
        groups.setdefault(ref[:5], []).append(g.Clone())
    blocks = []
    for key in sorted(groups):
        m = ogr.Geometry(ogr.wkbMultiPolygon)
        for g in groups[key]:
            for p in polygons_of(g):
                m.AddGeometry(p)
        for p in polygons_of(m.UnionCascaded()):
            blocks.append((key, p))
    cds = ogr.Open(os.path.join(data, "cons.gpkg"))
    cl = cds.GetLayer("cons")
    parts, seen = [], set()
    for f in cl:
        lid = f.GetField("localId") or ""
        if "_part" not in lid or lid in seen:
            continue
        g = f.GetGeometryRef()
        if filt and not g.Centroid().Within(filt):
            continue
        seen.add(lid)
        above = f.GetField("numberOfFloorsAboveGround") or 0
        below = f.GetField("numberOfFloorsBelowGround") or 0
        for p in polygons_of(g):
            parts.append((lid, above, below, p))
    return srs, blocks, parcels, parts


def noded_segments(polys):
    """The polygons' boundaries noded and dissolved (GEOS union), as 2-point segments."""
    m = ogr.Geometry(ogr.wkbMultiLineString)
    for p in polys:
        for i in range(p.GetGeometryCount()):
            ring = p.GetGeometryRef(i)
            ls = ogr.Geometry(ogr.wkbLineString)
            for k in range(ring.GetPointCount()):
                ls.AddPoint_2D(*ring.GetPoint_2D(k))
            m.AddGeometry(ls)
    u = m.Union(ogr.CreateGeometryFromWkt("MULTILINESTRING EMPTY"))
    segs, seen = [], set()

    def add(line):
        pts = [line.GetPoint_2D(k) for k in range(line.GetPointCount())]
        for a, b in zip(pts, pts[1:]):
            if a == b:
                continue
            key = (min(a, b), max(a, b))
            if key not in seen:
                seen.add(key)
                segs.append((a, b))

    if ogr.GT_Flatten(u.GetGeometryType()) == ogr.wkbLineString:
        add(u)
    else:
        for i in range(u.GetGeometryCount()):
            add(u.GetGeometryRef(i))
    segs.sort()
    return segs


def disk(rng, r):
    a = rng.uniform(0, 2 * math.pi)
    d = r * math.sqrt(rng.random())
    return d * math.cos(a), d * math.sin(a)


def degrade(layers, labels, level, rng, provenance=None):
    """layers: {name: [(a, b)]}; labels: [(x, y, text)]. Returns degraded copies. With a dict as
    `provenance`, fills it with {name: [(a, b, tag_a, tag_b)]}: what each drawn segment end is a copy
    of, ("v", truth vertex) or ("s", split point), ("p", None) for the ends of partial overlaps."""
    names = sorted(layers)
    tagged = {n: [(a, b, ("v", a), ("v", b)) for a, b in layers[n]] for n in names}
    if level >= 1:
        # 20 % split segments (at a random interior point), then 10 % duplicated.
        for n in names:
            out = []
            for a, b, ta, tb in tagged[n]:
                if rng.random() < 0.20:
                    t = rng.uniform(0.2, 0.8)
                    m = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
                    out += [(a, m, ta, ("s", m)), (m, b, ("s", m), tb)]
                else:
                    out.append((a, b, ta, tb))
            dup = [s for s in out if rng.random() < 0.10]
            tagged[n] = out + [(b, a, tb, ta) if rng.random() < 0.5 else (a, b, ta, tb) for a, b, ta, tb in dup]
        # Jitter <= 0.05 m, one move per distinct vertex (shared vertices stay shared).
        moves = {}
        for n in names:
            for s in tagged[n]:
                for p in s[:2]:
                    if p not in moves:
                        moves[p] = disk(rng, 0.05)
        mv = lambda p: (p[0] + moves[p][0], p[1] + moves[p][1])
        for n in names:
            tagged[n] = [(mv(a), mv(b), ta, tb) for a, b, ta, tb in tagged[n]]
    if level >= 2:
        for n in names:
            out = []
            for a, b, ta, tb in tagged[n]:
                # Separate jitter of each copy of a vertex.
                ja, jb = disk(rng, 0.3), disk(rng, 0.3)
                a = (a[0] + ja[0], a[1] + ja[1])
                b = (b[0] + jb[0], b[1] + jb[1])
                L = math.hypot(b[0] - a[0], b[1] - a[1])
                if L > 0:
                    ux, uy = (b[0] - a[0]) / L, (b[1] - a[1]) / L
                    # 15 % of ends over- (+) or undershot (-) by 0.1-0.8 m along the segment.
                    if rng.random() < 0.15:
                        d = rng.uniform(0.1, 0.8) * rng.choice((-1, 1))
                        d = max(d, -0.45 * L)
                        b = (b[0] + ux * d, b[1] + uy * d)
                    if rng.random() < 0.15:
                        d = rng.uniform(0.1, 0.8) * rng.choice((-1, 1))
                        d = max(d, -0.45 * L)
                        a = (a[0] - ux * d, a[1] - uy * d)
                out.append((a, b, ta, tb))
            tagged[n] = out
    if level >= 3:
        wrong = []
        for n in names:
            for s in tagged[n]:
                if rng.random() < 0.03:
                    wrong.append((rng.choice([m for m in names if m != n]), s))
            extra = []
            for a, b, _, _ in tagged[n]:
                if rng.random() < 0.10:
                    # A copy of a part of the segment (one end shared or neither).
                    t0, t1 = rng.uniform(0.0, 0.5), rng.uniform(0.5, 1.0)
                    p = lambda t: (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
                    extra.append((p(t0), p(t1), ("p", None), ("p", None)))
            tagged[n] = tagged[n] + extra
        for n, s in wrong:
            tagged[n].append(s)
        labels = [(x + disk(rng, 1.0)[0], y + disk(rng, 1.0)[1], t) for x, y, t in labels]
    for n in names:
        rng.shuffle(tagged[n])
    if provenance is not None:
        provenance.update(tagged)
    return {n: [(a, b) for a, b, _, _ in tagged[n]] for n in names}, labels


def write_dxf(path, layers, labels):
    if os.path.exists(path):
        os.remove(path)
    ds = ogr.GetDriverByName("DXF").CreateDataSource(path)
    lyr = ds.CreateLayer("entities", geom_type=ogr.wkbUnknown)
    defn = lyr.GetLayerDefn()
    for name in sorted(layers):
        for a, b in layers[name]:
            f = ogr.Feature(defn)
            f.SetField("Layer", name)
            ls = ogr.Geometry(ogr.wkbLineString)
            ls.AddPoint_2D(*a)
            ls.AddPoint_2D(*b)
            f.SetGeometry(ls)
            lyr.CreateFeature(f)
    for x, y, text in labels:
        f = ogr.Feature(defn)
        f.SetField("Layer", "FLOORS")
        f.SetStyleString('LABEL(f:"Arial",t:"%s",s:1g)' % text)
        pt = ogr.Geometry(ogr.wkbPoint)
        pt.AddPoint_2D(x, y)
        f.SetGeometry(pt)
        lyr.CreateFeature(f)
    ds = None


def write_truth(path, srs, blocks, parcels, parts, labels_by_part):
    if os.path.exists(path):
        os.remove(path)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    bl = ds.CreateLayer("blocks", srs, ogr.wkbPolygon)
    bl.CreateField(ogr.FieldDefn("block", ogr.OFTString))
    for key, p in blocks:
        f = ogr.Feature(bl.GetLayerDefn())
        f.SetField("block", key)
        f.SetGeometry(p)
        bl.CreateFeature(f)
    pl = ds.CreateLayer("parcels", srs, ogr.wkbPolygon)
    pl.CreateField(ogr.FieldDefn("reference", ogr.OFTString))
    for ref, p in parcels:
        f = ogr.Feature(pl.GetLayerDefn())
        f.SetField("reference", ref)
        f.SetGeometry(p)
        pl.CreateFeature(f)
    bp = ds.CreateLayer("building_parts", srs, ogr.wkbPolygon)
    for name, t in (("reference", ogr.OFTString), ("floors", ogr.OFTInteger),
                    ("floors_below", ogr.OFTInteger), ("height", ogr.OFTReal), ("label", ogr.OFTString)):
        bp.CreateField(ogr.FieldDefn(name, t))
    for i, (lid, above, below, p) in enumerate(parts):
        f = ogr.Feature(bp.GetLayerDefn())
        f.SetField("reference", lid)
        f.SetField("floors", above)
        f.SetField("floors_below", below)
        f.SetField("height", height_for(above))
        if labels_by_part[i]:
            f.SetField("label", labels_by_part[i])
        f.SetGeometry(p)
        bp.CreateFeature(f)
    ds = None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="output prefix: writes OUT.dxf and OUT_truth.gpkg")
    ap.add_argument("--level", default="L0", choices=["L0", "L1", "L2", "L3"])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--bbox", type=float, nargs=4, metavar=("XMIN", "YMIN", "XMAX", "YMAX"),
                    help="keep parcels/parts whose centroid is inside (a small extract for tests)")
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "sample_data", "sources", "catastro"),
                    help="folder with parcel.gpkg and cons.gpkg (default: the copy in sample_data/sources/catastro)")
    ap.add_argument("--replicate", type=int, default=1,
                    help="tile the drawing k x k times (offset by its extent + 50 m), for speed benches")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    srs, blocks, parcels, parts = load(args.data, args.bbox)
    if not parcels:
        sys.exit("make_cad.py: no parcel in the extract")
    labels, labels_by_part = [], []
    for lid, above, below, p in parts:
        text = label_for(above, below, rng)
        labels_by_part.append(text)
        if text:
            pt = p.PointOnSurface()
            labels.append((pt.GetX(), pt.GetY(), text))
    layers = {
        "BLOCKS": noded_segments([p for _, p in blocks]),
        "PARCELS": noded_segments([p for _, p in parcels]),
        "BUILDINGS": noded_segments([p for _, _, _, p in parts]),
    }
    level = int(args.level[1])
    if args.replicate > 1:
        xs = [c[0] for s in layers["PARCELS"] for c in s]
        ys = [c[1] for s in layers["PARCELS"] for c in s]
        dx, dy = max(xs) - min(xs) + 50.0, max(ys) - min(ys) + 50.0
        k = args.replicate
        for n in layers:
            layers[n] = [((a[0] + i * dx, a[1] + j * dy), (b[0] + i * dx, b[1] + j * dy))
                         for i in range(k) for j in range(k) for a, b in layers[n]]
        labels = [(x + i * dx, y + j * dy, t) for i in range(k) for j in range(k) for x, y, t in labels]
    layers, labels = degrade(layers, labels, level, rng)
    write_dxf(args.out + ".dxf", layers, labels)
    if args.replicate == 1:
        write_truth(args.out + "_truth.gpkg", srs, blocks, parcels, parts, labels_by_part)
    n = sum(len(v) for v in layers.values())
    print("make_cad: %s level %s seed %d: %d segments (%s), %d labels; truth %d blocks, %d parcels, "
          "%d building parts" % (args.out + ".dxf", args.level, args.seed, n,
                                  ", ".join("%s %d" % (k, len(v)) for k, v in sorted(layers.items())),
                                  len(labels), len(blocks), len(parcels), len(parts)))


if __name__ == "__main__":
    main()
