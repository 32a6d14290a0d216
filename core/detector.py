"""Sign detection with an ONNX model (onnxruntime), on images and on whole panoramas.

Models: YOLO-family detectors as Ultralytics, YOLOv5/v7 and NMS-exporting tools write
them. Input: one ``[batch, 3, h, w]`` float tensor, RGB in 0..1, letterboxed (aspect
kept, grey 114 padding, centred); or, as the bundled int8 detector takes it
(``devtools.train.rawinput``), the letterboxed pixels themselves: ``uint8 [batch, h, w, 3]``,
channels in the order the metadata ``channel_order`` gives (``BGR``, OpenCV's, else RGB).
Output: the first output, one of the layouts in :data:`LAYOUTS` (``nc`` = number of class
names, ``N`` = number of candidates)::

    yolov8  [1, 4+nc, N]  cx, cy, w, h, nc class scores (YOLOv8/11, no objectness)
    yolov5  [1, N, 5+nc]  cx, cy, w, h, objectness, nc class probabilities (YOLOv5/7);
                          score = objectness x class probability
    nms     [1, N, 6]     x1, y1, x2, y2, score, class id (NMS built in, or an NMS-free
                          head such as YOLOv10/YOLO26 end-to-end)

Box coordinates are in model-input pixels. The layout is chosen by which axis fits
``nc``; when two fit: the longer axis is the candidate axis (yolov8 against the others),
and ``[1, N, 6]`` with a single class (yolov5 with nc = 1 has 5+nc = 6 too) is read as
yolov5 only when N is a YOLOv5 anchor-grid count for the input size (3 anchors on strides
8/16/32, or 8/16/32/64), else as nms. ``layout=`` overrides the choice.

Class names, first found: names the caller gives; the model's metadata ``names``
(Ultralytics writes a Python dict literal ``{0: 'warning', ...}``; a list works too);
a labels file beside the model, ``<model stem>.labels.txt``, ``<model file>.labels.txt``
or ``labels.txt`` (one name per line).

Images are numpy ``H x W x 3`` uint8 arrays in OpenCV's BGR order (as
:func:`core.panorama.read_panorama` returns them); boxes come back in their pixels
(continuous coordinates, the image spans ``[0, W] x [0, H]``).
"""
from __future__ import annotations

import ast
import json
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Callable, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import sheeting
from .errors import SILENT, InputError, Progress
from .panorama import ViewSet, boxes_from_seam
from .zoomlook import ZoomRule, confirm, zoom_rules

#: Output layouts this module decodes, as named in messages.
LAYOUTS = {
    "yolov8": "YOLOv8/11 [1, 4+nc, N]",
    "yolov5": "YOLOv5/7 [1, N, 5+nc]",
    "nms": "NMS built in [1, N, 6] (x1, y1, x2, y2, score, class)",
}

#: Execution providers used when onnxruntime offers them, best first.
PREFERRED_PROVIDERS = ("CUDAExecutionProvider", "DmlExecutionProvider",
                       "CoreMLExecutionProvider", "CPUExecutionProvider")

DEFAULT_INPUT_PX = 640
#: Metadata entry with the channel order of a uint8 channels-last input: "BGR" or "RGB" (default).
CHANNEL_ORDER_KEY = "channel_order"
LETTERBOX_FILL = 114
MAX_DETECTIONS_PER_IMAGE = 300
MAX_BATCH = 8


@dataclass
class ImageDetections:
    """Detections in one image: ``boxes_xyxy`` (n, 4) float in image pixels, ``scores`` (n,)
    float, ``class_ids`` (n,) int."""

    boxes_xyxy: np.ndarray
    scores: np.ndarray
    class_ids: np.ndarray

    @classmethod
    def empty(cls) -> "ImageDetections":
        return cls(np.zeros((0, 4)), np.zeros(0), np.zeros(0, dtype=np.int64))

    def __len__(self) -> int:
        return len(self.scores)


@dataclass
class ModelInfo:
    """What the adapter logs about a model."""

    path: str
    input_width_px: int
    input_height_px: int
    class_names: List[str]
    names_source: str  # "caller", "metadata" or the labels file's path
    layout: str
    output_shape: Tuple[int, ...]
    providers: List[str]

    def describe(self) -> str:
        return (f"{os.path.basename(self.path)}: {LAYOUTS[self.layout]}, output "
                f"{list(self.output_shape)}, input {self.input_width_px} x {self.input_height_px} px, "
                f"{len(self.class_names)} classes ({', '.join(self.class_names)}) from "
                f"{self.names_source}, providers {', '.join(self.providers)}")


# --- class names ------------------------------------------------------------------------

def parse_names(text: str) -> Optional[List[str]]:
    """Class names from a metadata string: a dict ``{0: 'a', 1: 'b'}`` (Ultralytics) or a
    list, as a Python or JSON literal. ``None`` when it is neither."""
    value = None
    for parse in (ast.literal_eval, json.loads):  # literal_eval evaluates literals only
        try:
            value = parse(text)
            break
        except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError):
            continue
    if isinstance(value, dict):
        try:
            ids = {int(k): str(v) for k, v in value.items()}
        except (TypeError, ValueError):
            return None
        if not ids or min(ids) < 0:
            return None
        return [ids.get(k, f"class_{k}") for k in range(max(ids) + 1)]
    if isinstance(value, (list, tuple)) and value:
        return [str(v) for v in value]
    return None


def read_labels_file(path: str) -> List[str]:
    """One class name per line; blank lines are skipped."""
    try:
        with open(path, encoding="utf-8-sig") as f:
            names = [line.strip() for line in f if line.strip()]
    except (OSError, UnicodeDecodeError) as e:
        raise InputError("Cannot read the labels file {path}: {error}", path=path, error=str(e))
    if not names:
        raise InputError("The labels file {path} holds no class names (one name per line)", path=path)
    return names


def labels_file_candidates(model_path: str) -> List[str]:
    stem, _ = os.path.splitext(model_path)
    return [stem + ".labels.txt", model_path + ".labels.txt",
            os.path.join(os.path.dirname(model_path), "labels.txt")]


# --- layouts and decoders ---------------------------------------------------------------

def yolov5_anchor_counts(input_w: int, input_h: int) -> set:
    """Candidate counts of YOLOv5/7 dense heads (3 anchors a cell) for an input size."""
    def cells(strides):
        return 3 * sum(-(-input_w // s) * -(-input_h // s) for s in strides)
    return {cells((8, 16, 32)), cells((8, 16, 32, 64))}


def choose_layout(shape: Sequence[int], n_classes: int, input_w: int, input_h: int,
                  model_path: str = "") -> str:
    """The layout of an output of ``shape`` for ``n_classes`` (rules in the module doc)."""
    shape = tuple(int(s) for s in shape)
    fits = []
    if len(shape) == 3:
        a, b = shape[1], shape[2]
        if a == 4 + n_classes:
            fits.append("yolov8")
        if b == 5 + n_classes:
            fits.append("yolov5")
        if b == 6:
            fits.append("nms")
        if "yolov8" in fits and len(fits) > 1:
            fits = ["yolov8"] if b > a else [f for f in fits if f != "yolov8"]
        if fits == ["yolov5", "nms"]:
            fits = ["yolov5"] if a in yolov5_anchor_counts(input_w, input_h) else ["nms"]
    if not fits:
        raise InputError(
            "The model {path} has an output of shape {shape}, which is no layout this plugin "
            "decodes for {n_classes} class names; supported: {supported}",
            path=model_path, shape=list(shape), n_classes=n_classes,
            supported="; ".join(LAYOUTS.values()))
    return fits[0]


def check_layout(layout: str, shape: Sequence[int], n_classes: int, model_path: str = "") -> None:
    """Raise :class:`InputError` unless ``shape`` fits the forced ``layout``."""
    shape = tuple(int(s) for s in shape)
    want = {"yolov8": (1, 4 + n_classes), "yolov5": (2, 5 + n_classes), "nms": (2, 6)}
    if layout not in want:
        raise InputError("Unknown output layout {layout}: use one of {layouts}",
                         layout=layout, layouts=", ".join(LAYOUTS))
    axis, size = want[layout]
    if len(shape) != 3 or shape[axis] != size:
        raise InputError("The model {path} has an output of shape {shape}, which does not fit "
                         "the layout {layout} with {n_classes} class names",
                         path=model_path, shape=list(shape), layout=LAYOUTS[layout],
                         n_classes=n_classes)


def _xywh_to_xyxy(b: np.ndarray) -> np.ndarray:
    half = 0.5 * b[:, 2:4]
    return np.concatenate([b[:, :2] - half, b[:, :2] + half], axis=1)


def decode(layout: str, output: np.ndarray, confidence: float):
    """One image's raw output (the batch row, 2-D) -> boxes xyxy, scores, class ids above
    ``confidence``, in model-input pixels, before NMS."""
    out = np.asarray(output, dtype=np.float32)
    if layout == "yolov8":
        out = out.T  # [N, 4+nc]
        cls_scores = out[:, 4:]
        class_ids = cls_scores.argmax(axis=1)
        scores = cls_scores[np.arange(len(out)), class_ids]
        keep = scores > confidence
        return _xywh_to_xyxy(out[keep, :4]), scores[keep], class_ids[keep]
    if layout == "yolov5":
        out = out[out[:, 4] > confidence]
        cls_probs = out[:, 5:]
        class_ids = cls_probs.argmax(axis=1)
        scores = out[:, 4] * cls_probs[np.arange(len(out)), class_ids]
        keep = scores > confidence
        return _xywh_to_xyxy(out[keep, :4]), scores[keep], class_ids[keep]
    if layout == "nms":
        out = out[out[:, 4] > confidence]
        return out[:, :4].copy(), out[:, 4], np.rint(out[:, 5]).astype(np.int64)
    raise ValueError(layout)


def nms_per_class(boxes_xyxy: np.ndarray, scores: np.ndarray, class_ids: np.ndarray,
                  iou_threshold: float, max_detections: int = MAX_DETECTIONS_PER_IMAGE) -> np.ndarray:
    """Indices kept by per-class non-maximum suppression, best score first."""
    import cv2

    if len(scores) == 0:
        return np.zeros(0, dtype=np.int64)
    xywh = np.concatenate([boxes_xyxy[:, :2], boxes_xyxy[:, 2:] - boxes_xyxy[:, :2]], axis=1)
    kept_by_cv2 = cv2.dnn.NMSBoxesBatched(xywh.tolist(), np.asarray(scores, float).tolist(),
                                          np.asarray(class_ids, int).tolist(), 0.0, float(iou_threshold))
    keep = np.asarray(kept_by_cv2, dtype=np.int64).reshape(-1)
    keep = keep[np.argsort(-scores[keep], kind="stable")]
    return keep[:max_detections]


# --- letterbox --------------------------------------------------------------------------

#: An image a model of any input size runs on at its own size (``own_size``) is padded to
#: multiples of this: the bundled detector's coarsest stride.
OWN_SIZE_MULTIPLE_PX = 32


def letterbox(image: np.ndarray, input_w: int, input_h: int, fit: bool = True):
    """Resize keeping the aspect and pad centred with grey 114 (Ultralytics' letterbox);
    ``fit=False``: pad only (the image no larger than the input).

    Returns the padded image and ``(scale, pad_x, pad_y)``: input pixel = image pixel x
    scale + pad.
    """
    import cv2

    h, w = image.shape[:2]
    scale = min(input_w / w, input_h / h) if fit else 1.0
    new_w, new_h = int(round(w * scale)), int(round(h * scale))
    if (new_w, new_h) != (w, h):
        image = cv2.resize(image, (new_w, new_h), interpolation=cv2.INTER_LINEAR)
    dw, dh = (input_w - new_w) / 2.0, (input_h - new_h) / 2.0
    top, left = int(round(dh - 0.1)), int(round(dw - 0.1))
    if (new_w, new_h) != (input_w, input_h):
        image = cv2.copyMakeBorder(image, top, input_h - new_h - top, left, input_w - new_w - left,
                                   cv2.BORDER_CONSTANT, value=(LETTERBOX_FILL,) * 3)
    return image, (scale, float(left), float(top))


def unletterbox(boxes_xyxy: np.ndarray, transform, image_w: int, image_h: int) -> np.ndarray:
    """Model-input boxes back to image pixels, clipped to the image."""
    scale, pad_x, pad_y = transform
    b = (boxes_xyxy - np.array([pad_x, pad_y, pad_x, pad_y])) / scale
    return np.clip(b, 0.0, [image_w, image_h, image_w, image_h])


# --- the detector -----------------------------------------------------------------------

def choose_providers(available: Sequence[str]) -> List[str]:
    """The preferred execution providers onnxruntime offers, in :data:`PREFERRED_PROVIDERS` order."""
    chosen = [p for p in PREFERRED_PROVIDERS if p in available]
    return chosen or list(available)


#: Whether onnxruntime's intra-op threads spin while they wait for work. No: on two cores a
#: spinning thread holds the core that decoding the next panorama and cutting the sign-code
#: crops need (bench/README.md, "Threads that do not spin": ``detect_drive`` 1.4 x faster,
#: the same detections).
SPIN_WAIT = False


def open_session(model_path: str, threads: int = 0, providers: Optional[Sequence[str]] = None):
    """An onnxruntime session; :class:`InputError` naming the file when it is missing or
    not a model onnxruntime loads."""
    import onnxruntime as ort

    if not os.path.isfile(model_path):
        raise InputError("Model not found: {path}", path=model_path)
    options = ort.SessionOptions()
    options.intra_op_num_threads = int(threads)
    options.log_severity_level = 3
    options.add_session_config_entry("session.intra_op.allow_spinning", "1" if SPIN_WAIT else "0")
    try:
        return ort.InferenceSession(
            model_path, sess_options=options,
            providers=list(providers) if providers else choose_providers(ort.get_available_providers()))
    except Exception as e:  # onnxruntime raises its own pybind types (InvalidProtobuf, Fail, ...)
        error = (str(e).strip().splitlines() or [type(e).__name__])[0]
        raise InputError("{path} is not an ONNX model onnxruntime can load: {error}",
                         path=model_path, error=error)


class Detector:
    """An ONNX detection model in an onnxruntime session.

    ``class_names``: override the names from the model and labels files; ``layout``: force
    ``"yolov8"``, ``"yolov5"`` or ``"nms"``; ``threads``: onnxruntime intra-op threads (0 =
    its default); ``providers``: override the execution providers; ``input_size_px``: used
    when the model's input size is dynamic (else the metadata ``imgsz``, else 640);
    ``max_batch``: images a run when the model's batch is dynamic (default: 8 on an
    accelerator, 1 on the CPU).
    :class:`InputError` for a missing or non-ONNX file, a non-detection model, missing class
    names or an output layout not decoded.
    """

    def __init__(self, model_path: str, class_names: Optional[Sequence[str]] = None,
                 layout: Optional[str] = None, threads: int = 0,
                 providers: Optional[Sequence[str]] = None, input_size_px: Optional[int] = None,
                 max_batch: Optional[int] = None):
        self.model_path = model_path
        self.session = open_session(model_path, threads, providers)
        meta = self.session.get_modelmeta().custom_metadata_map or {}
        task = meta.get("task")
        if task and task != "detect":
            raise InputError("The model {path} is a {task} model; sign detection needs a "
                             "detection model", path=model_path, task=task)
        self.class_names, self.names_source = self._find_names(class_names, meta)

        inp = self.session.get_inputs()[0]
        #: uint8 [batch, h, w, 3] pixels (True) or float [batch, 3, h, w] in 0..1 (False)
        self.channels_last = inp.type == "tensor(uint8)"
        if len(inp.shape) != 4 or (self.channels_last and inp.shape[3] != 3):
            raise InputError("The model {path} takes an input of shape {shape}; an image model takes "
                             "float [batch, 3, height, width] or uint8 [batch, height, width, 3]",
                             path=model_path, shape=list(inp.shape))
        self.input_name = inp.name
        self.input_dtype = np.uint8 if self.channels_last else (
            np.float16 if inp.type == "tensor(float16)" else np.float32)
        self.input_bgr = self.channels_last and str(meta.get(CHANNEL_ORDER_KEY, "RGB")).upper() == "BGR"
        sides = inp.shape[1:3] if self.channels_last else inp.shape[2:4]
        self.input_w, self.input_h = self._input_size(sides, meta, input_size_px)
        #: Whether the model's input height and width are symbolic: it then also runs on
        #: images of their own size (``detect_many(..., own_size=True)``: a horizon band).
        self.takes_any_size = not all(isinstance(side, int) and side > 0 for side in sides)
        if isinstance(inp.shape[0], int) and inp.shape[0] > 1:
            raise InputError("The model {path} has a fixed batch of {batch}; use a batch of 1 or "
                             "a dynamic batch", path=model_path, batch=inp.shape[0])
        if isinstance(inp.shape[0], int):
            self.max_batch = 1
        elif max_batch:
            self.max_batch = int(max_batch)
        else:  # batches pay on an accelerator; on the CPU they only cost memory
            on_cpu = self.session.get_providers()[0] == "CPUExecutionProvider"
            self.max_batch = 1 if on_cpu else MAX_BATCH

        # The declared output shape may be symbolic: run one blank image to see the real one,
        # so a layout we do not decode fails here and not on the first panorama.
        blank = np.zeros((1, self.input_h, self.input_w, 3) if self.channels_last
                         else (1, 3, self.input_h, self.input_w), dtype=self.input_dtype)
        try:
            out = self.session.run(None, {self.input_name: blank})[0]
        except Exception as e:
            raise InputError("The model {path} failed on a blank {w} x {h} image: {error}",
                             path=model_path, w=self.input_w, h=self.input_h, error=str(e))
        self.output_shape = tuple(int(s) for s in out.shape)
        if layout:
            check_layout(layout, self.output_shape, len(self.class_names), model_path)
            self.layout = layout
        else:
            self.layout = choose_layout(self.output_shape, len(self.class_names),
                                        self.input_w, self.input_h, model_path)

    def _find_names(self, class_names, meta):
        if class_names:
            return [str(n) for n in class_names], "caller"
        names = parse_names(meta["names"]) if "names" in meta else None
        if names:
            return names, "metadata"
        for path in labels_file_candidates(self.model_path):
            if os.path.isfile(path):
                return read_labels_file(path), path
        raise InputError("The model {path} names no classes: its metadata has no readable "
                         "'names' and there is no labels file ({labels}, one class name per line)",
                         path=self.model_path,
                         labels=" or ".join(map(os.path.basename, labels_file_candidates(self.model_path))))

    @staticmethod
    def _input_size(sides, meta, input_size_px):
        h, w = sides
        if isinstance(h, int) and isinstance(w, int) and h > 0 and w > 0:
            return w, h
        if input_size_px:
            return int(input_size_px), int(input_size_px)
        imgsz = parse_names(meta["imgsz"]) if "imgsz" in meta else None  # "[640, 640]": h, w
        if imgsz and len(imgsz) == 2 and all(s.isdigit() for s in imgsz):
            return int(imgsz[1]), int(imgsz[0])
        return DEFAULT_INPUT_PX, DEFAULT_INPUT_PX

    @property
    def input_size(self) -> Tuple[int, int]:
        """``(width_px, height_px)`` of the model input: the natural size of the views."""
        return self.input_w, self.input_h

    def info(self) -> ModelInfo:
        return ModelInfo(self.model_path, self.input_w, self.input_h, list(self.class_names),
                         self.names_source, self.layout, self.output_shape,
                         list(self.session.get_providers()))

    def check_runs(self, width_px: int, height_px: int) -> None:
        """:class:`InputError` unless the model runs on a ``width_px`` x ``height_px`` image at
        its own size (:attr:`takes_any_size`, or that is its input size)."""
        if not self.takes_any_size and (width_px, height_px) != (self.input_w, self.input_h):
            raise InputError("The model {path} takes {w} x {h} px images only; the horizon seen as one band "
                             "({bw} x {bh} px) needs a model whose input height and width are free, as the bundled "
                             "detector's are", path=self.model_path, w=self.input_w, h=self.input_h,
                             bw=width_px, bh=height_px)

    def run_raw(self, images: Sequence[np.ndarray], own_size: bool = False):
        """Letterbox and infer a batch; returns the raw output rows and the transforms.
        ``own_size``: the images (all of one size) are padded to the next multiples of
        :data:`OWN_SIZE_MULTIPLE_PX` rather than fitted into the model's input size;
        :class:`InputError` unless the model takes any size (:attr:`takes_any_size`)."""
        import cv2

        if own_size:
            self.check_runs(images[0].shape[1], images[0].shape[0])
            h, w = images[0].shape[:2]
            m = OWN_SIZE_MULTIPLE_PX
            boxed = [letterbox(image, -(-w // m) * m, -(-h // m) * m, fit=False) for image in images]
        else:
            boxed = [letterbox(image, self.input_w, self.input_h) for image in images]
        if self.channels_last:           # the pixels as they are, BGR (OpenCV's order) or RGB
            blob = np.stack([b for b, _ in boxed])
            if not self.input_bgr:
                blob = np.ascontiguousarray(blob[..., ::-1])
        else:                            # BGR HWC uint8 -> RGB NCHW float in 0..1
            blob = cv2.dnn.blobFromImages([b for b, _ in boxed], 1.0 / 255.0, swapRB=True)
            if blob.dtype != self.input_dtype:
                blob = blob.astype(self.input_dtype)
        return self.session.run(None, {self.input_name: blob})[0], [t for _, t in boxed]

    def detect_many(self, images: Sequence[np.ndarray], confidence: float = 0.25,
                    iou_threshold: float = 0.45, own_size: bool = False) -> List[ImageDetections]:
        """Detections in each image (batched when the model's batch is dynamic); ``own_size``:
        as :meth:`run_raw`, one image a run."""
        results = []
        step = 1 if own_size else self.max_batch
        for start in range(0, len(images), step):
            chunk = images[start:start + step]
            output, transforms = self.run_raw(chunk, own_size)
            for image, row, transform in zip(chunk, output, transforms):
                results.append(self._postprocess(row, transform, image.shape[1], image.shape[0],
                                                 confidence, iou_threshold))
        return results

    def detect(self, image: np.ndarray, confidence: float = 0.25,
               iou_threshold: float = 0.45) -> ImageDetections:
        return self.detect_many([image], confidence, iou_threshold)[0]

    def _postprocess(self, row, transform, image_w, image_h, confidence, iou_threshold):
        boxes, scores, class_ids = decode(self.layout, row, confidence)
        valid = (class_ids >= 0) & (class_ids < len(self.class_names))
        boxes, scores, class_ids = boxes[valid], scores[valid], class_ids[valid]
        boxes = unletterbox(boxes, transform, image_w, image_h)
        nonempty = (boxes[:, 2] > boxes[:, 0]) & (boxes[:, 3] > boxes[:, 1])
        boxes, scores, class_ids = boxes[nonempty], scores[nonempty], class_ids[nonempty]
        keep = nms_per_class(boxes, scores, class_ids, iou_threshold)
        return ImageDetections(boxes[keep].astype(float), scores[keep].astype(float),
                               class_ids[keep].astype(np.int64))


def model_info(model_path: str, class_names: Optional[Sequence[str]] = None, **kwargs) -> ModelInfo:
    """Load a model as :class:`Detector` does (same errors) and describe it."""
    return Detector(model_path, class_names, **kwargs).info()


# --- panoramas --------------------------------------------------------------------------

@dataclass
class PanoramaDetections:
    """Signs found in one panorama, one row each (after merging across views).

    ``u0, v0, u1, v1``: panorama pixels in the detections layer's form (u0 in [0, W), u1 > u0,
    past W across the +-180 deg seam). ``view_index``: the view the box comes from;
    ``n_views``: how many view detections were merged into it. ``code`` and ``code_score``:
    the sign code a classifier read in the box and its probability
    (:func:`.detections.read_codes`; ``""`` and NaN without a classifier). ``candidate``:
    a box scored under the confidence, kept only for a second look (:mod:`.rescue`);
    :func:`detect_drive` drops the candidates that are left after it. ``lone_upward``: the
    box is one upward view's (:attr:`~.panorama.PerspectiveView.looks_up`) alone, no other
    view's box merged into it; the second look drops such a box when the classifier reads
    no sign code in it (:attr:`.rescue.RescueRule.drop_lone_upward_other`).
    """

    class_id: np.ndarray
    class_name: List[str]
    score: np.ndarray
    u0: np.ndarray
    v0: np.ndarray
    u1: np.ndarray
    v1: np.ndarray
    view_index: np.ndarray
    n_views: np.ndarray
    code: List[str] = field(default_factory=list)
    code_score: np.ndarray = field(default_factory=lambda: np.zeros(0))
    candidate: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    lone_upward: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))

    def __post_init__(self) -> None:
        n = len(self.score)
        if len(self.code) != n:
            self.code = [""] * n
        if len(self.code_score) != n:
            self.code_score = np.full(n, np.nan)
        if len(self.candidate) != n:
            self.candidate = np.zeros(n, bool)
        if len(self.lone_upward) != n:
            self.lone_upward = np.zeros(n, bool)

    def __len__(self) -> int:
        return len(self.score)

    def subset(self, rows) -> "PanoramaDetections":
        """The rows ``rows`` (a mask or indices), in that order."""
        rows = np.flatnonzero(rows) if np.asarray(rows).dtype == bool else np.asarray(rows, np.int64)
        return PanoramaDetections(
            self.class_id[rows], [self.class_name[k] for k in rows], self.score[rows], self.u0[rows],
            self.v0[rows], self.u1[rows], self.v1[rows], self.view_index[rows], self.n_views[rows],
            [self.code[k] for k in rows], self.code_score[rows], self.candidate[rows], self.lone_upward[rows])

    @staticmethod
    def concatenate(parts: Sequence["PanoramaDetections"]) -> "PanoramaDetections":
        """The rows of ``parts`` one after the other."""
        def cat(name):
            return np.concatenate([getattr(p, name) for p in parts])
        return PanoramaDetections(
            cat("class_id"), [n for p in parts for n in p.class_name], cat("score"), cat("u0"), cat("v0"),
            cat("u1"), cat("v1"), cat("view_index"), cat("n_views"), [c for p in parts for c in p.code],
            cat("code_score"), cat("candidate"), cat("lone_upward"))

    def boxes(self) -> np.ndarray:
        return np.stack([self.u0, self.v0, self.u1, self.v1], axis=1).reshape(-1, 4)


def seam_aware_overlap(box: np.ndarray, boxes: np.ndarray, pano_width_px: float) -> np.ndarray:
    """Intersection over the smaller area of ``box`` with each of ``boxes`` (u0, v0, u1, v1),
    comparing columns modulo W (a box is also tried shifted by -W and +W)."""
    ih = np.clip(np.minimum(box[3], boxes[:, 3]) - np.maximum(box[1], boxes[:, 1]), 0, None)
    iw = np.zeros(len(boxes))
    for shift in (-pano_width_px, 0.0, pano_width_px):
        iw = np.maximum(iw, np.clip(np.minimum(box[2] + shift, boxes[:, 2])
                                    - np.maximum(box[0] + shift, boxes[:, 0]), 0, None))
    area = (box[2] - box[0]) * (box[3] - box[1])
    areas = (boxes[:, 2] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 1])
    return iw * ih / np.maximum(np.minimum(area, areas), 1e-9)


def _seam_shift_px(kept_box: np.ndarray, boxes: np.ndarray, pano_width_px: float) -> np.ndarray:
    """Whole multiples of W that put each of ``boxes`` (n, 4) next to ``kept_box``."""
    b = np.asarray(boxes, float).reshape(-1, 4)
    return np.round(((kept_box[0] + kept_box[2]) - (b[:, 0] + b[:, 2])) / (2 * pano_width_px)) * pano_width_px


def _union_box(kept: np.ndarray, other: np.ndarray, pano_width_px: float) -> np.ndarray:
    """Union of two overlapping boxes, ``other`` shifted by a whole W to sit next to ``kept``."""
    shift = _seam_shift_px(kept, other, pano_width_px)[0]
    return np.array([min(kept[0], other[0] + shift), min(kept[1], other[1]),
                     max(kept[2], other[2] + shift), max(kept[3], other[3])])


def _fused_box(kept_box: np.ndarray, boxes: np.ndarray, scores: np.ndarray, pano_width_px: float) -> np.ndarray:
    """Score-weighted mean of complete ``boxes`` of one sign (weighted box fusion), each
    shifted by a whole W to sit next to ``kept_box``."""
    b = np.asarray(boxes, float).copy()
    b[:, [0, 2]] += _seam_shift_px(kept_box, b, pano_width_px)[:, None]
    w = np.asarray(scores, float)
    return (b * w[:, None]).sum(axis=0) / max(w.sum(), 1e-12)


def merge_view_detections(boxes: np.ndarray, scores: np.ndarray, class_ids: np.ndarray,
                          complete: np.ndarray, centrality: np.ndarray, pano_width_px: int,
                          overlap_threshold: float = 0.5, fuse_class_ids: Optional[np.ndarray] = None):
    """Merge the same sign seen in overlapping views.

    Candidates are ranked complete (not touching a view edge) first, then by score, then by
    centrality; each is kept unless it overlaps a kept one of the same class by at least
    ``overlap_threshold`` (intersection over the smaller box, seam-aware: a cut box lies
    inside the complete one). The box of a complete sign is the score-weighted mean of its
    complete boxes (weighted box fusion: views that see the sign whole each locate it); a
    kept box that is itself cut grows to the union with the cut boxes merged into it.
    The kept candidate gives the class and score. ``fuse_class_ids`` (default
    ``class_ids``): only members of the kept box's class in it move its box, so boxes merged
    across classes (``class_ids`` all alike) keep the place of the best one, not a place
    between two neighbouring signs. Returns (kept indices, merged boxes, merge counts).
    """
    fuse_ids = class_ids if fuse_class_ids is None else fuse_class_ids
    order = np.lexsort((-centrality, -scores, ~complete.astype(bool)))
    kept: List[int] = []
    kept_boxes: List[np.ndarray] = []
    members: List[List[int]] = []
    for i in order:
        match = -1
        same = [k for k, j in enumerate(kept) if class_ids[j] == class_ids[i]]
        if same:
            overlaps = seam_aware_overlap(boxes[i], np.array([kept_boxes[k] for k in same]), pano_width_px)
            best = int(np.argmax(overlaps))
            if overlaps[best] >= overlap_threshold:
                match = same[best]
        if match < 0:
            kept.append(i)
            kept_boxes.append(boxes[i].astype(float))
            members.append([i])
            continue
        members[match].append(i)
        if not complete[kept[match]] and not complete[i] and fuse_ids[i] == fuse_ids[kept[match]]:
            kept_boxes[match] = _union_box(kept_boxes[match], boxes[i], pano_width_px)
    for k, i in enumerate(kept):
        whole = [j for j in members[k] if complete[j] and fuse_ids[j] == fuse_ids[i]]
        if complete[i] and len(whole) > 1:
            kept_boxes[k] = _fused_box(kept_boxes[k], boxes[whole], scores[whole], pano_width_px)
    out = boxes_from_seam(np.array(kept_boxes).reshape(-1, 4), pano_width_px)  # the detections layer's form
    counts = np.array([len(m) for m in members], dtype=np.int64)
    return np.array(kept, dtype=np.int64), out, counts


#: Default of detectsigns' (and fusesigns') CONFIDENCE: boxes scoring below it are dropped,
#: or given the second look (:mod:`.rescue`) from its RESCUE_CONFIDENCE. The bundled file's
#: plugin path (second look on) on held-out real photographs, GTSDB 500-599, at the densities
#: the plugin's views give: best F1 at 0.5 (P 0.918 / R 0.944; 0.905 / 0.944 at 0.4, 0.917 /
#: 0.930 at 0.55, 0.942 / 0.915 at 0.6); at the photographs' own density 0.55 is one false
#: box better, and on five held-out generated streets 0.5 and 0.55 tie (models/README.md,
#: "Bundled on 27 November"; measured while the second look still read single codes).
DEFAULT_CONFIDENCE = 0.5

#: Shorter side (panorama pixels) under which ``roadsigns:detectsigns`` drops a box by
#: default: signs that small are boxed a few pixels off and their class is unsure, and a
#: drive sees them again, larger, from the next stations. 12 since 28 November (14 before):
#: the network's boxes of signs 14-20 px high are often 12-13 px wide, and 14 dropped them
#: (models/README.md, "The smallest box kept").
DEFAULT_MIN_BOX_PX = 12.0


def _merged(detector, rows: Sequence[np.ndarray], W: int, overlap_threshold: float, min_box_px: float,
            class_agnostic: bool = False) -> PanoramaDetections:
    """:func:`merge_view_detections` of the view boxes ``rows`` = (boxes in panorama pixels,
    scores, class ids, views, complete, central, from an upward view, cut at the view's left or
    right side) as rows; merged boxes whose shorter side is under ``min_box_px`` are dropped,
    and so is a box an upward view cut at its side that no other view's box joined
    (:func:`detect_panorama`). ``class_agnostic``: boxes of any class merge (the kept one
    gives the class and, with the boxes of its class, the place)."""
    boxes, scores, ids, views, complete, central, upward, side_cut = rows
    kept, merged, counts = merge_view_detections(
        boxes, scores, np.zeros_like(ids) if class_agnostic else ids, complete, central, W, overlap_threshold,
        fuse_class_ids=ids)
    big_enough = np.minimum(merged[:, 2] - merged[:, 0], merged[:, 3] - merged[:, 1]) >= min_box_px
    lone_upward = upward[kept] & (counts == 1)
    wanted = big_enough & ~(lone_upward & side_cut[kept])
    kept, merged, counts = kept[wanted], merged[wanted], counts[wanted]
    names = list(detector.class_names)
    return PanoramaDetections(ids[kept], [names[c] for c in ids[kept]], scores[kept],
                              merged[:, 0], merged[:, 1], merged[:, 2], merged[:, 3], views[kept], counts,
                              lone_upward=lone_upward[wanted])


def view_batches(views: ViewSet, batch: int) -> List[List[int]]:
    """The indices of ``views`` in the runs the detector makes, in view order: a view run at
    its own size (``own_size``, the horizon band) alone, the others ``batch`` at a time."""
    fitted = [k for k, view in enumerate(views) if not view.own_size]
    runs = [[k] for k, view in enumerate(views) if view.own_size]
    runs += [fitted[start:start + batch] for start in range(0, len(fitted), batch)]
    return sorted(runs)


def detect_panorama(detector, pano: np.ndarray, views: ViewSet, confidence: float = 0.25,
                    iou_threshold: float = 0.45, overlap_threshold: float = 0.5,
                    min_box_px: float = 0.0, candidate_confidence: Optional[float] = None,
                    progress: Progress = SILENT, fit_tall: bool = True,
                    zoom: Union[ZoomRule, Sequence[ZoomRule], None] = None,
                    view_images: Optional[Sequence[np.ndarray]] = None) -> PanoramaDetections:
    """Run ``detector`` on each view of ``pano`` (BGR array) and merge the results.
    ``view_images``: the views already cut (``list(views.cut_all(pano))``), else cut here.

    ``detector``: a :class:`Detector`, or any object with ``class_names`` and
    ``detect(image, confidence, iou_threshold) -> ImageDetections`` (``detect_many`` is
    used when present, to batch views). Boxes are mapped to panorama pixels through each
    view and merged by :func:`merge_view_detections`; merged boxes whose shorter side is
    under ``min_box_px`` panorama pixels are dropped. A view that is run at its own size
    (``own_size``: the horizon as one :class:`.panorama.BandView`) goes through a
    :class:`Detector` alone, with ``own_size=True``; another detector's ``detect`` takes it
    as it is.

    A box an upward view (:attr:`~.panorama.PerspectiveView.looks_up`) cuts at its left or
    right side is dropped unless another view's box joins it: those views look over the
    road for panels overhead, and a sign they cut at the side stands beside it, seen whole
    by the horizon views of the stations before; mapped to the panorama, the lone cut box
    lies on part of the sign only.

    ``candidate_confidence`` (under ``confidence``): the boxes scoring from it up to
    ``confidence`` are merged apart (across classes) and added as rows marked ``candidate``,
    except where they overlap a detection; the detections are the same as without it.

    ``zoom`` (a :class:`.zoomlook.ZoomRule`, several, or None): the zoomed look. The small
    boxes scoring from ``zoom.min_score`` under ``confidence`` that overlap no detection are
    cut again at a higher pixel density and detected once more, all of a panorama's in one
    network run (:func:`.zoomlook.zoomed_scores`); those scored
    ``confidence`` or more there become detections with the zoomed score, class and box. With
    several rules (``detectsigns``' edge-on look, :data:`.zoomlook.DEFAULT_EDGE_ON`, and its
    zoomed look), each cuts its own tiles of the boxes it takes, all packed into the same
    network runs, and a box two rules take keeps its higher zoomed score. The rest stay
    candidates when from ``candidate_confidence``.
    """
    H, W = pano.shape[:2]
    if view_images is None:
        view_images = list(views.cut_all(pano))
    lowest = confidence if candidate_confidence is None else min(confidence, candidate_confidence)
    looks = zoom_rules(zoom)
    for rule in looks:
        lowest = min(lowest, rule.min_score)
    batch = max(1, int(getattr(detector, "max_batch", 1)))
    all_boxes, all_scores, all_ids, all_views, all_complete, all_central = [], [], [], [], [], []
    all_upward: List[np.ndarray] = []
    all_side_cut: List[np.ndarray] = []
    for chunk in view_batches(views, batch):
        images = [view_images[k] for k in chunk]
        if views[chunk[0]].own_size and isinstance(detector, Detector):   # a horizon band, alone
            per_view = detector.detect_many(images, lowest, iou_threshold, own_size=True)
        elif hasattr(detector, "detect_many"):
            per_view = detector.detect_many(images, lowest, iou_threshold)
        else:
            per_view = [detector.detect(image, lowest, iou_threshold) for image in images]
        for k, det in zip(chunk, per_view):
            if len(det) == 0:
                continue
            view = views[k]
            all_boxes.append(view.boxes_to_pano(det.boxes_xyxy, W, H))
            all_scores.append(np.asarray(det.scores, float))
            all_ids.append(np.asarray(det.class_ids, np.int64))
            all_views.append(np.full(len(det), k, dtype=np.int64))
            all_complete.append(~view.touches_edge(det.boxes_xyxy))
            all_central.append(view.centrality(det.boxes_xyxy))
            all_upward.append(np.full(len(det), view.looks_up))
            all_side_cut.append(view.touches_side(det.boxes_xyxy))
        progress.report((chunk[-1] + 1) / len(views))
    if not all_boxes:
        z = np.zeros(0)
        return PanoramaDetections(np.zeros(0, np.int64), [], z, z, z, z, z,
                                  np.zeros(0, np.int64), np.zeros(0, np.int64))
    rows = [np.concatenate(a) for a in (all_boxes, all_scores, all_ids, all_views, all_complete, all_central,
                                        all_upward, all_side_cut)]
    sure = rows[1] >= confidence
    found = _merged(detector, [a[sure] for a in rows], W, overlap_threshold, min_box_px)
    if lowest < confidence and not sure.all():
        low = _merged(detector, [a[~sure] for a in rows], W, overlap_threshold, min_box_px, class_agnostic=True)
        on_sign = np.array([len(found) > 0 and seam_aware_overlap(box, found.boxes(), W).max() >= overlap_threshold
                            for box in low.boxes()], bool).reshape(-1)
        low = low.subset(~on_sign)
        low.candidate[:] = True
        if looks:
            low = zoomed_look(detector, pano, low, confidence, looks)
        if candidate_confidence is None:
            low = low.subset(~low.candidate)
        else:
            low = low.subset(~low.candidate | (low.score >= candidate_confidence))
        found = PanoramaDetections.concatenate([found, low])
    # candidates keep the network's box: the second look judges them on it, then fits them
    return fit_tall_boxes(pano, found, rows=~found.candidate) if fit_tall else found


def zoomed_look(detector, pano: np.ndarray, low: PanoramaDetections, confidence: float,
                zoom: Union[ZoomRule, Sequence[ZoomRule]]) -> PanoramaDetections:
    """``low`` (rows of the panorama ``pano``) with the candidates among them that the zoomed
    looks ``zoom`` confirm (:func:`.zoomlook.confirm`) made detections: :func:`detect_panorama`'s
    ``zoom``."""
    still = np.flatnonzero(low.candidate)
    rows, score, class_id, box = confirm(detector, pano, low.boxes()[still], low.score[still], confidence, zoom)
    rows = still[rows]
    names = list(detector.class_names)
    box = boxes_from_seam(box, pano.shape[1])   # the detections layer's form
    for k, s, c, b in zip(rows, score, class_id, box):
        low.candidate[k] = False
        low.score[k], low.class_id[k], low.class_name[k] = s, c, names[c]
        low.u0[k], low.v0[k], low.u1[k], low.v1[k] = b
    return low


def fit_tall_boxes(pano: np.ndarray, found: PanoramaDetections, rows: Optional[np.ndarray] = None
                   ) -> PanoramaDetections:
    """``found`` (detections of the panorama ``pano``, BGR) with each box much taller than
    wide narrowed to the columns that show sign sheeting colours
    (:func:`.sheeting.fit_tall_boxes`), in place; returns it. ``rows``: a mask of the rows to
    fit (default all). A sign passed close by is seen nearly edge-on, and the network boxes it
    about twice as wide as its face."""
    which = np.ones(len(found), bool) if rows is None else np.asarray(rows, bool)
    if which.any():
        fitted = boxes_from_seam(sheeting.fit_tall_boxes(pano, found.boxes()[which], wrap=True), pano.shape[1])
        u0, u1 = np.array(found.u0, float), np.array(found.u1, float)
        u0[which], u1[which] = fitted[:, 0], fitted[:, 2]
        found.u0, found.u1 = u0, u1
    return found


# --- a drive ------------------------------------------------------------------------------

#: Default of detectsigns' STATION_SPACING_M (metres): a panorama detected in at least every
#: 5 m of drive. Two held-out streets with a panorama every 5 m had every sign found, every
#: 10 m lost 2 in 45 (bench/README.md, "Fewer views, fewer stations"); two held-out streets
#: with a panorama every 1.25 m, detected in every 2.5 and every 5 m, in "Detection every 5 m".
DEFAULT_STATION_SPACING_M = 5.0


def spaced_stations(xyz_world, spacing_m: float) -> np.ndarray:
    """Indices of the stations to detect in, in order: the fewest that leave no more than
    ``spacing_m`` (3-D distance) between one kept station and the next, where the stations
    allow it. The first and the last station are kept; a station is kept when the one after
    it stands more than ``spacing_m`` from the last one kept (so a station farther than that
    from the one before it is kept, and so is that one). ``spacing_m`` <= 0 keeps all.

    A sign stays in view over many stations: skipping the ones that stand close together
    saves their detection time, at the price of fewer views (fewer rays) of each sign. A
    drive whose panoramas stand ``spacing_m`` or more apart keeps every one; one stopped at a
    crossing keeps one panorama where it stood.
    """
    xyz = np.asarray(xyz_world, float).reshape(-1, 3)
    n = len(xyz)
    if spacing_m <= 0 or n <= 2:
        return np.arange(n, dtype=np.int64)
    limit2 = float(spacing_m) ** 2
    points = xyz.tolist()
    kept = [0]
    last = points[0]
    for k in range(1, n - 1):
        after = points[k + 1]
        if (after[0] - last[0]) ** 2 + (after[1] - last[1]) ** 2 + (after[2] - last[2]) ** 2 > limit2:
            kept.append(k)
            last = points[k]
    kept.append(n - 1)
    return np.array(kept, dtype=np.int64)


@dataclass
class DriveDetections:
    """Detections over many panoramas: ``per_image[k]`` belongs to ``image_paths[k]``
    (None where the panorama was skipped); ``skipped`` lists (path, reason)."""
    per_image: List[Optional[PanoramaDetections]]
    skipped: List[Tuple[str, str]]

    @property
    def count(self) -> int:
        return sum(len(d) for d in self.per_image if d is not None)


def detect_drive(detector, image_paths: Sequence[str], views: ViewSet, confidence: float = 0.25,
                 iou_threshold: float = 0.45, min_box_px: float = 0.0,
                 progress: Progress = SILENT,
                 on_panorama: Optional[Callable[[np.ndarray, PanoramaDetections], object]] = None,
                 prefetch: bool = True, candidate_confidence: Optional[float] = None,
                 zoom: Union[ZoomRule, Sequence[ZoomRule], None] = None) -> DriveDetections:
    """:func:`detect_panorama` on each panorama file; missing or corrupt files are skipped.

    ``on_panorama(pano, found)`` is called after each panorama is detected, while it is in
    memory (so that it is read once): reading the sign codes of its detections, say
    (:func:`.detections.read_codes`); when it returns a :class:`PanoramaDetections`, that
    replaces ``found``. ``candidate_confidence``: boxes from this score up are kept as
    candidates for ``on_panorama`` (:func:`detect_panorama`, :func:`.rescue.second_look`);
    those still marked candidate after it are dropped. ``zoom``: :func:`detect_panorama`'s
    zoomed looks (a :class:`.zoomlook.ZoomRule`, several, or None for none). Progress
    advances per view; cancel stops between views. A skipped file adds ``(path, reason)`` to
    ``skipped`` and a warning to ``progress``. ``prefetch``: decode the next panorama in a
    background thread while this one is detected (OpenCV's decoder releases the GIL; two
    panoramas are in memory at once); results, order and warnings are the same either way.
    The views are cut in the same thread as the panorama is decoded (``cv2.remap`` releases
    the GIL too).
    """
    from .panorama import read_panorama

    def load(path: str):
        try:
            pano = read_panorama(path)
        except InputError as error:
            return None, None, error
        return pano, list(views.cut_all(pano)), None

    per_image: List[Optional[PanoramaDetections]] = []
    skipped: List[Tuple[str, str]] = []
    n = max(len(image_paths), 1)
    reader = ThreadPoolExecutor(max_workers=1) if prefetch and len(image_paths) > 1 else None
    try:
        pending = reader.submit(load, image_paths[0]) if reader is not None else None
        for k, path in enumerate(image_paths):
            progress.report(k / n)
            progress.step("Detecting signs: panorama {n} of {count} ({image})", n=k + 1,
                          count=len(image_paths), image=os.path.basename(path))
            if reader is not None and pending is not None:
                pano, view_images, error = pending.result()
                pending = reader.submit(load, image_paths[k + 1]) if k + 1 < len(image_paths) else None
            else:
                pano, view_images, error = load(path)
            if error is not None:
                skipped.append((path, str(error)))
                progress.warning(error.template, **error.fields)
                per_image.append(None)
                continue
            found = detect_panorama(detector, pano, views, confidence, iou_threshold,
                                    min_box_px=min_box_px, candidate_confidence=candidate_confidence,
                                    progress=progress.sub(k / n, (k + 1) / n), zoom=zoom,
                                    view_images=view_images)
            if on_panorama is not None:
                progress.check()
                answer = on_panorama(pano, found)
                if isinstance(answer, PanoramaDetections):
                    found = answer
            if found.candidate.any():
                found = found.subset(~found.candidate)
            per_image.append(found)
            del pano, view_images
    finally:
        if reader is not None:  # on cancel or an error: do not wait for a read in flight
            reader.shutdown(wait=False, cancel_futures=True)
    progress.report(1.0)
    return DriveDetections(per_image, skipped)
