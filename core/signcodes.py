"""Sign codes: what each sign says (``DE:274[50]``, speed limit 50), read by a small ONNX
classifier from a crop of the panorama around each detection, then voted across the views
of one sign.

Three pieces, used by the chain in this order:

* the **codes table** (:func:`read_codes_table`): the codes a classifier may answer, each
  with an English name and one of the six sign classes (:data:`SIGN_CLASSES`);
  ``models/sign-codes-de.csv`` is the bundled one. Format: semicolon-separated UTF-8 text
  (a byte-order mark is fine), lines starting with ``#`` are comments, the header
  ``code;name;class``, then one row per code.
* the **classifier** (:class:`CodeClassifier`): an ONNX model taking square RGB crops;
  the format is in ``models/README.md`` ("Sign-code classifier: the format"). Its answer
  :data:`OTHER_CODE` means "no code it knows" (or no sign at all), :data:`BACK_CODE` "the
  back of a sign" (a plain panel facing away), an :func:`unlisted_code` "a sign of this class
  whose code the table lacks".
* the **crops** (:func:`cut_crop`) and the **vote** (:func:`vote`).

Conventions: panoramas are ``H x W x 3`` uint8 **BGR** arrays (OpenCV's order, as
:func:`core.panorama.read_panorama` returns them); crops handed to and returned by this
module are ``h x w x 3`` uint8 **RGB** arrays. Boxes are panorama pixels in the detections
layer's form (``docs/formats.md`` 2.6: ``u0`` in ``[0, W)``, ``u1`` past ``W`` across the
+-180 deg seam). Angles are degrees unless the name says otherwise.
"""
from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import geometry
from .detector import open_session, parse_names
from .errors import InputError
from .panorama import PerspectiveView
from .schema import fields

#: The six sign classes (``docs/formats.md`` section 7), the ``class`` column of a codes table.
SIGN_CLASSES = ("warning", "prohibitory", "mandatory", "information", "stop", "yield")

#: The classifier's name for "no code of the table" (or no sign at all); never in a table.
OTHER_CODE = "other"

#: The classifier's name for the back of a sign: a plain panel (grey metal, mounting rails,
#: the pole in front of it) whose face looks away from the camera; never in a table. The
#: second look drops a detection that reads it (``core/rescue.py``): the sign's face is seen
#: from the stations on its other side.
BACK_CODE = "back"

#: The classifier's names that are no code and count for no sign class.
NO_SIGN_NAMES = (OTHER_CODE, BACK_CODE)

#: Prefix of the names a classifier may answer for "a sign of this class whose code the
#: table lacks" (``unlisted:prohibitory``: a foreign no-parking sign, a limit no code has).
#: Such a reading gives no code, but it tells a sign of that class from a look-alike (the
#: second look, ``core/rescue.py``). Never in a table.
UNLISTED_CODE_PREFIX = "unlisted:"


def unlisted_code(class_name: str) -> str:
    """The classifier's name for a sign of ``class_name`` whose code the table lacks."""
    return UNLISTED_CODE_PREFIX + class_name


def unlisted_code_class(name: str) -> Optional[str]:
    """The class of an :func:`unlisted_code` name (one of :data:`SIGN_CLASSES`), else None."""
    if not name.startswith(UNLISTED_CODE_PREFIX):
        return None
    klass = name[len(UNLISTED_CODE_PREFIX):]
    return klass if klass in SIGN_CLASSES else None


def is_code(name: str) -> bool:
    """Whether a classifier's answer is a code of the table: not empty, not one of
    :data:`NO_SIGN_NAMES`, not an :func:`unlisted_code`."""
    return bool(name) and name not in NO_SIGN_NAMES and not name.startswith(UNLISTED_CODE_PREFIX)


#: Fraction of the box's longer angular side added on each side of a crop.
DEFAULT_CROP_MARGIN = 0.15

#: Crops per run of a classifier whose batch is dynamic.
DEFAULT_MAX_BATCH = 64

#: Output kinds of the metadata ``output``: the model's own softmax, or raw scores.
OUTPUT_KINDS = ("probabilities", "logits")

#: The header of a codes table.
TABLE_HEADER = ("code", "name", "class")

#: Detection-level fields: the code the classifier read in that one view and its
#: probability (0..1); ``other`` when it knows none.
CODE_FIELDS = fields(("code", str), ("code_score", float))

#: Sign-level fields: the code voted across the sign's views (:func:`vote`), its name from
#: the codes table, its support (0..1: its share of the weighted vote x the mean code
#: probability of the views that read it; ``refine.vote_code``), the number of views that
#: read it, and ``code_check``: "" (code and class agree, or no code), ``class_from_code``
#: or ``code_dropped`` (code and class disagreed; the better-supported one was kept).
SIGN_CODE_FIELDS = fields(("code", str), ("code_name", str), ("code_score", float),
                          ("code_views", int), ("code_check", str))

#: Default minimum support of a voted code (``CODE_CONFIDENCE`` of ``refinesigns`` and
#: ``fusesigns``): a code whose support (:func:`code_support`) is below this is left empty.
DEFAULT_CODE_CONFIDENCE = 0.5
#: ``code_check`` values: the code's class replaced the class vote; the code was dropped.
CLASS_FROM_CODE, CODE_DROPPED = "class_from_code", "code_dropped"


# --- the codes table ----------------------------------------------------------------------

@dataclass(frozen=True)
class SignCode:
    """One row of a codes table: ``code`` (e.g. ``DE:274[50]``), its English ``name`` and
    its ``class_name``, one of :data:`SIGN_CLASSES`."""

    code: str
    name: str
    class_name: str


class CodesTable:
    """The codes a classifier may answer, in file order (see :func:`read_codes_table`)."""

    def __init__(self, entries: Sequence[SignCode], path: str = ""):
        self.path = path
        self._entries: Dict[str, SignCode] = {e.code: e for e in entries}
        self.codes: Tuple[str, ...] = tuple(e.code for e in entries)

    def entry(self, code: str) -> SignCode:
        """The row of ``code``; :class:`KeyError` when the table has none."""
        return self._entries[code]

    def __contains__(self, code: object) -> bool:
        return code in self._entries

    def __len__(self) -> int:
        return len(self.codes)

    def __iter__(self) -> Iterator[SignCode]:
        return (self._entries[c] for c in self.codes)


def read_codes_table(path: str) -> CodesTable:
    """Read a codes table (format in the module doc).

    :class:`InputError` naming the file, the line (1-based, comment and blank lines
    counted) and what was expected, for: an unreadable or non-UTF-8 file, a missing or
    other header, a row without exactly three fields, an empty code or name, the code
    :data:`NO_SIGN_NAMES`, a code twice (both lines named), a class not in
    :data:`SIGN_CLASSES`, and a table without rows. Blanks around fields are dropped and
    classes are read case-insensitively; empty fields after the third (a semicolon at the
    end of the line) are allowed.
    """
    try:
        with open(path, "r", encoding="utf-8-sig", newline="") as f:
            text = f.read()
    except FileNotFoundError:
        raise InputError("Sign codes table not found: {path}", path=path)
    except UnicodeDecodeError as e:
        raise InputError("Cannot read the sign codes table {path}: it is not UTF-8 text (byte "
                         "{position}); save it as UTF-8", path=path, position=e.start + 1)
    except OSError as e:
        raise InputError("Cannot read the sign codes table {path}: {error}", path=path,
                         error=e.strerror or str(e))

    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    header_seen = False
    entries: List[SignCode] = []
    line_of: Dict[str, int] = {}
    for line_no, line in enumerate(lines, start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            row = [f.strip() for f in next(csv.reader([line], delimiter=";"))]
        except csv.Error as e:
            raise InputError("Sign codes table {path}, line {line}: cannot split the line into "
                             "fields ({error})", path=path, line=line_no, error=str(e))
        while len(row) > len(TABLE_HEADER) and not row[-1]:
            row.pop()
        if not header_seen:
            if [f.lower() for f in row] != list(TABLE_HEADER):
                raise InputError("Sign codes table {path}, line {line}: expected the header "
                                 "{expected}, found {found}", path=path, line=line_no,
                                 expected=";".join(TABLE_HEADER), found=line.strip())
            header_seen = True
            continue
        if len(row) != len(TABLE_HEADER):
            raise InputError("Sign codes table {path}, line {line}: expected 3 fields separated "
                             "by semicolons ({expected}), found {count}", path=path, line=line_no,
                             expected=";".join(TABLE_HEADER), count=len(row))
        code, name, class_name = row[0], row[1], row[2].lower()
        if not code:
            raise InputError("Sign codes table {path}, line {line}: the code is empty",
                             path=path, line=line_no)
        if code.lower() in NO_SIGN_NAMES or code.lower().startswith(UNLISTED_CODE_PREFIX):
            raise InputError("Sign codes table {path}, line {line}: the code {code} is reserved "
                             "for signs the classifier cannot read and must not be in the table",
                             path=path, line=line_no, code=code)
        if not name:
            raise InputError("Sign codes table {path}, line {line}: the name of {code} is empty",
                             path=path, line=line_no, code=code)
        if code in line_of:
            raise InputError("Sign codes table {path}, lines {first} and {line}: the code {code} "
                             "is there twice", path=path, first=line_of[code], line=line_no, code=code)
        if class_name not in SIGN_CLASSES:
            raise InputError("Sign codes table {path}, line {line}: unknown class {found} for "
                             "{code}; expected one of {classes}", path=path, line=line_no,
                             found=row[2], code=code, classes=", ".join(SIGN_CLASSES))
        line_of[code] = line_no
        entries.append(SignCode(code, name, class_name))
    if not header_seen:
        raise InputError("Sign codes table {path} is empty: expected the header {expected} and "
                         "one row per code", path=path, expected=";".join(TABLE_HEADER))
    if not entries:
        raise InputError("Sign codes table {path} holds no codes: expected one row per code "
                         "after the header {expected}", path=path, expected=";".join(TABLE_HEADER))
    return CodesTable(entries, path)


# --- the classifier ---------------------------------------------------------------------

def _is_dim(value) -> bool:
    return isinstance(value, int) and value > 0


def softmax(x: np.ndarray) -> np.ndarray:
    """Softmax over the last axis (stable)."""
    z = np.asarray(x, np.float64)
    z = np.exp(z - z.max(axis=-1, keepdims=True))
    return z / z.sum(axis=-1, keepdims=True)


class CodeClassifier:
    """A sign-code classifier (ONNX, format in ``models/README.md``) in an onnxruntime session.

    ``table``: the codes its names must come from (besides :data:`NO_SIGN_NAMES` and
    :func:`unlisted_code` names); ``threads``:
    onnxruntime intra-op threads (0 = its default). Attributes: ``names`` (output order),
    ``input_px`` (the crop side S), ``crop_margin`` (metadata, else
    :data:`DEFAULT_CROP_MARGIN`), ``max_batch`` (:data:`DEFAULT_MAX_BATCH` when the batch is
    dynamic, else the fixed N), ``output_kind`` (``probabilities`` or ``logits``).
    :class:`InputError` for a missing or non-ONNX file, a model of another task, missing or
    unknown names, an input or output shape it does not support, or bad metadata.
    """

    def __init__(self, model_path: str, table: CodesTable, threads: int = 0):
        self.model_path = model_path
        self.table = table
        self.session = open_session(model_path, threads)
        meta = self.session.get_modelmeta().custom_metadata_map or {}
        task = meta.get("task")
        if task and task != "classify":
            raise InputError("The model {path} is a {task} model; reading sign codes needs a "
                             "classify model (metadata task = classify)", path=model_path, task=task)
        self.names: Tuple[str, ...] = self._read_names(meta)
        self.output_kind = self._read_output_kind(meta)
        self.crop_margin = self._read_crop_margin(meta)

        inp = self.session.get_inputs()[0]
        shape = list(inp.shape)
        if (len(shape) != 4 or shape[1] != 3 or not _is_dim(shape[2]) or shape[2] != shape[3]
                or inp.type not in ("tensor(float)", "tensor(float16)")):
            raise InputError("The model {path} takes an input {name} of shape {shape} and type "
                             "{type}; supported: float [batch, 3, S, S] (RGB crops S x S pixels, "
                             "values 0..1)", path=model_path, name=inp.name, shape=shape,
                             type=inp.type)
        self.input_name = inp.name
        self.input_dtype = np.float16 if inp.type == "tensor(float16)" else np.float32
        self.input_px = int(shape[2])
        self._fixed_batch = int(shape[0]) if _is_dim(shape[0]) else 0
        self.max_batch = self._fixed_batch or DEFAULT_MAX_BATCH

        # The declared output shape may be symbolic: run a blank batch to see the real one.
        blank = np.zeros((self._fixed_batch or 1, 3, self.input_px, self.input_px), self.input_dtype)
        try:
            out = np.asarray(self.session.run(None, {self.input_name: blank})[0])
        except Exception as e:  # onnxruntime raises its own pybind types
            raise InputError("The model {path} failed on a blank {side} x {side} crop: {error}",
                             path=model_path, side=self.input_px, error=str(e))
        if out.ndim != 2 or out.shape[1] != len(self.names) or out.shape[0] != blank.shape[0]:
            raise InputError("The model {path} has an output of shape {shape} for a batch of "
                             "{batch}; supported: [batch, C] with C = {count}, its number of names",
                             path=model_path, shape=list(out.shape), batch=blank.shape[0],
                             count=len(self.names))

    def _read_names(self, meta) -> Tuple[str, ...]:
        names = parse_names(meta["names"]) if "names" in meta else None
        if not names:
            raise InputError("The model {path} names no codes: its metadata needs 'names', a JSON "
                             "list of the sign codes in output order (such as [\"DE:206\", "
                             "\"other\"])", path=self.model_path)
        names = [n.strip() for n in names]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise InputError("The model {path} names {names} more than once in its metadata "
                             "'names'", path=self.model_path, names=", ".join(twice))
        unknown = [n for n in names if n not in NO_SIGN_NAMES and not unlisted_code_class(n) and n not in self.table]
        if unknown:
            shown = ", ".join(unknown[:5]) + (" and {} more".format(len(unknown) - 5)
                                              if len(unknown) > 5 else "")
            raise InputError("The model {path} answers codes that are not in the sign codes table "
                             "{table}: {names}", path=self.model_path, table=self.table.path,
                             names=shown)
        return tuple(names)

    def _read_output_kind(self, meta) -> str:
        kind = meta.get("output", OUTPUT_KINDS[0]).strip().lower()
        if kind not in OUTPUT_KINDS:
            raise InputError("The model {path} has the metadata output = {found}; expected "
                             "{expected}", path=self.model_path, found=meta.get("output"),
                             expected=" or ".join(OUTPUT_KINDS))
        return kind

    def _read_crop_margin(self, meta) -> float:
        if "crop_margin" not in meta:
            return DEFAULT_CROP_MARGIN
        try:
            margin = float(meta["crop_margin"])
        except ValueError:
            margin = float("nan")
        if not (0.0 <= margin <= 2.0):
            raise InputError("The model {path} has the metadata crop_margin = {found}; expected a "
                             "number from 0 to 2 (the fraction of the box's longer side added on "
                             "each side)", path=self.model_path, found=meta["crop_margin"])
        return margin

    def _blob(self, crops_rgb: Sequence[np.ndarray]) -> np.ndarray:
        import cv2

        s = self.input_px
        blob = np.zeros((len(crops_rgb), 3, s, s), np.float32)
        for k, crop in enumerate(crops_rgb):
            crop = np.asarray(crop)
            if crop.ndim != 3 or crop.shape[2] != 3 or crop.shape[0] < 1 or crop.shape[1] < 1:
                raise ValueError("crop {}: expected an h x w x 3 RGB array, got shape {}".format(
                    k, crop.shape))
            if crop.dtype != np.uint8:
                crop = np.clip(crop, 0, 255).astype(np.uint8)
            h, w = crop.shape[:2]
            if (h, w) != (s, s):
                shrinking = h >= s and w >= s
                crop = cv2.resize(crop, (s, s), interpolation=cv2.INTER_AREA if shrinking
                                  else cv2.INTER_LINEAR)
            blob[k] = crop.transpose(2, 0, 1).astype(np.float32) / 255.0
        return blob

    def probabilities(self, crops_rgb: Sequence[np.ndarray]) -> np.ndarray:
        """``(n, C)`` probabilities of each name for each crop (RGB uint8, any size)."""
        if len(crops_rgb) == 0:
            return np.zeros((0, len(self.names)))
        rows = []
        for start in range(0, len(crops_rgb), self.max_batch):
            blob = self._blob(crops_rgb[start:start + self.max_batch])
            n = len(blob)
            if self._fixed_batch and n < self._fixed_batch:  # pad a fixed batch with blanks
                blob = np.concatenate([blob, np.zeros((self._fixed_batch - n,) + blob.shape[1:],
                                                      blob.dtype)])
            out = self.session.run(None, {self.input_name: blob.astype(self.input_dtype)})[0]
            rows.append(np.asarray(out, np.float64)[:n])
        scores = np.concatenate(rows)
        return softmax(scores) if self.output_kind == "logits" else scores

    def classify(self, crops_rgb: Sequence[np.ndarray]) -> Tuple[List[str], np.ndarray]:
        """The best name for each crop (``h x w x 3`` uint8 **RGB**, any size: resized to S x S,
        ``INTER_AREA`` when both sides shrink, else ``INTER_LINEAR``) and its probability, in
        batches of ``max_batch``. An empty input gives ``([], empty array)``."""
        probs = self.probabilities(crops_rgb)
        best = probs.argmax(axis=1) if len(probs) else np.zeros(0, np.int64)
        return [self.names[i] for i in best], probs[np.arange(len(best)), best].astype(float)

    def cut_crop(self, pano_bgr: np.ndarray, box_px) -> np.ndarray:
        """The crop of a panorama box this classifier reads (:func:`cut_crop` with its margin):
        sampled at the panorama's density up to :data:`READ_SAMPLE_FACTOR` x its input side,
        which :meth:`classify` then shrinks to the input side with ``INTER_AREA``; sampling
        big signs at their full native density would cost more and give the same picture."""
        side = READ_SAMPLE_FACTOR * self.input_px
        return cut_crop(pano_bgr, box_px, self.crop_margin, max_side_px=side, max_sample_px=side)

    def describe(self) -> str:
        """One line for the log: file, number of codes, input size, output kind, providers."""
        n_codes = sum(1 for n in self.names if is_code(n))
        n_classes = sum(1 for n in self.names if unlisted_code_class(n))
        return ("{}: {} codes{}{}, input {} x {} px RGB crops (margin {:g}), {}, batch {}, "
                "providers {}".format(os.path.basename(self.model_path), n_codes,
                                      ", {} classes of signs without a code".format(n_classes) if n_classes else "",
                                      "".join(" and '{}'".format(n) for n in NO_SIGN_NAMES if n in self.names),
                                      self.input_px, self.input_px, self.crop_margin,
                                      self.output_kind, self.max_batch,
                                      ", ".join(self.session.get_providers())))


# --- crops ------------------------------------------------------------------------------

#: The widest crop cut, in degrees (a pinhole view cannot show half the sphere).
MAX_CROP_FOV_DEG = 120.0
#: Supersampling limit when a crop is cut smaller than its native size (anti-aliasing).
MAX_SUPERSAMPLE = 4
#: The crops the chain reads are sampled at most this many times the classifier's input
#: side (:meth:`CodeClassifier.cut_crop`).
READ_SAMPLE_FACTOR = 2


def square_view(yaw_deg: float, pitch_deg: float, size_deg: float, width_px: int,
                margin: float = DEFAULT_CROP_MARGIN, max_side_px: int = 256) -> Tuple[PerspectiveView, int]:
    """The square crop view looking along (``yaw_deg``, ``pitch_deg``) of the panorama (no
    roll) around a sign ``size_deg`` across, and the view's native side.

    Field of view: ``size_deg x (1 + 2 margin)``, at least one panorama pixel and at most
    :data:`MAX_CROP_FOV_DEG`. The native side is that field of view in panorama pixels
    (``fov / 360 x width_px``, the panorama's sampling along a great circle); the view's side
    is it clamped to ``[8, max_side_px]``.
    """
    fov_deg = float(size_deg) * (1.0 + 2.0 * max(float(margin), 0.0))
    fov_deg = min(max(fov_deg, 360.0 / width_px), MAX_CROP_FOV_DEG)  # at least one pixel
    native_px = fov_deg / 360.0 * width_px
    side = int(min(max(round(native_px), 8), max(int(max_side_px), 8)))
    return PerspectiveView(float(yaw_deg), float(pitch_deg), fov_deg, side, side), int(round(native_px))


def box_angles_deg(box_px, width_px: int, height_px: int) -> Tuple[float, float, float, float]:
    """A panorama box's centre ray (yaw, pitch) and its angular width and height, degrees:
    width ``(u1 - u0) / W x 360 x cos(elevation)``, height ``(v1 - v0) / H x 180``."""
    u0, v0, u1, v1 = (float(x) for x in box_px)
    if not all(math.isfinite(x) for x in (u0, v0, u1, v1)):
        raise InputError("The box {box} is not four finite pixel coordinates u0, v0, u1, v1",
                         box=[u0, v0, u1, v1])
    u, v = geometry.box_centre_pixel(u0, v0, u1, v1, width_px)
    yaw_rad, pitch_rad = geometry.pixel_to_angles_rad(u, v, width_px, height_px)
    box_w_deg = max(u1 - u0, 0.0) / width_px * 360.0 * math.cos(float(pitch_rad))
    box_h_deg = max(v1 - v0, 0.0) / height_px * 180.0
    return float(np.degrees(yaw_rad)), float(np.degrees(pitch_rad)), box_w_deg, box_h_deg


def crop_view(box_px, width_px: int, height_px: int, margin: float = DEFAULT_CROP_MARGIN,
              max_side_px: int = 256) -> Tuple[PerspectiveView, int]:
    """The square view :func:`cut_crop` cuts for a panorama box, and the box's native side.

    The view looks along the ray of the box centre; the sign's size is the box's larger
    angular side (:func:`box_angles_deg`); the rest is :func:`square_view`.
    """
    yaw_deg, pitch_deg, box_w_deg, box_h_deg = box_angles_deg(box_px, width_px, height_px)
    return square_view(yaw_deg, pitch_deg, max(box_w_deg, box_h_deg), width_px, margin, max_side_px)


def _aspect(box_w_deg: float, box_h_deg: float) -> float:
    larger = max(box_w_deg, box_h_deg)
    return min(box_w_deg, box_h_deg) / larger if larger > 0 else 0.0


def box_aspect(box_px, width_px: int, height_px: int) -> float:
    """A panorama box's smaller angular side over its larger (0..1; :func:`box_angles_deg`):
    1 for a sign seen face on, small for one seen edge-on."""
    return _aspect(*box_angles_deg(box_px, width_px, height_px)[2:])


def legible_side_px(box_px, width_px: int, height_px: int, margin: float = DEFAULT_CROP_MARGIN) -> float:
    """The pixels the classifier gets across a box's sign at its narrower side: the side of
    the crop :func:`crop_view` cuts x :func:`box_aspect` (the box's angles measured once). A
    sign seen face on keeps its crop side; one passed close by at a steep angle, boxed tall
    and narrow, is read from a crop squeezed across, and weighs that much less in the code
    vote."""
    yaw_deg, pitch_deg, box_w_deg, box_h_deg = box_angles_deg(box_px, width_px, height_px)
    view, _ = square_view(yaw_deg, pitch_deg, max(box_w_deg, box_h_deg), width_px, margin)
    return view.width_px * _aspect(box_w_deg, box_h_deg)


def view_box_crop_view(view: PerspectiveView, box_xyxy, width_px: int, margin: float = DEFAULT_CROP_MARGIN,
                       max_side_px: int = 256) -> Tuple[PerspectiveView, int]:
    """The square crop view (:func:`square_view`) of a box found in a perspective ``view``
    of a panorama ``width_px`` wide: centred on the ray of the box centre, the sign's size
    the angle the box's larger side spans there."""
    x0, y0, x1, y1 = (float(x) for x in box_xyxy)
    ray = view.pixel_to_ray(0.5 * (x0 + x1), 0.5 * (y0 + y1))
    yaw_rad, pitch_rad = geometry.ray_to_angles_rad(ray)
    corners = view.pixel_to_ray(np.array([x0, x1, x0, x0]), np.array([y0, y0, y0, y1]))
    across = [float(np.arccos(np.clip(np.dot(corners[i], corners[i + 1]), -1.0, 1.0))) for i in (0, 2)]
    return square_view(float(np.degrees(yaw_rad)), float(np.degrees(pitch_rad)), math.degrees(max(across)),
                       width_px, margin, max_side_px)


def cut_crop(pano_bgr: np.ndarray, box_px, margin: float = DEFAULT_CROP_MARGIN,
             max_side_px: int = 256, max_sample_px: Optional[int] = None) -> np.ndarray:
    """A square **RGB** uint8 crop of the panorama (``H x W x 3`` **BGR**) around a box.

    ``box_px``: ``(u0, v0, u1, v1)`` in panorama pixels, detections layer form (``u1`` past
    ``W`` across the seam). The crop is a rectified perspective view centred on the box
    centre's ray (:func:`crop_view`: field of view the box's larger angular side x
    ``(1 + 2 margin)``, side in panorama pixels at the native density, clamped to
    ``[8, max_side_px]``), cut by :func:`cut_square_view` (``max_sample_px``: see there).
    """
    pano = _bgr_panorama(pano_bgr)
    return cut_square_view(pano, *crop_view(box_px, pano.shape[1], pano.shape[0], margin, max_side_px),
                           max_sample_px=max_sample_px)


def _bgr_panorama(pano_bgr: np.ndarray) -> np.ndarray:
    pano = np.asarray(pano_bgr)
    if pano.ndim != 3 or pano.shape[2] != 3:
        raise ValueError("expected an H x W x 3 BGR panorama, got shape {}".format(pano.shape))
    return pano


def cut_square_view(pano_bgr: np.ndarray, view: PerspectiveView, native_px: int,
                    max_sample_px: Optional[int] = None) -> np.ndarray:
    """The **RGB** uint8 picture of a crop ``view`` (:func:`square_view`) of the panorama
    (``H x W x 3`` **BGR**). Columns wrap across the +-180 deg seam. A view cut smaller than
    its ``native_px`` side is sampled up to :data:`MAX_SUPERSAMPLE` x finer and shrunk with
    ``INTER_AREA``, so that fine print does not alias. With ``max_sample_px``, at most that
    many samples a side are taken; where that is coarser than the panorama, the panorama's
    patch under the view is first shrunk to the samples' density with ``INTER_AREA`` (the
    same anti-aliasing, from fewer rays)."""
    import cv2

    pano = _bgr_panorama(pano_bgr)
    H, W = pano.shape[:2]
    side = view.width_px
    factor = int(min(max(math.ceil(native_px / side), 1), MAX_SUPERSAMPLE))
    if max_sample_px is not None:
        factor = max(1, min(factor, int(max_sample_px) // side))
    n = side * factor
    sample = PerspectiveView(view.yaw_deg, view.pitch_deg, view.hfov_deg, n, n)
    ys, xs = np.mgrid[0:n, 0:n].astype(float) + 0.5
    u, v = geometry.ray_to_pixel(sample.pixel_to_ray(xs, ys), W, H)
    map_x = (u - 0.5).astype(np.float32)  # cv2 samples pixel centres at integer coordinates
    map_y = np.clip(v - 0.5, 0.0, H - 1.0).astype(np.float32)
    shrink = native_px / n
    if max_sample_px is not None and shrink > 1.0:
        crop = _remap_shrunk(pano, map_x, map_y, shrink)
        if crop is None:  # a view wider than the panorama's patches: supersampled as usual
            return cut_square_view(pano, view, native_px)
        return np.ascontiguousarray(crop[:, :, ::-1])
    # BORDER_WRAP joins the columns across the seam; rows never leave the image (clamped).
    crop = cv2.remap(pano, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_WRAP)
    if factor > 1:
        crop = cv2.resize(crop, (side, side), interpolation=cv2.INTER_AREA)
    return np.ascontiguousarray(crop[:, :, ::-1])


def _remap_shrunk(pano: np.ndarray, map_x: np.ndarray, map_y: np.ndarray,
                  shrink: float) -> Optional[np.ndarray]:
    """``cv2.remap`` of the panorama at maps sampling it ``shrink`` (> 1) x coarser than its
    pixels, from its patch under the maps shrunk by ``shrink`` with ``INTER_AREA``; columns
    are taken around the view's centre, across the seam too. None when the patch would be
    wider than half the panorama."""
    import cv2

    H, W = pano.shape[:2]
    n = map_x.shape[0]
    centre = float(map_x[n // 2, n // 2])
    map_x = (centre + np.mod(map_x - centre + 0.5 * W, W) - 0.5 * W).astype(np.float32)  # no jump at the seam
    x0, x1 = int(math.floor(float(map_x.min()))) - 2, int(math.ceil(float(map_x.max()))) + 3
    y0, y1 = max(int(math.floor(float(map_y.min()))) - 2, 0), min(int(math.ceil(float(map_y.max()))) + 3, H)
    if x1 - x0 > W // 2:
        return None
    patch = pano[y0:y1].take(np.arange(x0, x1), axis=1, mode="wrap")
    w_small = max(1, int(round((x1 - x0) / shrink)))
    h_small = max(1, int(round((y1 - y0) / shrink)))
    small = cv2.resize(patch, (w_small, h_small), interpolation=cv2.INTER_AREA)
    sx, sy = w_small / (x1 - x0), h_small / (y1 - y0)
    mx = ((map_x + 0.5 - x0) * sx - 0.5).astype(np.float32)
    my = ((map_y + 0.5 - y0) * sy - 0.5).astype(np.float32)
    return cv2.remap(small, mx, my, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)


# --- the vote ---------------------------------------------------------------------------

def vote(codes: Sequence[str], scores: Sequence[float],
         weights: Sequence[float]) -> Tuple[str, float, int]:
    """Weighted vote of the codes read in the views of one sign.

    View ``i`` gives its code ``codes[i]`` the vote ``weights[i] x scores[i]`` (the caller
    passes detection score x crop side as the weight; negative or NaN weights and scores
    count as 0). Returns the code with the largest total, its share of all the votes
    (0..1; 0 when every vote is 0) and the number of views that read it. Ties (equal
    totals) go to the code with the largest single weight, then to the code read first.
    :data:`OTHER_CODE` can win. No views: ``("", 0.0, 0)``.
    """
    if not (len(codes) == len(scores) == len(weights)):
        raise ValueError("vote: codes, scores and weights differ in length ({}, {}, {})".format(
            len(codes), len(scores), len(weights)))
    if not len(codes):
        return "", 0.0, 0

    def positive(x) -> float:
        x = float(x)
        return x if x > 0.0 else 0.0  # NaN fails the comparison too

    totals: Dict[str, float] = {}
    top_weight: Dict[str, float] = {}
    views: Dict[str, int] = {}
    for code, score, weight in zip(codes, scores, weights):
        w = positive(weight)
        totals[code] = totals.get(code, 0.0) + w * positive(score)
        top_weight[code] = max(top_weight.get(code, 0.0), w)
        views[code] = views.get(code, 0) + 1
    best_total = max(totals.values())
    tied = [c for c, t in totals.items() if math.isclose(t, best_total, rel_tol=1e-9, abs_tol=1e-12)]
    winner = max(tied, key=lambda c: top_weight[c])  # max keeps the first of equals: read first
    grand = sum(totals.values())
    share = totals[winner] / grand if grand > 0 else 0.0
    return winner, float(min(max(share, 0.0), 1.0)), views[winner]


def code_support(codes: Sequence[str], probs: Union[Sequence[float], np.ndarray],
                 weights: Union[Sequence[float], np.ndarray]) -> Tuple[str, float, int]:
    """The code voted across the views of one sign, and its **support**.

    View ``i`` read ``codes[i]`` with probability ``probs[i]`` and weighs ``weights[i]``
    (detection score x crop side in pixels); it votes ``weights[i] x probs[i]``
    (:func:`vote`). The support is the winner's share of the vote x the ``weights``-weighted
    mean probability of the views that read it (0..1; a code every view read with certainty
    has 1). Returns (code, support, views that read it); no views: ``("", nan, 0)``.
    """
    if not len(codes):
        return "", math.nan, 0
    p = np.clip(np.nan_to_num(np.asarray(probs, float)), 0.0, 1.0)
    w = np.clip(np.nan_to_num(np.asarray(weights, float)), 0.0, None)
    winner, share, n_views = vote(codes, p.tolist(), w.tolist())
    theirs = np.array([c == winner for c in codes], bool)
    mean_p = float((w[theirs] * p[theirs]).sum() / w[theirs].sum()) if w[theirs].sum() > 0 else 0.0
    return winner, float(share * mean_p), n_views


def class_support(classes: Sequence[str], scores: Sequence[float], klass: str) -> float:
    """How well views support the class ``klass`` (the other side of :func:`decide_code`'s
    check): its share of the score-weighted class vote (the detection scores of its views
    over all views' scores) x the mean detection score of its views; 0..1."""
    s = np.clip(np.nan_to_num(np.asarray(scores, float)), 0.0, 1.0)
    mine = np.array([c == klass for c in classes], bool)
    if not np.any(mine) or s.sum() <= 0:
        return 0.0
    return float(s[mine].sum() / s.sum() * s[mine].mean())


@dataclass
class CodeVote:
    """A sign's code after the vote and the class check (:func:`decide_code`): the
    :data:`SIGN_CODE_FIELDS` values and the sign's class after the check (``klass``)."""

    code: str
    name: str
    score: float
    views: int
    check: str
    klass: str

    def fields(self) -> Dict[str, Any]:
        return {"code": self.code, "code_name": self.name, "code_score": self.score,
                "code_views": self.views, "code_check": self.check}


def decide_code(winner: str, support: float, n_views: int, klass: str,
                class_support: Callable[[], float], table: Optional[CodesTable] = None,
                confidence: float = DEFAULT_CODE_CONFIDENCE) -> CodeVote:
    """What a sign keeps of the code :func:`code_support` voted, with its class ``klass``.

    ``code`` and ``code_name`` are empty when the winner is one of :data:`NO_SIGN_NAMES` or an
    :func:`unlisted_code` (:func:`is_code`), nothing was read (``winner`` empty) or the
    support is below ``confidence`` (``code_score`` and ``code_views`` still describe the
    winner). **Class check**, for a kept code whose class in
    ``table`` differs from ``klass`` (when ``klass`` is one of :data:`SIGN_CLASSES`):
    ``class_support()`` is the class's support (0..1); a code with a strictly larger support
    gives the sign its class (``code_check = class_from_code``), else the code is emptied
    (``code_check = code_dropped``). Without a ``table`` the name is empty and there is no
    check. The caller makes sure ``winner`` is in ``table``.
    """
    if not is_code(winner) or not support >= confidence:
        return CodeVote("", "", support, n_views, "", klass)
    if table is None:
        return CodeVote(winner, "", support, n_views, "", klass)
    entry = table.entry(winner)
    if entry.class_name == klass or klass not in SIGN_CLASSES:
        return CodeVote(winner, entry.name, support, n_views, "", klass)
    if support > class_support():
        return CodeVote(winner, entry.name, support, n_views, CLASS_FROM_CODE, entry.class_name)
    return CodeVote("", "", support, n_views, CODE_DROPPED, klass)
