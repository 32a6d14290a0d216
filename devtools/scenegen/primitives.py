"""Ray-cast primitives shared by the panorama renderer and the laser scanner.

Every primitive answers ``intersect(O, D) -> (t, aux)`` for ray origins ``O`` ((3,) or
(..., 3)) and unit directions ``D`` (..., 3) in local ENU metres (``t = inf``: miss), then
``surface(P, D, aux)`` for the hits only: albedo RGB in [0, 1], unit normal, LiDAR
reflectance in [0, 1], and the sign-mask value. Bounding sphere and box corners let the
renderers ray-test a primitive only on the pixels / scan window it can cover.
"""
from __future__ import annotations

import numpy as np

UP = np.array([0.0, 0.0, 1.0])


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _hash_noise(P, scale, seed_phase):
    """Cheap smooth 3D pseudo-noise in [-1, 1] (sums of incommensurate sines)."""
    x, y, z = P[..., 0] * scale, P[..., 1] * scale, P[..., 2] * scale
    p = seed_phase
    return (np.sin(1.7 * x + 2.3 * y + p) * np.sin(1.3 * y - 1.9 * z + 2 * p)
            + np.sin(2.9 * z + 0.7 * x - p) * np.sin(2.1 * x - 1.1 * z + 3 * p)) * 0.5


class Primitive:
    """Base: class code, sign id (0 = not a sign panel), material, bounds."""

    class_code = 1
    sign_id = 0
    kind = "object"
    centre: np.ndarray
    radius: float

    def corners(self) -> np.ndarray:
        """Corners (n, 3) of a convex body containing the primitive."""
        c, r = self.centre, self.radius
        return c + r * np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], float)


class Panel(Primitive):
    """Planar textured rectangle (sign panel, billboard, mirror), alpha-cut by its texture.

    ``normal`` is the front face's outward normal; ``right`` points to the viewer's right
    when looking at the front; ``up`` completes it. Texture row 0 = top edge.
    """

    kind = "panel"

    def __init__(self, centre, normal, width, height, levels, back_rgb, front_reflectance,
                 back_reflectance, class_code, sign_id=0, retroreflective=False, back_levels=None):
        self.centre = np.asarray(centre, float)
        n = np.asarray(normal, float)
        self.normal = n / np.linalg.norm(n)
        right = np.cross(-self.normal, UP)
        self.right = right / np.linalg.norm(right)
        self.up = np.cross(self.right, -self.normal)
        self.width, self.height = float(width), float(height)
        self.levels = levels                     # RGBA uint8 pyramid, level 0 first
        self.back_levels = back_levels
        self.alpha0 = levels[0][..., 3] >= 128
        self.back_rgb = np.asarray(back_rgb, float)
        self.front_reflectance, self.back_reflectance = front_reflectance, back_reflectance
        self.retroreflective = retroreflective
        self.class_code, self.sign_id = class_code, sign_id
        self.radius = 0.5 * float(np.hypot(width, height))

    def corner_points(self):
        """Top-left, top-right, bottom-right, bottom-left (seen from the front)."""
        hw, hh = self.width / 2, self.height / 2
        r, u, c = self.right, self.up, self.centre
        return np.array([c - hw * r + hh * u, c + hw * r + hh * u, c + hw * r - hh * u, c - hw * r - hh * u])

    def corners(self):
        return self.corner_points()

    def intersect(self, O, D):
        denom = _dot(D, self.normal)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = _dot(self.centre - O, self.normal) / denom
        t = np.where(np.isfinite(t) & (t > 1e-6), t, np.inf)
        tt = np.where(np.isfinite(t), t, 0.0)
        rel = O + tt[..., None] * D - self.centre
        a = _dot(rel, self.right) / self.width + 0.5
        b = 0.5 - _dot(rel, self.up) / self.height
        inside = (a >= 0) & (a < 1) & (b >= 0) & (b < 1) & np.isfinite(t)
        h, w = self.alpha0.shape
        ia = np.clip((a * w).astype(np.int32), 0, w - 1)
        ib = np.clip((b * h).astype(np.int32), 0, h - 1)
        inside &= self.alpha0[ib, ia]
        t = np.where(inside, t, np.inf)
        return t, (a, b, denom < 0)

    def surface(self, P, D, aux, level=0):
        a, b, front = aux
        levels = self.levels
        tex = levels[min(level, len(levels) - 1)]
        h, w = tex.shape[:2]
        rgb = tex[np.clip((b * h).astype(np.int32), 0, h - 1), np.clip((a * w).astype(np.int32), 0, w - 1), :3] / 255.0
        if self.back_levels is not None:
            back_tex = self.back_levels[min(level, len(self.back_levels) - 1)]
            bh, bw = back_tex.shape[:2]
            back = back_tex[np.clip((b * bh).astype(np.int32), 0, bh - 1),
                            np.clip(((1 - a) * bw).astype(np.int32), 0, bw - 1), :3] / 255.0
        else:
            back = np.broadcast_to(self.back_rgb, rgb.shape)
        rgb = np.where(front[..., None], rgb, back)
        normal = np.where(front[..., None], self.normal, -self.normal)
        refl = np.where(front, self.front_reflectance, self.back_reflectance)
        mask = np.where(front, self.sign_id, self.sign_id | 0x8000) if self.sign_id else np.zeros(a.shape, np.int32)
        return rgb, normal, refl, mask


class Box(Primitive):
    """Oriented box; ``axes`` rows are its unit axes (the third one vertical)."""

    kind = "box"

    def __init__(self, centre, axes, half, rgb, reflectance, class_code, style="plain"):
        self.centre = np.asarray(centre, float)
        self.axes = np.asarray(axes, float)
        self.half = np.asarray(half, float)
        self.rgb = np.asarray(rgb, float)
        self.reflectance, self.class_code, self.style = reflectance, class_code, style
        self.radius = float(np.linalg.norm(self.half))

    def corners(self):
        s = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], float)
        return self.centre + (s * self.half) @ self.axes

    def intersect(self, O, D):
        Ol = (O - self.centre) @ self.axes.T
        Dl = D @ self.axes.T
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / Dl
            t1 = (-self.half - Ol) * inv
            t2 = (self.half - Ol) * inv
        tlo = np.fmin(t1, t2)
        thi = np.fmax(t1, t2)
        tmin = np.nanmax(tlo, axis=-1)
        tmax = np.nanmin(thi, axis=-1)
        hit = (tmax >= tmin) & (tmin > 1e-6)
        face = np.argmax(np.nan_to_num(tlo, nan=-np.inf), axis=-1)
        return np.where(hit, tmin, np.inf), (face,)

    def surface(self, P, D, aux, level=0):
        (face,) = aux
        Dl = D @ self.axes.T
        sign = -np.sign(np.take_along_axis(Dl, face[..., None], -1))[..., 0]
        normal = self.axes[face] * sign[..., None]
        rgb = np.broadcast_to(self.rgb, P.shape).copy()
        local = (P - self.centre) @ self.axes.T
        if self.style == "building":
            # windows: dark glass in a grid on the walls, none on the roof
            wall = face != 2
            along = np.where(face == 0, local[..., 1], local[..., 0])
            floor_z = local[..., 2] + self.half[2]
            win = (wall & (np.mod(along, 3.0) > 1.0) & (np.mod(along, 3.0) < 2.2)
                   & (np.mod(floor_z, 3.2) > 1.0) & (np.mod(floor_z, 3.2) < 2.5) & (floor_z > 1.0))
            rgb[win] = (0.22, 0.27, 0.33)
        elif self.style == "car_cabin":
            rgb[(face != 2) & (local[..., 2] > -0.8 * self.half[2])] = (0.12, 0.14, 0.17)   # windows
        return rgb, normal, np.full(P.shape[:-1], self.reflectance), np.zeros(P.shape[:-1], np.int32)


class Cylinder(Primitive):
    """Vertical cylinder (pole, trunk, bin) from ``z0`` to ``z1`` with a top cap."""

    kind = "cylinder"

    def __init__(self, base_xy, radius, z0, z1, rgb, reflectance, class_code):
        self.base_xy = np.asarray(base_xy, float)
        self.r, self.z0, self.z1 = float(radius), float(z0), float(z1)
        self.centre = np.array([*self.base_xy, 0.5 * (z0 + z1)])
        self.radius = float(np.hypot(radius, 0.5 * (z1 - z0)))
        self.rgb = np.asarray(rgb, float)
        self.reflectance, self.class_code = reflectance, class_code

    def corners(self):
        r = self.r
        return np.array([[self.base_xy[0] + i * r, self.base_xy[1] + j * r, z]
                         for i in (-1, 1) for j in (-1, 1) for z in (self.z0, self.z1)])

    def intersect(self, O, D):
        px, py = O[..., 0] - self.base_xy[0], O[..., 1] - self.base_xy[1]
        a = D[..., 0] ** 2 + D[..., 1] ** 2
        b = px * D[..., 0] + py * D[..., 1]
        c = px * px + py * py - self.r * self.r
        disc = b * b - a * c
        with np.errstate(invalid="ignore", divide="ignore"):
            t = (-b - np.sqrt(disc)) / a
            z = O[..., 2] + t * D[..., 2]
            side = (disc > 0) & (t > 1e-6) & (z >= self.z0) & (z <= self.z1)
            tcap = (self.z1 - O[..., 2]) / D[..., 2]
            cx = px + tcap * D[..., 0]
            cy = py + tcap * D[..., 1]
            cap = (tcap > 1e-6) & (cx * cx + cy * cy <= self.r * self.r) & (D[..., 2] < 0)
        t = np.where(side, t, np.inf)
        t = np.where(cap & ~(t < tcap), tcap, t)
        return t, ()

    def surface(self, P, D, aux, level=0):
        radial = np.stack([P[..., 0] - self.base_xy[0], P[..., 1] - self.base_xy[1], np.zeros(P.shape[:-1])], -1)
        on_cap = P[..., 2] >= self.z1 - 1e-6
        normal = np.where(on_cap[..., None], UP, radial / self.r)
        rgb = np.broadcast_to(self.rgb, P.shape)
        return rgb, normal, np.full(P.shape[:-1], self.reflectance), np.zeros(P.shape[:-1], np.int32)


class Crown(Primitive):
    """Tree crown: a sphere of foliage with gaps (rays pass where the leaf noise is high)."""

    kind = "crown"

    def __init__(self, centre, radius, rgb, reflectance, class_code, phase, gap_threshold=0.45):
        self.centre = np.asarray(centre, float)
        self.radius = float(radius)
        self.rgb = np.asarray(rgb, float)
        self.reflectance, self.class_code = reflectance, class_code
        self.phase, self.gap_threshold = float(phase), gap_threshold

    def intersect(self, O, D):
        oc = O - self.centre
        b = _dot(D, oc) if oc.ndim == D.ndim else D @ oc
        c = _dot(oc, oc) - self.radius ** 2
        disc = b * b - c
        sq = np.sqrt(np.maximum(disc, 0))
        t_best = np.full(D.shape[:-1], np.inf)
        # entry, then an inner shell (half radius), then exit: leaves with gaps on each
        for frac_r, sgn in ((1.0, -1), (0.55, -1), (1.0, 1)):
            if frac_r == 1.0:
                tc = -b + sgn * sq
                ok = disc > 0
            else:
                c2 = _dot(oc, oc) - (frac_r * self.radius) ** 2
                d2 = b * b - c2
                tc = -b - np.sqrt(np.maximum(d2, 0))
                ok = d2 > 0
            P = O + np.where(ok, tc, 0)[..., None] * D
            leaf = _hash_noise(P, 2.5, self.phase) < self.gap_threshold
            ok &= leaf & (tc > 1e-6) & ~np.isfinite(t_best)
            t_best = np.where(ok, tc, t_best)
        return t_best, ()

    def surface(self, P, D, aux, level=0):
        normal = (P - self.centre) / self.radius
        shade = 0.8 + 0.35 * _hash_noise(P, 9.0, self.phase)[..., None]
        rgb = np.clip(self.rgb * shade, 0, 1)
        return rgb, normal, np.full(P.shape[:-1], self.reflectance), np.zeros(P.shape[:-1], np.int32)
