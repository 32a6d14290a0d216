"""Where detection time goes, per panorama, as ``roadsigns:detectsigns`` runs it (issue 14).

1. The split: each panorama is decoded (``read_panorama``, a 4096 x 2048 JPEG), prepared and
   cut into views (``ViewSet.prepare`` / ``PerspectiveView.cut``), inferred (letterbox,
   blob and the onnxruntime run, ``Detector.run_raw``), merged (decoding the outputs, NMS,
   boxes to the panorama, :func:`merge_view_detections`, as :func:`detect_panorama` does)
   and its sign codes read (:func:`read_codes` with the bundled classifier, as
   ``detect_drive``'s ``on_panorama``). Seconds per panorama for each part, panoramas per
   second overall.
2. ``detect_drive`` with and without ``prefetch`` (the next panorama decoded in a thread
   while this one is detected), alternating which goes first in each round, so the machine's
   load falls alike on both; the ratio is what counts on a busy machine.

    .venv/bin/python bench/bench_detect_speed.py [--scene bench/out/scene-default-7]
        [--max-images 20] [--threads 2] [--rounds 2] [--no-codes] [--horizon-views 8|6|band]
"""
from __future__ import annotations

import argparse
import glob
import os
import sys
import time
from functools import partial

import numpy as np

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools import import_roadsigns  # noqa: E402

detector_mod = import_roadsigns("roadsigns.core.detector")
panorama_mod = import_roadsigns("roadsigns.core.panorama")
detections_mod = import_roadsigns("roadsigns.core.detections")
signcodes_mod = import_roadsigns("roadsigns.core.signcodes")

PARTS = ("decode", "cut", "inference", "merge", "codes")


def split_one(path, detector, views, classifier, confidence, min_box_px, times):
    """One panorama through the steps of detect_drive, each timed into ``times``."""
    t = time.perf_counter()
    pano = panorama_mod.read_panorama(path)
    t, times["decode"] = time.perf_counter(), times["decode"] + time.perf_counter() - t
    H, W = pano.shape[:2]
    images = list(views.cut_all(pano))
    t, times["cut"] = time.perf_counter(), times["cut"] + time.perf_counter() - t
    rows = []
    for run in detector_mod.view_batches(views, detector.max_batch):   # the band alone, at its own size
        chunk = [images[k] for k in run]
        output, transforms = detector.run_raw(chunk, own_size=views[run[0]].own_size)
        rows += [(image, row, tr) for image, row, tr in zip(chunk, output, transforms)]
    t, times["inference"] = time.perf_counter(), times["inference"] + time.perf_counter() - t
    boxes, scores, ids, complete, central, view_k = [], [], [], [], [], []
    for k, (image, row, tr) in enumerate(rows):
        det = detector._postprocess(row, tr, image.shape[1], image.shape[0], confidence, 0.45)
        if len(det) == 0:
            continue
        view = views[k]
        boxes.append(view.boxes_to_pano(det.boxes_xyxy, W, H))
        scores.append(det.scores)
        ids.append(det.class_ids)
        complete.append(~view.touches_edge(det.boxes_xyxy))
        central.append(view.centrality(det.boxes_xyxy))
        view_k.append(np.full(len(det), k))
    found = None
    if boxes:
        kept, merged, counts = detector_mod.merge_view_detections(
            np.concatenate(boxes), np.concatenate(scores), np.concatenate(ids),
            np.concatenate(complete), np.concatenate(central), W)
        big = np.minimum(merged[:, 2] - merged[:, 0], merged[:, 3] - merged[:, 1]) >= min_box_px
        kept, merged, counts = kept[big], merged[big], counts[big]
        all_ids, all_scores = np.concatenate(ids), np.concatenate(scores)
        found = detector_mod.PanoramaDetections(
            all_ids[kept], [detector.class_names[c] for c in all_ids[kept]], all_scores[kept],
            merged[:, 0], merged[:, 1], merged[:, 2], merged[:, 3], np.concatenate(view_k)[kept], counts)
    t, times["merge"] = time.perf_counter(), times["merge"] + time.perf_counter() - t
    if classifier is not None and found is not None:
        detections_mod.read_codes(classifier, pano, found)
    times["codes"] += time.perf_counter() - t
    return 0 if found is None else len(found)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default=os.path.join(REPO_ROOT, "bench", "out", "scene-default-7"))
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx"))
    ap.add_argument("--classifier", default=os.path.join(REPO_ROOT, "models", "signcodes.onnx"))
    ap.add_argument("--codes-table", default=os.path.join(REPO_ROOT, "models", "sign-codes-de.csv"))
    ap.add_argument("--no-codes", action="store_true", help="leave the sign-code reading out")
    ap.add_argument("--max-images", type=int, default=None)
    ap.add_argument("--threads", type=int, default=2, help="onnxruntime intra-op threads")
    ap.add_argument("--rounds", type=int, default=2, help="rounds of the prefetch off/on comparison")
    ap.add_argument("--confidence", type=float, default=0.4)
    ap.add_argument("--upward", action="store_true",
                    help="also the upward views (detectsigns' UPWARD_VIEWS; default: the plugin's default)")
    ap.add_argument("--horizon-views", default=str(panorama_mod.DEFAULT_HORIZON_VIEWS),
                    choices=[str(c) for c in panorama_mod.HORIZON_CHOICES],
                    help="detectsigns' HORIZON_VIEWS: a ring of 8 or 6 views, or the horizon as one band")
    args = ap.parse_args(argv)

    paths = sorted(glob.glob(os.path.join(args.scene, "images", "*.jpg")))[:args.max_images]
    if not paths:
        sys.exit(f"no panoramas in {args.scene}/images")
    detector = detector_mod.Detector(args.model, threads=args.threads)
    views = panorama_mod.ViewSet.default(size_px=detector.input_size, upward=True if args.upward else None,
                                         horizon_views=panorama_mod.horizon_choice(args.horizon_views))
    classifier = None
    if not args.no_codes:
        table = signcodes_mod.read_codes_table(args.codes_table)
        classifier = signcodes_mod.CodeClassifier(args.classifier, table, threads=args.threads)
    min_box_px = detector_mod.DEFAULT_MIN_BOX_PX
    print(f"{len(paths)} panoramas of {args.scene}, {len(views)} views each, "
          f"{args.threads} threads, codes {'off' if classifier is None else 'on'}")

    split_one(paths[0], detector, views, classifier, args.confidence, min_box_px,
              dict.fromkeys(PARTS, 0.0))  # warm up: remap maps, sessions
    times = dict.fromkeys(PARTS, 0.0)
    n_found = sum(split_one(p, detector, views, classifier, args.confidence, min_box_px, times)
                  for p in paths)
    total = sum(times.values())
    print(f"\n1. split ({n_found} detections)")
    print(f"{'part':<10} {'s/panorama':>10} {'share':>6}")
    for part in PARTS:
        print(f"{part:<10} {times[part] / len(paths):10.4f} {times[part] / total:6.1%}")
    print(f"{'total':<10} {total / len(paths):10.4f}  -> {len(paths) / total:.2f} panoramas/s")

    on_panorama = None if classifier is None else partial(detections_mod.read_codes, classifier)
    wall = {False: [], True: []}
    counts = {}
    for r in range(args.rounds):
        for prefetch in ((False, True) if r % 2 == 0 else (True, False)):
            t = time.perf_counter()
            drive = detector_mod.detect_drive(detector, paths, views, args.confidence,
                                              min_box_px=min_box_px, on_panorama=on_panorama,
                                              prefetch=prefetch)
            wall[prefetch].append(time.perf_counter() - t)
            counts[prefetch] = drive.count
    print("\n2. detect_drive, prefetch off / on (alternating rounds)")
    for prefetch in (False, True):
        per = np.array(wall[prefetch]) / len(paths)
        print(f"prefetch {'on ' if prefetch else 'off'}: {' '.join(f'{p:.4f}' for p in per)} s/panorama, "
              f"best {1 / per.min():.2f} panoramas/s, {counts[prefetch]} detections")
    ratios = np.array(wall[True]) / np.array(wall[False])
    print(f"time on / off per round: {' '.join(f'{x:.3f}' for x in ratios)}  "
          f"(median {np.median(ratios):.3f})")
    if counts[False] != counts[True]:
        print("WARNING: prefetch changed the detections")


if __name__ == "__main__":
    main()
