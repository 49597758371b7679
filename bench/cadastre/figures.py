#!/usr/bin/python3
"""Figures of docs/cadastre.md from a real run: the raw L2 drawing, the structure, a 3D view of the OBJ.

Usage: figures.py DRAWING.dxf STRUCTURE.gpkg MODEL.obj OUTDIR
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection, PolyCollection
from mpl_toolkits.mplot3d.art3d import Poly3DCollection
from osgeo import ogr

ogr.UseExceptions()


def rings(g):
    t = ogr.GT_Flatten(g.GetGeometryType())
    if t == ogr.wkbPolygon:
        return [g.GetGeometryRef(0).GetPoints()]
    if t == ogr.wkbMultiPolygon:
        return [g.GetGeometryRef(i).GetGeometryRef(0).GetPoints() for i in range(g.GetGeometryCount())]
    return []


def main():
    dxf, gpkg, obj, out = sys.argv[1:5]
    os.makedirs(out, exist_ok=True)
    colours = {"BLOCKS": "#444444", "PARCELS": "#d04040", "BUILDINGS": "#3060c0"}
    segs = {k: [] for k in colours}
    labels = []
    src = ogr.Open(dxf)
    for f in src.GetLayer(0):
        g = f.GetGeometryRef()
        if ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbLineString and f.GetField("Layer") in segs:
            segs[f.GetField("Layer")].append(g.GetPoints())
        elif ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbPoint:
            labels.append((g.GetX(), g.GetY(), f.GetField("Text")))
    fig, ax = plt.subplots(figsize=(9, 7.5))
    for k, c in colours.items():
        ax.add_collection(LineCollection([[p[:2] for p in s] for s in segs[k]], colors=c, linewidths=0.5, label=k))
    for x, y, t in labels:
        ax.text(x, y, t, fontsize=3, color="#208020", ha="center", va="center")
    ax.autoscale()
    ax.set_aspect("equal")
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title("Raw drawing (L2: duplicated, split, jittered segments, over/undershoots) and floor labels")
    ax.set_axis_off()
    fig.savefig(os.path.join(out, "cadastre_raw.png"), dpi=150, bbox_inches="tight")
    plt.close(fig)

    ds = ogr.Open(gpkg)
    fig, ax = plt.subplots(figsize=(9, 7.5))
    cmap = plt.get_cmap("Reds")
    polys, facecol = [], []
    for f in ds.GetLayerByName("buildings"):
        for r in rings(f.GetGeometryRef()):
            polys.append([p[:2] for p in r])
            h = f.GetField("height")
            facecol.append("#f0f0e8" if h == 0 else cmap(0.25 + 0.75 * min(h, 13.0) / 13.0))
    ax.add_collection(PolyCollection(polys, facecolors=facecol, edgecolors="#606060", linewidths=0.2))
    par = [[p[:2] for p in r] for f in ds.GetLayerByName("parcels") for r in rings(f.GetGeometryRef())]
    ax.add_collection(PolyCollection(par, facecolors="none", edgecolors="#d04040", linewidths=0.5))
    blk = [[p[:2] for p in r] for f in ds.GetLayerByName("blocks") for r in rings(f.GetGeometryRef())]
    ax.add_collection(PolyCollection(blk, facecolors="none", edgecolors="black", linewidths=1.2))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title("Structure: blocks (black), parcels (red), building elements by height (0 m = courtyard, pale)")
    fig.savefig(os.path.join(out, "cadastre_structure.png"), dpi=150, bbox_inches="tight")
    plt.close(fig)

    verts, tris = [], []
    for line in open(obj):
        p = line.split()
        if p and p[0] == "v":
            verts.append(tuple(map(float, p[1:4])))
        elif p and p[0] == "f":
            tris.append([verts[int(x.split("/")[0]) - 1] for x in p[1:4]])
    fig = plt.figure(figsize=(10, 7))
    ax = fig.add_subplot(projection="3d")
    shade = []
    for t in tris:
        (ax_, ay, az), (bx, by, bz), (cx, cy, cz) = t
        nz = abs((bx - ax_) * (cy - ay) - (by - ay) * (cx - ax_))
        n = ((by - ay) * (cz - az) - (bz - az) * (cy - ay), (bz - az) * (cx - ax_) - (bx - ax_) * (cz - az), nz)
        ln = max(1e-9, sum(v * v for v in n) ** 0.5)
        light = 0.35 + 0.65 * abs(0.3 * n[0] + 0.5 * n[1] + 0.8 * n[2]) / ln
        shade.append((0.85 * light, 0.55 * light, 0.45 * light))
    ax.add_collection3d(Poly3DCollection(tris, facecolors=shade, edgecolors="none"))
    xs, ys = [v[0] for v in verts], [v[1] for v in verts]
    ax.set_xlim(min(xs), max(xs))
    ax.set_ylim(min(ys), max(ys))
    ax.set_zlim(0, (max(xs) - min(xs)) / 4)  # heights exaggerated 4 times
    ax.view_init(elev=35, azim=-60)
    ax.set_axis_off()
    ax.set_title("LoD1 model (OBJ prisms, heights 3 + 2.5 (floors - 1) m, drawn 4x)")
    fig.savefig(os.path.join(out, "cadastre_3d.png"), dpi=150, bbox_inches="tight")
    plt.close(fig)


if __name__ == "__main__":
    main()
