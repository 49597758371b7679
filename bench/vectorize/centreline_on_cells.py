#!/usr/bin/env python3
"""How far the result's centrelines are from the truth's where the truth lies on its own road cells
(issue 20, "Monaco's matchable blocks: lines on their cells"). The truth's centrelines are sampled every
quarter cell; for the samples that lie on a road cell of their own class, the distance (in cells) to the
nearest result centreline of the same class: the share farther than half a cell, the mean and the p95.
A line kept on its cells gives a small share (the unsmoothed cell-centre graph of Monaco: 2.5 %
secondary); smoothing that moves lines off their cells raises it (defaults: 15.5 %).

usage: centreline_on_cells.py <grid dir with landuse.tif and truth.gpkg> <result.gpkg>
"""
import sys

import numpy as np
from osgeo import gdal, ogr
from shapely import wkb
from shapely.geometry import Point
from shapely.strtree import STRtree

CODES = {"secondary": 2, "primary": 3}  # core/landuse.hpp


def lines(path, road_class):
    source = ogr.Open(path)  # kept open while its layer is read
    return [wkb.loads(bytes(f.GetGeometryRef().ExportToWkb())) for f in source.GetLayer("roads")
            if f.GetField("road_class") == road_class]


grid, result = sys.argv[1], sys.argv[2]
ds = gdal.Open(f"{grid}/landuse.tif")
codes = ds.ReadAsArray()
gt = ds.GetGeoTransform()
cell = abs(gt[1])
for road_class, code in CODES.items():
    result_lines = lines(result, road_class)
    if not result_lines:
        print(f"{road_class}: no result roads")
        continue
    tree = STRtree(result_lines)
    samples = []
    for g in lines(f"{grid}/truth.gpkg", road_class):
        step = cell / 4
        samples += [g.interpolate(i * step) for i in range(int(g.length / step) + 1)]
    xy = np.array([[p.x, p.y] for p in samples])
    col = np.floor((xy[:, 0] - gt[0]) / gt[1]).astype(int)
    row = np.floor((xy[:, 1] - gt[3]) / gt[5]).astype(int)
    inside = (col >= 0) & (row >= 0) & (col < codes.shape[1]) & (row < codes.shape[0])
    on = np.zeros(len(xy), bool)
    on[inside] = codes[row[inside], col[inside]] == code
    dist = np.array([tree.nearest(Point(x, y)).distance(Point(x, y)) for x, y in xy[on]]) / cell
    print(f"{road_class}: {on.sum()} truth samples on their cells, {100 * (dist > 0.5).mean():.1f} % "
          f"more than 0.5 cell from the result, mean {dist.mean():.3f}, p95 {np.percentile(dist, 95):.3f} cell")
