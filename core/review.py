"""Review material for analysts: an image chip of each sign from its best panorama, and an
HTML page with every sign's thumbnail and attributes (its code and the code's name in the
card's title).

A chip is a perspective (undistorted) view centred on the ray through the centre of the
sign's box in its best panorama, wide enough for the box plus ``margin_frac`` of its size
on each side, so a sign near the +-180 deg seam or the poles comes out whole.
"""
from __future__ import annotations

import html
import os
from typing import Dict, List, Optional, Sequence

import numpy as np

from . import geometry
from .errors import SILENT, InputError, Progress
from .outputs import write_text_atomically
from .panorama import PerspectiveView, read_panorama
from .schema import Field

CHIP_SIZE_PX = 256
#: The field the sign layer gains with review chips: the chip's path relative to the layer's folder.
CHIP_FIELD = Field("chip", str)


def chip_view(u0, v0, u1, v1, width_px: int, height_px: int, margin_frac: float = 0.5,
              size_px: int = CHIP_SIZE_PX) -> PerspectiveView:
    """The square perspective view showing a panorama box (detections layer form) with a margin."""
    u, v = geometry.box_centre_pixel(u0, v0, u1, v1, width_px)
    yaw_rad, pitch_rad = geometry.pixel_to_angles_rad(u, v, width_px, height_px)
    box_w_deg = (float(u1) - float(u0)) / width_px * 360.0 * np.cos(pitch_rad)
    box_h_deg = (float(v1) - float(v0)) / height_px * 180.0
    fov_deg = float(np.clip(max(box_w_deg, box_h_deg) * (1.0 + 2.0 * margin_frac), 2.0, 120.0))
    return PerspectiveView(float(np.degrees(yaw_rad)), float(np.degrees(pitch_rad)), fov_deg,
                           size_px, size_px)


def best_view_boxes(candidates, refined) -> List[Optional[np.ndarray]]:
    """Per sign of ``refined`` (a refine result), the box (u0, v0, u1, v1) of its best
    image among the candidates (a projection result) merged into it; None if none."""
    det = candidates.detections
    boxes: List[Optional[np.ndarray]] = []
    for k, sign in enumerate(refined.signs):
        rows = [i for i in np.flatnonzero(refined.candidate_sign == k) if det.image[i] == sign.best_image]
        boxes.append(det.box_px[max(rows, key=lambda i: det.score[i])] if rows else None)
    return boxes


def write_chips(signs: Sequence[Dict], boxes: Sequence[Optional[Sequence[float]]], images_dir: str,
                chips_dir: str, progress: Progress = SILENT) -> List[str]:
    """One JPEG per sign from its ``best_image`` (``boxes[k]``: u0, v0, u1, v1 in it).

    Returns the chip file names ("" where the sign has no box or its panorama cannot be
    read: a warning says so). Each panorama is read once.
    """
    import cv2

    os.makedirs(chips_dir, exist_ok=True)
    names = [""] * len(signs)
    by_image: Dict[str, List[int]] = {}
    for k, (sign, box) in enumerate(zip(signs, boxes)):
        if box is not None and sign.get("best_image"):
            by_image.setdefault(sign["best_image"], []).append(k)
    for done, (image, members) in enumerate(sorted(by_image.items())):
        progress.report(done / max(len(by_image), 1))
        try:
            pano = read_panorama(os.path.join(images_dir, image))
        except InputError as error:
            progress.warning(error.template, **error.fields)
            continue
        height_px, width_px = pano.shape[:2]
        for k in members:
            u0, v0, u1, v1 = boxes[k]  # type: ignore[misc]  # members only hold signs with a box
            chip = chip_view(u0, v0, u1, v1, width_px, height_px).cut(pano)
            name = "sign_{}.jpg".format(signs[k]["sign_id"])
            ok, data = cv2.imencode(".jpg", chip, [cv2.IMWRITE_JPEG_QUALITY, 90])
            if ok:
                data.tofile(os.path.join(chips_dir, name))
                names[k] = name
    progress.report(1.0)
    return names


REPORT_FIELDS = ("class", "score", "code", "code_name", "code_score", "code_views", "code_check",
                 "height", "bottom_height", "width", "panel_height", "azimuth",
                 "n_views", "n_points", "position_source", "best_image", "source_images",
                 "mean_intensity", "planarity", "x", "y", "z")
UNITS = {"height": "m", "bottom_height": "m", "width": "m", "panel_height": "m", "azimuth": "°",
         "x": "m", "y": "m", "z": "m"}


def _format(name: str, value) -> str:
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "–"
    if isinstance(value, float):
        digits = 3 if name in ("x", "y", "z", "score", "code_score", "planarity") else 2
        text = "{:.{}f}".format(value, digits)
    else:
        text = str(value)
    return html.escape(text + (" " + UNITS[name] if name in UNITS else ""))


def _code_title(sign: Dict) -> str:
    """``: DE:274[50] speed limit 50`` for a sign with a code (HTML-escaped); a check to
    make (``code_check``) is added in brackets; empty without either."""
    code = str(sign.get("code") or "").strip()
    check = str(sign.get("code_check") or "").strip()
    text = " ".join(t for t in (code, str(sign.get("code_name") or "").strip() if code else "") if t)
    if check:
        text += " ({})".format(check)
    return html.escape(": " + text.strip()) if text.strip() else ""


def write_review_report(signs: Sequence[Dict], chip_paths: Sequence[str], path: str,
                        title: str = "Road signs for review") -> None:
    """A self-contained HTML page (chips linked by relative path), written atomically with
    the user's normal permissions."""
    rows = []
    for sign, chip in zip(signs, chip_paths):
        picture = ('<img src="{}" alt="sign {}" width="{}">'.format(
            html.escape(chip), html.escape(str(sign["sign_id"])), CHIP_SIZE_PX // 2) if chip else "–")
        cells = "".join("<tr><th>{}</th><td>{}</td></tr>".format(html.escape(n), _format(n, sign.get(n)))
                        for n in REPORT_FIELDS)
        rows.append('<div class="sign"><h2>Sign {}{}</h2>{}<table>{}</table></div>'.format(
            html.escape(str(sign["sign_id"])), _code_title(sign), picture, cells))
    page = ("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>{title}</title><style>"
            "body{{font-family:sans-serif;margin:1em}} .sign{{display:inline-block;vertical-align:top;"
            "border:1px solid #ccc;margin:.4em;padding:.4em;width:300px}} h2{{font-size:1em;margin:.2em 0}}"
            " table{{font-size:.8em;border-collapse:collapse}} th{{text-align:left;padding-right:.6em}}"
            " td{{word-break:break-all}}</style></head><body><h1>{title}</h1><p>{count} signs</p>{rows}"
            "</body></html>").format(title=html.escape(title), count=len(signs), rows="".join(rows))
    write_text_atomically(path, page)
