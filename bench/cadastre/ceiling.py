#!/usr/bin/python3
"""Ceiling of building-part recall for vertex averaging on a make_cad.py drawing (issue 17).

Each truth vertex (of blocks, parcels and building parts) is moved to the mean of the drawing's
segment ends that lie nearer to it than to any other truth vertex and within 0.9 m — the perfect
clustering of every drawn copy of the vertex, with the topology of the truth — and the building parts so
moved are scored against the truth at IoU >= 0.9. No method that places a vertex at the mean of its
copies can do better; the spread is set by the generator's jitter alone.

Usage: ceiling.py DRAWING.dxf TRUTH.gpkg   (prints the recall)
"""
import os
import sys

import numpy as np
from osgeo import ogr
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from score import polygons, surface  # noqa: E402

ogr.UseExceptions()


def ring_points(path, layers):
    ds = ogr.Open(path)
    out = []
    for layer in layers:
        for f in ds.GetLayerByName(layer):
            g = f.GetGeometryRef()
            for i in range(g.GetGeometryCount()):
                r = g.GetGeometryRef(i)
                out += [r.GetPoint_2D(k) for k in range(r.GetPointCount())]
    return np.unique(np.array(out), axis=0)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    ends = []
    drawing = ogr.Open(sys.argv[1])
    for f in drawing.GetLayer(0):
        g = f.GetGeometryRef()
        if g is not None and ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbLineString:
            ends += [g.GetPoint_2D(0), g.GetPoint_2D(g.GetPointCount() - 1)]
    ends = np.array(ends)
    truth_vertices = ring_points(sys.argv[2], ["building_parts", "parcels", "blocks"])
    dist, nearest = cKDTree(truth_vertices).query(ends)
    position = {}
    for t in range(len(truth_vertices)):
        copies = ends[(nearest == t) & (dist < 0.9)]
        if len(copies):
            position[tuple(truth_vertices[t])] = copies.mean(axis=0)
    parts = polygons(sys.argv[2], "building_parts")
    hit = 0
    for g, _, area, _ in parts:
        moved = g.Clone()
        for i in range(moved.GetGeometryCount()):
            ring = moved.GetGeometryRef(i)
            for k in range(ring.GetPointCount()):
                p = ring.GetPoint_2D(k)
                if p in position:
                    ring.SetPoint_2D(k, *position[p])
        if not moved.IsValid():
            moved = moved.MakeValid()
        inter = surface(g.Intersection(moved))
        hit += inter / (area + moved.GetArea() - inter) >= 0.9
    print("%.3f" % (hit / max(1, len(parts))))


if __name__ == "__main__":
    main()
