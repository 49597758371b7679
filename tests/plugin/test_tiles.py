"""The vectorize algorithm's tiled mode (issue 22): TILED_WORKERS > 0 runs urbanvec-tiles on a local Dask
cluster, and the roads equal those of one run."""

import os
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import qgis_start  # noqa: E402

APP, PROVIDER = qgis_start.start()

import processing  # noqa: E402
from qgis.core import QgsApplication  # noqa: E402

PROGRAM = os.environ['URBANVEC']
SOURCE = os.environ['URBANVEC_SOURCE_DIR']
GRID = os.path.join(SOURCE, 'sample_data', 'bubenec')
TILES = os.path.join(SOURCE, 'tools', 'urbanvec-tiles')


def digests(path, layers):
    out = subprocess.run(['/usr/bin/python3', TILES, 'digest', path], stdout=subprocess.PIPE, text=True,
                         check=True).stdout.split('\n')
    return [line for line in out if line.split(' ')[0] in layers]


class TiledVectorize(unittest.TestCase):
    def test_the_tiled_mode_is_a_parameter_and_gives_the_single_runs_roads(self):
        alg = QgsApplication.processingRegistry().algorithmById('urbanvec:vectorize')
        names = [p.name() for p in alg.parameterDefinitions()]
        for name in ('TILED_WORKERS', 'TILE_CELLS', 'HALO_CELLS', 'SRCWIN'):
            self.assertIn(name, names)
        tmp = tempfile.mkdtemp()
        single = os.path.join(tmp, 'single.gpkg')
        tiled = os.path.join(tmp, 'tiled.gpkg')
        common = {'LANDUSE': os.path.join(GRID, 'landuse.tif'), 'ROADS_ONLY': True, 'NO_THROUGH_ROADS': True}
        processing.run('urbanvec:vectorize', dict(common, OUTPUT=single))
        processing.run('urbanvec:vectorize', dict(common, OUTPUT=tiled, TILED_WORKERS=2, TILE_CELLS=50,
                                                  HALO_CELLS=32))
        layers = ('roads', 'road_nodes')
        self.assertEqual(len(digests(tiled, layers)), 2)
        self.assertEqual(digests(tiled, layers), digests(single, layers))


if __name__ == '__main__':
    unittest.main(verbosity=2)
