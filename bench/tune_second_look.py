"""The second look's rule, chosen on one half of the held-out real signs and tested on the other.

detectsigns keeps a box the detector scores under ``CONFIDENCE`` when the sign-code classifier
confirms it (``core/rescue.py``). Its first rule was chosen on GTSDB 500-599, so those
photographs cannot test it. This bench collects, once, every box the bundled detector scores
from 0.05 on three sets of street photographs, cut into tiles as ``bench_detector.py`` cuts
them:

* ``tracks_A`` and ``tracks_B``: the held-out ``gtsrb-train`` tracks (real signs neither
  network trained on) pasted into GTSDB 500-599 frames (``bench_detector.heldout_track_frames``),
  every other track in each half, each half pasted with its own seed. Rules are **chosen on
  A** and **tested on B**.
* ``gtsdb``: GTSDB 500-599 as they are (the set the first rule was chosen on; shown, not used).

For each box under the confidence that overlaps no detection (a *candidate*, merged as
``core.rescue`` merges them): its box, its share of sheeting colours and the
classifier's probabilities. Every rule of a grid is then scored on each set without running a
network again: precision, recall and F1 of the detections plus the kept candidates, and
mandatory recall. Three kinds of rule: ``code`` (the rule until 27 November: the best code,
not ``other``, has at least the probability), ``class`` (today's: the codes of one class add
up to at least it, ``rescue.class_reading``: a speed limit whose digits are unsure is still a
prohibitory sign; that class is given) and ``sign``
(the probability that the crop is any sign in the table, ``1 - P(other)``, is at least it;
the class is the one whose codes add up to most).

    .venv/bin/python bench/tune_second_look.py [--json bench/out/tune-second-look.json]
"""
from __future__ import annotations

import argparse
import itertools
import json
import os
import sys
import time
from dataclasses import replace

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import bench_detector as bd  # noqa: E402

from devtools.train.codes import crop_square  # noqa: E402
from devtools.train.data import CLASSES, GTSDB_HELDOUT_IDS  # noqa: E402
from devtools.train.metrics import match_image  # noqa: E402

REPO_ROOT = bd.REPO_ROOT
#: The grid of rules: kind, probability, shortest side (px), sheeting share, lowest detector score.
KINDS = ("code", "class", "sign")
PROBABILITIES = (0.5, 0.6, 0.7, 0.8, 0.9, 0.95)
MIN_SIDES_PX = (10.0, 12.0, 14.0, 16.0)
MIN_SHEETING = (0.0, 0.02, 0.05, 0.1)
FLOORS = (0.05, 0.1, 0.2)


def collect(detector, classifier, frames, confidence):
    """Per frame: truth, ignored boxes (the road signs the truth leaves out among them), the
    detections at ``confidence`` and the candidates with their features (score, class id,
    box, sheeting, probabilities)."""
    rows = []
    for frame in frames:   # bench_detector.Frame
        image, gt, classes = frame.image, frame.boxes, frame.classes
        ignore = np.concatenate([frame.ignored, frame.unlabelled])
        boxes, scores, ids = bd.detect_tiled(detector, image, bd.rescue_mod.DEFAULT_RESCUE_CONFIDENCE)
        sure, cands = bd.photo_candidates(boxes, scores, confidence)
        rgb = image[..., ::-1]
        crops = [crop_square(rgb, boxes[j], margin=classifier.crop_margin, out_px=classifier.input_px)
                 for j in cands]
        probs = classifier.probabilities(crops) if len(crops) else np.zeros((0, len(classifier.names)))
        c_boxes = boxes[cands].reshape(-1, 4)
        rows.append({
            "gt": gt, "classes": classes, "ignore": ignore,
            "sure": (boxes[sure].reshape(-1, 4), scores[sure], ids[sure]),
            "cand_boxes": c_boxes, "cand_scores": scores[cands], "cand_ids": ids[cands],
            "sheeting": np.array([bd.sheeting_mod.sheeting_fraction(image, b) for b in c_boxes]),
            "probs": probs})
    return rows


class Reader:
    """What a rule reads in the classifier's probabilities: per candidate, for each kind of
    rule (:data:`KINDS`), the probability it compares and the class it gives: the best code's
    (``other`` excluded from being best), the best class's (its codes added up,
    ``rescue.class_reading``), and ``1 - P(other)`` (with the best class).
    ``other``: the column of ``other``; ``column_class``: each column's class
    (``rescue.code_classes``: detector order, negative for none); ``n_classes``: the
    detector's classes."""

    def __init__(self, other: int, column_class, n_classes: int):
        self.other, self.column_class, self.n_classes = other, np.asarray(column_class), n_classes

    @classmethod
    def of(cls, classifier, class_names):
        names = list(classifier.names)
        return cls(names.index(bd.signcodes_mod.OTHER_CODE),
                   bd.rescue_mod.code_classes(names, classifier.table, class_names), len(class_names))

    def read(self, probs, det_ids):
        if not len(probs):
            z = np.zeros(0)
            return {kind: (z, z.astype(np.int64)) for kind in KINDS}
        best = probs.argmax(1)
        code_p = np.where(best == self.other, 0.0, probs[np.arange(len(best)), best])
        code_cls = np.where(best == self.other, det_ids, self.column_class[best])
        code_cls = np.where(code_cls < 0, det_ids, code_cls)
        best_class, class_p = bd.rescue_mod.class_reading(probs, self.column_class, self.n_classes)
        best_class = np.where(best_class < 0, det_ids, best_class)
        return {"code": (code_p, code_cls), "class": (class_p, best_class),
                "sign": (1.0 - probs[:, self.other], best_class)}


def score_rule(rows, reads, rule, confidence):
    """Precision, recall, F1 and mandatory recall of the detections plus the candidates ``rule``
    keeps (kind, probability, side, sheeting, floor), on ``rows``. The size and colour checks
    are the plugin's own (``rescue.worth_reading`` with that side and sheeting share, so a
    candidate under ``small_box_px`` also needs ``small_min_score``, as in detectsigns)."""
    kind, p_min, side_min, sheet_min, floor = rule
    gate = replace(bd.rescue_mod.DEFAULT_RULE, min_box_px=side_min, min_sheeting=sheet_min)
    n_det = n_tp = n_true = n_hit = 0
    mand = CLASSES.index("mandatory")
    m_true = m_hit = 0
    for row, read in zip(rows, reads):
        prob, cls = read[kind]
        keep = ((row["cand_scores"] >= floor) & (prob >= p_min)
                & bd.rescue_mod.worth_reading(row["cand_boxes"], row["sheeting"], row["cand_scores"], gate))
        b, s, i = row["sure"]
        boxes = np.concatenate([b, row["cand_boxes"][keep]])
        scores = np.concatenate([s, np.full(int(keep.sum()), confidence)])
        ids = np.concatenate([i, cls[keep]]).astype(np.int64)
        m = match_image(boxes, scores, ids, row["gt"], row["classes"], 0.5,
                        ignore_boxes=row["ignore"] if len(row["ignore"]) else None)
        n_det += int((~m["ignored"]).sum())
        n_tp += int(m["tp"].sum())
        n_true += len(row["classes"])
        n_hit += int(m["hit"].sum())
        is_m = np.asarray(row["classes"]) == mand
        m_true += int(is_m.sum())
        m_hit += int(m["hit"][is_m].sum())
    p = n_tp / n_det if n_det else float("nan")
    r = n_hit / n_true if n_true else float("nan")
    f1 = 2 * p * r / (p + r) if p + r > 0 else 0.0
    return {"P": p, "R": r, "F1": f1, "mandatory_R": m_hit / m_true if m_true else float("nan"),
            "true": n_true, "hits": n_hit, "detections": n_det}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx"))
    ap.add_argument("--classifier", default=os.path.join(REPO_ROOT, "models", "signcodes.onnx"))
    ap.add_argument("--confidence", type=float, default=bd.detector_mod.DEFAULT_CONFIDENCE)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--top", type=int, default=15, help="rules printed, best F1 on A first")
    ap.add_argument("--json", default=os.path.join(REPO_ROOT, "bench", "out", "tune-second-look.json"))
    a = ap.parse_args(argv)

    detector = bd.detector_mod.Detector(a.model, threads=a.threads)
    table = bd.signcodes_mod.read_codes_table(os.path.join(REPO_ROOT, "models", "sign-codes-de.csv"))
    classifier = bd.signcodes_mod.CodeClassifier(a.classifier, table, threads=a.threads)
    reader = Reader.of(classifier, detector.class_names)
    sets = {"tracks_A": lambda: bd.heldout_track_frames(half=0, seed=11),
            "tracks_B": lambda: bd.heldout_track_frames(half=1, seed=12),
            "gtsdb": lambda: bd.gtsdb_frames(GTSDB_HELDOUT_IDS)}
    data = {}
    for name, frames in sets.items():
        t0 = time.perf_counter()
        rows = collect(detector, classifier, frames(), a.confidence)
        data[name] = (rows, [reader.read(r["probs"], r["cand_ids"]) for r in rows])
        print(f"{name}: {len(rows)} frames, {sum(len(r['classes']) for r in rows)} signs, "
              f"{sum(len(r['cand_scores']) for r in rows)} candidates ({time.perf_counter() - t0:.0f} s)", flush=True)

    today = ("class", bd.rescue_mod.DEFAULT_RULE.min_class_score, bd.rescue_mod.DEFAULT_RULE.min_box_px,
             bd.rescue_mod.DEFAULT_RULE.min_sheeting, bd.rescue_mod.DEFAULT_RESCUE_CONFIDENCE)
    none = ("code", 2.0, 0.0, 0.0, 1.0)  # keeps nothing: the detector alone
    grid = [none, today] + [r for r in itertools.product(KINDS, PROBABILITIES, MIN_SIDES_PX, MIN_SHEETING, FLOORS)
                            if r != today]
    results = []
    for rule in grid:
        results.append({"rule": dict(zip(("kind", "probability", "min_side_px", "min_sheeting", "floor"), rule)),
                        **{name: score_rule(rows, reads, rule, a.confidence) for name, (rows, reads) in data.items()}})
    ranked = sorted(results[2:], key=lambda r: -r["tracks_A"]["F1"])

    def line(label, r):
        cells = "  ".join(f"{r[n]['P']:.3f}/{r[n]['R']:.3f} F1 {r[n]['F1']:.3f} M {r[n]['mandatory_R']:.3f}"
                          for n in data)
        print(f"{label:<34}{cells}")

    print(f"\nconfidence {a.confidence}; per set P/R, F1 and mandatory recall: " + ", ".join(data))
    line("detector alone", results[0])
    line("today's rule " + "/".join(str(v) for v in today), results[1])
    for r in ranked[:a.top]:
        line("/".join(str(v) for v in r["rule"].values()), r)
    os.makedirs(os.path.dirname(a.json), exist_ok=True)
    with open(a.json, "w") as f:
        json.dump({"confidence": a.confidence, "detector_alone": results[0], "today": results[1],
                   "ranked_by_A": ranked}, f, indent=1, default=float)
    print(f"wrote {a.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
