"""Simulated profiling laser scanner on the survey vehicle, written to LAZ in chunks.

The scanner turns a mirror about its own x axis; its rays ``(0, sin th, -cos th)`` (scanner
frame, body-like axes: th = 0 up, 90 deg right, 180 deg down) sweep one profile per line.
Mounted yawed by -45 deg, its plane runs forward-right / back-left, so sign faces looking
back along the road are swept across instead of being edge-on. Every ray is cast against
the same ground and primitives as the panoramas: occlusion and range-dependent density come
out on their own. Each return carries range noise, an intensity from the material's
reflectance, its true class and its exact time.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import laspy
import numpy as np
import pyproj

from .layout import CLASS_CODES, REFLECTANCE

GROUND_REFLECTANCE = np.array([REFLECTANCE[k] for k in ("asphalt", "marking", "parking", "sidewalk", "curb", "grass")])


@dataclass(frozen=True)
class ScannerMount:
    """Scanner rates, accuracy and mounting on the body (x fwd, y right, z down)."""

    lines_per_s: float = 250.0
    points_per_line: int = 1500
    lever_arm_body_m: tuple = (-0.8, 0.0, -2.0)
    mount_roll_deg: float = 0.0
    mount_pitch_deg: float = 0.0
    mount_yaw_deg: float = -45.0
    range_noise_sd_m: float = 0.015
    min_range_m: float = 1.5
    max_range_m: float = 120.0

    def as_dict(self):
        return asdict(self)


class LazWriter:
    """Chunked LAS 1.4 / point format 6 writer (LAZ through lazrs) with the target CRS's WKT."""

    def __init__(self, path, origin_xyz, crs: str):
        header = laspy.LasHeader(point_format=6, version="1.4")
        header.scales = np.array([0.001, 0.001, 0.001])
        header.offsets = np.floor(np.asarray(origin_xyz, float) / 1000.0) * 1000.0
        header.add_crs(pyproj.CRS.from_user_input(crs))
        header.system_identifier = "roadsigns scenegen"
        header.generating_software = "devtools.scenegen"
        self.header = header
        self._writer = laspy.open(str(path), mode="w", header=header, do_compress=str(path).endswith(".laz"))
        self.count = 0

    def write(self, xyz, intensity, classification, gps_time, scan_angle):
        rec = laspy.ScaleAwarePointRecord.zeros(len(xyz), header=self.header)
        rec.x, rec.y, rec.z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
        rec.intensity = intensity
        rec.classification = classification
        rec.gps_time = gps_time
        rec.scan_angle = scan_angle
        rec.return_number = np.ones(len(xyz), np.uint8)
        rec.number_of_returns = np.ones(len(xyz), np.uint8)
        rec.point_source_id = np.ones(len(xyz), np.uint16)
        self._writer.write_points(rec)
        self.count += len(xyz)

    def close(self):
        self._writer.close()


def _scan_window(prim, S, R_ws, n_steps, margin=0.05):
    """Lines (slice) and mirror steps (indices) of a chunk whose rays can reach ``prim``."""
    rel = prim.centre - S                                   # (L, 3)
    q = np.einsum("lji,lj->li", R_ws, rel)                  # in the scanner frames
    near = np.abs(q[:, 0]) <= prim.radius + margin
    if not near.any():
        return None
    idx = np.nonzero(near)[0]
    l0, l1 = idx[0], idx[-1] + 1
    q = q[l0:l1]
    rho = np.hypot(q[:, 1], q[:, 2])
    if (rho <= prim.radius * 1.01).any():
        return slice(l0, l1), np.arange(n_steps)
    th = np.unwrap(np.arctan2(q[:, 1], -q[:, 2]))
    half = np.arcsin(np.clip(prim.radius / rho, 0, 1))
    lo, hi = (th - half).min(), (th + half).max()
    if hi - lo >= 2 * np.pi:
        return slice(l0, l1), np.arange(n_steps)
    step = 2 * np.pi / n_steps
    return slice(l0, l1), np.mod(np.arange(int(np.floor(lo / step)) - 1, int(np.ceil(hi / step)) + 2), n_steps)


def scan(scene, pose_fn, tau_start, tau_end, mount: ScannerMount, rng, writer, origin, time_offset,
         lines_per_chunk=400, geometry=None, progress=None):
    """Cast the scanner from ``tau_start`` to ``tau_end`` and write returns to ``writer``.

    ``pose_fn(tau) -> (C_body (n,3) local, R_world_from_body (n,3,3))``; ``origin`` is added
    to write world coordinates; ``gps_time = time_offset + tau``. Returns stats.
    """
    g = geometry
    N = int(mount.points_per_line)
    f = float(mount.lines_per_s)
    th = 2 * np.pi * np.arange(N) / N
    d_scan = np.stack([np.zeros(N), np.sin(th), -np.cos(th)], -1)     # (N, 3)
    R_bs = g.euler_zyx_matrix(mount.mount_roll_deg, mount.mount_pitch_deg, mount.mount_yaw_deg)
    lever = np.asarray(mount.lever_arm_body_m, float)
    scan_angle = np.round((np.degrees(th) - 180.0) / 0.006).astype(np.int16)
    n_lines = int(np.floor((tau_end - tau_start) * f))
    centres = np.array([p.centre for p in scene.prims])
    radii = np.array([p.radius for p in scene.prims])
    frac = (np.arange(N) / N)[None, :, None]
    n_written = 0
    by_class = {}
    for c0 in range(0, n_lines, lines_per_chunk):
        c1 = min(n_lines, c0 + lines_per_chunk)
        tau_l = tau_start + np.arange(c0, c1 + 1) / f                   # line starts (+1 end)
        C_b, R_wb = pose_fn(tau_l)
        S = C_b + np.einsum("lij,j->li", R_wb, lever)                  # scanner centres
        tau_mid = tau_l[:-1] + 0.5 / f
        _, R_wb_mid = pose_fn(tau_mid)
        R_ws = R_wb_mid @ R_bs                                          # (L, 3, 3)
        O = S[:-1, None, :] + frac * (S[1:] - S[:-1])[:, None, :]       # (L, N, 3) moving origin
        S = S[:-1]
        D = np.einsum("lij,nj->lni", R_ws, d_scan)
        t_best, material, normal = scene.road.intersect(O, D)
        cls = np.full(t_best.shape, CLASS_CODES["ground"], np.uint8)
        refl = GROUND_REFLECTANCE[material]
        cos_inc = np.abs(np.sum(normal * D, -1))
        retro = np.zeros(t_best.shape, bool)
        # cull primitives outside the slab swept by this chunk's scan planes and range
        n_first, n_last = R_ws[0][:, 0], R_ws[-1][:, 0]
        ahead = (centres - S[0]) @ n_first >= -radii - 0.1
        behind = (centres - S[-1]) @ n_last <= radii + 0.1
        in_range = (np.linalg.norm(centres - S[len(S) // 2], axis=1)
                    <= mount.max_range_m + radii + np.linalg.norm(S[-1] - S[0]))
        for i in np.nonzero(ahead & behind & in_range)[0]:
            prim = scene.prims[i]
            win = _scan_window(prim, S, R_ws, N)
            if win is None:
                continue
            ls, ks = win
            Ow, Dw = O[ls][:, ks], D[ls][:, ks]
            t, aux = prim.intersect(Ow, Dw)
            tb = t_best[ls][:, ks]
            closer = t < tb
            if not closer.any():
                continue
            Dh = Dw[closer]
            Ph = Ow[closer] + t[closer][:, None] * Dh
            _, nrm, rf, _ = prim.surface(Ph, Dh, tuple(a[closer] for a in aux))
            _assign(t_best, ls, ks, closer, t[closer])
            _assign(cls, ls, ks, closer, prim.class_code)
            _assign(refl, ls, ks, closer, rf)
            _assign(cos_inc, ls, ks, closer, np.abs(np.sum(nrm * Dh, -1)))
            is_retro = bool(getattr(prim, "retroreflective", False)) & (rf > 0.5)
            _assign(retro, ls, ks, closer, is_retro)
        ok = (t_best >= mount.min_range_m) & (t_best <= mount.max_range_m)
        n = int(ok.sum())
        if n == 0:
            continue
        rng_m = t_best[ok] + rng.normal(0.0, mount.range_noise_sd_m, n)
        xyz = O[ok] + rng_m[:, None] * D[ok] + origin
        inc = np.where(retro[ok], 1.0, 0.3 + 0.7 * cos_inc[ok])
        inten = refl[ok] * inc * (1.0 - 0.25 * rng_m / mount.max_range_m) * (1.0 + 0.06 * rng.standard_normal(n))
        intensity = np.clip(np.round(inten * 65535.0), 0, 65535).astype(np.uint16)
        tau_pt = (tau_l[:-1, None] + np.arange(N)[None, :] / (N * f))[ok]
        classes = cls[ok]
        writer.write(xyz, intensity, classes, time_offset + tau_pt, np.broadcast_to(scan_angle, ok.shape)[ok])
        n_written += n
        for code, cnt in zip(*np.unique(classes, return_counts=True)):
            by_class[int(code)] = by_class.get(int(code), 0) + int(cnt)
        if progress:
            progress(c1 / max(n_lines, 1))
    return {"lines": n_lines, "rays": n_lines * N, "points": n_written, "points_by_class": by_class}


def _assign(arr, ls, ks, where, values):
    """``arr[ls][:, ks][where] = values`` written back into ``arr``."""
    sub = arr[ls][:, ks]
    sub[where] = values
    arr[ls, ks] = sub
