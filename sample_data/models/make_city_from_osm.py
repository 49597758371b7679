"""Writes city_from_osm.model3: the QGIS model chaining urbanvec gridify -> vectorize -> evaluate.

Run with the urbanvec provider loaded (see docs/qgis.md), from the repository root:
    QT_QPA_PLATFORM=offscreen /usr/bin/python3 sample_data/models/make_city_from_osm.py
The model is saved next to this script. Built with the PyQGIS model API rather than by hand so the
file is exactly what QGIS's graphical modeler reads and writes.
"""

import os
import sys

from qgis.core import (
    QgsApplication,
    QgsProcessingModelAlgorithm,
    QgsProcessingModelChildAlgorithm,
    QgsProcessingModelChildParameterSource as Source,
    QgsProcessingModelOutput,
    QgsProcessingModelParameter,
    QgsProcessingParameterDistance,
    QgsProcessingParameterFile,
    QgsUnitTypes,
)
from qgis.PyQt.QtCore import QPointF

HERE = os.path.dirname(os.path.abspath(__file__))


def child(model, algorithm_id, child_id, description, x, y, sources, outputs=None):
    c = QgsProcessingModelChildAlgorithm(algorithm_id)
    c.setChildId(child_id)
    c.setDescription(description)
    c.setPosition(QPointF(x, y))
    for parameter, source in sources.items():
        c.addParameterSources(parameter, [source])
    if outputs:
        model_outputs = {}
        for name, (child_output, description, default) in outputs.items():
            o = QgsProcessingModelOutput(name, description)
            o.setChildId(child_id)
            o.setChildOutputName(child_output)
            o.setPosition(QPointF(x + 180, y + 60))
            if default is not None:
                o.setDefaultValue(default)
            model_outputs[name] = o
        c.setModelOutputs(model_outputs)
    model.addChildAlgorithm(c)
    return c


def build():
    m = QgsProcessingModelAlgorithm('city_from_osm', 'urbanvec')
    m.setHelpContent({
        'ALG_DESC': 'Turns an OpenStreetMap extract into a vector city and measures it: urbanvec gridify makes the '
                    'land-use, density and parcel grids (and the truth vectors), urbanvec vectorize turns the grids '
                    'into roads (and, as the program grows, blocks and parcels), and urbanvec evaluate compares the '
                    'result with the truth.',
        'ALG_CREATOR': 'urbanvec',
        'osm': 'OpenStreetMap extract (.osm.pbf or .osm), e.g. sample_data/sources/monaco.osm.pbf.',
        'cell_size': 'Cell size of the grids, in metres.',
    })
    osm = QgsProcessingParameterFile('osm', 'OpenStreetMap extract', QgsProcessingParameterFile.File, '',
                                     fileFilter='OpenStreetMap (*.osm.pbf *.pbf *.osm)')
    m.addModelParameter(osm, QgsProcessingModelParameter('osm'))
    m.parameterComponent('osm').setPosition(QPointF(120, 60))
    cell = QgsProcessingParameterDistance('cell_size', 'Cell size [m]', 12.0, minValue=0.5)
    cell.setDefaultUnit(QgsUnitTypes.DistanceMeters)
    m.addModelParameter(cell, QgsProcessingModelParameter('cell_size'))
    m.parameterComponent('cell_size').setPosition(QPointF(360, 60))

    child(m, 'urbanvec:gridify', 'gridify', 'Grid the OSM extract', 240, 200, {
        'INPUT': Source.fromModelParameter('osm'),
        'TR': Source.fromModelParameter('cell_size'),
    })  # the grid folder is an intermediate (temporary) output
    child(m, 'urbanvec:vectorize', 'vectorize', 'Vectorize the grid', 240, 360, {
        'LANDUSE': Source.fromChildOutput('gridify', 'LANDUSE'),
        'DENSITY': Source.fromChildOutput('gridify', 'DENSITY'),
        'PARCELS': Source.fromChildOutput('gridify', 'PARCELS'),
        'PARCEL_TABLE': Source.fromChildOutput('gridify', 'PARCELS_CSV'),
    }, {'city': ('OUTPUT', 'Vector city', None)})
    child(m, 'urbanvec:evaluate', 'evaluate', 'Evaluate against the truth', 240, 520, {
        'RESULT': Source.fromChildOutput('vectorize', 'OUTPUT'),
        'TRUTH': Source.fromChildOutput('gridify', 'TRUTH'),
    }, {'report': ('JSON', 'Evaluation report (JSON)', None)})
    return m


def write_model(build, algorithms, filename):
    """Builds the model with the urbanvec provider loaded (so the model knows its children's outputs
    and writes them) and saves it next to this script; exits with an error naming what is missing."""
    app = QgsApplication([], False)
    app.initQgis()
    sys.path[:0] = ['/usr/share/qgis/python/plugins', os.path.join(HERE, '..', '..', 'plugin')]
    from processing.core.Processing import Processing
    Processing.initialize()
    from urbanvec.provider import UrbanvecProvider
    provider = UrbanvecProvider()
    QgsApplication.processingRegistry().addProvider(provider)
    missing = [a for a in algorithms if provider.algorithm(a) is None]
    if missing:
        sys.exit('ERROR: the urbanvec program on PATH lacks ' + ', '.join(missing))
    model = build()
    path = os.path.join(HERE, filename)
    if not model.toFile(path):
        sys.exit('ERROR: cannot write ' + path)
    print(path)
    os._exit(0)


if __name__ == '__main__':
    write_model(build, ('gridify', 'vectorize', 'evaluate'), 'city_from_osm.model3')
