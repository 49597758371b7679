"""One tile: `urbanvec vectorize -srcwin <window>` into a per-tile GeoPackage in the shared work
folder, then keep what the tile owns (docs/scale.md "Ownership"):
- blocks whose representative point (GEOS PointOnSurface of the whole block) lies in the tile's
  half-open core, with their parcels, spines and vectorize_report rows (linked by block_id);
- road_nodes whose point lies in the core;
- roads cut at the core edges (pieces carry which ends are seam cuts, merged by stitch.py);
- pavement and water clipped to the core (pieces merged across seams by stitch.py).
Halo guard: a kept block, parcel or spine, or a road with a kept piece, that comes within one cell of a
side of the window that is not the grid's edge was cut off or shaped by the cut; so was a kept block
within one cell of a road the cut may have shaped (shaped_roads), and a kept
block or perimeter road in a road-bounded region that reaches such a side (stage A2 treats a region
touching the grid's edge as open, so a region cut by the window is not the single run's region); the tile is redone with twice the halo, up to
-max-halo, else the run fails naming the tile."""
import ctypes
import os
import pickle
import signal
import subprocess
import time
import uuid

import numpy as np
from osgeo import gdal, ogr
from scipy import ndimage

from urbanvec_tiles import geom as G

ogr.UseExceptions()

LAYERS = ["roads", "road_nodes", "pavement", "blocks", "water", "spines", "parcels", "vectorize_report"]
ROADS_ONLY_LAYERS = ["roads", "road_nodes"]


class TileError(Exception):
    """A tile that cannot be done (its message names the tile)."""


def _failure(proc):
    """Why a tile's process failed, in the words a user can act on: its own ERROR line, else the signal
    that stopped it (a full disk or quota shows as SIGXFSZ or an I/O error), else its last output."""
    errors = [l for l in proc.stderr.splitlines() if l.startswith("ERROR")]
    if errors:
        return "exit %d: %s" % (proc.returncode, errors[-1])
    if proc.returncode < 0:
        try:
            name = signal.Signals(-proc.returncode).name
        except ValueError:
            name = "signal %d" % -proc.returncode
        hint = {"SIGXFSZ": ": file size limit reached (disk full or quota on the work folder?)",
                "SIGKILL": ": killed (out of memory?)"}.get(name, "")
        return "killed by %s%s" % (name, hint)
    return "exit %d: %s" % (proc.returncode, proc.stderr.strip()[-300:])


def _die_with_parent():
    # The vectorize process dies with the worker that runs it (a killed worker leaves no orphan
    # writing into the shared folder while the task is retried elsewhere).
    try:
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except OSError:
        pass


def _schema(layer):
    d = layer.GetLayerDefn()
    return [(d.GetFieldDefn(k).GetName(), d.GetFieldDefn(k).GetType()) for k in range(d.GetFieldCount())]


def _attrs(f, names):
    return {n: f.GetField(n) for n in names}


def _envelope_u(g, s):
    minx, maxx, miny, maxy = g.GetEnvelope()
    ua, ub = sorted((s * miny, s * maxy))
    return minx, maxx, ua, ub


def _touches(env, wbox, tol):
    minx, maxx, ua, ub = env
    return minx <= wbox[0] + tol or maxx >= wbox[1] - tol or ua <= wbox[2] + tol or ub >= wbox[3] - tol


ROAD_CLASSES = {"secondary_road": 2, "primary_road": 3}


def road_mask(landuse, window, classes):
    """Road cells (classes 2 and 3, or the values -classes maps to them) of the window."""
    ds = gdal.Open(landuse)
    band = ds.GetRasterBand(1)
    a = band.ReadAsArray(*window)
    if not classes:
        return (a == 2) | (a == 3)
    mask = np.zeros(a.shape, dtype=bool)
    with open(classes) as fh:
        for line in fh:
            cols = [c.strip().strip('"') for c in line.replace(";", ",").replace("\t", ",").split(",")]
            if len(cols) >= 2 and cols[1].lower() in ROAD_CLASSES:
                try:
                    mask |= a == float(cols[0])
                except ValueError:
                    pass
    return mask


def open_mask(path, window):
    """The window of the whole grid's open-regions raster (regions.py): True where the cell's region
    reaches the grid's edge."""
    ds = gdal.Open(path)  # kept alive while its band is read
    return ds.GetRasterBand(1).ReadAsArray(*window) != 0


def open_regions(roads, window, frame, globally_open=None):
    """Per cell of the window, whether its road-bounded region (4-connected non-road cells, as stage
    A2 finds them) reaches a side of the window that is not the grid's edge and is enclosed in the
    whole grid (`globally_open` False there; without it every cut region counts): the window cuts
    such a region, which is not the single run's region, so nothing in it may be kept. A cut region
    that reaches the grid's edge is open land in both runs (vectorize -open-regions)."""
    labels, _ = ndimage.label(~roads)
    x0, y0, xs, ys = window
    edge = set()
    if x0 > 0:
        edge |= set(np.unique(labels[:, 0]))
    if x0 + xs < frame.width:
        edge |= set(np.unique(labels[:, -1]))
    if y0 > 0:
        edge |= set(np.unique(labels[0, :]))
    if y0 + ys < frame.height:
        edge |= set(np.unique(labels[-1, :]))
    edge.discard(0)
    cut = np.isin(labels, sorted(edge)) if edge else np.zeros(labels.shape, dtype=bool)
    return cut if globally_open is None else cut & ~globally_open


def shaped_roads(roads, wbox, s, tol):
    """The roads of a tile's output that the window's cut may have shaped: those that come within `tol`
    of a side of the window that is not the grid's edge (a road there is cut, or runs along the cut:
    a perimeter road follows the window's side where the single run's road lies outside it), and the
    roads that share an end node with one of them (the node's place is found from every road meeting
    there, so their ends move with it). A block's outline follows the roads around it, so a kept block
    next to one of these is shaped by the cut even when the block itself stays away from the window's
    side (Monaco at tiles of 128 and 256 cells: a perimeter road along the cut side 7 m from a kept
    block, and a junction 1.5 cells from it that moved the block's corner by 3 m).
    Returns [(envelope, geometry)]."""
    rows = []
    for f in roads:
        g = f.GetGeometryRef()
        rows.append((g.GetEnvelope(), g.Clone(), f.GetField("from_node"), f.GetField("to_node")))
    cut_nodes = set()
    cut = [k for k, (env, g, a, b) in enumerate(rows) if _touches(_envelope_u(g, s), wbox, tol)]
    for k in cut:
        cut_nodes.update(v for v in rows[k][2:] if v is not None)
    cut = set(cut)
    return [(env, g) for k, (env, g, a, b) in enumerate(rows) if k in cut or a in cut_nodes or b in cut_nodes]


def _near_any(g, shaped, tol):
    minx, maxx, miny, maxy = g.GetEnvelope()
    for (a, b, c, d), r in shaped:
        if a <= maxx + tol and b >= minx - tol and c <= maxy + tol and d >= miny - tol and g.Distance(r) <= tol:
            return True
    return False


def extract(path, tile, window, frame, roads_only, opened=None):
    """(owned layers, schemas, guard violations) of one tile's GeoPackage. `opened`: open_regions()."""
    gt = frame.gt
    x0w, y0w = window[0], window[1]

    def in_open_region(x, y, reach=0):
        if opened is None:
            return False
        c = int(np.floor((x - gt[0]) / gt[1])) - x0w
        r = int(np.floor((y - gt[3]) / gt[5])) - y0w
        sub = opened[max(0, r - reach):r + reach + 1, max(0, c - reach):c + reach + 1]
        return bool(sub.any())
    s = frame.s
    c0, r0, c1, r1 = tile.core
    core = frame.box(c0, r0, c1, r1)
    x0, y0, xs, ys = window
    wbox = frame.box(x0, y0, x0 + xs, y0 + ys)  # infinite on sides that are the grid's edge
    wfinite = frame.box(x0, y0, x0 + xs, y0 + ys, open_at_grid_edge=False)
    big = 10 * frame.cell * max(frame.width, frame.height)
    fallback = (wfinite[0] - big, wfinite[1] + big, wfinite[2] - big, wfinite[3] + big)
    core_rect = G.rect(core, fallback)
    seams_x = [v for v in core[0:2] if v != G.INF and v != -G.INF]
    seams_u = [v for v in core[2:4] if v != G.INF and v != -G.INF]
    seam_lines = core_rect.GetBoundary()  # the core's sides (in (x, u)); cuts lie on its seams
    tol = frame.cell
    ds = ogr.Open(path)
    out, schemas, violations = {}, {}, []

    def violation(layer, g):
        p = g.PointOnSurface() if g.GetDimension() == 2 else g.Centroid()
        violations.append("%s near (%.1f, %.1f)" % (layer, p.GetX(), p.GetY()))

    layers = ROADS_ONLY_LAYERS if roads_only else LAYERS
    for name in layers:
        lyr = ds.GetLayerByName(name)
        if lyr is None:
            raise TileError("tile %s: the tile output '%s' has no layer %s" % (tile.name, path, name))
        schemas[name] = (_schema(lyr), lyr.GetGeomType())
        out[name] = []
    names = {n: [f for f, _ in schemas[n][0]] for n in layers}

    kept_blocks = set()
    if not roads_only:
        shaped = shaped_roads(ds.GetLayerByName("roads"), wbox, s, tol)
        for f in ds.GetLayerByName("blocks"):
            g = f.GetGeometryRef()
            p = g.PointOnSurface()
            if G.owns(core, p.GetX(), s * p.GetY()):
                kept_blocks.add(f.GetField("block_id"))
                out["blocks"].append((g.ExportToWkb(), _attrs(f, names["blocks"])))
                if _touches(_envelope_u(g, s), wbox, tol) or in_open_region(p.GetX(), p.GetY()) or \
                        _near_any(g, shaped, tol):
                    violation("blocks", g)
        for name in ("parcels", "spines"):
            for f in ds.GetLayerByName(name):
                if f.GetField("block_id") in kept_blocks:
                    g = f.GetGeometryRef()
                    out[name].append((g.ExportToWkb(), _attrs(f, names[name])))
                    if _touches(_envelope_u(g, s), wbox, tol):
                        violation(name, g)
        for f in ds.GetLayerByName("vectorize_report"):
            if f.GetField("block_id") in kept_blocks:
                out["vectorize_report"].append((None, _attrs(f, names["vectorize_report"])))
        for name in ("pavement", "water"):
            for f in ds.GetLayerByName(name):
                g = f.GetGeometryRef()
                env = _envelope_u(g, s)
                if env[1] < core[0] or env[0] > core[1] or env[3] < core[2] or env[2] > core[3]:
                    continue
                attrs = _attrs(f, names[name])
                gu = G.to_u(g, s)
                if core[0] < env[0] and env[1] < core[1] and core[2] < env[2] and env[3] < core[3]:
                    out[name].append((g.ExportToWkb(), attrs, None))
                    continue
                kept = G.polygons_of(gu.Intersection(core_rect))
                if len(kept) == 1 and kept[0].GetArea() >= gu.GetArea() * (1 - 1e-12):
                    # Inside the closed core, touching a seam from this side only: a whole feature,
                    # not a piece to join with the neighbour's feature across the seam.
                    out[name].append((g.ExportToWkb(), attrs, None))
                    continue
                # Each piece keeps its cut: the stretches of its boundary that the clip made (on a
                # seam, not on the feature's own boundary). The stitcher joins pieces whose cuts
                # overlap, so two features that merely touch along a seam stay two.
                # The clip's points on a seam are moved onto it exactly (GEOS computes them to a few
                # ulps); a vertex of the feature itself is never that close to a seam without being on
                # it: vertices lie on the precision grid (1e-6 cells), so one tenth of that is the limit.
                own = gu.GetBoundary().Buffer(1e-7 * frame.cell)
                for piece in kept:
                    G.snap_to_seams(piece, seams_x, seams_u, 1e-7 * frame.cell)
                    cut = piece.GetBoundary().Intersection(seam_lines).Difference(own)
                    out[name].append((G.to_u(piece, s).ExportToWkb(), attrs, G.to_u(cut, s).ExportToWkb()))

    for f in ds.GetLayerByName("road_nodes"):
        g = f.GetGeometryRef()
        if G.owns(core, g.GetX(), s * g.GetY()):
            out["road_nodes"].append((g.ExportToWkb(), _attrs(f, names["road_nodes"])))
    for f in ds.GetLayerByName("roads"):
        g = f.GetGeometryRef()
        pts = [(g.GetX(k), s * g.GetY(k)) for k in range(g.GetPointCount())]
        attrs = _attrs(f, names["roads"])
        pieces = G.cut_line(pts, core)
        if pieces and (_touches(_envelope_u(g, s), wbox, tol) or (
                attrs.get("road_class") == "perimeter" and
                any(in_open_region(g.GetX(k), g.GetY(k), 1) for k in range(g.GetPointCount())))):
            violation("roads", g)  # running out of the window, or a perimeter of a cut region
        for pts_u, ss, es, ssyn, esyn in pieces:
            world = [(x, s * u) for x, u in pts_u]
            out["roads"].append((world, attrs, (ss, es, ssyn, esyn)))
    return out, schemas, violations


def read_styles(path):
    """(schema, rows) of the GeoPackage's layer_styles table (QGIS styles), or None."""
    ds = ogr.Open(path)
    lyr = ds.GetLayerByName("layer_styles")
    if lyr is None:
        return None
    schema = _schema(lyr)
    return schema, [_attrs(f, [n for n, _ in schema]) for f in lyr]


def run_tile(job):
    """Runs one tile (a dict made by cli.py); returns a small summary. Raises TileError."""
    tile, frame = job["tile"], job["frame"]
    halo = job["halo"]
    start = time.time()
    attempts = []
    while True:
        window = tile.window(halo, job.get("boxes", ()))
        tmp = os.path.join(job["workdir"], "tile_%s_h%d.%s.gpkg" % (tile.name, halo, uuid.uuid4().hex[:8]))
        cmd = [job["urbanvec"], "vectorize", "-q", "-srcwin"] + [str(v) for v in window] + job["vargs"] + [
            job["landuse"], tmp]
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              preexec_fn=_die_with_parent)
        if proc.returncode != 0:
            raise TileError("tile %s (window %s): urbanvec vectorize failed (%s)"
                            % (tile.name, " ".join(map(str, window)), _failure(proc)))
        try:
            mask = job.get("open_regions")
            opened = open_regions(road_mask(job["landuse"], window, job.get("classes")), window, frame,
                                  open_mask(mask, window) if mask else None)
            owned, schemas, violations = extract(tmp, tile, window, frame, job["roads_only"], opened)
            styles = read_styles(tmp)
        finally:
            if not job.get("keep_tiles"):
                for p in (tmp,):
                    if os.path.exists(p):
                        os.remove(p)
        attempts.append((halo, len(violations)))
        if not violations:
            break
        whole = window == (0, 0, frame.width, frame.height)
        if whole or halo >= job["max_halo"]:
            raise TileError(
                "tile %s (cells %d..%d x %d..%d): %d kept features reach the edge of its window with halo "
                "%d (%s); the halo is too small for these blocks: rerun with a larger -halo or -max-halo"
                % (tile.name, tile.core[0], tile.core[2] - 1, tile.core[1], tile.core[3] - 1,
                   len(violations), halo, ", ".join(violations[:3])))
        halo = min(job["max_halo"], 2 * halo if halo > 0 else 1)
    target = os.path.join(job["workdir"], "owned_%s.pkl" % tile.name)
    part = target + ".%s.part" % uuid.uuid4().hex[:8]
    with open(part, "wb") as fh:
        pickle.dump({"tile": tile.name, "halo": halo, "layers": owned, "schemas": schemas}, fh)
    os.replace(part, target)
    return {"tile": tile.name, "owned": target, "halo": halo, "attempts": attempts,
            "seconds": time.time() - start, "styles": styles, "warnings": [l for l in proc.stderr.splitlines() if l]}
