#!/usr/bin/python3
"""Before/after figures of city shrinking for docs/shrink.md (Monaco by default).

Runs `urbanvec shrink` with no seam (the skeleton in place) and with the given seams, and draws:
  docs/figures/shrink_monaco.png  left: original full map (grey), skeleton (black/red), landmarks
                                  (orange) and the removed seams (magenta); right: the shrunk city with
                                  the deformed full map (grey), same scale.
Usage: bench/shrink/figures.py [--urbanvec build/bin/urbanvec] [--shf 0.15] [--seams 100 100]
"""
import argparse
import os
import subprocess
import tempfile

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
from osgeo import ogr

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')


def lines(ds, layer, where=None):
    out = []
    for f in ds.GetLayer(layer):
        if where and not where(f):
            continue
        g = f.GetGeometryRef()
        if g.GetGeometryName() == 'POLYGON':
            g = g.GetGeometryRef(0)
        pts = [g.GetPoint_2D(i) for i in range(g.GetPointCount())]
        if pts:
            out.append(pts)
    return out


def draw(ax, ds, title, seams=None):
    for pts in lines(ds, 'full_streets'):
        ax.plot([p[0] for p in pts], [p[1] for p in pts], color='#c8c8c8', lw=0.4)
    if seams:
        for pts in lines(seams, 'seams'):
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color='#e040e0', lw=0.3, alpha=0.25)
    for f in ds.GetLayer('streets'):
        g = f.GetGeometryRef()
        pts = [g.GetPoint_2D(i) for i in range(g.GetPointCount())]
        important = f.GetField('kind') == 'important'
        ax.plot([p[0] for p in pts], [p[1] for p in pts], color='#c81e1e' if important else '#202020',
                lw=1.4 if important else 0.8)
    for pts in lines(ds, 'places'):
        ax.fill([p[0] for p in pts], [p[1] for p in pts], color='#f0a028', alpha=0.85)
    for pts in lines(ds, 'place_lines'):
        ax.plot([p[0] for p in pts], [p[1] for p in pts], color='#f0a028', lw=2.0)
    for pts in lines(ds, 'place_points'):
        ax.plot(pts[0][0], pts[0][1], 'o', color='#f0a028', ms=6)
    ax.set_title(title, fontsize=10)
    ax.set_aspect('equal')
    ax.set_xticks([])
    ax.set_yticks([])


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--urbanvec', default=os.path.join(ROOT, 'build', 'bin', 'urbanvec'))
    p.add_argument('--osm', default=os.path.join(ROOT, 'sample_data', 'sources', 'monaco.osm.pbf'))
    p.add_argument('--osmi', default=os.path.join(ROOT, 'sample_data', 'monaco', 'monaco.osmi'))
    p.add_argument('--shf', default='0.15')
    p.add_argument('--seams', nargs=2, default=['100', '100'])
    p.add_argument('--extra', default='', help='more shrink options in one string, e.g. --extra="-rotate auto"')
    p.add_argument('--out', default=os.path.join(ROOT, 'docs', 'figures', 'shrink_monaco.png'))
    a = p.parse_args()
    tmp = tempfile.mkdtemp()
    before, after = os.path.join(tmp, 'before.gpkg'), os.path.join(tmp, 'after.gpkg')
    base = [a.urbanvec, 'shrink', '-q', '-shf', a.shf] + a.extra.split()
    subprocess.run(base + ['-seams', '0', '0', a.osm, a.osmi, before], check=True)
    subprocess.run(base + ['-seams'] + a.seams + [a.osm, a.osmi, after], check=True)
    b, s = ogr.Open(before), ogr.Open(after)
    fig, axes = plt.subplots(1, 2, figsize=(11, 6.5), sharex=True, sharey=True)
    draw(axes[0], b, 'before: skeleton (shF %s %s)\nand the %s×%s removed seams (magenta)' % (a.shf, a.extra, a.seams[0], a.seams[1]), s)
    draw(axes[1], s, 'shrunk: landmarks translated, full map deformed (grey)')
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(a.out)


if __name__ == '__main__':
    main()
