"""The whole chain on a long drive (issue 14): the shipped model through qgis_process, per stage figures.

The drive comes from the scene generator (devtools/scenegen/drive.py): the LiDAR simulated
over its whole length, with signs, poles and furniture all along, and panoramas rendered
for a first stretch only; every later station shows one of those images again under its
own name and with its own pose. The chain does a real drive's work on every panorama,
but only the first stretch has image truth: the sign accuracy is measured there, and the
signs found in the cloud are also scored over the whole drive (the LiDAR truth is real
everywhere).

    .venv/bin/python bench/bench_drive.py --preset drivesmoke|drive1k|drive9k [--seed 4]
        [--drive DIR] [--render-m M | --render-count N] [--jobs N] [--separate] [--json OUT]

The chain runs once as the shipped model ``roadsigns:signinventory`` in one ``qgis_process
--verbose run`` (as README and scripts/demo.py run it). Its log says when each child
algorithm starts and how long QGIS timed it; meanwhile the process's resident memory and
CPU time are sampled every 50 ms, so each stage gets: wall time (QGIS's own), seconds per
panorama, seconds per million points, CPU seconds, resident memory when it started and
its peak while it ran (one process: a stage's peak includes what earlier stages left
allocated). ``--separate`` also runs every child of the model as its own qgis_process
run with the same parameters (each stage's own peak, QGIS start-up included), like
bench_chain.py. The totals are extrapolated linearly to the seed-004 drive (Balado et al.
2020: 9.2 km, 350 M points, 7,392 panoramas), each stage by what drives its cost.

Drives are cached in ``bench/out/drive-<preset>-<seed>/`` (the chain's outputs in its
``chain/``); ``bench/out`` is ignored by git. Prints a table, then the figures as JSON
(also written to ``--json``).
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import pty
import re
import select
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools.qgisrun import QgisProcess  # noqa: E402
from devtools.scenegen.presets import get_preset  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))   # the bench folder is not a package
from bench_chain import horizon_views_option  # noqa: E402

MODEL_PATH = os.path.join(REPO_ROOT, "models", "sign_inventory.model3")
MODEL_ID = "roadsigns:signinventory"
#: the seed-004 drive of Balado et al. 2020
SEED004 = {"length_km": 9.2, "points": 350e6, "panoramas": 7392}
#: what each stage's cost follows, for the extrapolation (the others: both, see DRIVER_NOTE)
DRIVER = {"importtrajectory": "panoramas", "detectsigns": "panoramas", "groundfilter": "points",
          "projectdetections": "points", "findsignsincloud": "points", "refinesigns": "panoramas",
          "fusesigns": "panoramas"}
DRIVER_NOTE = ("projectdetections reads the cloud and searches per detection, refinesigns "
               "works per candidate: scaled by points and panoramas respectively")
SAMPLE_S = 0.05
MATCH_RADIUS_M = 1.0
EVAL_KEYS = ("TP", "FP", "FN", "PRECISION", "RECALL", "CLASS_ACCURACY", "MEDIAN_ERROR", "P95_ERROR",
             "MEDIAN_HEIGHT_ERROR", "MEDIAN_AZIMUTH_ERROR", "MEDIAN_SIZE_ERROR", "P95_SIZE_ERROR",
             "CODE_ACCURACY")


# --- the model ------------------------------------------------------------------------------
def _opt(node, name):
    for child in node:
        if child.get("name") == name:
            return child
    return None


def model_children(path=MODEL_PATH):
    """The model's children: {child id: {"alg": algorithm id, "params": {name: source},
    "outputs": {model output name: child output name}}}; a source is ("model", parameter),
    ("child", child id, output) or ("static", value)."""
    root = ET.parse(path).getroot()
    children = {}
    for child in _opt(root, "children"):
        params = {}
        for p in _opt(child, "params"):
            for src in p:
                d = {c.get("name"): c.get("value") for c in src}
                kind = d.get("source")
                if kind == "0":
                    params[p.get("name")] = ("model", d["parameter_name"])
                elif kind == "1":
                    params[p.get("name")] = ("child", d["child_id"], d["output_name"])
                elif kind == "2":
                    params[p.get("name")] = ("static", d["static_value"])
        outputs = {}
        for o in (_opt(child, "outputs") or []):
            outputs[o.get("name")] = {c.get("name"): c.get("value") for c in o}.get("output_name")
        children[child.get("name")] = {"alg": _opt(child, "alg_id").get("value"), "params": params,
                                       "outputs": outputs}
    return children


def model_parameters(drive_dir, meta, work, cloud=None, ground_format="laz"):
    """The shipped model's inputs for the drive (``cloud``: the point cloud, default its
    ``cloud.laz``), and its outputs in ``work`` (the ground-classified cloud as
    ``ground.GROUND_FORMAT``: LAZ, or LAS, which the three stages after it read without
    decompressing)."""
    d = lambda name: os.path.join(drive_dir, name)  # noqa: E731
    w = lambda name: os.path.join(work, name)  # noqa: E731
    lever, bore = meta["lever_arm_m"], meta["boresight_deg"]
    inputs = dict(TRAJECTORY=d("trajectory.csv"), IMAGE_TIMES=d("image_times.csv"), IMAGES=d("images"),
                  TRAJECTORY_CRS=meta["trajectory_crs"], TARGET_CRS=meta["target_crs"],
                  POINT_CLOUD=cloud or d("cloud.laz"), LEVER_ARM_X=lever[0], LEVER_ARM_Y=lever[1],
                  LEVER_ARM_Z=lever[2], BORESIGHT_ROLL=bore["roll"], BORESIGHT_PITCH=bore["pitch"],
                  BORESIGHT_YAW=bore["yaw"])
    outputs = {"stations:Panorama stations": w("stations.gpkg"), "detections:Detections": w("detections.gpkg"),
               "ground:Ground-classified cloud": w("ground." + ground_format),
               "candidates:Sign candidates": w("candidates.gpkg"), "signs:Signs": w("signs.gpkg"),
               "signs:Panel outlines": w("panel_outlines.gpkg"), "signs:Review report": w("review.html"),
               "fused:Signs (fused)": w("inventory.gpkg"), "cloudsigns:Poles": w("poles.gpkg")}
    return inputs, outputs


# --- one qgis_process run, watched ----------------------------------------------------------
def _proc_sample(pid):
    """(VmRSS MB, VmHWM MB, CPU s of the process) or None when it is gone."""
    try:
        with open(f"/proc/{pid}/status") as f:
            status = f.read()
        with open(f"/proc/{pid}/stat") as f:
            stat = f.read()
    except OSError:
        return None
    kb = {k: int(v.split()[0]) for k, v in re.findall(r"^(VmRSS|VmHWM):\s+(.*)$", status, re.M)}
    fields = stat[stat.rindex(")") + 2:].split()
    cpu = (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    return kb.get("VmRSS", 0) / 1024.0, kb.get("VmHWM", 0) / 1024.0, cpu


def watched_run(qgis, args, log_path, timeout_s=48 * 3600):
    """Run ``qgis_process ARGS`` on a pseudo-terminal (so its log comes line by line), sampling
    its memory and CPU; split the run into the model's children from the log lines
    ``Running CHILD [k/N]`` and ``OK. Execution took S s``. Returns (returncode, wall s,
    peak RSS MB, stages: [{child, wall_s, qgis_s, cpu_s, rss_start_mb, peak_rss_mb}], log)."""
    master, slave = pty.openpty()
    start = time.perf_counter()
    p = subprocess.Popen([qgis.executable, *args], env=qgis.env, stdout=slave, stderr=slave,
                         stdin=subprocess.DEVNULL, close_fds=True)
    os.close(slave)
    stages, current, buf, lines = [], None, b"", []
    last = (0.0, 0.0, 0.0)
    peak_rss = 0.0
    with open(log_path, "w") as log:
        while True:
            ready, _, _ = select.select([master], [], [], SAMPLE_S)
            sample = _proc_sample(p.pid)
            if sample is not None and sample[1] > 0:
                last = sample
                peak_rss = max(peak_rss, sample[1])
                if current is not None:
                    current["_peak"] = max(current["_peak"], sample[0])
            if ready:
                try:
                    data = os.read(master, 65536)
                except OSError:
                    data = b""
                if not data:
                    break
                buf += data
                *complete, buf = buf.split(b"\n")
                now = time.perf_counter() - start
                for raw in complete:
                    line = raw.decode(errors="replace").replace("\r", "")
                    log.write("{:9.2f} | {}\n".format(now, line))
                    lines.append(line)
                    m = re.search(r"Running (\S+) \[(\d+)/(\d+)\]", line)
                    if m:
                        current = {"child": m.group(1), "_t0": now, "_cpu0": last[2], "_hwm0": last[1],
                                   "rss_start_mb": round(last[0], 1), "_peak": last[0]}
                        stages.append(current)
                    m = re.search(r"OK\. Execution took ([\d.]+) s", line)
                    if m and current is not None:
                        hwm = last[1]
                        peak = max(current.pop("_peak"), hwm if hwm > current.pop("_hwm0") else 0.0)
                        current.update(qgis_s=float(m.group(1)), wall_s=round(now - current.pop("_t0"), 2),
                                       cpu_s=round(last[2] - current.pop("_cpu0"), 1),
                                       peak_rss_mb=round(peak, 1))
                        current = None
                log.flush()
            elif p.poll() is not None and not ready:
                # the process is gone and the terminal is drained
                try:
                    if not select.select([master], [], [], 0.2)[0]:
                        break
                except OSError:
                    break
            if time.perf_counter() - start > timeout_s:
                p.kill()
                break
    os.close(master)
    returncode = p.wait()
    wall = time.perf_counter() - start
    if current is not None:          # the stage that failed
        for k in ("_t0", "_cpu0", "_hwm0"):
            current.pop(k, None)
        current["peak_rss_mb"] = round(current.pop("_peak"), 1)
        current["failed"] = True
    return returncode, wall, peak_rss, stages, lines


# --- the drive ------------------------------------------------------------------------------
def load_drive(args):
    from devtools.scenegen.drive import generate_drive, read_drive
    drive_dir = args.drive or os.path.join(REPO_ROOT, "bench", "out", f"drive-{args.preset}-{args.seed}")
    drive = read_drive(drive_dir)
    if drive is None:
        start = time.perf_counter()
        print(f"generating the drive {drive_dir} (resumable: run again to go on)", flush=True)
        drive = generate_drive(args.preset, args.seed, drive_dir, args.render_m, args.render_count,
                               jobs=args.jobs, verbose=True)
        print(f"generated in {time.perf_counter() - start:.0f} s", flush=True)
    elif args.render_m is not None or args.render_count is not None:
        print(f"note: {drive_dir} exists ({drive['rendered']} rendered): --render-m/--render-count ignored")
    with open(os.path.join(drive_dir, "scene.json")) as f:
        meta = json.load(f)
    return drive_dir, drive, meta


# --- accuracy -------------------------------------------------------------------------------
def _layer_points(path):
    """(fid, x, y, fields dict) of a point layer's features."""
    from osgeo import ogr
    ds = ogr.Open(path)
    out = []
    for f in ds.GetLayer(0):
        g = f.GetGeometryRef()
        out.append((f.GetFID(), g.GetX(), g.GetY(), f.items()))
    return out


def _subset_layer(src, dst, fids):
    from osgeo import gdal
    gdal.UseExceptions()
    if os.path.exists(dst):
        os.remove(dst)
    gdal.VectorTranslate(dst, src, options=gdal.VectorTranslateOptions(
        format="GPKG", where="fid IN ({})".format(",".join(str(int(i)) for i in fids))))


def _subset_reference(src, dst, keep):
    with open(src) as f:
        rows = list(csv.reader(f))
    with open(dst, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(rows[0])
        w.writerows(r for r in rows[1:] if keep(r))
    return sum(1 for r in rows[1:] if keep(r))


def evaluate_subset(qgis, signs_path, reference_path, work, label, keep_sign, keep_ref):
    """``roadsigns:evaluate`` on the signs and reference rows that ``keep_*`` accept."""
    signs = [(fid, x, y, items) for fid, x, y, items in _layer_points(signs_path) if keep_sign(x, y, items)]
    clipped_signs = os.path.join(work, f"eval-{label}-signs.gpkg")
    clipped_ref = os.path.join(work, f"eval-{label}-reference.csv")
    with open(reference_path) as f:
        header = next(csv.reader(f))
    ix, iy = header.index("x"), header.index("y")
    n_ref = _subset_reference(reference_path, clipped_ref, lambda r: keep_ref(float(r[ix]), float(r[iy])))
    record = {"signs": len(signs), "reference": n_ref}
    if not signs or not n_ref:
        record.update(TP=0, FP=len(signs), FN=n_ref, PRECISION=None, RECALL=0.0 if n_ref else None,
                      note="nothing to match")
        return record
    _subset_layer(signs_path, clipped_signs, [s[0] for s in signs])
    run = qgis.run("roadsigns:evaluate", SIGNS=clipped_signs, REFERENCE=clipped_ref, MATCH_RADIUS=MATCH_RADIUS_M,
                   OUTPUT_REPORT=os.path.join(work, f"evaluation-{label}.html"))
    if run.returncode != 0:
        record["error"] = run.text.strip().splitlines()[-1:]
        return record
    results = run.json["results"]
    record.update({k: results.get(k) for k in EVAL_KEYS})
    record["report"] = results.get("OUTPUT_REPORT")
    return record


def accuracy(qgis, drive_dir, drive, work):
    from devtools.scenegen.drive import Chainage, read_trajectory_xy
    chainage = Chainage(read_trajectory_xy(drive_dir))
    lo, hi = drive["truth_stretch"]["chainage_m"]

    def in_stretch(x, y):
        c = float(chainage([[x, y]])[0])
        return lo <= c <= hi

    reference = os.path.join(drive_dir, "reference_signs.csv")
    everything = lambda *a: True  # noqa: E731
    out = {"truth_stretch_chainage_m": [lo, hi]}
    for label, layer in (("inventory", "inventory.gpkg"), ("image-signs", "signs.gpkg")):
        out[label + " (truth stretch)"] = evaluate_subset(
            qgis, os.path.join(work, layer), reference, work, label + "-stretch",
            lambda x, y, items: in_stretch(x, y), in_stretch)
    out["cloud-found signs (whole drive)"] = evaluate_subset(
        qgis, os.path.join(work, "inventory.gpkg"), reference, work, "cloud-whole",
        lambda x, y, items: "lidar" in str(items.get("source") or ""), everything)
    return out


# --- separate runs --------------------------------------------------------------------------
def separate_runs(qgis, children, inputs, work):
    """Every child of the model as its own qgis_process run, in the model's order."""
    os.makedirs(work, exist_ok=True)
    order = ["stations", "detections", "ground", "cloudsigns", "candidates", "signs", "fused"]
    order = [c for c in order if c in children] + [c for c in children if c not in order]
    paths, records = {}, {}
    needed = {(src[1], src[2]) for c in children.values() for src in c["params"].values() if src[0] == "child"}
    for cid in order:
        child = children[cid]
        params = {}
        for name, src in child["params"].items():
            if src[0] == "model":
                if src[1] in inputs:
                    params[name] = inputs[src[1]]
            elif src[0] == "child":
                params[name] = paths[(src[1], src[2])]
            else:
                params[name] = src[1]
        for out_name in {o for (c, o) in needed if c == cid} | set(child["outputs"].values()):
            ext = ".laz" if child["alg"].endswith("groundfilter") and out_name == "OUTPUT" else ".gpkg"
            if out_name.endswith("REPORT"):
                ext = ".html"
            paths[(cid, out_name)] = params[out_name] = os.path.join(work, f"{cid}-{out_name.lower()}{ext}")
        run = qgis.run(child["alg"], **params)
        records[cid] = {"alg": child["alg"], "status": "ok" if run.returncode == 0 else "failed",
                        "wall_s": round(run.wall_s, 2), "peak_rss_mb": round(run.peak_rss_mb, 1)}
        print("  separate {:<22} {:>8} {:>9.1f} s {:>8.0f} MB".format(
            child["alg"], records[cid]["status"], run.wall_s, run.peak_rss_mb), flush=True)
        if run.returncode != 0:
            records[cid]["error"] = run.text.strip().splitlines()[-3:]
            break
    return records


# --- report ---------------------------------------------------------------------------------
def _fmt(v, nd=3):
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.{nd}f}"
    return str(v)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="drivesmoke", choices=["drivesmoke", "drive1k", "drive9k"])
    parser.add_argument("--seed", type=int, default=4)
    parser.add_argument("--drive", help="the drive's folder (default bench/out/drive-PRESET-SEED)")
    parser.add_argument("--render-m", type=float, help="when generating: render the first this many metres")
    parser.add_argument("--render-count", type=int, help="when generating: render this many first panoramas")
    parser.add_argument("--jobs", type=int, default=1, help="when generating: render in this many processes")
    parser.add_argument("--separate", action="store_true",
                        help="also run each child of the model as its own qgis_process run")
    parser.add_argument("--cloud", choices=["file", "tiles"], default="file",
                        help="the cloud as one LAZ (as generated) or as tiles of --tile-m of drive and a .vpc "
                             "(as a crew delivers a drive)")
    parser.add_argument("--tile-m", type=float, default=500.0)
    parser.add_argument("--station-spacing", type=float,
                        help="the model's STATION_SPACING_M (default: the model's own)")
    parser.add_argument("--horizon-views",
                        help="the model's HORIZON_VIEWS: the views of detectsigns' horizon ring, 8 or 6, or band for "
                             "the horizon as one band (default: the model's own, 8)")
    parser.add_argument("--ground-format", choices=["laz", "las"], default="laz",
                        help="the model's ground-classified cloud as LAZ (the default) or uncompressed LAS "
                             "(read by three later stages: no decompression, ~30 bytes a point on disk)")
    parser.add_argument("--json", help="also write the figures to this file")
    args = parser.parse_args(argv)

    load0 = os.getloadavg()
    drive_dir, drive, meta = load_drive(args)
    work = os.path.join(drive_dir, "chain")
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    n_pano, n_points = drive["panoramas"], drive["points"]
    units = {"panoramas": n_pano, "points": n_points}

    qgis = QgisProcess()
    children = model_children()
    alg_of = {cid: c["alg"].split(":", 1)[1] for cid, c in children.items()}
    cloud = None
    if args.cloud == "tiles":
        from devtools.scenegen.drive import write_tiles
        cloud = write_tiles(drive_dir, args.tile_m, verbose=True)
    inputs, outputs = model_parameters(drive_dir, meta, work, cloud, args.ground_format)
    if args.station_spacing is not None:
        inputs["STATION_SPACING_M"] = args.station_spacing
    if args.horizon_views is not None:
        inputs["HORIZON_VIEWS"] = horizon_views_option(args.horizon_views)
    args_run = ["--verbose", "run", MODEL_ID, "--"] + [f"{k}={v}" for k, v in {**inputs, **outputs}.items()]
    print(f"running {MODEL_ID} (models/sign_inventory.model3) on {drive_dir}: "
          f"{n_pano:,} panoramas, {n_points:,} points", flush=True)
    rc, wall, peak, stages, lines = watched_run(qgis, args_run, os.path.join(work, "model.log"))
    load1 = os.getloadavg()

    figures = {"drive": drive_dir, "preset": drive["preset"], "seed": drive["seed"],
               "length_m": drive["length_m"], "road_length_m": drive["road_length_m"],
               "panoramas": n_pano, "rendered": drive["rendered"], "reused": drive["reused"],
               "reuse": drive["reuse"], "points": n_points, "cloud": inputs["POINT_CLOUD"],
               "station_spacing_m": inputs.get("STATION_SPACING_M"),
               "horizon_views": args.horizon_views,
               "ground_output": outputs["ground:Ground-classified cloud"],
               "pano_width": drive["pano_width"],
               "image_spacing_m": drive["image_spacing_m"], "reference_signs": drive["reference_signs"],
               "generation_s": drive.get("timings_s"), "load_average": [round(load0[0], 2), round(load1[0], 2)],
               "model": {"returncode": rc, "wall_s": round(wall, 1), "peak_rss_mb": round(peak, 1),
                         "log": os.path.join(work, "model.log")},
               "stages": {}}
    per_unit_total = {"panoramas": 0.0, "points": 0.0}
    for st in stages:
        alg = alg_of.get(st["child"], st["child"])
        rec = dict(st)
        rec.pop("child")
        w = rec.get("qgis_s", rec.get("wall_s"))
        if w is not None:
            rec["s_per_panorama"] = round(w / n_pano, 4)
            rec["s_per_million_points"] = round(w / (n_points / 1e6), 3)
            driver = DRIVER.get(alg, "panoramas")
            rec["seed004_s"] = round(w / units[driver] * SEED004[driver], 0)
            per_unit_total[driver] += w
        figures["stages"][alg] = rec
    if rc != 0:
        figures["model"]["error"] = [ln for ln in lines if ln.strip()][-8:]
    total = sum(r.get("qgis_s", 0.0) for r in figures["stages"].values())
    figures["model"]["stages_s"] = round(total, 1)
    figures["seed004_extrapolation"] = {
        "target": SEED004, "rule": "linear: each stage by panoramas or by points (" + DRIVER_NOTE + ")",
        "chain_s": round(sum(r.get("seed004_s", 0) for r in figures["stages"].values())
                         + (wall - total), 0)}
    gen = drive.get("timings_s") or {}
    if gen.get("lidar"):
        per_m_points = gen["lidar"] / (n_points / 1e6)
        rpp = gen.get("render_s_per_panorama")
        figures["seed004_extrapolation"]["lidar_generation_s"] = round(per_m_points * SEED004["points"] / 1e6, 0)
        if rpp:
            figures["seed004_extrapolation"]["render_s_per_panorama"] = rpp

    if rc == 0:
        figures["accuracy"] = accuracy(qgis, drive_dir, drive, work)
    if args.separate:
        print("separate runs:", flush=True)
        figures["separate"] = separate_runs(qgis, children, inputs, os.path.join(work, "separate"))

    # --- print ---
    print()
    print("Drive {preset} seed {seed}: {length_m:,.0f} m driven ({road_length_m:,.0f} m furnished road), "
          "{points:,} LiDAR points over the whole length, {panoramas:,} panoramas {w} x {h} "
          "(one every {image_spacing_m} m); cloud {cloud}.".format(
              w=drive["pano_width"], h=drive["pano_width"] // 2, **figures))
    print("PANORAMAS: only the first {rendered:,} are rendered (road {a} to {b} m); the other {reused:,} reuse "
          "those images with their own poses ({reuse}). The chain does the full work on all of them, but the "
          "signs found from reused panoramas are not real.".format(
              a=drive["rendered_road_m"][0], b=drive["rendered_road_m"][1], **drive))
    print("Chain: the shipped model {} in one qgis_process run: exit {}, {:.1f} s wall, peak RSS {:.0f} MB; "
          "load average {:.1f} before, {:.1f} after (2 shared cores: times are inflated)."
          .format(MODEL_ID, rc, wall, peak, load0[0], load1[0]))
    if args.station_spacing is not None:
        print(f"STATION_SPACING_M = {args.station_spacing:g} m: detection in a panorama at least that often "
              f"(panoramas every {drive['image_spacing_m']} m here); s/panorama still divides by all of them.")
    if args.horizon_views is not None:
        seen = "as one band" if args.horizon_views == "band" else f"ring of {args.horizon_views} views"
        print(f"HORIZON_VIEWS: detectsigns' horizon {seen}.")
    print("\n{:<18} {:>9} {:>9} {:>11} {:>11} {:>8} {:>10} {:>9} {:>11}".format(
        "stage", "wall s", "CPU s", "s/panorama", "s/M points", "RSS in", "peak RSS", "driver", "9.2 km s"))
    for alg, r in figures["stages"].items():
        print("{:<18} {:>9} {:>9} {:>11} {:>11} {:>8} {:>10} {:>9} {:>11}".format(
            alg + (" FAILED" if r.get("failed") else ""), _fmt(r.get("qgis_s"), 1), _fmt(r.get("cpu_s"), 1),
            _fmt(r.get("s_per_panorama"), 4), _fmt(r.get("s_per_million_points"), 2),
            _fmt(r.get("rss_start_mb"), 0), _fmt(r.get("peak_rss_mb"), 0), DRIVER.get(alg, "-"),
            _fmt(r.get("seed004_s"), 0)))
    ext = figures["seed004_extrapolation"]
    print("{:<18} {:>9} {:>9} {:>11} {:>11} {:>8} {:>10} {:>9} {:>11}".format(
        "model total", _fmt(wall, 1), "", _fmt(wall / n_pano, 4), _fmt(wall / (n_points / 1e6), 2), "",
        _fmt(peak, 0), "", _fmt(ext["chain_s"], 0)))
    print("(wall s: QGIS's own time for the child; RSS in MB: when the stage started and its peak while it ran, "
          "in the model's one process; 9.2 km s: linear to 7,392 panoramas / 350 M points by the driver; "
          "{:.1f} s of the run are QGIS start-up and the model's own work)".format(wall - total))
    kind = get_preset("drive9k")
    if (drive["pano_width"], drive["image_spacing_m"]) != (kind.pano_width, kind.image_spacing_m):
        print("(this drive's panoramas are {} px wide every {} m, the 9.2 km drive's {} px every {} m: the "
              "9.2 km column is rough)".format(drive["pano_width"], drive["image_spacing_m"], kind.pano_width,
                                               kind.image_spacing_m))
    if gen:
        print("Generation of this drive: LiDAR {} s ({:.2f} s per M points), panoramas {} s ({} s each){}".format(
            gen.get("lidar", "-"), gen.get("lidar", 0) / (n_points / 1e6), gen.get("render_s", "-"),
            gen.get("render_s_per_panorama", "-"),
            "; LiDAR of 350 M points: ~{:.0f} min".format(ext["lidar_generation_s"] / 60)
            if "lidar_generation_s" in ext else ""))
    if "accuracy" in figures:
        acc = figures["accuracy"]
        lo, hi = acc["truth_stretch_chainage_m"]
        print("\nAccuracy (match radius {} m). Image truth only on the TRUTH STRETCH: chainage {:.0f}-{:.0f} m "
              "along the trajectory (the rendered panoramas less {} m), {} of the drive's {} reference signs; "
              "the cloud-found signs over the WHOLE drive (LiDAR is simulated everywhere):".format(
                  MATCH_RADIUS_M, lo, hi, drive["truth_stretch"]["end_margin_m"],
                  drive["truth_stretch"]["reference_signs"], drive["reference_signs"]))
        row = "{:<34} {:>5} {:>5} {:>4} {:>4} {:>4} {:>9} {:>7} {:>7} {:>8} {:>8} {:>11} {:>9}"
        print(row.format("set", "signs", "ref", "TP", "FP", "FN", "precision", "recall", "class", "median m",
                         "p95 m", "size med m", "size p95"))
        for label, r in acc.items():
            if not isinstance(r, dict):
                continue
            print(row.format(
                label, r.get("signs"), r.get("reference"), _fmt(r.get("TP")), _fmt(r.get("FP")), _fmt(r.get("FN")),
                _fmt(r.get("PRECISION")), _fmt(r.get("RECALL")), _fmt(r.get("CLASS_ACCURACY")),
                _fmt(r.get("MEDIAN_ERROR")), _fmt(r.get("P95_ERROR")),
                _fmt(r.get("MEDIAN_SIZE_ERROR")), _fmt(r.get("P95_SIZE_ERROR"))))
        print("(class accuracy of the cloud-found signs outside the truth stretch comes from reused panoramas: "
              "not meaningful)")
    if "separate" in figures:
        print("\nThe same stages, each its own qgis_process run (QGIS start-up included, own peak RSS):")
        print("{:<18} {:>8} {:>9} {:>11} {:>11} {:>10}".format(
            "stage", "status", "wall s", "s/panorama", "s/M points", "peak RSS"))
        for r in figures["separate"].values():
            print("{:<18} {:>8} {:>9} {:>11} {:>11} {:>10}".format(
                r["alg"].split(":", 1)[1], r["status"], _fmt(r["wall_s"], 1), _fmt(r["wall_s"] / n_pano, 4),
                _fmt(r["wall_s"] / (n_points / 1e6), 2), _fmt(r["peak_rss_mb"], 0)))
    text = json.dumps(figures, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text)
    return 0 if rc == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
