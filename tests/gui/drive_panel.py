"""Drives the sign review panel inside a running QGIS desktop (``qgis --code drive_panel.py``,
started by ``tests/gui/conftest.py`` under Xvfb), as an analyst would: it opens the layers,
opens the panel from the plugin's menu action, selects a sign with the map's select tool,
gives verdicts with keyboard shortcuts and buttons, changes a code, undoes, looks at the
panorama view, saves the edits, tries a layer without the sign fields and unloads the
plugin. What it saw goes to ``$ROADSIGNS_GUI_OUT/results.json`` (checked by
``tests/gui/test_review_panel.py``) with screenshots beside it; then QGIS exits.

Environment: ``ROADSIGNS_GUI_DATA`` (the folder of ``tests/helpers/reviewdata.build``),
``ROADSIGNS_GUI_OUT``; ``ROADSIGNS_GUI_MODE=screenshot`` only opens the panel on the first
sign and takes the screenshots (for the README).
"""
import json
import os
import sys
import traceback

import qgis.utils
from qgis.core import QgsProject, QgsVectorLayer
from qgis.PyQt.QtCore import QPoint, Qt, QTimer
from qgis.PyQt.QtTest import QTest
from qgis.PyQt.QtWidgets import QApplication, QDockWidget

DATA = os.environ["ROADSIGNS_GUI_DATA"]
OUT = os.environ["ROADSIGNS_GUI_OUT"]
MODE = os.environ.get("ROADSIGNS_GUI_MODE", "test")
REVIEW_FIELDS = ("review_status", "reviewed_class", "reviewed_code", "reviewed_at")
results = {"steps": [], "errors": []}
iface = qgis.utils.iface


def record_exception(kind, value, tb):
    """Exceptions raised in Qt slots (the panel's) are recorded, not shown in QGIS's modal
    Python error dialog (which would stop the run)."""
    results["errors"].append("".join(traceback.format_exception(kind, value, tb)))


sys.excepthook = record_exception


def plain(value):
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    return value if isinstance(value, (int, float, str)) else str(value)


def fid_of(layer, sign_id):
    return next(f.id() for f in layer.getFeatures() if f["sign_id"] == sign_id)


def sign_id_of(layer, fid):
    return None if fid is None else plain(layer.getFeature(fid)["sign_id"])


def review_of(layer):
    """sign_id -> review field values (those the layer has), as the edit buffer holds them."""
    names = layer.fields().names()
    return {str(plain(f["sign_id"])): {n: plain(f[n]) for n in REVIEW_FIELDS if n in names}
            for f in layer.getFeatures()}


def panel_state(panel, layer):
    return {"current": sign_id_of(layer, panel.current) if panel.layer is layer else None,
            "message": panel.message.text(), "class_text": panel.values["class"].text(),
            "code_text": panel.values["code"].text(), "score_text": panel.values["score"].text(),
            "condition_text": panel.values["condition"].text(), "sources_text": panel.values["sources"].text(),
            "chips": [panel.chips_layout.itemAt(k).widget().text() for k in range(panel.chips_layout.count())],
            "buttons_enabled": [b.isEnabled() for b in panel.verdict_buttons],
            "editable": layer.isEditable(), "undo_index": layer.undoStack().index(),
            "review": review_of(layer), "selected": [sign_id_of(layer, f) for f in layer.selectedFeatureIds()],
            "canvas_center": [iface.mapCanvas().center().x(), iface.mapCanvas().center().y()]}


def record(name, **values):
    results["steps"].append(dict(name=name, **values))


def focus_panel(panel):
    window = iface.mainWindow()
    window.activateWindow()
    window.raise_()
    if hasattr(QApplication, "setActiveWindow"):  # Qt 5
        QApplication.setActiveWindow(window)
    panel.root.setFocus()
    QApplication.processEvents()


def click_on_map(layer, sign_id):
    """A click with QGIS's select tool on the sign's symbol."""
    canvas = iface.mapCanvas()
    iface.actionSelect().trigger()
    point = layer.getFeature(fid_of(layer, sign_id)).geometry().asPoint()
    pixel = canvas.getCoordinateTransform().transform(point)
    QTest.mouseClick(canvas.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     QPoint(int(round(pixel.x())), int(round(pixel.y()))))


def steps():
    """The scenario; each ``yield`` lets QGIS run for that many milliseconds."""
    window = iface.mainWindow()
    window.resize(1500, 900)
    window.showMaximized()
    iface.messageBar().clearWidgets()
    plugin = qgis.utils.plugins["roadsigns"]
    results["plugin_loaded"] = plugin is not None and "roadsigns" in qgis.utils.active_plugins
    signs = QgsVectorLayer(os.path.join(DATA, "signs.gpkg"), "signs", "ogr")
    stations = QgsVectorLayer(os.path.join(DATA, "stations.gpkg"), "stations", "ogr")
    from roadsigns.algorithms.style import style_sign_layer
    style_sign_layer(signs)                                    # the shipped style
    QgsProject.instance().addMapLayers([stations, signs])
    iface.setActiveLayer(signs)
    canvas = iface.mapCanvas()
    extent = signs.extent()
    extent.combineExtentWith(stations.extent())
    extent.grow(15)
    canvas.setExtent(extent)
    canvas.refresh()
    yield 300

    # the panel, from the plugin's own action (Vector menu / toolbar)
    action = plugin.review_action
    results["action_text"] = action.text()
    results["panel_hidden_at_start"] = not plugin.review_panel.isVisible()
    action.trigger()
    panel = plugin.review_panel
    results["panel_visible"] = panel.isVisible()
    results["dock_area"] = str(window.dockWidgetArea(panel))
    window.resizeDocks([panel], [560], Qt.Orientation.Horizontal)
    panel.layer_combo.setLayer(signs)
    panel.stations_combo.setLayer(stations)
    panel.folder_widget.setFilePath(os.path.join(DATA, "images"))
    yield 800
    record("start", **panel_state(panel, signs))
    panel.grab().save(os.path.join(OUT, "review_panel.png"))
    window.grab().save(os.path.join(OUT, "review_window.png"))
    if MODE == "screenshot":
        dialog = panel.show_panorama()
        yield 300
        if dialog is not None:
            dialog.grab().save(os.path.join(OUT, "panorama_view.png"))
        return

    # select sign 3 on the map with the select tool
    click_on_map(signs, 3)
    yield 300
    record("select_on_map", **panel_state(panel, signs))

    # accept with the keyboard
    focus_panel(panel)
    QTest.keyClick(panel.root, Qt.Key.Key_A)
    yield 300
    record("accept_key", **panel_state(panel, signs))

    # reject with the button
    QTest.mouseClick(panel.reject_button, Qt.MouseButton.LeftButton)
    yield 300
    record("reject_button", **panel_state(panel, signs))

    # change the code: type it in the code field, Enter
    panel.code_edit.clear()
    QTest.keyClicks(panel.code_edit, "206-1")
    QTest.keyClick(panel.code_edit, Qt.Key.Key_Return)
    yield 300
    record("change_code", **panel_state(panel, signs))

    # undo it (U in the panel)
    focus_panel(panel)
    QTest.keyClick(panel.root, Qt.Key.Key_U)
    yield 300
    record("undo", **panel_state(panel, signs))

    # change the class of the same sign with the class box and the Change button
    panel.class_edit.setCurrentText("stop")
    QTest.mouseClick(panel.change_button, Qt.MouseButton.LeftButton)
    yield 300
    record("change_class", **panel_state(panel, signs))

    # needs another look (L), then step back (P)
    focus_panel(panel)
    QTest.keyClick(panel.root, Qt.Key.Key_L)
    yield 200
    record("unsure_key", **panel_state(panel, signs))
    QTest.keyClick(panel.root, Qt.Key.Key_P)
    yield 300
    record("previous_key", **panel_state(panel, signs))

    # the panorama view (V) of the current sign
    QTest.keyClick(panel.root, Qt.Key.Key_V)
    yield 500
    dialog = panel.pano_dialog
    info = {"shown": bool(dialog is not None and dialog.isVisible())}
    if dialog is not None:
        image = panel.pano_label.pixmap().toImage()
        info.update(width=image.width(), height=image.height(), title=dialog.windowTitle(),
                    caption=panel.pano_caption.text(),
                    centre=list(image.pixelColor(image.width() // 2, image.height() // 2).getRgb()[:3]),
                    corner=list(image.pixelColor(5, 5).getRgb()[:3]))
        dialog.grab().save(os.path.join(OUT, "panorama_view.png"))
        dialog.close()
    results["panorama_view"] = info
    panel.grab().save(os.path.join(OUT, "review_panel_after.png"))

    # save the edits with the panel's button; read the file back in a new layer
    QTest.mouseClick(panel.save_button, Qt.MouseButton.LeftButton)
    yield 300
    reread = QgsVectorLayer(os.path.join(DATA, "signs.gpkg"), "reread", "ogr")
    results["saved"] = {"fields": reread.fields().names(), "review": review_of(reread),
                        "still_editable": signs.isEditable(), "modified": signs.isModified()}

    # a point layer without the sign fields
    bare = QgsVectorLayer(os.path.join(DATA, "bare.gpkg"), "bare", "ogr")
    QgsProject.instance().addMapLayer(bare)
    panel.layer_combo.setLayer(bare)
    yield 200
    record("bare_layer", message=panel.message.text(), buttons_enabled=[b.isEnabled() for b in panel.verdict_buttons])

    # unload the plugin: the panel goes
    qgis.utils.unloadPlugin("roadsigns")
    yield 300
    docks = [d.objectName() for d in window.findChildren(QDockWidget) if d.objectName() == "RoadSignsReviewPanel"]
    results["after_unload"] = {"docks": docks, "plugin_panel": getattr(plugin, "review_panel", "gone")}


def run():
    sequence = steps()

    def advance():
        try:
            delay = next(sequence)
        except StopIteration:
            finish()
            return
        except Exception:
            results["errors"].append(traceback.format_exc())
            finish()
            return
        QTimer.singleShot(delay, advance)

    QTimer.singleShot(500, advance)


def finish():
    with open(os.path.join(OUT, "results.json"), "w") as f:
        json.dump(results, f, indent=1, default=str)
    os._exit(0)  # no "save the project?" question, no teardown


run()
