#!/usr/bin/env python3
"""How far block matching can go: for each truth block (>= 4 cells) the share of its area on land
cells of the land-use grid (codes other than 2 and 3, roads), next to its best IoU with a result block.
A vector block is the land between curbs, close to the union of land cells, so a truth block with
less than 0.7 of its area on land cannot reach IoU 0.7 (docs/vectorize_blocks.md, Known limits).

usage: truth_block_land_share.py <grid dir with landuse.tif and truth.gpkg> <result.gpkg>
"""
import sys

import numpy as np
from osgeo import gdal, ogr

grid_dir, result = sys.argv[1], sys.argv[2]
ds = gdal.Open(f"{grid_dir}/landuse.tif")
codes = ds.ReadAsArray()
gt = ds.GetGeoTransform()
cell = abs(gt[1])
SUB = 4  # truth blocks rasterized at 1/4 cell
mem = gdal.GetDriverByName("MEM").Create("", codes.shape[1] * SUB, codes.shape[0] * SUB, 1, gdal.GDT_Int32)
mem.SetGeoTransform((gt[0], gt[1] / SUB, gt[2] / SUB, gt[3], gt[4] / SUB, gt[5] / SUB))
mem.SetProjection(ds.GetProjection())
truth = ogr.Open(f"{grid_dir}/truth.gpkg")
blocks = truth.GetLayerByName("blocks")
gdal.RasterizeLayer(mem, [1], blocks, options=["ATTRIBUTE=block_id"])
ids = mem.ReadAsArray()
land = np.kron(~np.isin(codes, [2, 3]), np.ones((SUB, SUB), bool))
n = int(ids.max()) + 1
total = np.bincount(ids.ravel(), minlength=n)
on_land = np.bincount(ids.ravel(), weights=land.ravel(), minlength=n)
res = ogr.Open(result)
result_blocks = [f.GetGeometryRef().Clone() for f in res.GetLayerByName("blocks")]
rows = []
for f in blocks:
    shape = f.GetGeometryRef()
    if shape.GetArea() / cell / cell < 4:
        continue
    best = 0.0
    for r in result_blocks:
        if shape.Intersects(r):
            shared = shape.Intersection(r).GetArea()
            best = max(best, shared / (shape.GetArea() + r.GetArea() - shared))
    b = f.GetField("block_id")
    rows.append((best, shape.GetArea() / cell / cell, on_land[b] / max(total[b], 1), f.GetField("kind")))
low_land = [r for r in rows if r[3] != "external" and r[2] < 0.7]
external = [r for r in rows if r[3] == "external"]
print(f"truth blocks >= 4 cells: {len(rows)}; matched (IoU >= 0.7): {sum(r[0] >= 0.7 for r in rows)}")
print(f"internal with < 0.7 of their area on land cells: {len(low_land)}; external: {len(external)}")
print(f"at most {len(rows) - len(low_land) - len(external)} of {len(rows)} can match")
for r in sorted(rows):
    if r[0] < 0.7:
        print("IoU %.2f  area %.1f cells  on land %.2f  %s" % r)
