"""The detections layer: one ray per detected sign, with its box and its station's pose.

Written by ``roadsigns:detectsigns`` (from :class:`~.detector.DriveDetections` and the
stations) and read by ``roadsigns:projectdetections``. Conventions: boxes in panorama
pixels ``u0 < W``, ``u1`` may exceed ``W`` across the +-180 deg seam; the pose is the
panorama centre in world ENU metres and ``q_world_from_pano_wxyz`` (Hamilton, scalar
first) mapping panorama rays to world; ``heading_deg`` clockwise from grid north.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Mapping, Sequence, Tuple

import numpy as np

from . import geometry
from .errors import InputError
from .schema import Schema, fields, select
from .signcodes import CODE_FIELDS, DEFAULT_CROP_MARGIN, cut_crop

#: The detections layer (LineStringZ from the panorama centre along the box-centre ray).
#: ``code`` and ``code_score`` (:data:`.signcodes.CODE_FIELDS`): the sign code read in the box.
DETECTION_FIELDS: Schema = fields(
    ("det_id", int), ("station_id", int), ("image", str), ("class", str), ("score", float)) + CODE_FIELDS + fields(
    ("u0", float), ("v0", float), ("u1", float), ("v1", float), ("n_views", int),
    ("time", float), ("x", float), ("y", float), ("z", float),
    ("qw", float), ("qx", float), ("qy", float), ("qz", float),
    ("heading", float), ("width", int), ("height", int))
#: The detection fields projection needs, and the candidates layer carries on (``code`` and
#: ``code_score``: the sign code read in this view, :data:`.signcodes.CODE_FIELDS`).
DETECTION_POSE_FIELDS: Schema = select(DETECTION_FIELDS, (
    "det_id", "station_id", "image", "class", "score", "code", "code_score", "u0", "v0", "u1",
    "v1", "width", "height", "x", "y", "z", "qw", "qx", "qy", "qz"))
#: Fields that may be NULL or absent: the candidates layer does not carry the first three;
#: layers written before codes were read (or by another tool) lack the code fields, which
#: are then read as no code (empty ``code``, NaN ``code_score``).
OPTIONAL_FIELDS = ("n_views", "time", "heading", "code", "code_score")
#: The fields a detections (or candidates) layer must have.
REQUIRED_POSE_FIELDS: Tuple[str, ...] = tuple(
    f.name for f in DETECTION_POSE_FIELDS if f.name not in OPTIONAL_FIELDS)


@dataclass
class Detections:
    """Detections with the pose of their panorama, one row each.

    ``box_px`` (n, 4): u0, v0, u1, v1; ``pano_size_px`` (n, 2): W, H; ``centre_world`` (n, 3):
    panorama centre; ``q_world_from_pano_wxyz`` (n, 4). ``n_views``: view detections merged
    into the box; ``time_s`` and ``heading_deg``: the station's (NaN when unknown);
    ``code`` and ``code_score``: the sign code the classifier read in this view and its
    probability (``""`` and NaN when no code was read).
    """

    det_id: np.ndarray
    station_id: np.ndarray
    image: List[str]
    class_name: List[str]
    score: np.ndarray
    box_px: np.ndarray
    pano_size_px: np.ndarray
    centre_world: np.ndarray
    q_world_from_pano_wxyz: np.ndarray
    n_views: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    time_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    heading_deg: np.ndarray = field(default_factory=lambda: np.zeros(0))
    code: List[str] = field(default_factory=list)
    code_score: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __post_init__(self) -> None:
        n = len(self.det_id)
        if len(self.code) != n:
            self.code = [""] * n
        if len(self.code_score) != n:
            self.code_score = np.full(n, np.nan)
        if len(self.n_views) != n:
            self.n_views = np.ones(n, np.int64)
        if len(self.time_s) != n:
            self.time_s = np.full(n, np.nan)
        if len(self.heading_deg) != n:
            self.heading_deg = np.full(n, np.nan)

    def __len__(self) -> int:
        return len(self.det_id)

    def station_rows(self) -> np.ndarray:
        """The first row of each station (panorama), in ascending ``station_id``."""
        return np.unique(self.station_id, return_index=True)[1]

    @classmethod
    def empty(cls) -> "Detections":
        return cls(np.zeros(0, np.int64), np.zeros(0, np.int64), [], [], np.zeros(0),
                   np.zeros((0, 4)), np.zeros((0, 2)), np.zeros((0, 3)), np.zeros((0, 4)))

    @classmethod
    def from_records(cls, rows: Sequence[Mapping[str, Any]]) -> "Detections":
        """From dicts with :data:`DETECTION_POSE_FIELDS` (a detections or candidates layer's
        attributes); the :data:`OPTIONAL_FIELDS` are read when present."""
        rows = list(rows)
        if not rows:
            return cls.empty()
        missing = [name for name in REQUIRED_POSE_FIELDS if name not in rows[0]]
        if missing:
            raise InputError("The detections lack the field(s) {fields}; expected the output of "
                             "Detect signs", fields=", ".join(missing))

        def number(r, name, dtype=float):
            v = r[name]
            if v is None or (isinstance(v, float) and math.isnan(v)):
                raise InputError("Detection {det_id}: the field {field} is empty",
                                 det_id=r.get("det_id"), field=name)
            try:
                value = float(v)
                if not math.isfinite(value) or (dtype is not float and not (
                        value == int(value) and abs(value) < 2 ** 62)):
                    raise ValueError(value)
            except (TypeError, ValueError, OverflowError):
                raise InputError("Detection {det_id}, field {field}: expected a number, found '{value}'",
                                 det_id=r.get("det_id"), field=name, value=str(v)[:60])
            return int(value) if dtype is not float else value

        def col(name, dtype=float):
            return np.asarray([number(r, name, dtype) for r in rows], dtype=dtype)

        def optional(name, fill):
            return np.array([fill if r.get(name) is None else number(r, name) for r in rows])

        det = cls(col("det_id", np.int64), col("station_id", np.int64),
                  [str(r["image"]) for r in rows], [str(r["class"]) for r in rows],
                  col("score"), np.column_stack([col(k) for k in ("u0", "v0", "u1", "v1")]),
                  np.column_stack([col("width"), col("height")]),
                  np.column_stack([col(k) for k in ("x", "y", "z")]),
                  np.column_stack([col(k) for k in ("qw", "qx", "qy", "qz")]),
                  optional("n_views", 1).astype(np.int64), optional("time", np.nan),
                  optional("heading", np.nan),
                  [str(r.get("code") or "").strip() for r in rows], optional("code_score", np.nan))
        det.validate()
        return det

    def validate(self) -> None:
        """:class:`InputError` for boxes or poses that break the detections layer's form."""
        b, W, H = self.box_px, self.pano_size_px[:, 0], self.pano_size_px[:, 1]
        bad = ~((b[:, 0] < b[:, 2]) & (b[:, 1] < b[:, 3]) & (W > 0) & (H > 0)
                & (b[:, 2] - b[:, 0] <= W) & np.all(np.isfinite(b), axis=1))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            raise InputError("Detection {det_id}: the box ({u0}, {v0}, {u1}, {v1}) is not "
                             "u0 < u1, v0 < v1 inside a {w} x {h} panorama",
                             det_id=int(self.det_id[k]), u0=b[k, 0], v0=b[k, 1], u1=b[k, 2],
                             v1=b[k, 3], w=int(W[k]), h=int(H[k]))
        qn = np.linalg.norm(self.q_world_from_pano_wxyz, axis=1)
        bad = ~(np.abs(qn - 1.0) < 1e-3) | ~np.all(np.isfinite(self.centre_world), axis=1)
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            raise InputError("Detection {det_id}: the station pose is invalid (quaternion "
                             "norm {norm:.4f}, position {xyz})", det_id=int(self.det_id[k]),
                             norm=float(qn[k]), xyz=self.centre_world[k].tolist())

    def take(self, index) -> "Detections":
        index = np.asarray(index, dtype=np.int64)
        return Detections(self.det_id[index], self.station_id[index],
                          [self.image[i] for i in index], [self.class_name[i] for i in index],
                          self.score[index], self.box_px[index], self.pano_size_px[index],
                          self.centre_world[index], self.q_world_from_pano_wxyz[index],
                          self.n_views[index], self.time_s[index], self.heading_deg[index],
                          [self.code[i] for i in index], self.code_score[index])

    def R_world_from_pano(self) -> np.ndarray:
        return geometry.matrix_from_quat_wxyz(self.q_world_from_pano_wxyz)

    def centre_rays_world(self) -> np.ndarray:
        b = self.box_px
        return geometry.box_centre_ray_world(b[:, 0], b[:, 1], b[:, 2], b[:, 3],
                                             self.pano_size_px[:, 0], self.pano_size_px[:, 1],
                                             self.q_world_from_pano_wxyz)

    def ray_ends_world(self, ray_length_m: float) -> np.ndarray:
        """(n, 3) end points of the rays ``ray_length_m`` from the panorama centres."""
        return self.centre_world + ray_length_m * self.centre_rays_world().reshape(-1, 3)

    def records(self, schema: Schema = DETECTION_FIELDS) -> List[Dict]:
        """One dict per detection with ``schema``'s fields (the detections layer's by default)."""
        return list(self.iter_records(schema))

    def iter_records(self, schema: Schema = DETECTION_FIELDS) -> Iterator[Dict]:
        """:meth:`records` one at a time (a drive's layer written without a dict per row held)."""
        for k in range(len(self)):
            record = {"det_id": int(self.det_id[k]), "station_id": int(self.station_id[k]),
                      "image": self.image[k], "class": self.class_name[k],
                      "score": float(self.score[k]), "n_views": int(self.n_views[k]),
                      "code": self.code[k], "code_score": _finite_or_none(self.code_score[k]),
                      "time": _finite_or_none(self.time_s[k]),
                      "heading": _finite_or_none(self.heading_deg[k]),
                      "width": int(self.pano_size_px[k, 0]), "height": int(self.pano_size_px[k, 1])}
            record.update(zip(("u0", "v0", "u1", "v1"), map(float, self.box_px[k])))
            record.update(zip(("x", "y", "z"), map(float, self.centre_world[k])))
            record.update(zip(("qw", "qx", "qy", "qz"), map(float, self.q_world_from_pano_wxyz[k])))
            yield {f.name: record[f.name] for f in schema}


def _finite_or_none(value: float):
    return None if not np.isfinite(value) else float(value)


def read_codes(classifier, pano: np.ndarray, found):
    """The sign code of each detection of ``found`` (a :class:`.detector.PanoramaDetections`
    of the panorama ``pano``, ``H x W x 3`` BGR), read by ``classifier``: ``found.code`` and
    ``found.code_score`` set in place by :func:`read_code_probabilities`, and ``found``
    returned. Use it as :func:`.detector.detect_drive`'s ``on_panorama``.
    """
    read_code_probabilities(classifier, pano, found)
    return found


def read_code_probabilities(classifier, pano: np.ndarray, found) -> np.ndarray:
    """What :func:`read_codes` does, returning the classifier's probabilities ``(n, C)`` in
    the order of ``classifier.names``.

    ``classifier``: a :class:`.signcodes.CodeClassifier` (or any object with ``names``,
    ``probabilities(crops) -> (n, C)`` and ``crop_margin``). One rectified crop per box is
    cut at the panorama's native resolution (the classifier's ``cut_crop``, up to twice its
    input side, or :func:`.signcodes.cut_crop`, with the classifier's margin) and all are
    classified in batches; ``found.code`` and ``found.code_score`` (the best name and its
    probability; ``other`` when the classifier knows no code) are set in place.
    """
    if len(found) == 0:
        return np.zeros((0, len(classifier.names)))
    margin = float(getattr(classifier, "crop_margin", DEFAULT_CROP_MARGIN))
    cut = getattr(classifier, "cut_crop", None) or (lambda p, box: cut_crop(p, box, margin))
    probabilities = np.asarray(classifier.probabilities([cut(pano, box) for box in found.boxes()]), float)
    best = probabilities.argmax(axis=1)
    found.code = [str(classifier.names[i]) for i in best]
    found.code_score = probabilities[np.arange(len(best)), best]
    return probabilities


def drive_detections(stations, per_image: Sequence) -> Detections:
    """The detections of a drive as one :class:`Detections`, numbered from 1 in station order.

    ``stations``: a :class:`~.trajectory.Stations`; ``per_image[k]``: the
    :class:`~.detector.PanoramaDetections` of station k, or None where it was skipped.
    """
    rows: List[Tuple[int, int]] = [(k, j) for k, found in enumerate(per_image) if found is not None
                                   for j in range(len(found))]
    if not rows:
        return Detections.empty()
    k_station = np.array([k for k, _ in rows], np.int64)

    def per_row(attribute) -> np.ndarray:
        return np.array([getattr(per_image[k], attribute)[j] for k, j in rows])

    return Detections(
        np.arange(1, len(rows) + 1, dtype=np.int64), stations.station_id[k_station],
        [stations.image[k] for k in k_station], [per_image[k].class_name[j] for k, j in rows],
        per_row("score").astype(float),
        np.column_stack([per_row(a).astype(float) for a in ("u0", "v0", "u1", "v1")]),
        np.column_stack([stations.width_px[k_station], stations.height_px[k_station]]).astype(float),
        stations.xyz_world[k_station], stations.q_world_from_pano_wxyz[k_station],
        per_row("n_views").astype(np.int64), stations.time_s[k_station],
        stations.heading_deg[k_station], [per_image[k].code[j] for k, j in rows],
        per_row("code_score").astype(float))
