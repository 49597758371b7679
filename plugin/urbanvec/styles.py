"""Land-use styling of the layers the provider loads.

urbanvec stores a QGIS style per layer in its GeoPackages (`layer_styles`), but Processing opens
result layers without their default style, so the post-processor below loads it. Outputs without a
stored style (other formats, older programs) get the QML shipped in styles/ for their layer name.
"""

import os

from qgis.core import QgsProcessingLayerPostProcessorInterface, QgsRasterLayer, QgsVectorLayer

STYLES_FOLDER = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'styles')


def layer_name_of(layer):
    """'parcels' for '/x/city.gpkg|layername=parcels', 'landuse' for '/x/landuse.tif'."""
    source = layer.source()
    for part in source.split('|')[1:]:
        if part.startswith('layername='):
            return part[len('layername='):]
    return os.path.splitext(os.path.basename(source.split('|')[0]))[0]


def fallback_style(name):
    path = os.path.join(STYLES_FOLDER, name + '.qml')
    return path if os.path.isfile(path) else None


def dataset_has_layer(path, layer_name):
    from osgeo import ogr
    dataset = ogr.Open(path)
    return dataset is not None and dataset.GetLayerByName(layer_name) is not None


def apply_style(layer):
    """Applies the layer's stored default style, else the shipped one. Returns where the style came
    from: 'stored', 'shipped' or None."""
    if isinstance(layer, QgsVectorLayer):
        _, loaded = layer.loadDefaultStyle()
        if loaded:
            layer.triggerRepaint()
            return 'stored'
    elif not isinstance(layer, QgsRasterLayer):
        return None
    shipped = fallback_style(layer_name_of(layer))
    if shipped:
        _, loaded = layer.loadNamedStyle(shipped)
        if loaded:
            layer.triggerRepaint()
            return 'shipped'
    return None


class StylePostProcessor(QgsProcessingLayerPostProcessorInterface):
    def postProcessLayer(self, layer, context, feedback):
        apply_style(layer)


#: Every post-processor handed to Processing, kept alive here: Processing only holds a pointer to it.
_KEEP_ALIVE = []


def post_processor():
    processor = StylePostProcessor()
    _KEEP_ALIVE.append(processor)
    return processor
