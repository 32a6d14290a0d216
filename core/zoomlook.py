"""The zoomed look: small boxes the detector scores under its threshold, looked at again
with more pixels.

A sign 50 m away is 15-25 px high in a 4096 px panorama, and the 80 deg horizon views
(8 px a degree against the panorama's 11.4) shrink it further, to a size the detector
boxes at scores of 0.2-0.5. Cut again from the panorama at a higher density, the same sign
is as large as the signs the detector scores surely; a box on nothing stays under the
threshold (models/README.md, "The zoomed look"). So each small *candidate*
(:func:`.detector.detect_panorama`'s rows from ``ZoomRule.min_score`` under the
confidence) is cut again as a ``tile_px`` square view centred on it, whose field of view
makes the box's longer side ``box_px``; the tiles are laid side by side in one detector
input (a mosaic: one extra network run for up to ``(w // tile_px) x (h // tile_px)``
candidates), and a candidate the network then scores at the confidence or more, at the
same place, becomes a detection with the zoomed score, class and box.

The edge-on look (:data:`DEFAULT_EDGE_ON`) is the same with tiles stretched across, for
boxes much taller than wide: signs passed close by, which the views squeeze to slivers. Both
looks' tiles are packed into the same detector inputs (:func:`confirm`, :func:`mosaics`).

Conventions: boxes ``(u0, v0, u1, v1)`` in source pixels (a panorama's, with ``u1`` past
the width across its seam, or a photograph's); images in OpenCV's BGR order. The tiles of
a panorama are pinhole views (:class:`.panorama.PerspectiveView`), those of a photograph
crops scaled with OpenCV.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import partial
from typing import Callable, List, Sequence, Tuple, Union

import numpy as np

from . import geometry
from .panorama import PerspectiveView

#: Grey of the mosaic between and around the tiles (the detectors' letterbox grey).
MOSAIC_FILL = 114


@dataclass(frozen=True)
class ZoomRule:
    """Which candidates get the zoomed look and when one is kept.

    ``min_score``: the lowest network score of a candidate zoomed (detectsigns'
    ``RESCUE_CONFIDENCE`` default); ``max_box_px``: the longest side, in source pixels, of a
    box zoomed (larger boxes have pixels enough); ``box_px``: that side in the tile (the
    detector's surest sizes are 35-70 px); ``tile_px``: the tile's side; ``min_iou``: the
    overlap of the zoomed box, mapped back, with the candidate's for it to count; ``max_fov_deg``
    and ``min_fov_deg``: the tile's field of view is kept between them. ``stretch``: the tile
    is widened so many times after it is cut (its pixels ``stretch`` times as many a degree
    across as down; 1: a plain pinhole view); ``min_height_to_width``: only boxes at least so
    many times as tall as wide are taken (0: any). :data:`DEFAULT_EDGE_ON` is the rule of
    signs seen edge-on.

    Set before measuring, then checked (models/README.md, "The zoomed look"): on five
    held-out generated streets, of the candidates of 64 px or less, 15 of the 26 on counted
    signs no detection found scored 0.5 or more zoomed, and none of the 270 on nothing or the
    53 on the backs of signs; on two training streets 56 px confirmed 6 of 12 such signs,
    against 4 at 40 px and 7 at 72 px, which also boxed 2 backs of signs.
    """
    min_score: float = 0.2
    max_box_px: float = 64.0
    box_px: float = 56.0
    tile_px: int = 128
    min_iou: float = 0.3
    min_fov_deg: float = 2.0
    max_fov_deg: float = 60.0
    stretch: float = 1.0
    min_height_to_width: float = 0.0

    @property
    def tile_width_px(self) -> int:
        """The tile's width: ``tile_px`` widened ``stretch`` times."""
        return int(round(self.tile_px * self.stretch))


DEFAULT_ZOOM = ZoomRule()

#: The edge-on look: a candidate box at least ``min_height_to_width`` times as tall as wide
#: (a sign passed close by, seen more than 60-70 deg off its face's normal, whose face the
#: view squeezes to a sliver) is cut again as a tile of which its height is ``box_px``,
#: stretched across ``stretch`` times, so the face is about as wide as it is tall again: of
#: 50 real signs squeezed to 0.3 of their width, the network scores 11 at 0.5 or more as they
#: are and 44 stretched (models/README.md, "The edge-on look").
DEFAULT_EDGE_ON = ZoomRule(max_box_px=192.0, stretch=2.0, min_height_to_width=2.0)

#: Default of detectsigns' EDGE_ON_LOOK.
DEFAULT_EDGE_ON_LOOK = True

#: Default of detectsigns' ZOOMED_LOOK.
DEFAULT_ZOOMED_LOOK = True


def zoom_rules(zoom) -> Tuple[ZoomRule, ...]:
    """The zoomed looks ``zoom`` names: None for none, a :class:`ZoomRule` or a sequence of
    them (:func:`confirm` runs them together)."""
    if zoom is None:
        return ()
    return (zoom,) if isinstance(zoom, ZoomRule) else tuple(zoom)


#: A tile: its image and the map of boxes ``(n, 4)`` in its pixels to boxes in the source's.
Tile = Tuple[np.ndarray, Callable[[np.ndarray], np.ndarray]]


def zoomable(boxes: np.ndarray, scores: np.ndarray, rule: ZoomRule = DEFAULT_ZOOM) -> np.ndarray:
    """Mask of the boxes the zoomed look takes: scored from ``rule.min_score``, at most
    ``rule.max_box_px`` on their longer side and at least ``rule.min_height_to_width`` times as
    tall as wide."""
    b = np.asarray(boxes, float).reshape(-1, 4)
    width, height = b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]
    return ((np.asarray(scores, float) >= rule.min_score) & (np.maximum(width, height) <= rule.max_box_px)
            & (height >= rule.min_height_to_width * width))


def tile_view(box: np.ndarray, pano_width_px: int, pano_height_px: int, rule: ZoomRule = DEFAULT_ZOOM
              ) -> PerspectiveView:
    """The square pinhole view centred on the panorama box ``box`` whose field of view makes
    the box's longer side ``rule.box_px`` of the tile's ``rule.tile_px``."""
    W, H = pano_width_px, pano_height_px
    u_centre = np.mod(0.5 * (box[0] + box[2]), W)
    azimuth, elevation = geometry.pixel_to_angles_rad(u_centre, 0.5 * (box[1] + box[3]), W, H)
    longer_deg = max(box[2] - box[0], box[3] - box[1]) * 360.0 / W
    fov_deg = float(np.clip(longer_deg * rule.tile_px / rule.box_px, rule.min_fov_deg, rule.max_fov_deg))
    return PerspectiveView(float(np.degrees(azimuth)), float(np.degrees(elevation)), fov_deg,
                           rule.tile_px, rule.tile_px)


def panorama_tiles(pano: np.ndarray, boxes: np.ndarray, rule: ZoomRule = DEFAULT_ZOOM) -> List[Tile]:
    """A tile per box of the panorama ``pano`` (:func:`tile_view`, widened ``rule.stretch``
    times), with its map back to panorama pixels in the detections' form. The maps are made
    for each tile (not cached as the fixed views' are: every tile is another view)."""
    import cv2

    H, W = pano.shape[:2]
    tiles: List[Tile] = []
    for box in np.asarray(boxes, float).reshape(-1, 4):
        view = tile_view(box, W, H, rule)
        image = view.cut(pano, cached=False)
        if rule.tile_width_px != view.width_px:
            image = cv2.resize(image, (rule.tile_width_px, rule.tile_px), interpolation=cv2.INTER_LINEAR)
        tiles.append((image, partial(_view_to_pano, view, W, H, rule.tile_width_px / view.width_px)))
    return tiles


def _view_to_pano(view: PerspectiveView, pano_width_px: int, pano_height_px: int, stretch: float,
                  boxes: np.ndarray) -> np.ndarray:
    view_boxes = np.asarray(boxes, float).reshape(-1, 4) / [stretch, 1.0, stretch, 1.0]
    return view.boxes_to_pano(view_boxes, pano_width_px, pano_height_px)


def _tile_to_image(x0: float, y0: float, image_px_per_tile_px: float, stretch: float, boxes: np.ndarray
                   ) -> np.ndarray:
    scale = image_px_per_tile_px * np.array([1.0 / stretch, 1.0, 1.0 / stretch, 1.0])
    return np.asarray(boxes, float).reshape(-1, 4) * scale + [x0, y0, x0, y0]


def image_tiles(image: np.ndarray, boxes: np.ndarray, rule: ZoomRule = DEFAULT_ZOOM) -> List[Tile]:
    """A tile per box of a photograph (pinhole image): the square around the box's centre
    whose side makes the box's longer side ``rule.box_px``, scaled to ``rule.tile_px``
    (widened ``rule.stretch`` times; grey beyond the image's edge), with its map back to image
    pixels."""
    import cv2

    tiles: List[Tile] = []
    for box in np.asarray(boxes, float).reshape(-1, 4):
        side = max(box[2] - box[0], box[3] - box[1], 1.0) * rule.tile_px / rule.box_px
        scale = rule.tile_px / side
        x0, y0 = 0.5 * (box[0] + box[2]) - 0.5 * side, 0.5 * (box[1] + box[3]) - 0.5 * side
        to_tile = np.array([[scale * rule.stretch, 0.0, -x0 * scale * rule.stretch], [0.0, scale, -y0 * scale]])
        tile = cv2.warpAffine(image, to_tile, (rule.tile_width_px, rule.tile_px), flags=cv2.INTER_LINEAR,
                              borderMode=cv2.BORDER_CONSTANT, borderValue=(MOSAIC_FILL,) * 3)
        tiles.append((tile, partial(_tile_to_image, x0, y0, side / rule.tile_px, rule.stretch)))
    return tiles


def mosaics(tiles: Sequence[np.ndarray], input_w: int, input_h: int
            ) -> List[Tuple[np.ndarray, List[int], List[Tuple[int, int]]]]:
    """The tiles (as high as each other, of any widths) packed in detector inputs of
    ``input_w`` x ``input_h`` on grey: rows of the tiles' height, the widest tiles first (in
    their order among equals), each tile in the first row of the current input with room left,
    the next input when none has. A list of (image, the tile indices in its slots, each slot's
    top-left corner ``(x, y)``); tiles of one width fill the rows left to right, top to bottom.
    An input smaller than a tile takes one tile, the image a tile's size (the detector
    letterboxes it)."""
    out: List[Tuple[np.ndarray, List[int], List[Tuple[int, int]]]] = []
    if not len(tiles):
        return out
    row_h = max(int(t.shape[0]) for t in tiles)
    filled: List[int] = []
    for k in sorted(range(len(tiles)), key=lambda k: -int(tiles[k].shape[1])):
        w = int(tiles[k].shape[1])
        row = next((r for r, used in enumerate(filled) if out and used + w <= out[-1][0].shape[1]), None)
        if row is None:
            image = np.full((max(input_h, row_h), max(input_w, w), 3), MOSAIC_FILL, np.uint8)
            out.append((image, [], []))
            filled = [0] * max(1, image.shape[0] // row_h)
            row = 0
        image, slots, corners = out[-1]
        x, y = filled[row], row * row_h
        image[y:y + tiles[k].shape[0], x:x + w] = tiles[k]
        slots.append(k)
        corners.append((x, y))
        filled[row] += w
    return out


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    if w <= 0 or h <= 0:
        return 0.0
    inter = w * h
    return float(inter / ((a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter))


def zoomed_scores(detector, tiles: Sequence[Tile], boxes: np.ndarray, rule: ZoomRule = DEFAULT_ZOOM,
                  confidence: float = 0.05, wrap_px: float = 0.0
                  ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The network's best box on each candidate in its tile: per box of ``boxes`` (source
    pixels; ``tiles`` in the same order, packed by :func:`mosaics`), the score (0 where none),
    class id (-1) and box (the candidate's where none) of the highest-scoring detection from
    ``confidence`` whose centre lies in the candidate's tile and that overlaps the candidate
    by ``rule.min_iou`` once mapped back. ``wrap_px``: the panorama's width, for boxes across
    its seam (0: a photograph). ``detector``: a :class:`.detector.Detector` (``input_size``,
    ``detect_many``)."""
    boxes = np.asarray(boxes, float).reshape(-1, 4)
    score = np.zeros(len(boxes))
    class_id = np.full(len(boxes), -1, np.int64)
    best_box = boxes.copy()
    if not len(boxes):
        return score, class_id, best_box
    input_w, input_h = detector.input_size
    layout = mosaics([image for image, _ in tiles], input_w, input_h)
    found = detector.detect_many([image for image, _, _ in layout], confidence)
    for (_, slots, corners), det in zip(layout, found):
        for box_xyxy, s, c in zip(det.boxes_xyxy, det.scores, det.class_ids):
            cx, cy = 0.5 * (box_xyxy[0] + box_xyxy[2]), 0.5 * (box_xyxy[1] + box_xyxy[3])
            slot = next((n for n, (k, (x, y)) in enumerate(zip(slots, corners))
                         if x <= cx < x + tiles[k][0].shape[1] and y <= cy < y + tiles[k][0].shape[0]), None)
            if slot is None or s <= score[slots[slot]]:
                continue
            k, (x, y) = slots[slot], corners[slot]
            h, w = tiles[k][0].shape[:2]
            local = np.clip(box_xyxy - [x, y] * 2, 0.0, [w, h] * 2)
            mapped = tiles[k][1](local[None])[0]
            if wrap_px:   # to the candidate's side of the seam
                shift = wrap_px * np.round((boxes[k, 0] - mapped[0]) / wrap_px)
                mapped = mapped + [shift, 0.0, shift, 0.0]
            if _iou(mapped, boxes[k]) >= rule.min_iou:
                score[k], class_id[k], best_box[k] = float(s), int(c), mapped
    return score, class_id, best_box


def confirm(detector, image: np.ndarray, boxes: np.ndarray, scores: np.ndarray, confidence: float,
            rule: Union[ZoomRule, Sequence[ZoomRule]] = DEFAULT_ZOOM, panorama: bool = True
            ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The zoomed looks ``rule`` (one :class:`ZoomRule` or several) on candidates ``boxes``
    scored ``scores`` in ``image`` (a panorama, else a photograph): the rows the detector
    scores at ``confidence`` or more once cut again (:func:`panorama_tiles` or
    :func:`image_tiles`), with their zoomed scores, class ids and boxes (a panorama's on the
    candidate's side of its seam). Each rule cuts a tile of each candidate it takes
    (:func:`zoomable`); the tiles of all rules are packed together (:func:`mosaics`) and
    detected in the same network runs (:func:`zoomed_scores`); a candidate two rules take
    keeps its higher zoomed score. The rules must agree on ``min_iou``."""
    rules = zoom_rules(rule)
    if len({r.min_iou for r in rules}) > 1:
        raise ValueError("zoomed looks run together must have the same min_iou")
    boxes = np.asarray(boxes, float).reshape(-1, 4)
    owners, tiles = [], []
    for r in rules:
        rows = np.flatnonzero(zoomable(boxes, scores, r))
        tiles += panorama_tiles(image, boxes[rows], r) if panorama else image_tiles(image, boxes[rows], r)
        owners.append(rows)
    owner = np.concatenate(owners) if owners else np.zeros(0, np.int64)
    if not len(owner):
        return owner, np.zeros(0), np.zeros(0, np.int64), np.zeros((0, 4))
    score, class_id, box = zoomed_scores(detector, tiles, boxes[owner], rules[0], confidence=confidence,
                                         wrap_px=image.shape[1] if panorama else 0.0)
    best: dict = {}   # candidate row -> its tile with the highest zoomed score (the first among equals)
    for t, k in enumerate(owner):
        if int(k) not in best or score[t] > score[best[int(k)]]:
            best[int(k)] = t
    rows = np.array(sorted(best), np.int64)
    picked = np.array([best[k] for k in rows], np.int64)
    kept = score[picked] >= confidence
    return rows[kept], score[picked][kept], class_id[picked][kept], box[picked][kept]
