"""Training loop of the bundled sign detector: the data mix, CenterNet targets and losses,
validation on held-out GTSDB frames and panorama views, checkpoints, ONNX export."""
from __future__ import annotations

import copy
import json
import math
import os
import time

import cv2
import numpy as np
import torch
import torch.nn.functional as F

from . import data
from .data import CLASSES, Sample
from .metrics import average_precision, best_f1_threshold, match_image
from .model import STRIDE, SignNet, calibration_power, decode, export_onnx

#: Generated scenes used for training: (preset, seed, panorama width or None). Seeds from
#: 100 up are reserved for training; the bench and tests use seeds below 100.
TRAIN_SCENES = (("default", 100, None), ("tiny", 100, None), ("default", 101, None),
                ("default", 102, None))
#: The last panoramas of each training scene (at most this many, and a sixth) are kept for validation.
VAL_PANORAMAS_PER_SCENE = 8

SOURCE_WEIGHTS = {"gtsdb": 0.28, "gtsrb_paste": 0.14, "drawn_paste": 0.16, "views": 0.42}


def scene_dir_name(preset, seed, width):
    return f"{preset}-{seed}" + (f"-{width}" if width else "")


def ensure_scenes(scene_root: str, specs=TRAIN_SCENES, generate: bool = True):
    """Folders of the training scenes, generated (no LiDAR) when missing and ``generate``."""
    from devtools.scenegen import generate_scene

    folders = []
    for preset, seed, width in specs:
        folder = os.path.join(scene_root, scene_dir_name(preset, seed, width))
        if not os.path.isfile(os.path.join(folder, "scene.json")) and generate:
            print(f"[train] generating scene {preset} seed {seed} in {folder}", flush=True)
            generate_scene(preset, seed, folder, lidar=False, masks=False, pano_width=width)
        folders.append(folder)
    return folders


# --- the data mix ------------------------------------------------------------------------

def log_uniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


class DataMix:
    """Random training crops from every source (see :mod:`devtools.train.data`)."""

    def __init__(self, crop_px: int, work_dir: str, seed: int = 0):
        self.crop_px = crop_px
        self.rng = np.random.default_rng(seed)
        self.cache = data.ImageCache()
        self.gtsdb = data.read_gtsdb(data.GTSDB_TRAIN_IDS)
        self.gtsrb, self.gtsrb_classes = data.read_gtsrb()
        self.drawn, self.drawn_classes = data.drawn_signs()
        self.distractors = data.distractor_patches(self.rng)
        self.work_dir = work_dir
        self.views, self.val_views, self.scenes = [], [], set()
        print(f"[train] {len(self.gtsdb)} GTSDB scenes, {len(self.gtsrb)} GTSRB crops, "
              f"{len(self.drawn)} drawn signs, {len(self.distractors)} distractors", flush=True)

    def add_scenes(self, folders):
        """Cut the views of scenes not loaded yet (those whose scene.json exists)."""
        for folder in folders:
            if folder in self.scenes or not os.path.isfile(os.path.join(folder, "scene.json")):
                continue
            with open(os.path.join(folder, "scene.json")) as f:
                n = len(json.load(f)["images"])
            cache = os.path.join(self.work_dir, "views", os.path.basename(os.path.normpath(folder)))
            t0 = time.perf_counter()
            last = n - min(VAL_PANORAMAS_PER_SCENE, n // 6)
            train = data.scene_view_samples(folder, cache + "-train", rng=self.rng, image_filter=lambda k: k < last)
            val = data.scene_view_samples(folder, cache + "-val", keep_empty=0.3, rng=self.rng,
                                          image_filter=lambda k: k >= last)
            self.views += train
            self.val_views += val
            self.scenes.add(folder)
            print(f"[train] scene {folder}: {len(train)} training views, {len(val)} validation views "
                  f"({time.perf_counter() - t0:.0f} s)", flush=True)

    def _load(self, row) -> Sample:
        path, boxes, classes = row[0], row[1], row[2]
        ignore = row[3] if len(row) > 3 else np.zeros((0, 4), np.float32)
        real = path.startswith(data.DATA_DIR)  # GTSDB scenes stay decoded in memory
        return Sample(self.cache.get(path).copy() if real else cv2.imread(path),
                      boxes.copy(), classes.copy(), ignore.copy())

    def _crop(self, sample: Sample, scale: float, on_sign: float) -> Sample:
        rng, S = self.rng, self.crop_px
        h, w = sample.image.shape[:2]
        if len(sample.boxes) and rng.random() < on_sign:
            b = sample.boxes[int(rng.integers(len(sample.boxes)))]
            jitter = rng.uniform(-0.4, 0.4, 2) * S / scale
            centre = (0.5 * (b[0] + b[2]) + jitter[0], 0.5 * (b[1] + b[3]) + jitter[1])
        else:
            centre = (rng.uniform(0, w), rng.uniform(0, h))
        return data.crop_sample(sample, S, scale, centre, flip=bool(rng.random() < 0.5))

    def _paste_many(self, s: Sample, patches, classes, n, lo, hi):
        for _ in range(n):
            k = int(self.rng.integers(len(patches)))
            klass = None if classes is None else int(classes[k])
            data.paste(s, patches[k], log_uniform(self.rng, lo, hi), klass, self.rng)

    def _background(self) -> Sample:
        """A crop of a real scene or a view to paste onto (its own signs stay labelled)."""
        if self.views and self.rng.random() < 0.4:
            return self._crop(self._load(self.views[int(self.rng.integers(len(self.views)))]),
                              log_uniform(self.rng, 0.7, 1.4), 0.0)
        return self._crop(self._load(self.gtsdb[int(self.rng.integers(len(self.gtsdb)))]),
                          log_uniform(self.rng, 0.6, 1.5), 0.0)

    def sample(self) -> Sample:
        rng = self.rng
        source = rng.choice(list(SOURCE_WEIGHTS), p=list(SOURCE_WEIGHTS.values()))
        if source == "views" and not self.views:
            source = "gtsdb"
        if source == "gtsdb":
            s = self._crop(self._load(self.gtsdb[int(rng.integers(len(self.gtsdb)))]),
                           log_uniform(rng, 0.5, 1.8), 0.8)
            if rng.random() < 0.3:
                self._paste_many(s, self.distractors, None, 1, 14, 120)
        elif source == "gtsrb_paste":
            s = self._background()
            self._paste_many(s, self.gtsrb, self.gtsrb_classes, int(rng.integers(1, 5)), 10, 110)
        elif source == "drawn_paste":
            s = self._background()
            self._paste_many(s, self.drawn, self.drawn_classes, int(rng.integers(1, 4)), 10, 120)
            self._paste_many(s, self.distractors, None, int(rng.integers(0, 3)), 14, 160)
        else:
            s = self._load(self.views[int(rng.integers(len(self.views)))])
            if rng.random() < 0.3:
                s.image = data.resample_blur(s.image, rng)
            s = self._crop(s, log_uniform(rng, 0.65, 1.6), 0.75)
        s.image = data.colour_jitter(s.image, rng)
        return s


# --- targets and losses --------------------------------------------------------------------

MAX_OBJECTS = 64


def make_targets(sample: Sample, out_px: int, num_classes: int):
    """Heatmap [nc, G, G], valid-negative mask [G, G], indices, regression targets, mask."""
    g = out_px // STRIDE
    heat = np.zeros((num_classes, g, g), np.float32)
    valid = np.ones((g, g), np.float32)
    ind = np.zeros(MAX_OBJECTS, np.int64)
    reg = np.zeros((MAX_OBJECTS, 4), np.float32)
    mask = np.zeros(MAX_OBJECTS, np.float32)
    for b in sample.ignore / STRIDE:
        x0, y0 = int(max(math.floor(b[0]), 0)), int(max(math.floor(b[1]), 0))
        x1, y1 = int(min(math.ceil(b[2]), g)), int(min(math.ceil(b[3]), g))
        valid[y0:y1, x0:x1] = 0.0
    ys, xs = np.mgrid[0:g, 0:g].astype(np.float32)
    for k, (b, c) in enumerate(zip(sample.boxes[:MAX_OBJECTS] / STRIDE, sample.classes[:MAX_OBJECTS])):
        w, h = max(b[2] - b[0], 0.25), max(b[3] - b[1], 0.25)
        cx, cy = 0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3])
        ix, iy = min(int(cx), g - 1), min(int(cy), g - 1)
        sx, sy = max(0.6, 0.15 * w), max(0.6, 0.15 * h)
        gauss = np.exp(-((xs - ix) ** 2 / (2 * sx * sx) + (ys - iy) ** 2 / (2 * sy * sy)))
        np.maximum(heat[c], gauss, out=heat[c])
        heat[c, iy, ix] = 1.0
        ind[k] = iy * g + ix
        reg[k] = (cx - ix, cy - iy, math.log(w), math.log(h))
        mask[k] = 1.0
    return heat, valid, ind, reg, mask


def batch_tensors(samples, out_px, num_classes):
    images = np.stack([cv2.cvtColor(s.image, cv2.COLOR_BGR2RGB) for s in samples])
    x = torch.from_numpy(images).permute(0, 3, 1, 2).float().div_(255.0)
    targets = [make_targets(s, out_px, num_classes) for s in samples]
    return x, [torch.from_numpy(np.stack(t)) for t in zip(*targets)]


def focal_loss(logits, heat, valid):
    """CenterNet's penalty-reduced focal loss; negatives on ignore regions do not count."""
    pred = torch.sigmoid(logits).clamp(1e-4, 1 - 1e-4)
    pos = heat.eq(1.0).float()
    neg = (1.0 - pos) * torch.pow(1.0 - heat, 4) * valid.unsqueeze(1)
    pos_loss = torch.log(pred) * torch.pow(1 - pred, 2) * pos
    neg_loss = torch.log(1 - pred) * torch.pow(pred, 2) * neg
    return -(pos_loss.sum() + neg_loss.sum()) / pos.sum().clamp(min=1.0)


def regression_loss(regression, ind, reg, mask):
    b, c, h, w = regression.shape
    pred = regression.reshape(b, c, h * w).gather(2, ind.unsqueeze(1).expand(b, c, ind.shape[1])).permute(0, 2, 1)
    err = F.l1_loss(pred, reg, reduction="none") * mask.unsqueeze(2)
    return err[..., :2].sum() / mask.sum().clamp(min=1.0), err[..., 2:].sum() / mask.sum().clamp(min=1.0)


# --- validation ------------------------------------------------------------------------------

def _pad_to(image, multiple=32):
    h, w = image.shape[:2]
    H, W = -(-h // multiple) * multiple, -(-w // multiple) * multiple
    return cv2.copyMakeBorder(image, 0, H - h, 0, W - w, cv2.BORDER_CONSTANT, value=(114, 114, 114))


@torch.no_grad()
def predict(net, image_bgr, threshold=0.05):
    """Decoded detections (boxes, scores, classes) of one whole image, padded to a multiple of 32."""
    x = torch.from_numpy(cv2.cvtColor(_pad_to(image_bgr), cv2.COLOR_BGR2RGB)).permute(2, 0, 1)[None].float() / 255.0
    out = decode(*net(x))[0].numpy()
    out = out[out[:, 4] >= threshold]
    return out[:, :4], out[:, 4], out[:, 5].astype(np.int64)


def validate(net, sets):
    """AP50 and best-F1 precision/recall on each validation set: {name: [(path, boxes, classes, ignore)]}."""
    net.eval()
    results = {}
    for name, rows in sets.items():
        matches = []
        for row in rows:
            boxes, scores, classes = predict(net, cv2.imread(row[0]))
            matches.append(match_image(boxes, scores, classes, row[1], row[2], 0.5,
                                       ignore_boxes=row[3] if len(row) > 3 else None))
        t, p, r = best_f1_threshold(matches)
        results[name] = {"ap50": average_precision(matches), "best_f1_threshold": t, "precision": p, "recall": r,
                         "images": len(rows), "signs": int(sum(len(row[2]) for row in rows))}
    net.train()
    return results


# --- the loop --------------------------------------------------------------------------------

def train(out_path: str, minutes: float, work_dir: str, scene_root: str, generate_scenes: bool = True,
          crop_px: int = 320, batch_size: int = 16, lr: float = 3e-3, threads: int = 2,
          validate_every_min: float = 5.0, seed: int = 0, resume: str = None, val_images: int = 60):
    torch.set_num_threads(threads)
    torch.manual_seed(seed)
    os.makedirs(work_dir, exist_ok=True)
    t_start = time.perf_counter()
    scene_folders = ensure_scenes(scene_root, generate=generate_scenes)
    mix = DataMix(crop_px, work_dir, seed)
    mix.add_scenes(scene_folders)
    # a fixed subset of each validation set keeps a validation round under a minute
    val_sets = {"gtsdb_500_599": data.read_gtsdb(data.GTSDB_HELDOUT_IDS)[:val_images],
                "views": mix.val_views[::max(1, len(mix.val_views) // val_images)]}

    net = SignNet(len(CLASSES))  # channels_last makes the depthwise convolutions slower here
    if resume:
        net.load_state_dict(torch.load(resume)["model"])
    ema = copy.deepcopy(net).eval()
    for p in ema.parameters():
        p.requires_grad_(False)
    opt = torch.optim.AdamW(net.parameters(), lr=lr, weight_decay=5e-4)
    budget_s = minutes * 60.0
    t_train = time.perf_counter()
    step, next_val, best_score, history = 0, validate_every_min * 60.0, -1.0, []
    log = os.path.join(work_dir, "history.json")
    losses = []
    print(f"[train] {sum(p.numel() for p in net.parameters())} parameters; training for {minutes} min "
          f"(setup took {t_train - t_start:.0f} s)", flush=True)
    while True:
        elapsed = time.perf_counter() - t_train
        done = elapsed >= budget_s
        if elapsed >= next_val or done:
            mix.add_scenes(scene_folders)  # scenes generated meanwhile join in
            val_sets["views"] = mix.val_views[::max(1, len(mix.val_views) // val_images)]
            scores = validate(ema, val_sets)
            score = np.mean([v["ap50"] for v in scores.values() if v["images"]])
            entry = {"step": step, "minutes": round(elapsed / 60, 2), "loss": float(np.mean(losses[-200:] or [0])),
                     "score": float(score), **scores, "views_train": len(mix.views)}
            history.append(entry)
            print(f"[train] {json.dumps(entry)}", flush=True)
            state = {"model": ema.state_dict(), "step": step, "entry": entry}
            torch.save(state, os.path.join(work_dir, "last.pt"))
            if score > best_score:
                best_score = score
                torch.save(state, os.path.join(work_dir, "best.pt"))
            with open(log, "w") as f:
                json.dump(history, f, indent=1)
            next_val += validate_every_min * 60.0
            if done:
                break
        # linear warm-up, then cosine over the time budget
        frac = min(elapsed / budget_s, 1.0)
        for group in opt.param_groups:
            group["lr"] = lr * min(1.0, (step + 1) / 300) * (0.02 + 0.98 * 0.5 * (1 + math.cos(math.pi * frac)))
        samples = [mix.sample() for _ in range(batch_size)]
        x, (heat, valid, ind, reg, mask) = batch_tensors(samples, crop_px, len(CLASSES))
        logits, regression = net(x)
        l_heat = focal_loss(logits, heat, valid)
        l_off, l_size = regression_loss(regression, ind, reg, mask)
        loss = l_heat + l_off + l_size
        opt.zero_grad(set_to_none=True)
        loss.backward()
        torch.nn.utils.clip_grad_norm_(net.parameters(), 10.0)
        opt.step()
        with torch.no_grad():
            decay = min(0.998, (1 + step) / (10 + step))
            for e, p in zip(ema.state_dict().values(), net.state_dict().values()):
                if e.dtype.is_floating_point:
                    e.mul_(decay).add_(p.detach(), alpha=1 - decay)
                else:
                    e.copy_(p)
        losses.append(float(loss))
        step += 1
        if step % 50 == 0:
            print(f"[train] step {step} {elapsed / 60:.1f} min loss {np.mean(losses[-50:]):.3f} "
                  f"(heat {float(l_heat):.3f} off {float(l_off):.3f} size {float(l_size):.3f})", flush=True)

    return export_checkpoint(os.path.join(work_dir, "best.pt"), out_path, net)


def export_checkpoint(checkpoint: str, out_path: str, net: SignNet = None):
    """Export a checkpoint with its scores calibrated on the GTSDB validation: the best-F1
    threshold found there becomes the plugin's default confidence (0.4)."""
    best = torch.load(checkpoint)
    net = net or SignNet(len(CLASSES))
    net.load_state_dict(best["model"])
    threshold = best["entry"]["gtsdb_500_599"]["best_f1_threshold"]
    power = calibration_power(threshold)
    export_onnx(net, out_path, CLASSES, score_power=power, extra_metadata={
        "description": "Road sign detector (6 classes), CenterNet-style, trained by devtools/train",
        "score_calibration": f"raw ** {power:.4f}: the validation best-F1 threshold {threshold:.2f} maps to 0.40",
        "training": json.dumps({"step": best["step"], "validation": best["entry"]})})
    print(f"[train] exported {out_path} ({os.path.getsize(out_path) / 1e6:.2f} MB) from step {best['step']} "
          f"(scores ** {power:.3f}): {json.dumps(best['entry'])}", flush=True)
    return out_path
