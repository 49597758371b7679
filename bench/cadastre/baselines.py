#!/usr/bin/python3
"""What GIS users do by hand with a messy cadastral DXF (issue 17 baselines), scored like urbanvec.

Each method turns linework into polygons three times, as a user would: blocks from the block layer,
parcels from block + lot layers, buildings from all three; then floor labels go to buildings by
point in polygon (first label wins) and heights are 3 + 2.5 (floors - 1).
  plain  1 m greedy vertex clustering (grid), GEOS node + polygonize (QGIS native:polygonize);
  grass  GRASS v.clean tool=snap,break,rmdupl thresh=1.0, boundaries + v.centroids (grass --tmp-location);
  qgis   QGIS native:snapgeometries (tolerance 1, to itself) + native:polygonize (qgis_process, headless).

Usage: baselines.py METHOD DRAWING.dxf OUT.gpkg [--epsg 32628]
Writes layers sub_blocks, parcels, buildings (floors, height) for score.py.
"""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

from osgeo import gdal, ogr, osr

ogr.UseExceptions()
gdal.PushErrorHandler("CPLQuietErrorHandler")
SETS = {"sub_blocks": ("BLOCKS",), "parcels": ("BLOCKS", "PARCELS"), "buildings": ("BLOCKS", "PARCELS", "BUILDINGS")}
ROMAN = {"I": 1, "V": 5, "X": 10}


def floors_of(text):
    above = 0
    for part in text.upper().split("+"):
        if part.startswith("-"):
            continue
        if part.isdigit():
            above += int(part)
        elif part and all(c in ROMAN for c in part):
            v = [ROMAN[c] for c in part]
            above += sum(-a if i + 1 < len(v) and a < v[i + 1] else a for i, a in enumerate(v))
    return above


def read_dxf(path):
    ds = ogr.Open(path)
    lyr = ds.GetLayer(0)
    lines, labels = {}, []
    for f in lyr:
        g = f.GetGeometryRef()
        name = f.GetField("Layer")
        if g is None:
            continue
        if ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbPoint:
            labels.append((g.GetX(), g.GetY(), f.GetField("Text") or ""))
        elif ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbLineString:
            lines.setdefault(name, []).append([g.GetPoint_2D(i) for i in range(g.GetPointCount())])
    return lines, labels


def write_lines(path, lines, srs):
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    lyr = ds.CreateLayer("lines", srs, ogr.wkbLineString)
    for pts in lines:
        f = ogr.Feature(lyr.GetLayerDefn())
        ls = ogr.Geometry(ogr.wkbLineString)
        for p in pts:
            ls.AddPoint_2D(*p)
        f.SetGeometry(ls)
        lyr.CreateFeature(f)
    ds = None


def read_polygons(path, layer=None):
    ds = ogr.Open(path)
    lyr = ds.GetLayerByName(layer) if layer else ds.GetLayer(0)
    out = []
    for f in lyr:
        g = f.GetGeometryRef()
        if g is not None and not g.IsEmpty() and g.GetArea() > 0:
            out.append(g.Clone())
    return out


def plain(lines, work, tol=1.0):
    """Greedy clustering: each vertex joins the first cluster centre within tol (grid), then polygonize."""
    cell = {}
    centres = []

    def rep(p):
        cx, cy = int(math.floor(p[0] / tol)), int(math.floor(p[1] / tol))
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for k in cell.get((cx + i, cy + j), ()):
                    c = centres[k]
                    if math.hypot(c[0] - p[0], c[1] - p[1]) < tol:
                        return c
        centres.append(p)
        cell.setdefault((cx, cy), []).append(len(centres) - 1)
        return p

    clustered = []
    for pts in lines:
        q = [rep(p) for p in pts]
        if len(set(q)) >= 2:
            clustered.append(q)
    src = os.path.join(work, "clustered.gpkg")
    if os.path.exists(src):
        os.remove(src)
    write_lines(src, clustered, None)
    return geos_polygonize(src, work)


def grass(lines, srs_epsg, work):
    src = os.path.join(work, "in.gpkg")
    for p in (src, os.path.join(work, "grass_out.gpkg")):
        if os.path.exists(p):
            os.remove(p)
    write_lines(src, lines, None)
    out = os.path.join(work, "grass_out.gpkg")
    script = os.path.join(work, "run.sh")
    with open(script, "w") as f:
        f.write(f"""set -e
v.in.ogr -o input={src} output=raw --quiet
v.clean input=raw output=clean tool=snap,break,rmdupl threshold=1.0,0,0 --quiet
v.type input=clean output=bnd from_type=line to_type=boundary --quiet
v.centroids input=bnd output=areas --quiet
v.out.ogr input=areas output={out} type=area format=GPKG --quiet
""")
    subprocess.run(["grass", "--tmp-location", f"EPSG:{srs_epsg}", "--exec", "bash", script], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return read_polygons(out)


def qgis(lines, work):
    src = os.path.join(work, "in.gpkg")
    for p in (src, os.path.join(work, "snapped.gpkg")):
        if os.path.exists(p):
            os.remove(p)
    write_lines(src, lines, None)
    snapped = os.path.join(work, "snapped.gpkg")
    out = os.path.join(work, "poly.gpkg")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    subprocess.run(["qgis_process.bin", "run", "native:snapgeometries", f"--INPUT={src}", f"--REFERENCE_LAYER={src}",
                    "--TOLERANCE=1", "--BEHAVIOR=0", f"--OUTPUT={snapped}"], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return geos_polygonize(snapped, work)


def geos_polygonize(lines_path, work):
    """GEOS polygonize through QGIS (native:polygonize nodes the lines first)."""
    out = os.path.join(work, "poly.gpkg")
    if os.path.exists(out):
        os.remove(out)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    subprocess.run(["qgis_process.bin", "run", "native:polygonize", f"--INPUT={lines_path}", "--KEEP_FIELDS=false",
                    f"--OUTPUT={out}"], check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    polys = []
    for g in read_polygons(out):
        if ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbMultiPolygon:
            polys += [g.GetGeometryRef(i).Clone() for i in range(g.GetGeometryCount())]
        else:
            polys.append(g)
    return polys


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    method, dxf, out = sys.argv[1:4]
    epsg = 32628
    if "--epsg" in sys.argv:
        epsg = int(sys.argv[sys.argv.index("--epsg") + 1])
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    lines, labels = read_dxf(dxf)
    if os.path.exists(out):
        os.remove(out)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(out)
    work = tempfile.mkdtemp(prefix="cad_baseline_")
    try:
        for name, layers in SETS.items():
            soup = [l for n in layers for l in lines.get(n, [])]
            if method == "plain":
                polys = plain(soup, work)
            elif method == "grass":
                polys = grass(soup, epsg, work)
            elif method == "qgis":
                polys = qgis(soup, work)
            else:
                sys.exit("unknown method " + method)
            lyr = ds.CreateLayer(name, srs, ogr.wkbPolygon)
            lyr.CreateField(ogr.FieldDefn("floors", ogr.OFTInteger))
            lyr.CreateField(ogr.FieldDefn("height", ogr.OFTReal))
            for g in polys:
                floors = 0
                if name == "buildings":
                    env = g.GetEnvelope()
                    for x, y, t in labels:
                        if env[0] <= x <= env[1] and env[2] <= y <= env[3]:
                            pt = ogr.Geometry(ogr.wkbPoint)
                            pt.AddPoint_2D(x, y)
                            if g.Contains(pt):
                                floors = floors_of(t)
                                break
                f = ogr.Feature(lyr.GetLayerDefn())
                f.SetField("floors", floors)
                f.SetField("height", 0.0 if floors == 0 else 3.0 + 2.5 * (floors - 1))
                f.SetGeometry(g)
                lyr.CreateFeature(f)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    ds = None


if __name__ == "__main__":
    main()
