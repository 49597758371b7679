#!/usr/bin/env python3
"""Road cells against the truth's road surfaces (issue 20, "Monaco's matchable blocks"): per road class,
the area of the grid's road cells and of the union of the truth centrelines buffered by the curb half
widths gridify gives the truth blocks (0.5 cell secondary, 1 cell primary), and their ratio. A ratio
above 1 is road the grid draws wider than the truth's surfaces (4-connected staircases: |cos| + |sin|
cells per cell of length).

usage: road_cell_area.py <grid dir with landuse.tif and truth.gpkg>
"""
import sys

from osgeo import gdal, ogr
from shapely import wkb
from shapely.ops import unary_union

grid = sys.argv[1]
ds = gdal.Open(f"{grid}/landuse.tif")
codes = ds.ReadAsArray()
cell = abs(ds.GetGeoTransform()[1])
truth = ogr.Open(f"{grid}/truth.gpkg")
roads = truth.GetLayerByName("roads")
for name, code, half in (("secondary", 2, 0.5), ("primary", 3, 1.0)):
    roads.SetAttributeFilter(f"road_class = '{name}'")
    lines = [wkb.loads(bytes(f.GetGeometryRef().ExportToWkb())) for f in roads]
    if not lines:
        continue
    surface = unary_union([g.buffer(half * cell, 8) for g in lines]).area
    cells = float((codes == code).sum()) * cell * cell
    print(f"{name}: cells {cells:.0f} m2, truth surfaces {surface:.0f} m2, ratio {cells / surface:.3f}, "
          f"centrelines {sum(g.length for g in lines):.0f} m")
