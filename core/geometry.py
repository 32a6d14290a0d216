"""Frames, rotations and the equirectangular pixel <-> ray mapping (docs/formats.md).

Every later stage goes through these functions; they are vectorised (leading axes
broadcast) and take angles in degrees unless the name says ``_rad``.

Conventions (``docs/formats.md``):

* World: target projected CRS, axes East, North, Up (metres).
* Body: x forward, y right, z down. ``R_ned_from_body = Rz(heading) Ry(pitch) Rx(roll)``.
* Panorama frame: same axes as the body; ``R_body_from_pano = Rz(yaw) Ry(pitch) Rx(roll)``
  of the boresight, lever arm ``t_lever_body`` in metres in the body frame.
* ``R_enu_from_ned`` swaps (n, e, d) -> (e, n, -d); heading must already be a grid heading.
* Equirectangular image W x H (W = 2H), continuous pixel coordinates with pixel centres at
  +0.5: azimuth ``alpha = 2 pi (u/W - 0.5)`` (clockwise seen from above, 0 at the centre
  column), elevation ``eps = pi (0.5 - v/H)`` (up positive), ray
  ``d = (cos eps cos alpha, cos eps sin alpha, -sin eps)`` in the panorama frame.
* Quaternions are Hamilton, scalar first ``(w, x, y, z)``.
"""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

#: NED -> ENU axis swap: (n, e, d) -> (e, n, -d). A proper rotation (det = +1).
R_ENU_FROM_NED = np.array([[0.0, 1.0, 0.0],
                           [1.0, 0.0, 0.0],
                           [0.0, 0.0, -1.0]])


def _rot_axis(axis: int, angle_deg) -> np.ndarray:
    """Right-handed rotation matrices about one axis, shape ``angle.shape + (3, 3)``."""
    a = np.radians(np.asarray(angle_deg, dtype=float))
    c, s = np.cos(a), np.sin(a)
    R = np.zeros(a.shape + (3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    R[..., axis, axis] = 1.0
    R[..., i, i] = c
    R[..., j, j] = c
    R[..., i, j] = -s
    R[..., j, i] = s
    return R


def rot_x(angle_deg) -> np.ndarray:
    return _rot_axis(0, angle_deg)


def rot_y(angle_deg) -> np.ndarray:
    return _rot_axis(1, angle_deg)


def rot_z(angle_deg) -> np.ndarray:
    return _rot_axis(2, angle_deg)


def euler_zyx_matrix(roll_deg, pitch_deg, yaw_deg) -> np.ndarray:
    """``Rz(yaw) @ Ry(pitch) @ Rx(roll)``: the attitude and boresight form of docs/formats.md.

    For an INS attitude pass ``yaw_deg = heading_deg``; the result maps body vectors to NED.
    """
    return rot_z(yaw_deg) @ rot_y(pitch_deg) @ rot_x(roll_deg)


def R_ned_from_body(roll_deg, pitch_deg, heading_deg) -> np.ndarray:
    """Body (x fwd, y right, z down) -> local NED, ``Rz(heading) Ry(pitch) Rx(roll)``."""
    return euler_zyx_matrix(roll_deg, pitch_deg, heading_deg)


def R_body_from_pano(boresight_roll_deg, boresight_pitch_deg, boresight_yaw_deg) -> np.ndarray:
    """Panorama frame -> body frame from the boresight angles of the camera mount."""
    return euler_zyx_matrix(boresight_roll_deg, boresight_pitch_deg, boresight_yaw_deg)


def R_world_from_pano(roll_deg, pitch_deg, grid_heading_deg, R_body_from_pano_) -> np.ndarray:
    """Panorama rays -> world ENU: ``R_enu_from_ned @ R_ned_from_body @ R_body_from_pano``."""
    return R_ENU_FROM_NED @ R_ned_from_body(roll_deg, pitch_deg, grid_heading_deg) @ R_body_from_pano_


def pano_centre_world(C_body_world, roll_deg, pitch_deg, grid_heading_deg, t_lever_body) -> np.ndarray:
    """Panorama centre in world ENU: ``C + R_enu_from_ned R_ned_from_body t_lever``."""
    R_wb = R_ENU_FROM_NED @ R_ned_from_body(roll_deg, pitch_deg, grid_heading_deg)
    return np.asarray(C_body_world, float) + (R_wb @ np.asarray(t_lever_body, float)[..., None])[..., 0]


# --- equirectangular pixel <-> ray ----------------------------------------------------

def pixel_to_angles_rad(u, v, width, height):
    """Continuous pixel ``(u, v)`` -> (azimuth, elevation) in radians."""
    alpha = 2.0 * np.pi * (np.asarray(u, float) / width - 0.5)
    eps = np.pi * (0.5 - np.asarray(v, float) / height)
    return alpha, eps


def angles_to_ray(alpha_rad, eps_rad) -> np.ndarray:
    """(azimuth, elevation) in radians -> unit ray in the panorama frame, shape ``(..., 3)``."""
    ce = np.cos(eps_rad)
    return np.stack([ce * np.cos(alpha_rad), ce * np.sin(alpha_rad), -np.sin(eps_rad)], axis=-1)


def pixel_to_ray(u, v, width, height) -> np.ndarray:
    """Continuous pixel ``(u, v)`` -> unit ray ``(..., 3)`` in the panorama frame."""
    return angles_to_ray(*pixel_to_angles_rad(u, v, width, height))


def ray_to_angles_rad(d):
    """Ray(s) ``(..., 3)`` in the panorama frame (any length) -> (azimuth, elevation) radians.

    Azimuth is in [-pi, pi), elevation in [-pi/2, pi/2].
    """
    d = np.asarray(d, float)
    alpha = np.arctan2(d[..., 1], d[..., 0])
    alpha = np.where(alpha >= np.pi, alpha - 2 * np.pi, alpha)
    eps = np.arctan2(-d[..., 2], np.hypot(d[..., 0], d[..., 1]))
    return alpha, eps


def ray_to_pixel(d, width, height):
    """Ray(s) in the panorama frame -> continuous pixel ``(u, v)``, u in [0, W), v in [0, H]."""
    alpha, eps = ray_to_angles_rad(d)
    u = (alpha / (2.0 * np.pi) + 0.5) * width
    u = np.mod(u, width)
    v = (0.5 - eps / np.pi) * height
    return u, v


# --- world <-> panorama ----------------------------------------------------------------

def world_to_pano_ray(X_world, C_pano_world, R_world_from_pano_):
    """World points -> (unit ray in the panorama frame, range in metres).

    ``R_world_from_pano_`` may be one matrix or one per point (broadcast).
    """
    delta = np.asarray(X_world, float) - np.asarray(C_pano_world, float)
    R = np.asarray(R_world_from_pano_, float)
    d = np.einsum("...ji,...j->...i", R, delta)  # R^T @ delta
    rng = np.linalg.norm(d, axis=-1)
    return d / np.where(rng > 0, rng, 1.0)[..., None], rng


def world_to_pixel(X_world, C_pano_world, R_world_from_pano_, width, height):
    """World points -> continuous pixel ``(u, v)`` and range in metres."""
    d, rng = world_to_pano_ray(X_world, C_pano_world, R_world_from_pano_)
    u, v = ray_to_pixel(d, width, height)
    return u, v, rng


def pano_ray_to_world(d_pano, range_m, C_pano_world, R_world_from_pano_) -> np.ndarray:
    """Point at ``range_m`` along panorama-frame ray ``d_pano`` -> world ENU."""
    d = np.asarray(d_pano, float)
    R = np.asarray(R_world_from_pano_, float)
    d_world = np.einsum("...ij,...j->...i", R, d)
    return np.asarray(C_pano_world, float) + np.asarray(range_m, float)[..., None] * d_world


# --- quaternions and azimuths -----------------------------------------------------------

def quat_wxyz_from_matrix(R) -> np.ndarray:
    """Rotation matrices -> Hamilton unit quaternions, scalar first, with ``w >= 0``."""
    q_xyzw = Rotation.from_matrix(np.asarray(R, float).reshape(-1, 3, 3)).as_quat()
    q = np.concatenate([q_xyzw[:, 3:], q_xyzw[:, :3]], axis=1)
    q *= np.where(q[:, :1] < 0, -1.0, 1.0)
    return q.reshape(np.shape(R)[:-2] + (4,))


def matrix_from_quat_wxyz(q) -> np.ndarray:
    """Hamilton quaternions ``(w, x, y, z)`` -> rotation matrices (``v' = q v q*``)."""
    q = np.asarray(q, float)
    flat = q.reshape(-1, 4)
    R = Rotation.from_quat(np.concatenate([flat[:, 1:], flat[:, :1]], axis=1)).as_matrix()
    return R.reshape(q.shape[:-1] + (3, 3))


def azimuth_deg_of_enu(v_enu) -> np.ndarray:
    """Horizontal direction of ENU vectors, degrees clockwise from grid north in [0, 360)."""
    v = np.asarray(v_enu, float)
    return np.mod(np.degrees(np.arctan2(v[..., 0], v[..., 1])), 360.0)


def pano_forward_azimuth_deg(R_world_from_pano_) -> np.ndarray:
    """Azimuth of the panorama's forward axis (its x axis, the centre column) in world."""
    return azimuth_deg_of_enu(np.asarray(R_world_from_pano_)[..., :, 0])


def box_centre_pixel(u0, v0, u1, v1, width):
    """Centre of panorama boxes (detections layer form, u1 may exceed W across the seam), u in [0, W)."""
    return np.mod((np.asarray(u0, float) + np.asarray(u1, float)) / 2.0, width), \
        (np.asarray(v0, float) + np.asarray(v1, float)) / 2.0


def box_centre_ray_world(u0, v0, u1, v1, width, height, q_world_from_pano_wxyz) -> np.ndarray:
    """Unit world ENU ray through the centre of each panorama box."""
    u, v = box_centre_pixel(u0, v0, u1, v1, width)
    d_pano = pixel_to_ray(u, v, width, height)
    R = matrix_from_quat_wxyz(q_world_from_pano_wxyz)
    return np.einsum("...ij,...j->...i", R, d_pano)
