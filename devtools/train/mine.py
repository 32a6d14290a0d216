"""Hard negatives mined from real photographs: the boxes a detector scores on GTSDB's training
frames (0-499) where the truth has no sign, for training to look at again (the data mix's
``gtsdb_hard`` source crops round them).

GTSDB labels only the 43 GTSRB classes, so many of those boxes are real signs the truth
leaves out: parking and direction panels, crossings, no-parking signs. Training on those
frames has so far taught the detector that such signs are background. The contact sheet
(``--sheet``) numbers every mined box, and a person reads it: ``--signs`` gives the numbers
of real signs whose box fits, with their class (they become labelled signs of their frame),
``--ignore`` those too unsure or badly boxed (ignore regions). The rest are false alarms.

    python -m devtools.train.mine --model bench/out/train-faces/cand-384.onnx \
        --cache /tmp/mined-raw.json --sheet /tmp/mined.png
    python -m devtools.train.mine --model ... --cache /tmp/mined-raw.json \
        --signs 1:information,137:prohibitory --ignore 0,14
"""
from __future__ import annotations

import argparse
import json
import os
import sys

import cv2
import numpy as np

from . import data
from .metrics import iou_matrix

#: The committed list the data mix reads by default.
MINED_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gtsdb_false_alarms.json")
#: A box is a false alarm when it overlaps no true box by this IoU or more.
MAX_TRUTH_IOU = 0.1


def false_alarms(boxes, scores, class_ids, truth, confidence: float):
    """Rows ``[x0, y0, x1, y1, score, class]`` of the boxes scored ``>= confidence`` that
    overlap no ``truth`` box by :data:`MAX_TRUTH_IOU` or more, best first."""
    keep = np.asarray(scores) >= confidence
    boxes, scores, class_ids = np.asarray(boxes)[keep], np.asarray(scores)[keep], np.asarray(class_ids)[keep]
    if len(truth) and len(boxes):
        keep = iou_matrix(boxes, truth).max(axis=1) < MAX_TRUTH_IOU
        boxes, scores, class_ids = boxes[keep], scores[keep], class_ids[keep]
    order = np.argsort(-scores, kind="stable")
    return [[*map(float, boxes[k]), float(scores[k]), int(class_ids[k])] for k in order]


def mine(model_path: str, confidence: float, ids=data.GTSDB_TRAIN_IDS, progress=print):
    """``{frame id: false-alarm rows}`` of the detector ``model_path`` run as the bench runs it
    on photographs (tiles of its input size at full resolution)."""
    from devtools import import_roadsigns
    from devtools.photos import detect_tiled

    detector = import_roadsigns("roadsigns.core.detector").Detector(model_path, threads=2)
    out = {}
    for n, (frame_id, (path, truth, _)) in enumerate(zip(ids, data.read_gtsdb(ids))):
        image = cv2.imread(path)
        boxes, scores, class_ids = detect_tiled(detector, image, confidence)
        rows = false_alarms(boxes, scores, class_ids, truth, confidence)
        if rows:
            out[int(frame_id)] = rows
        if n % 100 == 0:
            progress(f"[mine] frame {frame_id}: {sum(len(v) for v in out.values())} false alarms so far")
    return out


def numbered(mined):
    """``(number, frame id, row)`` of every mined box, in a fixed order (frame, then score)."""
    k = 0
    for frame_id in sorted(mined, key=int):
        for row in mined[frame_id]:
            yield k, int(frame_id), row
            k += 1


def contact_sheet(mined, path: str, cell_px: int = 96, columns: int = 16):
    """A PNG of every mined box with some context, numbered, for a person to pick out real signs."""
    items = list(numbered(mined))
    rows = max(1, -(-len(items) // columns))
    sheet = np.full((rows * (cell_px + 14), columns * cell_px, 3), 255, np.uint8)
    ids = sorted({f for _, f, _ in items})
    paths = {frame_id: row[0] for frame_id, row in zip(ids, data.read_gtsdb(ids))}
    image, shown = None, None
    for k, frame_id, row in items:   # numbered() goes frame by frame: each frame read once
        if frame_id != shown:
            image, shown = cv2.imread(paths[frame_id]), frame_id
        x0, y0, x1, y1 = row[:4]
        side = max(x1 - x0, y1 - y0) * 1.6 + 8
        cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        a, b = int(max(0, cx - side / 2)), int(max(0, cy - side / 2))
        crop = image[b:int(cy + side / 2), a:int(cx + side / 2)]
        crop = cv2.resize(crop, (cell_px, cell_px), interpolation=cv2.INTER_AREA)
        r, c = divmod(k, columns)
        sheet[r * (cell_px + 14):r * (cell_px + 14) + cell_px, c * cell_px:(c + 1) * cell_px] = crop
        label = f"{k} {data.CLASSES[row[5]][:4]} {row[4]:.2f}"
        cv2.putText(sheet, label, (c * cell_px + 2, r * (cell_px + 14) + cell_px + 11), cv2.FONT_HERSHEY_PLAIN,
                    0.8, (0, 0, 0), 1, cv2.LINE_AA)
    cv2.imwrite(path, sheet)
    return len(items)


def read_mined(path: str = MINED_PATH):
    """The reviewed file: ``(false alarms, signs, ignored)``, each ``{frame id: rows}``;
    false alarms and ignored rows are boxes ``(4,)``, signs ``(box (4,), class index)``.
    Empty when the file is missing."""
    if not os.path.isfile(path):
        return {}, {}, {}
    with open(path) as f:
        doc = json.load(f)

    def boxes(key):
        return {int(k): [np.array(r[:4], np.float32) for r in rows] for k, rows in doc[key].items()}
    signs = {int(k): [(np.array(r[:4], np.float32), data.CLASS_INDEX[r[4]]) for r in rows]
             for k, rows in doc["unlabelled_signs"].items()}
    return boxes("false_alarms"), signs, boxes("ignored")


def label_frames(rows, ids, signs, ignored):
    """GTSDB ``rows`` ``(path, boxes, classes)`` of frames ``ids`` with the reviewed ``signs``
    (``{frame id: [(box, class index)]}``) added to their truth and ``ignored``
    (``{frame id: [box]}``) as their ignore regions: ``(path, boxes, classes, ignore)``."""
    out = []
    for frame_id, row in zip(ids, rows):
        path, boxes, classes = row[:3]
        extra = signs.get(int(frame_id), [])
        out.append((path,
                    np.concatenate([boxes, np.array([b for b, _ in extra], np.float32).reshape(-1, 4)]),
                    np.concatenate([classes, np.array([c for _, c in extra], np.int64)]),
                    np.array(ignored.get(int(frame_id), []), np.float32).reshape(-1, 4)))
    return out


def parse_review(signs: str, ignore: str):
    """``--signs "3:information,9:prohibitory"`` and ``--ignore "4,7"`` as ``({number: class},
    {numbers})``; a class must be one of :data:`data.CLASSES`."""
    named = {}
    for item in filter(None, (x.strip() for x in signs.split(","))):
        number, _, klass = item.partition(":")
        if klass not in data.CLASS_INDEX:
            raise ValueError(f"--signs {item!r}: NUMBER:CLASS expected, CLASS one of {', '.join(data.CLASSES)}")
        named[int(number)] = klass
    ignored = {int(x) for x in ignore.split(",") if x.strip()}
    both = sorted(set(named) & ignored)
    if both:
        raise ValueError(f"numbers both in --signs and --ignore: {both}")
    return named, ignored


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", required=True, help="the detector (ONNX) to mine with")
    ap.add_argument("--out", default=MINED_PATH)
    ap.add_argument("--confidence", type=float, default=0.3)
    ap.add_argument("--sheet", help="write a numbered contact sheet (PNG) of the mined boxes")
    ap.add_argument("--signs", default="", help="NUMBER:CLASS of real signs whose box fits, comma-separated")
    ap.add_argument("--ignore", default="", help="numbers of real or unsure signs to ignore, comma-separated")
    ap.add_argument("--cache", help="raw mined boxes (JSON): read if present, else written")
    a = ap.parse_args(argv)
    named, ignored = parse_review(a.signs, a.ignore)
    if a.cache and os.path.isfile(a.cache):
        with open(a.cache) as f:
            mined = json.load(f)
    else:
        mined = mine(a.model, a.confidence)
        if a.cache:
            with open(a.cache, "w") as f:
                json.dump(mined, f)
    if a.sheet:
        print(f"[mine] {contact_sheet(mined, a.sheet)} boxes on {a.sheet}")
    out = {"false_alarms": {}, "unlabelled_signs": {}, "ignored": {}}
    for k, frame_id, row in numbered(mined):
        box = [round(v, 1) for v in row[:4]]
        if k in named:
            out["unlabelled_signs"].setdefault(str(frame_id), []).append(box + [named[k]])
        else:
            key = "ignored" if k in ignored else "false_alarms"
            out[key].setdefault(str(frame_id), []).append(box + [round(row[4], 3)])
    doc = {"model": os.path.basename(a.model), "confidence": a.confidence, "frames": "GTSDB 0-499",
           "counts": {k: sum(len(v) for v in rows.values()) for k, rows in out.items()}, **out}
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(tmp, a.out)
    print(f"[mine] {doc['counts']} -> {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
