"""Run the whole chain through qgis_process on a generated scene and print its figures.

For each stage: wall time and the peak memory of its qgis_process run (RSS, from
``wait4``), plus the stage's own accuracy where the scene's truth allows (station poses
against the true poses, ground classes against the true classes) and the accuracy of the
final sign layer from ``roadsigns:evaluate``. Stages the provider does not have yet are
reported as missing, and the stages that need their output as blocked.

    python bench/bench_chain.py --preset default --seed 7 [--scene DIR] [--json out.json]
                                [--detections model|oracle] [--model MODEL.onnx]

``--detections oracle`` replaces the detector by the scene's true boxes (devtools/oracle.py),
to measure the cloud stages apart from the detector.

Prints a table, then the same figures as JSON (also written to ``--json`` if given).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time

if os.path.isdir("/usr/share/proj"):  # pyproj inside a venv looks under the venv otherwise
    os.environ.setdefault("PROJ_DATA", "/usr/share/proj")
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools.qgisrun import QgisProcess  # noqa: E402


def load_scene(args):
    scene_dir = args.scene or os.path.join(REPO_ROOT, "bench", "out",
                                           "scene-{}-{}".format(args.preset, args.seed))
    if not os.path.exists(os.path.join(scene_dir, "scene.json")):
        from devtools.scenegen import generate_scene
        start = time.perf_counter()
        generate_scene(args.preset, args.seed, scene_dir)
        print("generated scene {} in {:.1f} s".format(scene_dir, time.perf_counter() - start))
    with open(os.path.join(scene_dir, "scene.json")) as f:
        return scene_dir, json.load(f)


def horizon_views_option(choice) -> int:
    """The index of detectsigns' HORIZON_VIEWS option for a ring of ``choice`` views (an int
    or its digits) or the band (``band``)."""
    from devtools import import_roadsigns
    panorama = import_roadsigns("roadsigns.core.panorama")
    try:
        return panorama.HORIZON_CHOICES.index(panorama.horizon_choice(choice))
    except ValueError as e:
        raise SystemExit(f"--horizon-views: {e}")


def stage_plan(scene_dir, meta, work, model=None, station_spacing_m=None, upward_views=None, classifier=None,
               fore_aft_views=None, rescue_confidence=None, confidence=None, zoomed_look=None,
               horizon_views=None, edge_on_look=None):
    """(stage id, parameters, output key, what it needs) in chain order; ``horizon_views``: the
    number of views of detectsigns' horizon ring (None: its default)."""
    p = lambda name: os.path.join(scene_dir, name)  # noqa: E731
    w = lambda name: os.path.join(work, name)  # noqa: E731
    lever = meta["lever_arm_m"]
    bore = [meta["boresight_deg"][k] for k in ("roll", "pitch", "yaw")]
    return [
        ("importtrajectory", dict(TRAJECTORY=p("trajectory.csv"), IMAGE_TIMES=p("image_times.csv"),
                                  IMAGES=p("images"), TRAJECTORY_CRS=meta.get("trajectory_crs", "EPSG:32633"),
                                  TARGET_CRS=meta.get("target_crs", "EPSG:32633"),
                                  LEVER_ARM_X=lever[0], LEVER_ARM_Y=lever[1], LEVER_ARM_Z=lever[2],
                                  BORESIGHT_ROLL=bore[0], BORESIGHT_PITCH=bore[1], BORESIGHT_YAW=bore[2],
                                  OUTPUT=w("stations.gpkg")), "OUTPUT", []),
        ("detectsigns", dict(STATIONS=w("stations.gpkg"), OUTPUT=w("detections.gpkg"),
                             **({"CONFIDENCE": confidence} if confidence is not None else {}),
                             **({"STATION_SPACING_M": station_spacing_m} if station_spacing_m is not None else {}),
                             **({"UPWARD_VIEWS": upward_views} if upward_views is not None else {}),
                             **({"FORE_AFT_VIEWS": fore_aft_views} if fore_aft_views is not None else {}),
                             **({"HORIZON_VIEWS": horizon_views_option(horizon_views)}
                                if horizon_views is not None else {}),
                             **({"RESCUE_CONFIDENCE": rescue_confidence} if rescue_confidence is not None else {}),
                             **({"ZOOMED_LOOK": zoomed_look} if zoomed_look is not None else {}),
                             **({"EDGE_ON_LOOK": edge_on_look} if edge_on_look is not None else {}),
                             **({"MODEL": model} if model else {}),
                             **({"CLASSIFIER": classifier} if classifier else {})),
         "OUTPUT", ["importtrajectory"]),
        # the scene's cloud carries its true classes: reset them, compare afterwards
        ("groundfilter", dict(INPUT=p("cloud.laz"), METHOD=0, ENGINE=0, RESET_CLASSES=True,
                              OUTPUT=w("ground.laz")), "OUTPUT", []),
        ("projectdetections", dict(DETECTIONS=w("detections.gpkg"), POINT_CLOUD=w("ground.laz"),
                                   MAX_RANGE=40, OUTPUT=w("candidates.gpkg")), "OUTPUT",
         ["detectsigns", "groundfilter"]),
        ("refinesigns", dict(CANDIDATES=w("candidates.gpkg"), POINT_CLOUD=w("ground.laz"),
                             MERGE_RADIUS=1.0, OUTPUT=w("signs.gpkg")), "OUTPUT",
         ["projectdetections", "groundfilter"]),
        ("evaluate", dict(SIGNS=w("signs.gpkg"), REFERENCE=p("reference_signs.csv"), MATCH_RADIUS=1.0,
                          OUTPUT_REPORT=w("evaluation.html")), "OUTPUT_REPORT", ["refinesigns"]),
    ]


def station_accuracy(stations_path, meta):
    """Largest distance (m) between imported panorama centres and the scene's true ones."""
    import numpy as np
    from osgeo import ogr
    truth = {im["image"]: np.array(im["pano_centre"]) for im in meta.get("images", [])}
    dataset = ogr.Open(stations_path)
    errors = [np.linalg.norm(np.array([f["x"], f["y"], f["z"]]) - truth[f["image"]])
              for f in dataset.GetLayer(0) if f["image"] in truth]
    return {"stations": len(errors), "max_centre_error_m": float(max(errors))} if errors else {}


def ground_accuracy(input_path, ground_path, meta):
    """Share of points whose ground / non-ground class agrees with the scene's true class
    (the input's classification; the ground filter ran without a crop, so order is kept)."""
    import laspy
    import numpy as np
    ground_code = meta["class_codes"]["ground"]
    agree = total = 0
    with laspy.open(input_path) as truth_reader, laspy.open(ground_path) as reader:
        for truth, chunk in zip(truth_reader.chunk_iterator(2_000_000), reader.chunk_iterator(2_000_000)):
            true_ground = np.asarray(truth.classification) == ground_code
            agree += int(np.count_nonzero(true_ground == (np.asarray(chunk.classification) == 2)))
            total += len(chunk)
    return {"ground_agreement": agree / max(total, 1)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="default")
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--scene", help="an existing scene folder (else generated into bench/out)")
    parser.add_argument("--json", help="also write the figures to this file")
    parser.add_argument("--detections", choices=["model", "oracle"], default="model",
                        help="the detector (bundled or --model), or the scene's true boxes")
    parser.add_argument("--model", help="an ONNX model instead of the bundled one")
    parser.add_argument("--classifier", help="a sign-code classifier (ONNX) instead of the bundled one")
    parser.add_argument("--station-spacing", type=float, metavar="M",
                        help="detectsigns' STATION_SPACING_M: detect in a panorama at least every M metres, "
                             "the ones between skipped (0: every station; default: the algorithm's)")
    parser.add_argument("--upward", action=argparse.BooleanOptionalAction, default=None,
                        help="detectsigns with or without its upward views (UPWARD_VIEWS; default: the "
                             "algorithm's, off: the horizon views only)")
    parser.add_argument("--fore-aft", action=argparse.BooleanOptionalAction, default=None,
                        help="detectsigns with or without its fore-and-aft views (FORE_AFT_VIEWS; default: the "
                             "algorithm's, on)")
    parser.add_argument("--horizon-views", metavar="N",
                        help="detectsigns' HORIZON_VIEWS: the number of views of its horizon ring (8 or 6), or "
                             "band for the horizon as one band (default: the algorithm's, 8)")
    parser.add_argument("--zoomed-look", action=argparse.BooleanOptionalAction, default=None,
                        help="detectsigns with or without its zoomed look at small boxes (ZOOMED_LOOK; default: "
                             "the algorithm's, on)")
    parser.add_argument("--edge-on-look", action=argparse.BooleanOptionalAction, default=None,
                        help="detectsigns with or without its edge-on look at tall boxes (EDGE_ON_LOOK; default: "
                             "the algorithm's, on)")
    parser.add_argument("--rescue-confidence", type=float, metavar="S",
                        help="detectsigns' RESCUE_CONFIDENCE (its second look; the confidence or more: off)")
    parser.add_argument("--confidence", type=float, metavar="S",
                        help="detectsigns' CONFIDENCE (default: the algorithm's default)")
    parser.add_argument("--from", dest="from_stage", metavar="STAGE",
                        help="reuse the outputs of the stages before STAGE from an earlier run "
                             "(e.g. --from refinesigns while tuning the refinement)")
    args = parser.parse_args(argv)

    scene_dir, meta = load_scene(args)
    work = os.path.join(REPO_ROOT, "bench", "out", "chain-{}-{}-{}{}".format(
        os.path.basename(os.path.normpath(scene_dir)), args.detections, args.seed,
        f"-spacing{args.station_spacing:g}" if args.station_spacing is not None else "")
        + {None: "", False: "-noupward", True: "-upward"}[args.upward]
        + {None: "", False: "-noforeaft", True: "-foreaft"}[args.fore_aft]
        + {None: "", False: "-nozoom", True: "-zoom"}[args.zoomed_look]
        + {None: "", False: "-noedge", True: "-edge"}[args.edge_on_look]
        + (f"-horizon{args.horizon_views}" if args.horizon_views is not None else "")
        + (f"-rescue{args.rescue_confidence:g}" if args.rescue_confidence is not None else "")
        + (f"-conf{args.confidence:g}" if args.confidence is not None else "")
        + ("-model-" + os.path.splitext(os.path.basename(args.model))[0] if args.model else "")
        + ("-classifier-" + os.path.splitext(os.path.basename(args.classifier))[0] if args.classifier else ""))
    os.makedirs(work, exist_ok=True)
    qgis = QgisProcess()
    listing = qgis("--json", "list")
    available = set(listing.json["providers"]["roadsigns"]["algorithms"])

    figures = {"scene": scene_dir, "preset": args.preset, "seed": args.seed,
               "detections": args.detections, "station_spacing_m": args.station_spacing,
               "upward_views": args.upward, "fore_aft_views": args.fore_aft, "classifier": args.classifier,
               "rescue_confidence": args.rescue_confidence, "confidence": args.confidence,
               "zoomed_look": args.zoomed_look, "edge_on_look": args.edge_on_look, "horizon_views": args.horizon_views,
               "stages": {}}
    done = set()
    plan = stage_plan(scene_dir, meta, work, args.model, args.station_spacing, args.upward, args.classifier,
                      args.fore_aft, args.rescue_confidence, args.confidence, args.zoomed_look, args.horizon_views,
                      args.edge_on_look)
    if args.from_stage and args.from_stage not in [p[0] for p in plan]:
        parser.error(f"--from: no stage {args.from_stage}")
    reuse = args.from_stage is not None
    for stage, parameters, output_key, needs in plan:
        record = {"status": "missing"}
        reuse = reuse and stage != args.from_stage
        if reuse and os.path.exists(parameters.get("OUTPUT", "")):
            record = {"status": "reused"}
            done.add(stage)
        elif stage == "detectsigns" and args.detections == "oracle" and "importtrajectory" in done:
            from devtools.oracle import oracle_detections
            start = time.perf_counter()
            count = oracle_detections(scene_dir, parameters["STATIONS"], parameters["OUTPUT"])
            record = {"status": "oracle", "wall_s": round(time.perf_counter() - start, 2),
                      "detections": count}
            done.add(stage)
        elif "roadsigns:" + stage not in available:
            pass
        elif any(n not in done for n in needs):
            record["status"] = "blocked"
            record["needs"] = [n for n in needs if n not in done]
        else:
            run = qgis.run("roadsigns:" + stage, **parameters)
            record.update(status="ok" if run.returncode == 0 else "failed",
                          wall_s=round(run.wall_s, 2), peak_rss_mb=round(run.peak_rss_mb, 1))
            if run.returncode == 0:
                done.add(stage)
                results = run.json.get("results", {})
                if stage == "importtrajectory":
                    record.update(station_accuracy(results[output_key], meta))
                elif stage == "groundfilter":
                    record.update(ground_accuracy(parameters["INPUT"], results[output_key], meta))
                elif stage == "evaluate":
                    record.update({k: v for k, v in results.items() if k != output_key})
                    record["report"] = results[output_key]
            else:
                record["error"] = run.text.strip().splitlines()[-1:] if run.text.strip() else []
        figures["stages"][stage] = record

    print("\n{:<18} {:>8} {:>9} {:>11}  {}".format("stage", "status", "wall s", "peak MB", "accuracy"))
    for stage, r in figures["stages"].items():
        extra = {k: v for k, v in r.items() if k not in ("status", "wall_s", "peak_rss_mb", "report")}
        print("{:<18} {:>8} {:>9} {:>11}  {}".format(
            stage, r["status"], r.get("wall_s", "-"), r.get("peak_rss_mb", "-"),
            ", ".join("{}={}".format(k, round(v, 4) if isinstance(v, float) else v)
                      for k, v in extra.items())))
    text = json.dumps(figures, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
