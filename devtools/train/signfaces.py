"""Sign faces of many countries, drawn in code (issue 15: what makes a sign a sign).

The bundled detector learned German pictograms: on street views from other countries it
misses no-parking, parking, one-way and no-entry signs, even large ones. A face drawn here
keeps what a class shares across the countries that use its shape -- the outline, the
sheeting colours, the border -- and draws at random what varies: the legend (numbers and
words in several fonts and scripts, arrows, silhouettes of strokes and blobs), the
proportions, the shades of the sheeting, the border's width, rounded corners, fading and
dirt. Faces are RGBA (alpha 0 outside the sign), ``size_px`` along the longer side.

Families (:data:`FAMILIES`, class: what is drawn):

- ``prohibitory``: a red ring on white or yellow around numbers, letters or a silhouette,
  often crossed by a red bar; the no-parking (one bar) and no-stopping (a cross) signs, a
  red ring on blue; no entry, a red disc with a white bar;
- ``mandatory``: a blue disc with white arrows or a silhouette, sometimes a white rim;
- ``warning``: a triangle point up, red border, white or yellow field, a black legend;
- ``yield``: a triangle point down, red border, white or yellow field, sometimes a word;
- ``stop``: a red octagon, white rim, the word for stop in one of several languages;
- ``information``: rectangular panels, blue, green, white, yellow or brown, with a P, an
  arrow with or without words (one way), a pictogram square or lines of place names.

Nothing is downloaded: the fonts are the DejaVu faces Debian installs with QGIS; where
there are none, OpenCV's Hershey fonts draw the words.
"""
from __future__ import annotations

import functools
import glob
import math
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import cv2
import numpy as np

from devtools.scenegen.textures import AA, _fill, _regular_polygon, faded  # the generator's own helpers
from devtools.scenegen.textures import _arrow as _polyline_arrow

from .data import CLASSES  # noqa: F401  (the six classes, declared once there)

#: Where the TrueType fonts are looked for (Debian's fonts-dejavu).
FONT_GLOBS = ("/usr/share/fonts/truetype/dejavu/DejaVu*.ttf",)
#: Words for stop on octagons (Latin, Cyrillic, Greek scripts).
STOP_WORDS = ("STOP", "STOP", "STOP", "ALTO", "PARE", "ARRÊT", "СТОП", "DUR", "STÓJ", "ΣΤΟΠ")
#: Words on yield triangles (most carry none).
YIELD_WORDS = ("YIELD", "CEDA EL PASO", "GIVE WAY", "VORFAHRT")
#: Words under one-way arrows.
ONE_WAY_WORDS = ("ONE WAY", "SENS UNIQUE", "EINBAHN", "SENSO UNICO", "JEDNOSMJERNA")
#: Letters and short words on round and square faces.
LETTERS = "ABCDEFGHKLMNPRSTUVWXZ"
#: Class of each family, and how often it is drawn within its class.
FAMILIES: Dict[str, Tuple[str, float]] = {
    "ring_legend": ("prohibitory", 0.45),
    "no_parking": ("prohibitory", 0.2),
    "no_stopping": ("prohibitory", 0.15),
    "no_entry": ("prohibitory", 0.2),
    "blue_disc": ("mandatory", 1.0),
    "triangle_up": ("warning", 1.0),
    "triangle_down": ("yield", 1.0),
    "octagon": ("stop", 1.0),
    "panel_p": ("information", 0.25),
    "panel_one_way": ("information", 0.25),
    "panel_pictogram": ("information", 0.2),
    "panel_text": ("information", 0.3),
}


# --- colours ---------------------------------------------------------------------------

def _jitter(rng, rgb, spread: float) -> Tuple[int, int, int]:
    """``rgb`` moved by up to ``spread`` per channel, brightness scaled by 0.85-1.1."""
    c = np.asarray(rgb, float) * rng.uniform(0.85, 1.1) + rng.uniform(-spread, spread, 3)
    return tuple(int(v) for v in np.clip(c, 0, 255))


def sheeting(rng, name: str) -> Tuple[int, int, int]:
    """A shade of one sheeting colour (RGB), as different countries' films and ages give."""
    base = {
        "red": [(200, 25, 35), (180, 20, 30), (225, 40, 40), (190, 30, 60)],
        "blue": [(20, 80, 170), (0, 60, 140), (30, 110, 200), (10, 50, 120)],
        "white": [(245, 245, 245), (235, 235, 225), (240, 240, 248)],
        "yellow": [(250, 200, 20), (245, 215, 40), (255, 180, 0)],
        "green": [(0, 110, 70), (0, 130, 60), (20, 100, 80)],
        "brown": [(120, 70, 30), (100, 60, 35)],
        "black": [(20, 20, 20), (35, 35, 40)],
    }[name]
    return _jitter(rng, base[int(rng.integers(len(base)))], 12.0)


# --- drawing helpers ---------------------------------------------------------------------

@functools.lru_cache(maxsize=None)
def font_paths() -> Tuple[str, ...]:
    """The TrueType fonts found (sans, condensed, serif, mono; plain, bold, oblique)."""
    found: List[str] = []
    for pattern in FONT_GLOBS:
        found += [p for p in sorted(glob.glob(pattern)) if "Math" not in p and "ExtraLight" not in p]
    return tuple(found)


def _disc(img, centre, r, rgb) -> None:
    cv2.circle(img, (int(round(centre[0] * 16)), int(round(centre[1] * 16))), max(1, int(round(r * 16))),
               (*rgb, 255), -1, AA, shift=4)


def _line(img, p, q, rgb, thick) -> None:
    cv2.line(img, tuple(int(round(v)) for v in p), tuple(int(round(v)) for v in q), (*rgb, 255),
             max(1, int(round(thick))), AA)


def _rounded_polygon(pts: np.ndarray, radius: float, steps: int = 6) -> np.ndarray:
    """A convex polygon's corners rounded by ``radius`` pixels (the sheeting's cut)."""
    if radius <= 0:
        return pts
    out = []
    n = len(pts)
    for k in range(n):
        p, prev, nxt = pts[k], pts[k - 1], pts[(k + 1) % n]
        a, b = prev - p, nxt - p
        la, lb = np.linalg.norm(a), np.linalg.norm(b)
        cut = min(radius, 0.45 * la, 0.45 * lb)
        s, e = p + a / la * cut, p + b / lb * cut
        for t in np.linspace(0, 1, steps):   # a quadratic curve through the corner
            out.append((1 - t) ** 2 * s + 2 * (1 - t) * t * p + t ** 2 * e)
    return np.array(out)


def _shrunk(pts: np.ndarray, by_px: float) -> np.ndarray:
    """A convex polygon moved inwards by ``by_px`` (towards its centroid, by the inradius' share)."""
    c = pts.mean(0)

    def cross2(u, v):  # the z of the 3-D cross product (numpy 2 has no 2-D np.cross)
        return u[0] * v[1] - u[1] * v[0]
    inradius = min(abs(cross2(pts[(k + 1) % len(pts)] - pts[k], c - pts[k])) /
                   np.linalg.norm(pts[(k + 1) % len(pts)] - pts[k]) for k in range(len(pts)))
    return c + (pts - c) * max(0.05, 1.0 - by_px / inradius)


def draw_text(img, text: str, rgb, box, rng, font_path: Optional[str] = None) -> None:
    """``text`` fitted into ``box`` (x0, y0, x1, y1, pixels), centred, in a random font."""
    x0, y0, x1, y1 = box
    bw, bh = max(2.0, x1 - x0), max(2.0, y1 - y0)
    fonts = font_paths()
    if fonts:
        from PIL import Image, ImageDraw, ImageFont

        path = font_path or fonts[int(rng.integers(len(fonts)))]
        probe = ImageFont.truetype(path, 64)
        left, top, right, bottom = probe.getbbox(text)
        scale = min(bw / max(right - left, 1), bh / max(bottom - top, 1))
        size = max(6, int(64 * scale))
        font = ImageFont.truetype(path, size)
        left, top, right, bottom = font.getbbox(text)
        layer = Image.new("L", (img.shape[1], img.shape[0]), 0)
        ImageDraw.Draw(layer).text((x0 + (bw - (right - left)) / 2 - left, y0 + (bh - (bottom - top)) / 2 - top),
                                   text, fill=255, font=font)
        mask = np.asarray(layer, np.float32)[..., None] / 255.0
        img[..., :3] = np.round(img[..., :3] * (1 - mask) + np.asarray(rgb, np.float32) * mask).astype(np.uint8)
        return
    font = (cv2.FONT_HERSHEY_DUPLEX, cv2.FONT_HERSHEY_SIMPLEX, cv2.FONT_HERSHEY_TRIPLEX)[int(rng.integers(3))]
    ascii_text = text.encode("ascii", "replace").decode()
    thick = max(1, int(bh / 12))
    (tw, th), _ = cv2.getTextSize(ascii_text, font, 1.0, thick)
    scale = min(bw / tw, bh / th)
    (tw, th), _ = cv2.getTextSize(ascii_text, font, scale, thick)
    cv2.putText(img, ascii_text, (int(x0 + (bw - tw) / 2), int(y0 + (bh + th) / 2)), font, scale, (*rgb, 255),
                thick, AA)


def draw_arrow(img, pts, rgb, thick: float, head: Optional[float] = None) -> None:
    """A polyline ending in a filled head (the generator's arrow, at any thickness in pixels)."""
    _polyline_arrow(img, np.asarray(pts, float), rgb, max(1, int(round(thick))), head=head or 2.2 * thick)


def _random_arrow(img, rng, cx, cy, r, rgb, thick) -> None:
    """A straight, turning or curved arrow at a random angle inside a circle of radius ``r``."""
    angle = rng.uniform(0, 2 * np.pi) if rng.random() < 0.5 else rng.choice([-np.pi / 2, 0, np.pi, np.pi / 4])
    rot = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    kind = rng.integers(3)
    if kind == 0:
        local = [(-0.6, 0), (0.35, 0)]
    elif kind == 1:
        local = [(-0.55, 0.3), (0.05, 0.3), (0.05, -0.35)]
    else:
        a = np.linspace(np.pi * 0.9, np.pi * 0.1, 8)
        local = list(zip(0.45 * np.cos(a), 0.2 - 0.45 * np.sin(a)))
    pts = np.array([[cx, cy]]) + (np.asarray(local) @ rot.T) * r
    draw_arrow(img, pts, rgb, thick, head=rng.uniform(1.8, 2.6) * thick)


def _silhouette(img, rng, cx, cy, r, rgb) -> None:
    """A pictogram that is no real one: a person, a bicycle, a vehicle or blobs and strokes."""
    kind = rng.integers(4)
    t = max(1.0, r * rng.uniform(0.07, 0.12))
    if kind == 0:   # a person
        _disc(img, (cx, cy - 0.55 * r), 0.14 * r, rgb)
        lean = rng.uniform(-0.15, 0.15) * r
        _fill(img, [(cx - 0.12 * r, cy - 0.38 * r), (cx + 0.12 * r, cy - 0.38 * r),
                    (cx + 0.1 * r + lean, cy + 0.15 * r), (cx - 0.1 * r + lean, cy + 0.15 * r)], rgb)
        for dx in (-1, 1):
            _line(img, (cx + lean, cy + 0.1 * r), (cx + lean + dx * rng.uniform(0.1, 0.35) * r, cy + 0.65 * r), rgb, t)
    elif kind == 1:  # a bicycle
        for dx in (-0.4, 0.4):
            cv2.circle(img, (int(cx + dx * r), int(cy + 0.2 * r)), max(2, int(0.25 * r)), (*rgb, 255),
                       max(1, int(t * 0.7)), AA)
        for p, q in (((-0.4, 0.2), (0.0, 0.2)), ((0.0, 0.2), (0.2, -0.2)), ((-0.15, -0.2), (0.2, -0.2)),
                     ((0.2, -0.2), (0.4, 0.2)), ((-0.15, -0.2), (-0.4, 0.2))):
            _line(img, (cx + p[0] * r, cy + p[1] * r), (cx + q[0] * r, cy + q[1] * r), rgb, t * 0.8)
    elif kind == 2:  # a vehicle, side or front
        w, h = rng.uniform(0.6, 0.9) * r, rng.uniform(0.25, 0.45) * r
        cv2.rectangle(img, (int(cx - w), int(cy - h * 0.2)), (int(cx + w), int(cy + h)), (*rgb, 255), -1, AA)
        cab = rng.uniform(0.3, 0.7)
        cv2.rectangle(img, (int(cx - w * cab), int(cy - h)), (int(cx + w * cab * rng.uniform(0.3, 1)), int(cy)),
                      (*rgb, 255), -1, AA)
        for dx in (-0.6, 0.6):
            _disc(img, (cx + dx * w, cy + h), 0.18 * r, rgb)
    else:            # blobs and strokes
        for _ in range(int(rng.integers(2, 5))):
            ex, ey = rng.uniform(-0.4, 0.4, 2) * r
            axes = (max(1, int(rng.uniform(0.08, 0.3) * r)), max(1, int(rng.uniform(0.05, 0.25) * r)))
            cv2.ellipse(img, (int(cx + ex), int(cy + ey)), axes, rng.uniform(0, 180), 0, 360, (*rgb, 255), -1, AA)
        for _ in range(int(rng.integers(0, 3))):
            p, q = rng.uniform(-0.5, 0.5, 2) * r, rng.uniform(-0.5, 0.5, 2) * r
            _line(img, (cx + p[0], cy + p[1]), (cx + q[0], cy + q[1]), rgb, t)


def _legend(img, rng, cx, cy, r, rgb, numbers: float = 0.4) -> Optional[str]:
    """Numbers, letters, an arrow or a silhouette inside a circle of radius ``r``; returns
    the number or limit drawn (``"50"``, ``"3.5m"``), else None."""
    u = rng.random()
    if u < numbers:
        text = str(int(rng.choice([5, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130])))
        if rng.random() < 0.15:
            text = f"{rng.uniform(2.0, 4.5):.1f}m" if rng.random() < 0.5 else f"{int(rng.integers(3, 40))}t"
        w = r * (1.2 if len(text) >= 3 else 1.0)
        draw_text(img, text, rgb, (cx - w / 2 * 1.1, cy - 0.45 * r, cx + w / 2 * 1.1, cy + 0.45 * r), rng)
        return text
    elif u < numbers + 0.15:
        text = "".join(rng.choice(list(LETTERS), int(rng.integers(1, 3))))
        draw_text(img, text, rgb, (cx - 0.55 * r, cy - 0.5 * r, cx + 0.55 * r, cy + 0.5 * r), rng)
    elif u < numbers + 0.3:
        _random_arrow(img, rng, cx, cy, r, rgb, max(1.0, r * rng.uniform(0.1, 0.16)))
    else:
        _silhouette(img, rng, cx, cy, 0.85 * r, rgb)
    return None


# --- the families ------------------------------------------------------------------------

def _round_face(size_px: int):
    img = np.zeros((size_px, size_px, 4), np.uint8)
    c = (size_px - 1) / 2.0
    return img, c, c, size_px / 2.0 - 1.0


def _ring_legend(rng, size_px):
    img, cx, cy, r = _round_face(size_px)
    field = sheeting(rng, "yellow" if rng.random() < 0.15 else "white")
    _disc(img, (cx, cy), r, sheeting(rng, "white") if rng.random() < 0.3 else field)
    rim = r * rng.uniform(0.0, 0.04)
    _disc(img, (cx, cy), r - rim, sheeting(rng, "red"))
    inner = (r - rim) * rng.uniform(0.68, 0.82)
    _disc(img, (cx, cy), inner, field)
    legend = _legend(img, rng, cx, cy, inner * 0.85, sheeting(rng, "black"), numbers=0.45)
    if rng.random() < 0.35:   # crossed out: a red bar from upper left to lower right
        d = inner * 0.7
        _line(img, (cx - d, cy - d), (cx + d, cy + d), sheeting(rng, "red"), inner * rng.uniform(0.14, 0.22))
        legend = None         # not a limit any more
    return img, legend


def _no_parking(rng, size_px, cross: bool = False):
    img, cx, cy, r = _round_face(size_px)
    _disc(img, (cx, cy), r, sheeting(rng, "white"))
    rim = r * rng.uniform(0.0, 0.04)
    red = sheeting(rng, "red")
    _disc(img, (cx, cy), r - rim, red)
    inner = (r - rim) * rng.uniform(0.7, 0.82)
    _disc(img, (cx, cy), inner, sheeting(rng, "blue"))
    thick = inner * rng.uniform(0.18, 0.28)
    d = inner * 0.72
    _line(img, (cx - d, cy - d), (cx + d, cy + d), red, thick)
    if cross:
        _line(img, (cx + d, cy - d), (cx - d, cy + d), red, thick)
    if rng.random() < 0.2:   # a letter on the field (some countries' no-parking signs)
        draw_text(img, "P" if rng.random() < 0.5 else "E", sheeting(rng, "white"),
                  (cx - 0.35 * inner, cy - 0.45 * inner, cx + 0.35 * inner, cy + 0.45 * inner), rng)
    return img


def _no_entry(rng, size_px):
    img, cx, cy, r = _round_face(size_px)
    if rng.random() < 0.3:
        _disc(img, (cx, cy), r, sheeting(rng, "white"))
        r -= r * rng.uniform(0.02, 0.06)
    _disc(img, (cx, cy), r, sheeting(rng, "red"))
    hw, hh = r * rng.uniform(0.62, 0.8), r * rng.uniform(0.13, 0.22)
    bar = np.array([(cx - hw, cy - hh), (cx + hw, cy - hh), (cx + hw, cy + hh), (cx - hw, cy + hh)])
    _fill(img, _rounded_polygon(bar, hh * rng.uniform(0, 0.4)), sheeting(rng, "white"))
    if rng.random() < 0.15:
        draw_text(img, "NO ENTRY" if rng.random() < 0.5 else "SENS INTERDIT", sheeting(rng, "white"),
                  (cx - 0.6 * r, cy + hh * 1.3, cx + 0.6 * r, cy + hh * 1.3 + 0.25 * r), rng)
    return img


def _blue_disc(rng, size_px):
    img, cx, cy, r = _round_face(size_px)
    if rng.random() < 0.3:    # a white rim
        _disc(img, (cx, cy), r, sheeting(rng, "white"))
        r -= r * rng.uniform(0.04, 0.08)
    _disc(img, (cx, cy), r, sheeting(rng, "blue"))
    white = sheeting(rng, "white")
    u = rng.random()
    if u < 0.55:
        for _ in range(1 if rng.random() < 0.7 else 2):
            _random_arrow(img, rng, cx, cy, 0.8 * r, white, max(1.0, r * rng.uniform(0.1, 0.17)))
    elif u < 0.85:
        _silhouette(img, rng, cx, cy, 0.65 * r, white)
    else:
        draw_text(img, str(int(rng.choice([30, 40, 50, 60]))), white, (cx - 0.5 * r, cy - 0.4 * r, cx + 0.5 * r,
                                                                     cy + 0.4 * r), rng)
    return img


def _triangle(rng, size_px, up: bool):
    ratio = rng.uniform(0.82, 0.9)             # height / width of the plate
    w, h = size_px, int(round(size_px * ratio))
    img = np.zeros((h, w, 4), np.uint8)
    top, bot = (0.5, h - 1.5) if up else (h - 1.5, 0.5)
    tri = np.array([[w / 2, top], [0.5, bot], [w - 1.5, bot]])
    tri = _rounded_polygon(tri, w * rng.uniform(0.0, 0.07))
    if rng.random() < 0.25:   # a white rim outside the red
        _fill(img, tri, sheeting(rng, "white"))
        tri = _shrunk(tri, w * rng.uniform(0.015, 0.03))
    _fill(img, tri, sheeting(rng, "red"))
    field = _shrunk(tri, w * rng.uniform(0.07, 0.13))
    _fill(img, field, sheeting(rng, "yellow" if rng.random() < 0.25 else "white"))
    c = field.mean(0)
    ink = sheeting(rng, "black")
    if up:
        r = 0.3 * w
        u = rng.random()
        if u < 0.2:   # an exclamation mark
            _fill(img, [c + [-0.04 * w, -0.2 * h], c + [0.04 * w, -0.2 * h], c + [0.02 * w, 0.08 * h],
                        c + [-0.02 * w, 0.08 * h]], ink)
            _disc(img, c + [0, 0.15 * h], 0.04 * w, ink)
        elif u < 0.3 and font_paths():
            draw_text(img, "".join(rng.choice(list(LETTERS), 1)), ink,
                      (c[0] - 0.15 * w, c[1] - 0.15 * h, c[0] + 0.15 * w, c[1] + 0.17 * h), rng)
        elif u < 0.5:
            _random_arrow(img, rng, c[0], c[1] + 0.03 * h, 0.8 * r, ink, max(1.0, w * 0.045))
        else:
            _silhouette(img, rng, c[0], c[1] + 0.04 * h, 0.75 * r, ink)
    elif rng.random() < 0.15:
        word = YIELD_WORDS[int(rng.integers(len(YIELD_WORDS)))]
        draw_text(img, word, sheeting(rng, "red"), (c[0] - 0.22 * w, c[1] - 0.13 * h, c[0] + 0.22 * w,
                                                    c[1] + 0.02 * h), rng)
    return img


def _octagon(rng, size_px):
    img, cx, cy, r = _round_face(size_px)
    R = (r - 0.5) / math.cos(math.pi / 8)
    if rng.random() < 0.8:
        _fill(img, _regular_polygon(cx, cy, R, 8, math.pi / 8), sheeting(rng, "white"))
        R *= rng.uniform(0.88, 0.94)
    _fill(img, _regular_polygon(cx, cy, R, 8, math.pi / 8), sheeting(rng, "red"))
    word = STOP_WORDS[int(rng.integers(len(STOP_WORDS)))]
    span = 0.78 * R * (1.9 if len(word) >= 4 else 1.5)
    draw_text(img, word, sheeting(rng, "white"), (cx - span / 2, cy - 0.32 * R, cx + span / 2, cy + 0.32 * R), rng)
    return img


def _panel(rng, size_px, aspect: float, colour: str):
    """A rectangular panel (width / height = ``aspect``) with a rim; returns it and its field box."""
    w, h = (size_px, max(8, int(round(size_px / aspect)))) if aspect >= 1 else \
        (max(8, int(round(size_px * aspect))), size_px)
    img = np.zeros((h, w, 4), np.uint8)
    outline = np.array([(0.5, 0.5), (w - 1.5, 0.5), (w - 1.5, h - 1.5), (0.5, h - 1.5)])
    corner = min(w, h) * rng.uniform(0.0, 0.12)
    rim_colour = "black" if colour in ("white", "yellow") and rng.random() < 0.6 else "white"
    _fill(img, _rounded_polygon(outline, corner), sheeting(rng, rim_colour))
    m = max(1.0, min(w, h) * rng.uniform(0.025, 0.06))
    field = outline + np.array([(m, m), (-m, m), (-m, -m), (m, -m)])
    _fill(img, _rounded_polygon(field, max(0.0, corner - m)), sheeting(rng, colour))
    return img, (m, m, w - 1 - m, h - 1 - m)


def _ink_on(colour: str, rng):
    return sheeting(rng, "black") if colour in ("white", "yellow") else sheeting(rng, "white")


def _panel_p(rng, size_px):
    colour = "blue" if rng.random() < 0.85 else "green"
    aspect = rng.uniform(0.65, 1.05)
    img, (x0, y0, x1, y1) = _panel(rng, size_px, aspect, colour)
    ink = _ink_on(colour, rng)
    if rng.random() < 0.3:   # a sub-legend (times, a vehicle, an arrow) under the P
        draw_text(img, "P", ink, (x0 + 0.15 * (x1 - x0), y0 + 0.06 * (y1 - y0), x1 - 0.15 * (x1 - x0),
                                  y0 + 0.62 * (y1 - y0)), rng)
        sub = (x0 + 0.1 * (x1 - x0), y0 + 0.68 * (y1 - y0), x1 - 0.1 * (x1 - x0), y1 - 0.06 * (y1 - y0))
        draw_text(img, rng.choice(["8-18h", "2 HR", "MAX 2h", "P+R", "< 3.5t"]), ink, sub, rng)
    else:
        draw_text(img, "P", ink, (x0 + 0.15 * (x1 - x0), y0 + 0.12 * (y1 - y0), x1 - 0.15 * (x1 - x0),
                                  y1 - 0.12 * (y1 - y0)), rng)
    return img


def _panel_one_way(rng, size_px):
    colour = "blue" if rng.random() < 0.6 else "white"
    if rng.random() < 0.5:       # a long panel with a horizontal arrow
        aspect = rng.uniform(2.0, 3.6)
        img, (x0, y0, x1, y1) = _panel(rng, size_px, aspect, colour)
        ink = _ink_on(colour, rng)
        sgn = 1 if rng.random() < 0.5 else -1
        cy, w = (y0 + y1) / 2, x1 - x0
        thick = max(1.0, (y1 - y0) * rng.uniform(0.15, 0.3))
        xs = (x0 + 0.12 * w, x1 - 0.12 * w - 1.8 * thick)
        draw_arrow(img, [(xs[0] if sgn > 0 else xs[1] + 1.8 * thick, cy),
                         (xs[1] if sgn > 0 else xs[0] + 1.8 * thick, cy)], ink, thick)
        if rng.random() < 0.5:   # words on the arrow's shaft (in a contrasting colour)
            word = ONE_WAY_WORDS[int(rng.integers(len(ONE_WAY_WORDS)))]
            back = sheeting(rng, colour)
            draw_text(img, word, back, (x0 + 0.2 * w, cy - 0.4 * thick, x1 - 0.3 * w, cy + 0.4 * thick), rng)
    else:                        # a square panel with a vertical arrow
        img, (x0, y0, x1, y1) = _panel(rng, size_px, rng.uniform(0.8, 1.1), colour)
        ink = _ink_on(colour, rng)
        cx, h = (x0 + x1) / 2, y1 - y0
        thick = max(1.0, (x1 - x0) * rng.uniform(0.12, 0.2))
        draw_arrow(img, [(cx, y1 - 0.12 * h), (cx, y0 + 0.12 * h + 1.8 * thick)], ink, thick)
    return img


def _panel_pictogram(rng, size_px):
    colour = "blue" if rng.random() < 0.75 else ("green" if rng.random() < 0.5 else "brown")
    img, (x0, y0, x1, y1) = _panel(rng, size_px, rng.uniform(0.75, 1.1), colour)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    r = 0.42 * min(x1 - x0, y1 - y0)
    if rng.random() < 0.5:   # a white triangle or square holding a black pictogram (crossings)
        white = sheeting(rng, "white")
        if rng.random() < 0.6:
            _fill(img, [(cx, cy - 1.05 * r), (cx - 1.05 * r, cy + 0.85 * r), (cx + 1.05 * r, cy + 0.85 * r)], white)
            _silhouette(img, rng, cx, cy + 0.25 * r, 0.5 * r, sheeting(rng, "black"))
        else:
            cv2.rectangle(img, (int(cx - 0.8 * r), int(cy - 0.8 * r)), (int(cx + 0.8 * r), int(cy + 0.8 * r)),
                          (*white, 255), -1)
            _silhouette(img, rng, cx, cy, 0.65 * r, sheeting(rng, "black"))
    else:
        _silhouette(img, rng, cx, cy, 0.9 * r, sheeting(rng, "white"))
    return img


def _place_name(rng) -> str:
    n = int(rng.integers(3, 10))
    word = "".join(rng.choice(list("AEIOUAEIOU" + "BCDFGHKLMNPRSTVZ" * 2), n)).capitalize()
    return word + (f" {int(rng.integers(1, 250))}" if rng.random() < 0.6 else "")


def _panel_text(rng, size_px):
    u = rng.random()
    colour = "blue" if u < 0.35 else "green" if u < 0.6 else "white" if u < 0.8 else "yellow" if u < 0.9 else "brown"
    lines = int(rng.integers(1, 4))
    img, (x0, y0, x1, y1) = _panel(rng, size_px, rng.uniform(1.3, 4.0) * (1.0 if lines == 1 else 0.8), colour)
    ink = _ink_on(colour, rng)
    h = (y1 - y0) / lines
    arrow = rng.random() < 0.5
    right = x1 - (0.22 * (x1 - x0) if arrow else 0.05 * (x1 - x0))
    for k in range(lines):
        draw_text(img, _place_name(rng), ink, (x0 + 0.05 * (x1 - x0), y0 + (k + 0.18) * h, right,
                                               y0 + (k + 0.82) * h), rng)
    if arrow:
        ax = x1 - 0.11 * (x1 - x0)
        thick = max(1.0, 0.05 * (x1 - x0))
        draw_arrow(img, [(ax, y1 - 0.15 * (y1 - y0)), (ax, y0 + 0.15 * (y1 - y0) + 2 * thick)], ink, thick)
    return img


def _no_limit(draw: Callable) -> Callable:
    """A family's drawing that states no limit, as :data:`_DRAW` calls it: ``(rgba, None)``."""
    return lambda rng, size_px: (draw(rng, size_px), None)


#: Each family's drawing: ``(rng, size_px) -> (rgba, limit)``, the limit a face states
#: (:func:`random_face_with_limit`) or None.
_DRAW: Dict[str, Callable] = {
    "ring_legend": _ring_legend,
    "no_parking": _no_limit(_no_parking),
    "no_stopping": _no_limit(lambda rng, s: _no_parking(rng, s, cross=True)),
    "no_entry": _no_limit(_no_entry),
    "blue_disc": _no_limit(_blue_disc),
    "triangle_up": _no_limit(lambda rng, s: _triangle(rng, s, up=True)),
    "triangle_down": _no_limit(lambda rng, s: _triangle(rng, s, up=False)),
    "octagon": _no_limit(_octagon),
    "panel_p": _no_limit(_panel_p),
    "panel_one_way": _no_limit(_panel_one_way),
    "panel_pictogram": _no_limit(_panel_pictogram),
    "panel_text": _no_limit(_panel_text),
}


# --- wear and the public API ----------------------------------------------------------------

def weathered(face: np.ndarray, rng) -> np.ndarray:
    """Sun-bleached, dirty or streaked sheeting (the alpha is kept)."""
    fade = rng.uniform(0.0, 0.55) if rng.random() < 0.5 else 0.0
    out = faded(face, fade) if fade else face.copy()
    rgb = out[..., :3].astype(np.float32)
    if rng.random() < 0.4:   # dirt: a smooth dark mottling
        h, w = rgb.shape[:2]
        small = rng.uniform(0, 1, (max(2, h // 16), max(2, w // 16))).astype(np.float32)
        mottle = cv2.resize(small, (w, h), interpolation=cv2.INTER_CUBIC)
        rgb *= (1.0 - rng.uniform(0.05, 0.3) * np.clip(mottle, 0, 1))[..., None]
    if rng.random() < 0.15:  # vertical streaks from the top edge
        h, w = rgb.shape[:2]
        streak = np.zeros(w, np.float32)
        streak[rng.integers(0, w, int(rng.integers(2, 8)))] = 1.0
        streak = cv2.GaussianBlur(streak[None], (0, 0), max(0.5, w / 80))[0]
        rgb *= (1.0 - 0.25 * np.clip(streak / max(streak.max(), 1e-6), 0, 1))[None, :, None]
    out[..., :3] = np.clip(rgb, 0, 255).astype(np.uint8)
    return out


def family_class(family: str) -> str:
    return FAMILIES[family][0]


def random_face(rng, size_px: int = 160, cls: Optional[str] = None,
                families: Optional[Sequence[str]] = None) -> Tuple[np.ndarray, str, str]:
    """One face drawn at random: ``(rgba, class, family)``. ``cls`` picks the class (else
    each of the six equally), ``families`` limits the families drawn from."""
    face, cls, family, _ = random_face_with_limit(rng, size_px, cls, families)
    return face, cls, family


def random_face_with_limit(rng, size_px: int = 160, cls: Optional[str] = None,
                           families: Optional[Sequence[str]] = None
                           ) -> Tuple[np.ndarray, str, str, Optional[str]]:
    """:func:`random_face` (the same draws from ``rng``) and the limit a red ring states:
    its number or limit (``"50"``, ``"3.5m"``) when the face is a ``ring_legend`` with one
    and not crossed out, else None."""
    pool = [f for f in (families or FAMILIES) if cls is None or FAMILIES[f][0] == cls]
    if not pool:
        raise ValueError(f"no family of class {cls!r} among {families}")
    if cls is None:   # the classes equally, then the families by weight
        classes = sorted({FAMILIES[f][0] for f in pool})
        cls = classes[int(rng.integers(len(classes)))]
        pool = [f for f in pool if FAMILIES[f][0] == cls]
    weights = np.array([FAMILIES[f][1] for f in pool])
    family = pool[int(rng.choice(len(pool), p=weights / weights.sum()))]
    face, limit = _DRAW[family](rng, int(size_px))
    face[..., 3] = np.where(face[..., 3] >= 128, 255, 0).astype(np.uint8)
    return weathered(face, rng), cls, family, limit


def random_faces(n: int, seed: int = 0, size_px: int = 160) -> List[Tuple[np.ndarray, str, str]]:
    """``n`` faces, repeatable from ``seed``."""
    rng = np.random.default_rng(seed)
    return [random_face(rng, size_px) for _ in range(n)]
