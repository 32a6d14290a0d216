"""The sign-code classifier's figures: accuracy on held-out real and generated signs, on the
signs the detector finds in real photographs, and crops per second on the CPU.

    python bench/bench_codes.py [--model models/signcodes.onnx] [--compare OTHER.onnx ...]
                                [--threads 2] [--json bench/out/codes.json]

Everything runs through the plugin's own engine (``core.signcodes``: ``CodeClassifier``,
``cut_crop``), several models in the same run:

- **GTSRB held-out tracks**: the 188 tracks (1,880 crops) no model of the project trains on
  (``devtools.train.data.gtsrb_track_split``), each cut square around its ROI with the
  model's margin, as the chain cuts a box; accuracy, and the worst codes;
- **held-out generated panoramas**: every front face of ``bench/out/scene-default-7``,
  ``scene-tiny-3`` and ``scene-default-11`` (bench seeds, never trained on) at least 10 px
  and under 30 % occluded, cut from the panorama with ``cut_crop`` around its true box; and
  the same for boxes of at least detectsigns' MIN_SIZE default (12 px), the smallest detection
  the chain reads;
- **GTSDB 500-599, through the detector**: the bundled detector on tiles of its input size of each
  photograph (as ``bench_detector``); each detection matching a true sign (IoU >= 0.5) is cut
  with the model's margin and read; accuracy among them against the sign's GTSRB code;
- **speed**: crops per second on ``--threads`` threads for crops of 12-120 px (cutting from a
  panorama as the chain does, ``CodeClassifier.cut_crop``; resizing and inference), and the
  inference alone.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections import Counter

import numpy as np

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools import import_roadsigns  # noqa: E402
from devtools.train import codes as train_codes  # noqa: E402
from devtools.train.data import GTSDB_HELDOUT_IDS, read_gtsdb  # noqa: E402
from devtools.train.metrics import iou_matrix  # noqa: E402

signcodes = import_roadsigns("roadsigns.core.signcodes")
detector_mod = import_roadsigns("roadsigns.core.detector")

MODEL = os.path.join(REPO_ROOT, "models", "signcodes.onnx")
TABLE = os.path.join(REPO_ROOT, "models", "sign-codes-de.csv")


def read(classifier, crops_bgr):
    """Codes and scores of BGR crops through the plugin's classifier."""
    return classifier.classify([c[..., ::-1] for c in crops_bgr])


def accuracy_report(codes, truth):
    codes, truth = np.asarray(codes), np.asarray(truth)
    right = codes == truth
    wrong = Counter((t, c) for t, c, ok in zip(truth, codes, right) if not ok)
    per_code = {}
    for t in sorted(set(truth)):
        m = truth == t
        per_code[t] = {"n": int(m.sum()), "accuracy": float(right[m].mean())}
    return {"n": int(len(truth)), "accuracy": float(right.mean()) if len(truth) else float("nan"),
            "read_as_other": int((codes == signcodes.OTHER_CODE).sum()),
            "read_as_back": int((codes == signcodes.BACK_CODE).sum()),
            "confusions": [[t, c, n] for (t, c), n in wrong.most_common(12)],
            "worst_codes": sorted(([k, v["n"], round(v["accuracy"], 3)] for k, v in per_code.items()
                                   if v["accuracy"] < 1.0), key=lambda r: r[2])[:8]}


def bench_gtsrb(classifier):
    names = list(classifier.names)
    crops, labels, _ = train_codes.heldout_gtsrb(names, "test")
    found, _ = read(classifier, crops)
    return accuracy_report(found, [names[k] for k in labels])


def bench_panoramas(classifier, work):
    """The held-out panoramas' crops read once: the report on all of them (boxes of at least
    ``MIN_PANO_BOX_PX``) and on those the chain reads (at least its ``MIN_SIZE``)."""
    names = list(classifier.names)
    crops, labels, sides = train_codes.heldout_pano(names, train_codes.held_out_scenes(),
                                                    os.path.join(work, "pano-heldout.npz"))
    if not len(labels):
        note = {"n": 0, "note": "no held-out scenes in bench/out (run bench_chain.py --seed 7 first)"}
        return note, note
    found, _ = read(classifier, crops)
    truth = [names[k] for k in labels]
    chain = np.flatnonzero(sides >= train_codes.chain_min_box_px())
    return accuracy_report(found, truth), accuracy_report([found[k] for k in chain], [truth[k] for k in chain])


def bench_gtsdb(classifiers, detector_path, confidence):
    """Detections on GTSDB 500-599 that match a true sign, read by each classifier."""
    import cv2

    sys.path.insert(0, os.path.join(REPO_ROOT, "bench"))
    from bench_detector import detect_tiled

    gtsrb_code = train_codes.gtsrb_codes()
    det = detector_mod.Detector(detector_path, threads=2)
    crops, truth = [], []
    n_true, n_found = 0, 0
    raw = {path: [] for path, _, _ in read_gtsdb(GTSDB_HELDOUT_IDS)}  # GTSRB ids come from gt.txt below
    images = {}
    with open(os.path.join(train_codes.data.DATA_DIR, "gtsdb-train", "gt.txt")) as f:
        for line in f:
            p = line.strip().split(";")
            if len(p) == 6 and int(p[0].split(".")[0]) in GTSDB_HELDOUT_IDS:
                raw[os.path.join(train_codes.data.DATA_DIR, "gtsdb-train", "images",
                                 p[0].replace(".ppm", ".jpg"))].append([float(p[1]), float(p[2]), float(p[3]) + 1,
                                                                        float(p[4]) + 1, int(p[5])])
    for path, rows in raw.items():
        image = cv2.imread(path)
        boxes, scores, _ = detect_tiled(det, image, confidence)
        n_true += len(rows)
        if not len(rows) or not len(boxes):
            continue
        gt = np.array([r[:4] for r in rows])
        iou = iou_matrix(boxes, gt)
        for j in range(len(gt)):
            i = int(np.argmax(iou[:, j]))
            if iou[i, j] >= 0.5:
                n_found += 1
                crops.append(boxes[i])
                truth.append((path, gtsrb_code[rows[j][4]]))
                images[path] = image  # each photograph read once, cut once per classifier
    out = []
    for classifier in classifiers:
        cut = [train_codes.crop_square(images[p], b, margin=classifier.crop_margin,
                                       out_px=classifier.input_px) for (p, _), b in zip(truth, crops)]
        found, _ = read(classifier, cut)
        r = accuracy_report(found, [c for _, c in truth])
        r.update(true_signs=n_true, found_by_detector=n_found)
        out.append(r)
    return out


def bench_speed(classifier, threads, n=2000, seed=0):
    """Crops per second: cut from a 4096 x 2048 panorama + read, and the model alone."""
    rng = np.random.default_rng(seed)
    pano = rng.integers(0, 255, (2048, 4096, 3), np.uint8)
    sides = rng.uniform(12, 120, n)
    u0 = rng.uniform(0, 4096, n)
    v0 = rng.uniform(700, 1200, n)
    boxes = np.stack([u0, v0, u0 + sides, v0 + sides * rng.uniform(0.8, 1.2, n)], 1)
    t0 = time.perf_counter()
    crops = [classifier.cut_crop(pano, b) for b in boxes]  # as the chain cuts them
    t_cut = time.perf_counter() - t0
    classifier.classify(crops[:64])  # warm-up
    t0 = time.perf_counter()
    classifier.classify(crops)
    t_read = time.perf_counter() - t0
    blob = np.zeros((64, 3, classifier.input_px, classifier.input_px), np.float32)
    t0 = time.perf_counter()
    reps = max(1, n // 64)
    for _ in range(reps):
        classifier.session.run(None, {classifier.input_name: blob})
    t_model = time.perf_counter() - t0
    return {"threads": threads, "crops": n, "cut_per_s": n / t_cut, "read_per_s": n / t_read,
            "cut_and_read_per_s": n / (t_cut + t_read), "model_only_per_s": reps * 64 / t_model}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", default=MODEL)
    ap.add_argument("--compare", nargs="*", default=[], metavar="ONNX")
    ap.add_argument("--table", default=TABLE)
    ap.add_argument("--detector", default=os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx"))
    ap.add_argument("--confidence", type=float, default=0.4)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--skip-gtsdb", action="store_true")
    ap.add_argument("--work", default=train_codes.WORK_DIR)
    ap.add_argument("--json", default=os.path.join(REPO_ROOT, "bench", "out", "codes.json"))
    a = ap.parse_args(argv)
    os.makedirs(a.work, exist_ok=True)
    table = signcodes.read_codes_table(a.table)
    paths = list(dict.fromkeys(os.path.abspath(p) for p in [a.model] + list(a.compare)))  # each model once
    classifiers = [signcodes.CodeClassifier(p, table, threads=a.threads) for p in paths]
    results = {p: {"model": c.describe()} for p, c in zip(paths, classifiers)}
    for p, c in zip(paths, classifiers):
        train_codes.set_crop_px(c.input_px)  # held-out crops cut at this model's input size, as the chain's are
        results[p]["gtsrb_heldout_tracks"] = bench_gtsrb(c)
        (results[p]["heldout_generated_panoramas"],
         results[p]["heldout_generated_panoramas_min_size"]) = bench_panoramas(c, a.work)
        results[p]["speed"] = bench_speed(c, a.threads)
    if not a.skip_gtsdb:
        for p, r in zip(paths, bench_gtsdb(classifiers, a.detector, a.confidence)):
            results[p]["gtsdb_500_599_detected"] = r
    for p, r in results.items():
        print("\n==", os.path.relpath(p, REPO_ROOT), "--", r["model"])
        for key in ("gtsrb_heldout_tracks", "heldout_generated_panoramas", "heldout_generated_panoramas_min_size",
                    "gtsdb_500_599_detected"):
            v = r.get(key)
            if not v or not v.get("n"):
                continue
            print("  {:36s} accuracy {:.4f} of {:5d}  read as other {:3d}, as back {:3d}  worst {}".format(
                key, v["accuracy"], v["n"], v["read_as_other"], v["read_as_back"], v["worst_codes"][:4]))
            if v["confusions"]:
                print("  {:36s} confusions {}".format("", v["confusions"][:6]))
        s = r["speed"]
        print("  speed ({} threads): cut {:.0f}/s, read {:.0f}/s, cut+read {:.0f}/s, model alone {:.0f}/s".format(
            s["threads"], s["cut_per_s"], s["read_per_s"], s["cut_and_read_per_s"], s["model_only_per_s"]))
    with open(a.json, "w") as f:
        json.dump(results, f, indent=1)
    print("\nwritten", a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
