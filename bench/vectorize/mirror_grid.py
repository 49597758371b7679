#!/usr/bin/python3
"""Builds a large gridded input for `urbanvec vectorize` by mirroring a sample grid into tiles.

Tile (tx, ty) of the output is the source grid flipped left-right when tx is odd and top-bottom when
ty is odd, so every road that reaches an edge of the source continues into the next tile (the cells
on both sides of a tile edge are the same source cells). The mosaic is cut to size x size cells.

Writes landuse.tif (Byte, nodata 255), density.tif (Float32) and parcels.tif (Int32) on the source's
geotransform origin, cell size and CRS, and parcels.csv. Parcel ids stay unique per tile: a source
parcel id p in tile t becomes p + t * max_source_id. The table lists every id of the output raster,
with the land use of its source parcel and, as gridify writes them, cells = its cell count and
population = the sum of density over its cells (so a parcel cut by the mosaic's edge keeps a
consistent row). Deterministic: same source and size, same bytes.

The mosaic carries no metadata, gridify's URBANVEC_ROAD_SOURCE=mapped_streets included, so
`vectorize -road-removals auto` runs the documents' removals on it (paper), as every benchmark
figure before issue 20 did and as a simulator's grid would; time the mapped-streets mode with
`-road-removals none`. (Its mirrored edges are not mapped streets either.)

Usage: mirror_grid.py <source_dir> <size> <out_dir>
"""
import csv
import os
import sys

import numpy as np
from osgeo import gdal

gdal.UseExceptions()


def read(path):
    ds = gdal.Open(path)
    band = ds.GetRasterBand(1)
    return ds, band.ReadAsArray(), band.GetNoDataValue()


def write(path, array, gdal_type, like, nodata=None):
    driver = gdal.GetDriverByName("GTiff")
    rows, cols = array.shape
    ds = driver.Create(path, cols, rows, 1, gdal_type, ["COMPRESS=DEFLATE", "TILED=YES"])
    ds.SetGeoTransform(like.GetGeoTransform())
    ds.SetProjection(like.GetProjection())
    band = ds.GetRasterBand(1)
    if nodata is not None:
        band.SetNoDataValue(nodata)
    band.WriteArray(array)
    ds.FlushCache()
    ds = None


def mirror_index(n, period):
    """Source index and tile number of each of n output positions."""
    pos = np.arange(n)
    tile = pos // period
    local = pos % period
    local = np.where(tile % 2 == 1, period - 1 - local, local)
    return local, tile


def main():
    if len(sys.argv) != 4:
        sys.stderr.write(__doc__.split("\n\n")[-1] + "\n")
        return 2
    src, size, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    os.makedirs(out, exist_ok=True)
    lu_ds, lu, lu_nodata = read(os.path.join(src, "landuse.tif"))
    _, dens, _ = read(os.path.join(src, "density.tif"))
    _, pid, _ = read(os.path.join(src, "parcels.tif"))
    rows, cols = lu.shape
    lx, tx = mirror_index(size, cols)
    ly, ty = mirror_index(size, rows)
    tiles_x = int(tx.max()) + 1

    write(os.path.join(out, "landuse.tif"), lu[np.ix_(ly, lx)], gdal.GDT_Byte, lu_ds,
          lu_nodata if lu_nodata is not None else 255)
    density = dens[np.ix_(ly, lx)].astype(np.float32)
    write(os.path.join(out, "density.tif"), density, gdal.GDT_Float32, lu_ds)

    uses = {}
    with open(os.path.join(src, "parcels.csv"), newline="") as f:
        for row in csv.DictReader(f):
            uses[int(row["parcel_id"])] = row["land_use"]
    max_id = int(max(int(pid.max()), max(uses) if uses else 0))
    tile = (ty[:, None] * tiles_x + tx[None, :]).astype(np.int64)
    src_ids = pid[np.ix_(ly, lx)].astype(np.int64)
    ids = np.where(src_ids > 0, src_ids + tile * max_id, 0)
    if ids.max() > 2**31 - 1:
        sys.stderr.write("ERROR: parcel ids exceed Int32 at this size\n")
        return 1
    ids = ids.astype(np.int32)
    del tile, src_ids
    write(os.path.join(out, "parcels.tif"), ids, gdal.GDT_Int32, lu_ds)

    flat = ids.ravel()
    cells = np.bincount(flat)
    people = np.bincount(flat, weights=density.ravel().astype(np.float64))
    with open(os.path.join(out, "parcels.csv"), "w", newline="") as f:
        f.write("parcel_id,land_use,population,cells\n")
        for i in np.nonzero(cells)[0]:
            if i == 0:
                continue
            source = (int(i) - 1) % max_id + 1
            if source in uses:  # ids the source table leaves out stay out (vectorize derives them)
                f.write("%d,%s,%.10g,%d\n" % (i, uses[source], people[i], cells[i]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
