#!/usr/bin/env python3
"""Benchmark LAZ -> crop -> ground -> LAZ (built-in engine, chunked I/O) against a plain
laspy chunked read + write of the same file.

Each stage runs in its own subprocess so its peak memory (``ru_maxrss``) is its own.
Prints points per second, the ratio of the ground filter's time to the plain copy's,
and peak memory per stage.

    .venv/bin/python bench/bench_ground.py --points 5000000 --method csf
    .venv/bin/python bench/bench_ground.py --input big.laz --corridor-m 15
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


def _import_package():
    """Make the checkout importable as ``roadsigns``."""
    sys.path.insert(0, REPO)
    from devtools import import_roadsigns
    import_roadsigns()


def _peak_rss_mb() -> float:
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    return kb / 1024.0 if sys.platform != "darwin" else kb / 2**20


# ----------------------------------------------------------------------------- stages

def stage_generate(path: str, n_points: int, seed: int) -> dict:
    """Write a long straight road (60 m segments of the test scene, along +x) as LAZ,
    segment by segment, never holding more than one segment."""
    import laspy
    import numpy as np
    import pyproj

    sys.path.insert(0, os.path.join(REPO, "tests"))
    from helpers import cloudgen

    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales = np.array([0.001, 0.001, 0.001])
    header.offsets = np.array(cloudgen.ORIGIN)
    header.add_crs(pyproj.CRS.from_epsg(25833))
    written, k = 0, 0
    t0 = time.perf_counter()
    with laspy.open(path, mode="w", header=header, do_compress=True) as writer:
        while written < n_points:
            origin = (cloudgen.ORIGIN[0] + 60.0 * k, cloudgen.ORIGIN[1], cloudgen.ORIGIN[2])
            s = cloudgen.road_scene(length_m=60.0, slope=0.0, seed=seed + k, origin=origin)
            m = min(len(s), n_points - written)
            rec = laspy.ScaleAwarePointRecord.zeros(m, header=header)
            rec.x, rec.y, rec.z = s.xyz[:m, 0], s.xyz[:m, 1], s.xyz[:m, 2]
            rec.return_number = s.return_number[:m]
            rec.number_of_returns = s.number_of_returns[:m]
            rec.intensity = s.intensity[:m]
            rec.gps_time = s.gps_time[:m] + 6.0 * k
            writer.write_points(rec)
            written += m
            k += 1
    return {"points": written, "seconds": time.perf_counter() - t0,
            "length_m": 60.0 * k, "peak_rss_mb": _peak_rss_mb()}


def stage_baseline(src: str, dst: str, chunk_points: int) -> dict:
    """Plain laspy: read in chunks, write the chunks (LAZ -> LAZ)."""
    import laspy

    t0 = time.perf_counter()
    n = 0
    backends = laspy.LazBackend.detect_available()
    with laspy.open(src, laz_backend=backends) as reader:
        with laspy.open(dst, mode="w", header=reader.header, do_compress=True,
                        laz_backend=backends) as writer:
            for chunk in reader.chunk_iterator(chunk_points):
                writer.write_points(chunk)
                n += len(chunk)
    return {"points": n, "seconds": time.perf_counter() - t0, "peak_rss_mb": _peak_rss_mb()}


def stage_ground(src: str, dst: str, method: str, corridor_m: float,
                 chunk_points: int, trajectory: str = "-") -> dict:
    """Our run: LAZ -> corridor crop -> ground (built-in, tiled) -> LAZ."""
    import numpy as np
    _import_package()
    from shapely.geometry import LineString

    from roadsigns.core import ground, pointcloud

    header = pointcloud.read_header(src)
    crop = None
    if corridor_m > 0 and trajectory != "-":  # corridor around the vehicle's path
        from roadsigns.core.tables import read_table
        path = read_table(trajectory, ("x", "y"), numeric=("x", "y"))
        crop = [LineString(np.column_stack([path["x"], path["y"]])[::10]).buffer(corridor_m)]
    elif corridor_m > 0:  # the generated straight road: corridor around its centre line
        y_mid = 0.5 * (header.mins[1] + header.maxs[1])
        crop = [LineString([(header.mins[0], y_mid),
                            (header.maxs[0], y_mid)]).buffer(corridor_m)]
    t0 = time.perf_counter()
    res = ground.run_ground_filter(src, dst, method=method, engine="builtin",
                                   crop_polygons=crop, chunk_points=chunk_points)
    return {"points": int(header.point_count), "points_out": res.n_output,
            "ground": res.n_ground, "seconds": time.perf_counter() - t0,
            "peak_rss_mb": _peak_rss_mb()}


# ----------------------------------------------------------------------------- driver

def _run_stage(args: list) -> dict:
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "--stage"] + args,
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--points", type=int, default=5_000_000, help="size of the generated cloud")
    p.add_argument("--input", help="use this LAZ instead of generating one")
    p.add_argument("--method", choices=["csf", "smrf"], default="csf")
    p.add_argument("--corridor-m", type=float, default=12.0,
                   help="half width of the crop corridor around the centre line (0 = no crop)")
    p.add_argument("--trajectory", help="with --input: crop a corridor around this trajectory "
                   "CSV (projected x, y in the cloud's CRS) instead of a straight centre line")
    p.add_argument("--chunk-points", type=int, default=1_000_000)
    p.add_argument("--out-dir", default=os.path.join(HERE, "out"))
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--keep", action="store_true", help="keep the generated/output files")
    p.add_argument("--stage", nargs="+", help=argparse.SUPPRESS)
    args = p.parse_args(argv)

    if args.stage:  # child process
        name, rest = args.stage[0], args.stage[1:]
        if name == "generate":
            result = stage_generate(rest[0], int(rest[1]), int(rest[2]))
        elif name == "baseline":
            result = stage_baseline(rest[0], rest[1], int(rest[2]))
        else:
            result = stage_ground(rest[0], rest[1], rest[2], float(rest[3]), int(rest[4]), rest[5])
        print(json.dumps(result))
        return 0

    os.makedirs(args.out_dir, exist_ok=True)
    src = args.input
    made = False
    if not src:
        src = os.path.join(args.out_dir, f"road_{args.points}.laz")
        if not os.path.exists(src):
            gen = _run_stage(["generate", src, str(args.points), str(args.seed)])
            made = True
            print(f"generated {gen['points']:,} points ({gen['length_m']:.0f} m of road) "
                  f"in {gen['seconds']:.1f} s, {os.path.getsize(src) / 2**20:.0f} MiB LAZ")
    base_out = os.path.join(args.out_dir, "baseline.laz")
    ground_out = os.path.join(args.out_dir, f"ground_{args.method}.laz")
    base = _run_stage(["baseline", src, base_out, str(args.chunk_points)])
    grd = _run_stage(["ground", src, ground_out, args.method, str(args.corridor_m),
                      str(args.chunk_points), args.trajectory or "-"])
    n = base["points"]
    print(f"input: {src} ({n:,} points)")
    print(f"{'stage':<28}{'seconds':>9}{'points/s':>14}{'peak RSS MB':>13}")
    print(f"{'laspy chunked read+write':<28}{base['seconds']:>9.1f}"
          f"{n / base['seconds']:>14,.0f}{base['peak_rss_mb']:>13.0f}")
    print(f"{'crop+ground ' + args.method + ' (built-in)':<28}{grd['seconds']:>9.1f}"
          f"{n / grd['seconds']:>14,.0f}{grd['peak_rss_mb']:>13.0f}")
    print(f"ratio ground/baseline time: {grd['seconds'] / base['seconds']:.2f}  "
          f"(kept {grd['points_out']:,} points, {grd['ground']:,} ground)")
    print(json.dumps({"points": n, "method": args.method, "baseline": base, "ground": grd,
                      "ratio": grd["seconds"] / base["seconds"]}))
    if not args.keep:
        for path in (base_out, ground_out) + ((src,) if made else ()):
            if os.path.exists(path):
                os.unlink(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
