"""Stitching (the single writer): merges the tiles' owned features into one GeoPackage, written under
a temporary name beside the output and renamed when complete (docs/scale.md "Stitching").
- roads: pieces cut at core edges are joined at their seam end points into continuous lines (a
  computed crossing point is dropped again, so a merged line has exactly its single-run vertices);
  from_node / to_node point at the road_nodes at the line's ends;
- pavement, water: pieces clipped at core edges whose cuts (boundary stretches the clip made) share a
  stretch of seam are unioned, and the vertices the clip added on the seam are removed;
- ids are renumbered in a deterministic order (by representative point); block_id links follow."""
import math
import os

from osgeo import ogr, osr

from urbanvec_tiles import geom as G

ogr.UseExceptions()

EPS = 1e-6  # metres: end points closer than this are one point


def _key(x, y):
    return (round(x / EPS), round(y / EPS))


class _Points:
    """Lookup of points by position within EPS."""

    def __init__(self):
        self.d = {}

    def add(self, x, y, value):
        self.d.setdefault(_key(x, y), []).append(value)

    def find(self, x, y):
        kx, ky = _key(x, y)
        out = []
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                out.extend(self.d.get((kx + dx, ky + dy), []))
        return out


def _line(pts):
    g = ogr.Geometry(ogr.wkbLineString)
    for x, y in pts:
        g.AddPoint_2D(x, y)
    return g


def merge_roads(pieces, warnings):
    """pieces: (points, attrs, (start_seam, end_seam, start_synth, end_synth), tile). Returns
    [(points, attrs)]."""
    ends = _Points()
    for i, (pts, _, fl, _) in enumerate(pieces):
        if fl[0]:
            ends.add(pts[0][0], pts[0][1], (i, 0))
        if fl[1]:
            ends.add(pts[-1][0], pts[-1][1], (i, 1))
    used = [False] * len(pieces)
    lines, mismatched = [], 0

    def oriented(i, first_end):
        pts, attrs, fl, _ = pieces[i]
        if first_end == 0:
            return list(pts), fl
        return list(reversed(pts)), (fl[1], fl[0], fl[3], fl[2])

    order = [i for i in range(len(pieces)) if not pieces[i][2][0] or not pieces[i][2][1]]
    order += [i for i in range(len(pieces)) if pieces[i][2][0] and pieces[i][2][1]]
    for i in order:
        if used[i]:
            continue
        used[i] = True
        start_end = 0 if not pieces[i][2][0] else 1
        pts, fl = oriented(i, start_end)
        attrs = pieces[i][1]
        while fl[1]:  # the chain's end is a seam cut: find the piece across the seam
            x, y = pts[-1]
            cand = [(j, e) for j, e in ends.find(x, y) if not used[j]]
            if not cand:
                mismatched += 1
                break
            j, e = cand[0]
            used[j] = True
            if pieces[j][1].get("road_class") != attrs.get("road_class"):
                mismatched += 1
            nxt, nfl = oriented(j, e)
            pts = (pts[:-1] if fl[3] else pts) + nxt[1:]
            fl = (fl[0], nfl[1], fl[2], nfl[3])
        lines.append((pts, attrs))
    if mismatched:
        warnings.append("%d road pieces found no matching piece (or another road class) across a seam"
                        % mismatched)
    return lines


def _on_seam(x, u, seams_x, seams_u):
    return x in seams_x or u in seams_u


def _drop_seam_vertices(poly_u, seams_x, seams_u):
    """Removes ring vertices lying on a seam whose neighbours are collinear with them (the clip's)."""
    out = ogr.Geometry(ogr.wkbPolygon)
    for k in range(poly_u.GetGeometryCount()):
        ring = poly_u.GetGeometryRef(k)
        pts = [(ring.GetX(i), ring.GetY(i)) for i in range(ring.GetPointCount())][:-1]
        changed = True
        while changed and len(pts) > 3:
            changed = False
            for i in range(len(pts)):
                a, p, b = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
                near = any(abs(p[0] - v) <= 1e-7 for v in seams_x) or any(abs(p[1] - v) <= 1e-7 for v in seams_u)
                if not near:
                    continue
                cross = (p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0])
                lab = math.hypot(b[0] - a[0], b[1] - a[1])
                if lab == 0 or abs(cross) / lab <= 1e-6:
                    del pts[i]
                    changed = True
                    break
        r = ogr.Geometry(ogr.wkbLinearRing)
        for x, u in pts + pts[:1]:
            r.AddPoint_2D(x, u)
        out.AddGeometry(r)
    return out


def _line_length(g):
    """Length of the lines in g (0 for points and empty parts)."""
    t = ogr.GT_Flatten(g.GetGeometryType())
    if t in (ogr.wkbLineString, ogr.wkbMultiLineString):
        return g.Length()
    if t == ogr.wkbGeometryCollection:
        return sum(_line_length(g.GetGeometryRef(k)) for k in range(g.GetGeometryCount()))
    return 0.0


def _shared(inter, shortest=None):
    """Whether an intersection of two pieces is a stretch of boundary (or an overlap), not a point: longer
    than 1e-4 m, or (with `shortest`, the length of the shorter of the two cuts) all of that cut, so the
    two halves of a sliver thinner than 1e-4 m that a seam crosses are one piece too."""
    t = ogr.GT_Flatten(inter.GetGeometryType())
    if t in (ogr.wkbPolygon, ogr.wkbMultiPolygon):
        return inter.GetArea() > 0
    if t in (ogr.wkbLineString, ogr.wkbMultiLineString):
        length = inter.Length()
        return length > 1e-4 or (shortest is not None and 0 < shortest <= length * (1 + 1e-6))
    if t == ogr.wkbGeometryCollection:
        return any(_shared(inter.GetGeometryRef(k), shortest) for k in range(inter.GetGeometryCount()))
    return False


def merge_polygons(pieces, frame, seams_x, seams_u, id_field):
    """pieces: (world polygon, attrs, tile, cut lines). Unions pieces of different tiles with the same
    attributes (apart from the id) whose cuts (the boundary stretches the clip made on a seam) share a
    stretch: the pieces of one feature, never two features that touch along a seam. Returns
    [(world polygon, attrs)]."""
    s = frame.s
    geoms = [G.to_u(p, s) for p, _, _, _ in pieces]
    cuts = [c for _, _, _, c in pieces]
    parent = list(range(len(pieces)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    bucket = {}
    size = 64 * frame.cell
    for i, g in enumerate(geoms):
        minx, maxx, minu, maxu = g.GetEnvelope()
        for bx in range(int(math.floor(minx / size)), int(math.floor(maxx / size)) + 1):
            for bu in range(int(math.floor(minu / size)), int(math.floor(maxu / size)) + 1):
                bucket.setdefault((bx, bu), []).append(i)
    keyattrs = [tuple((k, v) for k, v in sorted(a.items()) if k != id_field) for _, a, _, _ in pieces]
    envs = [g.GetEnvelope() for g in geoms]
    seen = set()
    for members in bucket.values():
        for ia in range(len(members)):
            for ib in range(ia + 1, len(members)):
                a, b = members[ia], members[ib]
                if (a, b) in seen or pieces[a][2] == pieces[b][2] or keyattrs[a] != keyattrs[b]:
                    continue
                seen.add((a, b))
                ea, eb = envs[a], envs[b]
                if ea[1] < eb[0] - EPS or eb[1] < ea[0] - EPS or ea[3] < eb[2] - EPS or eb[3] < ea[2] - EPS:
                    continue
                inter = cuts[a].Intersection(cuts[b])
                if inter is not None and _shared(inter, min(_line_length(cuts[a]), _line_length(cuts[b]))):
                    parent[find(a)] = find(b)
    groups = {}
    for i in range(len(pieces)):
        groups.setdefault(find(i), []).append(i)
    out = []
    for members in groups.values():
        if len(members) == 1:
            out.append((pieces[members[0]][0], pieces[members[0]][1]))
            continue
        multi = ogr.Geometry(ogr.wkbMultiPolygon)
        for i in members:
            multi.AddGeometry(geoms[i])
        merged = multi.UnionCascaded()
        for poly in G.polygons_of(merged):
            out.append((G.to_u(_drop_seam_vertices(poly, seams_x, seams_u), s), pieces[members[0]][1]))
    return out


def _rep(g):
    p = g.PointOnSurface() if g.GetDimension() == 2 else (g.Centroid() if g.GetDimension() == 1 else g)
    if p is None or p.IsEmpty():
        p = g.Centroid()
    return (round(p.GetX(), 6), round(p.GetY(), 6))


def stitch(parts, frame, tile_cells, layers, crs_wkt, styles, tmp_path):
    """parts: the tiles' owned data (dicts from tile.run_tile's pickles), in tile order. Writes the
    merged GeoPackage to tmp_path; returns (counts per layer, warnings)."""
    warnings = []
    schemas = parts[0]["schemas"]
    seams_x = {frame.x_edge(c) for c in range(tile_cells, frame.width, tile_cells)}
    seams_u = {frame.u_edge(r) for r in range(tile_cells, frame.height, tile_cells)}
    final = {}

    # Blocks and what hangs on them: new ids by representative point.
    if "blocks" in layers:
        blocks = []
        for t, part in enumerate(parts):
            for wkb, attrs in part["layers"]["blocks"]:
                g = ogr.CreateGeometryFromWkb(wkb)
                blocks.append((_rep(g), t, g, attrs))
        blocks.sort(key=lambda b: b[0])
        new_block = {}
        final["blocks"] = []
        for n, (_, t, g, attrs) in enumerate(blocks, start=1):
            new_block[(t, attrs["block_id"])] = n
            final["blocks"].append((g, dict(attrs, block_id=n)))
        for name, idf in (("spines", "spine_id"), ("parcels", "parcel_id")):
            rows = []
            for t, part in enumerate(parts):
                for wkb, attrs in part["layers"][name]:
                    g = ogr.CreateGeometryFromWkb(wkb)
                    b = new_block[(t, attrs["block_id"])]
                    rows.append(((b, _rep(g)), g, dict(attrs, block_id=b)))
            rows.sort(key=lambda r: r[0])
            final[name] = [(g, dict(a, **{idf: n})) for n, (_, g, a) in enumerate(rows, start=1)]
        rows = []
        for t, part in enumerate(parts):
            for _, attrs in part["layers"]["vectorize_report"]:
                rows.append(dict(attrs, block_id=new_block[(t, attrs["block_id"])]))
        final["vectorize_report"] = [(None, a) for a in sorted(rows, key=lambda a: a["block_id"])]
        for name, idf in (("pavement", "pavement_id"), ("water", "water_id")):
            whole, cut = [], []
            for t, part in enumerate(parts):
                for wkb, attrs, cut_wkb in part["layers"][name]:
                    g = ogr.CreateGeometryFromWkb(wkb)
                    if cut_wkb is None:
                        whole.append((g, attrs, t))
                    else:
                        cut.append((g, attrs, t, ogr.CreateGeometryFromWkb(cut_wkb)))
            merged = [(g, a) for g, a, _ in whole] + merge_polygons(cut, frame, seams_x, seams_u, idf)
            merged.sort(key=lambda r: (_rep(r[0]), str(r[1])))
            final[name] = [(g, dict(a, **{idf: n})) for n, (g, a) in enumerate(merged, start=1)]

    # Road nodes by position, roads merged across seams.
    nodes = []
    for part in parts:
        for wkb, attrs in part["layers"]["road_nodes"]:
            g = ogr.CreateGeometryFromWkb(wkb)
            nodes.append(((g.GetX(), g.GetY()), g, attrs))
    nodes.sort(key=lambda n: n[0])
    index = _Points()
    final["road_nodes"] = []
    for n, (xy, g, attrs) in enumerate(nodes, start=1):
        index.add(xy[0], xy[1], n)
        final["road_nodes"].append((g, dict(attrs, node_id=n)))
    pieces = []
    for t, part in enumerate(parts):
        for pts, attrs, fl in part["layers"]["roads"]:
            pieces.append((pts, attrs, fl, t))
    lines = merge_roads(pieces, warnings)
    missing = 0
    roads = []
    for pts, attrs in lines:
        ids = []
        for x, y in (pts[0], pts[-1]):
            hit = index.find(x, y)
            ids.append(hit[0] if hit else None)
            missing += not hit
        g = _line(pts)
        a = dict(attrs, from_node=ids[0], to_node=ids[1])
        if "length" in a:
            a["length"] = g.Length()
        roads.append(((attrs.get("road_class") or "", pts[0], pts[-1]), g, a))
    if missing:
        warnings.append("%d road ends have no road node" % missing)
    roads.sort(key=lambda r: r[0])
    final["roads"] = [(g, dict(a, road_id=n)) for n, (_, g, a) in enumerate(roads, start=1)]

    drv = ogr.GetDriverByName("GPKG")
    ds = drv.CreateDataSource(tmp_path)
    srs = None
    if crs_wkt:
        srs = osr.SpatialReference()
        srs.ImportFromWkt(crs_wkt)
        srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    counts = {}
    for name in layers:
        fields, gtype = schemas[name]
        lyr = ds.CreateLayer(name, srs if gtype != ogr.wkbNone else None, gtype)
        for fname, ftype in fields:
            lyr.CreateField(ogr.FieldDefn(fname, ftype))
        defn = lyr.GetLayerDefn()
        lyr.StartTransaction()
        for g, attrs in final[name]:
            f = ogr.Feature(defn)
            for fname, _ in fields:
                v = attrs.get(fname)
                if v is not None:
                    f.SetField(fname, v)
            if g is not None:
                if gtype != ogr.wkbNone and ogr.GT_Flatten(gtype) == ogr.wkbMultiLineString and \
                        ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbLineString:
                    g = ogr.ForceToMultiLineString(g)
                f.SetGeometry(g)
            lyr.CreateFeature(f)
        lyr.CommitTransaction()
        counts[name] = len(final[name])
    if styles:
        fields, rows = styles
        lyr = ds.CreateLayer("layer_styles", None, ogr.wkbNone)
        for fname, ftype in fields:
            lyr.CreateField(ogr.FieldDefn(fname, ftype))
        for attrs in rows:
            f = ogr.Feature(lyr.GetLayerDefn())
            for fname, _ in fields:
                if attrs.get(fname) is not None:
                    f.SetField(fname, attrs[fname])
            lyr.CreateFeature(f)
    ds = None
    return counts, warnings
