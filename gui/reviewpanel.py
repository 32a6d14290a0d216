"""The sign review panel: a dock widget that steps through a sign layer one sign at a time,
shows its pictures and attributes, and writes the analyst's verdict to the layer.

* **Which sign**: the one selected on the map, or the next one without a verdict (in
  ``sign_id`` order, :func:`~roadsigns.core.reviewstate.next_unreviewed`); the map
  follows the current sign (centred on it, the sign selected).
* **What it shows**: the review chip of the layer (``chip``) and a chip cut from every
  panorama that saw the sign, best first (:mod:`~roadsigns.core.signviews`: needs the
  stations layer, and the panorama folder unless the stations' ``path`` is right); class,
  code (when the layer has a ``code`` field), confidence (``score``), condition (when
  present) and sources; the panorama view around the sign on demand.
* **Verdicts**: accept (A), reject (R), change the class or code (C, or Enter in the code
  field), needs another look (L); each writes ``review_status``, ``reviewed_class``,
  ``reviewed_code`` and ``reviewed_at`` (fields added when missing) through the layer's
  edit buffer as one undoable edit command, and steps on to the next unreviewed sign.
  N and P step without a verdict, V opens the panorama view, U undoes the last verdict (as
  QGIS's Undo, Ctrl+Z, does on the active layer). Saving the layer's edits (QGIS's Save, or
  the panel's button) writes them to the file.
"""
import html
import math
import os

from qgis.core import (
    Qgis,
    QgsCoordinateTransform,
    QgsFeatureRequest,
    QgsField,
    QgsMessageLog,
    QgsProject,
    QgsVectorLayer,
    QgsWkbTypes,
)
from qgis.gui import QgsFileWidget, QgsMapLayerComboBox
from qgis.PyQt.QtCore import QMetaType, QSize, Qt, QTimer
from qgis.PyQt.QtGui import QColor, QIcon, QImage, QKeySequence, QPainter, QPen, QPixmap
from qgis.PyQt.QtWidgets import (
    QComboBox,
    QDialog,
    QDockWidget,
    QFormLayout,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QScrollArea,
    QSizePolicy,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from ..algorithms.i18n import Translatable
from ..algorithms.style import CLASS_SYMBOLS
from ..core import reviewstate as rs
from ..core.errors import InputError
from ..core.schema import names

try:  # Qt 6
    from qgis.PyQt.QtGui import QShortcut
except ImportError:  # Qt 5
    from qgis.PyQt.QtWidgets import QShortcut

LOG_TAG = "Road sign inventory"
#: stations layer fields the panel needs to cut pictures
STATION_VIEW_FIELDS = ("image", "x", "y", "z", "qw", "qx", "qy", "qz")
CHIP_PX = 150
MAX_CHIPS = 6
#: the map zooms in to this scale when it shows more than ZOOM_IN_ABOVE (1:n)
FOLLOW_SCALE, ZOOM_IN_ABOVE = 1000.0, 5000.0


def _plain(value):
    """A field value as Python: None for NULL (a NULL QVariant in PyQt5)."""
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    return value


def _qimage(bgr):
    """A QImage (owning its pixels) of an OpenCV BGR uint8 array."""
    height, width = bgr.shape[:2]
    data = bgr[:, :, ::-1].tobytes()
    return QImage(data, width, height, 3 * width, QImage.Format.Format_RGB888).copy()


def _point_layer_filter():
    try:
        return Qgis.LayerFilter.PointLayer
    except AttributeError:  # QGIS before 3.34
        from qgis.core import QgsMapLayerProxyModel
        return QgsMapLayerProxyModel.PointLayer


class ReviewPanel(Translatable, QDockWidget):
    """The dock widget. ``iface``: QGIS's interface (map canvas, message bar)."""

    OBJECT_NAME = "RoadSignsReviewPanel"

    def __init__(self, iface, parent=None):
        QDockWidget.__init__(self, parent)
        self.setWindowTitle(self.tr("Sign review"))
        self.setObjectName(self.OBJECT_NAME)
        self.iface = iface
        self.layer = None
        self.order = []
        self.current = None
        self.history = []          # feature ids of the verdicts given here, last last
        self.views = []            # SignView of the chips shown
        self.pano_dialog = None
        self._stations = None      # (layer id, records) of the stations layer read
        self._cache = None
        self._syncing = False
        self._chip_token = 0
        self._build()
        self._shortcuts()
        self.layer_combo.layerChanged.connect(self.set_layer)
        self.stations_combo.layerChanged.connect(self._stations_changed)
        self.folder_widget.fileChanged.connect(self._stations_changed)
        # the layer box picks a layer of its own when the first layers come (no layerChanged then)
        QgsProject.instance().layersAdded.connect(self._sync_layer)
        self.set_layer(self.layer_combo.currentLayer())

    def _sync_layer(self, *args):
        if self.layer_combo.currentLayer() is not self.layer:
            self.set_layer(self.layer_combo.currentLayer())
        if self.layer is not None and self.stations_combo.currentLayer() is None:
            self._pick_stations()

    def showEvent(self, event):  # noqa: N802 (Qt's name)
        super().showEvent(event)
        self._sync_layer()

    # --- building ---------------------------------------------------------------------------

    def _build(self):
        root = QWidget(self)
        self.root = root
        outer = QVBoxLayout(root)
        form = QFormLayout()
        self.layer_combo = QgsMapLayerComboBox(root)
        self.layer_combo.setFilters(_point_layer_filter())
        self.layer_combo.setToolTip(self.tr("The sign layer to review (the output of Refine and merge signs, or "
                                            "any point layer with the sign fields)."))
        form.addRow(self.tr("Signs"), self.layer_combo)
        self.stations_combo = QgsMapLayerComboBox(root)
        self.stations_combo.setFilters(_point_layer_filter())
        self.stations_combo.setAllowEmptyLayer(True)
        self.stations_combo.setToolTip(self.tr("The panorama stations of the drive: with them the panel cuts the "
                                               "sign from every panorama that saw it."))
        form.addRow(self.tr("Stations"), self.stations_combo)
        self.folder_widget = QgsFileWidget(root)
        self.folder_widget.setStorageMode(QgsFileWidget.StorageMode.GetDirectory)
        self.folder_widget.setToolTip(self.tr("The panorama folder; empty: the path field of the stations layer."))
        form.addRow(self.tr("Panoramas"), self.folder_widget)
        outer.addLayout(form)

        self.message = QLabel(root)
        self.message.setWordWrap(True)
        self.message.setTextFormat(Qt.TextFormat.RichText)
        outer.addWidget(self.message)

        self.chips_box = QWidget(root)
        self.chips_layout = QHBoxLayout(self.chips_box)
        self.chips_layout.setContentsMargins(0, 0, 0, 0)
        self.chips_layout.setAlignment(Qt.AlignmentFlag.AlignLeft)
        scroll = QScrollArea(root)
        scroll.setWidgetResizable(True)
        scroll.setWidget(self.chips_box)
        scroll.setMinimumHeight(CHIP_PX + 48)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAsNeeded)
        outer.addWidget(scroll)

        details = QGroupBox(self.tr("Sign"), root)
        self.details = details
        grid = QFormLayout(details)
        self.values = {}
        for key, label in (("class", self.tr("Class")), ("code", self.tr("Code")),
                           ("score", self.tr("Confidence")), ("condition", self.tr("Condition")),
                           ("sources", self.tr("Sources")), ("size", self.tr("Panel")),
                           ("review", self.tr("Review"))):
            value = QLabel(details)
            value.setWordWrap(True)
            value.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            grid.addRow(label, value)
            self.values[key] = value
        outer.addWidget(details)

        change = QHBoxLayout()
        self.class_edit = QComboBox(root)
        self.class_edit.setEditable(True)
        self.class_edit.setToolTip(self.tr("The sign's class: pick or type another one, then Change."))
        self.code_edit = QLineEdit(root)
        self.code_edit.setPlaceholderText(self.tr("code"))
        self.code_edit.setToolTip(self.tr("The sign's code (e.g. 206): type it, then Enter or Change."))
        self.code_edit.returnPressed.connect(self.change)
        change.addWidget(self.class_edit, 2)
        change.addWidget(self.code_edit, 1)
        outer.addLayout(change)

        buttons = QGridLayout()
        self.accept_button = self._button(self.tr("Accept (A)"), self.accept_sign,
                                          self.tr("A real sign, class and code right: next sign."))
        self.reject_button = self._button(self.tr("Reject (R)"), self.reject_sign,
                                          self.tr("Not a sign, or a duplicate: next sign."))
        self.change_button = self._button(self.tr("Change (C)"), self.change,
                                          self.tr("A real sign with the class and code above: next sign."))
        self.unsure_button = self._button(self.tr("Look again (L)"), self.unsure_sign,
                                          self.tr("Needs another look: next sign."))
        self.previous_button = self._button(self.tr("Previous (P)"), self.previous_sign,
                                            self.tr("The sign before this one."))
        self.next_button = self._button(self.tr("Next unreviewed (N)"), self.next_sign,
                                        self.tr("The next sign without a verdict."))
        self.view_button = self._button(self.tr("Panorama view (V)"), self.show_panorama,
                                        self.tr("The panorama around the sign, from its best panorama."))
        self.undo_button = self._button(self.tr("Undo (U)"), self.undo,
                                        self.tr("Undo the last verdict given here."))
        self.save_button = self._button(self.tr("Save edits"), self.save,
                                        self.tr("Write the verdicts to the layer's file."))
        for k, button in enumerate((self.accept_button, self.reject_button, self.change_button,
                                    self.unsure_button, self.previous_button, self.next_button,
                                    self.view_button, self.undo_button, self.save_button)):
            buttons.addWidget(button, k // 2, k % 2)
        outer.addLayout(buttons)
        outer.addStretch(1)
        self.verdict_buttons = (self.accept_button, self.reject_button, self.change_button, self.unsure_button)
        self.setWidget(root)
        self.setMinimumWidth(340)

    def _button(self, text, slot, tip):
        button = QPushButton(text, self.root)
        button.setToolTip(tip)
        button.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
        button.clicked.connect(slot)
        return button

    def _shortcuts(self):
        self.shortcuts = []
        for keys, slot in (("A", self.accept_sign), ("R", self.reject_sign), ("C", self.change),
                           ("L", self.unsure_sign), ("N", self.next_sign), ("P", self.previous_sign),
                           ("V", self.show_panorama), ("U", self.undo)):
            shortcut = QShortcut(QKeySequence(keys), self.root)
            shortcut.setContext(Qt.ShortcutContext.WidgetWithChildrenShortcut)
            shortcut.activated.connect(slot)
            self.shortcuts.append(shortcut)

    # --- the layer ----------------------------------------------------------------------------

    def set_layer(self, layer):
        """Review ``layer`` (None: nothing); says which sign fields it lacks."""
        if self.layer is not None:
            self._disconnect(self.layer)
        self.layer = layer if isinstance(layer, QgsVectorLayer) else None
        self.order, self.current, self.history = [], None, []
        if self.layer_combo.currentLayer() is not self.layer:
            self.layer_combo.setLayer(self.layer)
        if self.layer is None:
            self._problem(self.tr("Choose a sign layer to review."))
            return
        self.layer.selectionChanged.connect(self._selection_changed)
        self.layer.afterRollBack.connect(self.refresh)
        self.layer.afterCommitChanges.connect(self.refresh)
        self.layer.undoStack().indexChanged.connect(self._undo_stack_changed)
        self.layer.willBeDeleted.connect(self._layer_deleted)
        missing = self.missing_fields()
        if missing:
            self._problem(self.tr("The layer {layer} lacks the field(s) {missing}. The review needs a sign layer "
                                  "with the fields {required} (the output of Refine and merge signs).").format(
                layer=self.layer.name(), missing=", ".join(missing), required=", ".join(rs.PANEL_REQUIRED)))
            return
        self._fill_classes()
        self._pick_stations()
        self.order = rs.review_order(self._records((("sign_id",))))
        selected = self.layer.selectedFeatureIds()
        start = selected[0] if len(selected) == 1 else rs.next_unreviewed(self.order, self._states()) \
            or (self.order[0] if self.order else None)
        self.show_sign(start)

    def missing_fields(self):
        """The sign fields the layer lacks (and a word when it is not a point layer)."""
        if self.layer is None:
            return list(rs.PANEL_REQUIRED)
        missing = rs.missing_fields(self.layer.fields().names())
        if self.layer.geometryType() != Qgis.GeometryType.Point:
            missing.append(self.tr("(point geometry)"))
        return missing

    def _disconnect(self, layer):
        for signal, slot in ((layer.selectionChanged, self._selection_changed), (layer.afterRollBack, self.refresh),
                             (layer.afterCommitChanges, self.refresh),
                             (layer.undoStack().indexChanged, self._undo_stack_changed),
                             (layer.willBeDeleted, self._layer_deleted)):
            try:
                signal.disconnect(slot)
            except (TypeError, RuntimeError):
                pass

    def _layer_deleted(self):
        self.layer = None
        self.order, self.current = [], None
        self._problem(self.tr("Choose a sign layer to review."))

    def _records(self, fields):
        """Feature id and ``fields`` (those the layer has) of every feature."""
        have = [name for name in fields if self.layer.fields().indexOf(name) >= 0]
        request = QgsFeatureRequest().setSubsetOfAttributes(have, self.layer.fields())
        request.setFlags(Qgis.FeatureRequestFlag.NoGeometry)
        return [dict({name: _plain(f[name]) for name in have}, fid=f.id()) for f in self.layer.getFeatures(request)]

    def _states(self):
        return {r["fid"]: r.get(rs.REVIEW_STATUS.name) for r in self._records((rs.REVIEW_STATUS.name,))}

    def _fill_classes(self):
        known = list(CLASS_SYMBOLS)
        index = self.layer.fields().indexOf("class")
        for value in sorted(str(v) for v in self.layer.uniqueValues(index) if _plain(v) is not None):
            if value not in known:
                known.append(value)
        self.class_edit.clear()
        self.class_edit.addItems(known)

    def _pick_stations(self):
        """Choose a stations layer of the project when none is chosen."""
        if self.stations_combo.currentLayer() is not None:
            return
        for layer in QgsProject.instance().mapLayers().values():
            if isinstance(layer, QgsVectorLayer) and layer is not self.layer and \
                    not rs.missing_fields(layer.fields().names(), STATION_VIEW_FIELDS):
                self.stations_combo.setLayer(layer)
                return

    def _stations_changed(self, *args):
        self._stations = None
        if self.current is not None:
            self._load_chips()

    def station_records(self):
        layer = self.stations_combo.currentLayer()
        if not isinstance(layer, QgsVectorLayer) or rs.missing_fields(layer.fields().names(), STATION_VIEW_FIELDS):
            return []
        if self._stations is None or self._stations[0] != layer.id():
            wanted = [n for n in STATION_VIEW_FIELDS + ("path", "time", "station_id") if n in layer.fields().names()]
            records = [{name: _plain(f[name]) for name in wanted} for f in layer.getFeatures()]
            self._stations = (layer.id(), [r for r in records if all(r.get(n) is not None
                                                                     for n in STATION_VIEW_FIELDS)])
        return self._stations[1]

    # --- showing a sign ----------------------------------------------------------------------

    def record(self, fid=None):
        """The attributes of feature ``fid`` (default: the current sign) as a dict, with
        ``x, y, z`` of its geometry."""
        fid = self.current if fid is None else fid
        if self.layer is None or fid is None:
            return None
        feature = self.layer.getFeature(fid)
        if not feature.isValid():
            return None
        record = {name: _plain(value) for name, value in zip(self.layer.fields().names(), feature.attributes())}
        geometry = feature.geometry()
        if geometry is not None and not geometry.isEmpty():
            point = geometry.constGet()
            record["x"], record["y"] = point.x(), point.y()
            if QgsWkbTypes.hasZ(point.wkbType()) and not math.isnan(point.z()):
                record["z"] = point.z()
            elif record.get("z") is None:
                record["z"] = 0.0
        return record

    def show_sign(self, fid):
        """Make ``fid`` the current sign: its attributes, its chips, the map on it."""
        self.current = fid
        record = self.record(fid)
        enabled = record is not None and not self.missing_fields()
        for button in self.verdict_buttons + (self.view_button, self.previous_button, self.next_button):
            button.setEnabled(enabled)
        if record is None:
            if self.layer is not None and not self.missing_fields():
                self._message(self.tr("The layer {} has no signs.").format(self.layer.name()))
            self._clear_chips()
            return
        self._show_record(record)
        self._follow(fid)
        self._load_chips()

    def _show_record(self, record):
        counts = rs.tally(self._states().values())
        position = self.order.index(self.current) + 1 if self.current in self.order else 0
        reviewed = len(self.order) - counts[rs.UNREVIEWED]
        self._message(self.tr("<b>Sign {sign}</b> ({position} of {total}) &#8212; {reviewed} of {total} "
                              "reviewed").format(sign=record.get("sign_id"), position=position,
                                                 total=len(self.order), reviewed=reviewed))
        self.details.setTitle(self.tr("Sign {}").format(record.get("sign_id")))
        klass, new_class = record.get("class"), record.get(rs.REVIEWED_CLASS.name)
        self.values["class"].setText(str(klass) if not new_class else "{} &#8594; <b>{}</b>".format(klass, new_class))
        self.values["class"].setTextFormat(Qt.TextFormat.RichText)
        code, new_code = record.get(rs.CODE_FIELD), record.get(rs.REVIEWED_CODE.name)
        code_text = html.escape(str(code)) if code else self.tr("(none)")
        if code and record.get("code_name"):  # the codes table's name (refinesigns)
            code_text += " ({})".format(html.escape(str(record["code_name"])))
        if record.get("code_check"):  # class_from_code or code_dropped: look at it
            code_text += " [{}]".format(html.escape(str(record["code_check"])))
        self.values["code"].setText(code_text + (" &#8594; <b>{}</b>".format(html.escape(str(new_code)))
                                                 if new_code else ""))
        self.values["code"].setTextFormat(Qt.TextFormat.RichText)
        score = record.get("score")
        self.values["score"].setText("{:.2f}".format(float(score)) if score is not None else "–")
        condition = record.get(rs.CONDITION_FIELD)
        self.values["condition"].setText(str(condition) if condition is not None else
                                         (self.tr("(no condition field)") if rs.CONDITION_FIELD not in record
                                          else "–"))
        images = rs.image_names_of(record)
        source = record.get(rs.SOURCE_FIELD) or record.get("position_source")
        self.values["sources"].setText(self.tr("{source}; seen in {n} panorama(s): {images}").format(
            source=source or "–", n=len(images), images=", ".join(images) or "–"))
        size = [record.get(k) for k in ("width", "panel_height", "height", "azimuth")]
        text = self.tr("{width} × {height} m, {above} m above the ground, facing {azimuth}°")
        self.values["size"].setText(text.format(
            width=self._fmt(size[0]), height=self._fmt(size[1]), above=self._fmt(size[2]),
            azimuth=self._fmt(size[3], 0)) if any(v is not None for v in size) else "–")
        self.values["review"].setText(self._state_text(record))
        self.class_edit.setCurrentText(rs.effective_class(record) or "")
        self.code_edit.setText(rs.effective_code(record) or "")

    @staticmethod
    def _fmt(value, digits=2):
        try:
            return "{:.{}f}".format(float(value), digits)
        except (TypeError, ValueError):
            return "–"

    def _state_text(self, record):
        labels = {rs.ACCEPTED: self.tr("accepted"), rs.CORRECTED: self.tr("corrected"),
                  rs.REJECTED: self.tr("rejected"), rs.UNSURE: self.tr("needs another look"),
                  rs.UNREVIEWED: self.tr("not reviewed")}
        state = rs.state_of(record.get(rs.REVIEW_STATUS.name))
        text = labels.get(state, state)
        if record.get(rs.REVIEWED_AT.name):
            text += " ({})".format(record[rs.REVIEWED_AT.name])
        return text

    def _follow(self, fid):
        """Select the sign and centre the map on it."""
        self._syncing = True
        try:
            if list(self.layer.selectedFeatureIds()) != [fid]:
                self.layer.selectByIds([fid])
        finally:
            self._syncing = False
        if self.iface is None:
            return
        canvas = self.iface.mapCanvas()
        feature = self.layer.getFeature(fid)
        if feature.geometry() is None or feature.geometry().isEmpty():
            return
        transform = QgsCoordinateTransform(self.layer.crs(), canvas.mapSettings().destinationCrs(),
                                           QgsProject.instance())
        try:
            point = transform.transform(feature.geometry().asPoint())
        except Exception:  # QgsCsException: the sign cannot be shown in the map's CRS
            return
        canvas.setCenter(point)
        if canvas.scale() > ZOOM_IN_ABOVE:
            canvas.zoomScale(FOLLOW_SCALE)
        canvas.refresh()

    # --- chips ------------------------------------------------------------------------------

    def _clear_chips(self):
        self._chip_token += 1
        self.views = []
        while self.chips_layout.count():
            item = self.chips_layout.takeAt(0)
            if item.widget() is not None:
                item.widget().deleteLater()

    def _add_chip(self, pixmap, caption, tip, view=None, on_click=None):
        button = QToolButton(self.chips_box)
        button.setIcon(QIcon(QPixmap(pixmap).scaled(CHIP_PX, CHIP_PX, Qt.AspectRatioMode.KeepAspectRatio,
                                                    Qt.TransformationMode.SmoothTransformation)))
        button.setIconSize(QSize(CHIP_PX, CHIP_PX))
        button.setText(caption)
        button.setToolTip(tip)
        button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextUnderIcon)
        button.setAutoRaise(True)
        if view is not None:
            button.clicked.connect(lambda checked=False, v=view: self.show_panorama(v))
        elif on_click is not None:
            button.clicked.connect(lambda checked=False: on_click())
        self.chips_layout.addWidget(button)
        return button

    def chip_path(self, record):
        """The file of the layer's review chip (``chip`` is relative to the layer's folder)."""
        from ..core.review import CHIP_FIELD

        value = record.get(CHIP_FIELD.name)
        if not value:
            return None
        source = self.layer.source().split("|")[0]
        path = value if os.path.isabs(value) else os.path.join(os.path.dirname(source), value)
        return path if os.path.isfile(path) else None

    def _load_chips(self):
        """The layer's chip at once, then (after the panel has been drawn) one chip per
        panorama that saw the sign, best first."""
        self._clear_chips()
        record = self.record()
        if record is None:
            return
        path = self.chip_path(record)
        if path:  # the layer's chip is from the best panorama: it stands for that one
            best = record.get("best_image")
            self._add_chip(QPixmap(path), self.tr("best · {} (review chip)").format(best) if best else
                           self.tr("review chip"), path, on_click=self.show_panorama)
        token = self._chip_token
        QTimer.singleShot(0, lambda: self._cut_chips(token, record, skip_best=bool(path)))

    def _cut_chips(self, token, record, skip_best):
        if token != self._chip_token or record.get("x") is None:
            return
        stations = self.station_records()
        if not stations:
            if not self.chips_layout.count():
                self._add_chip(QPixmap(), self.tr("no picture"),
                               self.tr("Choose the stations layer (and the panorama folder) to see the sign in "
                                       "every panorama that saw it."))
            return
        from ..core.signviews import PanoramaCache, sign_views
        if self._cache is None:
            self._cache = PanoramaCache()
        folder = self.folder_widget.filePath() or None
        try:
            views = sign_views(record, stations, folder, max_views=MAX_CHIPS)
        except (ValueError, KeyError, TypeError) as error:
            QgsMessageLog.logMessage(str(error), LOG_TAG, Qgis.MessageLevel.Warning)
            return
        self.views = views
        failed = []
        for view in views:
            if token != self._chip_token:
                return
            if skip_best and view.best:
                continue
            try:
                image = self._cache.cut(view)
            except InputError as error:
                failed.append(view.image)
                QgsMessageLog.logMessage(str(error), LOG_TAG, Qgis.MessageLevel.Warning)
                continue
            caption = "{}{} · {:.0f} m".format(self.tr("best · ") if view.best else "", view.image, view.range_m)
            self._add_chip(QPixmap.fromImage(_qimage(image)), caption,
                           self.tr("{} at {:.1f} m; click for the panorama view").format(view.path, view.range_m),
                           view)
        if failed:
            self._add_chip(QPixmap(), self.tr("{} panorama(s) not found").format(len(failed)),
                           self.tr("Not found or unreadable: {}. Set the panorama folder.").format(", ".join(failed)))

    # --- the panorama view -----------------------------------------------------------------------

    def show_panorama(self, view=None):
        """A window with the wide view around the current sign from ``view``'s panorama
        (default: the best one), the sign framed."""
        record = self.record()
        stations = self.station_records()
        if record is None:
            return None
        if not stations:
            self._bar(self.tr("The panorama view needs the stations layer of the drive."))
            return None
        from ..core.signviews import PanoramaCache, context_view, sign_views
        if self._cache is None:
            self._cache = PanoramaCache()
        folder = self.folder_widget.filePath() or None
        if not hasattr(view, "view"):  # from a button or a shortcut: the best panorama
            candidates = self.views or sign_views(record, stations, folder, max_views=1)
            if not candidates:
                self._bar(self.tr("No panorama of the stations layer saw this sign."))
                return None
            view = candidates[0]
        station = next(s for s in stations if str(s["image"]) == view.image)
        wide, box = context_view(record, station, folder)
        try:
            image = _qimage(self._cache.cut(wide))
        except InputError as error:
            self._bar(str(error))
            return None
        painter = QPainter(image)
        painter.setPen(QPen(QColor(255, 220, 0), 3))
        if all(math.isfinite(v) for v in box):
            pad = 6
            painter.drawRect(int(box[0]) - pad, int(box[1]) - pad, int(box[2] - box[0]) + 2 * pad,
                             int(box[3] - box[1]) + 2 * pad)
        painter.end()
        if self.pano_dialog is None:
            self.pano_dialog = QDialog(self)
            self.pano_dialog.setObjectName("RoadSignsPanoramaView")
            layout = QVBoxLayout(self.pano_dialog)
            self.pano_label = QLabel(self.pano_dialog)
            self.pano_caption = QLabel(self.pano_dialog)
            layout.addWidget(self.pano_label)
            layout.addWidget(self.pano_caption)
        self.pano_dialog.setWindowTitle(self.tr("Panorama view: sign {}").format(record.get("sign_id")))
        self.pano_label.setPixmap(QPixmap.fromImage(image))
        self.pano_caption.setText(self.tr("{} · {:.1f} m from the sign").format(view.image, wide.range_m))
        self.pano_dialog.show()
        self.pano_dialog.raise_()
        return self.pano_dialog

    # --- verdicts ------------------------------------------------------------------------------

    def accept_sign(self):
        return self.give(rs.ACCEPTED)

    def reject_sign(self):
        return self.give(rs.REJECTED)

    def unsure_sign(self):
        return self.give(rs.UNSURE)

    def change(self):
        return self.give(rs.CORRECTED, self.class_edit.currentText(), self.code_edit.text())

    def give(self, verdict, new_class=None, new_code=None):
        """Write ``verdict`` for the current sign through the edit buffer (one undoable edit
        command) and go on to the next unreviewed sign. False when nothing was written."""
        record = self.record()
        if record is None or self.missing_fields():
            return False
        layer, fid = self.layer, self.current
        if not layer.isEditable() and not layer.startEditing():
            self._bar(self.tr("The layer {} cannot be edited: its verdicts cannot be written.").format(layer.name()))
            return False
        values = rs.verdict_values(verdict, record, new_class, new_code)
        layer.beginEditCommand(self.tr("Sign review: {} sign {}").format(values[rs.REVIEW_STATUS.name],
                                                                         record.get("sign_id")))
        for name in rs.missing_review_fields(layer.fields().names()):
            if not layer.addAttribute(QgsField(name, QMetaType.Type.QString)):
                layer.destroyEditCommand()
                self._bar(self.tr("Cannot add the field {} to the layer {}.").format(name, layer.name()))
                return False
        for name in names(rs.REVIEW_FIELDS):
            if name in values:
                layer.changeAttributeValue(fid, layer.fields().indexOf(name), values[name])
        layer.endEditCommand()
        self.history.append(fid)
        layer.triggerRepaint()
        self.next_sign()
        return True

    def undo(self):
        """Undo the last edit of the layer (a verdict) and show its sign."""
        if self.layer is None or not self.layer.undoStack().canUndo():
            return
        fid = self.history.pop() if self.history else self.current
        self.layer.undoStack().undo()
        self.show_sign(fid)

    def save(self):
        if self.layer is not None and self.layer.isEditable() and not self.layer.commitChanges(False):
            self._bar(self.tr("Cannot save the edits of {}: {}").format(
                self.layer.name(), "; ".join(self.layer.commitErrors())))

    # --- stepping -------------------------------------------------------------------------------

    def next_sign(self):
        """The next sign without a verdict (the next one when every sign has one)."""
        if not self.order:
            return
        fid = rs.next_unreviewed(self.order, self._states(), self.current)
        if fid is None:
            fid = rs.step(self.order, self.current, 1)
            self._bar(self.tr("Every sign has a verdict."), Qgis.MessageLevel.Success)
        self.show_sign(fid)

    def previous_sign(self):
        if self.order:
            self.show_sign(rs.step(self.order, self.current, -1))

    def refresh(self, *args):
        if self.layer is not None and not self.missing_fields():
            self.order = rs.review_order(self._records(("sign_id",)))
            self.show_sign(self.current if self.current in self.order else (self.order[0] if self.order else None))
        elif self.layer is not None:
            self.set_layer(self.layer)

    def _undo_stack_changed(self, *args):
        if self.current is not None and self.layer is not None:
            record = self.record()
            if record is not None:
                self._show_record(record)

    def _selection_changed(self, selected, deselected, clear_and_select):
        if self._syncing or self.layer is None:
            return
        ids = self.layer.selectedFeatureIds()
        if len(ids) == 1 and ids[0] != self.current and not self.missing_fields():
            if ids[0] not in self.order:
                self.order = rs.review_order(self._records(("sign_id",)))
            self.show_sign(ids[0])
            self.root.setFocus()

    # --- messages ---------------------------------------------------------------------------------

    def _message(self, text):
        self.message.setStyleSheet("")
        self.message.setText(text)

    def _problem(self, text):
        self.message.setStyleSheet("color: #b00020;")
        self.message.setText(text)
        self.details.setTitle(self.tr("Sign"))
        for value in self.values.values():
            value.setText("")
        for button in self.verdict_buttons + (self.view_button, self.previous_button, self.next_button):
            button.setEnabled(False)
        self._clear_chips()

    def _bar(self, text, level=Qgis.MessageLevel.Warning):
        if self.iface is not None:
            self.iface.messageBar().pushMessage(self.tr("Sign review"), text, level=level, duration=5)

    def cleanup(self):
        """Before the panel goes (the plugin is unloaded): let go of the layer."""
        try:
            QgsProject.instance().layersAdded.disconnect(self._sync_layer)
        except (TypeError, RuntimeError):
            pass
        if self.layer is not None:
            self._disconnect(self.layer)
        self.layer = None
        if self.pano_dialog is not None:
            self.pano_dialog.close()

