#!/usr/bin/python3
"""City-shrinking measures on an OSM extract and an .osmi file (issue 19 "How it is judged").

Runs `urbanvec shrink` for shF 0.05 / 0.15 / 0.5 x seams 50x50 / 100x100 / 150x150 (imageSize 500),
then the street-realism variants (straightening, rotation trick) at shF 0.15 / 100x100, and prints
Markdown tables of the figures each run stores in its shrink_report layer (the measures are computed
by the library, src/urbanvec/shrink/measures.cpp):

  area kept vs ideal, worst landmark deviation from a pure translation (m), landmark pairs whose
  left-right / above-below order flipped, median change of pairwise bearings (deg), ratio of shrunk to
  original pairwise landmark distances (min / median / max), new crossings, intersections kept,
  components, new dead ends, orientation entropy and right-angle share before/after, mean block area
  of the skeleton before/after and of the whole original street map (the thesis's claim),
  and the pixels frozen so that no seam makes two streets cross or flips two landmarks (the guard).

Usage: bench/shrink/measure.py [--urbanvec build/bin/urbanvec] [--osm FILE] [--osmi FILE] [--out DIR]
"""
import argparse
import os
import subprocess
import sys
import tempfile

from osgeo import ogr

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')


def run(urbanvec, osm, osmi, out, args):
    subprocess.run([urbanvec, 'shrink', '-q', '-overwrite'] + args + [osm, osmi, out], check=True)
    ds = ogr.Open(out)
    f = ds.GetLayer('shrink_report').GetNextFeature()
    return {f.GetFieldDefnRef(i).GetName(): f.GetField(i) for i in range(f.GetFieldCount())}


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--urbanvec', default=os.path.join(ROOT, 'build', 'bin', 'urbanvec'))
    p.add_argument('--osm', default=os.path.join(ROOT, 'sample_data', 'sources', 'monaco.osm.pbf'))
    p.add_argument('--osmi', default=os.path.join(ROOT, 'sample_data', 'monaco', 'monaco.osmi'))
    p.add_argument('--out', default=None, help='folder for the GeoPackages (default: a temporary one)')
    a = p.parse_args()
    out = a.out or tempfile.mkdtemp(prefix='shrink-measures-')
    os.makedirs(out, exist_ok=True)

    print('| shF | seams (removed) | area kept (ideal) | landmark dev. m | order flips x/y | bearing change ° '
          '| distance ratio min/med/max | new crossings | intersections kept | components | new dead ends '
          '| mean block m² before → after (blocks) | city mean block m² (blocks) | pixels frozen: crossings / landmark order |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|')
    for shf in (0.05, 0.15, 0.5):
        for s in (50, 100, 150):
            r = run(a.urbanvec, a.osm, a.osmi, os.path.join(out, 'shf%g_%d.gpkg' % (shf, s)),
                    ['-shf', str(shf), '-seams', str(s), str(s)])
            print('| %g | %d×%d (%d×%d) | %.3f (%.3f) | %.1e | %d/%d | %.1f | %.2f/%.2f/%.2f | %d | %d/%d | %d→%d | %d | %.0f → %.0f (%d) | %.0f (%d) | %d / %d |' % (
                shf, s, s, r['seams_vertical'], r['seams_horizontal'], r['area_kept'], r['area_ideal'], r['landmark_max_deviation'],
                r['order_violations_x'], r['order_violations_y'], r['bearing_change_median'],
                r['distance_ratio_min'], r['distance_ratio_median'], r['distance_ratio_max'],
                r['new_crossings'], r['intersections_kept'], r['intersections_before'],
                r['components_before'], r['components_after'], r['new_dead_ends'],
                r['mean_block_area_before'], r['mean_block_area_after'], r['blocks_after'],
                r.get('mean_block_area_city', 0), r.get('blocks_city', 0),
                r.get('crossing_guard_pixels', r.get('way_separation_pixels', 0)),
                r.get('landmark_order_guard_pixels', 0)))
    print()
    print('| variant (shF 0.15, 100×100) | entropy before → after (nats) | right angles before → after '
          '| median deviation from 90° before → after | new crossings | seams removed |')
    print('|---|---|---|---|---|---|')
    variants = [('default (no post-process)', []), ('-straighten', ['-straighten']),
                ('-rotate auto', ['-rotate', 'auto']), ('-rotate auto -straighten', ['-rotate', 'auto', '-straighten']),
                ('-freeze-all-street-nodes', ['-freeze-all-street-nodes']),
                ('-translate-nodes-only (the thesis)', ['-translate-nodes-only'])]
    for name, extra in variants:
        r = run(a.urbanvec, a.osm, a.osmi, os.path.join(out, 'variant_%d.gpkg' % variants.index((name, extra))),
                ['-shf', '0.15', '-seams', '100', '100'] + extra)
        print('| %s | %.3f → %.3f | %.2f → %.2f | %.1f → %.1f | %d | %d×%d |' % (
            name, r['entropy_before'], r['entropy_after'], r['right_angle_share_before'],
            r['right_angle_share_after'], r['angle_deviation_before'], r['angle_deviation_after'],
            r['new_crossings'], r['seams_vertical'], r['seams_horizontal']))
    print('\n(GeoPackages in %s)' % out, file=sys.stderr)


if __name__ == '__main__':
    main()
