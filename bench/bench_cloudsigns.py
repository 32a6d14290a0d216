#!/usr/bin/env python3
"""Benchmark the LiDAR-only sign and pole finder (``core.cloudsigns``) on generated scenes.

For each ``--preset``/``--seed`` a scene is generated without panoramas under ``--out``
(reused when already there), the finder runs on its ``cloud.laz`` with the track of its
``trajectory.csv`` (raised by the scanner's 2.0 m above the IMU), in a subprocess so that
its peak memory is its own, and the results are matched to ``reference_signs.csv`` and
``reference_poles.csv``:

* signs: one-to-one (Hungarian) within ``--sign-radius`` (3D) of a reference centre;
  precision, recall, median and p95 position error;
* poles: within ``--pole-radius`` (2D, foot); precision, recall, median / max foot error,
  kind accuracy among the matched;
* faded: recall of faded reference signs flagged ``check``/``poor``; false-flag rate of
  healthy matched signs flagged so;
* time and peak memory, per million points;
* fusion, simulated: image signs made from the reference (2 cm jitter) with a share
  ``--drop`` of them left out at random, as a detector missing one sign in five would, fused
  with the panels (:func:`core.fusion.fuse_signs`); recall and precision of the fused signs
  (any source) and how many came from the laser alone. The real chain's figures need the
  detector; this isolates what the cloud adds.

Only reference objects the drive saw are scored: within the corridor of the track, not
beyond its ends (``DriveAxis`` arc length in ``[0, length]``), and scanned (at least
``MIN_OBSERVED_POINTS`` points of the object's true class near it: on the panel, around the
pole's axis; some are hidden behind billboards or out of the scanner's sweep); a detection
matched to a reference object outside that set counts neither way.

    .venv/bin/python bench/bench_cloudsigns.py --preset tiny --seed 1 2 3
    .venv/bin/python bench/bench_cloudsigns.py --preset default --seed 7 21 --json bench/out/cs.json
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
SCANNER_ABOVE_IMU_M = 2.0   # devtools/scenegen/lidar.py ScannerMount.lever_arm_body_m (z down)
FLAGGED = ("check", "poor")
MIN_OBSERVED_POINTS = 20
SIGN_CLASSES = (64,)          # devtools/scenegen/layout.py CLASS_CODES
POLE_CLASSES = (65, 66)


def _import_package():
    sys.path.insert(0, REPO)
    from devtools import import_roadsigns
    import_roadsigns()


def _memory_mb(field: str) -> float:
    """``VmHWM`` (peak) or ``VmRSS`` (now) of this process in MB from /proc (a child's
    ``ru_maxrss`` starts at its parent's size at fork), else ``ru_maxrss``."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith(field + ":"):
                    return float(line.split()[1]) / 1024.0
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def _peak_rss_mb() -> float:
    return _memory_mb("VmHWM")


def _read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def scene_folder(out: str, preset: str, seed: int) -> str:
    folder = os.path.join(out, "scene-{}-{}".format(preset, seed))
    if not os.path.exists(os.path.join(folder, "reference_poles.csv")):
        subprocess.run([sys.executable, "-m", "devtools.scenegen", "--preset", preset, "--seed", str(seed),
                        "--out", folder, "--no-panoramas"], cwd=REPO, check=True,
                       stdout=subprocess.DEVNULL)
    return folder


def run_finder(folder: str, chunk_points: int) -> dict:
    """Run the finder in this process (called in a subprocess by :func:`main`)."""
    _import_package()
    import numpy as np

    from roadsigns.core.cloudsigns import find_signs_in_cloud
    from roadsigns.core.drivewindows import Track

    base = _memory_mb("VmRSS")
    traj = np.genfromtxt(os.path.join(folder, "trajectory.csv"), delimiter=",", names=True)
    track = Track(np.column_stack([traj["x"], traj["y"], traj["z"] + SCANNER_ABOVE_IMU_M]), traj["time"])
    t0 = time.perf_counter()
    res = find_signs_in_cloud(os.path.join(folder, "cloud.laz"), track, chunk_points=chunk_points)
    seconds = time.perf_counter() - t0
    return {"signs": res.sign_records(), "poles": res.pole_records(), "seconds": seconds,
            "n_points": res.n_points, "n_candidates": res.n_candidates, "peak_rss_mb": _peak_rss_mb(),
            "base_rss_mb": base, "messages": [str(m) for m in res.messages],
            "warnings": [str(w) for w in res.warnings], "rejected": res.rejected,
            "threshold": res.threshold.value, "range_exponent": res.threshold.range_exponent,
            "reference": res.reference,
            "track_xyz": np.column_stack([traj["x"], traj["y"], traj["z"]])[::10].tolist()}


def observed_points(cloud_path, centres_xyz, radius_m, classes, planar=False):
    """Points of ``classes`` within ``radius_m`` of each centre (3D, or 2D when ``planar``),
    counted chunk by chunk."""
    import laspy
    import numpy as np
    from scipy.spatial import cKDTree

    centres = np.asarray(centres_xyz, dtype=float).reshape(-1, 3)
    counts = np.zeros(len(centres), np.int64)
    if len(centres) == 0:
        return counts
    dims = 2 if planar else 3
    tree = cKDTree(centres[:, :dims])
    with laspy.open(cloud_path) as reader:
        for chunk in reader.chunk_iterator(2_000_000):
            keep = np.isin(np.asarray(chunk.classification), classes)
            if not keep.any():
                continue
            xyz = np.column_stack([np.asarray(chunk.x)[keep], np.asarray(chunk.y)[keep], np.asarray(chunk.z)[keep]])
            for hits in tree.query_ball_point(xyz[:, :dims], radius_m):
                for j in hits:
                    counts[j] += 1
    return counts


def _match(a_xyz, b_xyz, radius):
    """One-to-one pairs (i, j, distance) within ``radius`` minimising the total distance."""
    import numpy as np
    from scipy.optimize import linear_sum_assignment

    if len(a_xyz) == 0 or len(b_xyz) == 0:
        return []
    d = np.linalg.norm(np.asarray(a_xyz)[:, None, :] - np.asarray(b_xyz)[None, :, :], axis=2)
    cost = np.where(d <= radius, d, 1e6)
    rows, cols = linear_sum_assignment(cost)
    return [(int(i), int(j), float(d[i, j])) for i, j in zip(rows, cols) if d[i, j] <= radius]


def _simulated_fusion(ref, ref_xyz, ref_vis, panels, radius, drop, seed, visible) -> dict:
    """Fuse image signs simulated from the reference (a share ``drop`` missed) with the
    panels; recall and precision of the fused layer over the scored reference signs."""
    import numpy as np

    from roadsigns.core.fusion import SOURCE_LIDAR, fuse_signs

    rng = np.random.default_rng([int(seed), 17])
    kept = rng.random(len(ref)) >= drop
    images = []
    for j in np.flatnonzero(kept):
        xyz = ref_xyz[j] + rng.normal(0.0, 0.02, 3)
        images.append({"sign_id": int(ref[j]["sign_id"]), "class": ref[j]["class"], "score": 0.9,
                       "x": xyz[0], "y": xyz[1], "z": xyz[2], "azimuth": float(ref[j]["azimuth"]),
                       "position_source": "cloud"})
    fused = fuse_signs(images, panels).signs
    f_xyz = np.array([[r["x"], r["y"], r["z"]] for r in fused]).reshape(-1, 3)
    pairs = _match(f_xyz, ref_xyz, radius)
    tp = [(i, j) for i, j, _ in pairs if ref_vis[j]]
    matched = {i for i, _, _ in pairs}
    f_vis = visible(f_xyz[:, :2]) if len(f_xyz) else np.zeros(0, bool)
    fp = [i for i in range(len(fused)) if i not in matched and f_vis[i]]
    n_ref = int(ref_vis.sum())
    missed_by_images = int((ref_vis & ~kept).sum())
    recovered = sum(1 for i, j in tp if not kept[j] and fused[i]["source"] == SOURCE_LIDAR)
    return {"drop": drop, "image_signs": len(images), "missed_by_images": missed_by_images,
            "recovered_by_lidar": recovered, "recall": len(tp) / max(n_ref, 1),
            "precision": len(tp) / max(len(tp) + len(fp), 1)}


def score(folder: str, run: dict, sign_radius: float, pole_radius: float, corridor_m: float,
          drop: float = 0.2, seed: int = 0) -> dict:
    _import_package()
    import numpy as np

    from roadsigns.core.drivewindows import DriveAxis, Track

    axis = DriveAxis(Track.from_polyline(np.asarray(run["track_xyz"])))

    def visible(xy):
        s, off, _ = axis.locate(np.atleast_2d(xy))
        return (s >= 0) & (s <= axis.length_m) & (np.abs(off) <= corridor_m)

    ref = _read_csv(os.path.join(folder, "reference_signs.csv"))
    ref_xyz = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in ref])
    ref_faded = np.array([int(r.get("faded", 0)) for r in ref], bool)
    cloud = os.path.join(folder, "cloud.laz")
    ref_vis = visible(ref_xyz[:, :2]) & (observed_points(cloud, ref_xyz, 0.5, SIGN_CLASSES) >= MIN_OBSERVED_POINTS)
    det = run["signs"]
    det_xyz = np.array([[s["x"], s["y"], s["z"]] for s in det]).reshape(-1, 3)
    pairs = _match(det_xyz, ref_xyz, sign_radius)
    matched_det = {i for i, _, _ in pairs}
    tp = [(i, j, d) for i, j, d in pairs if ref_vis[j]]
    dont_care = {i for i, j, _ in pairs if not ref_vis[j]}
    det_vis = visible(det_xyz[:, :2]) if len(det_xyz) else np.zeros(0, bool)
    fp = [i for i in range(len(det)) if i not in matched_det and det_vis[i]]
    n_ref = int(ref_vis.sum())
    err = np.array([d for _, _, d in tp])
    faded_j = [j for j in np.flatnonzero(ref_vis & ref_faded)]
    by_ref = {j: i for i, j, _ in tp}
    faded_flagged = sum(1 for j in faded_j if j in by_ref and det[by_ref[j]]["condition"] in FLAGGED)
    healthy = [(i, j) for i, j, _ in tp if not ref_faded[j]]
    healthy_flagged = sum(1 for i, _ in healthy if det[i]["condition"] in FLAGGED)
    missed = [ref[j]["sign_id"] for j in np.flatnonzero(ref_vis) if j not in by_ref]
    false_signs = [{k: det[i][k] for k in ("sign_id", "x", "y", "z", "width", "panel_height", "support",
                                           "bright_share")} for i in fp]

    rp = _read_csv(os.path.join(folder, "reference_poles.csv"))
    rp_xy = np.array([[float(r["x"]), float(r["y"])] for r in rp]).reshape(-1, 2)
    rp_foot = np.array([[float(r["x"]), float(r["y"]), 0.0] for r in rp]).reshape(-1, 3)
    rp_vis = (visible(rp_xy) & (observed_points(cloud, rp_foot, 0.3, POLE_CLASSES, planar=True)
                                >= MIN_OBSERVED_POINTS)) if len(rp_xy) else np.zeros(0, bool)
    dp = run["poles"]
    dp_xy = np.array([[p["x"], p["y"]] for p in dp]).reshape(-1, 2)
    ppairs = _match(np.column_stack([dp_xy, np.zeros(len(dp_xy))]),
                    np.column_stack([rp_xy, np.zeros(len(rp_xy))]), pole_radius)
    ptp = [(i, j, d) for i, j, d in ppairs if rp_vis[j]]
    pmatched = {i for i, _, _ in ppairs}
    dp_vis = visible(dp_xy) if len(dp_xy) else np.zeros(0, bool)
    pfp = [i for i in range(len(dp)) if i not in pmatched and dp_vis[i]]
    perr = np.array([d for _, _, d in ptp])
    kind_ok = sum(1 for i, j, _ in ptp if dp[i]["kind"] == rp[j]["kind"])
    n_rp = int(rp_vis.sum())
    pmissed = [(rp[j]["pole_id"], rp[j]["kind"]) for j in np.flatnonzero(rp_vis) if j not in {b for _, b, _ in ptp}]
    pfalse = [{k: dp[i][k] for k in ("pole_id", "kind", "x", "y", "height")} for i in pfp]
    mpts = run["n_points"] / 1e6
    fusion = _simulated_fusion(ref, ref_xyz, ref_vis, det, sign_radius, drop, seed, visible)

    def ratio(a, b):
        return a / b if b else float("nan")

    return {
        "signs": {"reference": n_ref, "found": len(tp) + len(fp), "tp": len(tp), "fp": len(fp),
                  "precision": ratio(len(tp), len(tp) + len(fp)), "recall": ratio(len(tp), n_ref),
                  "median_error_m": float(np.median(err)) if len(err) else float("nan"),
                  "p95_error_m": float(np.percentile(err, 95)) if len(err) else float("nan"),
                  "missed": missed, "false": false_signs, "dont_care": len(dont_care)},
        "poles": {"reference": n_rp, "tp": len(ptp), "fp": len(pfp),
                  "precision": ratio(len(ptp), len(ptp) + len(pfp)), "recall": ratio(len(ptp), n_rp),
                  "median_foot_error_m": float(np.median(perr)) if len(perr) else float("nan"),
                  "max_foot_error_m": float(perr.max()) if len(perr) else float("nan"),
                  "kind_accuracy": ratio(kind_ok, len(ptp)), "missed": pmissed, "false": pfalse},
        "faded": {"reference": len(faded_j), "flagged": faded_flagged,
                  "recall": ratio(faded_flagged, len(faded_j)),
                  "healthy": len(healthy), "healthy_flagged": healthy_flagged,
                  "false_flag_rate": ratio(healthy_flagged, len(healthy))},
        "cost": {"points": run["n_points"], "seconds": run["seconds"],
                 "seconds_per_mpoint": ratio(run["seconds"], mpts),
                 "peak_rss_mb": run["peak_rss_mb"], "peak_over_base_mb": run["peak_rss_mb"] - run["base_rss_mb"],
                 "mb_per_mpoint": ratio(run["peak_rss_mb"] - run["base_rss_mb"], mpts)},
        "fusion": fusion,
        "log": run["messages"] + run["warnings"], "rejected": run["rejected"],
    }


def _print(name: str, s: dict) -> None:
    g, p, f, c = s["signs"], s["poles"], s["faded"], s["cost"]
    print("{}: signs P {:.3f} R {:.3f} ({}/{} found, {} false) median {:.3f} m p95 {:.3f} m".format(
        name, g["precision"], g["recall"], g["tp"], g["reference"], g["fp"], g["median_error_m"],
        g["p95_error_m"]))
    print("    poles P {:.3f} R {:.3f} ({}/{}, {} false) foot median {:.3f} max {:.3f} m, kind {:.3f}".format(
        p["precision"], p["recall"], p["tp"], p["reference"], p["fp"], p["median_foot_error_m"],
        p["max_foot_error_m"], p["kind_accuracy"]))
    print("    faded recall {:.3f} ({}/{}), healthy flagged {:.3f} ({}/{})".format(
        f["recall"], f["flagged"], f["reference"], f["false_flag_rate"], f["healthy_flagged"], f["healthy"]))
    print("    {:.2f} M points in {:.1f} s ({:.1f} s per M), peak {:.0f} MB ({:.0f} MB over the base, "
          "{:.1f} MB per M)".format(c["points"] / 1e6, c["seconds"], c["seconds_per_mpoint"], c["peak_rss_mb"],
                                    c["peak_over_base_mb"], c["mb_per_mpoint"]))
    u = s["fusion"]
    print("    fusion (simulated, {:.0%} of signs missed by the images: {}): recall {:.3f}, precision {:.3f}, "
          "{} recovered by the laser".format(u["drop"], u["missed_by_images"], u["recall"], u["precision"],
                                             u["recovered_by_lidar"]))
    if g["missed"] or g["false"]:
        print("    missed signs {} false {}".format(g["missed"], g["false"]))
    if p["missed"] or p["false"]:
        print("    missed poles {} false {}".format(p["missed"], p["false"]))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--preset", default="tiny")
    ap.add_argument("--seed", type=int, nargs="+", default=[1])
    ap.add_argument("--out", default="/tmp/roadsigns-bench-cloudsigns")
    ap.add_argument("--chunk-points", type=int, default=1_000_000)
    ap.add_argument("--sign-radius", type=float, default=0.5)
    ap.add_argument("--pole-radius", type=float, default=0.5)
    ap.add_argument("--corridor-m", type=float, default=11.0,
                    help="score objects this close to the track (the finder's corridor less its edge clearance)")
    ap.add_argument("--drop", type=float, default=0.2, help="share of signs the simulated images miss")
    ap.add_argument("--json", help="write all figures here")
    ap.add_argument("--run-one", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.run_one:   # the subprocess: run the finder, print its result as JSON
        print(json.dumps(run_finder(args.run_one, args.chunk_points)))
        return 0
    results = {}
    for seed in args.seed:
        folder = scene_folder(args.out, args.preset, seed)
        out = subprocess.run([sys.executable, os.path.abspath(__file__), "--run-one", folder,
                              "--chunk-points", str(args.chunk_points)], cwd=REPO, check=True,
                             capture_output=True, text=True)
        run = json.loads(out.stdout.strip().splitlines()[-1])
        s = score(folder, run, args.sign_radius, args.pole_radius, args.corridor_m, args.drop, seed)
        name = "{} {}".format(args.preset, seed)
        _print(name, s)
        results[name] = s
    if len(results) > 1:
        tot = {k: sum(r["signs"][k] for r in results.values()) for k in ("tp", "fp", "reference")}
        ptot = {k: sum(r["poles"][k] for r in results.values()) for k in ("tp", "fp", "reference")}
        ftot = {k: sum(r["faded"][k] for r in results.values())
                for k in ("flagged", "reference", "healthy_flagged", "healthy")}
        print("all: signs P {:.3f} R {:.3f}; poles P {:.3f} R {:.3f}; faded recall {:.3f}, false flags {:.3f}".format(
            tot["tp"] / max(tot["tp"] + tot["fp"], 1), tot["tp"] / max(tot["reference"], 1),
            ptot["tp"] / max(ptot["tp"] + ptot["fp"], 1), ptot["tp"] / max(ptot["reference"], 1),
            ftot["flagged"] / max(ftot["reference"], 1), ftot["healthy_flagged"] / max(ftot["healthy"], 1)))
    if args.json:
        os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
        with open(args.json, "w") as fh:
            json.dump(results, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
