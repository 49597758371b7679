"""Starts headless QGIS with Processing and the urbanvec plugin's provider, for the Python tests."""

import os

from qgis.core import QgsApplication

_app = None


def start():
    """Returns (QgsApplication, provider); the provider is the one QGIS registered from the plugin."""
    global _app
    if _app is None:
        _app = QgsApplication([], False)
        _app.initQgis()
        from processing.core.Processing import Processing
        Processing.initialize()
        from urbanvec.provider import UrbanvecProvider
        provider = UrbanvecProvider()
        QgsApplication.processingRegistry().addProvider(provider)
        _app.urbanvec_provider = provider
    return _app, _app.urbanvec_provider


def make_inputs(folder):
    """A 4 x 3 Byte GeoTIFF (UTM 31N), a one-layer and a two-layer GeoPackage; returns their paths."""
    from osgeo import gdal, ogr, osr
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32631)
    raster = os.path.join(folder, 'grid.tif')
    ds = gdal.GetDriverByName('GTiff').Create(raster, 4, 3, 1, gdal.GDT_Byte)
    ds.SetGeoTransform((500000, 10, 0, 4800030, 0, -10))
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).Fill(4)
    ds = None
    paths = {'raster': raster}
    for name, layers in (('one.gpkg', ['roads']), ('two.gpkg', ['roads', 'parcels'])):
        path = os.path.join(folder, name)
        ds = ogr.GetDriverByName('GPKG').CreateDataSource(path)
        for layer_name in layers:
            layer = ds.CreateLayer(layer_name, srs, ogr.wkbLineString)
            feature = ogr.Feature(layer.GetLayerDefn())
            feature.SetGeometry(ogr.CreateGeometryFromWkt('LINESTRING (500000 4800000, 500040 4800030)'))
            layer.CreateFeature(feature)
        ds = None
        paths[name] = path
    return paths
