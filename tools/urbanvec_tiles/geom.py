"""Geometry helpers shared by tile extraction and stitching: ownership of points by a half-open core
rectangle, deterministic cutting of lines at the core edges, clipping of polygons to the core.

Coordinates are world (x, y). Rows run along u = s * y with s = -1 for a north-up grid, so a core is
the half-open box xmin <= x < xmax, umin <= u < umax in every direction; a tile on the grid's edge
has an open side (infinite bound), so features outside the grid still have an owner."""
import math

from osgeo import ogr

ogr.UseExceptions()
INF = math.inf


class Frame:
    """The whole grid's frame: seams are whole-grid cell edges, the same numbers in every process."""

    def __init__(self, gt, width, height):
        if gt[2] != 0 or gt[4] != 0:
            raise ValueError("the grid is rotated (geotransform terms %g, %g); tiles need a north-up grid"
                             % (gt[2], gt[4]))
        if gt[1] <= 0:
            raise ValueError("the grid's columns run westwards (pixel width %g); tiles need gt[1] > 0" % gt[1])
        self.gt, self.width, self.height = tuple(gt), width, height
        self.s = -1.0 if gt[5] < 0 else 1.0
        self.cell = abs(gt[1])

    def x_edge(self, col):
        return self.gt[0] + col * self.gt[1]

    def u_edge(self, row):
        return self.s * (self.gt[3] + row * self.gt[5])

    def box(self, c0, r0, c1, r1, open_at_grid_edge=True):
        """(xmin, xmax, umin, umax) of cells [c0, c1) x [r0, r1); sides on the grid's edge are open
        (infinite) when asked. x grows with the column (gt[1] > 0) and u with the row."""
        xa, xb, ua, ub = self.x_edge(c0), self.x_edge(c1), self.u_edge(r0), self.u_edge(r1)
        if open_at_grid_edge:
            xa = -INF if c0 == 0 else xa
            xb = INF if c1 == self.width else xb
            ua = -INF if r0 == 0 else ua
            ub = INF if r1 == self.height else ub
        return (xa, xb, ua, ub)


def owns(box, x, u):
    return box[0] <= x < box[1] and box[2] <= u < box[3]


def _crossing(a, b, axis, value):
    """The point where segment a-b crosses the line coordinate[axis] = value, computed from the
    endpoints in lexicographic order so both neighbouring tiles get the same numbers."""
    p, q = (a, b) if a <= b else (b, a)
    t = (value - p[axis]) / (q[axis] - p[axis])
    other = 1 - axis
    pt = [0.0, 0.0]
    pt[axis] = value
    pt[other] = p[other] + t * (q[other] - p[other])
    return (pt[0], pt[1])


def cut_line(pts, box):
    """Pieces of polyline `pts` (points in (x, u)) inside the half-open box, as lists of
    (points, start_on_seam, end_on_seam, start_synthetic, end_synthetic). A piece end is on a seam when
    it is not an end of the line; synthetic when it is a computed crossing, not one of the line's
    vertices."""
    pieces = []
    cur = None  # [points, start_seam, start_synth]
    n = len(pts)
    for i in range(n - 1):
        a, b = pts[i], pts[i + 1]
        cuts = []
        for axis, bounds in ((0, box[0:2]), (1, box[2:4])):
            for v in bounds:
                if math.isfinite(v) and (a[axis] - v) * (b[axis] - v) < 0:
                    t = (v - a[axis]) / (b[axis] - a[axis])
                    cuts.append((t, _crossing(a, b, axis, v)))
        cuts.sort()
        stops = [(0.0, a, False)] + [(t, p, True) for t, p in cuts] + [(1.0, b, False)]
        for k in range(len(stops) - 1):
            p, q = stops[k][1], stops[k + 1][1]
            mid = ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
            if owns(box, mid[0], mid[1]):
                if cur is None:
                    at_line_start = i == 0 and k == 0
                    cur = [[p], not at_line_start, stops[k][2]]
                cur[0].append(q)
            elif cur is not None:
                pieces.append((cur[0], cur[1], True, cur[2], stops[k][2]))
                cur = None
    if cur is not None:
        pieces.append((cur[0], cur[1], False, cur[2], False))
    return pieces


def rect(box, fallback):
    """A polygon of the box, infinite bounds replaced by `fallback` (xmin, xmax, umin, umax)."""
    b = [box[k] if math.isfinite(box[k]) else fallback[k] for k in range(4)]
    ring = ogr.Geometry(ogr.wkbLinearRing)
    for x, u in ((b[0], b[2]), (b[1], b[2]), (b[1], b[3]), (b[0], b[3]), (b[0], b[2])):
        ring.AddPoint_2D(x, u)
    poly = ogr.Geometry(ogr.wkbPolygon)
    poly.AddGeometry(ring)
    return poly


def to_u(geom, s):
    """A copy of `geom` with y replaced by u = s * y (an involution: apply again to go back)."""
    g = geom.Clone()
    if s == 1.0:
        return g

    def flip(h):
        if h.GetGeometryCount() > 0:
            for k in range(h.GetGeometryCount()):
                flip(h.GetGeometryRef(k))
        else:
            for k in range(h.GetPointCount()):
                x, y = h.GetX(k), h.GetY(k)
                h.SetPoint_2D(k, x, -y)

    flip(g)
    return g


def polygons_of(geom):
    """The polygons (with area) of any geometry, as separate ogr Polygons."""
    out = []
    t = ogr.GT_Flatten(geom.GetGeometryType())
    if t == ogr.wkbPolygon:
        if geom.GetArea() > 0:
            out.append(geom.Clone())
    elif t in (ogr.wkbMultiPolygon, ogr.wkbGeometryCollection):
        for k in range(geom.GetGeometryCount()):
            out.extend(polygons_of(geom.GetGeometryRef(k)))
    return out


def snap_to_seams(geom, xs, us, tol):
    """Moves vertices within tol of a seam (x in xs, u in us) onto it exactly (geometry in (x, u))."""
    def fix(h):
        if h.GetGeometryCount() > 0:
            for k in range(h.GetGeometryCount()):
                fix(h.GetGeometryRef(k))
            return
        for k in range(h.GetPointCount()):
            x, u = h.GetX(k), h.GetY(k)
            for v in xs:
                if abs(x - v) <= tol:
                    x = v
            for v in us:
                if abs(u - v) <= tol:
                    u = v
            h.SetPoint_2D(k, x, u)

    fix(geom)
    return geom
