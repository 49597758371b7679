"""Writes city_from_scratch.model3: the QGIS model growing a city from nothing with urbanvec
boundary -> streets -> gridify -> vectorize, ending in parcels.

Run with the urbanvec provider loaded (see docs/qgis.md), from the repository root:
    QT_QPA_PLATFORM=offscreen /usr/bin/python3 sample_data/models/make_city_from_scratch.py
The model is saved next to this script (built with the PyQGIS model API, like city_from_osm).
"""

import os
import sys

from qgis.core import (
    QgsProcessingModelAlgorithm,
    QgsProcessingModelChildParameterSource as Source,
    QgsProcessingModelParameter,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QPointF

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from make_city_from_osm import child, write_model  # noqa: E402  (the same helpers)


def build():
    m = QgsProcessingModelAlgorithm('city_from_scratch', 'urbanvec')
    m.setHelpContent({
        'ALG_DESC': 'Grows a city from nothing: urbanvec boundary draws a realistic city outline (UTM 33N, 6 m '
                    'pixels), urbanvec streets grows major and minor streets inside it from a tensor field '
                    'shaped by the outline, urbanvec gridify turns the streets and their blocks into land-use, '
                    'density and parcel grids, and urbanvec vectorize turns those into roads, blocks and parcels.',
        'ALG_CREATOR': 'urbanvec',
        'seed': 'Seed of the boundary and of the street noise: the same seed gives the same city.',
        'dsep_major': 'Separation of major roads, in metres (minor roads: half of it).',
    })
    seed = QgsProcessingParameterNumber('seed', 'Seed', QgsProcessingParameterNumber.Integer, 3, minValue=0)
    m.addModelParameter(seed, QgsProcessingModelParameter('seed'))
    m.parameterComponent('seed').setPosition(QPointF(120, 60))
    dsep = QgsProcessingParameterNumber('dsep_major', 'Major road separation [m]',
                                        QgsProcessingParameterNumber.Double, 360.0, minValue=10.0)
    m.addModelParameter(dsep, QgsProcessingModelParameter('dsep_major'))
    m.parameterComponent('dsep_major').setPosition(QPointF(360, 60))

    child(m, 'urbanvec:boundary', 'boundary', 'Draw a city boundary', 240, 180, {
        'SEED': Source.fromModelParameter('seed'),
        'A_SRS': Source.fromStaticValue('EPSG:32633'),
        'CELLSIZE': Source.fromStaticValue(6.0),
    })
    child(m, 'urbanvec:streets', 'streets', 'Grow streets inside it', 240, 320, {
        'BOUNDARY': Source.fromChildOutput('boundary', 'OUTPUT'),
        'BOUNDARY_FIELD': Source.fromStaticValue(True),
        'DSEP_MAJOR': Source.fromModelParameter('dsep_major'),
        'SEED': Source.fromModelParameter('seed'),
    }, {'streets': ('OUTPUT', 'Streets, street nodes and blocks', None)})
    child(m, 'urbanvec:gridify', 'gridify', 'Grid the streets and blocks', 240, 460, {
        'INPUT': Source.fromChildOutput('streets', 'OUTPUT'),
        'TR': Source.fromStaticValue(8.0),
        'LANDUSE_LAYER': Source.fromStaticValue('blocks'),
        'LANDUSE_FIELD': Source.fromStaticValue('land_use'),
    })
    child(m, 'urbanvec:vectorize', 'vectorize', 'Vectorize the grid into parcels', 240, 600, {
        'LANDUSE': Source.fromChildOutput('gridify', 'LANDUSE'),
        'DENSITY': Source.fromChildOutput('gridify', 'DENSITY'),
        'PARCELS': Source.fromChildOutput('gridify', 'PARCELS'),
        'PARCEL_TABLE': Source.fromChildOutput('gridify', 'PARCELS_CSV'),
        'SEED': Source.fromModelParameter('seed'),
    }, {'city': ('OUTPUT', 'Vector city (roads, blocks, parcels)', None)})
    return m


if __name__ == '__main__':
    write_model(build, ('boundary', 'streets', 'gridify', 'vectorize'), 'city_from_scratch.model3')
