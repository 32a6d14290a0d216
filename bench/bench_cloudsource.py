#!/usr/bin/env python3
"""Benchmark reading a point cloud as users receive it (core/cloudsource.py): one LAZ, a
folder of LAZ tiles, a COPC file; one block of drive read from each, and the projection of a
whole drive from the file and from the tiles.

The drive is the test sign scene (tests/helpers/signscene.py) repeated along the road, as in
bench_projection_memory.py, written as one LAZ, as 50 m tiles (a folder) and, when PDAL's
Python module is there, as COPC. Each case runs in a fresh process that prints its peak RSS
(VmHWM), time and points read:

* ``block-file`` / ``block-tiles`` / ``block-copc``: ``CloudSource.index`` of one 150 m block of
  drive (the box of its road): the file is read whole, the tiles under the block only, the
  COPC file by the octree nodes under it;
* ``project-file`` / ``project-tiles``: ``project_detections`` over the whole drive.

    .venv/bin/python bench/bench_cloudsource.py [--copies 9] [--keep DIR]
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
sys.path.insert(0, HERE)
from bench_projection import _import_package  # noqa: E402  (the bench folder is not a package)
from bench_projection_memory import drive, peak_rss_mb  # noqa: E402

BLOCK_M = 150.0
TILE_M = 50.0


def child(case: str, cloud: str, detections_path: str) -> None:
    _import_package()
    import numpy as np
    import shapely

    from roadsigns.core import projection as P
    from roadsigns.core.cloudsource import open_cloud
    from roadsigns.core.pointcloud import CropRegion, TiledIndex

    before = peak_rss_mb()
    t0 = time.perf_counter()
    source = open_cloud(cloud)
    read = []
    if case.startswith("block"):
        x0, y0, _, _, _, _ = source.bounds
        region = CropRegion(shapely.box(x0 + 2 * BLOCK_M, y0, x0 + 3 * BLOCK_M, y0 + 60.0))

        def counted():  # what CloudSource.index reads, counted
            for i, c in source.iter_indexed_chunks(area=region.geometry):
                read.append(len(c))
                yield i, c

        index = TiledIndex.from_chunks(counted(), region, ("intensity", "classification"), 5.0)
        result = {"kept": len(index), "read": int(sum(read))}
    else:
        with open(detections_path) as f:
            det = P.Detections.from_records(json.load(f))
        res = P.project_detections(det, source)
        result = {"ok": int(sum(s == "ok" for s in res.status)), "xyz": np.round(res.xyz_world, 3).tolist()}
    result.update(peak_mb=peak_rss_mb(), baseline_mb=before, seconds=time.perf_counter() - t0)
    print(json.dumps(result))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--copies", type=int, default=9, help="drive length, in scenes of 160 m")
    parser.add_argument("--keep", help="folder for the clouds (default: a temporary one)")
    parser.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        child(*args.child)
        return 0
    _import_package()
    import laspy
    import numpy as np
    from helpers import signscene
    from helpers.cloudtiles import split_into_tiles

    folder = args.keep or tempfile.mkdtemp(prefix="bench-cloudsource-")
    scene = drive(args.copies)
    las = os.path.join(folder, "drive.las")
    signscene.write_las(scene, las)
    laz = os.path.join(folder, "drive.laz")
    laspy.read(las).write(laz)
    det_path = os.path.join(folder, "detections.json")
    with open(det_path, "w") as f:
        json.dump(scene.detections, f)
    tiles = split_into_tiles(laz, os.path.join(folder, "tiles"), size_m=TILE_M)
    clouds = {"file": laz, "tiles": os.path.join(folder, "tiles")}
    try:
        import pdal

        copc = os.path.join(folder, "drive.copc.laz")
        pdal.Pipeline(json.dumps({"pipeline": [laz, {"type": "writers.copc", "filename": copc}]})).execute()
        clouds["copc"] = copc
    except Exception as e:  # no PDAL, or one without writers.copc
        print(f"(no COPC case: {e})")
    rows = []
    for case in [f"block-{k}" for k in clouds] + ["project-file", "project-tiles"]:
        cloud = clouds[case.split("-", 1)[1]]
        out = subprocess.run([sys.executable, __file__, "--child", case, cloud, det_path],
                             capture_output=True, text=True, check=True)
        rows.append((case, json.loads(out.stdout.strip().splitlines()[-1])))
    print(f"drive {args.copies} x 160 m, {len(scene.xyz_world)} points, {len(scene.detections)} detections; "
          f"{len(tiles)} tiles of {TILE_M:.0f} m; block {BLOCK_M:.0f} m")
    print(f"{'case':>14} {'peak MB':>8} {'s':>6} {'points read':>12} {'kept':>8}")
    for case, r in rows:
        print(f"{case:>14} {r['peak_mb']:>8.0f} {r['seconds']:>6.2f} {r.get('read', ''):>12} "
              f"{r.get('kept', r.get('ok', '')):>8}")
    projected = {case: r["xyz"] for case, r in rows if case.startswith("project")}
    a, b = (np.array(v, dtype=float) for v in projected.values())
    print("projection from the tiles = from the file (within 2 mm):",
          bool(np.all(np.isnan(a) == np.isnan(b)) and np.nanmax(np.abs(a - b)) <= 0.002))
    print("peak RSS (VmHWM) of a fresh process per case, imports included.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
