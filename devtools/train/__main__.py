"""CLI: ``python -m devtools.train --minutes 40 --out models/roadsigns.onnx``.

Generates the training scenes when missing (devtools.scenegen, seeds 100 and up, no LiDAR),
trains on 2 CPU threads for the given wall time, validates every few minutes and exports
the best checkpoint to ONNX. See models/README.md.
"""
from __future__ import annotations

import argparse
import os
import sys

from .. import REPO_ROOT


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m devtools.train", description=__doc__)
    ap.add_argument("--minutes", type=float, default=40.0, help="training wall time (after set-up)")
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, "models", "roadsigns.onnx"))
    ap.add_argument("--work", default=os.path.join(REPO_ROOT, "bench", "out", "train"),
                    help="checkpoints, cut views, history.json")
    ap.add_argument("--scenes", default=None, help="folder of the generated training scenes (default WORK/scenes)")
    ap.add_argument("--no-generate", action="store_true",
                    help="use only the training scenes already there (others join when they appear)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--batch", type=int, default=16)
    ap.add_argument("--crop", type=int, default=320)
    ap.add_argument("--lr", type=float, default=3e-3)
    ap.add_argument("--validate-every", type=float, default=5.0, help="minutes")
    ap.add_argument("--val-images", type=int, default=60, help="images per validation set and round")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--resume", default=None, help="a checkpoint (.pt) to start from")
    ap.add_argument("--export-only", metavar="CKPT", help="only export this checkpoint (.pt) to --out")
    a = ap.parse_args(argv)
    from .train import export_checkpoint, train
    if a.export_only:
        export_checkpoint(a.export_only, a.out)
        return 0
    train(a.out, a.minutes, a.work, a.scenes or os.path.join(a.work, "scenes"), generate_scenes=not a.no_generate,
          crop_px=a.crop, batch_size=a.batch, lr=a.lr, threads=a.threads, validate_every_min=a.validate_every,
          seed=a.seed, resume=a.resume, val_images=a.val_images)
    return 0


if __name__ == "__main__":
    sys.exit(main())
