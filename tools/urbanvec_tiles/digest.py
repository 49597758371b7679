"""Canonical digest and comparison of two vectorize outputs (issue 22's equality check).

A feature's canonical form leaves out its own id, follows its links (a road's from_node / to_node
become the nodes' positions, a parcel's / spine's / report row's block_id its block's representative
point), normalizes its geometry (vertices collinear within 1e-7 m removed, GEOS normalize: ring start
and orientation, line direction) and rounds coordinates to 1 mm and reals to 6 significant digits.
Features are sorted by that form, so the order and numbering of the features do not matter."""
import hashlib
import math

from osgeo import ogr

ogr.UseExceptions()

IDS = {"road_id", "node_id", "pavement_id", "water_id", "spine_id", "parcel_id", "sim_block_id"}
LINKED = {"parcels", "spines", "vectorize_report"}


def _drop_collinear(pts, closed, tol=1e-7):
    changed = True
    while changed:
        changed = False
        lo, hi = (0, len(pts) - 1) if closed else (1, len(pts) - 1)
        n = len(pts) - (1 if closed else 0)
        if n <= (3 if closed else 2):
            break
        for i in range(lo, hi):
            a, p, b = pts[i - 1] if i > 0 else pts[-2], pts[i], pts[i + 1]
            lab = math.hypot(b[0] - a[0], b[1] - a[1])
            cross = (p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0])
            if lab > 0 and abs(cross) / lab <= tol and min(a[0], b[0]) - tol <= p[0] <= max(a[0], b[0]) + tol \
                    and min(a[1], b[1]) - tol <= p[1] <= max(a[1], b[1]) + tol:
                del pts[i]
                if closed and i == 0:
                    pts[-1] = pts[0]
                changed = True
                break
    return pts


def normalized(g):
    """A normalized copy: GEOS Normalize, collinear vertices removed, GEOS Normalize again. The first
    Normalize fixes each ring's start, so the removal (greedy, from the start) does not depend on where
    the writer began the ring."""
    g = g.Clone()
    first = g.Normalize()
    if first is not None:
        g = first

    def fix(h):
        if h.GetGeometryCount() > 0:
            for k in range(h.GetGeometryCount()):
                fix(h.GetGeometryRef(k))
            return
        if h.GetPointCount() < 3:
            return
        pts = [(h.GetX(k), h.GetY(k)) for k in range(h.GetPointCount())]
        closed = pts[0] == pts[-1]
        pts = _drop_collinear(pts, closed)
        h.Empty()
        for x, y in pts:
            h.AddPoint_2D(x, y)

    fix(g)
    n = g.Normalize()  # returns the normalized copy
    return n if n is not None else g


def coords(g):
    out = []

    def walk(h):
        if h.GetGeometryCount() > 0:
            out.append("(")
            for k in range(h.GetGeometryCount()):
                walk(h.GetGeometryRef(k))
            out.append(")")
        else:
            out.append([(h.GetX(k), h.GetY(k)) for k in range(h.GetPointCount())])

    walk(g)
    return out


def _mm(v):
    return "%.3f" % (round(v * 1000) / 1000 + 0.0)


def _text(c):
    return "".join(x if isinstance(x, str) else ",".join(_mm(a) + " " + _mm(b) for a, b in x) + ";" for x in c)


def _value(v):
    if isinstance(v, float):
        return "%.6g" % v
    return str(v)


def rep(g):
    p = g.PointOnSurface() if g.GetDimension() == 2 else g.Centroid()
    return (p.GetX(), p.GetY())


def canonical(path):
    """{layer: [(sort key, text, coordinate lists)]}."""
    ds = ogr.Open(path)
    out = {}
    block_rep, node_at = {}, {}
    if ds.GetLayerByName("blocks") is not None:
        for f in ds.GetLayerByName("blocks"):
            x, y = rep(f.GetGeometryRef())
            block_rep[f.GetField("block_id")] = "%s %s" % (_mm(x), _mm(y))
    if ds.GetLayerByName("road_nodes") is not None:
        for f in ds.GetLayerByName("road_nodes"):
            g = f.GetGeometryRef()
            node_at[f.GetField("node_id")] = "%s %s" % (_mm(g.GetX()), _mm(g.GetY()))
    for k in range(ds.GetLayerCount()):
        lyr = ds.GetLayer(k)
        name = lyr.GetName()
        if name == "layer_styles":
            continue
        d = lyr.GetLayerDefn()
        fields = [d.GetFieldDefn(i).GetName() for i in range(d.GetFieldCount())]
        rows = []
        for f in lyr:
            vals = []
            for fn in fields:
                v = f.GetField(fn)
                if fn in IDS or (fn == "block_id" and name == "blocks"):
                    continue
                if fn == "block_id" and name in LINKED:
                    v = "block@" + block_rep.get(v, "?")
                elif fn in ("from_node", "to_node"):
                    continue  # as the unordered pair of end nodes below (normalizing may reverse a line)
                vals.append("%s=%s" % (fn, _value(v)))
            if "from_node" in fields and "to_node" in fields:
                ends = sorted("node@" + node_at.get(f.GetField(fn), "?") for fn in ("from_node", "to_node"))
                vals.append("ends=%s/%s" % tuple(ends))
            g = f.GetGeometryRef()
            if g is not None:
                n = normalized(g)
                c = coords(n)
                x, y = rep(n)
                key = (name, tuple(vals), round(x, 2), round(y, 2))
                rows.append((key, " ".join(vals) + " | " + _text(c), c))
            else:
                rows.append(((name, tuple(vals)), " ".join(vals), []))
        rows.sort(key=lambda r: r[1])
        out[name] = rows
    return out


def digest(path):
    res = []
    for name, rows in canonical(path).items():
        h = hashlib.sha256("\n".join(r[1] for r in rows).encode()).hexdigest()[:16]
        res.append((name, h, len(rows)))
    return res


def _flat(c):
    return [p for x in c if not isinstance(x, str) for p in x]


def compare(a, b, tol=1e-6):
    """Matches features by attributes (links followed) and representative point; reports per layer
    the count of unmatched features and the largest coordinate difference of matched ones."""
    ca, cb = canonical(a), canonical(b)
    ok, lines = True, []
    for name in sorted(set(ca) | set(cb)):
        ra, rb = ca.get(name, []), cb.get(name, [])
        if not ra or not ra[0][2]:  # tables: compare texts (rounded)
            sa, sb = sorted(r[1] for r in ra), sorted(r[1] for r in rb)
            same = sa == sb
            lines.append("%-17s %6d %6d  %s" % (name, len(ra), len(rb), "same" if same else "DIFFERENT"))
            ok &= same
            continue
        # Match by attribute text and nearest representative point (within 1 cm).
        # Candidates bucketed by attributes and a 5 cm cell of their point (linear, not quadratic, in
        # the features of a layer); a point within 2 cm lies in one of the 3 x 3 cells around.
        # Features with the same canonical text are equal and matched first, so that two small
        # features whose points lie within 2 cm of each other are not paired crosswise.
        same_text = {}
        for r in rb:
            same_text[r[1]] = same_text.get(r[1], 0) + 1
        rest_a = []
        for r in ra:
            if same_text.get(r[1], 0) > 0:
                same_text[r[1]] -= 1
            else:
                rest_a.append(r)
        pool = {}
        for r in rb:
            if same_text.get(r[1], 0) <= 0:
                continue
            same_text[r[1]] -= 1
            pool.setdefault((r[0][1], math.floor(r[0][2] / 0.05), math.floor(r[0][3] / 0.05)), []).append(r)
        worst, unmatched = 0.0, 0
        for r in rest_a:
            best, bd, home = None, None, None
            cx, cy = math.floor(r[0][2] / 0.05), math.floor(r[0][3] / 0.05)
            for i in (cx - 1, cx, cx + 1):
                for j in (cy - 1, cy, cy + 1):
                    for c in pool.get((r[0][1], i, j), []):
                        d = math.hypot(c[0][2] - r[0][2], c[0][3] - r[0][3])
                        if d <= 0.02 and (bd is None or d < bd):
                            best, bd, home = c, d, (r[0][1], i, j)
            if best is None:
                unmatched += 1
                continue
            pool[home].remove(best)
            pa, pb = _flat(r[2]), _flat(best[2])
            if len(pa) != len(pb):
                worst = max(worst, math.inf)
                continue
            for p, q in zip(pa, pb):
                worst = max(worst, abs(p[0] - q[0]), abs(p[1] - q[1]))
        left = sum(len(v) for v in pool.values())
        good = unmatched == 0 and left == 0 and worst <= tol
        ok &= good
        lines.append("%-17s %6d %6d  unmatched %d/%d  max coordinate difference %s  %s" % (
            name, len(ra), len(rb), unmatched, left, "%.3g m" % worst if math.isfinite(worst) else "vertex count differs",
            "same" if good else "DIFFERENT"))
    return ok, lines
