"""Train the sign-code classifier ``models/signcodes.onnx``.

    python -m devtools.train.codes --minutes 30 --out models/signcodes.onnx
    python -m devtools.train.codes --resume bench/out/codes/last.pt --minutes 60   # go on
    python -m devtools.train.codes --evaluate models/signcodes.onnx                # figures only

A crop is cut the way the chain cuts it (:func:`roadsigns.core.signcodes.cut_crop`): a square
around the sign's box, the box's longer side plus :data:`CROP_MARGIN` of it on each side, at
the source's native pixel density, then resized to :data:`CROP_PX` (area when shrinking).

Sources (``models/README.md``, "Sign-code classifier"):

- ``gtsrb-train``: real crops, 43 codes (``sign-codes-de.csv`` of the shared data folder maps
  GTSRB class ids to codes). **Split by track**: the tracks the detector holds out
  (``data.gtsrb_track_split``, every 7th of each class) are the test set here too, and
  every 9th of the rest is validation; no frame of those tracks is trained on.
  ``gtsrb-subset`` frames of training tracks join them.
- signs drawn by ``devtools.scenegen.textures`` (every variant with a code, fresh and
  faded), warped obliquely onto real street backgrounds (GTSDB 0-499) and degraded as a
  distant camera sees them;
- crops cut from generated panoramas of training scenes (seeds >= 100) around each sign's
  box, with the box jittered as a detector's would be;
- ``other``: street backgrounds, procedural look-alikes (``data.hard_negative``: traffic
  lights, shop signs, red-ringed logos, mirrors, roundels, sign backs), the generator's
  billboards and gantry panels, signs of the six shapes with legends no code in the table
  has (weight and height limits, other numbers, letters), and boxes mostly off a sign.

No horizontal flips: left and right are different codes.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import signal
import sys
import time
from collections import defaultdict
from typing import Optional

import cv2
import numpy as np

from .. import REPO_ROOT, import_roadsigns
from . import data

CROP_PX = 32
CROP_MARGIN = 0.15
OTHER = "other"
TABLE_PATH = os.path.join(REPO_ROOT, "models", "sign-codes-de.csv")
GTSRB_CODES_PATH = os.path.join(data.DATA_DIR, "sign-codes-de.csv")
WORK_DIR = os.path.join(REPO_ROOT, "bench", "out", "codes")
#: generated scenes whose panoramas give training crops (seeds >= 100), and held-out ones
TRAIN_SCENES = (os.path.join(REPO_ROOT, "bench", "out", "train", "scenes", "default-100"),
                os.path.join(REPO_ROOT, "bench", "out", "train", "scenes", "tiny-100"))
#: every this-many-th training track of each class (offset 1) is validation
VAL_EVERY = 9
#: share of each source in a batch
MIX = {"gtsrb": 0.45, "drawn": 0.15, "pano": 0.15, "other": 0.25}
#: composites (a drawn sign or a look-alike warped onto a street) are kept in a pool and
#: re-cut with a new jitter; each draw replaces a pooled one with this probability
POOL_SIZE, POOL_RENEW = 2000, 0.15


# --- labels --------------------------------------------------------------------------------

def read_table_codes(path: str = TABLE_PATH):
    """The codes of the table (file order): the classifier's names, ``other`` last."""
    with open(path, encoding="utf-8-sig") as f:
        lines = [ln for ln in f if ln.strip() and not ln.startswith("#")]
    rows = list(csv.DictReader(lines, delimiter=";"))
    return [r["code"] for r in rows]


def gtsrb_codes(path: str = GTSRB_CODES_PATH):
    with open(path, encoding="utf-8") as f:
        return {int(r["gtsrb_id"]): r["traffic_sign"] for r in csv.DictReader(f, delimiter=";")}


# --- cutting -------------------------------------------------------------------------------

def set_crop_px(px: int) -> None:
    """Train or evaluate at crops of ``px`` x ``px`` (``--crop-px``; default :data:`CROP_PX`):
    the network is size independent (global pooling), the exported model's input is ``px``,
    and the plugin cuts crops at its model's input size. Set before the workers start."""
    global CROP_PX
    if px < 16:
        raise SystemExit(f"--crop-px {px}: at least 16")
    CROP_PX = int(px)


def crop_square(image: np.ndarray, box, margin: float = CROP_MARGIN, scale: float = 1.0,
                shift=(0.0, 0.0), angle_deg: float = 0.0, out_px: Optional[int] = None) -> np.ndarray:
    """A square around ``box`` (x0, y0, x1, y1, exclusive ends) like the chain's crop: side =
    longer box side x (1 + 2 margin) x ``scale``, centre moved by ``shift`` x side, turned by
    ``angle_deg``; cut at native density (borders reflected), then resized to ``out_px``
    (default :data:`CROP_PX`)."""
    x0, y0, x1, y1 = (float(v) for v in box)
    side = max(x1 - x0, y1 - y0) * (1.0 + 2.0 * margin) * scale
    cx = 0.5 * (x0 + x1) + shift[0] * side
    cy = 0.5 * (y0 + y1) + shift[1] * side
    n = max(8, int(round(side)))
    M = cv2.getRotationMatrix2D((cx, cy), angle_deg, n / side)
    M[:, 2] += (0.5 * n - cx, 0.5 * n - cy)
    native = cv2.warpAffine(image, M, (n, n), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REFLECT101)
    return resize_to(native, out_px)


def resize_to(crop: np.ndarray, out_px: Optional[int] = None) -> np.ndarray:
    out_px = out_px or CROP_PX
    interp = cv2.INTER_AREA if crop.shape[0] > out_px else cv2.INTER_LINEAR
    return cv2.resize(crop, (out_px, out_px), interpolation=interp)


def far_camera(crop: np.ndarray, rng, strength: float = 1.0) -> np.ndarray:
    """A crop as a worse or farther camera sees it: fewer pixels, blur, JPEG, colour."""
    out = crop
    if rng.random() < 0.5 * strength:
        f = rng.uniform(0.35, 0.9)
        small = max(6, int(round(CROP_PX * f)))
        out = cv2.resize(cv2.resize(out, (small, small), interpolation=cv2.INTER_AREA), (CROP_PX, CROP_PX),
                         interpolation=cv2.INTER_LINEAR)
    if rng.random() < 0.25 * strength:
        out = cv2.filter2D(out, -1, data.motion_kernel(rng.uniform(1.2, 3.0), rng.uniform(0, 180)))
    out = data.colour_jitter(out, rng)
    if rng.random() < 0.3:
        out = data.jpeg(out, rng)
    return out


# --- sources -------------------------------------------------------------------------------

def _gtsrb_rows():
    root = os.path.join(data.DATA_DIR, "gtsrb-train")
    with open(os.path.join(root, "GT-train.csv")) as f:
        return root, list(csv.DictReader(f, delimiter=";"))


def gtsrb_split():
    """Track keys (ClassId, Track) of the test part (the detector's held-out tracks) and of
    the validation part (every :data:`VAL_EVERY`-th remaining track of each class)."""
    _, rows = _gtsrb_rows()
    test = data.gtsrb_track_split(rows)
    tracks = defaultdict(set)
    for row in rows:
        key = (int(row["ClassId"]), row["Track"])
        if key not in test:
            tracks[key[0]].add(row["Track"])
    val = set()
    for c, ts in tracks.items():
        val.update((c, t) for t in sorted(ts)[1::VAL_EVERY])
    return test, val


def load_gtsrb(part: str, names):
    """(image BGR, ROI box, label index, track key) of one part: train, val or test."""
    root, rows = _gtsrb_rows()
    test, val = gtsrb_split()
    code_of = gtsrb_codes()
    index = {n: k for k, n in enumerate(names)}
    out = []
    for row in rows:
        key = (int(row["ClassId"]), row["Track"])
        where = "test" if key in test else "val" if key in val else "train"
        if where != part:
            continue
        image = cv2.imread(os.path.join(root, "train", row["File"]))
        if image is None:
            continue
        box = (int(row["Roi.X1"]), int(row["Roi.Y1"]), int(row["Roi.X2"]) + 1, int(row["Roi.Y2"]) + 1)
        out.append((image, box, index[code_of[key[0]]], key))
    if part == "train":  # gtsrb-subset: one frame per physical sign, training tracks only
        sroot = os.path.join(data.DATA_DIR, "gtsrb-subset")
        with open(os.path.join(sroot, "GT-subset.csv")) as f:
            for row in csv.DictReader(f, delimiter=";"):
                key = (int(row["ClassId"]), row["Filename"].split("_")[0])
                if key in test or key in val:
                    continue
                image = cv2.imread(os.path.join(sroot, "train", row["ClassFolder"], row["Filename"]))
                if image is None:
                    continue
                box = (int(row["Roi.X1"]), int(row["Roi.Y1"]), int(row["Roi.X2"]) + 1, int(row["Roi.Y2"]) + 1)
                out.append((image, box, index[code_of[key[0]]], key))
    return out


def drawn_codes(names):
    """(class, variant, label index) of every sign ``textures.sign_texture`` draws with a code
    (``VARIANT_CODES``), the speed limit 40 too (the layouts do not use it, no GTSRB class has
    it). Gantry panels are drawn apart (``textures.gantry_texture``)."""
    tx = data.import_textures()
    index = {n: k for k, n in enumerate(names)}
    return [(cls, var, index[code]) for (cls, var), code in tx.VARIANT_CODES.items()
            if code in index and (var in tx.VARIANTS.get(cls, ()) or var.isdigit())]


def pano_crops(scene_dirs, names, cache_path: str):
    """Native-density crops (up to 96 px) of the front faces in generated panoramas, with the
    code of each sign from ``scene.json``: list of (crop BGR, label index). Cached."""
    if os.path.isfile(cache_path):
        z = np.load(cache_path, allow_pickle=True)
        return list(zip(z["crops"], z["labels"]))
    signcodes = import_roadsigns("roadsigns.core.signcodes")
    tx = data.import_textures()
    index = {n: k for k, n in enumerate(names)}
    crops, labels = [], []
    for scene_dir in scene_dirs:
        with open(os.path.join(scene_dir, "scene.json")) as f:
            scene = json.load(f)
        code = {s["sign_id"]: tx.VARIANT_CODES.get((s["class"], s["variant"]), OTHER) for s in scene["signs"]}
        for meta in scene["images"]:
            pano = cv2.imread(os.path.join(scene_dir, "images", meta["image"]))
            if pano is None:
                continue
            for s in meta["signs"]:
                b = s.get("visible_box")
                if s["facing"] != "front" or b is None or s["occlusion"] > 0.3:
                    continue
                if min(b[2] - b[0], b[3] - b[1]) < 10:
                    continue
                crop = signcodes.cut_crop(pano, (b[0], b[1], b[2] + 1, b[3] + 1), margin=CROP_MARGIN + 0.1,
                                          max_side_px=128)
                crops.append(cv2.cvtColor(crop, cv2.COLOR_RGB2BGR))
                labels.append(index.get(code[s["sign_id"]], index[OTHER]))
    np.savez(cache_path, crops=np.array(crops, dtype=object), labels=np.array(labels))
    return list(zip(crops, labels))


_UNKNOWN_LEGENDS = ("10", "15", "25", "35", "45", "90", "110", "130", "3.5t", "7.5t", "2.8m", "3m", "6t",
                    "AB", "X", "Z", "30t", "5", "B", "H", "E", "KM", "12", "U")


def unknown_sign(rng, size_px: int = 128) -> np.ndarray:
    """A sign of one of the six shapes whose legend no code in the table has (BGRA)."""
    tx = data.import_textures()
    kind = rng.choice(["ring", "ring", "triangle", "blue_disc", "blue_panel", "white_panel", "yellow_diamond"])
    if kind == "ring":
        img = tx.sign_texture("prohibitory", "30", size_px)
        c, r = size_px // 2, size_px // 2
        cv2.circle(img, (c, c), int(0.77 * r), (*tx.WHITE, 255), -1, cv2.LINE_AA)
        text = str(rng.choice(_UNKNOWN_LEGENDS))
        tx._text(img, text, tx.BLACK, (0.95 if len(text) >= 3 else 0.8) * r, (c, c), max(2, r // 14))
    elif kind == "triangle":
        img = tx.sign_texture("warning", "exclamation", size_px)
        h, w = img.shape[:2]
        # wipe the pictogram, draw another: letters or a blob
        tri = np.array([[w / 2, 0], [0, h - 1], [w - 1, h - 1]])
        cen = tri.mean(0)
        tx._fill(img, cen + 0.7 * (tri - cen), tx.WHITE)
        if rng.random() < 0.5:
            tx._text(img, str(rng.choice(["AB", "X", "!?", "Z", "KM", "E"])), tx.BLACK, 0.3 * w, cen + [0, 0.05 * h],
                     max(2, w // 40))
        else:
            pts = cen + rng.uniform(-0.15, 0.15, (int(rng.integers(3, 7)), 2)) * [w, h]
            tx._fill(img, cv2.convexHull(pts.astype(np.float32))[:, 0], tx.BLACK)
    elif kind == "blue_disc":
        img = tx.sign_texture("mandatory", "ahead", size_px)
        c, r = size_px // 2, size_px // 2
        cv2.circle(img, (c, c), r - 1, (*tx.BLUE, 255), -1, cv2.LINE_AA)
        if rng.random() < 0.5:
            tx._text(img, str(rng.choice(["AB", "30", "E", "KM"])), tx.WHITE, 0.9 * r, (c, c), max(2, r // 12))
        else:  # a bicycle-like glyph: two rings and a bar
            for dx in (-0.35, 0.35):
                cv2.circle(img, (int(c + dx * r), int(c + 0.2 * r)), int(0.25 * r), (*tx.WHITE, 255), max(2, r // 14),
                           cv2.LINE_AA)
            cv2.line(img, (int(c - 0.35 * r), int(c + 0.2 * r)), (int(c + 0.1 * r), int(c - 0.3 * r)),
                     (*tx.WHITE, 255), max(2, r // 14), cv2.LINE_AA)
    else:
        w, h = size_px, int(size_px * rng.uniform(0.6, 1.0))
        img = np.zeros((h, w, 4), np.uint8)
        bg = {"blue_panel": tx.BLUE, "white_panel": tx.WHITE, "yellow_diamond": tx.YELLOW}[kind]
        fg = tx.BLACK if kind != "blue_panel" else tx.WHITE
        if kind == "yellow_diamond":
            h = w
            img = np.zeros((h, w, 4), np.uint8)
            tx._fill(img, [[w / 2, 0], [w - 1, h / 2], [w / 2, h - 1], [0, h / 2]], tx.WHITE)
            tx._fill(img, [[w / 2, 0.08 * h], [0.92 * w, h / 2], [w / 2, 0.92 * h], [0.08 * w, h / 2]], tx.YELLOW)
        else:
            cv2.rectangle(img, (0, 0), (w - 1, h - 1), (*tx.WHITE, 255), -1)
            cv2.rectangle(img, (3, 3), (w - 4, h - 4), (*bg, 255), -1)
            cv2.rectangle(img, (5, 5), (w - 6, h - 6), (*fg, 255), 2)
            tx._text(img, str(rng.choice(["H", "i", "WC", "BUS", "ZONE", "Km", "SOS", "A7", "30"])), fg, 0.55 * w,
                     (w / 2, h / 2), max(2, w // 25))
        img[..., 3] = np.where(img[..., :3].max(-1) > 0, 255, 0).astype(np.uint8)
    img = cv2.cvtColor(img, cv2.COLOR_RGBA2BGRA)
    return img


class Sampler:
    """Draws labelled training crops (``CROP_PX`` square, BGR) from every source."""

    def __init__(self, names, seed: int = 0, pano_cache: str = ""):
        self.names = list(names)
        self.other = self.names.index(OTHER)
        self.rng = np.random.default_rng(seed)
        self.pools: dict = {}
        self.gtsrb = load_gtsrb("train", self.names)
        by_class = defaultdict(list)
        for k, item in enumerate(self.gtsrb):
            by_class[item[2]].append(k)
        self.gtsrb_classes = sorted(by_class)
        self.gtsrb_by_class = [np.array(by_class[c]) for c in self.gtsrb_classes]
        p = np.sqrt([len(by_class[c]) for c in self.gtsrb_classes])
        self.gtsrb_p = p / p.sum()
        tx = data.import_textures()
        self.tx = tx
        self.drawn = []
        for cls, var, label in drawn_codes(self.names):
            tex = cv2.cvtColor(tx.sign_texture(cls, var, 128), cv2.COLOR_RGBA2BGRA)
            self.drawn.append((tex, label))
            self.drawn.append((cv2.cvtColor(tx.faded(tx.sign_texture(cls, var, 128), 0.45), cv2.COLOR_RGBA2BGRA),
                               label))
        gantry_label = self.names.index(tx.VARIANT_CODES[("information", "gantry")])
        for lines in (["WIEN 12", "LINZ 180"], ["GRAZ 45", "A1"], ["ZENTRUM"], ["FLUGHAFEN 20", "MESSE 3"]):
            self.drawn.append((cv2.cvtColor(tx.gantry_texture(lines, 256), cv2.COLOR_RGBA2BGRA), gantry_label))
        self.scenes = data.read_gtsdb(data.GTSDB_TRAIN_IDS)
        self.images = data.ImageCache()
        self.pano = pano_crops(TRAIN_SCENES, self.names, pano_cache) if pano_cache else []

    # backgrounds
    def background(self, side: int) -> np.ndarray:
        path, boxes, _ = self.scenes[int(self.rng.integers(len(self.scenes)))]
        image = self.images.get(path)
        H, W = image.shape[:2]
        side = int(min(side, H - 1, W - 1))
        for _ in range(10):
            x, y = int(self.rng.integers(0, W - side)), int(self.rng.integers(0, H - side))
            if not len(boxes) or not any(
                    (x < b[2] and b[0] < x + side and y < b[3] and b[1] < y + side) for b in boxes):
                break
        return image[y:y + side, x:x + side].copy()

    def composite(self, patch_bgra: np.ndarray, sign_px: float):
        """``patch`` warped obliquely, pasted at ``sign_px`` (longer side) on a real street
        background; returns the image and the patch's box."""
        h, w = patch_bgra.shape[:2]
        s = sign_px / max(h, w)
        tw, th = max(4, int(round(w * s))), max(4, int(round(h * s)))
        small = cv2.resize(patch_bgra, (tw, th), interpolation=cv2.INTER_AREA)
        squeeze = math.cos(math.radians(self.rng.uniform(0, 55)))
        src = np.float32([[0, 0], [tw, 0], [tw, th], [0, th]])
        skew = self.rng.uniform(-0.08, 0.08) * th
        dw = tw * squeeze
        dst = np.float32([[0, 0], [dw, skew], [dw, th + skew], [0, th]])
        dst -= dst.min(0)
        out_w, out_h = int(math.ceil(dst[:, 0].max())) + 1, int(math.ceil(dst[:, 1].max())) + 1
        warped = cv2.warpPerspective(small, cv2.getPerspectiveTransform(src, dst), (out_w, out_h),
                                     flags=cv2.INTER_LINEAR)
        pad = int(max(out_w, out_h) * 0.8) + 4
        bg = self.background(max(out_w, out_h) + 2 * pad)
        if bg.shape[0] < out_h + 2 * pad:
            bg = cv2.resize(bg, (out_w + 2 * pad, out_h + 2 * pad))
        x0, y0 = pad, pad
        alpha = warped[..., 3:4].astype(np.float32) / 255.0
        roi = bg[y0:y0 + out_h, x0:x0 + out_w].astype(np.float32)
        bg[y0:y0 + out_h, x0:x0 + out_w] = (alpha * warped[..., :3] + (1 - alpha) * roi).astype(np.uint8)
        return bg, (x0, y0, x0 + out_w, y0 + out_h)

    def pooled(self, kind: str, make):
        """``make()`` -> (image, box, label), from a pool of recent ones (the warp is the slow part)."""
        pool = self.pools.setdefault(kind, [])
        if len(pool) < POOL_SIZE:
            pool.append(make())
            return pool[-1]
        k = int(self.rng.integers(len(pool)))
        if self.rng.random() < POOL_RENEW:
            pool[k] = make()
        return pool[k]

    def jitter(self):
        return dict(scale=self.rng.uniform(0.88, 1.15), shift=self.rng.uniform(-0.07, 0.07, 2),
                    angle_deg=self.rng.uniform(-7, 7))

    # sources
    def from_gtsrb(self):
        c = self.rng.choice(len(self.gtsrb_classes), p=self.gtsrb_p)
        image, box, label, _ = self.gtsrb[int(self.rng.choice(self.gtsrb_by_class[c]))]
        return far_camera(crop_square(image, box, **self.jitter()), self.rng), label

    def _drawn_composite(self):
        tex, label = self.drawn[int(self.rng.integers(len(self.drawn)))]
        image, box = self.composite(tex, self.rng.uniform(14, 90))
        image = data.degrade(np.dstack([image, np.full(image.shape[:2], 255, np.uint8)]), self.rng)[..., :3]
        return image, box, label

    def _other_composite(self):
        r = self.rng.random()
        if r < 0.35:
            patch, _ = data.hard_negative(self.rng, self.background(128))
        elif r < 0.85:
            patch = unknown_sign(self.rng)
        else:
            patch = cv2.cvtColor(self.tx.billboard_texture(self.rng, 256), cv2.COLOR_RGBA2BGRA)
        image, box = self.composite(patch, self.rng.uniform(14, 100))
        return image, box, self.other

    def from_drawn(self):
        image, box, label = self.pooled("drawn", self._drawn_composite)
        return far_camera(crop_square(image, box, **self.jitter()), self.rng, 0.7), label

    def from_pano(self):
        crop, label = self.pano[int(self.rng.integers(len(self.pano)))]
        n = crop.shape[0]
        inner = n / (1.0 + 2.0 * (CROP_MARGIN + 0.1))  # the sign's box inside the cached crop
        box = ((n - inner) / 2, (n - inner) / 2, (n + inner) / 2, (n + inner) / 2)
        return far_camera(crop_square(crop, box, **self.jitter()), self.rng, 0.5), int(label)

    def from_other(self):
        r = self.rng.random()
        if r < 0.25:
            crop = resize_to(self.background(int(self.rng.integers(12, 160))))
        elif r < 0.88:
            image, box, _ = self.pooled("other", self._other_composite)
            crop = crop_square(image, box, **self.jitter())
        else:  # a box mostly off a real sign
            image, box, _, _ = self.gtsrb[int(self.rng.integers(len(self.gtsrb)))]
            big = cv2.copyMakeBorder(image, *(4 * [image.shape[0]]), cv2.BORDER_REFLECT101)
            o = image.shape[0]
            shifted = [box[0] + o, box[1] + o, box[2] + o, box[3] + o]
            direction = self.rng.normal(size=2)
            direction /= np.linalg.norm(direction) + 1e-9
            crop = crop_square(big, shifted, shift=direction * self.rng.uniform(0.65, 1.0))
        return far_camera(crop, self.rng, 0.7), self.other

    def sample(self):
        sources = [k for k in MIX if k != "pano" or self.pano]
        p = np.array([MIX[k] for k in sources])
        which = sources[int(self.rng.choice(len(sources), p=p / p.sum()))]
        return getattr(self, "from_" + which)()

    def batch(self, n: int):
        crops, labels = zip(*(self.sample() for _ in range(n)))
        return np.stack(crops), np.array(labels, np.int64)


# --- held-out sets -------------------------------------------------------------------------

def heldout_gtsrb(names, part: str = "test"):
    """Crops of the held-out tracks as the chain would cut them (no jitter), and labels."""
    items = load_gtsrb(part, names)
    crops = np.stack([crop_square(image, box) for image, box, _, _ in items])
    return crops, np.array([lab for _, _, lab, _ in items]), [key for *_, key in items]


def heldout_pano(names, scene_dirs, cache_path: str):
    """Crops of held-out generated panoramas at the chain's margin (no jitter)."""
    items = pano_crops(scene_dirs, names, cache_path)
    out, labels = [], []
    for crop, label in items:
        n = crop.shape[0]
        inner = n / (1.0 + 2.0 * (CROP_MARGIN + 0.1))
        out.append(crop_square(crop, ((n - inner) / 2, (n - inner) / 2, (n + inner) / 2, (n + inner) / 2)))
        labels.append(int(label))
    return np.stack(out) if out else np.zeros((0, CROP_PX, CROP_PX, 3), np.uint8), np.array(labels, np.int64)


# --- model ---------------------------------------------------------------------------------

def build_net(n_classes: int, widths=(32, 64, 96, 160)):
    import torch.nn as nn

    from .model import ConvBN

    c1, c2, c3, c4 = widths

    class CodeNet(nn.Module):
        """RGB 0..1 ``[N, 3, S, S]`` (S = :data:`CROP_PX`; any size works) -> logits; normalisation inside."""

        def __init__(self):
            super().__init__()
            self.features = nn.Sequential(
                ConvBN(3, c1), nn.MaxPool2d(2),
                ConvBN(c1, c2), ConvBN(c2, c2), nn.MaxPool2d(2),
                ConvBN(c2, c3), ConvBN(c3, c3), nn.MaxPool2d(2),
                ConvBN(c3, c4), nn.AdaptiveAvgPool2d(1), nn.Flatten())
            self.head = nn.Sequential(nn.Dropout(0.25), nn.Linear(c4, n_classes))

        def forward(self, x):
            return self.head(self.features((x - 0.5) / 0.25))

    return CodeNet()


def to_tensor(crops_bgr: np.ndarray, device):
    import torch

    rgb = crops_bgr[..., ::-1].astype(np.float32) / 255.0
    return torch.from_numpy(np.ascontiguousarray(rgb.transpose(0, 3, 1, 2))).to(device)


def predict(net, crops_bgr: np.ndarray, device, batch: int = 512) -> np.ndarray:
    import torch

    net.eval()
    out = []
    with torch.no_grad():
        for k in range(0, len(crops_bgr), batch):
            out.append(torch.softmax(net(to_tensor(crops_bgr[k:k + batch], device)), 1).cpu().numpy())
    net.train()
    return np.concatenate(out) if out else np.zeros((0, 1))


def export_onnx(net, names, out_path: str, training: dict) -> None:
    import onnx
    import torch

    class WithSoftmax(torch.nn.Module):
        def __init__(self, inner):
            super().__init__()
            self.inner = inner

        def forward(self, x):
            return torch.softmax(self.inner(x), 1)

    net = net.cpu().eval()
    tmp = out_path + ".tmp.onnx"
    torch.onnx.export(WithSoftmax(net), torch.zeros(1, 3, CROP_PX, CROP_PX), tmp, input_names=["crops"],
                      output_names=["probabilities"], dynamic_axes={"crops": {0: "batch"},
                                                                    "probabilities": {0: "batch"}},
                      opset_version=17, dynamo=False)
    model = onnx.load(tmp)
    meta = {"names": json.dumps(list(names)), "task": "classify", "output": "probabilities",
            "crop_margin": str(CROP_MARGIN), "imgsz": json.dumps([CROP_PX, CROP_PX]),
            "training": json.dumps(training)}
    del model.metadata_props[:]
    for k, v in meta.items():
        entry = model.metadata_props.add()
        entry.key, entry.value = k, v
    onnx.save(model, tmp)
    os.replace(tmp, out_path)


# --- training ------------------------------------------------------------------------------

def pick_device(name: str):
    import torch

    if name == "auto":
        return torch.device("cuda" if torch.cuda.is_available() else "cpu")
    return torch.device(name)


def accuracy(prob: np.ndarray, labels: np.ndarray) -> float:
    return float((prob.argmax(1) == labels).mean()) if len(labels) else float("nan")


def _feed(names, seed, pano_cache, batch, queue):
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    sampler = Sampler(names, seed, pano_cache)
    while True:
        queue.put(sampler.batch(batch))


class BatchFeeder:
    """Training batches drawn in worker processes (the cut-and-warp work is the slow part on a
    CPU); each worker has its own random stream (``seed`` + 1000 k)."""

    def __init__(self, names, seed, pano_cache, batch, workers):
        import multiprocessing as mp

        ctx = mp.get_context("fork")
        self.queue = ctx.Queue(maxsize=16)
        self.procs = [ctx.Process(target=_feed, args=(names, seed + 1000 * (k + 1), pano_cache, batch, self.queue),
                                  daemon=True) for k in range(workers)]
        for p in self.procs:
            p.start()

    def get(self):
        return self.queue.get()

    def close(self):
        for p in self.procs:
            p.terminate()


def train(out_path: str, minutes: float, work: str, threads: int = 1, batch: int = 128, lr: float = 3e-3,
          seed: int = 0, resume: str = "", device: str = "auto", checkpoint_every_min: float = 5.0,
          workers: int = 1, use_pano: bool = True, crop_px: int = 0, log=print) -> dict:
    """Train (or go on from ``resume``) for ``minutes`` in all; ``crop_px`` (0: the
    checkpoint's, else :data:`CROP_PX`) sets the crop side (:func:`set_crop_px`)."""
    import torch
    import torch.nn.functional as F

    torch.set_num_threads(threads)
    os.makedirs(work, exist_ok=True)
    names = read_table_codes() + [OTHER]
    dev = pick_device(device)
    net = build_net(len(names)).to(dev)
    opt = torch.optim.AdamW(net.parameters(), lr=lr, weight_decay=5e-4)
    step, elapsed = 0, 0.0
    state = None
    if resume:
        state = torch.load(resume, map_location=dev, weights_only=False)
        if state["names"] != names:
            raise SystemExit(f"{resume} was trained for other codes; start afresh")
        if crop_px and crop_px != state.get("crop_px", 32):
            raise SystemExit(f"{resume} was trained on {state.get('crop_px', 32)} px crops, not {crop_px}")
        crop_px = state.get("crop_px", 32)
        net.load_state_dict(state["net"])
        opt.load_state_dict(state["opt"])
        step, elapsed = state["step"], state["elapsed_s"]
        seed = seed + step
    set_crop_px(crop_px or CROP_PX)
    pano_cache = os.path.join(work, "pano-train.npz") if use_pano else ""  # native density: any CROP_PX
    sampler = Sampler(names, seed, pano_cache)
    torch.manual_seed(seed)
    if state is not None and "rng" in state:
        sampler.rng.bit_generator.state = state["rng"]
    val_x, val_y, _ = heldout_gtsrb(names, "val")
    log(f"codes: {len(names)} names, {len(sampler.gtsrb)} GTSRB train crops, {len(sampler.drawn)} drawn, "
        f"{len(sampler.pano)} panorama crops; validation {len(val_y)} crops; {CROP_PX} px crops; device {dev}")
    feeder = BatchFeeder(names, seed, pano_cache, batch, workers) if workers else None
    stop = {"now": False}

    def on_signal(signum, frame):
        stop["now"] = True

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)
    total_s = minutes * 60.0

    def save(path):
        torch.save({"net": net.state_dict(), "opt": opt.state_dict(), "step": step, "elapsed_s": elapsed,
                    "names": names, "rng": sampler.rng.bit_generator.state, "crop_px": CROP_PX}, path + ".tmp")
        os.replace(path + ".tmp", path)

    t_last_ckpt = time.time()
    t0 = time.time() - elapsed
    running = []
    while elapsed < total_s and not stop["now"]:
        frac = elapsed / total_s
        for g in opt.param_groups:
            g["lr"] = lr * min(1.0, (step + 1) / 200) * 0.5 * (1 + math.cos(math.pi * frac))
        x, y = feeder.get() if feeder else sampler.batch(batch)
        logits = net(to_tensor(x, dev))
        loss = F.cross_entropy(logits, torch.from_numpy(y).to(dev), label_smoothing=0.05)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        running.append(float(loss))
        step += 1
        elapsed = time.time() - t0
        if step % 200 == 0:
            acc = accuracy(predict(net, val_x, dev), val_y)
            log(f"step {step} {elapsed / 60:.1f} min loss {np.mean(running):.3f} val GTSRB acc {acc:.4f}")
            running = []
        if time.time() - t_last_ckpt > checkpoint_every_min * 60:
            save(os.path.join(work, "last.pt"))
            t_last_ckpt = time.time()
    save(os.path.join(work, "last.pt"))
    if feeder:
        feeder.close()
    if stop["now"]:
        log("stopped; go on with --resume " + os.path.join(work, "last.pt"))
        return {}
    figures = evaluate_net(net, names, dev, work, log)
    export_onnx(net, names, out_path, dict(figures, steps=step, minutes=round(elapsed / 60, 1)))
    log(f"exported {out_path}")
    return figures


def held_out_scenes():
    """Generated scenes the classifier never trained on (bench seeds < 100), where present."""
    root = os.path.join(REPO_ROOT, "bench", "out")
    return [os.path.join(root, d) for d in ("scene-default-7", "scene-tiny-3")
            if os.path.isfile(os.path.join(root, d, "scene.json"))]


def evaluate_net(net, names, dev, work, log=print) -> dict:
    test_x, test_y, _ = heldout_gtsrb(names, "test")
    acc = accuracy(predict(net, test_x, dev), test_y)
    figures = {"gtsrb_test_tracks_accuracy": round(acc, 4), "gtsrb_test_crops": int(len(test_y))}
    try:
        px, py = heldout_pano(names, held_out_scenes(), os.path.join(work, "pano-heldout.npz"))
    except ImportError as e:  # the plugin's cut_crop is missing in this checkout
        log(f"no held-out panorama figures: {e}")
        px, py = np.zeros(0), np.zeros(0)
    if len(py):
        figures["heldout_panorama_accuracy"] = round(accuracy(predict(net, px, dev), py), 4)
        figures["heldout_panorama_crops"] = int(len(py))
    log("held out: " + json.dumps(figures))
    return figures


def evaluate_onnx(model_path: str, work: str = WORK_DIR) -> dict:
    """Held-out figures of an exported classifier, run through onnxruntime like the plugin."""
    import onnxruntime as ort

    session = ort.InferenceSession(model_path, providers=["CPUExecutionProvider"])
    names = json.loads(session.get_modelmeta().custom_metadata_map["names"])
    name = session.get_inputs()[0].name
    set_crop_px(int(session.get_inputs()[0].shape[2]))  # crops as the plugin cuts them for this model

    def run(crops_bgr):
        rgb = crops_bgr[..., ::-1].astype(np.float32).transpose(0, 3, 1, 2) / 255.0
        return np.concatenate([session.run(None, {name: rgb[k:k + 256]})[0] for k in range(0, len(rgb), 256)])

    test_x, test_y, _ = heldout_gtsrb(names, "test")
    figures = {"gtsrb_test_tracks_accuracy": round(accuracy(run(test_x), test_y), 4),
               "gtsrb_test_crops": int(len(test_y))}
    px, py = heldout_pano(names, held_out_scenes(), os.path.join(work, "pano-heldout.npz"))
    if len(py):
        figures["heldout_panorama_accuracy"] = round(accuracy(run(px), py), 4)
        figures["heldout_panorama_crops"] = int(len(py))
    return figures


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m devtools.train.codes", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--minutes", type=float, default=30.0, help="training time in all (resumed runs count it)")
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, "models", "signcodes.onnx"))
    ap.add_argument("--work", default=WORK_DIR)
    ap.add_argument("--threads", type=int, default=1, help="torch threads")
    ap.add_argument("--workers", type=int, default=1, help="processes drawing training batches (0: in the main one)")
    ap.add_argument("--checkpoint-every", type=float, default=5.0, help="minutes between WORK/last.pt saves")
    ap.add_argument("--no-pano", action="store_true", help="no crops from generated panoramas")
    ap.add_argument("--evaluate", metavar="ONNX", help="only print the held-out figures of an exported model")
    ap.add_argument("--batch", type=int, default=128)
    ap.add_argument("--lr", type=float, default=3e-3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--device", default="auto")
    ap.add_argument("--resume", default="")
    ap.add_argument("--crop-px", type=int, default=0,
                    help=f"crop side in pixels (default {CROP_PX}, or the resumed checkpoint's)")
    a = ap.parse_args(argv)
    if a.evaluate:
        print(json.dumps(evaluate_onnx(a.evaluate, a.work), indent=1))
        return 0
    train(a.out, a.minutes, a.work, a.threads, a.batch, a.lr, a.seed, a.resume, a.device,
          a.checkpoint_every, a.workers, not a.no_pano, a.crop_px)
    return 0


if __name__ == "__main__":
    sys.exit(main())
