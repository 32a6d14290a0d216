"""Signs the detector scores low but the sign-code classifier reads: the second look.

The detector learned real signs from few photographs; on real streets it scores many
small or unusual signs under its threshold (GTSDB 500-599: 14 of 71 signs, most of them
17-31 px, at scores 0.05-0.4) while still putting a box on them. The sign-code classifier
was trained on 11,000 real sign crops and on look-alikes labelled ``other``. The second
look keeps such a low-scoring box (a *candidate*) when the classifier reads a sign code in
it with a high probability (the probabilities of the codes of one class added up: a speed
limit whose digits are unsure is still a prohibitory sign) and the box shows sign sheeting
colours.

Conventions: boxes ``(u0, v0, u1, v1)`` in image (or panorama) pixels, ``u1`` past the
width across a panorama's seam; images in OpenCV's BGR order. The sheeting colours are
:mod:`.sheeting`'s.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np

from .sheeting import sheeting_fraction
from .signcodes import BACK_CODE, NO_SIGN_NAMES, OTHER_CODE, unlisted_code_class

#: Default of detectsigns' RESCUE_CONFIDENCE: the lowest detector score of a candidate. 0.2
#: since the wider detector (27 November): at 0.05 its candidates cost precision on
#: held-out real signs for little recall (models/README.md, "A wider detector").
DEFAULT_RESCUE_CONFIDENCE = 0.2


@dataclass(frozen=True)
class RescueRule:
    """When a candidate is kept: the codes (not ``other``) of one of the detector's classes
    add up to at least ``min_class_score`` in the classifier's reading (:func:`class_reading`),
    its box is at least ``min_box_px`` on its shorter side (a box under ``small_box_px`` needs
    a detector score of at least ``small_min_score``), and at least ``min_sheeting`` of
    its pixels are sheeting colours (red, blue or yellow: grey and dark shapes such as pylon
    insulators are not signs).

    Chosen on GTSDB 500-599 (models/README.md, "The second look"): the results hardly move
    for a score from 0.8 to 0.95 and a sheeting share from 0.02 to 0.1. Until 27 November the
    best single code had to reach the score; the class's codes added up gave more recall at
    the same precision on held-out real signs (models/README.md, "The second look reads
    classes").

    Boxes of 12-16 px since 28 November (16 px and more before): far signs 14-20 px high,
    which the detector boxes at scores 0.3-0.5, and whose boxes are often 12-15 px wide. The
    floor of 0.35 for them keeps the precision on real photographs: the two boxes on nothing
    that such candidates added in GTSDB 500-599 scored under it (models/README.md, "Small
    candidates").

    ``drop_lone_upward_other``: a detection one upward view found alone
    (:attr:`.detector.PanoramaDetections.lone_upward`) is dropped when the classifier's best
    reading is ``other``. Those views look over the road for panels overhead; beside it they
    see facades, whose dark windows they may box (models/README.md, "Overhead panels read").
    Elsewhere a detection read ``other`` stays: a sign whose legend the table lacks (a
    foreign no-parking sign) reads ``other`` too.

    ``drop_backs``: a detection (anywhere) whose best reading is ``back``
    (:data:`.signcodes.BACK_CODE`) with at least ``min_back_score`` is dropped: the detector
    boxes the plain grey backs of signs for their shape, and a sign's face is seen from the
    stations on its other side (models/README.md, "The backs of signs read").
    """
    min_class_score: float = 0.9
    min_box_px: float = 12.0
    small_box_px: float = 16.0
    small_min_score: float = 0.35
    min_sheeting: float = 0.05
    drop_lone_upward_other: bool = True
    drop_backs: bool = True
    min_back_score: float = 0.5


DEFAULT_RULE = RescueRule()


def worth_reading(box_px: np.ndarray, sheeting: np.ndarray, scores: np.ndarray,
                  rule: RescueRule = DEFAULT_RULE) -> np.ndarray:
    """Which candidates (``box_px`` (n, 4), their :func:`sheeting_fraction`, their detector
    ``scores``) may be kept if the classifier reads them: the checks that need no classifier,
    done first to read fewer."""
    box_px = np.asarray(box_px, float).reshape(-1, 4)
    side = np.minimum(box_px[:, 2] - box_px[:, 0], box_px[:, 3] - box_px[:, 1])
    scored_enough = (side >= rule.small_box_px) | (np.asarray(scores, float).reshape(-1) >= rule.small_min_score)
    return (side >= rule.min_box_px) & scored_enough & (np.asarray(sheeting, float) >= rule.min_sheeting)


#: :func:`code_classes`' mark for the column of ``other`` (and of ``back``), and for a code
#: of a class the detector lacks (or that the codes table does not hold).
OTHER_COLUMN, UNMAPPED_COLUMN = -2, -1


def code_classes(names: Sequence[str], table, class_names: Sequence[str]) -> np.ndarray:
    """Per classifier column (``names``), the class of its code as an index into
    ``class_names`` (the detector's); :data:`UNMAPPED_COLUMN` for a code of a class the
    detector lacks (or not in the codes ``table``), :data:`OTHER_COLUMN` for ``other`` and
    ``back`` (:data:`.signcodes.NO_SIGN_NAMES`). An
    ``unlisted:`` name (a sign of a class whose code the table lacks,
    :func:`.signcodes.unlisted_code`) counts for its class."""
    out = np.full(len(names), OTHER_COLUMN, np.int64)
    for k, name in enumerate(names):
        if name not in NO_SIGN_NAMES:
            klass = unlisted_code_class(name) or class_of_code(name, table, class_names)
            out[k] = list(class_names).index(klass) if klass is not None and klass in class_names else UNMAPPED_COLUMN
    return out


def class_reading(probabilities, column_class: np.ndarray, n_classes: int) -> Tuple[np.ndarray, np.ndarray]:
    """Per crop, the class whose codes' probabilities add up to most in ``probabilities``
    (``(n, C)``; ``column_class``: :func:`code_classes` of its columns), and that sum. The
    class is an index into the detector's ``n_classes``, or -1 for the codes of classes the
    detector lacks, added up together: the box then keeps the detector's class. ``other``
    counts for no class."""
    probs = np.asarray(probabilities, float).reshape(-1, len(column_class))
    per_class = np.zeros((len(probs), n_classes + 1))     # the last column: classes the detector lacks
    for k, c in enumerate(np.asarray(column_class)):
        if c != OTHER_COLUMN:
            per_class[:, n_classes if c == UNMAPPED_COLUMN else c] += probs[:, k]
    best = per_class.argmax(1)
    return np.where(best == n_classes, -1, best), per_class[np.arange(len(probs)), best]


def confirmed(class_scores, rule: RescueRule = DEFAULT_RULE) -> np.ndarray:
    """Which read candidates the classifier confirms: their class's codes add up to at least
    ``rule.min_class_score`` (:func:`class_reading`)."""
    scores = np.asarray(class_scores, float).reshape(-1)
    with np.errstate(invalid="ignore"):
        return scores >= rule.min_class_score


def class_of_code(code: str, table, class_names: Sequence[str]) -> Optional[str]:
    """The class a confirmed code gives its box: the codes table's class for it when the
    detector has that class, else None (the detector's own class stays)."""
    if table is None or code not in table:
        return None
    name = table.entry(code).class_name
    return name if name in class_names else None


def second_look(classifier, pano: np.ndarray, found, class_names: Sequence[str],
                rule: RescueRule = DEFAULT_RULE, fit_tall: bool = True):
    """Read the sign codes of a panorama's detections and candidates and keep the candidates
    the classifier confirms: :func:`.detector.detect_drive`'s ``on_panorama``.

    ``found``: a :class:`.detector.PanoramaDetections` of ``pano`` (BGR) with candidate rows;
    ``class_names``: the detector's classes; ``classifier``: a
    :class:`.signcodes.CodeClassifier` (``names``, ``table``, ``probabilities``). The
    candidates that fail :func:`worth_reading` are dropped unread; the codes of the rest and of
    every detection are read (:func:`.detections.read_code_probabilities`); a candidate whose class reading
    is :func:`confirmed` becomes a detection of that class (:func:`class_reading`; its own
    class for codes of classes the detector lacks) and keeps its detector score and its best
    code; the others are dropped. A detection an upward view found alone is dropped when its
    code reads ``other`` (``rule.drop_lone_upward_other``), and any detection or candidate
    that reads ``back`` (``rule.drop_backs``). ``fit_tall``: a candidate is judged
    (:func:`worth_reading`) on the network's box, then fitted as the detections were
    (:func:`.detector.fit_tall_boxes`) and read on the fitted box: a sign seen edge-on fills
    the network's box only in part (fitted before the judging, such a box fell under
    ``rule.small_box_px``; read unfitted, the pole and the wall beside it blur the reading). Returns the new
    :class:`~.detector.PanoramaDetections`.
    """
    from .detections import read_code_probabilities
    from .detector import fit_tall_boxes

    candidate = found.candidate
    if candidate.any():
        boxes = found.boxes()
        sheeting = np.zeros(len(found))
        for k in np.flatnonzero(candidate):
            sheeting[k] = sheeting_fraction(pano, boxes[k], wrap=True)
        readable = ~candidate | worth_reading(boxes, sheeting, found.score, rule)
        found = found.subset(readable)
        if fit_tall:   # judged on the network's box, read on the fitted one
            fit_tall_boxes(pano, found, rows=found.candidate)
    probabilities = read_code_probabilities(classifier, pano, found)
    if rule.drop_lone_upward_other:
        overhead_other = found.lone_upward & (np.array(found.code, dtype=object) == OTHER_CODE)
        if overhead_other.any():
            keep = ~overhead_other
            found, probabilities = found.subset(keep), probabilities[keep]
    if rule.drop_backs:
        back = (np.array(found.code, dtype=object) == BACK_CODE) & (found.code_score >= rule.min_back_score)
        if back.any():
            keep = ~back
            found, probabilities = found.subset(keep), probabilities[keep]
    if not found.candidate.any():
        return found
    names = list(class_names)
    columns = code_classes(classifier.names, getattr(classifier, "table", None), names)
    best, score = class_reading(probabilities, columns, len(names))
    kept = ~found.candidate | confirmed(score, rule)
    for k in np.flatnonzero(found.candidate & kept & (best >= 0)):
        found.class_name[k] = names[best[k]]
        found.class_id[k] = best[k]
    found = found.subset(kept)
    found.candidate[:] = False
    return found
