# Why each matchable truth block is left unmatched (issue 20): for every truth block with >= 0.7 of its
# area on land cells (as evaluate's matchable share) whose best result block has IoU < 0.7, one of
#   gridify: its raw (4-connected land) block of the grid also holds other truth blocks;
#   merged in vectorize: the best result block lies < 70 % inside it but covers >= 70 % of it;
#   split / cut short: the result covers < 70 % of it but lies >= 70 % inside it;
#   boundary offset: both overlaps >= 70 % (the IoU is lost along the boundary).
# Usage: /usr/bin/python3 bench/vectorize/unmatched_blocks.py <landuse.tif> <truth.gpkg> <result.gpkg> [ids]
# prints block_id, area (m2), best IoU, share of the truth covered, share of the result inside, class;
# with ids (comma-separated), which truth blocks share each one's best result block.
import sys
import numpy as np
from osgeo import gdal, ogr
from scipy import ndimage
lu_path, truth_path, res_path = sys.argv[1:4]
d = gdal.Open(lu_path); a = d.ReadAsArray(); gt = d.GetGeoTransform(); cs = gt[1]
land = ~np.isin(a, [1, 2, 3])
raw, nraw = ndimage.label(land)
def shapes(path, layer):
    ds = ogr.Open(path); out = []
    for f in ds.GetLayerByName(layer):
        out.append(f.GetGeometryRef().Clone())
    return out
truth = shapes(truth_path, "blocks"); res = shapes(res_path, "blocks")
# truth block cells: rasterize by id
drv = gdal.GetDriverByName("MEM")
t = drv.Create("", a.shape[1], a.shape[0], 1, gdal.GDT_Int32); t.SetGeoTransform(gt); t.SetProjection(d.GetProjection())
tds = ogr.Open(truth_path)
gdal.RasterizeLayer(t, [1], tds.GetLayerByName("blocks"), options=["ATTRIBUTE=block_id"])
tb = t.ReadAsArray()
ids = [f.GetField("block_id") for f in tds.GetLayerByName("blocks")]
counts = {}
rows = []
for i, tpoly in enumerate(truth):
    if tpoly.GetArea() < 4 * cs * cs: continue
    cells = tb == ids[i]
    if cells.sum() == 0: continue
    share = land[cells].mean()
    if share < 0.7: continue
    cands = [r for r in res if r.Intersects(tpoly)]
    best, bi = 0.0, None
    for r in cands:
        inter = tpoly.Intersection(r).GetArea()
        iou = inter / (tpoly.GetArea() + r.GetArea() - inter)
        if iou > best: best, bi = iou, r
    if best >= 0.7: continue
    # raw blocks (4-connected land) holding this truth block's land cells
    comps = np.unique(raw[cells & land]); comps = comps[comps > 0]
    main = np.bincount(raw[cells & land]).argmax()
    others = np.unique(tb[(raw == main) & (tb > 0)])
    others = [o for o in others if o != ids[i] and (tb == o).sum() >= 4 and ((raw == main) & (tb == o)).sum() >= 0.5 * (tb == o).sum()]
    rshare = bi.Intersection(tpoly).GetArea() / bi.GetArea() if bi is not None else 0
    tcov = bi.Intersection(tpoly).GetArea() / tpoly.GetArea() if bi is not None else 0
    if others:
        why = "gridify: raw block holds %d other truth block(s)" % len(others)
    elif bi is None:
        why = "no result block"
    elif rshare < 0.7 and tcov >= 0.7:
        why = "merged in vectorize (result block %.0f%% this truth)" % (100 * rshare)
    elif tcov < 0.7 and rshare >= 0.7:
        why = "split / cut short (covers %.0f%% of truth)" % (100 * tcov)
    else:
        why = "boundary offset"
    key = why.split(" (")[0].split(":")[0]
    counts[key] = counts.get(key, 0) + 1
    rows.append((ids[i], round(tpoly.GetArea()), round(best, 2), round(tcov, 2), round(rshare, 2), why))
for r in sorted(rows, key=lambda r: r[5]): print(*r, sep="\t")
print(counts)
# Detail for merged blocks: which truth blocks share the best result block, and their raw blocks.
if len(sys.argv) > 4:
    for want in map(int, sys.argv[4].split(",")):
        i = ids.index(want); tpoly = truth[i]
        best, bi = 0, None
        for r in res:
            if not r.Intersects(tpoly): continue
            inter = tpoly.Intersection(r).GetArea(); iou = inter / (tpoly.GetArea() + r.GetArea() - inter)
            if iou > best: best, bi = iou, r
        shared = []
        for k, o in enumerate(truth):
            if o.Intersects(bi):
                sh = o.Intersection(bi).GetArea() / bi.GetArea()
                if sh > 0.05:
                    cells = tb == ids[k]
                    rb = np.bincount(raw[cells & land]).argmax() if (cells & land).any() else -1
                    shared.append((ids[k], round(sh, 2), int(rb)))
        lum = a[tb == want]
        print("truth", want, "result block area", round(bi.GetArea()), "shares:", shared, "classes", np.bincount(lum, minlength=9)[:9])
