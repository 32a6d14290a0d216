"""Equirectangular panorama renderer: ray casting with a z-buffer, per-primitive windows.

The panorama frame and pixel <-> ray mapping are the contract's (``roadsigns.core.geometry``):
pixel centres at +0.5, azimuth 0 at the centre column growing to the right, elevation up.
Sky and ground are cast for every pixel (in row strips); every other primitive only on the
pixel window its bounds project to (seam and poles handled). Output: RGB uint8, a sign mask
(uint16: sign id on a panel's front face, ``id | 0x8000`` on its back, 0 elsewhere) and
per-sign pixel statistics.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple

import cv2
import numpy as np

from . import road as rd
from .primitives import Panel
from .textures import noise_tile


@dataclass(frozen=True)
class Look:
    """The light and the camera of a scene's panoramas: the ranges the sun's elevation (per
    scene) and each image's camera effects (:func:`finish_image`) are drawn from."""

    name: str
    sun_elevation_deg: Tuple[float, float] = (35.0, 60.0)
    gain: Tuple[float, float] = (0.75, 1.3)          # exposure
    white_balance: float = 0.05                      # per channel, +-
    blur_sigma_px: Tuple[float, float] = (0.5, 1.1)
    motion_blur_share: float = 0.3                   # images with a little horizontal blur
    noise_sd: Tuple[float, float] = (1.5, 4.0)       # sensor noise, 8-bit levels
    jpeg_quality: Tuple[int, int] = (75, 94)         # [lo, hi)


#: ``training``: every training and bench scene until now. The others are held-out looks
#: whose every range lies outside the training one (issue 15): scenes rendered with them
#: test whether the detector learned signs or our renderer.
LOOKS = {
    "training": Look("training"),
    # low sun, under-exposed, noisy, strongly compressed
    "dusk": Look("dusk", sun_elevation_deg=(6.0, 15.0), gain=(0.42, 0.62), white_balance=0.12,
                 blur_sigma_px=(1.15, 1.6), motion_blur_share=0.6, noise_sd=(4.5, 8.0), jpeg_quality=(50, 68)),
    # high sun, over-exposed, a colour cast, strongly compressed
    "glare": Look("glare", sun_elevation_deg=(65.0, 80.0), gain=(1.35, 1.75), white_balance=0.12,
                  blur_sigma_px=(0.2, 0.45), motion_blur_share=0.0, noise_sd=(0.5, 1.4), jpeg_quality=(55, 72)),
}

SKY_ZENITH = np.array([0.30, 0.48, 0.80])
SKY_HORIZON = np.array([0.80, 0.86, 0.92])
HAZE = np.array([0.74, 0.78, 0.82])
GROUND_RGB = np.array([
    (0.30, 0.30, 0.31),   # asphalt
    (0.90, 0.90, 0.88),   # marking
    (0.34, 0.33, 0.33),   # parking strip
    (0.66, 0.64, 0.60),   # sidewalk
    (0.74, 0.73, 0.71),   # curb
    (0.30, 0.47, 0.19),   # grass
])
MAX_OBJECT_RANGE_M = 250.0
MAX_WINDOW_PIXELS = 600_000


class PanoramaRenderer:
    """Renders the scene's panoramas; one instance per scene (noise tiles, sun)."""

    def __init__(self, scene, width: int, rng: np.random.Generator, look: Look = LOOKS["training"]):
        self.scene = scene
        self.W, self.H = int(width), int(width) // 2
        self.ground_noise = noise_tile(rng, 256, 2.0)
        self.cloud_noise = noise_tile(rng, 256, 6.0)
        sun_az, sun_el = rng.uniform(0, 2 * np.pi), np.radians(rng.uniform(*look.sun_elevation_deg))
        self.sun = np.array([np.sin(sun_az) * np.cos(sun_el), np.cos(sun_az) * np.cos(sun_el), np.sin(sun_el)])
        u = np.arange(self.W) + 0.5
        v = np.arange(self.H) + 0.5
        alpha = 2 * np.pi * (u / self.W - 0.5)
        eps = np.pi * (0.5 - v / self.H)
        self.ca, self.sa = np.cos(alpha), np.sin(alpha)
        self.ce, self.se = np.cos(eps), np.sin(eps)

    # --- rays ----------------------------------------------------------------------
    def _dirs(self, R, v0, v1, cols):
        """World unit rays (rows, cols, 3) of pixel rows v0:v1 and columns ``cols``."""
        ce, se = self.ce[v0:v1, None], self.se[v0:v1, None]
        ca, sa = self.ca[cols][None, :], self.sa[cols][None, :]
        dx, dy, dz = ce * ca, ce * sa, -se * np.ones_like(ca)
        return dx[..., None] * R[:, 0] + dy[..., None] * R[:, 1] + dz[..., None] * R[:, 2]

    def _window(self, prim, C, R):
        """Pixel rows (v0, v1) and column indices a primitive can cover, or None."""
        W, H = self.W, self.H
        rel = prim.centre - C
        dist = float(np.linalg.norm(rel))
        if dist - prim.radius > MAX_OBJECT_RANGE_M:
            return None
        all_cols = np.arange(W)
        if dist <= prim.radius * 1.01 + 0.05:
            return 0, H, all_cols
        dp = R.T @ rel
        eps_c = np.arcsin(np.clip(-dp[2] / dist, -1, 1))
        half = np.arcsin(min(1.0, prim.radius / dist))
        e_hi, e_lo = eps_c + half, eps_c - half
        v0 = max(0, int(np.floor(H * (0.5 - e_hi / np.pi))) - 1)
        v1 = min(H, int(np.ceil(H * (0.5 - e_lo / np.pi))) + 1)
        if e_hi >= np.pi / 2 - 1e-3 or e_lo <= -np.pi / 2 + 1e-3:
            return v0, v1, all_cols
        cp = (prim.corners() - C) @ R            # corners in the panorama frame
        az = np.arctan2(cp[:, 1], cp[:, 0])
        az_c = np.arctan2(dp[1], dp[0])
        relaz = np.mod(az - az_c + np.pi, 2 * np.pi) - np.pi
        if relaz.max() - relaz.min() >= np.pi:
            return v0, v1, all_cols
        u_lo = int(np.floor(W * ((az_c + relaz.min()) / (2 * np.pi) + 0.5))) - 1
        u_hi = int(np.ceil(W * ((az_c + relaz.max()) / (2 * np.pi) + 0.5))) + 1
        return v0, v1, np.mod(np.arange(u_lo, u_hi + 1), W)

    def _strips(self, v0, v1, ncols):
        step = max(1, MAX_WINDOW_PIXELS // max(ncols, 1))
        for a in range(v0, v1, step):
            yield a, min(v1, a + step)

    # --- shading ---------------------------------------------------------------------
    def _sky(self, D):
        """Sky colours of world rays (n, 3): gradient and clouds on a plane 1 km up."""
        el = np.clip(D[:, 2], 0, 1)
        sky = SKY_HORIZON + (SKY_ZENITH - SKY_HORIZON) * (el[:, None] ** 0.6)
        zc = np.maximum(D[:, 2], 0.02)
        ci = np.mod(D[:, 0] / zc * 33.0, 256).astype(np.int32)
        cj = np.mod(D[:, 1] / zc * 33.0, 256).astype(np.int32)
        fade = np.clip((D[:, 2] - 0.02) * 8, 0, 1)
        cloud = np.clip((self.cloud_noise[cj, ci] - 0.2) * 2.5, 0, 1) * fade
        return sky * (1 - cloud[:, None]) + 0.96 * cloud[:, None]

    def _ground(self, P, t, material, normal):
        """Ground colours at hits (n, 3): material, grain, paving joints, sun, haze."""
        base = GROUND_RGB[material]
        gi = np.mod(P[:, 0] * 8, 256).astype(np.int32)
        gj = np.mod(P[:, 1] * 8, 256).astype(np.int32)
        amp = np.where(material == rd.GRASS, 0.18, 0.06)
        shade = 0.55 + 0.45 * np.clip(normal @ self.sun, 0, 1)
        factor = (1 + amp * self.ground_noise[gj, gi]) * shade
        walk = material == rd.SIDEWALK
        if walk.any():
            s, tl = self.scene.road.st(P[walk, 0], P[walk, 1])
            factor[walk] *= np.where((np.mod(s, 0.5) < 0.03) | (np.mod(tl, 0.5) < 0.03), 0.8, 1.0)
        fog = (1 - np.exp(-t / 350.0))[:, None]
        return base * factor[:, None] * (1 - fog) + HAZE * fog

    # --- main ------------------------------------------------------------------------------
    def render(self, C, R):
        """Render from panorama centre ``C`` (local ENU) with ``R`` = R_world_from_pano.

        Returns ``(rgb_linear float32 HxWx3, mask uint16, sign_stats)``; ``sign_stats`` maps
        a sign id to its amodal pixel window and front/back hit counts.
        """
        W, H = self.W, self.H
        zbuf = np.empty((H, W), np.float32)
        img = np.empty((H, W, 3), np.float32)
        mask = np.zeros((H, W), np.uint16)
        all_cols = np.arange(W)
        gx, gy = self.scene.road.gradient
        for a, b in self._strips(0, H, W):
            D = self._dirs(R, a, b, all_cols).reshape(-1, 3)
            down = D[:, 2] - gx * D[:, 0] - gy * D[:, 1] < 0      # can meet the terrain plane
            t = np.full(len(D), np.inf)
            t[down], material, normal = self.scene.road.intersect(C, D[down])
            hit = np.isfinite(t)
            rgb = np.empty(D.shape, np.float32)
            rgb[~hit] = self._sky(D[~hit])
            hit_d = hit[down]
            th = t[hit]
            rgb[hit] = self._ground(C + th[:, None] * D[hit], th, material[hit_d], normal[hit_d])
            img[a:b] = rgb.reshape(b - a, W, 3)
            zbuf[a:b] = t.reshape(b - a, W)
        stats = {}
        for prim in self.scene.prims:
            win = self._window(prim, C, R)
            if win is None:
                continue
            v0, v1, cols = win
            level = 0
            if isinstance(prim, Panel):
                footprint = np.linalg.norm(prim.centre - C) * 2 * np.pi / W
                texels = prim.levels[0].shape[1] / prim.width
                level = max(0, int(np.floor(np.log2(max(footprint * texels, 1e-9)))))
            for a, b in self._strips(v0, v1, len(cols)):
                D = self._dirs(R, a, b, cols)
                t, aux = prim.intersect(C, D)
                hit = np.isfinite(t)
                if not hit.any():
                    continue
                if prim.sign_id:
                    st = stats.setdefault(prim.sign_id, {"rows": [], "cols": [], "front": 0, "back": 0})
                    front = aux[2] & hit
                    st["front"] += int(front.sum())
                    st["back"] += int((hit & ~front).sum())
                    rr, cc = np.nonzero(hit)
                    st["rows"].append(rr + a)
                    st["cols"].append(cols[cc])
                zsub = zbuf[a:b, cols]
                win_hit = hit & (t < zsub)
                if not win_hit.any():
                    continue
                Dh = D[win_hit]
                th = t[win_hit]
                P = C + th[:, None] * Dh
                rgb, normal, _, maskv = prim.surface(P, Dh, tuple(x[win_hit] for x in aux), level)
                normal = np.where((np.sum(normal * Dh, -1) > 0)[:, None], -normal, normal)
                lit = np.clip(normal @ self.sun, 0, 1)
                retro = getattr(prim, "retroreflective", False)
                rgb = rgb * ((0.85 + 0.15 * lit) if retro else (0.5 + 0.5 * lit))[:, None]
                fog = (1 - np.exp(-th / 350.0))[:, None]
                rgb = rgb * (1 - fog) + HAZE * fog
                zsub[win_hit] = th
                zbuf[a:b, cols] = zsub
                isub = img[a:b, cols]
                isub[win_hit] = rgb
                img[a:b, cols] = isub
                msub = mask[a:b, cols]
                msub[win_hit] = maskv
                mask[a:b, cols] = msub
        return img, mask, stats


def unwrapped_box(rows, cols, width):
    """Pixel box (u0, v0, u1, v1) of pixel indices, unwrapped across the seam (u1 may exceed W)."""
    cols = np.asarray(cols)
    if cols.max() - cols.min() > width // 2:
        cols = np.where(cols < width // 2, cols + width, cols)
    return int(cols.min()), int(np.min(rows)), int(cols.max()) + 1, int(np.max(rows)) + 1


def sign_boxes(mask, stats, width):
    """Per sign seen in an image: amodal box, visible box, pixel counts, facing, occlusion."""
    out = []
    for sign_id, st in sorted(stats.items()):
        rows = np.concatenate(st["rows"])
        cols = np.concatenate(st["cols"])
        facing = "front" if st["front"] >= st["back"] else "back"
        want = sign_id if facing == "front" else sign_id | 0x8000
        amodal = st["front"] if facing == "front" else st["back"]
        vis = mask[rows, cols] == want
        n_vis = int(vis.sum())
        rec = {"sign_id": int(sign_id), "facing": facing, "pixels": int(amodal), "visible_pixels": n_vis,
               "occlusion": round(1.0 - n_vis / max(amodal, 1), 4), "box": list(unwrapped_box(rows, cols, width))}
        rec["visible_box"] = list(unwrapped_box(rows[vis], cols[vis], width)) if n_vis else None
        out.append(rec)
    return out


def finish_image(img_linear, rng, look: Look = LOOKS["training"]):
    """Camera effects (ranges of ``look``): exposure and white balance, blur, sensor noise ->
    uint8 RGB; and a JPEG quality."""
    gain = rng.uniform(*look.gain)
    wb = rng.uniform(1.0 - look.white_balance, 1.0 + look.white_balance, 3).astype(np.float32)
    out = img_linear * np.float32(gain * 255.0) * wb
    sigma = rng.uniform(*look.blur_sigma_px)
    out = cv2.GaussianBlur(out, (0, 0), sigma)
    if rng.random() < look.motion_blur_share:  # a little horizontal motion blur
        k = np.full((1, 3), 1 / 3.0, np.float32)
        out = cv2.filter2D(out, -1, k)
    noise_sd = rng.uniform(*look.noise_sd)
    out += rng.standard_normal(out.shape, dtype=np.float32) * np.float32(noise_sd)
    quality = int(rng.integers(*look.jpeg_quality))
    return np.clip(out, 0, 255).astype(np.uint8), quality, {"gain": round(gain, 4), "blur_sigma_px": round(sigma, 3),
                                                              "noise_sd": round(noise_sd, 3), "jpeg_quality": quality}
