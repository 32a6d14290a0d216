"""A long drive: the LiDAR simulated over the whole length, panoramas rendered for a first stretch.

Rendering is the generator's slow part (a 4096 x 2048 panorama takes ~35 s on one core),
so a drive of thousands of panoramas renders only the stations of its first stretch and
gives every later station one of those images again under its own name, with its own
pose in ``image_times.csv`` and ``poses.csv``: station ``i`` shows the image of station
``i mod K`` (K rendered), as a hard link (or symlink, or copy). The chain does the work of a
real drive on them (every panorama is decoded and searched, every detection projected), but
what the reused panoramas show is the first stretch seen from elsewhere: the signs found
from them are not real. Only the first stretch has known image truth; the LiDAR and the
reference signs and poles are real over the whole length.

    python -m devtools.scenegen.drive --preset drive1k --seed 4 --out bench/out/drive-drive1k-4 \
        [--render-m 100 | --render-count 80] [--jobs 1]

``drive.json`` (written last: its presence means the drive is complete) says which images
were rendered, how the others map onto them, and the truth stretch as chainage along
``trajectory.csv`` (metres from its first sample, along its polyline): reference signs in
it were seen by rendered panoramas only. :func:`chainage` computes the same chainage for
any points.
"""
from __future__ import annotations

import argparse
import csv
import json
import multiprocessing
import os
import resource
import shutil
import sys
import time

import numpy as np

from . import roadsigns_geometry
from .presets import get_preset

#: per drive preset: the rendered first stretch (metres of road from the first panorama,
#: or a number of panoramas) and the panorama width; what a call does not set comes from here
DRIVES = {
    "drivesmoke": {"render_count": 8},
    "drive1k": {"render_m": 100.0},
    "drive9k": {"render_m": 1000.0},
}
#: reference signs this close to the last rendered panorama (along the drive) or beyond it
#: are left out of the truth stretch: their later views would come from reused images
END_MARGIN_M = 10.0
DRIVE_JSON = "drive.json"


class Chainage:
    """Metres along the trajectory polyline ``traj_xy`` (n, 2) of points (m, 2): each point's
    projection onto its nearest segment."""

    def __init__(self, traj_xy: np.ndarray):
        from scipy.spatial import cKDTree
        self.xy = np.asarray(traj_xy, float)
        self.seg = np.diff(self.xy, axis=0)
        self.seg_len = np.linalg.norm(self.seg, axis=1)
        self.cum = np.concatenate([[0.0], np.cumsum(self.seg_len)])
        self.tree = cKDTree(self.xy)

    def __call__(self, xy) -> np.ndarray:
        xy = np.asarray(xy, float).reshape(-1, 2)
        if len(xy) == 0:
            return np.zeros(0)
        _, nearest = self.tree.query(xy)
        best = np.full(len(xy), np.nan)
        best_d = np.full(len(xy), np.inf)
        for k in (nearest - 1, nearest):                     # the segments either side of the vertex
            k = np.clip(k, 0, len(self.seg) - 1)
            rel = xy - self.xy[k]
            f = np.clip(np.einsum("ij,ij->i", rel, self.seg[k]) / np.maximum(self.seg_len[k] ** 2, 1e-12), 0.0, 1.0)
            d = np.linalg.norm(rel - f[:, None] * self.seg[k], axis=1)
            closer = d < best_d
            best[closer] = (self.cum[k] + f * self.seg_len[k])[closer]
            best_d[closer] = d[closer]
        return best


def chainage(traj_xy: np.ndarray, xy) -> np.ndarray:
    """:class:`Chainage` of ``xy`` along ``traj_xy``, once."""
    return Chainage(traj_xy)(xy)


def read_trajectory_xy(drive_dir: str) -> np.ndarray:
    """``trajectory.csv``'s x, y columns (the drive is generated in a projected CRS)."""
    data = np.loadtxt(os.path.join(drive_dir, "trajectory.csv"), delimiter=",", skiprows=1, usecols=(1, 2))
    return data.reshape(-1, 2)


def read_drive(drive_dir: str):
    """``drive.json`` of a complete drive, or None."""
    path = os.path.join(drive_dir, DRIVE_JSON)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def write_tiles(drive_dir: str, tile_m: float = 500.0, verbose: bool = False) -> str:
    """``cloud.laz`` split into tiles of ``tile_m`` of drive (by the points' times: the
    scanner writes them in time order) in ``cloud_tiles/``, and ``cloud.vpc`` listing them;
    returns the ``.vpc``'s path (made once). Streams: memory stays flat."""
    import laspy

    from .. import import_roadsigns
    cloudsource = import_roadsigns("roadsigns.core.cloudsource")
    vpc = os.path.join(drive_dir, "cloud.vpc")
    if os.path.exists(vpc):
        return vpc
    folder = os.path.join(drive_dir, "cloud_tiles")
    if os.path.isdir(folder):
        shutil.rmtree(folder)
    os.makedirs(folder)
    traj = np.loadtxt(os.path.join(drive_dir, "trajectory.csv"), delimiter=",", skiprows=1, usecols=(0, 1, 2))
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(traj[:, 1:3], axis=0), axis=1))])
    cuts = np.interp(np.arange(tile_m, cum[-1], tile_m), cum, traj[:, 0])   # GPS times of the cuts
    paths, writer, current = [], None, -1
    with laspy.open(os.path.join(drive_dir, "cloud.laz")) as reader:
        header = cloudsource.template_header(reader.header)
        crs = reader.header.parse_crs()
        for chunk in reader.chunk_iterator(2_000_000):
            tile = np.searchsorted(cuts, np.asarray(chunk.gps_time), side="right")
            for k in np.unique(tile):
                if k != current:
                    if writer is not None:
                        writer.close()
                    paths.append(os.path.join(folder, f"tile_{int(k):03d}.laz"))
                    writer = laspy.open(paths[-1], mode="w", header=header, do_compress=True)
                    current = k
                writer.write_points(chunk[tile == k])
    if writer is not None:
        writer.close()
    tiles = []
    for path in paths:
        with laspy.open(path) as r:
            tiles.append((path, r.header))
    with open(vpc + ".tmp", "w") as f:
        f.write(cloudsource.vpc_text(tiles, crs.to_wkt() if crs is not None else None, drive_dir))
    os.replace(vpc + ".tmp", vpc)
    if verbose:
        print(f"[drive] {len(paths)} tiles of {tile_m:.0f} m in {folder}, listed in {vpc}", flush=True)
    return vpc


def _link(src: str, dst: str) -> str:
    """``dst`` as another name of ``src``: a hard link, else a relative symlink, else a copy."""
    if os.path.lexists(dst):
        os.remove(dst)
    try:
        os.link(src, dst)
        return "hard link"
    except OSError:
        pass
    try:
        os.symlink(os.path.relpath(src, os.path.dirname(dst)), dst)
        return "symlink"
    except OSError:
        shutil.copyfile(src, dst)
        return "copy"


def generate_drive(preset="drive1k", seed=4, out_dir="drive", render_m=None, render_count=None,
                   pano_width=None, jobs=1, masks=False, verbose=False):
    """Write a drive into ``out_dir`` (see the module's doc); returns its ``drive.json`` dict.

    Steps already done by an interrupted call are kept: the scene without panoramas
    (``scene.json`` present), and each panorama already rendered (``render_log.jsonl``).
    """
    from .generate import (
        BORESIGHT_DEG,
        GPS_TIME_START,
        LEVER_ARM_BODY_M,
        PANORAMAS,
        _Frames,
        _rng,
        generate_scene,
        render_panorama,
    )
    from .layout import build_scene
    from .render import LOOKS, PanoramaRenderer
    from .road import Motion

    defaults = DRIVES.get(preset, {"render_m": 100.0})
    if render_m is None and render_count is None:
        render_m, render_count = defaults.get("render_m"), defaults.get("render_count")
    p = get_preset(preset, pano_width=pano_width)
    os.makedirs(out_dir, exist_ok=True)
    done = read_drive(out_dir)
    if done is not None:
        return done
    timings = {}

    def say(text):
        if verbose:
            print("[drive] " + text, flush=True)

    # 1. the drive without panoramas: trajectory, SBET, image times, poses, LiDAR, reference
    scene_json = os.path.join(out_dir, "scene.json")
    if not os.path.exists(scene_json):
        start = time.perf_counter()
        generate_scene(preset, seed, out_dir, crs="projected", panoramas=False, lidar=True,
                       pano_width=pano_width, masks=False, verbose=verbose)
        timings["trajectory_lidar_reference_s"] = round(time.perf_counter() - start, 1)
        say("trajectory, LiDAR and reference in {:.0f} s".format(timings["trajectory_lidar_reference_s"]))
    with open(scene_json) as f:
        meta = json.load(f)

    # 2. the stations' poses, exactly as generate_scene computes them
    g = roadsigns_geometry()
    frames = _Frames()
    scene = build_scene(p, _rng(seed, "layout"))
    mrng = _rng(seed, "motion")
    motion = Motion(scene.road, s_start=-p.lead_in_m, speed_mps=p.speed_mps,
                    phase=tuple(mrng.uniform(0, 2 * np.pi, 4)))
    s_img = np.arange(0.0, p.road_length_m + 1e-9, p.image_spacing_m)
    s_img = s_img + _rng(seed, "images_jitter").uniform(-0.3, 0.3, len(s_img))
    tau_img = np.round(motion.tau_of_s(s_img), 6)
    names = [f"pano_{i:05d}.jpg" for i in range(len(tau_img))]
    with open(os.path.join(out_dir, "image_times.csv")) as f:
        written = list(csv.reader(f))[1:]
    if [r[0] for r in written] != names or not np.allclose(
            [float(r[1]) for r in written], GPS_TIME_START + tau_img, atol=2e-6):
        raise RuntimeError("image_times.csv does not match the drive's stations: delete {} and run again"
                           .format(out_dir))
    x, y, z, roll, pitch, hdg = motion.state(tau_img)
    R_wb = g.R_ENU_FROM_NED @ g.R_ned_from_body(roll, pitch, hdg)
    C_pano = np.stack([x, y, z], -1) + R_wb @ np.asarray(LEVER_ARM_BODY_M)
    R_wp = R_wb @ g.R_body_from_pano(*BORESIGHT_DEG)

    n = len(names)
    if render_count is None:
        render_count = int(np.count_nonzero(s_img <= float(render_m)))
    K = max(1, min(int(render_count), n))

    # 3. render the first K panoramas (resumable: render_log.jsonl lists the finished ones)
    images = os.path.join(out_dir, "images")
    os.makedirs(images, exist_ok=True)
    masks_dir = os.path.join(out_dir, "masks")
    if masks:
        os.makedirs(masks_dir, exist_ok=True)
    log_path = os.path.join(out_dir, "render_log.jsonl")
    rendered = {}
    if os.path.exists(log_path):
        with open(log_path) as f:
            for line in f:
                if line.strip():
                    rec = json.loads(line)
                    if os.path.exists(os.path.join(images, rec["image"])):
                        rendered[rec["image"]] = rec
    todo = [i for i in range(K) if names[i] not in rendered]
    start = time.perf_counter()
    if todo:
        say("rendering {} of {} panoramas at {} x {} ({} jobs)".format(len(todo), K, p.pano_width,
                                                                     p.pano_width // 2, jobs))
        PANORAMAS.update(renderer=PanoramaRenderer(scene, p.pano_width, _rng(seed, "render")),
                         C_pano=C_pano, R_wp=R_wp, tau_img=tau_img, names=names, seed=seed, look=LOOKS["training"],
                         images=images, masks=masks_dir if masks else None, width=p.pano_width,
                         origin=frames.origin, centres={s.sign_id: s.panel.centre for s in scene.signs})
        with open(log_path, "a") as log:
            if jobs > 1:
                pool = multiprocessing.get_context("fork").Pool(jobs)
                results = pool.imap_unordered(render_panorama, todo)
            else:
                pool, results = None, map(render_panorama, todo)
            for k, rec in enumerate(results, 1):
                rendered[rec["image"]] = rec
                log.write(json.dumps(rec) + "\n")
                log.flush()
                if verbose and (k == len(todo) or k % max(1, len(todo) // 20) == 0):
                    say("rendered {} of {} ({:.1f} s each)".format(k, len(todo),
                                                                   (time.perf_counter() - start) / k))
            if pool is not None:
                pool.close()
                pool.join()
        PANORAMAS.clear()
        timings["render_s"] = round(time.perf_counter() - start, 1)
        timings["render_s_per_panorama"] = round(timings["render_s"] / len(todo), 2)
        timings["render_timed_panoramas"] = len(todo)   # those rendered by this call

    # 4. the other stations: the rendered images again, under their own names
    how = set()
    for i in range(K, n):
        how.add(_link(os.path.join(images, names[i % K]), os.path.join(images, names[i])))

    # 5. the truth stretch (chainage along trajectory.csv) and drive.json
    traj_xy = read_trajectory_xy(out_dir)
    c_img = chainage(traj_xy, (C_pano[:, :2] + frames.origin[:2]))
    stretch = [0.0, round(float(c_img[K - 1] - END_MARGIN_M), 3)]
    ref_xy = np.array([s["centre"][:2] for s in meta["signs"]]).reshape(-1, 2)
    c_ref = chainage(traj_xy, ref_xy)
    in_stretch = [s["sign_id"] for s, c in zip(meta["signs"], c_ref) if stretch[0] <= c <= stretch[1]]
    drive = {
        "preset": p.name, "seed": int(seed), "road_length_m": p.road_length_m,
        "length_m": round(float(chainage(traj_xy, traj_xy[-1:])[0]), 1),
        "image_spacing_m": p.image_spacing_m, "pano_width": p.pano_width,
        "panoramas": n, "rendered": K, "reused": n - K,
        "rendered_images": [names[0], names[K - 1]],
        "rendered_road_m": [round(float(s_img[0]), 2), round(float(s_img[K - 1]), 2)],
        "reuse": "station i shows the image of station i mod {} ({})".format(K, ", ".join(sorted(how)) or "none"),
        "points": (meta.get("lidar") or {}).get("points"),
        "reference_signs": len(meta["signs"]), "reference_poles": len(meta["poles"]),
        "truth_stretch": {"chainage_m": stretch, "end_margin_m": END_MARGIN_M,
                          "reference_signs": len(in_stretch), "sign_ids": in_stretch,
                          "what": "chainage along trajectory.csv (m from its first sample); reference "
                                  "signs before the last rendered panorama less the end margin"},
        "timings_s": {**meta.get("timings_s", {}), **timings},
    }
    meta["images"] = [rendered[nm] for nm in names[:K]]
    meta["drive"] = {k: v for k, v in drive.items() if k != "truth_stretch"}
    with open(scene_json, "w") as f:
        json.dump(meta, f, indent=1)
    with open(os.path.join(out_dir, DRIVE_JSON), "w") as f:
        json.dump(drive, f, indent=1)
    return drive


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m devtools.scenegen.drive", description=__doc__.splitlines()[0])
    ap.add_argument("--preset", default="drive1k", choices=sorted(DRIVES))
    ap.add_argument("--seed", type=int, default=4)
    ap.add_argument("--out", required=True)
    ap.add_argument("--render-m", type=float, help="render the panoramas of the first this many metres")
    ap.add_argument("--render-count", type=int, help="render this many first panoramas")
    ap.add_argument("--pano-width", type=int)
    ap.add_argument("--jobs", type=int, default=1, help="render in this many processes")
    ap.add_argument("--masks", action="store_true", help="also write the sign-id masks of the rendered ones")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    drive = generate_drive(a.preset, a.seed, a.out, a.render_m, a.render_count, a.pano_width, a.jobs,
                           a.masks, verbose=True)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print("[drive] {} in {:.0f} s (peak {:.0f} MiB): {} panoramas, {} rendered, {} points"
          .format(a.out, time.perf_counter() - t0, peak, drive["panoramas"], drive["rendered"], drive["points"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
