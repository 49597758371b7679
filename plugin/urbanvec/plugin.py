"""QGIS plugin entry point: registers the urbanvec Processing provider."""

from qgis.core import QgsApplication

from .provider import UrbanvecProvider


class UrbanvecPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None

    def initProcessing(self):
        if self.provider is None:
            self.provider = UrbanvecProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)

    def initGui(self):
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
