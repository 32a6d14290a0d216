"""The class of a sign found without a detection, read from the panoramas that saw it.

A sign found in the cloud alone (``source = lidar``) has a position, a size and a facing
but no class. Each of the best panoramas that saw it (:func:`.signviews.sign_views`: in
front of its face, nearest and most frontal first) gives a perspective view centred on the
sign, the sign filling about ``1 / (1 + 2 * margin_frac)`` of the view's width; the
detector runs on that view, and a detection counts for the sign when its box centre lies
within :data:`CENTRE_TOLERANCE` of the view's width from the view's centre. The class is the
one with the highest summed score over the views; it is kept when its best single score
reaches ``confidence``, else the sign stays ``unknown``.

With a sign-code classifier (:class:`.signcodes.CodeClassifier`), each detection that
counts is also read: a square crop is cut from the panorama around it
(:func:`.signcodes.view_box_crop_view`, the classifier's margin, at the panorama's native
density, as :func:`.signcodes.cut_crop` cuts a detection's box) and the codes are voted
across the views (:func:`.signcodes.code_support`, each weighing detection score x crop
side, as refinement votes them) and checked against the class
(:func:`.signcodes.decide_code`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence

import numpy as np

from .errors import SILENT, InputError, Progress
from .fusion import UNKNOWN_CLASS
from .panorama import read_panorama
from .signcodes import (
    DEFAULT_CODE_CONFIDENCE,
    DEFAULT_CROP_MARGIN,
    CodeVote,
    class_support,
    code_support,
    cut_square_view,
    decide_code,
    view_box_crop_view,
)
from .signviews import sign_views

#: A detection belongs to the sign when its centre is this share of the view width from the centre.
CENTRE_TOLERANCE = 0.15
#: Margin around the sign in each view, as a share of its size on each side.
VIEW_MARGIN_FRAC = 1.5


@dataclass(frozen=True)
class ViewClass:
    """What the panoramas say of one sign: ``klass`` (or ``unknown``), the best score, the
    images looked at and the images whose view found it; ``code``: the code read there
    (None when no classifier ran). When the code's class won the check, ``klass`` is the
    code's class (``code.check``)."""

    klass: str
    score: float
    images_seen: List[str]
    images_found: List[str]
    code: Optional[CodeVote] = None


def classify_from_views(signs: Sequence[Dict], stations: Sequence[Dict], detector, folder=None,
                        confidence: float = 0.4, max_views: int = 3, progress: Progress = SILENT,
                        codes=None, code_confidence: float = DEFAULT_CODE_CONFIDENCE) -> List[ViewClass]:
    """A :class:`ViewClass` per sign record (``x, y, z``, ``width``, ``panel_height``,
    ``azimuth``; see :func:`.signviews.sign_views`), from the ``stations`` records and the
    panorama ``folder``. ``detector``: a :class:`.detector.Detector` (or any object with
    ``input_size`` and ``detect(image, confidence)``); ``codes``: a
    :class:`.signcodes.CodeClassifier` (or None: no codes read), ``code_confidence`` the
    minimum support of a kept code. A panorama that cannot be read is skipped with a
    warning."""
    size_px = int(min(detector.input_size))
    out: List[ViewClass] = []
    for k, sign in enumerate(signs):
        progress.step("Looking for the cloud's signs in the panoramas: sign {n} of {count}", n=k + 1,
                      count=len(signs))
        votes: Dict[str, float] = {}
        best: Dict[str, float] = {}
        seen: List[str] = []
        found: List[str] = []
        classes: List[str] = []
        scores: List[float] = []
        crops: list = []
        weights: List[float] = []
        for view in sign_views(sign, stations, folder, max_views=max_views, size_px=size_px,
                               margin_frac=VIEW_MARGIN_FRAC):
            try:
                pano = read_panorama(view.path)
            except InputError as error:
                progress.warning(error.template, **error.fields)
                continue
            seen.append(view.image)
            detections = detector.detect(view.view.cut(pano), confidence * 0.5)
            if len(detections) == 0:
                continue
            boxes = np.asarray(detections.boxes_xyxy, float).reshape(-1, 4)
            centre = 0.5 * (boxes[:, :2] + boxes[:, 2:])
            near = np.linalg.norm(centre - 0.5 * size_px, axis=1) <= CENTRE_TOLERANCE * size_px
            names = [detector.class_names[int(c)] for c in np.asarray(detections.class_ids)]
            for j in np.flatnonzero(near):
                score = float(detections.scores[j])
                votes[names[j]] = votes.get(names[j], 0.0) + score
                best[names[j]] = max(best.get(names[j], 0.0), score)
                classes.append(names[j])
                scores.append(score)
                if codes is not None:
                    crop_view, native = view_box_crop_view(view.view, boxes[j], pano.shape[1], codes.crop_margin)
                    crops.append(cut_square_view(pano, crop_view, native))
                    weights.append(score * view_box_crop_view(view.view, boxes[j], pano.shape[1],
                                                              DEFAULT_CROP_MARGIN)[0].width_px)
            if near.any():
                found.append(view.image)
        klass = max(votes, key=lambda c: votes[c]) if votes else UNKNOWN_CLASS
        if klass != UNKNOWN_CLASS and best[klass] < confidence:
            klass = UNKNOWN_CLASS
        score = best.get(klass, 0.0)  # the class vote's, also when the code's class wins (as refine)
        code = None
        if codes is not None and klass != UNKNOWN_CLASS:
            read, probs = codes.classify(crops)
            winner, support, n_views = code_support(read, probs, weights)
            code = decide_code(winner, support, n_views, klass, lambda: class_support(classes, scores, klass),
                               codes.table, code_confidence)
            klass = code.klass
        out.append(ViewClass(klass, score, seen, found if klass != UNKNOWN_CLASS else [], code))
        progress.report((k + 1) / max(1, len(signs)))
    return out
