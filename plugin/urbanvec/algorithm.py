"""One Processing algorithm per urbanvec subcommand, built from the subcommand's JSON usage."""

import html
import os

from qgis.core import (
    QgsProcessing,
    QgsProcessingParameterNumber,
    QgsProcessingAlgorithm,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProcessingOutputFile,
    QgsProcessingOutputRasterLayer,
    QgsProcessingOutputVectorLayer,
    QgsProcessingUtils,
)

from .arguments import Argument, parameter_name
from .runner import ProgramRun
from . import styles

#: What a folder output holds when its command names no files: the gridded input of vectorize
#: (CONVENTIONS.md "Gridded input"), the only kind of folder urbanvec writes.
GRID_FOLDER_FILES = ['landuse.tif', 'density.tif', 'parcels.tif', 'parcels.csv', 'truth.gpkg']

_RASTER_EXTENSIONS = ('.tif', '.tiff', '.vrt', '.img')

#: Tiled mode of vectorize (issue 22, docs/scale.md): with TILED_WORKERS > 0 the algorithm runs
#: `urbanvec-tiles run --local N -tile T -halo H` (installed beside the program) instead of one run.
TILED_WORKERS, TILE_CELLS, HALO_CELLS = 'TILED_WORKERS', 'TILE_CELLS', 'HALO_CELLS'


def tiles_program(program):
    """urbanvec-tiles beside the program (installed), or in the source tree's tools/ (build/bin)."""
    folder = os.path.dirname(os.path.abspath(program))
    for candidate in (os.path.join(folder, 'urbanvec-tiles'),
                      os.path.join(folder, '..', '..', 'tools', 'urbanvec-tiles')):
        if os.path.isfile(candidate):
            return os.path.normpath(candidate)
    raise QgsProcessingException('tiled mode needs urbanvec-tiles beside {} (cmake --install puts it there)'.format(
        program))
_VECTOR_EXTENSIONS = ('.gpkg', '.shp', '.geojson', '.fgb', '.sqlite')


def _group_id(group):
    return ''.join(c if c.isalnum() else '_' for c in (group or 'other').lower()).strip('_') or 'other'


def _display_name(name):
    words = name.replace('_', ' ').replace('-', ' ')
    return words[:1].upper() + words[1:]


class LayerOutput:
    """A layer (in a vector output) or a file (in an output folder) the command declares it writes."""

    def __init__(self, name, layer, argument):
        self.name = name        # Processing output name, e.g. PARCELS
        self.layer = layer      # 'parcels' or 'landuse.tif'
        self.argument = argument  # the destination argument it lives in

    @property
    def is_file(self):
        return self.argument.role == 'output_folder'

    def location(self, destination):
        """The layer's URI (or file path) inside the written destination."""
        if self.is_file:
            return os.path.join(destination, self.layer)
        return '{}|layername={}'.format(destination, self.layer)

    def exists(self, destination):
        if self.is_file:
            return os.path.exists(self.location(destination))
        return styles.dataset_has_layer(destination, self.layer)

    def output_definition(self):
        extension = os.path.splitext(self.layer)[1].lower()
        description = '{} ({})'.format(_display_name(os.path.splitext(self.layer)[0]),
                                       'file' if self.is_file else 'layer')
        if self.is_file and extension in _RASTER_EXTENSIONS:
            return QgsProcessingOutputRasterLayer(self.name, description)
        if self.is_file and extension not in _VECTOR_EXTENSIONS:
            return QgsProcessingOutputFile(self.name, description)
        return QgsProcessingOutputVectorLayer(self.name, description, QgsProcessing.TypeVectorAnyGeometry)

    @property
    def is_raster(self):
        return self.is_file and os.path.splitext(self.layer)[1].lower() in _RASTER_EXTENSIONS


class UrbanvecAlgorithm(QgsProcessingAlgorithm):
    """Runs `urbanvec <command>`; everything it shows comes from the command's JSON usage."""

    def __init__(self, command, program_locator):
        super().__init__()
        self.command = command
        self._program_locator = program_locator
        self.arguments = []
        self.layer_outputs = []
        used = set()

        def unique(raw):
            name = parameter_name(raw)
            while name in used:
                name += '_'
            used.add(name)
            return name

        for spec in command.get('options', []):
            self.arguments.append(Argument(spec, False, unique(spec['name'])))
        for spec in command.get('positionals', []):
            self.arguments.append(Argument(spec, True, unique(spec['name'])))
        picks_layers = any(a.flag and a.flag.endswith('-layer') for a in self.arguments)
        for argument in self.arguments:
            argument.picks_layers_by_name = picks_layers
        destination = next((a for a in self.arguments if a.positional and a.role in ('output_vector', 'output_folder')),
                           None)
        if destination is not None:
            declared = list(command.get('output_layers', []))
            if destination.role == 'output_folder' and not any(os.path.splitext(l)[1] for l in declared):
                declared = GRID_FOLDER_FILES  # the names are layers of a file in it, not files
            stems = []
            for layer in declared:
                stem, extension = os.path.splitext(layer)
                raw = stem if stem not in stems else stem + '_' + extension.lstrip('.')
                stems.append(stem)
                name = parameter_name(raw)
                if name in used:
                    name = 'OUTPUT_' + name
                used.add(name)
                self.layer_outputs.append(LayerOutput(name, layer, destination))

    # -- identity -------------------------------------------------------------------------------
    def createInstance(self):
        return UrbanvecAlgorithm(self.command, self._program_locator)

    def name(self):
        return self.command['name']

    def displayName(self):
        return _display_name(self.command['name'])

    def group(self):
        return self.command.get('group') or 'Other'

    def groupId(self):
        return _group_id(self.command.get('group'))

    def tags(self):
        words = ['urbanvec', self.command['name'], 'urban', 'city', 'land use']
        return words + [w for w in self.command.get('summary', '').lower().replace(',', ' ').split() if len(w) > 3]

    def shortDescription(self):
        return self.command.get('summary', '')

    def shortHelpString(self):
        parts = []
        if self.command.get('summary'):
            parts.append('<p><b>{}</b></p>'.format(html.escape(self.command['summary'])))
        for paragraph in (self.command.get('description') or '').split('\n\n'):
            if paragraph.strip():
                parts.append('<p>{}</p>'.format(html.escape(paragraph.strip())))
        rows = []
        for argument in self.arguments:
            if argument.flag == '-overwrite':
                continue
            rows.append('<li><b>{}</b> ({}): {}</li>'.format(
                html.escape(argument.definition().description()),
                html.escape(argument.flag or '<{}>'.format(argument.spec['name'])),
                html.escape(argument.definition().help())))
        if rows:
            parts.append('<p>Parameters:</p><ul>{}</ul>'.format(''.join(rows)))
        if self.layer_outputs:
            parts.append('<p>Outputs: {}.</p>'.format(html.escape(', '.join(o.layer for o in self.layer_outputs))))
        parts.append('<p>Runs <code>urbanvec {}</code>; see <code>urbanvec {} --help</code>.</p>'.format(
            html.escape(self.name()), html.escape(self.name())))
        return '\n'.join(parts)

    def flags(self):
        # The program is its own process: the algorithm may run in a background thread and be cancelled.
        return super().flags() | QgsProcessingAlgorithm.FlagCanCancel

    # -- parameters and outputs -----------------------------------------------------------------
    def initAlgorithm(self, config=None):
        for argument in self.arguments:
            if argument.flag == '-overwrite':
                continue  # Processing overwrites its destinations; see buildArguments
            self.addParameter(argument.definition())
        for output in self.layer_outputs:
            self.addOutput(output.output_definition())
        if self.name() == 'vectorize':
            for name, text, default, minimum, advanced in (
                    (TILED_WORKERS, 'Tiled mode: local Dask workers (0 = one run on the whole grid)', 0, 0, False),
                    (TILE_CELLS, 'Tiled mode: tile size', 1024, 1, True),
                    (HALO_CELLS, 'Tiled mode: halo around each tile', 256, 0, True)):
                p = QgsProcessingParameterNumber(name, text, QgsProcessingParameterNumber.Integer, default, True,
                                                 minimum)
                if advanced:
                    p.setFlags(p.flags() | p.FlagAdvanced)
                self.addParameter(p)

    def _tiled(self, parameters, context):
        if self.name() != 'vectorize' or TILED_WORKERS not in parameters:
            return 0
        return self.parameterAsInt(parameters, TILED_WORKERS, context)

    def _overwrite_argument(self):
        return next((a for a in self.arguments if a.flag == '-overwrite'), None)

    def buildArguments(self, parameters, context, feedback=None):
        """The program's argument list (after the program path) for these parameter values."""
        return self._prepare(parameters, context, feedback)[0]

    def _prepare(self, parameters, context, feedback):
        """(argument list, {destination parameter: path}); every value is resolved once, because a
        temporary destination gets a new name each time it is resolved."""
        options = []
        positionals = []
        destinations = {}
        for argument in self.arguments:
            if argument.flag == '-overwrite':
                continue
            words = argument.arguments(self, parameters, context, feedback)
            if argument.is_destination and words:
                destinations[argument.name] = words[-1]
            (positionals if argument.positional else options).extend(words)
        # A layer picked in QGIS from a dataset of several, for a command reading one layer named by
        # -layer: the dataset goes through and -layer names the layer (unless set explicitly).
        layer_option = next((a for a in self.arguments if a.flag == '-layer'), None)
        inputs = [a for a in self.arguments if a.positional and a.role == 'input_vector']
        if layer_option is not None and len(inputs) == 1 and inputs[0].picked_layer \
                and layer_option.flag not in options:
            options += [layer_option.flag, inputs[0].picked_layer]
        overwrite = self._overwrite_argument()
        if overwrite is not None and self._may_overwrite(destinations):
            options.append(overwrite.flag)
        return [self.name(), '-progress', 'lines'] + options + positionals, destinations

    def _may_overwrite(self, destinations):
        """Destinations are replaced as Processing does, but a folder is replaced only when it is empty
        or holds nothing but what this command writes, so a user's folder is never wiped."""
        for argument in self.arguments:
            # An output folder given as an argument is replaced as a whole; one given to an option
            # (e.g. -debug-stages) only receives files.
            if argument.role != 'output_folder' or not argument.positional or argument.name not in destinations:
                continue
            folder = destinations[argument.name]
            if folder and os.path.isdir(folder):
                ours = {o.layer for o in self.layer_outputs if o.argument is argument}
                foreign = [e for e in os.listdir(folder) if e not in ours]
                if foreign:
                    raise QgsProcessingException(
                        'output folder {} is not empty (it holds {}); choose a new or empty folder'.format(
                            folder, ', '.join(sorted(foreign)[:3]) + (', …' if len(foreign) > 3 else '')))
        return True

    def processAlgorithm(self, parameters, context, feedback):
        program = self._program_locator()
        arguments, destinations = self._prepare(parameters, context, feedback)
        workers = self._tiled(parameters, context)
        if workers > 0:
            # urbanvec-tiles run takes the vectorize options and positionals as they are.
            program, arguments = tiles_program(program), [
                'run', '--local', str(workers), '-tile', str(self.parameterAsInt(parameters, TILE_CELLS, context)),
                '-halo', str(self.parameterAsInt(parameters, HALO_CELLS, context))] + arguments[1:]
        ProgramRun(program, arguments, feedback, temporary_outputs=list(destinations.values())).run()

        results = dict(destinations)
        for output in self.layer_outputs:
            destination = destinations.get(output.argument.name)
            if destination and output.exists(destination):
                results[output.name] = output.location(destination)
        self._load_outputs(context, results)
        return results

    def _load_outputs(self, context, results):
        """When the user asked to open an output, opens each layer written into it (not just the
        dataset's first layer, which is what Processing would do), styled by land use."""
        from .arguments import dataset_path
        pending = context.layersToLoadOnCompletion()
        requested = {}  # destination parameter -> project to load into
        for argument in self.arguments:
            destination = results.get(argument.name)
            if not destination:
                continue
            if argument.role not in ('output_vector', 'output_raster'):
                continue  # file and folder destinations are never opened by Processing
            for key in list(pending):
                if dataset_path(key) == destination:
                    details = pending[key]
                    if argument.role == 'output_vector' and any(o.argument is argument for o in self.layer_outputs):
                        requested[argument.name] = details.project
                        del pending[key]
                    else:
                        details.setPostProcessor(styles.post_processor())
                        pending[key] = details
        context.setLayersToLoadOnCompletion(pending)
        for output in self.layer_outputs:
            project = requested.get(output.argument.name)
            if project is None or output.name not in results:
                continue
            hint = QgsProcessingUtils.LayerHint.Raster if output.is_raster else QgsProcessingUtils.LayerHint.Vector
            details = QgsProcessingContext.LayerDetails(os.path.splitext(output.layer)[0], project, output.name, hint)
            details.setPostProcessor(styles.post_processor())
            context.addLayerToLoadOnCompletion(results[output.name], details)
