"""Sign faces, billboards and mirrors drawn with OpenCV into RGBA textures (RGB order).

A texture covers the panel's bounding rectangle; alpha 255 inside the sign's outline, 0
outside (rays pass there). Texture row 0 is the panel's top edge, column 0 its left edge
seen from the front. ``pyramid`` gives area-downsampled levels for distance-dependent
sampling in the panorama renderer.
"""
from __future__ import annotations

import cv2
import numpy as np

RED = (200, 25, 35)
BLUE = (20, 80, 170)
WHITE = (245, 245, 245)
BLACK = (20, 20, 20)
GREEN = (0, 110, 70)
YELLOW = (250, 200, 20)
AA = cv2.LINE_AA

#: panel size (width, height) in metres per class
PANEL_SIZE = {
    "warning": (0.90, 0.78), "yield": (0.90, 0.78), "prohibitory": (0.60, 0.60),
    "mandatory": (0.60, 0.60), "stop": (0.60, 0.60), "information": (0.60, 0.60),
}
VARIANTS = {
    "warning": ["exclamation", "curve", "crossroads", "children"],
    "prohibitory": ["30", "50", "70", "100", "no_overtaking", "no_entry_trucks"],
    "mandatory": ["ahead", "right", "left", "keep_right", "roundabout"],
    "information": ["parking", "crossing", "one_way", "dead_end", "direction"],
    "stop": ["stop"],
    "yield": ["yield"],
}
#: OpenStreetMap ``traffic_sign`` code (Germany) of each drawn variant, as in
#: ``models/sign-codes-de.csv``; written to ``reference_signs.csv`` (column ``code``).
VARIANT_CODES = {
    ("warning", "exclamation"): "DE:101", ("warning", "curve"): "DE:103-10",
    ("warning", "crossroads"): "DE:102", ("warning", "children"): "DE:136-10",
    ("prohibitory", "30"): "DE:274[30]", ("prohibitory", "40"): "DE:274[40]",
    ("prohibitory", "50"): "DE:274[50]", ("prohibitory", "70"): "DE:274[70]",
    ("prohibitory", "100"): "DE:274[100]", ("prohibitory", "no_overtaking"): "DE:276",
    ("prohibitory", "no_entry_trucks"): "DE:253",
    ("mandatory", "ahead"): "DE:209-30", ("mandatory", "right"): "DE:209", ("mandatory", "left"): "DE:209-10",
    ("mandatory", "keep_right"): "DE:222", ("mandatory", "roundabout"): "DE:215",
    ("information", "parking"): "DE:314", ("information", "crossing"): "DE:350-10",
    ("information", "one_way"): "DE:220-20", ("information", "dead_end"): "DE:357",
    ("information", "direction"): "DE:434", ("information", "gantry"): "DE:434",
    ("stop", "stop"): "DE:206", ("yield", "yield"): "DE:205",
}


def _canvas(w, h):
    return np.zeros((h, w, 4), np.uint8)


def _fill(img, pts, rgb):
    cv2.fillPoly(img, [np.round(np.asarray(pts) * 16).astype(np.int32)], (*rgb, 255), AA, shift=4)


def _text(img, text, rgb, box_w, centre, thickness, font=cv2.FONT_HERSHEY_DUPLEX):
    """Text of width ``box_w`` pixels centred at ``centre``."""
    (tw, th), _ = cv2.getTextSize(text, font, 1.0, thickness)
    scale = box_w / tw
    (tw, th), _ = cv2.getTextSize(text, font, scale, thickness)
    org = (int(round(centre[0] - tw / 2)), int(round(centre[1] + th / 2)))
    cv2.putText(img, text, org, font, scale, (*rgb, 255), thickness, AA)


def _arrow(img, pts, rgb, thick, head=None):
    pts = np.round(np.asarray(pts, float)).astype(np.int32)
    cv2.polylines(img, [pts], False, (*rgb, 255), thick, AA)
    p, q = pts[-2].astype(float), pts[-1].astype(float)
    d = (q - p) / max(np.linalg.norm(q - p), 1e-9)
    n = np.array([-d[1], d[0]])
    head = head or 2.2 * thick
    tip = q + d * head
    _fill(img, [tip, q + n * head, q - n * head], rgb)


def _regular_polygon(cx, cy, r, n, rot):
    a = rot + 2 * np.pi * np.arange(n) / n
    return np.stack([cx + r * np.cos(a), cy + r * np.sin(a)], 1)


def sign_texture(cls: str, variant: str, size_px: int = 256) -> np.ndarray:
    """RGBA texture of one sign face, ``size_px`` along its longer side."""
    pw, ph = PANEL_SIZE[cls] if variant != "direction" else (1.0, 0.6)
    w = size_px if pw >= ph else int(round(size_px * pw / ph))
    h = size_px if ph >= pw else int(round(size_px * ph / pw))
    img = _canvas(w, h)
    cx, cy, r = w / 2, h / 2, min(w, h) / 2
    if cls in ("warning", "yield"):
        up = cls == "warning"
        top, bot = (0.0, h - 1.0) if up else (h - 1.0, 0.0)
        tri = np.array([[w / 2, top], [0, bot], [w - 1, bot]])
        _fill(img, tri, RED)
        centroid = tri.mean(0)
        _fill(img, centroid + 0.72 * (tri - centroid), WHITE)
        if cls == "warning":
            c = centroid + [0, 0.05 * h]
            if variant == "exclamation":
                _fill(img, [c + [-0.035 * w, -0.22 * h], c + [0.035 * w, -0.22 * h],
                            c + [0.018 * w, 0.08 * h], c + [-0.018 * w, 0.08 * h]], BLACK)
                cv2.circle(img, tuple(np.round(c + [0, 0.16 * h]).astype(int)), int(0.04 * w), (*BLACK, 255), -1, AA)
            elif variant == "curve":
                _arrow(img, [c + [0.05 * w, 0.2 * h], c + [0.05 * w, 0.0], c + [-0.05 * w, -0.12 * h],
                             c + [-0.05 * w, -0.2 * h]], BLACK, max(2, int(0.05 * w)))
            elif variant == "crossroads":
                t = max(2, int(0.06 * w))
                cv2.line(img, tuple(np.round(c + [0, -0.25 * h]).astype(int)),
                         tuple(np.round(c + [0, 0.22 * h]).astype(int)), (*BLACK, 255), t, AA)
                cv2.line(img, tuple(np.round(c + [-0.17 * w, 0]).astype(int)),
                         tuple(np.round(c + [0.17 * w, 0]).astype(int)), (*BLACK, 255), t, AA)
            else:  # children: two figures
                for dx, s in ((-0.08, 1.0), (0.08, 0.8)):
                    hc = c + [dx * w, -0.12 * h * s]
                    cv2.circle(img, tuple(np.round(hc).astype(int)), int(0.035 * w * s), (*BLACK, 255), -1, AA)
                    _fill(img, [hc + [-0.04 * w * s, 0.05 * h], hc + [0.04 * w * s, 0.05 * h],
                                hc + [0.05 * w * s, 0.3 * h * s], hc + [-0.05 * w * s, 0.3 * h * s]], BLACK)
    elif cls == "prohibitory":
        cv2.circle(img, (int(cx), int(cy)), int(r - 1), (*RED, 255), -1, AA)
        cv2.circle(img, (int(cx), int(cy)), int(0.78 * r), (*WHITE, 255), -1, AA)
        if variant.isdigit():
            _text(img, variant, BLACK, (0.95 if len(variant) == 3 else 0.85) * r, (cx, cy), max(2, int(r / 14)))
        elif variant == "no_overtaking":
            for dx, col in ((-0.28, RED), (0.28, BLACK)):
                _fill(img, [[cx + (dx - 0.15) * r, cy + 0.25 * r], [cx + (dx + 0.15) * r, cy + 0.25 * r],
                            [cx + (dx + 0.12) * r, cy - 0.3 * r], [cx + (dx - 0.12) * r, cy - 0.3 * r]], col)
        else:
            _fill(img, [[cx - 0.45 * r, cy - 0.2 * r], [cx + 0.1 * r, cy - 0.2 * r],
                        [cx + 0.1 * r, cy + 0.2 * r], [cx - 0.45 * r, cy + 0.2 * r]], BLACK)
            _fill(img, [[cx + 0.15 * r, cy - 0.05 * r], [cx + 0.45 * r, cy - 0.05 * r],
                        [cx + 0.45 * r, cy + 0.2 * r], [cx + 0.15 * r, cy + 0.2 * r]], BLACK)
    elif cls == "mandatory":
        cv2.circle(img, (int(cx), int(cy)), int(r - 1), (*BLUE, 255), -1, AA)
        t = max(2, int(0.16 * r))
        if variant == "ahead":
            _arrow(img, [(cx, cy + 0.6 * r), (cx, cy - 0.25 * r)], WHITE, t)
        elif variant in ("right", "left"):
            sgn = 1 if variant == "right" else -1
            _arrow(img, [(cx - 0.2 * sgn * r, cy + 0.6 * r), (cx - 0.2 * sgn * r, cy - 0.05 * r),
                         (cx + 0.3 * sgn * r, cy - 0.05 * r)], WHITE, t)
        elif variant == "keep_right":
            _arrow(img, [(cx - 0.35 * r, cy - 0.35 * r), (cx + 0.2 * r, cy + 0.2 * r)], WHITE, t)
        else:  # roundabout: three arrows on a circle
            for k in range(3):
                a0 = 2 * np.pi * k / 3
                arc = [(cx + 0.45 * r * np.cos(a), cy + 0.45 * r * np.sin(a)) for a in np.linspace(a0, a0 + 1.3, 6)]
                _arrow(img, arc, WHITE, max(2, int(0.1 * r)), head=0.16 * r)
    elif cls == "stop":
        oct_ = _regular_polygon(cx, cy, r / np.cos(np.pi / 8) - 1, 8, np.pi / 8)
        _fill(img, oct_, WHITE)
        _fill(img, _regular_polygon(cx, cy, 0.9 * r / np.cos(np.pi / 8), 8, np.pi / 8), RED)
        _text(img, "STOP", WHITE, 1.45 * r, (cx, cy), max(2, int(r / 10)))
        img[..., 3] = np.where(img[..., 3] > 0, 255, 0)
    else:  # information
        bg = GREEN if variant == "direction" else BLUE
        cv2.rectangle(img, (0, 0), (w - 1, h - 1), (*WHITE, 255), -1)
        m = max(2, int(0.04 * min(w, h)))
        cv2.rectangle(img, (m, m), (w - 1 - m, h - 1 - m), (*bg, 255), -1)
        if variant == "parking":
            _text(img, "P", WHITE, 0.55 * w, (cx, cy), max(3, int(w / 12)))
        elif variant == "crossing":
            _fill(img, [[cx, 0.15 * h], [0.12 * w, 0.82 * h], [0.88 * w, 0.82 * h]], WHITE)
            cv2.circle(img, (int(cx), int(0.38 * h)), int(0.05 * w), (*BLACK, 255), -1, AA)
            cv2.line(img, (int(cx), int(0.43 * h)), (int(cx - 0.06 * w), int(0.75 * h)), (*BLACK, 255),
                     max(2, int(0.035 * w)), AA)
            for k in range(4):
                x0 = 0.2 * w + k * 0.16 * w
                cv2.rectangle(img, (int(x0), int(0.77 * h)), (int(x0 + 0.08 * w), int(0.8 * h)), (*BLACK, 255), -1)
        elif variant == "one_way":
            _arrow(img, [(0.22 * w, cy), (0.68 * w, cy)], WHITE, max(3, int(0.12 * h)))
        elif variant == "dead_end":
            cv2.rectangle(img, (int(0.42 * w), int(0.35 * h)), (int(0.58 * w), int(0.85 * h)), (*WHITE, 255), -1)
            cv2.rectangle(img, (int(0.25 * w), int(0.2 * h)), (int(0.75 * w), int(0.35 * h)), (*RED, 255), -1)
        else:  # direction sign
            _text(img, "WIEN 12", WHITE, 0.62 * w, (0.42 * w, 0.33 * h), max(2, int(h / 30)))
            _text(img, "LINZ 180", WHITE, 0.62 * w, (0.42 * w, 0.7 * h), max(2, int(h / 30)))
            _arrow(img, [(0.8 * w, 0.75 * h), (0.8 * w, 0.3 * h)], WHITE, max(3, int(0.06 * h)))
        img[..., 3] = 255
    img[..., 3] = np.where(img[..., 3] >= 128, 255, 0)
    return img


def faded(tex: np.ndarray, amount: float = 0.55) -> np.ndarray:
    """Sun-bleached sheeting: colours washed out towards pale grey."""
    out = tex.copy()
    rgb = out[..., :3].astype(np.float32)
    grey = rgb.mean(-1, keepdims=True)
    rgb = (1 - amount) * rgb + amount * (0.5 * grey + 0.5 * 200)
    out[..., :3] = np.clip(rgb, 0, 255).astype(np.uint8)
    return out


def gantry_texture(text_lines, size_px=512) -> np.ndarray:
    """Large green direction panel (3 x 1.5 m)."""
    w, h = size_px, size_px // 2
    img = _canvas(w, h)
    cv2.rectangle(img, (0, 0), (w - 1, h - 1), (*WHITE, 255), -1)
    cv2.rectangle(img, (6, 6), (w - 7, h - 7), (*GREEN, 255), -1)
    for k, line in enumerate(text_lines):
        _text(img, line, WHITE, 0.6 * w, (0.4 * w, (0.3 + 0.38 * k) * h), 3)
    _arrow(img, [(0.85 * w, 0.85 * h), (0.85 * w, 0.25 * h)], WHITE, 10)
    img[..., 3] = 255
    return img


def billboard_texture(rng, size_px=512) -> np.ndarray:
    """Advertising board (3 x 2 m) with red and blue round shapes that fool detectors."""
    w, h = size_px, int(size_px * 2 / 3)
    img = _canvas(w, h)
    bg = tuple(int(c) for c in rng.integers(60, 250, 3))
    img[...] = (*bg, 255)
    for _ in range(3):
        col = [RED, RED, BLUE, YELLOW][int(rng.integers(0, 4))]
        c = (int(rng.integers(40, w - 40)), int(rng.integers(40, h - 40)))
        rad = int(rng.integers(25, 70))
        cv2.circle(img, c, rad, (*col, 255), -1, AA)
        if rng.random() < 0.6:
            cv2.circle(img, c, int(rad * 0.7), (*WHITE, 255), -1, AA)
            _text(img, str(int(rng.integers(10, 99))), BLACK, rad, c, 3)
    _text(img, ["SALE", "PIZZA", "BANK", "KAFFEE"][int(rng.integers(0, 4))], BLACK, 0.5 * w, (w / 2, 0.85 * h), 5)
    cv2.rectangle(img, (0, 0), (w - 1, h - 1), (*WHITE, 255), 8)
    img[..., 3] = 255
    return img


def mirror_texture(size_px=256) -> np.ndarray:
    """Convex traffic mirror: red-and-white ring around a silvery-blue glass."""
    img = _canvas(size_px, size_px)
    c = size_px // 2
    cv2.circle(img, (c, c), c - 1, (*RED, 255), -1, AA)
    for k in range(8):  # white stripes on the ring
        a0 = k * 45.0
        cv2.ellipse(img, (c, c), (c - 1, c - 1), 0, a0, a0 + 20, (*WHITE, 255), -1, AA)
    yy, xx = np.mgrid[0:size_px, 0:size_px]
    rr = np.hypot(xx - c, yy - c) / (0.8 * c)
    glass = rr <= 1
    shade = np.clip(200 - 70 * rr + 40 * (yy < c), 0, 255)
    img[glass, 0] = (shade[glass] * 0.8).astype(np.uint8)
    img[glass, 1] = (shade[glass] * 0.9).astype(np.uint8)
    img[glass, 2] = shade[glass].astype(np.uint8)
    img[..., 3] = np.where(img[..., 3] >= 128, 255, 0)
    return img


def pyramid(tex: np.ndarray, min_side: int = 8):
    """Area-downsampled levels of an RGBA texture, level 0 first (alpha kept binary)."""
    levels = [tex]
    while min(levels[-1].shape[:2]) >= 2 * min_side:
        h, w = levels[-1].shape[:2]
        nxt = cv2.resize(levels[-1], (w // 2, h // 2), interpolation=cv2.INTER_AREA)
        levels.append(nxt)
    return levels


def noise_tile(rng, size=256, smooth=3.0) -> np.ndarray:
    """Smooth periodic noise in [-1, 1] (float32), for asphalt, grass, foliage, clouds."""
    n = rng.standard_normal((size, size)).astype(np.float32)
    n = cv2.GaussianBlur(np.tile(n, (3, 3)), (0, 0), smooth)[size:2 * size, size:2 * size]
    return n / max(float(np.abs(n).max()), 1e-6)
