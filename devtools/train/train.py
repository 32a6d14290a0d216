"""Training loop of the bundled sign detector: the data mix, CenterNet targets and losses,
validation on held-out GTSDB frames and panorama views, checkpoints, ONNX export."""
from __future__ import annotations

import copy
import json
import math
import os
import time
from typing import Dict, List, Set, Tuple

import cv2
import numpy as np
import torch
import torch.nn.functional as F

from . import data, mine
from .data import CLASS_INDEX, CLASSES, Sample, log_uniform
from .metrics import average_precision, best_f1_threshold, match_image, summarise
from .model import (
    ARCH_DEFAULT,
    PLUGIN_DEFAULT_CONFIDENCE,
    STRIDE,
    ConvBN,
    SignNet,
    calibration_power,
    decode,
    export_onnx,
    onnx_arch,
    widened,
)

#: Generated scenes used for training: (preset, seed, panorama width or None). Seeds from
#: 100 up are reserved for training; the bench and tests use seeds below 100.
TRAIN_SCENES = (("default", 100, None), ("tiny", 100, None), ("default", 101, None),
                ("default", 102, None))
#: The last panoramas of each training scene (at most this many, and a sixth) are kept for validation.
VAL_PANORAMAS_PER_SCENE = 8

SOURCE_WEIGHTS = {"gtsdb": 0.24, "gtsrb_paste": 0.30, "drawn_paste": 0.10, "views": 0.36, "faces_paste": 0.12,
                  "gtsdb_hard": 0.08}
#: "gtsdb_hard" crops GTSDB training frames round the false alarms of an earlier detector
#: (devtools/train/mine.py; the reviewed list also labels the signs GTSDB leaves out).
#: Sign faces of many countries drawn at the start (devtools/train/signfaces.py), pasted by
#: "faces_paste"; drawn from seed 0 (the bench draws its own from a seed over 1000).
FACES = 2000
# pasted real signs: share drawn at the 14-35 px of far signs (those the detector scores too
# low on real photographs), beside the sizes of _gtsrb_height; 0 = as the bundled file
SMALL_PASTE_PX = (14.0, 35.0)
#: Share of training crops that get 1-3 pasted look-alikes (unlabelled).
NEGATIVE_SHARE = 0.45
#: Mandatory signs (GTSDB's weakest class) are drawn this many times more often.
MANDATORY_BOOST = 2.5
#: The scales a crop of a generated view is taken at (log-uniform): a 320 px crop at these
#: scales shows a sign of more than ~150 view pixels whole only now and then, and none over
#: 490 (``--large-share``: :func:`.data.whole_sign_crop`). ``--view-scales`` sets others.
VIEW_CROP_SCALES = (0.65, 1.6)


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

class DataMix:
    """Random training crops from every source (see :mod:`devtools.train.data`)."""

    def __init__(self, crop_px: int, work_dir: str, seed: int = 0, mandatory_boost: float = MANDATORY_BOOST,
                 source_weights=None, small_share: float = 0.0, faces: int = FACES,
                 mined_path: str = mine.MINED_PATH, large_share: float = 0.0, view_scales=None,
                 tall_share: float = 0.0, cut_jobs: int = 1):
        self.crop_px = crop_px
        self.cut_jobs = cut_jobs        # processes a scene's panoramas are cut in (data.scene_view_samples)
        self.view_scales = tuple(view_scales or VIEW_CROP_SCALES)
        self.small_share = small_share
        self.large_share = large_share
        self.tall_share = tall_share
        w = dict(SOURCE_WEIGHTS, **(source_weights or {}))
        self.source_names = list(w)
        self.source_p = np.array([w[k] for k in self.source_names], float) / sum(w.values())
        self.rng = np.random.default_rng(seed)
        self.cache = data.ImageCache()
        self.gtsdb = data.read_gtsdb(data.GTSDB_TRAIN_IDS)
        self.hard = self._add_mined(mined_path)
        self._drop_missing_frames()
        # scenes with a mandatory sign come up more often (the weakest class on GTSDB)
        w = np.array([1.0 + (mandatory_boost - 1.0) * bool(np.any(r[2] == CLASS_INDEX["mandatory"]))
                      for r in self.gtsdb])
        self.gtsdb_p = w / w.sum()
        # gtsrb-train: the training tracks only (held-out tracks are never pasted)
        self.gtsrb, self.gtsrb_classes, tracks, self.gtsrb_heights = data.read_gtsrb_train("train")
        self.gtsrb_p = data.class_sampling_weights(self.gtsrb_classes, {CLASS_INDEX["mandatory"]: mandatory_boost})
        self.drawn, self.drawn_classes = data.drawn_signs()
        self.faces, self.faces_classes = data.drawn_faces(faces, seed=0)
        self.distractors = data.distractor_patches(self.rng)
        self.work_dir = work_dir
        self.views, self.val_views, self.scenes = [], [], set()
        self.tall_views: List[int] = []   # indices into self.views of those with a sign seen edge-on
        #: a generated view's path -> (its scene's decoded views, its row there): data.view_store
        self.view_pixels: Dict[str, Tuple[np.ndarray, int]] = {}
        self._scene_views: Dict[str, Tuple[str, list]] = {}   # folder -> (its views' folder, rows)
        self._views_mapped: Set[str] = set()
        print(f"[train] {len(self.gtsdb)} GTSDB scenes, {len(self.gtsrb)} GTSRB crops of {len(set(tracks))} "
              f"training tracks, {len(self.drawn)} drawn signs, {len(self.faces)} faces of many countries, "
              f"{len(self.distractors)} distractors, {len(self.hard)} mined false alarms", flush=True)

    def _add_mined(self, path: str):
        """Label the signs of the GTSDB training frames that the reviewed mined file adds
        (:func:`mine.label_frames`) and return its false alarms as ``[(index into self.gtsdb, box)]``."""
        false_alarms, signs, ignored = mine.read_mined(path)
        self.gtsdb = mine.label_frames(self.gtsdb, data.GTSDB_TRAIN_IDS, signs, ignored)
        index = {frame_id: k for k, frame_id in enumerate(data.GTSDB_TRAIN_IDS)}
        return [(index[frame_id], box) for frame_id, boxes in sorted(false_alarms.items()) for box in boxes]

    def _drop_missing_frames(self):
        """Leave out the GTSDB training frames whose image is not there (a device machine
        gets a subset: devtools/train/device_run.py), and their mined false alarms."""
        present = [os.path.isfile(row[0]) for row in self.gtsdb]
        if all(present):
            return
        if not any(present):
            raise SystemExit(f"no GTSDB training frame in {os.path.dirname(self.gtsdb[0][0])}")
        new_index = {old: new for new, old in enumerate(k for k, there in enumerate(present) if there)}
        self.gtsdb = [row for row, there in zip(self.gtsdb, present) if there]
        self.hard = [(new_index[k], box) for k, box in self.hard if k in new_index]
        print(f"[train] {present.count(False)} GTSDB training frames are missing: trained without them", flush=True)

    def add_scenes(self, folders, cut: bool = True):
        """Cut the views of scenes not loaded yet (those whose scene.json exists); ``cut``
        False: only load scenes whose views are cut already (a worker process: the main
        process cuts, so two processes never write one cache)."""
        for folder in folders:
            if folder in self.scenes:
                self._map_views(folder, build=cut)   # a store another process has made since
                continue
            if not os.path.isfile(os.path.join(folder, "scene.json")):
                continue
            with open(os.path.join(folder, "scene.json")) as f:
                n = len(json.load(f)["images"])
            cache = os.path.join(self.work_dir, "views", os.path.basename(os.path.normpath(folder)))
            if not cut and not all(os.path.isfile(os.path.join(cache + part, "labels.json"))
                                   for part in ("-train", "-val")):
                continue
            t0 = time.perf_counter()
            last = n - min(VAL_PANORAMAS_PER_SCENE, n // 6)
            train = data.scene_view_samples(folder, cache + "-train", rng=self.rng, image_filter=lambda k: k < last,
                                            jobs=self.cut_jobs)
            val = data.scene_view_samples(folder, cache + "-val", keep_empty=0.3, rng=self.rng,
                                          image_filter=lambda k: k >= last, jobs=self.cut_jobs, store=False)
            self.tall_views += [len(self.views) + k for k, row in enumerate(train) if len(data.tall_boxes(row[1]))]
            self._scene_views[folder] = (cache + "-train", train)
            self._map_views(folder, build=cut)
            self.views += train
            self.val_views += val
            self.scenes.add(folder)
            print(f"[train] scene {folder}: {len(train)} training views, {len(val)} validation views "
                  f"({time.perf_counter() - t0:.0f} s)", flush=True)

    def _map_views(self, folder: str, build: bool) -> None:
        """Read the training views of ``folder`` from their decoded store
        (:func:`.data.view_store`) once it is there; ``build``: make it if it is missing (the
        main process: a worker waits for it and reads the JPEGs meanwhile)."""
        if folder in self._views_mapped:
            return
        cache_dir, rows = self._scene_views[folder]
        store = data.view_store(cache_dir, [row[0] for row in rows], build=build)
        if store is not None:
            self.view_pixels.update({row[0]: (store, k) for k, row in enumerate(rows)})
        if store is not None or build:      # made, or views no store can hold: not tried again
            self._views_mapped.add(folder)

    def _load(self, row) -> Sample:
        path, boxes, classes = row[0], row[1], row[2]
        ignore = row[3] if len(row) > 3 else np.zeros((0, 4), np.float32)
        if path.startswith(data.DATA_DIR):      # GTSDB scenes stay decoded in memory
            image = self.cache.get(path).copy()
        elif path in self.view_pixels:          # a generated view, decoded once for the run
            store, k = self.view_pixels[path]
            image = np.array(store[k])
        else:
            image = cv2.imread(path)
        return Sample(image, boxes.copy(), classes.copy(), ignore.copy())

    def _crop(self, sample: Sample, scale: float, on_sign: float, around=None) -> Sample:
        """A crop at ``scale``: near the box ``around`` if given, else near one of the sample's
        signs with probability ``on_sign``, else anywhere."""
        rng, S = self.rng, self.crop_px
        h, w = sample.image.shape[:2]
        if around is None and len(sample.boxes) and rng.random() < on_sign:
            around = sample.boxes[int(rng.integers(len(sample.boxes)))]
        if around is not None:
            jitter = rng.uniform(-0.4, 0.4, 2) * S / scale
            centre = (0.5 * (around[0] + around[2]) + jitter[0], 0.5 * (around[1] + around[3]) + jitter[1])
        else:
            centre = (rng.uniform(0, w), rng.uniform(0, h))
        return data.crop_sample(sample, S, scale, centre, flip=bool(rng.random() < 0.5))

    def _view_crop(self, s: Sample) -> Sample:
        """A crop of a generated view at ``view_scales`` (:data:`VIEW_CROP_SCALES`), or, with probability
        ``large_share``, one that shows its largest sign whole if that sign is large
        (:func:`.data.whole_sign_crop`)."""
        rng, S = self.rng, self.crop_px
        whole = data.whole_sign_crop(s.boxes, S, rng) if self.large_share and rng.random() < self.large_share else None
        if whole is not None:
            scale, centre = whole
            return data.crop_sample(s, S, scale, centre, flip=bool(rng.random() < 0.5))
        return self._crop(s, log_uniform(rng, *self.view_scales), 0.75)

    def _paste_many(self, s: Sample, patches, classes, n, lo, hi, degraded: bool = False):
        """``n`` of ``patches`` at heights drawn in [lo, hi] px; ``degraded``: as distant signs."""
        post = (lambda p: data.degrade(p, self.rng)) if degraded else None
        for _ in range(n):
            k = int(self.rng.integers(len(patches)))
            klass = None if classes is None else int(classes[k])
            data.paste(s, patches[k], log_uniform(self.rng, lo, hi), klass, self.rng, post=post)

    def _gtsrb_height(self, k: int) -> float:
        """Pasted height of a real crop: near its own size (the camera's real blur), or the
        15-60 px of a distant sign, now and then larger."""
        if self.small_share and self.rng.random() < self.small_share:
            return log_uniform(self.rng, *SMALL_PASTE_PX)
        r = self.rng.random()
        if r < 0.4:
            h = self.gtsrb_heights[k] * self.rng.uniform(0.6, 1.2)
        elif r < 0.9:
            h = log_uniform(self.rng, 15, 60)
        else:
            h = log_uniform(self.rng, 60, 130)
        return float(np.clip(h, 13, 130))

    def _paste_real(self, s: Sample, n: int):
        for _ in range(n):
            k = int(self.rng.choice(len(self.gtsrb), p=self.gtsrb_p))
            data.paste(s, self.gtsrb[k], self._gtsrb_height(k), int(self.gtsrb_classes[k]), self.rng,
                       post=lambda p: data.degrade(p, self.rng))

    def _paste_negatives(self, s: Sample, n: int):
        for _ in range(n):
            if self.rng.random() < 0.75:
                patch, _ = data.hard_negative(self.rng, background=s.image)
            else:
                patch = self.distractors[int(self.rng.integers(len(self.distractors)))]
            data.paste(s, patch, log_uniform(self.rng, 14, 140), None, self.rng,
                       post=lambda p: data.degrade(p, self.rng))

    def _background(self) -> Sample:
        """A crop of a real scene or a view to paste onto (its own signs stay labelled)."""
        if self.views and self.rng.random() < 0.4:
            return self._crop(self._load(self.views[int(self.rng.integers(len(self.views)))]),
                              log_uniform(self.rng, 0.7, 1.4), 0.0)
        k = int(self.rng.choice(len(self.gtsdb), p=self.gtsdb_p))
        return self._crop(self._load(self.gtsdb[k]), log_uniform(self.rng, 0.6, 1.5), 0.0)

    def sample(self) -> Sample:
        rng = self.rng
        source = self.source_names[int(rng.choice(len(self.source_names), p=self.source_p))]
        if ((source == "views" and not self.views) or (source == "faces_paste" and not self.faces)
                or (source == "gtsdb_hard" and not self.hard)):
            source = "gtsdb"
        if source == "gtsdb_hard":   # round a false alarm of an earlier detector
            k, box = self.hard[int(rng.integers(len(self.hard)))]
            s = self._crop(self._load(self.gtsdb[k]), log_uniform(rng, 0.6, 1.5), 0.0, around=box)
        elif source == "gtsdb":
            k = int(rng.choice(len(self.gtsdb), p=self.gtsdb_p))
            s = self._crop(self._load(self.gtsdb[k]), log_uniform(rng, 0.5, 1.8), 0.8)
        elif source == "gtsrb_paste":
            s = self._background()
            self._paste_real(s, int(rng.integers(1, 6)))
        elif source == "drawn_paste":
            s = self._background()
            self._paste_many(s, self.drawn, self.drawn_classes, int(rng.integers(1, 4)), 10, 120)
        elif source == "faces_paste":   # degraded as distant signs, like the real crops
            s = self._background()
            self._paste_many(s, self.faces, self.faces_classes, int(rng.integers(1, 4)), 12, 120, degraded=True)
        else:   # a generated view; with probability tall_share round a sign seen edge-on
            edge_on = bool(self.tall_share and self.tall_views and rng.random() < self.tall_share)
            pool = self.tall_views if edge_on else range(len(self.views))
            k = pool[int(rng.integers(len(pool)))]
            s = self._load(self.views[k])
            if rng.random() < 0.3:
                s.image = data.resample_blur(s.image, rng)
            if edge_on:
                scale, centre = data.tall_sign_crop(s.boxes, self.crop_px, rng)
                s = data.crop_sample(s, self.crop_px, scale, centre, flip=bool(rng.random() < 0.5))
            else:
                s = self._view_crop(s)
        if rng.random() < NEGATIVE_SHARE:
            self._paste_negatives(s, int(rng.integers(1, 4)))
        s.image = data.colour_jitter(s.image, rng)
        if rng.random() < 0.3:
            s.image = data.jpeg(s.image, rng)
        return s


def pasted_validation(n_images: int = 30, seed: int = 1234):
    """A fixed validation set of held-out real signs: the held-out gtsrb-train tracks pasted
    (15-60 px, degraded) onto GTSDB 500-599 frames. Rows (image BGR, boxes, classes)."""
    rng = np.random.default_rng(seed)
    patches, classes, _, _ = data.read_gtsrb_train("val")
    rows = []
    for path, boxes, cls in data.read_gtsdb(data.GTSDB_HELDOUT_IDS)[:n_images]:
        s = Sample(cv2.imread(path), boxes.copy(), cls.copy())
        for _ in range(int(rng.integers(3, 7))):
            k = int(rng.integers(len(patches)))
            data.paste(s, patches[k], log_uniform(rng, 15, 60), int(classes[k]), rng,
                       post=lambda p: data.degrade(p, rng))
        rows.append((s.image, s.boxes, s.classes))
    return rows


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


def batch_tensors(samples, out_px, num_classes, as_uint8: bool = False):
    """Images [B, 3, S, S] RGB in 0..1 (``as_uint8``: 0..255 bytes, a quarter of the bytes
    to pass between processes; :func:`to_unit` on the device) and the targets."""
    images = np.stack([cv2.cvtColor(s.image, cv2.COLOR_BGR2RGB) for s in samples])
    x = torch.from_numpy(images).permute(0, 3, 1, 2)
    targets = [make_targets(s, out_px, num_classes) for s in samples]
    return (x if as_uint8 else to_unit(x)), [torch.from_numpy(np.stack(t)) for t in zip(*targets)]


def to_unit(x: torch.Tensor) -> torch.Tensor:
    """Image bytes 0..255 to floats 0..1 (a float tensor passes unchanged)."""
    return x.float().div_(255.0) if x.dtype == torch.uint8 else x


class BatchStream(torch.utils.data.IterableDataset):
    """Training batches drawn in ``DataLoader`` worker processes (forked: each starts from
    the main process's :class:`DataMix`). Each worker draws from its own random stream,
    seeded from (``seed``, ``first_step``, worker number), and loads the scenes the main
    process has cut meanwhile every ``rescan_every_s`` seconds. A resumed run's batches are
    therefore not the batches the run would have drawn uncut (the single-process path's
    are)."""

    def __init__(self, mix: "DataMix", scene_folders, batch_size: int, seed: int, first_step: int,
                 rescan_every_s: float = 20.0):
        super().__init__()
        self.mix, self.scene_folders, self.batch_size = mix, list(scene_folders), batch_size
        self.seed, self.first_step, self.rescan_every_s = seed, first_step, rescan_every_s

    def __iter__(self):
        info = torch.utils.data.get_worker_info()
        worker = info.id if info is not None else 0
        mix = self.mix
        mix.rng = np.random.default_rng([self.seed, self.first_step, worker])
        n_classes = len(CLASSES)
        next_scan = 0.0
        while True:
            if time.monotonic() >= next_scan:
                mix.add_scenes(self.scene_folders, cut=False)
                next_scan = time.monotonic() + self.rescan_every_s
            yield batch_tensors([mix.sample() for _ in range(self.batch_size)], mix.crop_px, n_classes,
                                as_uint8=True)


def batch_loader(mix: "DataMix", scene_folders, batch_size: int, seed: int, first_step: int, workers: int,
                 pin: bool):
    """An endless iterator of training batches drawn by ``workers`` processes."""
    loader = torch.utils.data.DataLoader(
        BatchStream(mix, scene_folders, batch_size, seed, first_step), batch_size=None, num_workers=workers,
        pin_memory=pin, prefetch_factor=4, persistent_workers=True, multiprocessing_context="fork")
    return iter(loader)  # the workers start (fork) here


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


#: Weight of the distillation loss beside the targets' losses (``train(teacher=...)``).
DISTILL_WEIGHT = 1.0
#: Where the teacher's heatmap reaches this score (any class), the student also learns the
#: teacher's box offsets and log sizes.
DISTILL_MIN_TEACHER_SCORE = 0.1


def distillation_loss(student_logits, student_regression, teacher_logits, teacher_regression, valid,
                      min_teacher_score: float = DISTILL_MIN_TEACHER_SCORE):
    """Knowledge distillation from a teacher with the same outputs (a wider :class:`SignNet`):
    the Bernoulli KL divergence of the student's per-class centre heatmap from the teacher's,
    summed over the cells that are not ignored (``valid``, as the focal loss takes it) and
    divided by the teacher's sure cells (score >= 0.5, at least 1), plus the L1 distance to the
    teacher's box offsets and log sizes, averaged over the cells where the teacher's heatmap
    reaches ``min_teacher_score``. Zero where the student computes what the teacher does;
    the teacher's outputs take no gradient."""
    teacher = torch.sigmoid(teacher_logits.detach()).clamp(1e-4, 1 - 1e-4)
    kl = (teacher * (torch.log(teacher) - F.logsigmoid(student_logits))
          + (1.0 - teacher) * (torch.log(1.0 - teacher) - F.logsigmoid(-student_logits)))
    sure = (teacher >= 0.5).float().sum().clamp(min=1.0)
    heat_loss = (kl * valid.unsqueeze(1)).sum() / sure
    cells = (teacher.amax(dim=1, keepdim=True) >= min_teacher_score).float()
    box_err = (student_regression - teacher_regression.detach()).abs() * cells
    box_loss = box_err.sum() / (cells.sum() * student_regression.shape[1]).clamp(min=1.0)
    return heat_loss + box_loss


def load_network(path: str, calibration_batches, arch=None) -> SignNet:
    """The network of an exported detector (``.onnx``, its batch norms recovered on the batches
    ``calibration_batches()`` returns: :func:`recover_from_onnx`; ``arch``: its widths where the
    file records none) or of a checkpoint (``.pt``, its EMA weights)."""
    if not path.endswith(".onnx"):
        start = torch.load(path, map_location="cpu", weights_only=False)
        net = SignNet(len(CLASSES), **checkpoint_arch(start))
        net.load_state_dict(start["model"])
        return net
    net = SignNet(len(CLASSES), **onnx_arch(path))
    try:
        return recover_from_onnx(net, path, calibration_batches())
    except ValueError as e:
        if not arch:
            raise ValueError(f"{e}: give the exported file's widths (--widths, --fpn, --head)") from e
        return recover_from_onnx(SignNet(len(CLASSES), **dict(ARCH_DEFAULT, **arch)), path, calibration_batches())


def load_teacher(path: str, calibration_batches, device) -> SignNet:
    """:func:`load_network`'s network of ``path``, in eval mode on ``device``, frozen."""
    teacher = load_network(path, calibration_batches).eval().to(device)
    for p in teacher.parameters():
        p.requires_grad_(False)
    return teacher


# --- validation ------------------------------------------------------------------------------

def _pad_to(image, multiple=32):
    h, w = image.shape[:2]
    H, W = -(-h // multiple) * multiple, -(-w // multiple) * multiple
    return cv2.copyMakeBorder(image, 0, H - h, 0, W - w, cv2.BORDER_CONSTANT, value=(114, 114, 114))


@torch.no_grad()
def predict(net, image_bgr, threshold=0.05):
    """Decoded detections (boxes, scores, classes) of one whole image, padded to a multiple of 32."""
    device = next(net.parameters()).device
    x = torch.from_numpy(cv2.cvtColor(_pad_to(image_bgr), cv2.COLOR_BGR2RGB)).permute(2, 0, 1)[None]
    heat, reg = net(x.to(device).float() / 255.0)
    out = decode(heat.float(), reg.float())[0].cpu().numpy()
    out = out[out[:, 4] >= threshold]
    return out[:, :4], out[:, 4], out[:, 5].astype(np.int64)


def validate(net, sets):
    """AP50 and best-F1 precision/recall on each validation set: {name: [(path or image,
    boxes, classes[, ignore])]}; per-class recall at the best-F1 threshold for GTSDB."""
    was_training = net.training
    net.eval()
    results = {}
    for name, rows in sets.items():
        matches = []
        for row in rows:
            image = cv2.imread(row[0]) if isinstance(row[0], str) else row[0]
            boxes, scores, classes = predict(net, image)
            matches.append(match_image(boxes, scores, classes, row[1], row[2], 0.5,
                                       ignore_boxes=row[3] if len(row) > 3 else None))
        t, p, r = best_f1_threshold(matches)
        results[name] = {"ap50": average_precision(matches), "best_f1_threshold": t, "precision": p, "recall": r,
                         "images": len(rows), "signs": int(sum(len(row[2]) for row in rows))}
        if name.startswith("gtsdb"):
            per = summarise(matches, CLASSES, t)
            results[name]["recall_per_class"] = {k: round(v["recall"], 3) for k, v in per.items()
                                                 if k != "all" and v["true"]}
    net.train(was_training)
    return results


# --- starting points: checkpoints and the bundled ONNX ----------------------------------------

def recover_from_onnx(net: SignNet, onnx_path: str, calibration_batches) -> SignNet:
    """Load the weights of an exported ONNX file (convolutions with batch norm folded in)
    into ``net``. Each batch norm gets the statistics of its convolution's output on
    ``calibration_batches`` and the scale and shift that undo them, so the network in eval
    mode computes exactly the exported function and training-mode batch statistics start
    close to the running ones."""
    import onnx
    from onnx import numpy_helper

    proto = onnx.load(onnx_path)
    init = {i.name: numpy_helper.to_array(i) for i in proto.graph.initializer}
    conv_inputs = [(n.input[1], n.input[2] if len(n.input) > 2 else None)
                   for n in proto.graph.node if n.op_type == "Conv"]
    # the torch convolutions in the order the forward pass runs them (= the graph's order)
    order, hooks = [], []
    for module in net.modules():
        if isinstance(module, torch.nn.Conv2d):
            hooks.append(module.register_forward_hook(lambda m, i, o: order.append(m)))
    net.eval()
    with torch.no_grad():
        net(torch.zeros(1, 3, 64, 64))
    for h in hooks:
        h.remove()
    if len(order) != len(conv_inputs):
        raise ValueError(f"{onnx_path}: {len(conv_inputs)} convolutions, the network has {len(order)}")
    bn_of = {}
    for module in net.modules():
        if isinstance(module, ConvBN):
            bn_of[module[0]] = module[1]
    for conv, (w_name, b_name) in zip(order, conv_inputs):
        w = torch.from_numpy(init[w_name].copy())
        if tuple(w.shape) != tuple(conv.weight.shape):
            raise ValueError(f"{w_name}: shape {tuple(w.shape)} != {tuple(conv.weight.shape)}")
        b = torch.from_numpy(init[b_name].copy()) if b_name else torch.zeros(w.shape[0])
        with torch.no_grad():
            conv.weight.copy_(w)
            if conv in bn_of:
                bn = bn_of[conv]
                bn.weight.fill_(1.0)
                bn.bias.copy_(b)
                bn.running_mean.zero_()
                bn.running_var.fill_(1.0 - bn.eps)
            else:
                conv.bias.copy_(b)
    # statistics of each convolution's output (exact function in eval mode)
    sums = {conv: [0.0, 0.0, 0] for conv in bn_of}
    hooks = [conv.register_forward_hook(
        lambda m, i, o: sums[m].__setitem__(slice(0, 3), [sums[m][0] + o.double().mean((0, 2, 3)),
                                                          sums[m][1] + (o.double() ** 2).mean((0, 2, 3)),
                                                          sums[m][2] + 1])) for conv in bn_of]
    with torch.no_grad():
        for x in calibration_batches:
            net(x)
    for h in hooks:
        h.remove()
    with torch.no_grad():
        for conv, bn in bn_of.items():
            s1, s2, n = sums[conv]
            if not n:
                continue
            mean = (s1 / n).float()
            var = (s2 / n - (s1 / n) ** 2).clamp(min=1e-6).float()
            bn.running_mean.copy_(mean)
            bn.running_var.copy_(var)
            bn.weight.copy_(torch.sqrt(var + bn.eps))
            bn.bias.add_(mean)
    return net


# --- checkpoints -------------------------------------------------------------------------------

def save_checkpoint(path, net, ema, opt, scaler, step, elapsed_s, history, best_score, mix, extra=None):
    """Everything a run needs to go on: raw and EMA weights, optimiser, AMP scaler, step,
    training time, validation history, and the random states (numpy, torch, cuda)."""
    state = {"model": ema.state_dict(), "net": net.state_dict(), "arch": net.arch, "opt": opt.state_dict(),
             "scaler": scaler.state_dict() if scaler is not None else None, "step": step,
             "elapsed_s": elapsed_s, "history": history, "best_score": best_score,
             "rng": {"numpy": mix.rng.bit_generator.state, "torch": torch.get_rng_state(),
                     "cuda": torch.cuda.get_rng_state_all() if torch.cuda.is_available() else None},
             "entry": history[-1] if history else None, **(extra or {})}
    tmp = path + ".tmp"
    torch.save(state, tmp)
    os.replace(tmp, path)


def checkpoint_arch(state) -> dict:
    """The widths a checkpoint's network has (``model.ARCH_DEFAULT`` for those saved before
    checkpoints recorded them)."""
    return dict(ARCH_DEFAULT, **(state.get("arch") or {}))


def pick_device(name: str) -> torch.device:
    if name == "auto":
        return torch.device("cuda" if torch.cuda.is_available() else "cpu")
    return torch.device(name)


def _until_seconds(until: str):
    """Seconds from now to ``HH:MM`` (UTC, today or tomorrow) or an ISO time."""
    import datetime as dt

    now = dt.datetime.now(dt.timezone.utc)
    if until is None:
        return None
    if len(until) <= 5:
        hh, mm = (int(v) for v in until.split(":"))
        t = now.replace(hour=hh, minute=mm, second=0, microsecond=0)
        if t < now:
            t += dt.timedelta(days=1)
    else:
        t = dt.datetime.fromisoformat(until)
        t = t if t.tzinfo else t.replace(tzinfo=dt.timezone.utc)
    return max(0.0, (t - now).total_seconds())


# --- the loop --------------------------------------------------------------------------------

def train(out_path: str, minutes: float, work_dir: str, scene_root: str, generate_scenes: bool = True,
          crop_px: int = 320, batch_size: int = 16, lr: float = 3e-3, threads: int = 2,
          validate_every_min: float = 5.0, seed: int = 0, resume: str = None, val_images: int = 60,
          init: str = None, device: str = "auto", checkpoint_every_min: float = 10.0, until: str = None,
          warmup_steps: int = 300, amp: bool = True, scenes=None, export: bool = True,
          ema_decay: float = 0.998, source_weights=None, small_share: float = 0.0, faces: int = FACES,
          arch=None, large_share: float = 0.0, view_scales=None, workers: int = 0, tall_share: float = 0.0,
          teacher: str = None, distill_weight: float = DISTILL_WEIGHT):
    """Train (or go on training) for ``minutes`` of training time in all (a resumed run
    counts the time already spent), or until the wall-clock time ``until``; validate every
    ``validate_every_min`` (best by AP50 on GTSDB 500-599), checkpoint every
    ``checkpoint_every_min`` and on SIGTERM/SIGINT, then export the best checkpoint.
    ``arch``: the network's widths (``model.ARCH_DEFAULT``'s keys; None: the start's own, or
    the default); wider than ``init``'s, the start is widened keeping its function
    (:func:`model.widened`). A resumed run keeps its checkpoint's. ``workers`` > 0: the
    batches are drawn in that many processes (:class:`BatchStream`; what keeps a GPU fed),
    else in this one. ``teacher`` (an exported ``.onnx`` or a ``.pt`` checkpoint, e.g. the bundled
    detector): the network also learns what the teacher computes on each batch
    (:func:`distillation_loss`, weighted ``distill_weight``), as a smaller student of it does;
    a resumed run needs it named again."""
    import signal

    if workers > 0:
        # no OpenCV thread pool in this process: the batch workers fork from it, and a forked
        # child's first parallel OpenCV call can wait forever on the parent's pool threads
        cv2.setNumThreads(0)
    torch.set_num_threads(threads)
    torch.manual_seed(seed)
    dev = pick_device(device)
    use_amp = amp and dev.type == "cuda"
    os.makedirs(work_dir, exist_ok=True)
    t_start = time.perf_counter()
    scene_folders = ensure_scenes(scene_root, specs=scenes or TRAIN_SCENES, generate=generate_scenes)
    # the views are cut in forked processes only where OpenCV's thread pool is off (with batch
    # workers, above): forked after that pool has started, a child can hang
    mix = DataMix(crop_px, work_dir, seed, source_weights=source_weights, small_share=small_share, faces=faces,
                  large_share=large_share, view_scales=view_scales, tall_share=tall_share,
                  cut_jobs=len(os.sched_getaffinity(0)) if workers > 0 else 1)
    mix.add_scenes(scene_folders)
    # GTSDB 500-599 picks the best checkpoint; views and pasted held-out tracks are watched
    val_sets = {"gtsdb_500_599": data.read_gtsdb(data.GTSDB_HELDOUT_IDS)[:val_images],
                "gtsrb_val_tracks": pasted_validation(min(30, val_images)),
                "views": mix.val_views[::max(1, len(mix.val_views) // val_images)]}

    state = torch.load(resume, map_location="cpu", weights_only=False) if resume else None
    # the batch workers fork here, before this process runs any torch computation: a
    # process forked after torch's thread pool has started can hang in its first operation
    loader = (batch_loader(mix, scene_folders, batch_size, seed, state.get("step", 0) if state else 0, workers,
                           pin=dev.type == "cuda")
              if workers > 0 else None)

    calibration: List[torch.Tensor] = []

    def calibration_batches():  # for an exported file's batch norms (recover_from_onnx), drawn once
        if not calibration:
            calibration.extend(batch_tensors([mix.sample() for _ in range(batch_size)], crop_px, len(CLASSES))[0]
                               for _ in range(6))
        return calibration

    if state is not None:
        net = SignNet(len(CLASSES), **checkpoint_arch(state))
        net.load_state_dict(state.get("net", state["model"]))
    elif init:
        net = load_network(init, calibration_batches, arch)
        if init.endswith(".onnx"):
            print(f"[train] weights recovered from {init}", flush=True)
    else:
        net = SignNet(len(CLASSES), **(arch or {}))
    want = dict(net.arch, **(arch or {}))
    want["widths"] = tuple(int(c) for c in want["widths"])
    if state is None and want != net.arch:
        net = widened(net, **want)
        print(f"[train] widened to {net.arch} (the same function to start from)", flush=True)
    net.to(dev)
    if dev.type == "cuda":
        net = net.to(memory_format=torch.channels_last)
    teacher_net = None
    if teacher:
        teacher_net = load_teacher(teacher, calibration_batches, dev)
        if dev.type == "cuda":
            teacher_net = teacher_net.to(memory_format=torch.channels_last)
        print(f"[train] distilling from {teacher} ({sum(p.numel() for p in teacher_net.parameters())} parameters, "
              f"weight {distill_weight})", flush=True)
    ema = copy.deepcopy(net).eval()
    if state is not None:
        ema.load_state_dict(state["model"])
    for p in ema.parameters():
        p.requires_grad_(False)
    opt = torch.optim.AdamW(net.parameters(), lr=lr, weight_decay=5e-4)
    scaler = torch.amp.GradScaler("cuda") if use_amp else None
    step, elapsed0, best_score, history = 0, 0.0, -1.0, []
    if state is not None:
        if state.get("opt"):
            opt.load_state_dict(state["opt"])
        if scaler is not None and state.get("scaler"):
            scaler.load_state_dict(state["scaler"])
        step, elapsed0 = state.get("step", 0), state.get("elapsed_s", 0.0)
        history, best_score = state.get("history", []), state.get("best_score", -1.0)
        rng = state.get("rng") or {}
        if rng.get("numpy"):
            mix.rng.bit_generator.state = rng["numpy"]
        if rng.get("torch") is not None:
            torch.set_rng_state(rng["torch"])
        if rng.get("cuda") is not None and torch.cuda.is_available():
            torch.cuda.set_rng_state_all(rng["cuda"])
        print(f"[train] resumed {resume} at step {step}, {elapsed0 / 60:.1f} min trained", flush=True)
    budget_s = minutes * 60.0
    left = _until_seconds(until)
    if left is not None:
        budget_s = min(budget_s, elapsed0 + left)
    stop = {"now": False}

    def on_signal(signum, frame):
        stop["now"] = True
    for sig in (signal.SIGTERM, signal.SIGINT):
        signal.signal(sig, on_signal)

    t_train = time.perf_counter()
    next_val = elapsed0 + validate_every_min * 60.0
    next_ckpt = elapsed0 + checkpoint_every_min * 60.0
    log = os.path.join(work_dir, "history.json")
    losses = []
    resumed = state is not None
    print(f"[train] {sum(p.numel() for p in net.parameters())} parameters on {dev} (amp {use_amp}, "
          f"{threads} threads, {workers or 'no'} batch workers); training to {budget_s / 60:.1f} min "
          f"(setup took {t_train - t_start:.0f} s)", flush=True)
    while True:
        elapsed = elapsed0 + time.perf_counter() - t_train
        done = elapsed >= budget_s or stop["now"]
        if elapsed >= next_val or done:
            mix.add_scenes(scene_folders)  # scenes generated meanwhile join in
            val_sets["views"] = mix.val_views[::max(1, len(mix.val_views) // val_images)]
            scores = validate(ema, val_sets)
            score = scores["gtsdb_500_599"]["ap50"]
            entry = {"step": step, "minutes": round(elapsed / 60, 2), "loss": float(np.mean(losses[-200:] or [0])),
                     "score": float(score), **scores, "views_train": len(mix.views)}
            history.append(entry)
            print(f"[train] {json.dumps(entry)}", flush=True)
            if score > best_score:
                best_score = score
                torch.save({"model": ema.state_dict(), "arch": net.arch, "step": step, "entry": entry},
                           os.path.join(work_dir, "best.pt"))
            save_checkpoint(os.path.join(work_dir, "last.pt"), net, ema, opt, scaler, step, elapsed, history,
                            best_score, mix)
            with open(log, "w") as f:
                json.dump(history, f, indent=1)
            next_val = elapsed + validate_every_min * 60.0
            next_ckpt = elapsed + checkpoint_every_min * 60.0
            if done:
                break
        elif elapsed >= next_ckpt:
            save_checkpoint(os.path.join(work_dir, "last.pt"), net, ema, opt, scaler, step, elapsed, history,
                            best_score, mix)
            next_ckpt = elapsed + checkpoint_every_min * 60.0
        # linear warm-up (from the run's first step), then cosine over the time budget
        frac = min(elapsed / budget_s, 1.0)
        for group in opt.param_groups:
            warm = 1.0 if resumed else min(1.0, (step + 1) / warmup_steps)
            group["lr"] = lr * warm * (0.02 + 0.98 * 0.5 * (1 + math.cos(math.pi * frac)))
        if loader is not None:
            x, (heat, valid, ind, reg, mask) = next(loader)
        else:
            x, (heat, valid, ind, reg, mask) = batch_tensors([mix.sample() for _ in range(batch_size)], crop_px,
                                                             len(CLASSES))
        x, heat, valid, ind, reg, mask = (t.to(dev, non_blocking=True) for t in (x, heat, valid, ind, reg, mask))
        x = to_unit(x)
        if dev.type == "cuda":
            x = x.contiguous(memory_format=torch.channels_last)
        with torch.autocast(device_type=dev.type, dtype=torch.float16, enabled=use_amp):
            logits, regression = net(x)
        l_heat = focal_loss(logits.float(), heat, valid)
        l_off, l_size = regression_loss(regression.float(), ind, reg, mask)
        loss = l_heat + l_off + l_size
        l_distill = torch.zeros(())
        if teacher_net is not None:
            with torch.no_grad(), torch.autocast(device_type=dev.type, dtype=torch.float16, enabled=use_amp):
                t_logits, t_regression = teacher_net(x)
            l_distill = distillation_loss(logits.float(), regression.float(), t_logits.float(), t_regression.float(),
                                          valid)
            loss = loss + distill_weight * l_distill
        opt.zero_grad(set_to_none=True)
        if scaler is not None:
            scaler.scale(loss).backward()
            scaler.unscale_(opt)
            torch.nn.utils.clip_grad_norm_(net.parameters(), 10.0)
            scaler.step(opt)
            scaler.update()
        else:
            loss.backward()
            torch.nn.utils.clip_grad_norm_(net.parameters(), 10.0)
            opt.step()
        with torch.no_grad():
            decay = min(ema_decay, (1 + step) / (10 + step))
            for e, p in zip(ema.state_dict().values(), net.state_dict().values()):
                if e.dtype.is_floating_point:
                    e.mul_(decay).add_(p.detach(), alpha=1 - decay)
                else:
                    e.copy_(p)
        losses.append(float(loss.detach()))
        step += 1
        if step % 50 == 0:
            print(f"[train] step {step} {elapsed / 60:.1f} min loss {np.mean(losses[-50:]):.3f} "
                  f"(heat {float(l_heat.detach()):.3f} off {float(l_off.detach()):.3f} "
                  f"size {float(l_size.detach()):.3f}"
                  + (f" distill {float(l_distill.detach()):.3f})" if teacher_net is not None else ")"), flush=True)

    if not export:
        return None
    return export_checkpoint(os.path.join(work_dir, "best.pt"), out_path)


def export_checkpoint(checkpoint: str, out_path: str, net: SignNet = None, operating_point: float = None,
                      maps_to: float = None):
    """Export a checkpoint with its scores calibrated: ``operating_point`` (a raw score; default
    the best-F1 threshold of the checkpoint's GTSDB validation) becomes the exported score
    ``maps_to`` (default ``model.PLUGIN_DEFAULT_CONFIDENCE``)."""
    best = torch.load(checkpoint, map_location="cpu", weights_only=False)
    net = net or SignNet(len(CLASSES), **checkpoint_arch(best))
    net = net.cpu().to(memory_format=torch.contiguous_format)
    net.load_state_dict(best["model"])
    threshold = operating_point or best["entry"]["gtsdb_500_599"]["best_f1_threshold"]
    target = maps_to or PLUGIN_DEFAULT_CONFIDENCE
    power = calibration_power(threshold, target)
    source = "the chosen operating point" if operating_point else "the validation best-F1 threshold"
    export_onnx(net, out_path, CLASSES, score_power=power, extra_metadata={
        "description": "Road sign detector (6 classes), CenterNet-style, trained by devtools/train",
        "score_calibration": f"raw ** {power:.4f}: {source} {threshold:.3f} maps to {target:.2f}",
        "training": json.dumps({"step": best["step"], "validation": best["entry"]})})
    print(f"[train] exported {out_path} ({os.path.getsize(out_path) / 1e6:.2f} MB) from step {best['step']} "
          f"(scores ** {power:.3f}): {json.dumps(best['entry'])}", flush=True)
    return out_path
