"""Street photographs run through a detector as the bench runs them: cut into tiles of the
model's input size at full resolution, as the plugin cuts its views at the model's input
size (bench/bench_detector.py, devtools/train/mine.py)."""
from __future__ import annotations

import numpy as np

TILE_PX = 640


def tiles(width, height, tile_w=TILE_PX, tile_h=TILE_PX):
    """Tile origins covering the image, and each tile's core (a partition of the image):
    a detection is kept by the tile whose core holds its centre."""
    def starts(n, size):
        k = max(1, int(np.ceil((n - size) / (size * 0.6))) + 1) if n > size else 1
        return [int(round(i * (n - size) / max(k - 1, 1))) for i in range(k)] if n > size else [0]
    xs, ys = starts(width, tile_w), starts(height, tile_h)

    def cores(s, n, size):
        edges = [0] + [(s[i] + size + s[i + 1]) // 2 for i in range(len(s) - 1)] + [n]
        return list(zip(edges[:-1], edges[1:]))
    return [(x, y, cx, cy) for x, cx in zip(xs, cores(xs, width, tile_w))
            for y, cy in zip(ys, cores(ys, height, tile_h))]


def detect_tiled(detector, image, confidence):
    """Tiles of the model's input size (width x height) at full resolution, as the plugin
    cuts its views at the model's input size."""
    h, w = image.shape[:2]
    tile_w, tile_h = getattr(detector, "input_size", (TILE_PX, TILE_PX))
    plan = tiles(w, h, tile_w, tile_h)
    found = detector.detect_many([image[y:y + tile_h, x:x + tile_w] for x, y, _, _ in plan], confidence)
    boxes, scores, ids = [], [], []
    for (x, y, (cx0, cx1), (cy0, cy1)), det in zip(plan, found):
        b = det.boxes_xyxy + [x, y, x, y]
        mx, my = 0.5 * (b[:, 0] + b[:, 2]), 0.5 * (b[:, 1] + b[:, 3])
        keep = (mx >= cx0) & (mx < cx1) & (my >= cy0) & (my < cy1)
        boxes.append(b[keep]), scores.append(det.scores[keep]), ids.append(det.class_ids[keep])
    return np.concatenate(boxes), np.concatenate(scores), np.concatenate(ids)
