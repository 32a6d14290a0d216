"""The road (a circular arc on a tilted terrain plane) and the vehicle driving it.

Local frame: ENU metres of the projected target CRS, relative to the scene origin.
Road coordinates: ``s`` arc length along the centre line (driving direction of the survey
vehicle), ``t`` lateral offset, positive to the right of that direction. Cross section
(``|t|`` in metres): lanes 0-3.5 (edge line at 3.5), parking strip 3.5-5.5 (asphalt),
raised sidewalk 5.5-7.5 (curbs 0.15 m high on both sides), grass verge beyond.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

LANE_HALF_WIDTH = 3.5
CURB_T = 5.5
SIDEWALK_OUTER_T = 7.5
CURB_HEIGHT = 0.15

# ground materials (codes used by the renderers)
ASPHALT, MARKING, PARKING, SIDEWALK, CURB, GRASS = range(6)


@dataclass
class Road:
    """Circular arc centre line on the terrain plane ``z = z0 + gx x + gy y``."""

    curvature: float            # 1/m, + = left turn (never 0)
    start_angle_rad: float      # tangent direction at s = 0, math angle CCW from east
    gradient: tuple             # (dz/dx, dz/dy) of the terrain plane
    z0: float = 0.0
    crossing_s: tuple = ()      # start s of zebra crossings (4 m long)
    stop_line_s: tuple = ()     # s of stop lines across the right lane

    def __post_init__(self):
        b0 = self.start_angle_rad
        self.radius_signed = 1.0 / self.curvature
        # arc centre: start + left normal * R (signed)
        self.centre_xy = np.array([-np.sin(b0), np.cos(b0)]) * self.radius_signed

    # --- centre line -------------------------------------------------------------
    def tangent_angle(self, s):
        return self.start_angle_rad + self.curvature * np.asarray(s, float)

    def point(self, s, t=0.0):
        """Local (x, y) of road coordinates (s, t)."""
        b = self.tangent_angle(s)
        k = self.radius_signed + np.asarray(t, float)
        return np.stack([self.centre_xy[0] + np.sin(b) * k, self.centre_xy[1] - np.cos(b) * k], -1)

    def grid_azimuth_deg(self, s):
        """Azimuth of the driving direction at s, degrees clockwise from grid north."""
        return np.mod(90.0 - np.degrees(self.tangent_angle(s)), 360.0)

    def st(self, x, y):
        """Road coordinates (s, t) of local points."""
        wx = np.asarray(x, float) - self.centre_xy[0]
        wy = np.asarray(y, float) - self.centre_xy[1]
        sg = np.sign(self.curvature)
        rho = np.hypot(wx, wy)
        b = np.arctan2(sg * wx, -sg * wy)
        db = np.mod(b - self.start_angle_rad + np.pi, 2 * np.pi) - np.pi
        return db / self.curvature, sg * rho - self.radius_signed

    # --- terrain ----------------------------------------------------------------------
    def base_z(self, x, y):
        return self.z0 + self.gradient[0] * np.asarray(x, float) + self.gradient[1] * np.asarray(y, float)

    def ground_z(self, x, y):
        """Height of the ground surface (sidewalk tops included) below local points."""
        _, t = self.st(x, y)
        on_walk = (np.abs(t) >= CURB_T) & (np.abs(t) <= SIDEWALK_OUTER_T)
        return self.base_z(x, y) + np.where(on_walk, CURB_HEIGHT, 0.0)

    # --- ray casting ----------------------------------------------------------------------
    def intersect(self, O, D):
        """Nearest hit of rays with the ground surface (plane, sidewalk tops, curb faces).

        ``O`` (3,) or (..., 3), ``D`` (..., 3) unit. Returns ``t`` (inf = no hit), the material
        code and the unit surface normal at the hit.
        """
        O = np.asarray(O, float)
        Ox, Oy, Oz = O[..., 0], O[..., 1], O[..., 2]
        Dx, Dy, Dz = D[..., 0], D[..., 1], D[..., 2]
        gx, gy = self.gradient
        # height of the ray above the base plane: h(t) = h0 + t * dh
        h0 = Oz - self.base_z(Ox, Oy)
        dh = Dz - gx * Dx - gy * Dy
        with np.errstate(divide="ignore", invalid="ignore"):
            t_base = np.where(dh < 0, -h0 / dh, np.inf)
            t_top = np.where(dh < 0, (CURB_HEIGHT - h0) / dh, np.inf)
        t_base = np.where(t_base > 0, t_base, np.inf)
        t_top = np.where(t_top > 0, t_top, np.inf)
        # base plane only outside the sidewalk band, the top only inside it
        at_base = np.abs(self._t_at(O, D, t_base))
        t_base = np.where((at_base < CURB_T) | (at_base > SIDEWALK_OUTER_T), t_base, np.inf)
        at_top = np.abs(self._t_at(O, D, t_top))
        t_top = np.where((at_top >= CURB_T) & (at_top <= SIDEWALK_OUTER_T), t_top, np.inf)
        best = np.minimum(t_base, t_top)
        material = np.where(t_top < t_base, SIDEWALK, ASPHALT).astype(np.int8)
        # curb faces: vertical cylinders about the arc centre
        cx, cy = self.centre_xy
        px, py = Ox - cx, Oy - cy
        a = Dx * Dx + Dy * Dy
        b = 2 * (px * Dx + py * Dy)
        c0 = px * px + py * py
        curb_t = np.full(best.shape, np.inf)
        for lateral in (-SIDEWALK_OUTER_T, -CURB_T, CURB_T, SIDEWALK_OUTER_T):
            r = abs(self.radius_signed + lateral)
            disc = b * b - 4 * a * (c0 - r * r)
            with np.errstate(invalid="ignore", divide="ignore"):
                sq = np.sqrt(np.maximum(disc, 0))
                for root in ((-b - sq) / (2 * a), (-b + sq) / (2 * a)):
                    h = h0 + root * dh
                    ok = (disc > 0) & (root > 0) & (h >= 0) & (h <= CURB_HEIGHT)
                    curb_t = np.where(ok & (root < curb_t), root, curb_t)
        is_curb = curb_t < best
        best = np.where(is_curb, curb_t, best)
        material = np.where(is_curb, CURB, material)
        P = O + best[..., None] * D
        P = np.where(np.isfinite(best)[..., None], P, 0.0)
        s, t = self.st(P[..., 0], P[..., 1])
        flat = material == ASPHALT
        material = np.where(flat & (np.abs(t) > SIDEWALK_OUTER_T), GRASS, material)
        material = np.where(flat & (np.abs(t) > LANE_HALF_WIDTH) & (np.abs(t) < CURB_T), PARKING, material)
        material = np.where(flat & self._is_marking(s, t), MARKING, material).astype(np.int8)
        up = np.array([-gx, -gy, 1.0]) / np.sqrt(gx * gx + gy * gy + 1.0)
        normal = np.broadcast_to(up, P.shape).copy()
        if is_curb.any():
            radial = np.stack([P[..., 0] - cx, P[..., 1] - cy, np.zeros_like(best)], -1)
            radial /= np.maximum(np.linalg.norm(radial, axis=-1, keepdims=True), 1e-9)
            normal = np.where(is_curb[..., None], radial, normal)
        return best, material, normal

    def _t_at(self, O, D, t):
        x = O[..., 0] + np.where(np.isfinite(t), t, 0) * D[..., 0]
        y = O[..., 1] + np.where(np.isfinite(t), t, 0) * D[..., 1]
        return self.st(x, y)[1]

    def _is_marking(self, s, t):
        """White paint: dashed centre line, edge lines, zebra crossings, stop lines."""
        at = np.abs(t)
        mark = (at < 0.075) & (np.mod(s, 9.0) < 3.0)
        mark |= np.abs(at - (LANE_HALF_WIDTH - 0.1)) < 0.075
        for s0 in self.crossing_s:
            mark |= (s >= s0) & (s <= s0 + 4.0) & (at < LANE_HALF_WIDTH - 0.3) & (np.mod(t, 1.0) < 0.5)
        for s0 in self.stop_line_s:
            mark |= (np.abs(s - s0) < 0.25) & (t > 0.1) & (t < LANE_HALF_WIDTH - 0.2)
        return mark


@dataclass
class Motion:
    """The survey vehicle: smooth speed, lane keeping wander, terrain and body roll.

    ``tau`` is seconds since the start of the drive; poses are of the body (IMU) frame.
    """

    road: Road
    s_start: float
    speed_mps: float
    lane_t: float = 1.75
    imu_height: float = 0.75
    phase: tuple = (0.0, 0.0, 0.0, 0.0)
    speed_amp: float = 0.12
    speed_period_s: float = 17.0
    wander_m: float = 0.15
    wander_wavelength_m: float = 37.0

    def s(self, tau):
        tau = np.asarray(tau, float)
        w = 2 * np.pi / self.speed_period_s
        return self.s_start + self.speed_mps * (tau + self.speed_amp / w * (1 - np.cos(w * tau)))

    def speed(self, tau):
        w = 2 * np.pi / self.speed_period_s
        return self.speed_mps * (1 + self.speed_amp * np.sin(w * np.asarray(tau, float)))

    def tau_of_s(self, s_values):
        """Inverse of :meth:`s` (monotonic) by bisection-free Newton iterations."""
        s_values = np.asarray(s_values, float)
        tau = (s_values - self.s_start) / self.speed_mps
        for _ in range(30):
            tau = tau - (self.s(tau) - s_values) / self.speed(tau)
        return tau

    def lateral(self, s):
        k = 2 * np.pi / self.wander_wavelength_m
        return (self.lane_t + self.wander_m * np.sin(k * s + self.phase[0]),
                self.wander_m * k * np.cos(k * s + self.phase[0]))

    def state(self, tau):
        """Body pose at times ``tau``: local x, y, z (m), roll, pitch, grid heading (deg)."""
        tau = np.asarray(tau, float)
        s = self.s(tau)
        t, dt_ds = self.lateral(s)
        xy = self.road.point(s, t)
        yaw_off = np.degrees(np.arctan2(dt_ds, 1 + self.road.curvature * t))
        heading = np.mod(self.road.grid_azimuth_deg(s) + yaw_off, 360.0)
        hr = np.radians(heading)
        gx, gy = self.road.gradient
        slope_fwd = gx * np.sin(hr) + gy * np.cos(hr)
        slope_right = gx * np.cos(hr) - gy * np.sin(hr)
        v = self.speed(tau)
        roll = (np.degrees(np.arctan(-slope_right)) + 0.4 * v * v * self.road.curvature
                + 0.25 * np.sin(2 * np.pi * 1.3 * tau + self.phase[1]) + 0.1 * np.sin(2 * np.pi * 0.37 * tau))
        pitch = (np.degrees(np.arctan(slope_fwd)) + 0.2 * np.sin(2 * np.pi * 0.9 * tau + self.phase[2])
                 - 0.3 * np.sin(2 * np.pi * tau / self.speed_period_s))
        z = (self.road.base_z(xy[..., 0], xy[..., 1]) + self.imu_height
             + 0.01 * np.sin(2 * np.pi * 1.7 * tau + self.phase[3]))
        return xy[..., 0], xy[..., 1], z, roll, pitch, heading
