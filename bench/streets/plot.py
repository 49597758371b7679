#!/usr/bin/python3
"""Renders a streets run for docs/streets.md: the field's major direction as short ticks (from the
-field raster), water, the real roads that shaped the field, and the generated streets by class.
usage: plot.py OUT.png STREETS.gpkg [--field F.tif] [--water W.gpkg] [--roads R.gpkg] [--title T]"""
import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from osgeo import gdal, ogr  # noqa: E402


def lines_of(path, layer=None, where=None):
    ds = ogr.Open(path)
    lyr = ds.GetLayerByName(layer) if layer else ds.GetLayer(0)
    if where:
        lyr.SetAttributeFilter(where)
    for f in lyr:
        g = f.GetGeometryRef()
        if g is None:
            continue
        yield f, g


def draw_geom(ax, g, **kw):
    t = g.GetGeometryType() & 0xFF
    if t in (2,):
        pts = g.GetPoints()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], **kw)
    elif t in (3, 5, 6, 7):
        for i in range(g.GetGeometryCount()):
            draw_geom(ax, g.GetGeometryRef(i), **kw)
    elif t == 101 or t == 1:
        pass


def main():
    a = argparse.ArgumentParser()
    a.add_argument("out")
    a.add_argument("streets")
    a.add_argument("--field")
    a.add_argument("--water")
    a.add_argument("--roads")
    a.add_argument("--boundary")
    a.add_argument("--title", default="")
    o = a.parse_args()
    fig, ax = plt.subplots(figsize=(8, 8), dpi=110)
    if o.field:
        ds = gdal.Open(o.field)
        gt = ds.GetGeoTransform()
        ang = ds.GetRasterBand(1).ReadAsArray()
        h, w = ang.shape
        step = max(1, int(max(w, h) / 45))
        c = gt[1] * step * 0.4
        for j in range(0, h, step):
            for i in range(0, w, step):
                x = gt[0] + (i + 0.5) * gt[1]
                y = gt[3] + (j + 0.5) * gt[5]
                t = math.radians(float(ang[j, i]))
                ax.plot([x - c * math.cos(t), x + c * math.cos(t)], [y - c * math.sin(t), y + c * math.sin(t)],
                        color="#9ecae1", lw=0.6)
    if o.water:
        for _, g in lines_of(o.water):
            gb = g.GetBoundary()
            draw_geom(ax, gb, color="#3182bd", lw=0.8)
    if o.boundary:
        for _, g in lines_of(o.boundary):
            draw_geom(ax, g.GetBoundary(), color="black", lw=0.8, ls="--")
    for f, g in lines_of(o.streets, "streets"):
        major = f.GetField("class") == "major"
        draw_geom(ax, g, color="#d95f0e" if major else "#444444", lw=1.4 if major else 0.6)
    if o.roads:
        for _, g in lines_of(o.roads):
            draw_geom(ax, g, color="#31a354", lw=0.8, alpha=0.7)
    ax.set_aspect("equal")
    ax.set_title(o.title)
    ax.tick_params(labelsize=7)
    fig.tight_layout()
    fig.savefig(o.out)


main()
