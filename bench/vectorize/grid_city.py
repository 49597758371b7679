#!/usr/bin/env python3
"""Synthetic grid-plan city (issue 20): a street grid turned by <angle> degrees, with a primary main
street, a primary diagonal avenue crossing the grid at about 27 degrees, and a few streets cut short so
they end in T-junctions, written as vectors that `urbanvec gridify` rasterises (the truth is exact).

usage: grid_city.py <output.gpkg> <angle degrees> [half size m = 260] [street spacing m = 80]

Layers (EPSG:32633, centred at 460004, 5550004): `roads` (LineString, highway = residential or
primary), `landuse` (one residential polygon around the grid).
"""
import math
import sys

from osgeo import ogr, osr

out, angle = sys.argv[1], float(sys.argv[2])
half = float(sys.argv[3]) if len(sys.argv) > 3 else 260.0
spacing = float(sys.argv[4]) if len(sys.argv) > 4 else 80.0
# Centred half a cell of 8 m off the 8 m lattice, so streets at 0 degrees run along cell centres.
X0, Y0 = 460004.0, 5550004.0
c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))


def world(u, v):
    return X0 + u * c - v * s, Y0 + u * s + v * c


roads = []  # (highway, [(u, v), ...]) in the grid's own frame
k_max = int(half // spacing)
ticks = [k * spacing for k in range(-k_max, k_max + 1)]
# Streets cut short (T-junctions): the street along u at v = ticks[1] stops at u = 0, the street
# along v at u = ticks[-2] stops at v = ticks[1].
for v in ticks:
    if v == 0:
        roads.append(("primary", [(-half, v), (half, v)]))  # main street
    elif v == ticks[1]:
        roads.append(("residential", [(-half, v), (0.0, v)]))
    else:
        roads.append(("residential", [(-half, v), (half, v)]))
for u in ticks:
    if u == ticks[-2]:
        roads.append(("residential", [(u, -half), (u, ticks[1])]))
    else:
        roads.append(("residential", [(u, -half), (u, half)]))
# The diagonal avenue: v = u / 2 + spacing / 3, clipped to the square.
u0, u1 = -half, half
roads.append(("primary", [(u0, u0 / 2 + spacing / 3), (u1, u1 / 2 + spacing / 3)]))

srs = osr.SpatialReference()
srs.ImportFromEPSG(32633)
drv = ogr.GetDriverByName("GPKG")
ds = drv.CreateDataSource(out)
layer = ds.CreateLayer("roads", srs, ogr.wkbLineString)
layer.CreateField(ogr.FieldDefn("highway", ogr.OFTString))
for highway, points in roads:
    f = ogr.Feature(layer.GetLayerDefn())
    f.SetField("highway", highway)
    g = ogr.Geometry(ogr.wkbLineString)
    for u, v in points:
        g.AddPoint_2D(*world(u, v))
    f.SetGeometry(g)
    layer.CreateFeature(f)
landuse = ds.CreateLayer("landuse", srs, ogr.wkbPolygon)
landuse.CreateField(ogr.FieldDefn("landuse", ogr.OFTString))
ring = ogr.Geometry(ogr.wkbLinearRing)
m = half + spacing / 2
for u, v in [(-m, -m), (m, -m), (m, m), (-m, m), (-m, -m)]:
    ring.AddPoint_2D(*world(u, v))
poly = ogr.Geometry(ogr.wkbPolygon)
poly.AddGeometry(ring)
f = ogr.Feature(landuse.GetLayerDefn())
f.SetField("landuse", "residential")
f.SetGeometry(poly)
landuse.CreateFeature(f)
ds = None
