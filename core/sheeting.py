"""Sign sheeting colours in an image: the share of them in a box, and a tall box's width
fitted to them.

Road signs are printed on retroreflective sheeting in a few saturated colours (red, blue,
yellow); walls, poles, roads and trees are mostly not. Two uses:

- the second look (:mod:`.rescue`) reads a low-scoring box only when enough of it is
  sheeting (:func:`sheeting_fraction`);
- a sign passed close by is seen nearly edge-on, a sliver of its face beside its pole. The
  detector boxes it about twice as wide as the face (the pole and the wall beside it
  included), and such a box misses the sign at IoU 0.5 and lets the projection take the
  pole's points. :func:`fit_tall_boxes` narrows a box much taller than wide to the columns
  in which sheeting colours stand (models/README.md, "Signs seen edge-on").

Conventions: images in OpenCV's BGR order, colours in 8-bit HSV (hue 0-179); boxes
``(u0, v0, u1, v1)`` in image (or panorama) pixels, ``u1`` past the width across a
panorama's seam.
"""
from __future__ import annotations

import numpy as np

#: Saturation (8-bit HSV) from which a pixel counts as coloured sheeting.
SHEETING_MIN_SATURATION = 80
#: Hue ranges (8-bit HSV, inclusive) of the sheeting colours: red (both ends), blue, yellow.
SHEETING_HUES = ((0, 10), (160, 179), (95, 130), (15, 35))
#: A box at least this many times as high as it is wide is fitted by :func:`fit_tall_boxes`:
#: a sign's face, even a tall panel, is seldom so narrow unless it is seen edge-on.
TALL_BOX_HEIGHT_TO_WIDTH = 1.8
#: A column of a tall box belongs to the sign when at least this share of its pixels are
#: sheeting colours (a red rim crosses a white face's column in two short runs).
MIN_COLUMN_SHEETING = 0.15
#: A tall box is fitted only when at least this share of it is sheeting colours: the boxes of
#: edge-on signs measured 0.11-0.38; a green panel (no sheeting colour) 0.04.
MIN_TALL_BOX_SHEETING = 0.08
#: The fit is kept only when it narrows the box to at most this share of its width: a panel
#: the colours fill is left as the network boxed it (edge-on signs narrowed to 0.36-0.62).
MAX_FITTED_WIDTH_SHARE = 0.75


def box_patch(image_bgr: np.ndarray, box, wrap: bool = False) -> np.ndarray:
    """The pixels of ``box`` in ``image_bgr`` (rows clipped to the image). ``wrap``: columns
    wrap around the width (a panorama's seam); else they are clipped too. May be empty."""
    h, w = image_bgr.shape[:2]
    u0, v0, u1, v1 = (int(round(float(c))) for c in box)
    v0, v1 = max(v0, 0), min(v1, h)
    if v1 <= v0 or u1 <= u0:
        return image_bgr[:0, :0]
    if wrap:
        return np.take(image_bgr[v0:v1], np.arange(u0, u1) % w, axis=1)
    return image_bgr[v0:v1, max(u0, 0):min(u1, w)]


def sheeting_mask(patch_bgr: np.ndarray) -> np.ndarray:
    """Which pixels of ``patch_bgr`` are sheeting colours (saturated red, blue or yellow)."""
    import cv2

    if patch_bgr.size == 0:
        return np.zeros(patch_bgr.shape[:2], bool)
    hsv = cv2.cvtColor(np.ascontiguousarray(patch_bgr), cv2.COLOR_BGR2HSV)
    hue = hsv[..., 0]
    coloured = np.zeros(hue.shape, bool)
    for lo, hi in SHEETING_HUES:
        coloured |= (hue >= lo) & (hue <= hi)
    return coloured & (hsv[..., 1] >= SHEETING_MIN_SATURATION)


def sheeting_fraction(image_bgr: np.ndarray, box, wrap: bool = False) -> float:
    """The share of the pixels of ``box`` in ``image_bgr`` whose colour is sign sheeting
    (:func:`sheeting_mask`). ``wrap``: as :func:`box_patch`. 0 for an empty box."""
    mask = sheeting_mask(box_patch(image_bgr, box, wrap))
    return float(mask.mean()) if mask.size else 0.0


def fit_tall_boxes(image_bgr: np.ndarray, boxes, wrap: bool = False) -> np.ndarray:
    """``boxes`` (n, 4) with each box at least :data:`TALL_BOX_HEIGHT_TO_WIDTH` times as high
    as wide narrowed to its columns from the first to the last in which at least
    :data:`MIN_COLUMN_SHEETING` of the pixels are sheeting colours. Rows and every other box
    stay as they are, and so does a tall box under :data:`MIN_TALL_BOX_SHEETING` of sheeting,
    or whose such columns span more than :data:`MAX_FITTED_WIDTH_SHARE` of its width (a panel
    the colours fill; a sign against a blue sky). ``wrap``: as :func:`box_patch` (a panorama)."""
    out = np.array(boxes, float).reshape(-1, 4)
    width, height = out[:, 2] - out[:, 0], out[:, 3] - out[:, 1]
    for k in np.flatnonzero((width > 0) & (height >= TALL_BOX_HEIGHT_TO_WIDTH * width)):
        u0 = int(round(out[k, 0]))
        patch = box_patch(image_bgr, (u0, out[k, 1], int(round(out[k, 2])), out[k, 3]), wrap)
        if patch.size == 0:
            continue
        mask = sheeting_mask(patch)
        columns = np.flatnonzero(mask.mean(axis=0) >= MIN_COLUMN_SHEETING)
        if (mask.mean() < MIN_TALL_BOX_SHEETING or len(columns) == 0
                or columns[-1] + 1 - columns[0] > MAX_FITTED_WIDTH_SHARE * patch.shape[1]):
            continue
        left = u0 if wrap else max(u0, 0)        # box_patch clips the columns when not wrapping
        out[k, 0], out[k, 2] = left + columns[0], left + columns[-1] + 1
    return out
