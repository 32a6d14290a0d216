"""Road Sign Inventory: a QGIS Processing plugin (package ``roadsigns``).

Importing this package imports nothing from QGIS; ``classFactory`` (QGIS desktop and
``qgis_process``) loads the plugin class, whose ``initProcessing`` registers the
provider ``roadsigns`` and whose ``initGui`` (QGIS desktop) adds the sign review panel.
"""


def classFactory(iface):
    from .plugin import RoadSignsPlugin
    return RoadSignsPlugin(iface)
