#!/usr/bin/python3
"""Renders the README/docs figures headless with PyQGIS: a simulation grid beside the vector city that
`urbanvec vectorize` made from it, with the styles the GeoPackage carries (what a user sees in QGIS).

usage: render_figures.py <grid_dir> <city.gpkg> <out_prefix> [width_px]
writes <out_prefix>_landuse.png (land-use grid | parcels by land use, pavement, roads, water) and
<out_prefix>_density.png (density grid | parcels by people per m², the "parcels density" style).
"""
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from osgeo import ogr  # noqa: E402
from qgis.core import (  # noqa: E402
    QgsApplication,
    QgsColorRampShader,
    QgsMapRendererSequentialJob,
    QgsMapSettings,
    QgsPalettedRasterRenderer,
    QgsRasterLayer,
    QgsRasterShader,
    QgsSingleBandPseudoColorRenderer,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QSize, Qt  # noqa: E402
from qgis.PyQt.QtGui import QColor, QFont, QImage, QPainter  # noqa: E402
from qgis.PyQt.QtXml import QDomDocument  # noqa: E402

# Land-use codes of landuse.tif (CONVENTIONS.md) and the parcels style's colours (io/layer_styles.cpp).
LAND_USE_COLOURS = [
    (0, "unused", "#ffffff"),
    (1, "water", "#78b4e6"),
    (2, "secondary road", "#5a5a5a"),
    (3, "primary road", "#c85a28"),
    (4, "residential", "#f6e05e"),
    (5, "commercial", "#e04040"),
    (6, "industrial", "#466edc"),
    (7, "park", "#5ab45a"),
    (8, "reserved", "#aaaaaa"),
]
DENSITY_STOPS = [(0.0, "#ffffff"), (0.005, "#ffffb2"), (0.01, "#fed976"), (0.02, "#feb24c"),
                 (0.04, "#fd8d3c"), (0.08, "#f03b20"), (0.16, "#bd0026")]


def fail(message):
    sys.stderr.write("ERROR: " + message + "\n")
    sys.exit(1)


def stored_style(gpkg, layer, style_name):
    ds = ogr.Open(gpkg)
    if ds is None:
        fail(f"cannot open '{gpkg}'")
    sql = f"SELECT styleQML FROM layer_styles WHERE f_table_name = '{layer}' AND styleName = '{style_name}'"
    result = ds.ExecuteSQL(sql)
    feature = result.GetNextFeature() if result else None
    qml = feature.GetField(0) if feature else None
    if result:
        ds.ReleaseResultSet(result)
    if not qml:
        fail(f"'{gpkg}' has no style '{style_name}' for layer '{layer}'")
    return qml


def vector_layer(gpkg, name, style_name=None):
    layer = QgsVectorLayer(f"{gpkg}|layername={name}", name, "ogr")
    if not layer.isValid():
        fail(f"cannot load layer '{name}' of '{gpkg}'")
    doc = QDomDocument()
    doc.setContent(stored_style(gpkg, name, style_name or name))
    layer.importNamedStyle(doc)
    return layer


def land_use_raster(path):
    layer = QgsRasterLayer(path, "land use")
    if not layer.isValid():
        fail(f"cannot load raster '{path}'")
    classes = [QgsPalettedRasterRenderer.Class(code, QColor(colour), label)
               for code, label, colour in LAND_USE_COLOURS]
    layer.setRenderer(QgsPalettedRasterRenderer(layer.dataProvider(), 1, classes))
    return layer


def density_raster(path, cell_area):
    layer = QgsRasterLayer(path, "density")
    if not layer.isValid():
        fail(f"cannot load raster '{path}'")
    # density.tif holds people per cell; the stops are people per m², as on the parcels.
    ramp = QgsColorRampShader()
    ramp.setColorRampType(QgsColorRampShader.Interpolated)
    ramp.setColorRampItemList([QgsColorRampShader.ColorRampItem(v * cell_area, QColor(c)) for v, c in DENSITY_STOPS])
    shader = QgsRasterShader()
    shader.setRasterShaderFunction(ramp)
    layer.setRenderer(QgsSingleBandPseudoColorRenderer(layer.dataProvider(), 1, shader))
    return layer


def render(layers, extent, crs, size):
    settings = QgsMapSettings()
    settings.setLayers(layers)
    settings.setDestinationCrs(crs)
    settings.setExtent(extent)
    settings.setOutputSize(size)
    settings.setBackgroundColor(QColor("white"))
    job = QgsMapRendererSequentialJob(settings)
    job.start()
    job.waitForFinished()
    return job.renderedImage()


def side_by_side(left, right, left_title, right_title, path):
    title_height = 36
    image = QImage(left.width() + right.width() + 12, max(left.height(), right.height()) + title_height,
                   QImage.Format_ARGB32)
    image.fill(QColor("white"))
    painter = QPainter(image)
    painter.setFont(QFont("DejaVu Sans", 14))
    painter.setPen(QColor("black"))
    painter.drawText(0, 0, left.width(), title_height, Qt.AlignCenter, left_title)
    painter.drawText(left.width() + 12, 0, right.width(), title_height, Qt.AlignCenter, right_title)
    painter.drawImage(0, title_height, left)
    painter.drawImage(left.width() + 12, title_height, right)
    painter.end()
    if not image.save(path + ".tmp.png"):
        fail(f"cannot write '{path}'")
    os.replace(path + ".tmp.png", path)


def main():
    if len(sys.argv) not in (4, 5):
        fail("usage: render_figures.py <grid_dir> <city.gpkg> <out_prefix> [width_px]")
    grid_dir, gpkg, prefix = sys.argv[1:4]
    width = int(sys.argv[4]) if len(sys.argv) == 5 else 700
    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    land_use = land_use_raster(os.path.join(grid_dir, "landuse.tif"))
    pixel = land_use.rasterUnitsPerPixelX()
    density = density_raster(os.path.join(grid_dir, "density.tif"), pixel * pixel)
    extent = land_use.extent()
    size = QSize(width, int(round(width * extent.height() / extent.width())))
    crs = land_use.crs()
    city = [vector_layer(gpkg, n) for n in ("roads", "water", "pavement", "parcels")]
    city_density = [city[0], city[1], city[2], vector_layer(gpkg, "parcels", "parcels density")]
    side_by_side(render([land_use], extent, crs, size), render(city, extent, crs, size),
                 "input: land-use grid (landuse.tif)", "output: parcels by land use, pavement, roads",
                 prefix + "_landuse.png")
    side_by_side(render([density], extent, crs, size), render(city_density, extent, crs, size),
                 "input: population grid (density.tif)", "output: parcels by people per m²",
                 prefix + "_density.png")
    # Layers must go before the application, or PyQGIS 3.22 crashes on exit.
    del city, city_density, land_use, density
    app.exitQgis()


if __name__ == "__main__":
    main()
