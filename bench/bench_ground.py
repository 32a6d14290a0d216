#!/usr/bin/env python3
"""Benchmark the ground filter's engines: the built-in engine, PDAL's ``pdal`` application
and PDAL's Python bindings, with CSF and SMRF, on the whole cloud and on a crop corridor,
in one run; plus a plain laspy chunked read + write of the same file as a yardstick.

Every run is LAZ -> (crop) -> ground -> LAZ through ``run_ground_filter`` (what the
algorithm calls) in a subprocess of its own, so that its peak memory is its own (the
``pdal`` process's counted too). Prints wall seconds, points per second (points read),
CPU seconds, peak memory, the points kept and classified ground, the agreement of each
PDAL run with the built-in run of the same method and crop, and the time ratio PDAL /
built-in. Parameters are the algorithm's defaults (threshold 0.2 m, 0.5 m cells), classes
reset, as a user of ``roadsigns:groundfilter`` gets them.

The built-in engine works a cloud larger than a block (512 m) block by block; ``--block-m 0``
runs it with one grid over the whole cloud, as before 3 December.

PDAL: ``--pdal-executable`` (default ``../shared/tools/pdal-2.9.2/bin/pdal``, else
ROADSIGNS_PDAL_EXECUTABLE, else PATH or QGIS's bin folder) and the ``pdal`` module of this
Python (``make setup`` installs the bindings from ``../shared/tools/pdal-2.9.2``); an engine
that is not there is left out, saying so.

    .venv/bin/python bench/bench_ground.py --points 2000000
    .venv/bin/python -m devtools.scenegen --preset default --seed 1 --no-panoramas --no-masks \\
        --out bench/out/scene_default
    .venv/bin/python bench/bench_ground.py --input bench/out/scene_default/cloud.laz \\
        --trajectory bench/out/scene_default/trajectory.csv --corridor-m 20
"""
from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import time

if os.path.isdir("/usr/share/proj"):  # pyproj inside a venv looks under the venv otherwise
    os.environ.setdefault("PROJ_DATA", "/usr/share/proj")
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
SHARED_PDAL = os.path.normpath(os.path.join(REPO, "..", "shared", "tools", "pdal-2.9.2", "bin", "pdal"))
ENGINES = ("builtin", "pdal-cli", "pdal-python")
METHODS = ("csf", "smrf")
CROPS = ("whole", "corridor")

sys.path.insert(0, HERE)
from bench_projection_memory import peak_rss_mb  # noqa: E402  (the bench folder is not a package)


def _import_package():
    """Make the checkout importable as ``roadsigns``."""
    sys.path.insert(0, REPO)
    from devtools import import_roadsigns
    import_roadsigns()


def _usage() -> dict:
    """Peak memory (this process, or the ``pdal`` child it waited for) and CPU time."""
    me = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    scale = 1024.0 if sys.platform != "darwin" else 2.0 ** 20  # KiB on Linux
    # this process's own peak (VmHWM): ru_maxrss would start at the parent's size at fork
    return {"peak_rss_mb": max(peak_rss_mb(), kids.ru_maxrss / scale),
            "cpu_s": me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime}


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
    return {"points": written, "seconds": time.perf_counter() - t0, "length_m": 60.0 * k}


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
    return {"points": n, "seconds": time.perf_counter() - t0, **_usage()}


def _corridor(src: str, corridor_m: float, trajectory: str):
    """The crop corridor: ``corridor_m`` around the trajectory (every 10th position), or
    around the centre line of the generated straight road."""
    import numpy as np
    from shapely.geometry import LineString

    from roadsigns.core import pointcloud

    if trajectory:
        from roadsigns.core.tables import read_table
        path = read_table(trajectory, ("x", "y"), numeric=("x", "y"))
        return [LineString(np.column_stack([path["x"], path["y"]])[::10]).buffer(corridor_m)]
    header = pointcloud.read_header(src)
    y_mid = 0.5 * (header.mins[1] + header.maxs[1])
    return [LineString([(header.mins[0], y_mid), (header.maxs[0], y_mid)]).buffer(corridor_m)]


def stage_ground(spec: dict) -> dict:
    """One run: LAZ -> (corridor) -> ground -> LAZ with one engine and method."""
    _import_package()
    from roadsigns.core import ground

    crop = _corridor(spec["src"], spec["corridor_m"], spec["trajectory"]) \
        if spec["crop"] == "corridor" else None
    params = ground.CsfParams(resolution=spec["cell"], threshold=spec["threshold"]) \
        if spec["method"] == "csf" else ground.SmrfParams(cell=spec["cell"], threshold=spec["threshold"])
    t0 = time.perf_counter()
    res = ground.run_ground_filter(
        spec["src"], spec["dst"], method=spec["method"],
        engine="builtin" if spec["engine"] == "builtin" else "pdal", params=params,
        crop_polygons=crop, reset_classes=True, chunk_points=spec["chunk_points"],
        pdal_executable=spec["pdal_executable"] if spec["engine"] == "pdal-cli" else None,
        **({} if spec.get("block_m", -1) < 0 else {"block_m": spec["block_m"] or None}))
    seconds = time.perf_counter() - t0
    if res.engine != spec["engine"]:
        raise SystemExit(f"asked for {spec['engine']}, {res.engine} ran")
    return {"points": res.n_input, "points_out": res.n_output, "ground": res.n_ground,
            "seconds": seconds, **_usage()}


# ----------------------------------------------------------------------------- driver

def _run_stage(args: list) -> dict:
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "--stage"] + args,
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _points(path: str):
    """The stored X, Y, Z and the classification of a LAS/LAZ file, read in chunks, in the
    order of their coordinates."""
    import laspy
    import numpy as np

    parts = []
    with laspy.open(path, laz_backend=laspy.LazBackend.detect_available()) as reader:
        for chunk in reader.chunk_iterator(1_000_000):
            parts.append(np.column_stack([chunk.X, chunk.Y, chunk.Z, chunk.classification]))
    points = np.concatenate(parts) if parts else np.zeros((0, 4), np.int64)
    # sorted by X, Y, Z: the built-in engine writes a cloud larger than a block block by block
    return points[np.lexsort((points[:, 2], points[:, 1], points[:, 0]))]


def _pdal_executable(given):
    if given:
        return given
    if os.access(SHARED_PDAL, os.X_OK):
        return SHARED_PDAL
    if os.environ.get("ROADSIGNS_PDAL_EXECUTABLE"):
        return os.environ["ROADSIGNS_PDAL_EXECUTABLE"]
    _import_package()
    from roadsigns.core.ground import find_pdal_executable
    return find_pdal_executable()


def _available_engines(wanted, executable):
    engines = []
    for engine in wanted:
        if engine == "pdal-cli" and not executable:
            print("pdal-cli left out: no pdal executable found")
            continue
        if engine == "pdal-python":
            try:
                import pdal
                print(f"pdal-python: the bindings {pdal.__version__} on PDAL {pdal.info.version}")
            except Exception as e:
                print(f"pdal-python left out: the pdal module does not import ({e})")
                continue
        if engine == "pdal-cli":
            version = subprocess.run([executable, "--version"], capture_output=True, text=True).stdout
            found = re.search(r"pdal (\d[\w.]*)", version)
            print(f"pdal-cli: {executable} (PDAL {found.group(1) if found else 'version unknown'})")
        engines.append(engine)
    return engines


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--points", type=int, default=5_000_000, help="size of the generated cloud")
    p.add_argument("--input", help="use this LAZ instead of generating one")
    p.add_argument("--methods", default=",".join(METHODS), help="csf,smrf")
    p.add_argument("--engines", default=",".join(ENGINES), help="builtin,pdal-cli,pdal-python")
    p.add_argument("--crops", default=",".join(CROPS), help="whole,corridor")
    p.add_argument("--corridor-m", type=float, default=12.0,
                   help="half width of the crop corridor around the centre line or the trajectory")
    p.add_argument("--trajectory", help="with --input: the corridor follows this trajectory CSV "
                   "(projected x, y in the cloud's CRS) instead of a straight centre line")
    p.add_argument("--threshold", type=float, default=0.2, help="ground threshold (m), the algorithm's default")
    p.add_argument("--cell", type=float, default=0.5, help="cloth resolution / cell (m), the algorithm's default")
    p.add_argument("--pdal-executable", help="the pdal application (default: ../shared/tools/pdal-2.9.2)")
    p.add_argument("--no-baseline", action="store_true", help="skip the plain laspy copy")
    p.add_argument("--chunk-points", type=int, default=1_000_000)
    p.add_argument("--block-m", type=float, default=-1.0,
                   help="the built-in engine's block side (m); 0: one grid over the whole cloud; default: the engine's")
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
            result = stage_ground(json.loads(rest[0]))
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
    executable = _pdal_executable(args.pdal_executable)
    engines = _available_engines([e for e in args.engines.split(",") if e], executable)
    methods = [m for m in args.methods.split(",") if m]
    crops = [c for c in args.crops.split(",") if c]
    print(f"input: {src}; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")

    base = None
    if not args.no_baseline:
        base_out = os.path.join(args.out_dir, "baseline.laz")
        base = _run_stage(["baseline", src, base_out, str(args.chunk_points)])
        if not args.keep:
            os.unlink(base_out)
        print(f"laspy chunked read + write: {base['seconds']:.1f} s, "
              f"{base['points'] / base['seconds']:,.0f} points/s, {base['peak_rss_mb']:.0f} MB")

    header = (f"{'method':<6} {'crop':<9} {'engine':<12} {'wall s':>7} {'points/s':>11} {'CPU s':>7} "
              f"{'peak MB':>8} {'kept':>10} {'ground':>10} {'agreement':>10} {'PDAL/built-in':>14}")
    print(header)
    rows = []
    for method in methods:
        for crop in crops:
            reference = None
            for engine in engines:
                dst = os.path.join(args.out_dir, f"ground_{method}_{crop}_{engine}.laz")
                spec = {"src": src, "dst": dst, "method": method, "engine": engine, "crop": crop,
                        "corridor_m": args.corridor_m, "trajectory": args.trajectory or "",
                        "threshold": args.threshold, "cell": args.cell,
                        "chunk_points": args.chunk_points, "pdal_executable": executable,
                        "block_m": args.block_m}
                r = _run_stage(["ground", json.dumps(spec)])
                r.update(method=method, crop=crop, engine=engine)
                points = _points(dst) if len(engines) > 1 else None   # compared with PDAL's only
                if engine == "builtin":
                    reference = (r, points)
                elif reference is not None:
                    ref, ref_points = reference
                    same = points.shape == ref_points.shape and (points[:, :3] == ref_points[:, :3]).all()
                    r["same_points_kept"] = bool(same)
                    r["agreement"] = float(((points[:, 3] == 2) == (ref_points[:, 3] == 2)).mean()) \
                        if same else None
                    r["ratio"] = r["seconds"] / ref["seconds"]
                if not args.keep:
                    os.unlink(dst)
                rows.append(r)
                agreement = "" if engine == "builtin" else "other points" if r.get("agreement") is None \
                    else f"{r['agreement']:.3%}"
                ratio = "" if "ratio" not in r else f"{r['ratio']:.2f}"
                print(f"{method:<6} {crop:<9} {engine:<12} {r['seconds']:>7.1f} "
                      f"{r['points'] / r['seconds']:>11,.0f} {r['cpu_s']:>7.1f} {r['peak_rss_mb']:>8.0f} "
                      f"{r['points_out']:>10,} {r['ground']:>10,} {agreement:>10} {ratio:>14}", flush=True)
    print(json.dumps({"input": src, "threshold": args.threshold, "cell": args.cell,
                      "corridor_m": args.corridor_m, "baseline": base, "runs": rows}))
    if made and not args.keep:
        os.unlink(src)
    return 0


if __name__ == "__main__":
    sys.exit(main())
