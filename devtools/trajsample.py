"""A small analytic drive for tests and the demo: trajectory CSV/SBET, image times, poses,
panorama files, and the exact truth to check the import against.

The vehicle drives an arc of constant curvature in the world CRS (EPSG:32633, placed
2.5 deg east of the central meridian at 48 deg N, so that the meridian convergence is
about +1.86 deg) with gentle roll and pitch oscillations. Heading in the files is TRUE
heading: grid heading + convergence. Truth is evaluated analytically at the image times.
"""
from __future__ import annotations

import csv
import os
from dataclasses import dataclass

import numpy as np
from pyproj import CRS, Proj, Transformer

WORLD_CRS = "EPSG:32633"
GEOGRAPHIC_CRS = "EPSG:4326"
START_LONLAT = (17.5, 48.0)


@dataclass
class Drive:
    """Analytic drive: state at any time ``t`` (s) in the world CRS."""
    start_time_s: float = 1000.0
    duration_s: float = 12.0
    speed_m_s: float = 10.0
    radius_m: float = 150.0
    initial_grid_heading_deg: float = 60.0
    altitude_m: float = 230.0
    climb_m_s: float = 0.3

    def __post_init__(self):
        to_world = Transformer.from_crs(GEOGRAPHIC_CRS, WORLD_CRS, always_xy=True)
        self.e0, self.n0 = to_world.transform(*START_LONLAT)

    def state(self, t):
        """(E, N, U, roll_deg, pitch_deg, grid_heading_deg) of the body at times ``t``."""
        s = self.speed_m_s * (np.asarray(t, float) - self.start_time_s)
        h0 = np.radians(self.initial_grid_heading_deg)
        turn = s / self.radius_m  # turning right: heading grows
        heading = h0 + turn
        # integrate (sin h, cos h) along the arc analytically (E = sin, N = cos of heading)
        e = self.e0 + self.radius_m * (np.cos(h0) - np.cos(heading))
        n = self.n0 + self.radius_m * (np.sin(heading) - np.sin(h0))
        u = self.altitude_m + self.climb_m_s * (np.asarray(t, float) - self.start_time_s)
        tau = np.asarray(t, float) - self.start_time_s
        roll = 1.5 * np.sin(2 * np.pi * 0.3 * tau) + 0.8
        pitch = 1.0 * np.cos(2 * np.pi * 0.2 * tau) - 0.5
        return e, n, u, roll, pitch, np.mod(np.degrees(heading), 360.0)

    def convergence_deg(self, e, n):
        lon, lat = Transformer.from_crs(WORLD_CRS, GEOGRAPHIC_CRS, always_xy=True).transform(e, n)
        return np.asarray(Proj(CRS(WORLD_CRS)).get_factors(lon, lat).meridian_convergence)

    def samples(self, rate_hz=100.0):
        t = self.start_time_s + np.arange(int(self.duration_s * rate_hz) + 1) / rate_hz
        e, n, u, roll, pitch, grid = self.state(t)
        true_heading = np.mod(grid + self.convergence_deg(e, n), 360.0)
        return t, e, n, u, roll, pitch, true_heading


def _lonlat(e, n):
    return Transformer.from_crs(WORLD_CRS, GEOGRAPHIC_CRS, always_xy=True).transform(e, n)


def write_trajectory_csv(path, drive: Drive, crs="projected", rate_hz=100.0, delimiter=","):
    t, e, n, u, roll, pitch, heading = drive.samples(rate_hz)
    x, y = (e, n) if crs == "projected" else _lonlat(e, n)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, delimiter=delimiter)
        w.writerow(["time", "x", "y", "z", "roll", "pitch", "heading", "quality"])
        for row in zip(t, x, y, u, roll, pitch, heading):
            w.writerow(["{:.6f}".format(row[0])] + ["{:.10f}".format(v) for v in row[1:]] + ["1"])
    return path


def write_sbet(path, drive: Drive, rate_hz=200.0, wander_deg=17.0):
    t, e, n, u, roll, pitch, heading = drive.samples(rate_hz)
    lon, lat = _lonlat(e, n)
    rec = np.zeros((len(t), 17))
    rec[:, 0] = t
    rec[:, 1] = np.radians(lat)
    rec[:, 2] = np.radians(lon)
    rec[:, 3] = u
    rec[:, 7] = np.radians(roll)
    rec[:, 8] = np.radians(pitch)
    rec[:, 9] = np.radians(heading + wander_deg)  # platform heading = true + wander
    rec[:, 10] = np.radians(wander_deg)
    rec.astype("<f8").tofile(path)
    return path


def image_times(drive: Drive, spacing_m=5.0):
    """Exposure times about every ``spacing_m``, strictly inside the drive."""
    step = spacing_m / drive.speed_m_s
    return drive.start_time_s + 0.013 + np.arange(0.2, drive.duration_s - 0.2, step)


def write_images(folder, names, width_px=64, fmt="JPEG"):
    from PIL import Image
    os.makedirs(folder, exist_ok=True)
    for k, name in enumerate(names):
        Image.new("RGB", (width_px, width_px // 2), (40 + k % 200, 120, 200)).save(
            os.path.join(folder, name), fmt)


def write_image_times(path, names, times):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["image", "time"])
        for name, t in zip(names, times):
            w.writerow([name, "{:.6f}".format(t)])
    return path


def write_poses(path, drive: Drive, names, times, crs="projected", with_time=True):
    e, n, u, roll, pitch, grid = drive.state(times)
    heading = np.mod(grid + drive.convergence_deg(e, n), 360.0)
    x, y = (e, n) if crs == "projected" else _lonlat(e, n)
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["image", "x", "y", "z", "roll", "pitch", "heading"] + (["time"] if with_time else []))
        for k, name in enumerate(names):
            row = [name] + ["{:.10f}".format(v) for v in (x[k], y[k], u[k], roll[k], pitch[k], heading[k])]
            w.writerow(row + (["{:.6f}".format(times[k])] if with_time else []))
    return path


def make_sample(folder, drive: Drive = None, width_px=64, crs="projected"):
    """Write a complete small sample into ``folder``; returns a dict of paths and the drive."""
    drive = drive or Drive()
    times = image_times(drive)
    names = ["pano_{:04d}.jpg".format(k) for k in range(len(times))]
    images = os.path.join(folder, "images")
    write_images(images, names, width_px)
    return {
        "drive": drive, "names": names, "times": times, "images": images,
        "trajectory_csv": write_trajectory_csv(os.path.join(folder, "trajectory.csv"), drive, crs),
        "trajectory_crs": WORLD_CRS if crs == "projected" else GEOGRAPHIC_CRS,
        "sbet": write_sbet(os.path.join(folder, "trajectory.out"), drive),
        "image_times": write_image_times(os.path.join(folder, "image_times.csv"), names, times),
        "poses": write_poses(os.path.join(folder, "poses.csv"), drive, names, times, crs),
    }
