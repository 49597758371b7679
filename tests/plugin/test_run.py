"""Runs the provider's algorithms in headless PyQGIS: progress, cancellation, errors, warnings,
program lookup and the styling of loaded outputs."""

import os
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import qgis_start  # noqa: E402

APP, PROVIDER = qgis_start.start()

import processing  # noqa: E402
from qgis.core import (  # noqa: E402
    QgsProcessingContext,
    QgsProcessingException,
    QgsProcessingFeedback,
    QgsProcessingOutputLayerDefinition,
    QgsProject,
    QgsSettings,
)
from qgis.core import QgsVectorLayer  # noqa: E402
from urbanvec import program as program_module  # noqa: E402
from urbanvec import styles  # noqa: E402
from urbanvec.runner import ProgramRun, parse_progress  # noqa: E402

PROGRAM = os.environ['URBANVEC']
SOURCE = os.environ['URBANVEC_SOURCE_DIR']
OSM = os.path.join(SOURCE, 'sample_data', 'sources', 'monaco.osm.pbf')
if not os.path.exists(OSM):
    OSM = os.path.join(SOURCE, '..', 'shared', 'data', 'real', 'monaco.osm.pbf')


class RecordingFeedback(QgsProcessingFeedback):
    """Records progress, stages and warnings; cancels once progress reaches `cancel_at` percent."""

    def __init__(self, cancel_at=None):
        super().__init__()
        self.progress_values = []
        self.stages = []
        self.warnings = []
        self.commands = []
        self.cancel_at = cancel_at
        self.cancelled_at = None
        self.progressChanged.connect(self._on_progress)

    def _on_progress(self, value):
        self.progress_values.append(value)
        if self.cancel_at is not None and value >= self.cancel_at and not self.isCanceled():
            self.cancelled_at = time.monotonic()
            self.cancel()

    def setProgressText(self, text):
        self.stages.append(text)
        super().setProgressText(text)

    def pushWarning(self, text):
        self.warnings.append(text)
        super().pushWarning(text)

    def pushCommandInfo(self, text):
        self.commands.append(text)
        super().pushCommandInfo(text)


class ConsoleRendering(RecordingFeedback):
    """Prints into `printed` what qgis_process.bin's console feedback (QGIS 3.22) prints: progress as
    GDAL-style ticks without a newline, each text on a line ending with a newline."""

    def __init__(self):
        super().__init__()
        self.printed = ''
        self.last_tick = -1

    def _on_progress(self, value):
        super()._on_progress(value)
        tick = min(40, max(0, int(value * 0.4)))
        while tick > self.last_tick:
            self.last_tick += 1
            self.printed += str(self.last_tick // 4 * 10) if self.last_tick % 4 == 0 else '.'
        if tick == 40:
            self.printed += ' - done.\n'

    def setProgressText(self, text):
        super().setProgressText(text)
        self.printed += text + '\n'

    def pushConsoleInfo(self, text):
        super().pushConsoleInfo(text)
        self.printed += text + '\n'

    def pushWarning(self, text):
        super().pushWarning(text)
        self.printed += 'WARNING:\t' + text + '\n'


def toolbox_entries():
    """{provider row: [algorithm rows]} of the urbanvec provider in the Processing toolbox's model."""
    from qgis.PyQt.QtCore import QModelIndex, Qt
    from qgis.core import QgsApplication
    from qgis.gui import QgsProcessingToolboxProxyModel
    model = QgsProcessingToolboxProxyModel(None, QgsApplication.processingRegistry())
    model.setFilters(QgsProcessingToolboxProxyModel.FilterToolbox)
    entries = {}
    for row in range(model.rowCount(QModelIndex())):
        provider = model.index(row, 0, QModelIndex())
        if model.data(provider, Qt.DisplayRole) == 'urbanvec':
            entries['urbanvec'] = [model.data(model.index(r, 0, provider), Qt.DisplayRole)
                                   for r in range(model.rowCount(provider))]
    return entries


def running_with(marker):
    """Process ids whose command line mentions `marker` (read from /proc)."""
    found = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open('/proc/{}/cmdline'.format(entry), 'rb') as f:
                if marker.encode() in f.read():
                    found.append(int(entry))
        except OSError:
            pass
    return found


def run(algorithm, parameters, feedback=None):
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    feedback = feedback or RecordingFeedback()
    return processing.run(algorithm, parameters, context=context, feedback=feedback), feedback


class RunTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()

    def test_progress_reaches_100_and_never_goes_backwards(self):
        out = os.path.join(self.tmp, 'grid')
        results, feedback = run('urbanvec:gridify', {'INPUT': OSM, 'OUTPUT_DIR': out, 'TR': 24})
        values = feedback.progress_values
        self.assertGreaterEqual(len(values), 5)
        self.assertEqual(values, sorted(values), 'progress went backwards')
        self.assertEqual(values[-1], 100.0)
        self.assertTrue(all(0.0 <= v <= 100.0 for v in values))
        self.assertGreaterEqual(len(set(feedback.stages)), 3)  # the program's stage names are shown
        self.assertEqual(len(feedback.commands), 1)
        self.assertIn('gridify -progress lines -tr 24 -overwrite', feedback.commands[0])
        self.assertEqual(results['LANDUSE'], os.path.join(out, 'landuse.tif'))
        self.assertEqual(results['TRUTH'], os.path.join(out, 'truth.gpkg'))
        self.assertTrue(os.path.isfile(results['LANDUSE']))

    def test_cancelling_mid_run_stops_the_program_and_leaves_no_output(self):
        out = os.path.join(self.tmp, 'cancelled_grid')
        feedback = RecordingFeedback(cancel_at=20)
        with self.assertRaisesRegex(QgsProcessingException, 'cancelled'):
            run('urbanvec:gridify', {'INPUT': OSM, 'OUTPUT_DIR': out, 'TR': 6}, feedback)
        self.assertIsNotNone(feedback.cancelled_at, 'the run ended before it could be cancelled')
        self.assertLess(max(feedback.progress_values), 100.0)
        self.assertLess(time.monotonic() - feedback.cancelled_at, 15.0)  # SIGTERM, then SIGKILL after 10 s
        self.assertFalse(os.path.exists(out))
        self.assertEqual(os.listdir(self.tmp), [], 'a temporary output was left behind')
        self.assertEqual(running_with(out), [], 'the program is still running')

    def test_bad_input_raises_with_the_programs_message(self):
        inputs = qgis_start.make_inputs(self.tmp)  # QGIS opens two.gpkg fine; the program finds no such layer
        out = os.path.join(self.tmp, 'grid')
        direct = subprocess.run([PROGRAM, 'gridify', '-q', '-roads-layer', 'streets', inputs['two.gpkg'], out],
                                stderr=subprocess.PIPE, check=False)
        self.assertEqual(direct.returncode, 1)
        expected = direct.stderr.decode().strip().splitlines()[-1]
        self.assertRegex(expected, "^ERROR: .*has no layer 'streets'")
        with self.assertRaises(QgsProcessingException) as raised:
            run('urbanvec:gridify', {'INPUT': inputs['two.gpkg'], 'ROADS_LAYER': 'streets', 'OUTPUT_DIR': out})
        self.assertEqual(str(raised.exception), expected[len('ERROR: '):])
        self.assertFalse(os.path.exists(out))

    def test_runner_forwards_warnings_and_errors_line_by_line(self):
        feedback = RecordingFeedback()
        script = ("printf 'PROGRESS 10 read'; sleep 0.3; printf 'ing\\nPROGRESS 5 x\\nPROGRESS 60 work\\n'; "
                  "echo 'Warning: 3 roads were too short' >&2; echo 'ERROR: cannot write out.gpkg' >&2; exit 1")
        runner = ProgramRun('/bin/sh', ['-c', script], feedback)
        with self.assertRaisesRegex(QgsProcessingException, '^cannot write out.gpkg$'):
            runner.run()
        self.assertEqual(feedback.warnings, ['3 roads were too short'])
        self.assertEqual(feedback.progress_values, [10.0, 60.0])
        self.assertEqual(feedback.stages, ['reading', 'x', 'work'])

    def test_progress_lines_become_the_percent_and_the_stage_in_words(self):
        """A PROGRESS line gives setProgress(percent) and setProgressText(stage). In qgis_process the
        percent is printed as ticks without a newline ('0...10'), so a stage must start a new line
        there: ConsoleRendering shows what qgis_process prints (test_program_lookup checks the real
        output), which was '0...10patch cleaning' before."""
        self.assertEqual(parse_progress('PROGRESS 10.0 patch cleaning'), (10.0, 'patch cleaning'))
        self.assertEqual(parse_progress('PROGRESS 0  road   graph '), (0.0, 'road graph'))
        self.assertEqual(parse_progress('PROGRESS 100.0'), (100.0, ''))
        self.assertEqual(parse_progress('PROGRESS 140 done'), (100.0, 'done'))
        self.assertIsNone(parse_progress('PROGRESS10parcels'))
        self.assertIsNone(parse_progress('gridify: 582 roads'))
        lines = ['PROGRESS 0.0 raw blocks', 'PROGRESS 4.0 raw blocks', 'PROGRESS 10.0 patch cleaning',
                 'PROGRESS 30.0 parcels', 'PROGRESS 35.0 parcels']
        for console, expected in (
                (True, 'raw blocks\n0...10\npatch cleaning\n...20...30\nparcels\n..\nWARNING:\tslow\n'),
                (False, 'raw blocks\n0...10patch cleaning\n...20...30parcels\n..WARNING:\tslow\n')):
            feedback = ConsoleRendering()
            runner = ProgramRun('urbanvec', [], feedback, console=console)
            for line in lines:
                runner._on_stdout(line)
            runner._on_stderr('Warning: slow')
            self.assertEqual(feedback.progress_values, [4.0, 10.0, 30.0, 35.0])
            self.assertEqual(feedback.stages, ['raw blocks', 'patch cleaning', 'parcels'])  # words only
            self.assertEqual(feedback.printed, expected)

    def test_a_program_ignoring_sigterm_is_killed_and_its_temporary_output_removed(self):
        out = os.path.join(self.tmp, 'city.gpkg')
        # Like urbanvec inside a long stage: busy, not checking for cancellation, temporary output open.
        script = ('trap "" TERM; touch "{0}/.city.tmp-$$.gpkg" "{0}/.city.tmp-$$.gpkg-journal"; '
                  'echo "PROGRESS 30 working"; while :; do sleep 0.05; done').format(self.tmp)
        feedback = RecordingFeedback(cancel_at=30)
        runner = ProgramRun('/bin/sh', ['-c', script], feedback, temporary_outputs=[out])
        runner.terminate_grace_ms = 500
        start = time.monotonic()
        with self.assertRaisesRegex(QgsProcessingException, 'cancelled'):
            runner.run()
        self.assertLess(time.monotonic() - start, 5.0)
        self.assertEqual(os.listdir(self.tmp), [])

    def test_program_comes_from_the_setting_else_the_install_prefix_else_path(self):
        settings = QgsSettings()
        key = '/Processing/Configuration/' + program_module.PROGRAM_SETTING
        missing = os.path.join(self.tmp, 'missing-urbanvec')
        try:
            settings.setValue(key, PROGRAM)
            program, usage, skipped = program_module.resolve()
            self.assertEqual((program, skipped), (os.path.abspath(PROGRAM), []))
            self.assertIn('gridify', [c['name'] for c in usage['commands']])
            settings.setValue(key, missing)  # a setting that does not work is named, and PATH is used
            program, _, skipped = program_module.resolve()
            self.assertEqual(os.path.realpath(program), os.path.realpath(PROGRAM))
            self.assertEqual(skipped, ['the plugin setting ({}): {} does not exist'.format(
                program_module.SETTING_PLACE, missing)])
        finally:
            settings.remove(key)
        self.assertEqual(os.path.realpath(program_module.find_program()), os.path.realpath(PROGRAM))  # from PATH
        # The prefix `cmake --install` put the plugin under (CMakeLists.txt: share/qgis/python/plugins).
        self.assertEqual(program_module.install_prefix('/opt/uv/share/qgis/python/plugins/urbanvec'), '/opt/uv')
        self.assertEqual(program_module.install_prefix('/share/qgis/python/plugins/urbanvec'), '/')
        self.assertIsNone(program_module.install_prefix(os.path.join(SOURCE, 'plugin', 'urbanvec')))
        self.assertIsNone(program_module.install_prefix(
            os.path.expanduser('~/.local/share/QGIS/QGIS3/profiles/default/python/plugins/urbanvec')))

    def test_without_a_program_the_provider_has_a_placeholder_saying_why(self):
        old_path = os.environ['PATH']
        os.environ['PATH'] = os.pathsep.join(
            d for d in old_path.split(os.pathsep) if not os.path.exists(os.path.join(d, 'urbanvec')))
        try:
            with self.assertRaises(program_module.ProgramNotFound) as raised:
                program_module.resolve()
            message = str(raised.exception)
            self.assertTrue(message.startswith('No usable urbanvec program was found'), message)
            self.assertIn('3. PATH ({}): no urbanvec in its folders\n'.format(os.environ['PATH']), message)
            PROVIDER.refreshAlgorithms()
            self.assertEqual([a.id() for a in PROVIDER.algorithms()], ['urbanvec:program_not_found'])
            self.assertEqual(PROVIDER.longName(), 'urbanvec (program not found)')
            self.assertEqual(PROVIDER.algorithms()[0].shortHelpString(), message)
            # What the Processing toolbox shows (it hides a provider without algorithms).
            self.assertEqual(toolbox_entries(), {'urbanvec': ['urbanvec program not found (open for how to fix it)']})
            with self.assertRaisesRegex(QgsProcessingException, '^No usable urbanvec program was found'):
                run('urbanvec:program_not_found', {})
        finally:
            os.environ['PATH'] = old_path
            PROVIDER.refreshAlgorithms()
        self.assertIn('urbanvec:gridify', [a.id() for a in PROVIDER.algorithms()])
        self.assertTrue(PROVIDER.longName().startswith('urbanvec '), PROVIDER.longName())

    def gridify(self, cell_size=24):
        grid = os.path.join(self.tmp, 'grid')
        subprocess.run([PROGRAM, 'gridify', '-q', '-tr', str(cell_size), OSM, grid], check=True)
        return grid

    def test_loaded_outputs_carry_the_land_use_styling(self):
        grid = self.gridify()
        project = QgsProject.instance()
        project.removeAllMapLayers()
        city = os.path.join(self.tmp, 'city.gpkg')
        results = processing.runAndLoadResults('urbanvec:vectorize', {
            'LANDUSE': os.path.join(grid, 'landuse.tif'), 'DENSITY': os.path.join(grid, 'density.tif'),
            'PARCELS': os.path.join(grid, 'parcels.tif'), 'PARCEL_TABLE': os.path.join(grid, 'parcels.csv'),
            'OUTPUT': QgsProcessingOutputLayerDefinition(city, project)})
        self.assertEqual(results['ROADS'], city + '|layername=roads')
        from osgeo import ogr
        dataset = ogr.Open(city)
        written = {dataset.GetLayer(i).GetName() for i in range(dataset.GetLayerCount())}
        dataset = None
        loaded = {layer.name(): layer for layer in project.mapLayers().values()}
        self.assertIn('roads', loaded)
        self.assertIn('road_nodes', loaded)
        roads = loaded['roads'].renderer()
        self.assertEqual(roads.type(), 'categorizedSymbol')
        self.assertEqual(roads.classAttribute(), 'road_class')
        if 'parcels' in written:  # once vectorize writes parcels, they are loaded styled by land use
            parcels = loaded['parcels'].renderer()
            self.assertEqual(parcels.type(), 'categorizedSymbol')
            self.assertEqual(parcels.classAttribute(), 'land_use')
        # Only the requested layers are opened, one per layer of the GeoPackage, nothing else.
        self.assertEqual(sorted(loaded), sorted(written - {'layer_styles'}))

    def test_parcels_style_stored_in_the_geopackage_else_shipped(self):
        grid = self.gridify()
        truth = os.path.join(grid, 'truth.gpkg')  # written with layer_styles by the program
        stored = QgsVectorLayer(truth + '|layername=parcels', 'parcels', 'ogr')
        self.assertEqual(styles.apply_style(stored), 'stored')
        self.assertEqual(stored.renderer().type(), 'categorizedSymbol')
        self.assertEqual(stored.renderer().classAttribute(), 'land_use')
        from osgeo import gdal
        bare = os.path.join(self.tmp, 'parcels.gpkg')  # the same parcels without layer_styles
        gdal.VectorTranslate(bare, truth, layers=['parcels'])
        shipped = QgsVectorLayer(bare + '|layername=parcels', 'parcels', 'ogr')
        self.assertEqual(styles.apply_style(shipped), 'shipped')
        renderer = shipped.renderer()
        self.assertEqual(renderer.classAttribute(), 'land_use')
        colours = {c.value(): c.symbol().color().name() for c in renderer.categories()}
        self.assertEqual(colours['residential'], '#f6e05e')
        self.assertEqual(colours['park'], '#5ab45a')
        self.assertEqual(colours['undeveloped'], '#ffffff')
        # The land-use grid gets the class colours.
        from qgis.core import QgsRasterLayer
        grid_layer = QgsRasterLayer(os.path.join(grid, 'landuse.tif'), 'landuse')
        self.assertEqual(styles.apply_style(grid_layer), 'shipped')
        palette = grid_layer.renderer()
        self.assertEqual(palette.type(), 'paletted')
        self.assertEqual({c.value: c.color.name() for c in palette.classes()}[4], '#f6e05e')


if __name__ == '__main__':
    result = unittest.main(exit=False, verbosity=2).result
    os._exit(0 if result.wasSuccessful() else 1)
