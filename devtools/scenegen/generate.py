"""Orchestration: lay out a scene, drive it, write every file of a scene folder.

Files (``shared/CONTRACT.md``): ``trajectory.csv`` (100 Hz body poses, true heading, in the
trajectory CRS), ``trajectory.out`` (SBET), ``image_times.csv``, ``poses.csv``,
``images/*.jpg``, ``masks/*.png`` (sign ids, uint16, optional), ``cloud.laz`` (EPSG:32633),
``reference_signs.csv`` and ``reference_poles.csv`` (EPSG:32633) and ``scene.json``.
"""
from __future__ import annotations

import csv
import json
import os
import time

import cv2
import numpy as np
import pyproj

from .. import forked_map
from . import roadsigns_geometry
from . import textures as tx
from .layout import CLASS_CODES, REFLECTANCE, build_scene
from .lidar import LazWriter, ScannerMount, scan
from .presets import get_preset
from .render import LOOKS, PanoramaRenderer, finish_image, sign_boxes
from .road import Motion

TARGET_CRS = "EPSG:32633"
GEOGRAPHIC_CRS = "EPSG:4326"
ORIGIN_LONLAT = (16.9, 48.2)          # 1.9 deg east of zone 33's central meridian: gamma ~ +1.42 deg
ORIGIN_HEIGHT_M = 230.0               # ellipsoidal height of the terrain plane at the origin
GPS_TIME_START = 388800.0             # GPS seconds of week at tau = 0
TRAJECTORY_RATE_HZ = 100.0
LEVER_ARM_BODY_M = (0.3, 0.0, -1.9)
BORESIGHT_DEG = (0.2, -0.3, 0.5)      # roll, pitch, yaw
WANDER_RAD = (0.35, 0.002)            # wander angle = a + b * tau (nonzero, drifting)
STREAMS = {"layout": 0, "motion": 1, "render": 2, "lidar": 3, "images": 4, "images_jitter": 5}


def _rng(seed, stream, *extra):
    return np.random.default_rng([int(seed), STREAMS[stream], *extra])


class _Frames:
    """Local ENU <-> world (EPSG:32633) <-> geographic, and meridian convergence."""

    def __init__(self):
        self.to_utm = pyproj.Transformer.from_crs(GEOGRAPHIC_CRS, TARGET_CRS, always_xy=True)
        self.to_geo = pyproj.Transformer.from_crs(TARGET_CRS, GEOGRAPHIC_CRS, always_xy=True)
        e, n = self.to_utm.transform(*ORIGIN_LONLAT)
        self.origin = np.array([round(e), round(n), ORIGIN_HEIGHT_M])
        self.proj = pyproj.Proj(TARGET_CRS)

    def lonlat(self, x_world, y_world):
        return self.to_geo.transform(np.asarray(x_world, float), np.asarray(y_world, float))

    def convergence_deg(self, x_world, y_world):
        lon, lat = self.lonlat(x_world, y_world)
        return np.asarray(self.proj.get_factors(lon, lat).meridian_convergence, float)


def _write_csv(path, header, columns, formats):
    rows = zip(*[[fmt % v if not isinstance(v, str) else v for v in col] for col, fmt in zip(columns, formats)])
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def _pose_columns(frames, traj_geographic, state):
    """World/trajectory-CRS columns and true heading for body states (local ENU)."""
    x, y, z, roll, pitch, grid_heading = state
    X = x + frames.origin[0]
    Y = y + frames.origin[1]
    Z = z + frames.origin[2]
    gamma = frames.convergence_deg(X, Y)
    true_heading = np.mod(grid_heading + gamma, 360.0)
    if traj_geographic:
        lon, lat = frames.lonlat(X, Y)
        cols, fmts = [lon, lat, Z], ["%.10f", "%.10f", "%.4f"]
    else:
        cols, fmts = [X, Y, Z], ["%.4f", "%.4f", "%.4f"]
    return cols + [roll, pitch, true_heading], fmts + ["%.6f"] * 3, gamma


def _write_sbet(path, frames, motion, tau):
    """Applanix SBET: 17 little-endian float64 per record, angles in radians.

    Fields: time, latitude, longitude, ellipsoidal height, x/y/z velocity, roll, pitch,
    platform heading, wander angle, x/y/z acceleration, x/y/z angular rate. Platform heading
    = true heading + wander angle, i.e. the wander frame's x axis points at true azimuth
    -wander; velocities are in that frame (z down). Accelerations and angular rates are finite
    differences (of the wander-frame velocity and of roll, pitch, heading), for completeness.
    """
    x, y, z, roll, pitch, grid_heading = motion.state(tau)
    X, Y = x + frames.origin[0], y + frames.origin[1]
    lon, lat = frames.lonlat(X, Y)
    gamma = frames.convergence_deg(X, Y)
    true_heading = np.radians(np.mod(grid_heading + gamma, 360.0))
    wander = WANDER_RAD[0] + WANDER_RAD[1] * tau
    platform = np.mod(true_heading + wander + np.pi, 2 * np.pi) - np.pi
    dt = np.gradient(tau)
    v_e, v_n, v_u = np.gradient(x) / dt, np.gradient(y) / dt, np.gradient(z) / dt
    # rotate the grid ENU velocity into true north, then into the wander frame
    g = np.radians(gamma)
    v_true_n = v_n * np.cos(g) - v_e * np.sin(g)
    v_true_e = v_n * np.sin(g) + v_e * np.cos(g)
    vx = v_true_n * np.cos(wander) - v_true_e * np.sin(wander)
    vy = v_true_n * np.sin(wander) + v_true_e * np.cos(wander)
    vz = -v_u
    acc = [np.gradient(v, tau) for v in (vx, vy, vz)]
    rates = [np.gradient(np.unwrap(np.radians(a)), tau) for a in (roll, pitch, grid_heading)]
    rec = np.stack([GPS_TIME_START + tau, np.radians(lat), np.radians(lon), z + frames.origin[2], vx, vy, vz,
                    np.radians(roll), np.radians(pitch), platform, wander, *acc, *rates], 1)
    rec.astype("<f8").tofile(path)


#: The renderer and the panoramas' poses (:func:`render_panorama`'s keys), shared with the
#: forked workers of :func:`generate_scene` and of :func:`.drive.generate_drive`
PANORAMAS: dict = {}


def render_panorama(i: int):
    """Render and write panorama ``i`` of :data:`PANORAMAS` (``renderer``, ``names``,
    ``C_pano``, ``R_wp``, ``tau_img``, ``seed``, ``look``, ``images``, ``masks`` (a folder or
    None), ``width``, ``origin``, ``centres``); returns its image metadata. The image is
    written under a temporary name, then renamed: a drive resumed after a stop never reads
    half an image."""
    r = PANORAMAS
    name, C = r["names"][i], r["C_pano"][i]
    img, mask, stats = r["renderer"].render(C, r["R_wp"][i])
    rgb, quality, camera = finish_image(img, _rng(r["seed"], "images", i), r["look"])
    tmp = os.path.join(r["images"], "." + name + ".tmp.jpg")
    cv2.imwrite(tmp, cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), [cv2.IMWRITE_JPEG_QUALITY, quality])
    os.replace(tmp, os.path.join(r["images"], name))
    if r["masks"]:
        cv2.imwrite(os.path.join(r["masks"], name.replace(".jpg", ".png")), mask)
    boxes = sign_boxes(mask, stats, r["width"])
    for b in boxes:
        b["range_m"] = round(float(np.linalg.norm(r["centres"][b["sign_id"]] - C)), 3)
    return {"image": name, "time": round(GPS_TIME_START + float(r["tau_img"][i]), 6),
            "pano_centre": [round(float(v), 4) for v in C + r["origin"]], "camera": camera, "signs": boxes}


def generate_scene(preset="tiny", seed=1, out_dir="scene", crs="projected", panoramas=True, lidar=True,
                   pano_width=None, masks=True, verbose=False, image_spacing_m=None, look="training",
                   jobs=1):
    """Write one synthetic scene into ``out_dir``; returns a dict of the written paths.

    ``jobs`` > 1: the panoramas are rendered by that many forked processes; each panorama
    draws from its own random stream, so the files are the same as with one.

    ``look``: the light and camera of the panoramas, a name of :data:`.render.LOOKS`
    (``training`` for every training and bench scene; the others are held out).

    ``crs``: ``projected`` (trajectory, poses in EPSG:32633) or ``geographic`` (EPSG:4326 lon/lat,
    ellipsoidal height). The world (cloud, reference signs) is always EPSG:32633. Same
    ``seed`` and options give the same files.
    """
    if crs not in ("projected", "geographic"):
        raise ValueError("crs must be 'projected' or 'geographic'")
    p = get_preset(preset, pano_width=pano_width, image_spacing_m=image_spacing_m)
    if look not in LOOKS:
        raise ValueError(f"unknown look {look!r}; choose one of {sorted(LOOKS)}")
    g = roadsigns_geometry()
    os.makedirs(out_dir, exist_ok=True)
    timings = {}
    clock = time.perf_counter()

    def lap(name):
        nonlocal clock
        now = time.perf_counter()
        timings[name] = round(now - clock, 3)
        clock = now
        if verbose:
            print(f"[scenegen] {name}: {timings[name]:.1f} s", flush=True)

    frames = _Frames()
    scene = build_scene(p, _rng(seed, "layout"))
    mrng = _rng(seed, "motion")
    motion = Motion(scene.road, s_start=-p.lead_in_m, speed_mps=p.speed_mps, phase=tuple(mrng.uniform(0, 2 * np.pi, 4)))
    tau_end = float(motion.tau_of_s(p.road_length_m + p.lead_in_m))
    geographic = crs == "geographic"
    traj_crs = GEOGRAPHIC_CRS if geographic else TARGET_CRS
    paths = {"scene_json": os.path.join(out_dir, "scene.json")}

    # --- trajectory, SBET --------------------------------------------------------------
    tau_traj = np.arange(int(np.floor(tau_end * TRAJECTORY_RATE_HZ)) + 1) / TRAJECTORY_RATE_HZ
    cols, fmts, _ = _pose_columns(frames, geographic, motion.state(tau_traj))
    paths["trajectory"] = os.path.join(out_dir, "trajectory.csv")
    _write_csv(paths["trajectory"], ["time", "x", "y", "z", "roll", "pitch", "heading"],
               [GPS_TIME_START + tau_traj] + cols, ["%.6f"] + fmts)
    paths["sbet"] = os.path.join(out_dir, "trajectory.out")
    _write_sbet(paths["sbet"], frames, motion, tau_traj)

    # --- image exposures: one every ~spacing metres, not on the 100 Hz grid ---------------
    s_img = np.arange(0.0, p.road_length_m + 1e-9, p.image_spacing_m)
    s_img = s_img + _rng(seed, "images_jitter").uniform(-0.3, 0.3, len(s_img))
    tau_img = np.round(motion.tau_of_s(s_img), 6)
    names = [f"pano_{i:05d}.jpg" for i in range(len(tau_img))]
    img_state = motion.state(tau_img)
    cols, fmts, gamma_img = _pose_columns(frames, geographic, img_state)
    paths["image_times"] = os.path.join(out_dir, "image_times.csv")
    _write_csv(paths["image_times"], ["image", "time"], [names, GPS_TIME_START + tau_img], ["%s", "%.6f"])
    paths["poses"] = os.path.join(out_dir, "poses.csv")
    _write_csv(paths["poses"], ["image", "x", "y", "z", "roll", "pitch", "heading", "time"],
               [names] + cols + [GPS_TIME_START + tau_img], ["%s"] + fmts + ["%.6f"])
    lap("trajectory")

    # --- reference signs -------------------------------------------------------------------
    paths["reference"] = os.path.join(out_dir, "reference_signs.csv")
    ref_rows = []
    for s in scene.signs:
        c = s.panel.centre + frames.origin
        az = float(g.azimuth_deg_of_enu(s.panel.normal))
        ref_rows.append([s.sign_id, s.cls, "%.4f" % c[0], "%.4f" % c[1], "%.4f" % c[2], "%.4f" % s.height_above_ground,
                         "%.3f" % s.panel.width, "%.3f" % s.panel.height, "%.3f" % az, int(s.faded),
                         tx.VARIANT_CODES.get((s.cls, s.variant), "")])
    with open(paths["reference"], "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        # ``faded`` (1: the face lost its retroreflective sheeting) and ``code`` (the sign's
        # OpenStreetMap traffic_sign code) come last: older readers ignore them
        w.writerow(["sign_id", "class", "x", "y", "z", "height", "width", "panel_height", "azimuth", "faded",
                    "code"])
        w.writerows(ref_rows)

    # --- reference poles ---------------------------------------------------------------------
    paths["reference_poles"] = os.path.join(out_dir, "reference_poles.csv")
    with open(paths["reference_poles"], "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["pole_id", "kind", "x", "y", "z_foot", "height", "diameter", "structure_id", "sign_ids"])
        for pole in scene.poles:
            f = pole.foot + frames.origin
            w.writerow([pole.pole_id, pole.kind, "%.4f" % f[0], "%.4f" % f[1], "%.4f" % f[2], "%.4f" % pole.height,
                        "%.3f" % pole.diameter, pole.structure_id, " ".join(str(i) for i in pole.sign_ids)])

    def body_pose(tau):
        x, y, z, roll, pitch, hdg = motion.state(tau)
        R_wb = g.R_ENU_FROM_NED @ g.R_ned_from_body(roll, pitch, hdg)
        return np.stack([x, y, z], -1), R_wb

    # --- LiDAR -----------------------------------------------------------------------------
    mount = ScannerMount(lines_per_s=p.scan_lines_per_s, points_per_line=p.points_per_line)
    lidar_stats = None
    if lidar:
        paths["cloud"] = os.path.join(out_dir, "cloud.laz")
        writer = LazWriter(paths["cloud"], frames.origin, TARGET_CRS)
        try:
            lidar_stats = scan(scene, body_pose, 0.05, tau_end - 0.05, mount, _rng(seed, "lidar"), writer,
                               frames.origin, GPS_TIME_START, geometry=g)
        finally:
            writer.close()
        lap("lidar")

    # --- panoramas ---------------------------------------------------------------------------
    R_bp = g.R_body_from_pano(*BORESIGHT_DEG)
    C_body, R_wb_img = body_pose(tau_img)
    C_pano = C_body + R_wb_img @ np.asarray(LEVER_ARM_BODY_M)
    R_wp = R_wb_img @ R_bp
    images_meta = []
    if panoramas:
        paths["images"] = os.path.join(out_dir, "images")
        os.makedirs(paths["images"], exist_ok=True)
        if masks:
            paths["masks"] = os.path.join(out_dir, "masks")
            os.makedirs(paths["masks"], exist_ok=True)
        PANORAMAS.update(renderer=PanoramaRenderer(scene, p.pano_width, _rng(seed, "render"), LOOKS[look]),
                          names=names, C_pano=C_pano, R_wp=R_wp, tau_img=tau_img, seed=seed, look=LOOKS[look],
                          images=paths["images"], masks=paths.get("masks"), width=p.pano_width,
                          origin=frames.origin, centres={s.sign_id: s.panel.centre for s in scene.signs})
        try:
            images_meta = forked_map(render_panorama, range(len(names)), jobs)
        finally:
            PANORAMAS.clear()
        lap("panoramas")

    # --- scene.json --------------------------------------------------------------------------
    def world(v):
        return [round(float(a), 4) for a in np.asarray(v) + frames.origin]

    meta = {
        "generator": "devtools.scenegen", "format_version": 1, "preset": p.name, "seed": int(seed),
        "target_crs": TARGET_CRS, "trajectory_crs": traj_crs, "trajectory_heading": "true",
        "origin": world(np.zeros(3)), "origin_lonlat": list(ORIGIN_LONLAT),
        "meridian_convergence_deg_at_origin": round(float(frames.convergence_deg(*frames.origin[:2])), 6),
        "gps_time_start": GPS_TIME_START, "trajectory_rate_hz": TRAJECTORY_RATE_HZ,
        "lever_arm_m": list(LEVER_ARM_BODY_M),
        "boresight_deg": dict(zip(("roll", "pitch", "yaw"), BORESIGHT_DEG)),
        "sbet_wander_angle_rad": {"offset": WANDER_RAD[0], "rate_per_s": WANDER_RAD[1]},
        "image_width": p.pano_width, "image_height": p.pano_width // 2, "look": look,
        "mask_encoding": "uint16 PNG: sign_id on a panel's front face, sign_id | 0x8000 on its back, 0 elsewhere",
        "class_codes": CLASS_CODES, "reflectance": REFLECTANCE,
        "intensity_scale": "intensity = reflectance * incidence factor * range factor * (1 + 6% noise) * 65535",
        "scanner": mount.as_dict(),
        "road": {"curvature_per_m": scene.road.curvature, "length_m": p.road_length_m,
                 "gradient": list(scene.road.gradient),
                 "start": world([*scene.road.point(0.0), scene.road.base_z(0, 0)])},
        "preset_options": {k: getattr(p, k) for k in p.__dataclass_fields__},
        "signs": [{"sign_id": s.sign_id, "class": s.cls, "variant": s.variant, "mount": s.mount, "facing": s.facing,
                   "faded": s.faded, "near_tree": s.near_tree, "centre": world(s.panel.centre),
                   "normal": [round(float(a), 6) for a in s.panel.normal],
                   "azimuth_deg": round(float(g.azimuth_deg_of_enu(s.panel.normal)), 3),
                   "width": s.panel.width, "panel_height": s.panel.height,
                   "height_above_ground": round(s.height_above_ground, 4),
                   "corners_tl_tr_br_bl": [world(c) for c in s.panel.corner_points()]} for s in scene.signs],
        "distractors": [{"kind": d["kind"], "xyz": world(d["xyz"])} for d in scene.distractors],
        "poles": [{"pole_id": q.pole_id, "kind": q.kind, "foot": world(q.foot), "height": round(q.height, 4),
                   "diameter": q.diameter, "structure_id": q.structure_id, "sign_ids": list(q.sign_ids)}
                  for q in scene.poles],
        "images": images_meta,
        "lidar": lidar_stats,
        "timings_s": timings,
        "files": {k: os.path.relpath(v, out_dir) for k, v in paths.items()},
    }
    with open(paths["scene_json"], "w") as fh:
        json.dump(meta, fh, indent=1)
    return paths
