"""urbanvec: QGIS Processing provider running the `urbanvec` program (gridded land use -> vector city)."""


def classFactory(iface):
    from .plugin import UrbanvecPlugin
    return UrbanvecPlugin(iface)
