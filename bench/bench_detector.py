"""Bench of a sign detector (default: the bundled models/roadsigns.onnx).

1. Precision and recall at IoU 0.5 per class on the panoramas of generated scenes whose
   seeds were never used in training (default: ``default`` preset, seed 7), run exactly as
   ``roadsigns:detectsigns`` runs it: ``Detector`` + ``ViewSet.default`` + ``detect_panorama``.
   Truth: front faces of ``scene.json`` (``visible_box``; a detection also matches the
   amodal ``box``). Counted for the goal: signs >= 20 px tall with occlusion <= 0.5;
   smaller or more hidden signs are reported separately and a detection on them is no
   false alarm. Back faces are not signs: a detection there is a false alarm. A second
   figure leaves out counted signs seen edge-on (under 8 px wide): they count in the first.
2. The same on GTSDB images 500-599 (held out from training), on 640 x 640 tiles at full
   resolution (6 per frame) and, for comparison, on whole frames letterboxed to 640 px.
3. Panoramas per second at 4096 x 2048 (decoding the JPEG not included; reported apart).

    .venv/bin/python bench/bench_detector.py [--model M] [--scene DIR ...] [--threads 2]
        [--json bench/out/detector.json]
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools import import_roadsigns  # noqa: E402
from devtools.train.data import CLASSES, GTSDB_HELDOUT_IDS, read_gtsdb  # noqa: E402
from devtools.train.metrics import iou_matrix, match_image, summarise  # noqa: E402

detector_mod = import_roadsigns("roadsigns.core.detector")
panorama_mod = import_roadsigns("roadsigns.core.panorama")

MIN_HEIGHT_PX = 20.0
EDGE_ON_MAX_WIDTH_PX = 8.0  # a counted sign seen this narrow is a sliver (edge-on): reported apart
MAX_OCCLUSION = 0.5
TILE_PX = 640


def seam_iou(width_px):
    """IoU of panorama boxes, columns compared modulo W; truth rows hold visible and amodal
    boxes (8 numbers) and the better of the two counts."""
    def iou(pred, truth):
        pred = np.asarray(pred, float).reshape(-1, 4)
        truth = np.asarray(truth, float)
        truth = truth.reshape(len(truth), -1) if truth.size else np.zeros((0, 4))
        best = np.zeros((len(pred), len(truth)))
        for k in range(0, truth.shape[1], 4):
            for shift in (-width_px, 0.0, width_px):
                best = np.maximum(best, iou_matrix(pred + [shift, 0, shift, 0], truth[:, k:k + 4]))
        return best
    return iou


def scene_truth(meta, sign_class):
    """Counted signs (visible + amodal boxes, classes), uncounted ones (small/hidden), back faces."""
    counted, classes, small, hidden, back = [], [], [], [], []
    for s in meta["signs"]:
        if s.get("visible_box") is None:
            continue
        boxes = list(s["visible_box"]) + list(s["box"])
        if s["facing"] != "front":
            back.append(boxes)
            continue
        height = s["visible_box"][3] - s["visible_box"][1]
        if s["occlusion"] > MAX_OCCLUSION:
            hidden.append((boxes, sign_class[s["sign_id"]]))
        elif height < MIN_HEIGHT_PX:
            small.append((boxes, sign_class[s["sign_id"]]))
        else:
            counted.append(boxes)
            classes.append(CLASSES.index(sign_class[s["sign_id"]]))
    return np.array(counted).reshape(-1, 8), np.array(classes, np.int64), small, hidden, back


def bench_panoramas(detector, scene_dirs, confidence, max_images=None, min_box_px=0.0):
    views = panorama_mod.ViewSet.default(size_px=detector.input_size)
    matches, small_matches, hidden_matches, face_on_matches = [], [], [], []
    back_hits = decode_s = detect_s = 0.0
    n_images, warm = 0, False
    for scene_dir in scene_dirs:
        with open(os.path.join(scene_dir, "scene.json")) as f:
            scene = json.load(f)
        sign_class = {s["sign_id"]: s["class"] for s in scene["signs"]}
        for meta in scene["images"][:max_images]:
            t0 = time.perf_counter()
            pano = panorama_mod.read_panorama(os.path.join(scene_dir, "images", meta["image"]))
            if not warm:  # build the cached remap tables and onnxruntime's buffers first
                detector_mod.detect_panorama(detector, pano, views, confidence=0.05)
                warm = True
            t1 = time.perf_counter()
            found = detector_mod.detect_panorama(detector, pano, views, confidence=0.05, min_box_px=min_box_px)
            t2 = time.perf_counter()
            decode_s, detect_s, n_images = decode_s + t1 - t0, detect_s + t2 - t1, n_images + 1
            iou = seam_iou(pano.shape[1])
            counted, classes, small, hidden, back = scene_truth(meta, sign_class)
            boxes, scores, ids = found.boxes(), found.score, found.class_id
            uncounted_boxes = np.array([b for b, _ in small + hidden]).reshape(-1, 8)
            m = match_image(boxes, scores, ids, counted, classes, 0.5, ignore_boxes=uncounted_boxes, iou_fn=iou)
            matches.append(m)
            edge_on = (counted[:, 2] - counted[:, 0]) < EDGE_ON_MAX_WIDTH_PX
            face_on_matches.append(match_image(
                boxes, scores, ids, counted[~edge_on], classes[~edge_on], 0.5, iou_fn=iou,
                ignore_boxes=np.concatenate([uncounted_boxes, counted[edge_on]])))
            if back and len(boxes):
                back_hits += int(((iou(boxes, np.array(back)).max(1) >= 0.5) & (scores >= confidence)).sum())
            for group, out in ((small, small_matches), (hidden, hidden_matches)):
                if group:
                    out.append(match_image(boxes, scores, ids, np.array([b for b, _ in group]),
                                           np.array([CLASSES.index(c) for _, c in group]), 0.5, iou_fn=iou))
    def recall_only(group):  # every detection of the image takes part: only recall means something
        s = summarise(group, CLASSES, confidence)["all"]
        return {k: s[k] for k in ("true", "hits", "recall")}
    return {"images": n_images, "per_class": summarise(matches, CLASSES, confidence),
            "small_under_20px": recall_only(small_matches),
            "without_edge_on": summarise(face_on_matches, CLASSES, confidence)["all"],
            "occluded_over_half": recall_only(hidden_matches),
            "detections_on_back_faces": int(back_hits),
            "seconds_per_panorama_detect": detect_s / max(n_images, 1),
            "seconds_per_panorama_decode_jpeg": decode_s / max(n_images, 1),
            "threshold_sweep": {f"{t:.2f}": summarise(matches, CLASSES, t)["all"] for t in (0.2, 0.3, 0.4, 0.5, 0.6)}}


def tiles(width, height, size=TILE_PX):
    """Tile origins covering the image, and each tile's core (a partition of the image):
    a detection is kept by the tile whose core holds its centre."""
    def starts(n):
        k = max(1, int(np.ceil((n - size) / (size * 0.6))) + 1) if n > size else 1
        return [int(round(i * (n - size) / max(k - 1, 1))) for i in range(k)] if n > size else [0]
    xs, ys = starts(width), starts(height)

    def cores(s, n):
        edges = [0] + [(s[i] + size + s[i + 1]) // 2 for i in range(len(s) - 1)] + [n]
        return list(zip(edges[:-1], edges[1:]))
    return [(x, y, cx, cy) for x, cx in zip(xs, cores(xs, width)) for y, cy in zip(ys, cores(ys, height))]


def detect_tiled(detector, image, confidence):
    h, w = image.shape[:2]
    plan = tiles(w, h)
    found = detector.detect_many([image[y:y + TILE_PX, x:x + TILE_PX] for x, y, _, _ in plan], confidence)
    boxes, scores, ids = [], [], []
    for (x, y, (cx0, cx1), (cy0, cy1)), det in zip(plan, found):
        b = det.boxes_xyxy + [x, y, x, y]
        mx, my = 0.5 * (b[:, 0] + b[:, 2]), 0.5 * (b[:, 1] + b[:, 3])
        keep = (mx >= cx0) & (mx < cx1) & (my >= cy0) & (my < cy1)
        boxes.append(b[keep]), scores.append(det.scores[keep]), ids.append(det.class_ids[keep])
    return np.concatenate(boxes), np.concatenate(scores), np.concatenate(ids)


def bench_gtsdb(detector, confidence, ids=GTSDB_HELDOUT_IDS):
    import cv2

    out = {}
    rows = read_gtsdb(ids)
    for mode in ("tiles_640", "whole_frame_letterboxed"):
        matches, matches_20 = [], []
        t0 = time.perf_counter()
        for path, gt, classes in rows:
            image = cv2.imread(path)
            if mode == "tiles_640":
                boxes, scores, ids = detect_tiled(detector, image, 0.05)
            else:
                d = detector.detect(image, 0.05)
                boxes, scores, ids = d.boxes_xyxy, d.scores, d.class_ids
            matches.append(match_image(boxes, scores, ids, gt, classes, 0.5))
            big = (gt[:, 3] - gt[:, 1]) >= MIN_HEIGHT_PX
            matches_20.append(match_image(boxes, scores, ids, gt[big], classes[big], 0.5, ignore_boxes=gt[~big]))
        out[mode] = {"images": len(rows), "per_class": summarise(matches, CLASSES, confidence),
                     "signs_20px_and_up": summarise(matches_20, CLASSES, confidence)["all"],
                     "seconds_per_image": (time.perf_counter() - t0) / len(rows),
                     "threshold_sweep": {f"{t:.2f}": summarise(matches, CLASSES, t)["all"]
                                         for t in (0.2, 0.3, 0.4, 0.5, 0.6)}}
    return out


def print_table(title, per_class):
    print(f"\n{title}")
    print(f"{'class':<13}{'true':>6}{'det':>6}{'hits':>6}{'precision':>11}{'recall':>8}")
    for name, s in per_class.items():
        print(f"{name:<13}{s['true']:>6}{s['detections']:>6}{s['hits']:>6}{s['precision']:>11.3f}{s['recall']:>8.3f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns.onnx"))
    ap.add_argument("--scene", action="append", help="held-out generated scene folder(s); "
                    "default bench/out/scene-default-7, generated when missing")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--confidence", type=float, default=0.4, help="the plugin's default CONFIDENCE")
    ap.add_argument("--min-size", type=float, default=detector_mod.DEFAULT_MIN_BOX_PX,
                    help="the plugin's MIN_SIZE: merged boxes with a shorter side under this (px) are dropped")
    ap.add_argument("--max-images", type=int, default=None, help="panoramas per scene (default all)")
    ap.add_argument("--skip-gtsdb", action="store_true")
    ap.add_argument("--json", default=os.path.join(REPO_ROOT, "bench", "out", "detector.json"))
    a = ap.parse_args(argv)

    scenes = a.scene or [os.path.join(REPO_ROOT, "bench", "out", "scene-default-7")]
    for scene in scenes:
        if not os.path.isfile(os.path.join(scene, "scene.json")):
            from devtools.scenegen import generate_scene
            name = os.path.basename(os.path.normpath(scene)).split("-")
            generate_scene(name[1], int(name[2]), scene, lidar=False)
    detector = detector_mod.Detector(a.model, threads=a.threads)
    print(detector.info().describe())
    result = {"model": os.path.relpath(a.model, REPO_ROOT), "model_mb": os.path.getsize(a.model) / 1e6,
              "threads": a.threads, "confidence": a.confidence, "scenes": scenes}
    result["min_size_px"] = a.min_size
    result["panoramas"] = bench_panoramas(detector, scenes, a.confidence, a.max_images, a.min_size)
    p = result["panoramas"]
    print_table(f"Generated panoramas ({p['images']}, held-out seeds), signs >= {MIN_HEIGHT_PX:.0f} px, "
                f"occlusion <= {MAX_OCCLUSION}, confidence {a.confidence}, boxes from {a.min_size:g} px",
                p["per_class"])
    print(f"signs under {MIN_HEIGHT_PX:.0f} px: {p['small_under_20px']}\nsigns more than half hidden: "
          f"{p['occluded_over_half']}\n"
          f"detections on back faces: {p['detections_on_back_faces']}\n"
          f"without signs seen edge-on (< {EDGE_ON_MAX_WIDTH_PX:.0f} px wide): {p['without_edge_on']}")
    print("threshold sweep (all classes): " + ", ".join(
        f"{t}: P {v['precision']:.3f} R {v['recall']:.3f}" for t, v in p["threshold_sweep"].items()))
    result["panoramas_per_second"] = 1.0 / p["seconds_per_panorama_detect"]
    print(f"panoramas per second ({a.threads} threads, decoded): {result['panoramas_per_second']:.2f} "
          f"(+ {p['seconds_per_panorama_decode_jpeg']:.3f} s to decode each JPEG)")
    if not a.skip_gtsdb:
        result["gtsdb_500_599"] = bench_gtsdb(detector, a.confidence)
        for mode, r in result["gtsdb_500_599"].items():
            print_table(f"GTSDB 500-599, {mode}, confidence {a.confidence}", r["per_class"])
            print(f"signs >= 20 px: {r['signs_20px_and_up']}")
            print("threshold sweep (all classes): " + ", ".join(
                f"{t}: P {v['precision']:.3f} R {v['recall']:.3f}" for t, v in r["threshold_sweep"].items()))
    os.makedirs(os.path.dirname(a.json), exist_ok=True)
    with open(a.json, "w") as f:
        json.dump(result, f, indent=1, default=float)
    print(f"\nwrote {a.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
