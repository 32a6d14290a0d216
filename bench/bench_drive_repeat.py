#!/usr/bin/env python3
"""Each cloud stage alone on a drive and on the same drive repeated N times (issue 14: "a
drive ten times longer needs no more memory than one of the same kind").

The drive is ``bench_drive``'s (``drive1k`` by default: run ``bench/bench_drive.py --preset
drive1k`` first, which leaves the chain's layers and ground-classified cloud in
``DRIVE/chain``). Its copies are laid ``--spacing`` metres apart along X, each as the drive
itself, so the long drive is N times the same work:

- the cloud: ``chain/ground.laz`` as a folder of N tiles, each the same file with its
  header's X offset (and X bounds) moved by k x spacing; the points are not rewritten, so
  making 9 copies of 38 M points takes seconds. The drive alone is a folder of one tile,
  so both runs read tiles the same way;
- the layers (stations, detections, candidates): every geometry and every easting field
  moved the same way, ids renumbered per copy. Times are kept (the cloud's cannot move
  without rewriting its points), so the long drive's station times repeat and its stages
  take each point's sensor position from the nearest track position, as for a track
  without times, where the drive alone uses its times (the output says so).

Each stage then runs through ``qgis_process`` on the drive and on its copies, each in a
process of its own: wall time, peak RSS and their ratios are printed (memory ratio 1.00:
flat), and the growth per kilometre of drive (``drive.json``'s length, the gaps between the
copies not counted). Nothing is timed against a threshold: read the ratios. One run's
peak moves by tens of MB on the same input (which windows or blocks the two threads hold
at once), so ``--repeats N`` runs each stage N times on each drive, alternating, and
compares the medians (the ranges printed beside them).

    .venv/bin/python bench/bench_drive_repeat.py --copies 3
    .venv/bin/python bench/bench_drive_repeat.py --copies 9 --repeats 3 --align-m 50 --stages findsignsincloud
    .venv/bin/python bench/bench_drive_repeat.py --copies 3 9 27 --stages findsignsincloud \\
        projectdetections refinesigns --json bench/out/drive-repeat.json
"""
from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, REPO)

DEFAULT_DRIVE = os.path.join(HERE, "out", "drive-drive1k-4")
STAGES = ("findsignsincloud", "projectdetections", "refinesigns", "detectsigns", "groundfilter")
#: LAS public header: X offset, max X, min X (little-endian doubles, LAS 1.0-1.4).
LAS_X_OFFSET_AT, LAS_MAX_X_AT, LAS_MIN_X_AT = 155, 179, 187
#: Fields holding eastings (moved with the geometry) and ids (renumbered per copy).
EASTING_FIELDS = ("x", "cand_x")
ID_FIELDS = ("station_id", "det_id")


def shifted_las(src: str, dst: str, dx_m: float) -> None:
    """``src`` (LAS or LAZ) copied to ``dst`` with every point ``dx_m`` further east: the
    header's X offset and X bounds moved, the points untouched."""
    shutil.copyfile(src, dst)
    with open(dst, "r+b") as f:
        head = f.read(195)
        if head[:4] != b"LASF":
            raise ValueError(f"{src} is not a LAS/LAZ file")
        for at in (LAS_X_OFFSET_AT, LAS_MAX_X_AT, LAS_MIN_X_AT):
            (value,) = struct.unpack_from("<d", head, at)
            f.seek(at)
            f.write(struct.pack("<d", value + dx_m))


def repeated_layer(src: str, dst: str, copies: int, spacing_m: float) -> int:
    """The first layer of GeoPackage ``src`` repeated ``copies`` times into ``dst``, copy k
    moved ``k x spacing_m`` east (geometry and :data:`EASTING_FIELDS`) with its
    :data:`ID_FIELDS` raised by k x the largest id. Returns the features written."""
    from osgeo import ogr

    source = ogr.Open(src)
    layer = source.GetLayer(0)
    defn = layer.GetLayerDefn()
    names = [defn.GetFieldDefn(i).GetName() for i in range(defn.GetFieldCount())]
    top = {name: max((f.GetField(name) or 0) for f in layer) for name in ID_FIELDS if name in names}
    if os.path.exists(dst):
        os.remove(dst)
    out_source = ogr.GetDriverByName("GPKG").CreateDataSource(dst)
    out = out_source.CreateLayer(layer.GetName(), layer.GetSpatialRef(), layer.GetGeomType())
    for i in range(defn.GetFieldCount()):
        out.CreateField(defn.GetFieldDefn(i))
    n = 0
    out_source.StartTransaction()
    for k in range(copies):
        layer.ResetReading()
        for feature in layer:
            copy = ogr.Feature(out.GetLayerDefn())
            for i, name in enumerate(names):
                value = feature.GetField(i)
                if value is not None and name in EASTING_FIELDS:
                    value += k * spacing_m
                elif value is not None and name in top:
                    value += k * top[name]
                copy.SetField(i, value)
            geometry = feature.GetGeometryRef()
            if geometry is not None:
                geometry = geometry.Clone()
                for j in range(geometry.GetPointCount()):     # points and lines
                    x, y, z = geometry.GetPoint(j)
                    geometry.SetPoint(j, x + k * spacing_m, y, z)
                copy.SetGeometry(geometry)
            out.CreateFeature(copy)
            n += 1
    out_source.CommitTransaction()
    out_source = None   # closed: written
    return n


def make_drive(chain: str, folder: str, copies: int, spacing_m: float) -> dict:
    """The chain's layers and ground cloud repeated ``copies`` times in ``folder``."""
    os.makedirs(os.path.join(folder, "tiles"), exist_ok=True)
    for k in range(copies):
        shifted_las(os.path.join(chain, "ground.laz"), os.path.join(folder, "tiles", f"tile_{k}.laz"), k * spacing_m)
    counts = {}
    for name in ("stations", "detections", "candidates"):
        counts[name] = repeated_layer(os.path.join(chain, f"{name}.gpkg"), os.path.join(folder, f"{name}.gpkg"),
                                      copies, spacing_m)
    return counts


def drive_length_km(drive: str) -> float:
    """The drive's length (``drive.json``'s ``length_m``, :func:`devtools.scenegen.drive.read_drive`)
    in km, 0 when it does not say: the memory a longer drive needs is also printed per km of
    drive (the copies' gaps not counted)."""
    from devtools.scenegen.drive import read_drive

    return float((read_drive(drive) or {}).get("length_m", 0.0)) / 1000.0


def aligned_spacing_m(stations_gpkg: str, spacing_m: float, align_m: float) -> float:
    """The spacing (metres east, at least ``spacing_m``) that puts each copy's first station a
    whole multiple of ``align_m`` metres of the stations' track after the last copy's first
    station: the track of one copy (its stations in order) and the straight link from its last
    station to the next copy's first. With ``align_m`` the windows' length of
    ``findsignsincloud`` (``CloudSignParams.window_m``), which cuts the track into windows from
    its start, every copy is cut into the same windows holding the same points (but for the
    few metres past each copy's ends, which lie along the link to the next copy): the longer
    drive is the same work window for window, and what its memory adds is the drive's own."""
    from osgeo import ogr

    source = ogr.Open(stations_gpkg)
    xy = np.array([(f.GetGeometryRef().GetX(), f.GetGeometryRef().GetY()) for f in source.GetLayer(0)])
    track_m = float(np.linalg.norm(np.diff(xy, axis=0), axis=1).sum())
    dx, dy = xy[0, 0] - xy[-1, 0], xy[0, 1] - xy[-1, 1]   # first station less the last

    def per_copy_m(spacing):
        return track_m + math.hypot(dx + spacing, dy)

    whole = math.ceil(per_copy_m(spacing_m) / align_m)
    link_m = whole * align_m - track_m
    return math.sqrt(link_m * link_m - dy * dy) - dx


def summary(runs: list) -> dict:
    """The median wall time and peak of a stage's runs on one drive, the peaks' range and
    every run: one run's peak moves with which windows or blocks the two threads happen to
    hold at once (tens of MB on the same input), so a ratio of single runs can mislead."""
    peaks = sorted(r["peak_rss_mb"] for r in runs)
    return {"wall_s": round(float(np.median([r["wall_s"] for r in runs])), 1),
            "peak_rss_mb": round(float(np.median(peaks)), 1), "peak_rss_mb_range": [peaks[0], peaks[-1]],
            "runs": runs}


def stage_args(stage: str, folder: str) -> list:
    cloud, out = os.path.join(folder, "tiles"), os.path.join(folder, "out")
    os.makedirs(out, exist_ok=True)
    return {
        "findsignsincloud": ["STATIONS=" + os.path.join(folder, "stations.gpkg"), "POINT_CLOUD=" + cloud,
                             "OUTPUT=" + os.path.join(out, "cloudsigns.gpkg"),
                             "POLES=" + os.path.join(out, "poles.gpkg")],
        "projectdetections": ["DETECTIONS=" + os.path.join(folder, "detections.gpkg"), "POINT_CLOUD=" + cloud,
                              "OUTPUT=" + os.path.join(out, "candidates.gpkg")],
        "refinesigns": ["CANDIDATES=" + os.path.join(folder, "candidates.gpkg"), "POINT_CLOUD=" + cloud,
                        "OUTPUT=" + os.path.join(out, "signs.gpkg")],
        "detectsigns": ["STATIONS=" + os.path.join(folder, "stations.gpkg"),
                        "OUTPUT=" + os.path.join(out, "detections.gpkg")],
        # cropped 25 m around the stations as the shipped model crops; the copies are of the
        # ground-classified cloud, so its classes are made anew, as on a raw cloud
        "groundfilter": ["INPUT=" + cloud, "CROP=" + os.path.join(folder, "stations.gpkg"), "CROP_BUFFER=25",
                         "RESET_CLASSES=true", "OUTPUT=" + os.path.join(out, "ground.laz")],
    }[stage]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drive", default=DEFAULT_DRIVE, help="a bench_drive folder whose chain/ was run")
    ap.add_argument("--copies", type=int, nargs="+", default=[3],
                    help="the longer drives, in copies of the drive (several: does the growth level off?)")
    ap.add_argument("--spacing", type=float, default=2000.0, help="metres between the copies (more than the drive)")
    ap.add_argument("--align-m", type=float,
                    help="lay the copies so each starts a whole multiple of this many metres of track after "
                         "the last (findsignsincloud's windows: 50): the same windows in every copy")
    ap.add_argument("--stages", nargs="+", choices=STAGES, default=list(STAGES[:3]))
    ap.add_argument("--repeats", type=int, default=1,
                    help="run each stage this many times on each drive, alternating; the medians are compared")
    ap.add_argument("--work", help="where the copies go (default DRIVE/repeat)")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    from devtools.qgisrun import QgisProcess

    chain = os.path.join(a.drive, "chain")
    if not os.path.isfile(os.path.join(chain, "candidates.gpkg")):
        sys.exit(f"{chain} has no chain outputs: run bench/bench_drive.py --preset drive1k first")
    work = a.work or os.path.join(a.drive, "repeat")
    counts = sorted({1, *a.copies})
    if a.align_m:
        a.spacing = aligned_spacing_m(os.path.join(chain, "stations.gpkg"), a.spacing, a.align_m)
        print(f"copies {a.spacing:.3f} m apart: each starts a whole multiple of {a.align_m:g} m of track "
              "after the last", flush=True)
    drives = {}
    for copies in counts:
        folder = os.path.join(work, f"x{copies}")
        drives[copies] = {"folder": folder, "features": make_drive(chain, folder, copies, a.spacing)}
        print(f"x{copies}: {copies} tile(s) of {os.path.join(chain, 'ground.laz')}, "
              f"{drives[copies]['features']} in {folder}", flush=True)
    print("the repeated drive's station times repeat: its stages take sensor positions from the track, "
          "the drive alone from its times")
    length_km = drive_length_km(a.drive)
    q = QgisProcess()
    results = []
    for stage in a.stages:
        runs = {copies: [] for copies in counts}
        for repeat in range(a.repeats):     # alternated: 1 x, N x, 1 x, N x, ...
            for copies in counts:
                r = q("run", "roadsigns:" + stage, "--", *stage_args(stage, drives[copies]["folder"]), timeout=7200)
                if r.returncode != 0:
                    print(r.text[-3000:])
                    sys.exit(f"{stage} on x{copies} failed")
                runs[copies].append({"wall_s": round(r.wall_s, 1), "peak_rss_mb": round(r.peak_rss_mb, 1)})
                print(f"{stage:<18} x{copies:<3} {r.wall_s:8.1f} s  peak {r.peak_rss_mb:7.0f} MB"
                      + (f"  (run {repeat + 1} of {a.repeats})" if a.repeats > 1 else ""), flush=True)
        one = summary(runs[1])
        for copies in counts[1:]:
            many = summary(runs[copies])
            rec = {"stage": stage, "copies": copies, "x1": one, f"x{copies}": many,
                   "memory_ratio": round(many["peak_rss_mb"] / one["peak_rss_mb"], 3),
                   "time_ratio": round(many["wall_s"] / one["wall_s"], 3)}
            if length_km:
                rec["mb_per_km"] = round((many["peak_rss_mb"] - one["peak_rss_mb"]) / ((copies - 1) * length_km), 2)
            results.append(rec)
            per_km = f", {rec['mb_per_km']:+.1f} MB a km of drive" if "mb_per_km" in rec else ""
            spread = (f" (medians of {a.repeats} runs; peaks x1 {one['peak_rss_mb_range'][0]:.0f}-"
                      f"{one['peak_rss_mb_range'][1]:.0f}, x{copies} {many['peak_rss_mb_range'][0]:.0f}-"
                      f"{many['peak_rss_mb_range'][1]:.0f} MB)" if a.repeats > 1 else "")
            print(f"{stage:<18} x{copies} / x1: memory {rec['memory_ratio']:.2f}{per_km}, time "
                  f"{rec['time_ratio']:.2f} (linear: {copies:.2f}){spread}", flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"drive": a.drive, "copies": counts[1:], "spacing_m": a.spacing, "align_m": a.align_m,
                       "repeats": a.repeats, "stages": results,
                       "features": {k: v["features"] for k, v in drives.items()}}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
