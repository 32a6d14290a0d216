#!/usr/bin/env python3
"""``findsignsincloud`` (``core.cloudsigns``) as the drive grows, and with one or two threads.

On one ground-classified cloud of a generated drive (by default ``bench_drive``'s
``drive1k``: run ``bench/bench_drive.py --preset drive1k`` first), the finder runs on the
first ``L`` metres of the drive's track for each ``--lengths`` (the whole cloud is read each
time; only what lies along the track is kept), each run in its own subprocess so that its
peak memory is its own, with ``window_threads`` 1 and 2. Printed per run: wall time, CPU
time, peak RSS, signs and poles found, the largest window in points; then the peak against
the shortest drive's and the time with two threads against one, in the same run.

    .venv/bin/python bench/bench_cloudsigns_memory.py
    .venv/bin/python bench/bench_cloudsigns_memory.py --lengths 100 1000 --threads 2 --json bench/out/csmem.json
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
DEFAULT_DRIVE = os.path.join(HERE, "out", "drive-drive1k-4")


def _peak_mb() -> float:
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def track_of(poses_csv: str, length_m: float):
    """The panorama centres (x, y, z) of ``poses.csv`` up to ``length_m`` of drive."""
    import numpy as np
    with open(poses_csv, newline="") as f:
        xyz = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in csv.DictReader(f)])
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(xyz[:, :2], axis=0), axis=1))]
    return xyz[s <= length_m]


def run_one(cloud: str, poses: str, length_m: float, threads: int) -> dict:
    sys.path.insert(0, REPO)
    from devtools import import_roadsigns
    import_roadsigns()
    from roadsigns.core.cloudsigns import CloudSignParams, find_signs_in_cloud
    from roadsigns.core.drivewindows import Track

    track = track_of(poses, length_m)
    cpu0, t0 = time.process_time(), time.perf_counter()
    res = find_signs_in_cloud(cloud, Track.from_polyline(track), CloudSignParams(window_threads=threads))
    return {"length_m": length_m, "threads": threads, "wall_s": round(time.perf_counter() - t0, 2),
            "cpu_s": round(time.process_time() - cpu0, 2), "peak_rss_mb": round(_peak_mb(), 1),
            "signs": len(res.signs), "poles": len(res.poles), "points_read": res.n_points,
            "points_kept": res.n_candidates, "windows": res.n_windows,
            "max_window_points": res.max_window_points}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drive", default=DEFAULT_DRIVE, help="a bench_drive folder (chain/ground.laz, poses.csv)")
    ap.add_argument("--cloud", help="the ground-classified cloud (default DRIVE/chain/ground.laz)")
    ap.add_argument("--lengths", type=float, nargs="+", default=[100.0, 1100.0],
                    help="metres of drive (the whole track when longer)")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--json")
    ap.add_argument("--run-one", nargs=4, help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.run_one:
        cloud, poses, length, threads = a.run_one
        print(json.dumps(run_one(cloud, poses, float(length), int(threads))))
        return 0
    cloud = a.cloud or os.path.join(a.drive, "chain", "ground.laz")
    poses = os.path.join(a.drive, "poses.csv")
    if not os.path.isfile(cloud):
        sys.exit(f"{cloud} is missing: run bench/bench_drive.py --preset drive1k first")
    load0 = os.getloadavg()[0]
    runs = []
    for length in a.lengths:
        for threads in a.threads:
            out = subprocess.run([sys.executable, os.path.abspath(__file__), "--run-one", cloud, poses,
                                  str(length), str(threads)], capture_output=True, text=True, check=True)
            rec = json.loads(out.stdout.strip().splitlines()[-1])
            runs.append(rec)
            print("{length_m:>7.0f} m  {threads} thread(s)  {wall_s:>7.1f} s wall  {cpu_s:>7.1f} s CPU  "
                  "peak {peak_rss_mb:>6.0f} MB  {signs:>3} signs  {poles:>3} poles  {points_kept:>11,} points kept  "
                  "{windows:>3} windows  largest {max_window_points:>9,} points".format(**rec), flush=True)
    print(f"load average {load0:.2f} before, {os.getloadavg()[0]:.2f} after")
    base = {t: next(r for r in runs if r["threads"] == t) for t in a.threads}
    for r in runs:
        b = base[r["threads"]]
        r["peak_vs_shortest"] = round(r["peak_rss_mb"] / b["peak_rss_mb"], 3)
        one = next((x for x in runs if x["length_m"] == r["length_m"] and x["threads"] == 1), None)
        if one is not None:
            r["time_vs_one_thread"] = round(r["wall_s"] / one["wall_s"], 3)
        print("{:>7.0f} m  {} thread(s): peak x{:.2f} of the shortest drive's; time x{} of one thread's".format(
            r["length_m"], r["threads"], r["peak_vs_shortest"], r.get("time_vs_one_thread", "-")))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"cloud": cloud, "runs": runs, "load_average_before": load0}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
