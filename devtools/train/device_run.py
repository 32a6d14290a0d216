"""Pack a training run of the detector for a device machine (a GPU lent for minutes).

The data (``../shared/data``) and the training scenes do not travel in one call: a call
carries at most 64 MiB, the repository included. So the run is two calls on one machine:

1. ``python -m devtools.train.device_run --out .devdata`` writes here, in a folder the device
   tool can carry (list ``/.devdata/`` in ``.git/info/exclude``), two parts that each fit a
   call (:func:`travel_bytes`; GTSDB training frames that fit in neither are left out, and said):

   - ``a/``: the wheels the renderer needs and the machine lacks (pyproj, laspy; fetched once
     into ``.whl/``), ``stash.sh``, and two thirds of the GTSDB training frames;
   - ``b/``: every third GTSDB training frame (``k % 3 == 0``: part b alone trains on a
     spread), GTSDB frames 500-529 (validation), six of the ten ``gtsrb-train`` crops of
     every track (:data:`GTSRB_TRACK_FRAMES`; re-encoded as JPEG under their PNG names:
     OpenCV reads an image by its content), the code table, the ``tiny`` training
     street, and ``run.sh``.

2. Call 1 (carry ``.devdata/a``): ``bash .devdata/a/stash.sh`` puts part a in ``/root/rsi-a``,
   installs the wheels there, and (``CHECK=1``) times a training step on random data with
   every CUDA path of the run (``--check-cuda``).
3. Call 2 at once (carry ``.devdata/b``; the machine stays warm 30 s only): ``BUDGET_S=590 bash
   .devdata/b/run.sh`` with ``timeout_s`` 600 (a call runs 10 minutes at most, and a session has
   15 minutes of device time, the machine's start included: on 4 December call 1 and the start
   took 41 s, call 2's transfers about 30 s, six streets 4.5 minutes and the training's set-up
   80 s, which left about 3 minutes of training at 25 steps a second; the three streets of the
   default take about 2.2 minutes, which leaves about 5). The script keeps
   to ``BUDGET_S`` seconds from its start: it begins no street after ``RENDER_S`` (240) and
   trains (``--until``) for what is left less ``EXPORT_S`` (60), through
   ``devtools/train/device_train.sh``. A third call on the same warm machine goes on from the
   last checkpoint with call 2's flags: ``RESUME=1 BUDGET_S=200 bash
   devtools/train/device_train.sh`` (``BUDGET_S``: what the lease has left), carrying nothing
   (the script is in the repository). run.sh puts
   the data where the scripts read it (``../shared/data``; it refuses where that exists: on the
   same machine again, remove ``../shared`` and ``/tmp/w`` first), adds part a when the machine
   still has it (else it trains on part b's frames alone and says so), renders the
   ``default`` training streets first (each with every core: ``scenegen --jobs``), and trains
   from the bundled float file on CUDA with :data:`WORKERS` batch workers. ``$OUT`` gets the
   log, ``history.json``, and the best and the last checkpoint exported (``roadsigns-gpu.onnx``,
   ``roadsigns-last.onnx``: ``--init`` goes on from either; a checkpoint with its optimiser is
   over the 16 MiB a returned file may have).

The flags are the bundled file's run (models/README.md, "Bundled on 28 November, tenth
session") on its own four training streets (:data:`DEFAULT_SEEDS`, :data:`TINY_SCENES`) and its
mix (:data:`DEFAULT_TALL_SHARE`), with batch 32: a lease then measures what more steps alone
give. ``--seeds`` and ``--tall-share`` pack the second GPU run's choices instead.

Measured on the H200 (28 November, sixteenth session; models/README.md, "The first GPU
run"): a training step of batch 32 takes 18 ms on the GPU; the twelve workers fed it about
700 crops a second (22 steps a second: the CPU, not the GPU, set the pace). Since 4 December
(thirty-eighth session) a worker draws a crop 1.8-2.1 x faster (a scene's views decoded once,
:func:`.data.view_store`; the colour jitter one matrix), so twelve should keep the GPU's
1,780 crops a second busy. Rendered beside
the training, the six streets took 8.5 minutes each and joined only as the run ended; so
``run.sh`` renders them first, each with every core (untried on the machine: 61 panoramas
of 4.5 s on one core each: 140 s a street with two jobs here, about 3 minutes for the six on
sixteen cores).
"""
from __future__ import annotations

import argparse
import collections
import csv
import os
import shutil
import subprocess
import sys

import cv2

from .. import REPO_ROOT
from .data import DATA_DIR, GTSDB_HELDOUT_IDS, GTSDB_TRAIN_IDS
from .device_smoke import copy_file, copy_gtsdb

#: GTSDB held-out frames carried for the run's validation (its first ``--val-images``)
VAL_IMAGES = 30
VAL_FRAMES = tuple(GTSDB_HELDOUT_IDS[:VAL_IMAGES])
#: The frames of each gtsrb-train track carried, by their order far to near (of ten): the
#: rest do not fit in a call; the scripts leave out the crops that are not there
GTSRB_TRACK_FRAMES = (0, 2, 4, 6, 8, 9)
GTSRB_JPEG_QUALITY = 88
#: What one call may carry, the repository included (the device tool's limit), and a margin
CALL_BYTES = 64 * 2**20
MARGIN_BYTES = 2**20
#: Wheels (Python 3.12, x86-64) of what the renderer needs and the device machine lacks
WHEELS = os.path.join(REPO_ROOT, ".whl")
WHEEL_NAMES = ("pyproj", "laspy")
WHEEL_DOWNLOAD = ("python3 -m pip download --no-deps --only-binary=:all: --python-version 3.12 --implementation cp "
                  "--platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64 "
                  "-d .whl pyproj==3.7.1 laspy==2.7.0")
WORKERS = 12
SCENES = os.path.join(REPO_ROOT, "bench", "out", "train", "scenes")
#: The training streets: by default the bundled file's own (``tiny`` 100, ``default``
#: 100-102), rendered on the machine; ``--seeds`` may add 106-108 (:data:`MORE_SEEDS`, the
#: second GPU run's six). ``default`` 103-105 and ``tiny`` 101 stay out: they are the "four
#: more streets" no bundled file was trained on, a second held-out set.
TINY_SCENES = ("tiny-100",)
DEFAULT_SEEDS = (100, 101, 102)
MORE_SEEDS = (106, 107, 108)
#: The share of generated-view crops centred on a sign seen edge-on (``train --tall-share``):
#: the bundled file's run had none; the second GPU run's 0.25 came with twice the false boxes
#: (models/README.md, "The second GPU run"), so a lease tries the bundled file's own mix first.
DEFAULT_TALL_SHARE = 0.0
HELD_OUT_SCENES = ("default-103", "default-104", "default-105", "tiny-101")

STASH_SH = r"""#!/bin/bash
# Call 1 of a device training run (devtools/train/device_run.py): keep part a on the machine,
# and check every CUDA path of a training step on random data (seconds) before call 2.
set -e
HERE="$(cd "$(dirname "$0")" && pwd)"
mkdir -p /root/rsi-a && cp -r "$HERE/images" /root/rsi-a/
ls /root/rsi-a/images | wc -l
python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target /root/rsi-a/site \
  "$HERE"/whl/*.whl
nvidia-smi --query-gpu=name,memory.total --format=csv
cd "$HERE/../.."
if [ "${CHECK:-0}" = 1 ]; then python3 -m devtools.train.device_run --check-cuda; fi
"""

RUN_SH = r"""#!/bin/bash
# Call 2 of a device training run (written by devtools/train/device_run.py).
set -x
T0=$(date +%s)
HERE="$(cd "$(dirname "$0")" && pwd)"
cd "$HERE/../.."
[ -e ../shared/data ] && { echo "../shared/data exists: this script is for the bare device machine"; exit 1; }
mkdir -p ../shared && cp -r "$HERE/shared/data" ../shared/
if [ -d /root/rsi-a/images ]; then cp /root/rsi-a/images/* ../shared/data/gtsdb-train/images/;
else echo "PART A IS NOT ON THIS MACHINE: training on part b's GTSDB frames alone"; fi
ls ../shared/data/gtsdb-train/images | wc -l
nvidia-smi --query-gpu=name,memory.total --format=csv
export PYTHONUNBUFFERED=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
W=/tmp/w; mkdir -p $W/scenes && cp -r "$HERE"/scenes/* $W/scenes/
[ -d /root/rsi-a/site ] || echo "NO PYPROJ: the default streets cannot be generated, only the tiny one trains"
# the streets first, one after another, each with every core (rendered beside the training they
# took 8.5 minutes each and joined only as it ended; not nproc, which obeys OMP_NUM_THREADS),
# none begun after RENDER_S seconds of the call's budget (BUDGET_S, from this script's start)
for s in @SEEDS@; do
  [ $(( $(date +%s) - T0 )) -gt ${RENDER_S:-240} ] && { echo "street $s not rendered: too late"; continue; }
  [ -d /root/rsi-a/site ] && PYTHONPATH=/root/rsi-a/site \
  python3 -m devtools.scenegen --preset default --seed $s --no-lidar --no-masks --out $W/scenes/default-$s \
    --jobs $(getconf _NPROCESSORS_ONLN) > $OUT/scenegen-$s.log 2>&1
  echo "street $s rendered at $(( $(date +%s) - T0 )) s"
done
grep -h "panoramas:" $OUT/scenegen-*.log
# the training (devtools/train/device_train.sh, which a third call runs alone with RESUME=1) with
# these flags, to this script's budget; counted after its set-up (loading the data and cutting the views)
echo "--device ${DEVICE:-cuda} --init models/roadsigns.onnx --no-generate --scenes $W/scenes \
  --train-scenes @TRAIN_SCENES@ --work $W --minutes 600 --validate-every 1.5 --checkpoint-every 1.5 \
  --val-images @VAL@ --workers @WORKERS@ --batch 32 --lr 3e-4 --warmup 100 --ema-decay 0.998 \
  --small-share 0.3 --large-share 0.3 --tall-share @TALL@" > $W/train.args
T0=$T0 W=$W bash devtools/train/device_train.sh
"""


def _write_script(path: str, text: str) -> None:
    with open(path, "w") as f:
        f.write(text)
    os.chmod(path, 0o755)


def travel_bytes(size: int) -> int:
    """What one file of ``size`` bytes counts towards a call: its bytes in 512-byte blocks and a
    512-byte header, as in a tar archive. (Counted as plain bytes, a part 1.5 MiB under the limit
    was refused: its 6,700 small crops cost some 5 MB more.)"""
    return 512 + -(-size // 512) * 512


def tree_bytes(folder: str) -> int:
    return sum(travel_bytes(os.path.getsize(os.path.join(d, f))) for d, _, files in os.walk(folder) for f in files)


def repository_bytes() -> int:
    """What the files git tracks count: they travel with every call beside the carried folder."""
    names = subprocess.run(["git", "ls-files", "-z"], cwd=REPO_ROOT, capture_output=True, check=True).stdout
    return sum(travel_bytes(os.path.getsize(os.path.join(REPO_ROOT, n))) for n in names.decode().split("\0")
               if n and os.path.isfile(os.path.join(REPO_ROOT, n)))


def pack(out_dir: str, data_dir: str = DATA_DIR, scenes: str = SCENES, wheels: str = WHEELS,
         seeds=DEFAULT_SEEDS, tall_share: float = DEFAULT_TALL_SHARE) -> dict:
    """Write parts ``a`` and ``b`` into ``out_dir`` (replaced), each within a call's bytes, for a
    run on the ``default`` streets ``seeds`` (rendered there) with ``tall_share``; returns their
    sizes and the GTSDB training frames neither could take."""
    held_out = [s for s in seeds if f"default-{s}" in HELD_OUT_SCENES]
    if held_out:
        raise SystemExit(f"default {', '.join(map(str, held_out))}: held out, never trained on")
    for name in TINY_SCENES:
        if not os.path.isfile(os.path.join(scenes, name, "scene.json")):
            raise SystemExit(f"{scenes}/{name} is missing: python -m devtools.scenegen --preset tiny "
                             f"--seed {name.split('-')[1]} --no-lidar --no-masks --out {scenes}/{name}")
    found = {w: [f for f in sorted(os.listdir(wheels)) if f.startswith(w + "-") and f.endswith(".whl")]
             if os.path.isdir(wheels) else [] for w in WHEEL_NAMES}
    if not all(found.values()):
        raise SystemExit(f"the wheels {', '.join(WHEEL_NAMES)} are not in {wheels}: {WHEEL_DOWNLOAD}")
    shutil.rmtree(out_dir, ignore_errors=True)
    budget = CALL_BYTES - repository_bytes() - MARGIN_BYTES
    part_a, part_b = os.path.join(out_dir, "a"), os.path.join(out_dir, "b")
    # part b: what the run cannot do without
    data = os.path.join(part_b, "shared", "data")
    copy_gtsdb(data_dir, data, VAL_FRAMES)
    src = os.path.join(data_dir, "gtsrb-train")
    copy_file(os.path.join(src, "GT-train.csv"), os.path.join(data, "gtsrb-train", "GT-train.csv"))
    with open(os.path.join(src, "GT-train.csv"), newline="") as f:
        rows = list(csv.DictReader(f, delimiter=";"))
    tracks = collections.defaultdict(list)
    for row in rows:
        tracks[(row["ClassId"], row["Track"])].append(row)
    for track in tracks.values():
        for n, row in enumerate(sorted(track, key=lambda r: int(r["Frame"]))):
            if n not in GTSRB_TRACK_FRAMES:
                continue
            dst = os.path.join(data, "gtsrb-train", "train", row["File"])
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            image = cv2.imread(os.path.join(src, "train", row["File"]))
            ok, enc = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, GTSRB_JPEG_QUALITY])
            with open(dst, "wb") as out:
                out.write(enc.tobytes())
    for name in TINY_SCENES:
        shutil.copytree(os.path.join(scenes, name), os.path.join(part_b, "scenes", name))
    train_scenes = ",".join([f"default:{s}" for s in seeds] + [n.replace("-", ":") for n in TINY_SCENES])
    _write_script(os.path.join(part_b, "run.sh"),
                  RUN_SH.replace("@SEEDS@", " ".join(str(s) for s in seeds))
                  .replace("@TRAIN_SCENES@", train_scenes).replace("@WORKERS@", str(WORKERS))
                  .replace("@VAL@", str(VAL_IMAGES)).replace("@TALL@", f"{tall_share:g}"))
    # part a: the wheels the renderer needs, the check
    for names in found.values():
        copy_file(os.path.join(wheels, names[-1]), os.path.join(part_a, "whl", names[-1]))
    _write_script(os.path.join(part_a, "stash.sh"), STASH_SH)
    # the GTSDB training frames: every third to b (so b alone trains on a spread), the rest to
    # a, each while it has room; then what is left to whichever has room
    sizes = {"a": tree_bytes(part_a), "b": tree_bytes(part_b)}
    for part, size in sizes.items():
        if size > budget:
            raise SystemExit(f"part {part} needs {size / 2**20:.1f} MiB before any GTSDB training frame; "
                             f"a call carries {budget / 2**20:.1f} MiB beside the repository")
    left = []
    for k in sorted(GTSDB_TRAIN_IDS, key=lambda k: (k % 3 != 0, k)):
        path = os.path.join(data_dir, "gtsdb-train", "images", f"{k:05d}.jpg")
        size = travel_bytes(os.path.getsize(path))
        for part in (("b", "a") if k % 3 == 0 else ("a", "b")):
            if sizes[part] + size <= budget:
                where = os.path.join(part_a, "images") if part == "a" else os.path.join(data, "gtsdb-train", "images")
                copy_file(path, os.path.join(where, os.path.basename(path)))
                sizes[part] += size
                break
        else:
            left.append(k)
    return {"a": sizes["a"], "b": sizes["b"], "budget": budget, "left_out": left}


def check_cuda() -> None:
    """One training step of the detector on random data on the GPU with every CUDA path the
    run takes (channels-last, float16 autocast, the gradient scaler, the losses, decoding),
    timed over 20 steps of batch 32, then an ONNX export from the trained weights."""
    import tempfile
    import time

    import torch

    from .data import CLASSES
    from .model import SignNet, decode, export_onnx, onnx_arch
    from .train import focal_loss, regression_loss

    dev = torch.device("cuda" if torch.cuda.is_available() else "cpu")
    net = SignNet(len(CLASSES), **onnx_arch(os.path.join(REPO_ROOT, "models", "roadsigns.onnx")))
    net = net.to(dev).to(memory_format=torch.channels_last)
    opt = torch.optim.AdamW(net.parameters(), lr=3e-4)
    scaler = torch.amp.GradScaler("cuda") if dev.type == "cuda" else None
    x = torch.rand(32, 3, 320, 320, device=dev).contiguous(memory_format=torch.channels_last)
    g = 320 // 4
    heat = torch.zeros(32, len(CLASSES), g, g, device=dev)
    heat[:, 0, 10, 10] = 1.0
    valid = torch.ones(32, g, g, device=dev)
    ind = torch.full((32, 64), 10 * g + 10, dtype=torch.long, device=dev)
    reg = torch.zeros(32, 64, 4, device=dev)
    mask = torch.zeros(32, 64, device=dev)
    mask[:, 0] = 1.0
    for k in range(21):
        if k == 1:
            if dev.type == "cuda":
                torch.cuda.synchronize()
            t0 = time.perf_counter()
        with torch.autocast(device_type=dev.type, dtype=torch.float16, enabled=dev.type == "cuda"):
            logits, regression = net(x)
        loss = focal_loss(logits.float(), heat, valid) + sum(regression_loss(regression.float(), ind, reg, mask))
        opt.zero_grad(set_to_none=True)
        if scaler is not None:
            scaler.scale(loss).backward()
            scaler.unscale_(opt)
            scaler.step(opt)
            scaler.update()
        else:
            loss.backward()
            opt.step()
    if dev.type == "cuda":
        torch.cuda.synchronize()
    step_ms = (time.perf_counter() - t0) / 20 * 1000
    boxes = decode(logits.float(), regression.float())
    path = os.path.join(tempfile.mkdtemp(), "check.onnx")
    export_onnx(net.cpu().to(memory_format=torch.contiguous_format), path, CLASSES)
    print(f"[check] {dev}: loss {float(loss):.3f}, {step_ms:.1f} ms a step of 32 at 320 px, decoded "
          f"{tuple(boxes.shape)}, exported {os.path.getsize(path) / 1e6:.2f} MB")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m devtools.train.device_run", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, ".devdata"))
    ap.add_argument("--check-cuda", action="store_true", help="only time a training step on the GPU (call 1)")
    ap.add_argument("--seeds", default=",".join(map(str, DEFAULT_SEEDS)),
                    help="the default streets rendered and trained on, comma-separated (default: the bundled "
                         f"file's; {','.join(map(str, DEFAULT_SEEDS + MORE_SEEDS))}: the second GPU run's six)")
    ap.add_argument("--tall-share", type=float, default=DEFAULT_TALL_SHARE,
                    help="train --tall-share: crops centred on a sign seen edge-on (default: the bundled file's 0)")
    a = ap.parse_args(argv)
    if a.check_cuda:
        check_cuda()
        return 0
    packed = pack(a.out, seeds=tuple(int(s) for s in a.seeds.split(",") if s.strip()), tall_share=a.tall_share)
    for part in ("a", "b"):
        print(f"{a.out}/{part}: {packed[part] / 2**20:.1f} MiB (a call may carry {packed['budget'] / 2**20:.1f})")
    print(f"GTSDB training frames left out: {len(packed['left_out'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
