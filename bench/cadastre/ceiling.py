#!/usr/bin/python3
"""Ceilings of building-part recall on make_cad.py drawings (issue 17): vertex placements with the
topology of the truth, scored against the truth at IoU >= 0.9.

  ceiling.py DRAWING.dxf TRUTH.gpkg
      each truth vertex at the mean of the drawing's segment ends nearer to it than to any other truth
      vertex and within 0.9 m (a perfect clusterer that does not know which copy is which).
  ceiling.py --seed S [--level L2] [VARIANT ...]
      regenerates the drawing with make_cad.py and the provenance of every drawn end (which truth
      vertex or split point it is a copy of), then places the vertices by each VARIANT (default: all
      of VARIANTS below) and prints recall and the RMS vertex error per variant:
        mean       the mean of every copy of the vertex;
        robust     least squares over the copies, each across its own segment at full weight and along
                   it with a Huber weight (over- and undershoots move ends along their line);
        split      + split points (copies of a point inside an edge) hold the edge's line;
        straight   + a vertex whose two edges are within 10 degrees of straight and 0.15 m of the line
                   of its neighbours stays on it (soft, 0.03 m);
        right      + angles within 10 degrees of 90 whose shorter arm's end is within 0.15 m of square
                   are held square (soft, 0.03 in cosine);
        full       straight and right together (what `urbanvec cadastre` does, on its own topology);
        meanfit    the means, weighted by their number of copies, with the straight constraints only.
"""
import math
import os
import random
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from osgeo import ogr
from scipy.spatial import cKDTree

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "..", "tests", "cadastre"))
from score import polygons, surface  # noqa: E402

ogr.UseExceptions()

SIGMA = 0.15  # per-axis spread of a copy jittered uniformly in a 0.3 m disc
VARIANTS = {
    "mean": None,
    "robust": dict(split=False),
    "split": dict(),
    "straight": dict(straight=10),
    "right": dict(right=10),
    "full": dict(straight=10, right=10),
    "meanfit": dict(meanobs=True, straight=10),
}


def ring_points(path, layers):
    ds = ogr.Open(path)
    out = []
    for layer in layers:
        for f in ds.GetLayerByName(layer):
            g = f.GetGeometryRef()
            for i in range(g.GetGeometryCount()):
                r = g.GetGeometryRef(i)
                out += [r.GetPoint_2D(k) for k in range(r.GetPointCount())]
    return np.unique(np.array(out), axis=0)


def recall(parts, position):
    """Share of truth parts at IoU >= 0.9 once every vertex is moved by `position` (coordinate ->
    new coordinate)."""
    hit = 0
    for g, _, area, _ in parts:
        moved = g.Clone()
        for i in range(moved.GetGeometryCount()):
            ring = moved.GetGeometryRef(i)
            for k in range(ring.GetPointCount()):
                p = ring.GetPoint_2D(k)
                if p in position:
                    ring.SetPoint_2D(k, *position[p])
        if not moved.IsValid():
            moved = moved.MakeValid()
        inter = surface(g.Intersection(moved))
        hit += inter / (area + moved.GetArea() - inter) >= 0.9
    return hit / max(1, len(parts))


def nearest_mean(drawing, truth):
    ends = []
    ds = ogr.Open(drawing)
    for f in ds.GetLayer(0):
        g = f.GetGeometryRef()
        if g is not None and ogr.GT_Flatten(g.GetGeometryType()) == ogr.wkbLineString:
            ends += [g.GetPoint_2D(0), g.GetPoint_2D(g.GetPointCount() - 1)]
    ends = np.array(ends)
    truth_vertices = ring_points(truth, ["building_parts", "parcels", "blocks"])
    dist, nearest = cKDTree(truth_vertices).query(ends)
    position = {}
    for t in range(len(truth_vertices)):
        copies = ends[(nearest == t) & (dist < 0.9)]
        if len(copies):
            position[tuple(truth_vertices[t])] = copies.mean(axis=0)
    return recall(polygons(truth, "building_parts"), position)


def drawing_with_provenance(seed, level):
    """make_cad.py's drawing of the sample: truth edges (all layers, noded), the truth parts, and the
    copies (vertex id or -1 for a split point, truth edge id, x, y)."""
    import make_cad as mc
    rng = random.Random(seed)
    _, blocks, parcels, parts = mc.load(os.path.join(here, "..", "..", "sample_data", "sources", "catastro"), None)
    for _, above, below, _ in parts:
        mc.label_for(above, below, rng)  # the labels draw from the generator first, as in make_cad.main
    layers = {"BLOCKS": mc.noded_segments([p for _, p in blocks]),
              "PARCELS": mc.noded_segments([p for _, p in parcels]),
              "BUILDINGS": mc.noded_segments([p for _, _, _, p in parts])}
    truth_edges = sorted({(min(a, b), max(a, b)) for segs in layers.values() for a, b in segs})
    provenance = {}
    mc.degrade({n: list(v) for n, v in layers.items()}, [], level, rng, provenance)
    vid = {}
    for a, b in truth_edges:
        vid.setdefault(a, len(vid))
        vid.setdefault(b, len(vid))
    edges = [(vid[a], vid[b]) for a, b in truth_edges]
    vertices = np.zeros((len(vid), 2))
    for p, i in vid.items():
        vertices[i] = p
    # The truth edge each drawn segment copies: from its tagged ends (a split point lies on its edge).
    edge_of = {e: k for k, e in enumerate(truth_edges)}
    split_edge = {}
    copies = []
    for segs in provenance.values():
        for a, b, ta, tb in segs:
            k = segment_edge(ta, tb, edge_of, truth_edges, split_edge)
            if k is None:
                continue
            for c, t in ((a, ta), (b, tb)):
                copies.append((vid[t[1]] if t[0] == "v" else -1, k, c[0], c[1]))
    return vertices, edges, vid, copies, polygons_of_parts(parts)


def segment_edge(ta, tb, edge_of, truth_edges, split_edge):
    """The truth edge a drawn segment is (a part of), from the tags of its ends."""
    if ta[0] == "v" and tb[0] == "v":
        return edge_of.get((min(ta[1], tb[1]), max(ta[1], tb[1])))
    ends = [t for t in (ta, tb) if t[0] == "s"]
    if not ends:
        return None
    m = ends[0][1]
    if m not in split_edge:
        # The edge the split point lies on (it was made on exactly one).
        best, bk = 1e300, None
        for k, (a, b) in enumerate(truth_edges):
            ab = (b[0] - a[0], b[1] - a[1])
            l2 = ab[0] ** 2 + ab[1] ** 2
            t = ((m[0] - a[0]) * ab[0] + (m[1] - a[1]) * ab[1]) / l2
            if 0 < t < 1:
                d = abs((m[0] - a[0]) * ab[1] - (m[1] - a[1]) * ab[0]) / math.sqrt(l2)
                if d < best:
                    best, bk = d, k
        split_edge[m] = bk
    return split_edge[m]


def polygons_of_parts(parts):
    out = []
    for _, _, _, p in parts:
        g = p.Clone()
        out.append((g, g.GetEnvelope(), g.GetArea(), {}))
    return out


def fit(vertices, edges, copies, start, split=True, straight=None, right=None, meanobs=False, reach=0.15,
        sig_straight=0.03, sig_right=0.03, huber=1.5, rounds=5):
    """Least-squares placement (reweighted Gauss-Newton) of the vertices: see the module doc."""
    n = len(vertices)
    pos = start.copy()
    adj = [[] for _ in range(n)]
    for a, b in edges:
        adj[a].append(b)
        adj[b].append(a)
    ea = np.array(edges)
    cu = np.array([c[0] for c in copies])
    ck = np.array([c[1] for c in copies])
    cx = np.array([[c[2], c[3]] for c in copies])
    along_w = np.ones(len(copies))
    for _ in range(rounds):
        rows, cols, vals, rhs, w = [], [], [], [], []

        def add(coefs, b, weight):
            r = len(rhs)
            for j, v in coefs:
                rows.append(r)
                cols.append(j)
                vals.append(v)
            rhs.append(b)
            w.append(weight)

        d = pos[ea[:, 1]] - pos[ea[:, 0]]
        length = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-9)
        t = d / length[:, None]
        nrm = np.stack([-t[:, 1], t[:, 0]], 1)
        along = np.zeros(len(copies))
        for i in range(len(copies)):
            u, k, c = cu[i], ck[i], cx[i]
            if u >= 0 and meanobs:
                add([(2 * u, 1.0)], c[0], 1 / SIGMA ** 2)
                add([(2 * u + 1, 1.0)], c[1], 1 / SIGMA ** 2)
            elif u >= 0:
                add([(2 * u, nrm[k][0]), (2 * u + 1, nrm[k][1])], nrm[k] @ c, 1 / SIGMA ** 2)
                along[i] = t[k] @ (c - pos[u])
                add([(2 * u, t[k][0]), (2 * u + 1, t[k][1])], t[k] @ c, along_w[i] / SIGMA ** 2)
            elif split or meanobs:
                a, b = ea[k]
                lam = np.clip(t[k] @ (c - pos[a]) / length[k], 0, 1)
                nk = nrm[k]
                add([(2 * a, nk[0] * (1 - lam)), (2 * a + 1, nk[1] * (1 - lam)), (2 * b, nk[0] * lam),
                     (2 * b + 1, nk[1] * lam)], nk @ c, 1 / SIGMA ** 2)
        r = np.abs(along) / SIGMA
        along_w = np.where(r > huber, huber / np.maximum(r, 1e-9), 1.0)
        for wv in range(n):
            for i in range(len(adj[wv])):
                for j in range(i + 1, len(adj[wv])):
                    u, v = adj[wv][i], adj[wv][j]
                    a, b = pos[u] - pos[wv], pos[v] - pos[wv]
                    la, lb = np.hypot(*a), np.hypot(*b)
                    if la < 1e-9 or lb < 1e-9:
                        continue
                    a, b = a / la, b / lb
                    cos = a @ b
                    angle = math.degrees(math.acos(max(-1.0, min(1.0, cos))))
                    uv = pos[v] - pos[u]
                    luv = np.hypot(*uv)
                    off_line = abs(uv[0] * (pos[wv] - pos[u])[1] - uv[1] * (pos[wv] - pos[u])[0]) / luv
                    if straight and angle >= 180 - straight and off_line <= reach:
                        tt = uv / luv
                        nn = np.array([-tt[1], tt[0]])
                        lam = tt @ (pos[wv] - pos[u]) / luv
                        add([(2 * u, nn[0] * (1 - lam)), (2 * u + 1, nn[1] * (1 - lam)), (2 * v, nn[0] * lam),
                             (2 * v + 1, nn[1] * lam), (2 * wv, -nn[0]), (2 * wv + 1, -nn[1])], 0.0,
                            1 / sig_straight ** 2)
                    if right and abs(angle - 90) <= right and abs(cos) * min(la, lb) <= reach:
                        gu, gv = (b - cos * a) / la, (a - cos * b) / lb
                        gw = -(gu + gv)
                        add([(2 * u, gu[0]), (2 * u + 1, gu[1]), (2 * v, gv[0]), (2 * v + 1, gv[1]),
                             (2 * wv, gw[0]), (2 * wv + 1, gw[1])],
                            gu @ pos[u] + gv @ pos[v] + gw @ pos[wv] - cos, 1 / sig_right ** 2)
        A = sp.csr_matrix((vals, (rows, cols)), shape=(len(rhs), 2 * n))
        W = sp.diags(np.array(w))
        normal = (A.T @ W @ A).tocsc() + sp.identity(2 * n) * 1e-9
        pos = spla.spsolve(normal, A.T @ (W @ np.array(rhs))).reshape(-1, 2)
    return pos


def oracle(seed, level, variants):
    vertices, edges, vid, copies, parts = drawing_with_provenance(seed, level)
    total = np.zeros((len(vertices), 2))
    count = np.zeros(len(vertices))
    for u, _, x, y in copies:
        if u >= 0:
            total[u] += (x, y)
            count[u] += 1
    mean = vertices.copy()
    mean[count > 0] = total[count > 0] / count[count > 0, None]
    out = []
    for name in variants:
        kw = VARIANTS[name]
        pos = mean if kw is None else fit(vertices, edges, copies, mean, **kw)
        position = {p: tuple(pos[i]) for p, i in vid.items()}
        rms = math.sqrt(float(((pos - vertices) ** 2).sum(axis=1).mean()))
        out.append("%s %.3f (rms %.3f m)" % (name, recall(parts, position), rms))
    print("seed %d L%d: " % (seed, level) + "; ".join(out))


def main():
    args = sys.argv[1:]
    if "--seed" in args:
        i = args.index("--seed")
        seed = int(args[i + 1])
        del args[i:i + 2]
        level = 2
        if "--level" in args:
            i = args.index("--level")
            level = int(args[i + 1].lstrip("L"))
            del args[i:i + 2]
        oracle(seed, level, args or list(VARIANTS))
        return
    if len(args) != 2:
        sys.exit(__doc__)
    print("%.3f" % nearest_mean(args[0], args[1]))


if __name__ == "__main__":
    main()
