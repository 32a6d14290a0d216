"""The class of a sign found without a detection, read from the panoramas that saw it.

A sign found in the cloud alone (``source = lidar``) has a position, a size and a facing
but no class. Each of the best panoramas that saw it (:func:`.signviews.sign_views`: in
front of its face, nearest and most frontal first) gives a perspective view centred on the
sign, the sign filling about ``1 / (1 + 2 * margin_frac)`` of the view's width; the
detector runs on that view, and a detection counts for the sign when its box centre lies
within :data:`CENTRE_TOLERANCE` of the view's width from the view's centre. The class is the
one with the highest summed score over the views; it is kept when its best single score
reaches ``confidence``, else the sign stays ``unknown``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, List, Sequence

import numpy as np

from .errors import SILENT, InputError, Progress
from .fusion import UNKNOWN_CLASS
from .panorama import read_panorama
from .signviews import sign_views

#: A detection belongs to the sign when its centre is this share of the view width from the centre.
CENTRE_TOLERANCE = 0.15
#: Margin around the sign in each view, as a share of its size on each side.
VIEW_MARGIN_FRAC = 1.5


@dataclass(frozen=True)
class ViewClass:
    """What the panoramas say of one sign: ``klass`` (or ``unknown``), the best score, the
    images looked at and the images whose view found it."""

    klass: str
    score: float
    images_seen: List[str]
    images_found: List[str]


def classify_from_views(signs: Sequence[Dict], stations: Sequence[Dict], detector, folder=None,
                        confidence: float = 0.4, max_views: int = 3,
                        progress: Progress = SILENT) -> List[ViewClass]:
    """A :class:`ViewClass` per sign record (``x, y, z``, ``width``, ``panel_height``,
    ``azimuth``; see :func:`.signviews.sign_views`), from the ``stations`` records and the
    panorama ``folder``. ``detector``: a :class:`.detector.Detector` (or any object with
    ``input_size`` and ``detect(image, confidence)``). A panorama that cannot be read is
    skipped with a warning."""
    size_px = int(min(detector.input_size))
    out: List[ViewClass] = []
    for k, sign in enumerate(signs):
        votes: Dict[str, float] = {}
        best: Dict[str, float] = {}
        seen: List[str] = []
        found: List[str] = []
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
            if near.any():
                found.append(view.image)
        klass = max(votes, key=lambda c: votes[c]) if votes else UNKNOWN_CLASS
        if klass != UNKNOWN_CLASS and best[klass] < confidence:
            klass = UNKNOWN_CLASS
        out.append(ViewClass(klass, best.get(klass, 0.0), seen, found if klass != UNKNOWN_CLASS else []))
        progress.report((k + 1) / max(1, len(signs)))
    return out
