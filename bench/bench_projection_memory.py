#!/usr/bin/env python3
"""Benchmark core.projection's peak memory as the drive grows: block by block vs one index.

The drive is the test sign scene (tests/helpers/signscene.py, 160 m of road with its
stations and detections) repeated 1x, 3x, 9x along the road, detections included, so
cloud and detections grow together as on a longer drive. Each case runs in a child
process that prints its peak RSS (VmHWM) and time:

* ``blocks``: ``project_detections(detections, las_path)``, the plugin's way: one
  streaming read spooled to disk along the drive, then one block of drive at a time;
* ``one-index``: the earlier way, every point under the frusta of the whole drive in one
  ``TiledIndex`` (``TiledIndex.from_las`` cropped to the frusta), then the search.

Both give the same candidates (checked here). Ratios are to the 1x case of each way.

    .venv/bin/python bench/bench_projection_memory.py [--copies 1 3 9] [--keep DIR]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
SHIFT_M = (160.0, 0.0, 1.6)
sys.path.insert(0, HERE)
from bench_projection import _import_package  # noqa: E402  (the bench folder is not a package)


def drive(copies: int):
    """The scene repeated ``copies`` times along +x, with every copy's detections."""
    import numpy as np
    from helpers import signscene

    base = signscene.make_scene(seed=1)
    shift = np.array(SHIFT_M)
    xyz = np.concatenate([base.xyz_world + k * shift for k in range(copies)])
    detections = []
    for k in range(copies):
        for record in base.detections:
            moved = dict(record)
            moved["x"], moved["y"], moved["z"] = (record[c] + k * shift[i] for i, c in enumerate("xyz"))
            moved["det_id"] = record["det_id"] + 100_000 * k
            moved["station_id"] = record["station_id"] + 100_000 * k
            detections.append(moved)
    scene = signscene.SignScene(xyz, np.tile(base.classification, copies), np.tile(base.intensity, copies),
                                base.station_centre_world, base.station_q_wxyz, base.station_images,
                                base.panels, detections)
    return scene


def peak_rss_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def child(way: str, las_path: str, detections_path: str) -> None:
    """Run one case and print its figures as JSON (called in a fresh process)."""
    _import_package()
    import shapely

    from roadsigns.core import projection as P
    from roadsigns.core.pointcloud import CropRegion, TiledIndex

    with open(detections_path) as f:
        det = P.Detections.from_records(json.load(f))
    before = peak_rss_mb()
    t0 = time.perf_counter()
    if way == "blocks":
        result = P.project_detections(det, las_path)
    else:
        frusta = P.Frusta.build(det, P.DEFAULT_MAX_RANGE_M, 0.25, 0.1)
        index = TiledIndex.from_las(las_path, CropRegion(shapely.union_all(frusta.footprints())),
                                    dimensions=("intensity", "classification"), tile_size_m=5.0)
        result = P.project_detections(det, index)
    seconds = time.perf_counter() - t0
    print(json.dumps({"peak_mb": peak_rss_mb(), "baseline_mb": before, "seconds": seconds,
                      "status": result.status, "xyz": result.xyz_world.round(4).tolist()}))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--copies", type=int, nargs="+", default=[1, 3, 9], help="drive lengths, in scenes")
    parser.add_argument("--keep", help="folder for the LAS files (default: a temporary one)")
    parser.add_argument("--ways", nargs="+", default=["blocks", "one-index"], choices=["blocks", "one-index"],
                        help="which ways to run (default both, and their results compared)")
    parser.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        child(*args.child)
        return 0
    _import_package()
    from helpers import signscene

    folder = args.keep or tempfile.mkdtemp(prefix="bench-projection-memory-")
    rows = []
    for copies in args.copies:
        scene = drive(copies)
        las_path = os.path.join(folder, f"drive_x{copies}.las")
        det_path = os.path.join(folder, f"detections_x{copies}.json")
        signscene.write_las(scene, las_path)
        with open(det_path, "w") as f:
            json.dump(scene.detections, f)
        figures = {}
        for way in args.ways:
            out = subprocess.run([sys.executable, __file__, "--child", way, las_path, det_path],
                                 capture_output=True, text=True, check=True)
            figures[way] = json.loads(out.stdout.strip().splitlines()[-1])
        same = len(figures) < 2 or (figures["blocks"]["status"] == figures["one-index"]["status"]
                                    and figures["blocks"]["xyz"] == figures["one-index"]["xyz"])
        rows.append((copies, len(scene.xyz_world), len(scene.detections), figures, same))
    print(f"{'drive':>6} {'points':>10} {'detections':>10} | "
          + " | ".join(f"{way + ' MB':>12} {'x':>5} {'s':>6}" for way in args.ways) + " | same result")
    first = rows[0][3]
    for copies, n_points, n_det, figures, same in rows:
        cells = [f"{figures[w]['peak_mb']:>12.0f} {figures[w]['peak_mb'] / first[w]['peak_mb']:>5.2f} "
                 f"{figures[w]['seconds']:>6.1f}" for w in args.ways]
        print(f"{copies:>5}x {n_points:>10d} {n_det:>10d} | " + " | ".join(cells) + f" | {same}")
    print("peak RSS (VmHWM) of a fresh process per case, imports included; x: ratio to the first drive "
          "of the same way.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
