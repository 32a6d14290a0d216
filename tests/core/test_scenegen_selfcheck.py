"""Self-check of the synthetic scene generator (``devtools/scenegen``) against the contract.

The checks re-implement the contract's formulas in plain numpy here (no import of the
generator's internals nor of ``roadsigns.core.geometry``): a reference sign centre projected
into a panorama must land on that sign's pixels (sign-id mask written beside the images),
the cloud must hold sign-panel points on each reference panel, and the trajectory CSV,
SBET and per-image poses must describe the same motion with TRUE heading.
"""
import csv
import json
import os
import sys

import numpy as np
import pytest

os.environ.setdefault("PROJ_DATA", "/usr/share/proj")
import cv2  # noqa: E402
import laspy  # noqa: E402
import pyproj  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
if REPO not in sys.path:
    sys.path.insert(0, REPO)
from helpers.contract import NED_TO_ENU, Rx, Ry, Rz  # noqa: E402
from helpers.scenes import render_scene  # noqa: E402

from devtools.scenegen import generate_scene  # noqa: E402

PANO_WIDTH = 2048
UTM = "EPSG:32633"
TO_UTM = pyproj.Transformer.from_crs("EPSG:4326", UTM, always_xy=True)
TO_GEO = pyproj.Transformer.from_crs(UTM, "EPSG:4326", always_xy=True)
R_ENU_NED = NED_TO_ENU


# --- the contract, re-implemented (tests/helpers/contract.py, independent of core) --------
def zyx(roll, pitch, yaw):
    return Rz(yaw) @ Ry(pitch) @ Rx(roll)


def convergence_deg(x_utm, y_utm):
    lon, lat = TO_GEO.transform(x_utm, y_utm)
    return np.asarray(pyproj.Proj(UTM).get_factors(lon, lat).meridian_convergence, float)


def to_utm(x, y, geographic):
    return TO_UTM.transform(x, y) if geographic else (np.asarray(x, float), np.asarray(y, float))


def pano_pose(row, meta, geographic):
    """Panorama centre and R_world_from_pano from a poses.csv row (true heading)."""
    x, y = to_utm(float(row["x"]), float(row["y"]), geographic)
    grid = float(row["heading"]) - float(convergence_deg(x, y))
    R_wb = R_ENU_NED @ zyx(float(row["roll"]), float(row["pitch"]), grid)
    C = np.array([x, y, float(row["z"])]) + R_wb @ np.asarray(meta["lever_arm_m"], float)
    b = meta["boresight_deg"]
    return C, R_wb @ zyx(b["roll"], b["pitch"], b["yaw"])


def world_to_pixel(X, C, R, W, H):
    d = R.T @ (np.asarray(X, float) - C)
    alpha = np.arctan2(d[1], d[0])
    eps = np.arctan2(-d[2], np.hypot(d[0], d[1]))
    return W * (alpha / (2 * np.pi) + 0.5), H * (0.5 - eps / np.pi), float(np.linalg.norm(d))


def face_normal(azimuth_deg):
    a = np.radians(azimuth_deg)
    return np.array([np.sin(a), np.cos(a), 0.0])


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def column(rows, key):
    return np.array([float(r[key]) for r in rows])


# --- scenes -------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def projected(tmp_path_factory):
    return render_scene(tmp_path_factory.mktemp("scene_projected"), "tiny", 3, "--crs", "projected",
                        "--pano-width", PANO_WIDTH)


@pytest.fixture(scope="module")
def geographic(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("scene_geographic"))
    generate_scene("tiny", 3, out, crs="geographic", panoramas=False, lidar=False)
    return out


def load_meta(folder):
    with open(os.path.join(folder, "scene.json")) as fh:
        return json.load(fh)


def test_reference_centres_project_onto_their_sign_pixels(projected):
    meta = load_meta(projected)
    W, H = meta["image_width"], meta["image_height"]
    assert (W, H) == (PANO_WIDTH, PANO_WIDTH // 2)
    signs = {int(r["sign_id"]): r for r in read_csv(os.path.join(projected, "reference_signs.csv"))}
    assert {r["class"] for r in signs.values()} >= {"warning", "prohibitory", "mandatory", "information", "stop",
                                                    "yield"}
    claimed = {m["image"]: {b["sign_id"]: b for b in m["signs"]} for m in meta["images"]}
    checked = 0
    for row in read_csv(os.path.join(projected, "poses.csv")):
        C, R = pano_pose(row, meta, geographic=False)
        mask = cv2.imread(os.path.join(projected, "masks", row["image"].replace(".jpg", ".png")), cv2.IMREAD_UNCHANGED)
        assert mask.shape == (H, W) and mask.dtype == np.uint16
        image = cv2.imread(os.path.join(projected, "images", row["image"]))
        assert image.shape == (H, W, 3)
        for sid, s in signs.items():
            X = np.array([float(s["x"]), float(s["y"]), float(s["z"])])
            u, v, rng = world_to_pixel(X, C, R, W, H)
            view_cos = np.dot(C - X, face_normal(float(s["azimuth"]))) / rng
            box = claimed[row["image"]].get(sid)
            if view_cos < 0.3 or rng > 40.0 or box is None or box["occlusion"] > 0.05:
                continue  # seen from behind or edge-on, far, or partly hidden
            ui, vi = int(np.floor(u)) % W, int(np.floor(v))
            assert mask[vi, ui] == sid, (row["image"], sid, u, v, mask[vi, ui])
            u0, v0, u1, v1 = box["visible_box"]
            assert v0 <= v < v1 and (u0 <= u < u1 or u0 <= u + W < u1), (row["image"], sid, u, v, box)
            checked += 1
    assert checked >= 15


def test_cloud_has_panel_points_on_each_reference_panel(projected):
    meta = load_meta(projected)
    las = laspy.read(os.path.join(projected, "cloud.laz"))
    assert las.header.parse_crs().to_epsg() == 32633
    code = meta["class_codes"]["sign_panel"]
    cls = np.asarray(las.classification)
    P = np.stack([las.x, las.y, las.z], 1)[cls == code]
    traj = read_csv(os.path.join(projected, "trajectory.csv"))
    T = np.stack([column(traj, "x"), column(traj, "y")], 1)
    gps = np.asarray(las.gps_time)
    assert column(traj, "time")[0] <= gps.min() and gps.max() <= column(traj, "time")[-1]
    on_some_panel = np.zeros(len(P), bool)
    for s in read_csv(os.path.join(projected, "reference_signs.csv")):
        c = np.array([float(s["x"]), float(s["y"]), float(s["z"])])
        if np.min(np.hypot(*(T - c[:2]).T)) > 30.0:
            continue  # out of the scanner's reach
        n = face_normal(float(s["azimuth"]))
        right = np.cross(-n, [0, 0, 1.0])
        rel = P - c
        dist, a, b = rel @ n, rel @ right, rel[:, 2]
        inside = (np.abs(a) <= float(s["width"]) / 2) & (np.abs(b) <= float(s["panel_height"]) / 2)
        on_plane = inside & (np.abs(dist) < 0.03)
        assert on_plane.sum() >= 20, (s, int(on_plane.sum()))
        on_some_panel |= inside & (np.abs(dist) < 0.06)
    assert on_some_panel.mean() > 0.98
    # intensity by material: retroreflective faces bright, asphalt dark
    ground = np.asarray(las.intensity)[cls == 2]
    assert np.percentile(np.asarray(las.intensity)[cls == code], 90) > 5 * np.median(ground)


def _interp_trajectory(traj, t, geographic):
    tt = column(traj, "time")
    x, y = to_utm(column(traj, "x"), column(traj, "y"), geographic)
    out = {k: np.interp(t, tt, v) for k, v in (("x", x), ("y", y), ("z", column(traj, "z")),
                                               ("roll", column(traj, "roll")), ("pitch", column(traj, "pitch")))}
    out["heading"] = np.mod(np.interp(t, tt, np.degrees(np.unwrap(np.radians(column(traj, "heading"))))), 360)
    return out


@pytest.mark.parametrize("variant", ["projected", "geographic"])
def test_trajectory_sbet_poses_agree_with_true_heading(variant, request):
    folder = request.getfixturevalue(variant)
    geographic = variant == "geographic"
    meta = load_meta(folder)
    assert meta["trajectory_crs"] == ("EPSG:4326" if geographic else "EPSG:32633")
    traj = read_csv(os.path.join(folder, "trajectory.csv"))
    t = column(traj, "time")
    assert np.allclose(np.diff(t), 0.01, atol=1e-6)
    x, y = to_utm(column(traj, "x"), column(traj, "y"), geographic)
    # heading is TRUE: grid direction of motion = heading - convergence, and convergence matters
    gamma = convergence_deg(x, y)
    assert gamma.min() > 1.0
    motion_az = np.degrees(np.arctan2(np.gradient(x), np.gradient(y)))
    diff = np.mod(column(traj, "heading") - gamma - motion_az + 180, 360) - 180
    assert np.abs(diff[1:-1]).max() < 0.05
    # SBET: same times, positions, attitude; true heading = platform heading - wander angle
    sbet = np.fromfile(os.path.join(folder, "trajectory.out"), "<f8").reshape(-1, 17)
    assert np.allclose(sbet[:, 0], t, atol=1e-6)
    sx, sy = TO_UTM.transform(np.degrees(sbet[:, 2]), np.degrees(sbet[:, 1]))
    assert np.hypot(sx - x, sy - y).max() < 0.002
    assert np.abs(sbet[:, 3] - column(traj, "z")).max() < 0.001
    assert np.abs(sbet[:, 10]).min() > 0.1
    true_hdg = np.degrees(sbet[:, 9] - sbet[:, 10])
    assert np.abs(np.mod(true_hdg - column(traj, "heading") + 180, 360) - 180).max() < 1e-4
    assert np.abs(np.degrees(sbet[:, 7]) - column(traj, "roll")).max() < 1e-4
    # per-image poses = trajectory interpolated at the image times
    poses = read_csv(os.path.join(folder, "poses.csv"))
    times = {r["image"]: float(r["time"]) for r in read_csv(os.path.join(folder, "image_times.csv"))}
    tp = column(poses, "time")
    assert all(abs(times[r["image"]] - float(r["time"])) < 1e-6 for r in poses)
    assert np.diff(tp).min() > 0 and (np.mod(tp * 100, 1) > 1e-3).any()  # not on the 100 Hz grid
    ref = _interp_trajectory(traj, tp, geographic)
    px, py = to_utm(column(poses, "x"), column(poses, "y"), geographic)
    assert np.hypot(px - ref["x"], py - ref["y"]).max() < 0.005
    for k in ("roll", "pitch"):
        assert np.abs(column(poses, k) - ref[k]).max() < 0.01
    assert np.abs(np.mod(column(poses, "heading") - ref["heading"] + 180, 360) - 180).max() < 0.01
    # image spacing ~5 m
    step = np.hypot(np.diff(px), np.diff(py))
    assert 4.0 < step.min() and step.max() < 6.0


def test_same_seed_same_files(projected, geographic, tmp_path):
    generate_scene("tiny", 3, str(tmp_path), crs="projected", panoramas=False)
    for name in ("trajectory.csv", "poses.csv", "image_times.csv", "reference_signs.csv", "trajectory.out"):
        with open(os.path.join(projected, name), "rb") as a, open(os.path.join(tmp_path, name), "rb") as b:
            assert a.read() == b.read(), name
    with open(os.path.join(projected, "reference_signs.csv"), "rb") as a, \
            open(os.path.join(geographic, "reference_signs.csv"), "rb") as b:
        assert a.read() == b.read()
    first, again = laspy.read(os.path.join(projected, "cloud.laz")), laspy.read(os.path.join(tmp_path, "cloud.laz"))
    assert len(first.points) == len(again.points) > 100_000
    for dim in ("X", "Y", "Z", "intensity", "classification", "gps_time"):
        assert np.array_equal(np.asarray(first[dim]), np.asarray(again[dim])), dim


def test_held_out_looks_draw_outside_the_training_ranges():
    """Held-out looks (dusk, glare) draw every camera effect and the sun from ranges the
    training look never reaches; the training look's draws are unchanged by their option."""
    from devtools.scenegen.render import LOOKS, finish_image

    train = LOOKS["training"]
    linear = np.full((8, 16, 3), 0.5, np.float32)
    for name in ("dusk", "glare"):
        look = LOOKS[name]
        for lo_hi, t in ((look.sun_elevation_deg, train.sun_elevation_deg), (look.gain, train.gain),
                         (look.jpeg_quality, train.jpeg_quality)):
            assert lo_hi[1] < t[0] or lo_hi[0] > t[1]          # disjoint from training's range
        for seed in range(5):
            _, quality, camera = finish_image(linear, np.random.default_rng(seed), look)
            assert look.gain[0] <= camera["gain"] <= look.gain[1]
            assert look.jpeg_quality[0] <= quality < look.jpeg_quality[1]
            assert not train.gain[0] <= camera["gain"] <= train.gain[1]
    a = finish_image(linear, np.random.default_rng(3))
    b = finish_image(linear, np.random.default_rng(3), train)
    assert np.array_equal(a[0], b[0]) and a[1:] == b[1:]
