"""Matching detections to true boxes at an IoU threshold; precision, recall, AP50 (numpy only)."""
from __future__ import annotations

from typing import Dict, List

import numpy as np


def iou_matrix(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    a = np.asarray(a, float).reshape(-1, 4)
    b = np.asarray(b, float).reshape(-1, 4)
    iw = np.clip(np.minimum(a[:, None, 2], b[None, :, 2]) - np.maximum(a[:, None, 0], b[None, :, 0]), 0, None)
    ih = np.clip(np.minimum(a[:, None, 3], b[None, :, 3]) - np.maximum(a[:, None, 1], b[None, :, 1]), 0, None)
    inter = iw * ih
    area_a = (a[:, 2] - a[:, 0]) * (a[:, 3] - a[:, 1])
    area_b = (b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1])
    return inter / np.maximum(area_a[:, None] + area_b[None, :] - inter, 1e-9)


def match_image(pred_boxes, pred_scores, pred_classes, gt_boxes, gt_classes, iou_threshold=0.5,
                ignore_boxes=None, iou_fn=iou_matrix):
    """Greedy matching, best score first, same class, IoU >= threshold.

    Returns per prediction ``tp`` (bool) and ``ignored`` (unmatched but on an ignore box: a
    sign not counted, so neither a hit nor a false alarm), and per true box ``hit`` (bool).
    """
    order = np.argsort(-np.asarray(pred_scores, float), kind="stable")
    n, m = len(order), len(gt_classes)
    tp, ignored, hit = np.zeros(n, bool), np.zeros(n, bool), np.zeros(m, bool)
    # boxes go to ``iou_fn`` as given (a custom one may take wider truth rows)
    iou = iou_fn(np.asarray(pred_boxes), np.asarray(gt_boxes)) if n and m else np.zeros((n, m))
    ign = (iou_fn(np.asarray(pred_boxes), np.asarray(ignore_boxes))
           if n and ignore_boxes is not None and len(ignore_boxes) else np.zeros((n, 0)))
    for rank, i in enumerate(order):
        if m:
            cand = np.where((np.asarray(gt_classes) == pred_classes[i]) & ~hit, iou[i], -1.0)
            j = int(np.argmax(cand))
            if cand[j] >= iou_threshold:
                tp[rank], hit[j] = True, True
                continue
            if iou[i].max(initial=0.0) >= iou_threshold:  # right place, wrong class or a duplicate
                continue
        if ign.shape[1] and ign[i].max() >= iou_threshold:
            ignored[rank] = True
    scores_sorted = np.asarray(pred_scores, float)[order]
    classes_sorted = np.asarray(pred_classes)[order]
    return {"scores": scores_sorted, "classes": classes_sorted, "tp": tp, "ignored": ignored,
            "hit": hit, "gt_classes": np.asarray(gt_classes)}


def summarise(matches: List[dict], class_names, threshold: float) -> Dict[str, dict]:
    """Per class and overall: true boxes, hits, detections, precision, recall at ``threshold``."""
    out = {}
    for c, name in list(enumerate(class_names)) + [(None, "all")]:
        n_gt = n_hit = n_det = n_tp = 0
        for m in matches:
            sel_det = (m["scores"] >= threshold) & ~m["ignored"]
            if c is not None:
                sel_det &= m["classes"] == c
            # a true box counts as hit when a detection at or above the threshold matched it
            n_det += int(sel_det.sum())
            n_tp += int((sel_det & m["tp"]).sum())
            gt_sel = m["gt_classes"] == c if c is not None else np.ones(len(m["gt_classes"]), bool)
            n_gt += int(gt_sel.sum())
        # recall from tp counts (each tp hits exactly one true box)
        n_hit = n_tp
        out[name] = {"true": n_gt, "detections": n_det, "hits": n_hit,
                     "precision": n_tp / n_det if n_det else float("nan"),
                     "recall": n_hit / n_gt if n_gt else float("nan")}
    return out


def average_precision(matches: List[dict]) -> float:
    """AP at the matching IoU over all classes (all-point interpolation)."""
    scores = np.concatenate([m["scores"][~m["ignored"]] for m in matches] or [np.zeros(0)])
    tp = np.concatenate([m["tp"][~m["ignored"]] for m in matches] or [np.zeros(0, bool)])
    n_gt = sum(len(m["gt_classes"]) for m in matches)
    if n_gt == 0 or len(scores) == 0:
        return 0.0
    order = np.argsort(-scores, kind="stable")
    tp = tp[order]
    ctp = np.cumsum(tp)
    recall = ctp / n_gt
    precision = ctp / np.arange(1, len(tp) + 1)
    precision = np.maximum.accumulate(precision[::-1])[::-1]
    r = np.concatenate([[0.0], recall])
    return float(np.sum((r[1:] - r[:-1]) * precision))


def best_f1_threshold(matches: List[dict], thresholds=np.arange(0.1, 0.9, 0.05)):
    """(threshold, precision, recall) of the best F1 over all classes."""
    best = (0.3, 0.0, 0.0, -1.0)
    for t in thresholds:
        s = summarise(matches, [], t)["all"]
        p, r = s["precision"], s["recall"]
        if np.isnan(p) or np.isnan(r):
            continue
        f1 = 2 * p * r / max(p + r, 1e-9)
        if f1 > best[3]:
            best = (float(t), p, r, f1)
    return best[:3]
