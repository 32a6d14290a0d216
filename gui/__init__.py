"""The plugin's widgets in the QGIS desktop: the sign review panel (a dock widget)."""
