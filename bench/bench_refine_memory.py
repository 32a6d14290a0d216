#!/usr/bin/env python3
"""Benchmark core.refine's peak memory as the drive grows: block by block vs one index.

The drive is the test sign scene (tests/helpers/signscene.py, 160 m of road with its
stations and detections) repeated 1x, 3x, 10x along the road (as
bench_projection_memory.py), written to one LAS file; the candidates are projected once
(``project_detections``, block by block) and saved. Each case then refines them in a child
process that prints its peak RSS (VmHWM) and time:

* ``blocks``: ``refine_signs(candidates, las_path)``, the plugin's way: blocks of
  ``DEFAULT_BLOCK_M`` (150 m) along the drive, one block's points held at a time;
* ``one-index``: ``block_m=inf``, the earlier way: the points near every candidate of the
  drive in one ``TiledIndex``.

Both give the same signs (checked here). Ratios are to the 1x case of each way.

    .venv/bin/python bench/bench_refine_memory.py [--copies 1 3 10] [--keep DIR]
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


def child(way: str, las_path: str, candidates_path: str) -> None:
    """Run one case and print its figures as JSON (called in a fresh process)."""
    _import_package()
    from roadsigns.core import projection as P
    from roadsigns.core import refine as R

    with open(candidates_path) as f:
        cand = P.ProjectionResult.from_records(json.load(f))
    before = peak_rss_mb()
    t0 = time.perf_counter()
    block_m = R.DEFAULT_BLOCK_M if way == "blocks" else float("inf")
    result = R.refine_signs(cand, las_path, block_m=block_m)
    seconds = time.perf_counter() - t0
    signs = [[s.klass, round(s.x, 3), round(s.y, 3), round(s.z, 3), s.n_points] for s in result.signs]
    print(json.dumps({"peak_mb": peak_rss_mb(), "baseline_mb": before, "seconds": seconds,
                      "signs": signs}))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--copies", type=int, nargs="+", default=[1, 3, 10], help="drive lengths, in scenes")
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

    from roadsigns.core import projection as P

    folder = args.keep or tempfile.mkdtemp(prefix="bench-refine-memory-")
    os.makedirs(folder, exist_ok=True)
    rows = []
    for copies in args.copies:
        scene = drive(copies)
        las_path = os.path.join(folder, f"drive_x{copies}.las")
        cand_path = os.path.join(folder, f"candidates_x{copies}.json")
        signscene.write_las(scene, las_path)
        cand = P.project_detections(P.Detections.from_records(scene.detections), las_path)
        with open(cand_path, "w") as f:
            json.dump(cand.records(), f)
        figures = {}
        for way in args.ways:
            out = subprocess.run([sys.executable, __file__, "--child", way, las_path, cand_path],
                                 capture_output=True, text=True, check=True)
            figures[way] = json.loads(out.stdout.strip().splitlines()[-1])
        same = len(figures) < 2 or figures["blocks"]["signs"] == figures["one-index"]["signs"]
        n_signs = len(next(iter(figures.values()))["signs"])
        rows.append((copies, len(scene.xyz_world), len(cand), n_signs, figures, same))
    print(f"{'drive':>6} {'points':>10} {'candidates':>10} {'signs':>6} | "
          + " | ".join(f"{way + ' MB':>12} {'x':>5} {'net MB':>6} {'x':>5} {'s':>6}" for way in args.ways)
          + " | same signs")
    first = rows[0][4]
    for copies, n_points, n_cand, n_signs, figures, same in rows:
        net = {w: figures[w]["peak_mb"] - figures[w]["baseline_mb"] for w in args.ways}
        net0 = {w: first[w]["peak_mb"] - first[w]["baseline_mb"] for w in args.ways}
        cells = [f"{figures[w]['peak_mb']:>12.0f} {figures[w]['peak_mb'] / first[w]['peak_mb']:>5.2f} "
                 f"{net[w]:>6.0f} {net[w] / max(net0[w], 1e-9):>5.2f} {figures[w]['seconds']:>6.1f}"
                 for w in args.ways]
        print(f"{copies:>5}x {n_points:>10d} {n_cand:>10d} {n_signs:>6d} | " + " | ".join(cells) + f" | {same}")
    print("peak RSS (VmHWM) of a fresh process per case, imports included; net: above the RSS after "
          "the imports and reading the candidates; x: ratio to the first drive of the same way.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
