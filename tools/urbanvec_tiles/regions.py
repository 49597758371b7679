"""Road-bounded regions of the whole grid, found tile by tile (docs/scale.md "Open land and large
blocks").

Stage A2 of `urbanvec vectorize` splits the non-road cells into regions (4-connected) and treats a
region that reaches the grid's edge as open land (its unused cells are no block). A window cannot tell
a region it cuts from open land, so the driver answers that question for the whole grid before any
tile runs:

1. each core tile is labelled on its own (scipy.ndimage.label, 4-connectivity) and keeps only its
   labels along its four sides, the labels on the grid's edge and each label's bounding box;
2. labels that face each other across a seam (both cells non-road) are one region: the components of
   that graph (scipy.sparse.csgraph) are the whole grid's regions, open when one of their labels lies
   on the grid's edge;
3. the answer is written as a Byte GeoTIFF on the grid (1 = open region, 0 = enclosed region or road),
   read by every tile with `vectorize -open-regions` through its window; and every enclosed region
   keeps its bounding box, so a tile reads at least the whole of each enclosed region its core meets.

Memory on the client: the side labels (4 T per tile) and one bounding box per label (at 100,000²
cells with tiles of 1024 and ~10^7 regions: about 0.3 GB each); time: each core is read and labelled
twice (once per pass), 5 s for 4096² here."""
import numpy as np
from osgeo import gdal
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from urbanvec_tiles import tile as T

gdal.UseExceptions()


class Regions:
    """The enclosed regions of the whole grid, as bounding boxes (c0, r0, c1, r1) per core tile they
    meet."""

    def __init__(self, boxes_of_tile):
        self.boxes_of_tile = boxes_of_tile

    def enclosed_boxes(self, tile):
        return self.boxes_of_tile.get((tile.row, tile.col), [])


def _label(landuse, classes, core):
    c0, r0, c1, r1 = core
    roads = T.road_mask(landuse, (c0, r0, c1 - c0, r1 - r0), classes)
    labels, n = ndimage.label(~roads)
    return labels, n


def compute(landuse, classes, tiles, tile_cells, frame, path, progress=None):
    """Labels the grid tile by tile, writes the open-regions raster to `path` and returns Regions."""
    offsets, n_total = {}, 0
    sides = {}
    border = []
    boxes = []
    for k, t in enumerate(tiles):
        labels, n = _label(landuse, classes, t.core)
        c0, r0, c1, r1 = t.core
        offsets[t.name] = n_total
        g = np.where(labels > 0, labels - 1 + n_total, -1).astype(np.int64)
        sides[(t.row, t.col)] = (g[:, 0].copy(), g[:, -1].copy(), g[0, :].copy(), g[-1, :].copy())
        for on_edge, line in ((c0 == 0, g[:, 0]), (c1 == frame.width, g[:, -1]),
                              (r0 == 0, g[0, :]), (r1 == frame.height, g[-1, :])):
            if on_edge:
                border.append(line[line >= 0])
        objs = ndimage.find_objects(labels)
        boxes.append(np.array([(c0 + s[1].start, r0 + s[0].start, c0 + s[1].stop, r0 + s[0].stop) for s in objs],
                              dtype=np.int32).reshape(-1, 4))
        n_total += n
        if progress:
            progress(0.05 * (k + 1) / len(tiles), "regions")
    a, b = [], []
    for (r, c), (left, right, top, bottom) in sides.items():
        if (r, c + 1) in sides:
            other = sides[(r, c + 1)][0]
            m = (right >= 0) & (other >= 0)
            a.append(right[m]), b.append(other[m])
        if (r + 1, c) in sides:
            other = sides[(r + 1, c)][2]
            m = (bottom >= 0) & (other >= 0)
            a.append(bottom[m]), b.append(other[m])
    a = np.concatenate(a) if a else np.zeros(0, dtype=np.int64)
    b = np.concatenate(b) if b else np.zeros(0, dtype=np.int64)
    graph = coo_matrix((np.ones(len(a), dtype=np.int8), (a, b)), shape=(n_total, n_total))
    _, component = connected_components(graph, directed=False)
    n_comp = int(component.max()) + 1 if n_total else 0
    comp_open = np.zeros(n_comp, dtype=bool)
    if border:
        comp_open[component[np.concatenate(border)]] = True
    box = np.concatenate(boxes).astype(np.int64) if boxes else np.zeros((0, 4), dtype=np.int64)
    comp_box = np.empty((n_comp, 4), dtype=np.int64)
    comp_box[:, 0:2] = np.iinfo(np.int64).max
    comp_box[:, 2:4] = np.iinfo(np.int64).min
    np.minimum.at(comp_box[:, 0], component, box[:, 0])
    np.minimum.at(comp_box[:, 1], component, box[:, 1])
    np.maximum.at(comp_box[:, 2], component, box[:, 2])
    np.maximum.at(comp_box[:, 3], component, box[:, 3])

    src = gdal.Open(landuse)
    drv = gdal.GetDriverByName("GTiff")
    out = drv.Create(path, frame.width, frame.height, 1, gdal.GDT_Byte,
                     ["TILED=YES", "COMPRESS=DEFLATE", "BIGTIFF=IF_SAFER"])
    out.SetGeoTransform(src.GetGeoTransform())
    out.SetProjection(src.GetProjection())
    band = out.GetRasterBand(1)
    for k, t in enumerate(tiles):
        labels, _ = _label(landuse, classes, t.core)
        mask = np.zeros(labels.shape, dtype=np.uint8)
        inside = labels > 0
        mask[inside] = comp_open[component[labels[inside] - 1 + offsets[t.name]]]
        band.WriteArray(mask, t.core[0], t.core[1])
        if progress:
            progress(0.05 + 0.05 * (k + 1) / len(tiles), "regions")
    out.FlushCache()
    out = None
    boxes_of_tile = {}
    for c in np.flatnonzero(~comp_open):
        c0, r0, c1, r1 = (int(v) for v in comp_box[c])
        for tr in range(r0 // tile_cells, (r1 - 1) // tile_cells + 1):
            for tc in range(c0 // tile_cells, (c1 - 1) // tile_cells + 1):
                boxes_of_tile.setdefault((tr, tc), []).append((c0, r0, c1, r1))
    return Regions(boxes_of_tile)
