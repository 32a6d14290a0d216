"""Pack a GPU smoke check of the training scripts for a bare device machine.

``python -m devtools.train.device_smoke --out .devdata`` writes, in a folder the device tool
can carry (list it in ``.git/info/exclude``, name it in ``carry``):

- ``shared/data``: a subset of ``../shared/data`` small enough to travel (about 24 MB):
  the first :data:`GTSDB_PER_PART` GTSDB frames of each part (0-39, 500-539),
  :data:`GTSRB_TRACKS_PER_CLASS` gtsrb-train tracks and :data:`SUBSET_PER_CLASS`
  gtsrb-subset crops a class, the code table;
- ``scenes/tiny-100``: the smallest training scene (``bench/out/train/scenes``);
- ``run.sh``: on the device (``bash .devdata/run.sh``, ``OUT`` set), it puts the data where
  the scripts read it (``../shared/data``; it refuses where that exists, so it never
  overwrites the real data), links the missing GTSDB numbers to frames that are there (their
  truth then does not match the image: a smoke check, not a training run), then trains the
  detector from the bundled float file for 2 minutes on CUDA, resumes it to 3 minutes,
  exports it, and trains the code classifier for 1 minute on CUDA. The output is what to
  read: steps per minute on the GPU, and that every CUDA path (mixed precision, the
  gradient scaler, channels-last, resume, export) runs.
"""
from __future__ import annotations

import argparse
import collections
import csv
import os
import shutil
import sys

from .. import REPO_ROOT
from .data import DATA_DIR, GTSDB_HELDOUT_IDS, GTSDB_TRAIN_IDS

#: GTSDB frames carried: the first of the training part and of the held-out part
GTSDB_PER_PART = 40
GTSDB_FRAMES = tuple(GTSDB_TRAIN_IDS[:GTSDB_PER_PART]) + tuple(GTSDB_HELDOUT_IDS[:GTSDB_PER_PART])
GTSRB_TRACKS_PER_CLASS = 4
SUBSET_PER_CLASS = 4
SCENE = os.path.join(REPO_ROOT, "bench", "out", "train", "scenes", "tiny-100")

RUN_SH = r"""#!/bin/bash
# GPU smoke check of the training scripts (written by devtools/train/device_smoke.py).
set -x
cd "$(dirname "$0")/.."
HERE="$(basename "$(dirname "$0")")"
[ -e ../shared/data ] && { echo "../shared/data exists: this script is for the bare device machine"; exit 1; }
mkdir -p ../shared && cp -r "$HERE/shared/data" ../shared/
cd ../shared/data/gtsdb-train/images
set +x
for k in $(seq 0 @LAST@); do
  f=$(printf %05d $k).jpg; [ -e $f ] || ln -s $(printf %05d $(( k < @HELD@ ? k % @EACH@ : @HELD@ + k % @EACH@ ))).jpg $f
done
set -x
cd - > /dev/null
nvidia-smi --query-gpu=name,memory.total --format=csv
python3 -c "import torch, cv2, numpy, onnx, onnxruntime; print(torch.__version__, torch.cuda.is_available())"
export PYTHONUNBUFFERED=1
W=/tmp/w
time python3 -m devtools.train --device cuda --init models/roadsigns.onnx --no-generate --scenes "$HERE/scenes" \
  --work $W --out $OUT/smoke.onnx --minutes 2 --validate-every 1 --checkpoint-every 1 --val-images 20 \
  --faces 200 --no-export 2>&1 | tail -40
time python3 -m devtools.train --device cuda --resume $W/last.pt --no-generate --scenes "$HERE/scenes" \
  --work $W --out $OUT/smoke.onnx --minutes 3 --validate-every 1 --checkpoint-every 1 --val-images 20 \
  --faces 200 2>&1 | tail -25
mkdir -p bench/out/train/scenes && cp -r "$HERE/scenes/tiny-100" bench/out/train/scenes/
time python3 -m devtools.train.codes --device cuda --minutes 1 --workers 6 --crop-px 40 --work /tmp/wc \
  --out $OUT/codes-smoke.onnx 2>&1 | grep -v -i warning | tail -15
ls -la $OUT
"""


def _subset_csv(src: str, dst: str, keep) -> list:
    """The rows of the ``;`` CSV ``src`` that ``keep(rows)`` returns, written to ``dst``."""
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f, delimiter=";"))
    kept = keep(rows)
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    with open(dst, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]), delimiter=";")
        writer.writeheader()
        writer.writerows(kept)
    return kept


def copy_file(src: str, dst: str) -> None:
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    shutil.copy(src, dst)


def copy_gtsdb(data_dir: str, data: str, frames) -> None:
    """The data folder's README, the code table, GTSDB's truth and the GTSDB images numbered
    ``frames`` from ``data_dir`` into ``data`` (a subset of it that travels)."""
    for name in ("README.md", "sign-codes-de.csv", os.path.join("gtsdb-train", "gt.txt")):
        copy_file(os.path.join(data_dir, name), os.path.join(data, name))
    for k in frames:
        name = os.path.join("gtsdb-train", "images", f"{k:05d}.jpg")
        copy_file(os.path.join(data_dir, name), os.path.join(data, name))


def first_tracks(rows, n: int = GTSRB_TRACKS_PER_CLASS):
    """The rows of each class's first ``n`` tracks."""
    tracks = collections.defaultdict(set)
    for row in rows:
        tracks[row["ClassId"]].add(row["Track"])
    keep = {c: set(sorted(t)[:n]) for c, t in tracks.items()}
    return [row for row in rows if row["Track"] in keep[row["ClassId"]]]


def first_per_class(rows, n: int = SUBSET_PER_CLASS):
    """The first ``n`` rows of each class."""
    seen: collections.Counter = collections.Counter()
    kept = []
    for row in rows:
        if seen[row["ClassId"]] < n:
            kept.append(row)
            seen[row["ClassId"]] += 1
    return kept


def pack(out_dir: str, data_dir: str = DATA_DIR, scene: str = SCENE) -> None:
    """Write the subset, the scene and ``run.sh`` into ``out_dir`` (replaced)."""
    if not os.path.isfile(os.path.join(scene, "scene.json")):
        raise SystemExit(f"{scene} is missing: generate it first (python -m devtools.scenegen --preset tiny "
                         f"--seed 100 --no-lidar --no-masks --out {scene})")
    shutil.rmtree(out_dir, ignore_errors=True)
    data = os.path.join(out_dir, "shared", "data")
    copy_gtsdb(data_dir, data, GTSDB_FRAMES)
    for row in _subset_csv(os.path.join(data_dir, "gtsrb-train", "GT-train.csv"),
                           os.path.join(data, "gtsrb-train", "GT-train.csv"), first_tracks):
        name = os.path.join("gtsrb-train", "train", row["File"])
        copy_file(os.path.join(data_dir, name), os.path.join(data, name))
    for row in _subset_csv(os.path.join(data_dir, "gtsrb-subset", "GT-subset.csv"),
                           os.path.join(data, "gtsrb-subset", "GT-subset.csv"), first_per_class):
        name = os.path.join("gtsrb-subset", "train", row["ClassFolder"], row["Filename"])
        copy_file(os.path.join(data_dir, name), os.path.join(data, name))
    shutil.copytree(scene, os.path.join(out_dir, "scenes", os.path.basename(scene)))
    with open(os.path.join(out_dir, "run.sh"), "w") as f:
        f.write(RUN_SH.replace("@HELD@", str(GTSDB_HELDOUT_IDS[0])).replace("@EACH@", str(GTSDB_PER_PART))
                .replace("@LAST@", str(GTSDB_HELDOUT_IDS[-1])))
    os.chmod(os.path.join(out_dir, "run.sh"), 0o755)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m devtools.train.device_smoke", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, ".devdata"))
    a = ap.parse_args(argv)
    pack(a.out)
    size = sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(a.out) for f in files)
    print(f"{a.out}: {size / 2**20:.1f} MB; on the device: OUT=$OUT bash {os.path.basename(a.out)}/run.sh")
    return 0


if __name__ == "__main__":
    sys.exit(main())
