"""Unit tests: each algorithm's parameters come from the JSON usage, and each builds the exact
argument list expected for given parameter values, without running the program."""

import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import qgis_start  # noqa: E402

APP, PROVIDER = qgis_start.start()

from qgis.core import (  # noqa: E402
    QgsProcessingContext,
    QgsProcessingException,
    QgsProcessingFeatureSourceDefinition,
    QgsProcessingFeedback,
    QgsProcessingOutputRasterLayer,
    QgsProcessingOutputVectorLayer,
    QgsProcessingOutputFile,
    QgsProcessingOutputFolder,
    QgsProcessingParameterDefinition,
    QgsProject,
    QgsUnitTypes,
    QgsVectorLayer,
)
from osgeo import ogr  # noqa: E402
from urbanvec.algorithm import UrbanvecAlgorithm  # noqa: E402
from urbanvec.program import load_usage  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PROGRAM = os.environ['URBANVEC']


def algorithms_of(document):
    algs = {}
    for command in document['commands']:
        alg = UrbanvecAlgorithm(command, lambda: PROGRAM)
        alg.initAlgorithm()
        algs[command['name']] = alg
    return algs


class FixtureTest(unittest.TestCase):
    """The mapping of every argument type and role, on a usage document that declares them all."""

    @classmethod
    def setUpClass(cls):
        with open(os.path.join(HERE, 'fixtures', 'usage_every_kind.json')) as f:
            cls.algs = algorithms_of(json.load(f))
        cls.tmp = tempfile.mkdtemp()
        cls.inputs = qgis_start.make_inputs(cls.tmp)

    def setUp(self):
        self.context = QgsProcessingContext()
        self.context.setProject(QgsProject.instance())
        self.feedback = QgsProcessingFeedback()
        self.alg = self.algs['every-kind']

    def args(self, parameters, alg=None):
        return (alg or self.alg).buildArguments(parameters, self.context, self.feedback)

    def required(self, **extra):
        p = {'GRID': self.inputs['raster'], 'LINES': self.inputs['one.gpkg'],
             'OUTPUT': os.path.join(self.tmp, 'out.gpkg')}
        p.update(extra)
        return p

    def test_parameter_types_defaults_and_bounds(self):
        alg = self.alg
        types = {p.name(): p.type() for p in alg.parameterDefinitions()}
        self.assertEqual(types, {
            'TR': 'distance', 'MIN_AREA': 'number', 'MAX_TRIES': 'number', 'SEED': 'number', 'METHOD': 'enum',
            'NO_WATER': 'boolean', 'TE': 'string', 'A_SRS': 'crs', 'REPORT': 'fileDestination',
            'DENSITY': 'raster', 'LCO': 'string', 'GRID': 'raster', 'LINES': 'source', 'TABLE': 'file',
            'OUTPUT': 'vectorDestination'})
        tr = alg.parameterDefinition('TR')
        self.assertEqual(tr.defaultValue(), 12.0)
        self.assertEqual((tr.minimum(), tr.maximum()), (0.5, 1000.0))
        self.assertEqual(tr.defaultUnit(), QgsUnitTypes.DistanceMeters)
        self.assertIn('[m²]', alg.parameterDefinition('MIN_AREA').description())
        self.assertEqual(alg.parameterDefinition('MAX_TRIES').dataType(), 0)  # Integer
        self.assertTrue(alg.parameterDefinition('MAX_TRIES').flags() & QgsProcessingParameterDefinition.FlagAdvanced)
        method = alg.parameterDefinition('METHOD')
        self.assertEqual(method.options(), ['skeleton', 'obb', 'voronoi'])
        self.assertEqual(method.defaultValue(), 'skeleton')
        self.assertTrue(method.usesStaticStrings())
        self.assertTrue(alg.parameterDefinition('TABLE').flags() & QgsProcessingParameterDefinition.FlagOptional)
        self.assertTrue(alg.parameterDefinition('REPORT').flags() & QgsProcessingParameterDefinition.FlagOptional)
        self.assertFalse(alg.parameterDefinition('OUTPUT').flags() & QgsProcessingParameterDefinition.FlagOptional)
        self.assertIn('Command-line option: -tr.', tr.help())
        self.assertIsNone(alg.parameterDefinition('OVERWRITE'))
        outputs = {o.name(): type(o) for o in alg.outputDefinitions()}
        self.assertEqual(outputs['ROADS'], QgsProcessingOutputVectorLayer)
        self.assertEqual(outputs['PARCELS'], QgsProcessingOutputVectorLayer)
        self.assertEqual(alg.group(), 'Test fixtures')
        self.assertEqual(alg.groupId(), 'test_fixtures')
        self.assertIn('urbanvec every-kind', alg.shortHelpString())

    def test_minimal_arguments_leave_defaults_to_the_program(self):
        self.assertEqual(self.args(self.required()), [
            'every-kind', '-progress', 'lines', '-overwrite',
            self.inputs['raster'], self.inputs['one.gpkg'], os.path.join(self.tmp, 'out.gpkg')])

    def test_every_option(self):
        report = os.path.join(self.tmp, 'report.json')
        table = os.path.join(HERE, 'fixtures', 'usage_every_kind.json')  # any existing file
        parameters = self.required(
            TR=7.5, MIN_AREA=40, MAX_TRIES=3, SEED=1, METHOD='obb', NO_WATER=True,
            TE='500000 4800000, 500040 4800030', A_SRS='EPSG:2154', REPORT=report,
            DENSITY=self.inputs['raster'], LCO='SPATIAL_INDEX=NO|FID=fid', TABLE=table)
        self.assertEqual(self.args(parameters), [
            'every-kind', '-progress', 'lines',
            '-tr', '7.5', '-max-tries', '3', '-method', 'obb', '-no-water',
            '-te', '500000', '4800000', '500040', '4800030', '-a_srs', 'EPSG:2154', '-report', report,
            '-density', self.inputs['raster'], '-lco', 'SPATIAL_INDEX=NO', '-lco', 'FID=fid', '-overwrite',
            self.inputs['raster'], self.inputs['one.gpkg'], table, os.path.join(self.tmp, 'out.gpkg')])

    def test_enum_by_index_and_integer_formatting(self):
        args = self.args(self.required(METHOD=2, MAX_TRIES=4.0, TR=12.0))
        self.assertIn('-method', args)
        self.assertEqual(args[args.index('-method') + 1], 'voronoi')
        self.assertEqual(args[args.index('-max-tries') + 1], '4')
        self.assertNotIn('-tr', args)  # equal to the program's default

    def test_wrong_count_of_values_raises(self):
        with self.assertRaisesRegex(QgsProcessingException, '-te expects 4 values'):
            self.args(self.required(TE='1 2 3'))

    def test_out_of_range_value_is_rejected_before_running(self):
        ok, message = self.alg.checkParameterValues(self.required(TR=0.1), self.context)
        self.assertFalse(ok)

    def test_missing_required_input_raises(self):
        parameters = self.required()
        del parameters['GRID']
        with self.assertRaises(QgsProcessingException):
            self.args(parameters)

    def test_vector_inputs(self):
        one, two = self.inputs['one.gpkg'], self.inputs['two.gpkg']
        # The only layer of a dataset: the dataset itself.
        self.assertEqual(self.args(self.required(LINES=one + '|layername=roads'))[-2], one)
        # One layer of several: exported to a single-layer file.
        exported = self.args(self.required(LINES=two + '|layername=parcels'))[-2]
        self.assertNotEqual(exported, two)
        ds = ogr.Open(exported)
        self.assertEqual(ds.GetLayerCount(), 1)
        self.assertEqual(ds.GetLayer(0).GetFeatureCount(), 1)
        # A project layer with a selection: only the selected features are exported.
        layer = QgsVectorLayer(two + '|layername=roads', 'roads', 'ogr')
        QgsProject.instance().addMapLayer(layer)
        layer.selectAll()
        selected = self.args(self.required(LINES=QgsProcessingFeatureSourceDefinition(layer.id(), True)))[-2]
        self.assertNotEqual(selected, two)
        selected_ds = ogr.Open(selected)
        self.assertEqual(selected_ds.GetLayer(0).GetFeatureCount(), 1)

    def test_folder_destination_is_never_wiped(self):
        alg = self.algs['folder-writer']
        table = os.path.join(HERE, 'fixtures', 'usage_every_kind.json')
        outputs = {o.name(): type(o) for o in alg.outputDefinitions()}
        self.assertEqual(outputs, {'OUTPUT_DIR': QgsProcessingOutputFolder,
                                   'LANDUSE': QgsProcessingOutputRasterLayer,
                                   'PARCELS': QgsProcessingOutputRasterLayer,
                                   'PARCELS_CSV': QgsProcessingOutputFile,
                                   'TRUTH': QgsProcessingOutputVectorLayer})
        new = os.path.join(self.tmp, 'new_folder')
        self.assertEqual(self.args({'INPUT': table, 'OUTPUT_DIR': new}, alg),
                         ['folder-writer', '-progress', 'lines', '-overwrite', table, new])
        ours = os.path.join(self.tmp, 'previous_run')
        os.makedirs(ours)
        open(os.path.join(ours, 'landuse.tif'), 'w').close()
        self.assertIn('-overwrite', self.args({'INPUT': table, 'OUTPUT_DIR': ours}, alg))
        foreign = os.path.join(self.tmp, 'my_documents')
        os.makedirs(foreign)
        open(os.path.join(foreign, 'thesis.odt'), 'w').close()
        with self.assertRaisesRegex(QgsProcessingException, 'is not empty .*thesis.odt'):
            self.args({'INPUT': table, 'OUTPUT_DIR': foreign}, alg)


class ProgramUsageTest(unittest.TestCase):
    """The algorithms built from the real program's --json-usage."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp()
        cls.usage, _ = load_usage(PROGRAM, os.path.join(cls.tmp, 'cache.json'))
        cls.algs = algorithms_of(cls.usage)
        cls.inputs = qgis_start.make_inputs(cls.tmp)

    def setUp(self):
        self.context = QgsProcessingContext()
        self.feedback = QgsProcessingFeedback()

    def test_provider_has_one_algorithm_per_subcommand(self):
        names = sorted(a.name() for a in PROVIDER.algorithms())
        self.assertEqual(names, sorted(c['name'] for c in self.usage['commands']))
        self.assertIn('evaluate', names)

    def test_every_option_is_a_parameter_with_the_program_default(self):
        for command in self.usage['commands']:
            alg = self.algs[command['name']]
            for option in command['options']:
                if option['name'] == '-overwrite':
                    continue
                definition = alg.parameterDefinition(option['name'].lstrip('-').replace('-', '_').upper())
                self.assertIsNotNone(definition, '{} {}'.format(command['name'], option['name']))
                if option['default'] is None:
                    continue
                if option['type'] in ('integer', 'real') and option['arity'] == 1:
                    self.assertEqual(definition.defaultValue(), float(option['default']))
                elif option['type'] in ('choice', 'string'):
                    self.assertEqual(definition.defaultValue(), option['default'])
            # with only the defaults, no option but -progress and -overwrite reaches the command line
            for positional in command['positionals']:
                self.assertIsNotNone(alg.parameterDefinition(positional['name'].upper()))

    def test_evaluate_arguments(self):
        alg = self.algs['evaluate']
        report = os.path.join(self.tmp, 'report.json')
        two, one = self.inputs['two.gpkg'], self.inputs['one.gpkg']
        # evaluate picks its layers by name (-roads-layer ...): a layer of a dataset stands for the dataset.
        parameters = {'RESULT': two + '|layername=parcels', 'TRUTH': one, 'JSON': report, 'CELL_SIZE': 10,
                      'PARCELS_LAYER': 'lots', 'ROADS_LAYER': 'roads'}
        self.assertEqual(alg.buildArguments(parameters, self.context, self.feedback), [
            'evaluate', '-progress', 'lines', '-json', report, '-cell-size', '10', '-parcels-layer', 'lots',
            '-overwrite', two, one])

    def test_shape_metrics_reads_the_layer_picked_in_qgis(self):
        alg = self.algs['shape-metrics']
        two = self.inputs['two.gpkg']
        out = os.path.join(self.tmp, 'metrics.gpkg')
        self.assertEqual(alg.buildArguments({'INPUT': two + '|layername=parcels', 'OUTPUT': out}, self.context),
                         ['shape-metrics', '-progress', 'lines', '-layer', 'parcels', '-overwrite', two, out])
        self.assertEqual(alg.buildArguments({'INPUT': two, 'LAYER': 'roads', 'OUTPUT': out}, self.context),
                         ['shape-metrics', '-progress', 'lines', '-layer', 'roads', '-overwrite', two, out])

    def test_every_dialog_opens_with_acceptable_defaults(self):
        from qgis.gui import QgsGui
        from processing.gui.AlgorithmDialog import AlgorithmDialog
        QgsGui.instance()
        for alg in PROVIDER.algorithms():
            dialog = AlgorithmDialog(alg.create(), False, None)
            wrappers = dialog.mainWidget().wrappers
            for definition in alg.parameterDefinitions():
                if definition.isDestination() or definition.type() in ('raster', 'source'):
                    continue  # layer inputs are empty until the project has layers
                value = wrappers[definition.name()].parameterValue()
                self.assertTrue(definition.checkValueIsAcceptable(value),
                                '{} {}: the dialog shows {!r}'.format(alg.id(), definition.name(), value))
            dialog.deleteLater()

    def test_usage_is_cached_per_program(self):
        cache = os.path.join(self.tmp, 'cache2.json')
        first, from_cache = load_usage(PROGRAM, cache)
        self.assertFalse(from_cache)
        second, from_cache = load_usage(PROGRAM, cache)
        self.assertTrue(from_cache)
        self.assertEqual(first, second)
        with open(cache) as f:
            stored = json.load(f)
        stored['key']['mtime_ns'] -= 1  # the program changed: the cache is not used
        with open(cache, 'w') as f:
            json.dump(stored, f)
        self.assertFalse(load_usage(PROGRAM, cache)[1])


if __name__ == '__main__':
    result = unittest.main(exit=False, verbosity=2).result
    os._exit(0 if result.wasSuccessful() else 1)
