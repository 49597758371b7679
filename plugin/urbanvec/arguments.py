"""From one argument of `urbanvec <sub> --json-usage` to a QGIS Processing parameter, and from that
parameter's value back to command-line arguments.

Options become parameters named after the option without its dash, upper-cased (`-min-area` ->
MIN_AREA); positionals after their name (`output_dir` -> OUTPUT_DIR). An option is written on the
command line only when its value differs from the program's default, so the logged command stays
short and the program's own defaults stay authoritative.
"""

import os
import re

from qgis.core import (
    QgsProcessing,
    QgsProcessingException,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterDefinition,
    QgsProcessingParameterDistance,
    QgsProcessingParameterEnum,
    QgsProcessingFeatureSourceDefinition,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterDestination,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
    QgsProcessingParameterVectorDestination,
    QgsProcessingOutputLayerDefinition,
    QgsProviderRegistry,
    QgsUnitTypes,
)

#: Separator of several values in one text parameter (repeatable options such as -lco), as in GDAL's provider.
MULTI_VALUE_SEPARATOR = '|'

#: File dialog filters by extension, for file parameters whose metavar names a file type.
_FILTERS = {
    'gpkg': 'GeoPackage (*.gpkg)',
    'json': 'JSON files (*.json)',
    'csv': 'CSV files (*.csv)',
    'tif': 'GeoTIFF (*.tif *.tiff)',
    'pbf': 'OpenStreetMap (*.osm.pbf *.pbf *.osm)',
    'osm': 'OpenStreetMap (*.osm *.osm.pbf *.pbf)',
    'geojson': 'GeoJSON (*.geojson)',
    'html': 'HTML files (*.html)',
    'txt': 'Text files (*.txt)',
}
_ALL_FILES = 'All files (*.*)'

_INT32_MIN, _INT32_MAX = -2147483648.0, 2147483647.0

_UNIT_LABELS = {'m': 'm', 'm2': 'm²', 'm^2': 'm²', 'degrees': '°'}


def parameter_name(raw):
    """'-min-area' -> 'MIN_AREA', 'output_dir' -> 'OUTPUT_DIR'."""
    name = re.sub(r'[^A-Za-z0-9]+', '_', raw.lstrip('-')).strip('_').upper()
    return name or 'VALUE'


def format_number(value, integer):
    if integer:
        return str(int(round(float(value))))
    text = repr(float(value))
    return text[:-2] if text.endswith('.0') else text


def _extension_from_metavar(metavar):
    match = re.search(r'\.([A-Za-z0-9]+)>?$', metavar or '')
    return match.group(1).lower() if match else ''


def _file_filter(metavar, fallback_extension=''):
    extension = _extension_from_metavar(metavar) or fallback_extension
    if extension in _FILTERS:
        return _FILTERS[extension] + ';;' + _ALL_FILES
    return _ALL_FILES


def _first_clause(text):
    """The help up to its first sentence end or semicolon outside brackets ('e.g.', 'Eq. 3' and
    '(1 = exact. ...)' do not end it)."""
    depth = 0
    for i, c in enumerate(text):
        if c in '([':
            depth += 1
        elif c in ')]':
            depth = max(0, depth - 1)
        elif depth == 0 and c == ';':
            return text[:i].strip()
        elif depth == 0 and c == '.' and (i + 1 == len(text) or (
                text[i + 1] == ' ' and i + 2 < len(text) and text[i + 2].isupper())):
            return text[:i].strip()
    return text.strip().rstrip('.')


def _label(spec):
    """Short parameter label from the one-sentence help, with the unit in brackets."""
    text = (spec.get('help') or '').strip() or spec['name'].lstrip('-').replace('-', ' ').replace('_', ' ')
    first = _first_clause(text)
    if len(first) > 80:
        first = first[:77].rsplit(' ', 1)[0] + '…'
    first = first[0].upper() + first[1:] if first else first
    unit = spec.get('unit') or ''
    if unit and '[' not in first:
        first += ' [{}]'.format(_UNIT_LABELS.get(unit, unit))
    return first


def _help(spec, flag):
    parts = [(spec.get('help') or '').strip()]
    if spec.get('unit'):
        parts.append('Unit: {}.'.format(spec['unit']))
    if spec.get('default') not in (None, ''):
        parts.append('Default: {}.'.format(spec['default']))
    if flag:
        parts.append('Command-line option: {}.'.format(flag))
    return ' '.join(p for p in parts if p)


class Argument:
    """One positional or option of a command and the parameter that stands for it."""

    def __init__(self, spec, positional, name):
        self.spec = spec
        self.positional = positional
        self.name = name
        self.flag = None if positional else spec['name']
        self.role = spec.get('role') or ''
        self.type = spec.get('type', 'string') if not positional else 'string'
        self.arity = int(spec.get('arity', 1)) if not positional else 1
        self.repeatable = bool(spec.get('repeatable')) if not positional else False
        self.default = spec.get('default') if not positional else None
        self.choices = list(spec.get('choices') or [])
        self.optional = bool(spec.get('optional')) if positional else self.default in (None, '')
        #: Set by the algorithm when the command chooses layers itself (options such as -roads-layer).
        self.picks_layers_by_name = False
        #: For a vector input: the layer picked in QGIS when its whole dataset is passed, else None.
        self.picked_layer = None

    @property
    def is_destination(self):
        return self.role in ('output_vector', 'output_raster', 'output_folder', 'output_file')

    # -- parameter definition -------------------------------------------------------------------
    def definition(self):
        spec = self.spec
        label = _label(spec)
        role = self.role
        optional = self.optional
        default = self.default
        if role == 'input_raster':
            p = QgsProcessingParameterRasterLayer(self.name, label, optional=optional)
        elif role == 'input_vector':
            p = QgsProcessingParameterFeatureSource(self.name, label, [QgsProcessing.TypeVector], optional=optional)
        elif role == 'input_file':
            p = QgsProcessingParameterFile(self.name, label, QgsProcessingParameterFile.File,
                                           optional=optional, fileFilter=_file_filter(spec.get('metavar')))
        elif role == 'output_vector':
            # A vector destination (not a plain file) so QGIS offers "Open output file after running";
            # the layers inside are then opened one by one (see UrbanvecAlgorithm._load_outputs).
            p = QgsProcessingParameterVectorDestination(self.name, label, QgsProcessing.TypeVectorAnyGeometry,
                                                        None, optional, not optional)
        elif role == 'output_raster':
            p = QgsProcessingParameterRasterDestination(self.name, label, optional=optional,
                                                        createByDefault=not optional)
        elif role == 'output_folder':
            p = QgsProcessingParameterFolderDestination(self.name, label, optional=optional,
                                                        createByDefault=not optional)
        elif role == 'output_file':
            p = QgsProcessingParameterFileDestination(self.name, label, _file_filter(spec.get('metavar')),
                                                      optional=optional, createByDefault=not optional)
        elif role == 'crs':
            p = QgsProcessingParameterCrs(self.name, label, optional=optional)
        elif self.type == 'flag':
            p = QgsProcessingParameterBoolean(self.name, label, defaultValue=str(default).lower() == 'true')
        elif self.type == 'choice':
            p = QgsProcessingParameterEnum(self.name, label, self.choices, False, default, optional, True)
        elif self.type in ('integer', 'real') and self.arity == 1 and not self.repeatable:
            integer = self.type == 'integer'
            default_number = float(default) if default not in (None, '') else None
            if not integer and spec.get('unit') == 'm':
                p = QgsProcessingParameterDistance(self.name, label, default_number, optional=optional)
                p.setDefaultUnit(QgsUnitTypes.DistanceMeters)
            else:
                p = QgsProcessingParameterNumber(
                    self.name, label,
                    QgsProcessingParameterNumber.Integer if integer else QgsProcessingParameterNumber.Double,
                    default_number, optional)
            minimum, maximum = spec.get('minimum'), spec.get('maximum')
            if integer:
                # QGIS edits integers in a 32-bit spin box, which wraps around beyond these bounds.
                minimum = max(float(minimum), _INT32_MIN) if minimum is not None else None
                maximum = min(float(maximum), _INT32_MAX) if maximum is not None else None
            if minimum is not None:
                p.setMinimum(float(minimum))
            if maximum is not None:
                p.setMaximum(float(maximum))
        else:
            p = QgsProcessingParameterString(self.name, label, default, False, optional)
        help_text = _help(spec, self.flag)
        if self.arity > 1:
            help_text += ' Give {} values separated by spaces.'.format(self.arity)
        if self.repeatable:
            help_text += ' Several values are separated by "{}".'.format(MULTI_VALUE_SEPARATOR)
        p.setHelp(help_text)
        if spec.get('advanced'):
            p.setFlags(p.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
        return p

    # -- values -> arguments --------------------------------------------------------------------
    def values(self, algorithm, parameters, context, feedback):
        """The command-line words for this argument (without the flag); [] when not given."""
        role = self.role
        name = self.name
        if role == 'input_raster':
            layer = algorithm.parameterAsRasterLayer(parameters, name, context)
            if layer is None:
                return self._missing(parameters)
            return [_raster_path(layer)]
        if role == 'input_vector':
            return self._vector_input(algorithm, parameters, context, feedback)
        if role == 'input_file':
            path = algorithm.parameterAsFile(parameters, name, context)
            return [path] if path else self._missing(parameters)
        if role == 'output_vector':
            if self.optional and not _destination_given(parameters.get(name)):
                return []
            destination = algorithm.parameterAsOutputLayer(parameters, name, context)
            return [dataset_path(destination)] if destination else self._missing(parameters)
        if role in ('output_file', 'output_folder'):
            if self.optional and not _destination_given(parameters.get(name)):
                return []
            path = algorithm.parameterAsFileOutput(parameters, name, context)
            return [path] if path else self._missing(parameters)
        if role == 'output_raster':
            if self.optional and not _destination_given(parameters.get(name)):
                return []
            path = algorithm.parameterAsOutputLayer(parameters, name, context)
            return [path] if path else self._missing(parameters)
        if role == 'crs':
            crs = algorithm.parameterAsCrs(parameters, name, context)
            if not crs.isValid():
                return self._missing(parameters)
            return [crs.authid() or crs.toWkt()]
        if self.type == 'flag':
            return ['true'] if algorithm.parameterAsBool(parameters, name, context) else []
        if self.type == 'choice':
            value = parameters.get(name)
            if isinstance(value, (int, float)) or (isinstance(value, str) and value.isdigit()
                                                   and value not in self.choices):
                index = int(value)  # models and scripts may give the option's index
                if not 0 <= index < len(self.choices):
                    raise QgsProcessingException('{} must be one of {}, got index {}'.format(
                        self.flag, ', '.join(self.choices), index))
                return [self.choices[index]]
            value = algorithm.parameterAsEnumString(parameters, name, context)
            return [value] if value else []
        if self.type in ('integer', 'real') and self.arity == 1 and not self.repeatable:
            value = parameters.get(name)
            if value is None or value == '':
                return self._missing(parameters) if self.default in (None, '') else []
            number = (algorithm.parameterAsInt(parameters, name, context) if self.type == 'integer'
                      else algorithm.parameterAsDouble(parameters, name, context))
            return [format_number(number, self.type == 'integer')]
        text = algorithm.parameterAsString(parameters, name, context) if name in parameters else ''
        text = (text or '').strip()
        if not text:
            return self._missing(parameters) if self.default in (None, '') else []
        if self.repeatable:
            return [v.strip() for v in text.split(MULTI_VALUE_SEPARATOR) if v.strip()]
        if self.arity > 1:
            words = text.replace(',', ' ').split()
            if len(words) != self.arity:
                raise QgsProcessingException('{} expects {} values, got "{}"'.format(
                    self.flag or self.name, self.arity, text))
            return words
        return [text]

    def arguments(self, algorithm, parameters, context, feedback):
        """This argument's part of the command line, in order."""
        values = self.values(algorithm, parameters, context, feedback)
        if self.positional:
            return values
        if not values:
            return []
        if self.type == 'flag':
            return [self.flag]
        if self.default not in (None, '') and not self.repeatable and self.arity == 1 \
                and self._equals_default(values[0]):
            return []
        words = []
        if self.repeatable and self.arity == 1:
            for v in values:
                words += [self.flag, v]
        else:
            words = [self.flag] + values
        return words

    def _equals_default(self, value):
        if self.type in ('integer', 'real'):
            try:
                return float(value) == float(self.default)
            except ValueError:
                return False
        return value == str(self.default)

    def _missing(self, parameters):
        if self.optional:
            return []
        raise QgsProcessingException('{} is required'.format(self.flag or self.name))

    def _vector_input(self, algorithm, parameters, context, feedback):
        """A dataset path the program can open. A dataset given as a path goes through as is (the
        program picks its layers itself). A layer of an OGR file goes through as its dataset when
        that holds only this layer, or when the command picks layers by name (-roads-layer ...);
        anything else (selections, filters, other providers, one layer of many) is exported."""
        self.picked_layer = None
        value = parameters.get(self.name)
        if isinstance(value, str) and '|' not in value and os.path.exists(value):
            return [value]
        selected_only = isinstance(value, QgsProcessingFeatureSourceDefinition) and (
            value.selectedFeaturesOnly or value.featureLimit != -1)
        layer = algorithm.parameterAsVectorLayer(parameters, self.name, context)
        if layer is None:
            if algorithm.parameterAsSource(parameters, self.name, context) is None:
                return self._missing(parameters)
        elif layer.providerType() == 'ogr' and not selected_only and not layer.subsetString():
            parts = QgsProviderRegistry.instance().decodeUri('ogr', layer.source())
            path = parts.get('path') or ''
            if path and os.path.isfile(path) and not path.startswith('/vsi') and (
                    not parts.get('layerName') or self.picks_layers_by_name
                    or _layer_count(path) == 1):
                self.picked_layer = parts.get('layerName') or None
                return [path]
        path = algorithm.parameterAsCompatibleSourceLayerPath(
            parameters, self.name, context, ['gpkg', 'shp', 'geojson', 'fgb'], 'gpkg', feedback)
        return [path]


def _destination_given(value):
    if isinstance(value, QgsProcessingOutputLayerDefinition):
        value = value.sink.staticValue()
    return value not in (None, '')


def dataset_path(destination):
    """The file of a vector destination: '/x/city.gpkg' for itself and for the
    'ogr:dbname='/x/city.gpkg' table="t" (geom)' QGIS's "Save to GeoPackage" gives."""
    match = re.match(r"^ogr:dbname='((?:[^']|'')*)'", destination)
    if match:
        return match.group(1).replace("''", "'")
    return destination.split('|')[0]


def _layer_count(path):
    from osgeo import ogr
    dataset = ogr.Open(path)
    return dataset.GetLayerCount() if dataset is not None else 0


def _raster_path(layer):
    if layer.providerType() == 'gdal':
        parts = QgsProviderRegistry.instance().decodeUri('gdal', layer.source())
        if parts.get('path'):
            return parts['path']
    return layer.source()
