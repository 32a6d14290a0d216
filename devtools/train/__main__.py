"""CLI: ``python -m devtools.train --minutes 40 --out models/roadsigns.onnx``.

Generates the training scenes when missing (devtools.scenegen, seeds 100 and up, no LiDAR),
trains for the given training time (CUDA with mixed precision where present, else the
CPU), validates every few minutes (best by AP50 on GTSDB 500-599), checkpoints every few
minutes and on SIGTERM, and exports the best checkpoint to ONNX. A run cut off goes on with
the same command plus ``--resume WORK/last.pt``. See models/README.md.
"""
from __future__ import annotations

import argparse
import os
import sys

from .. import REPO_ROOT
from .data import parse_scale_range, parse_scene_specs, parse_shares


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m devtools.train", description=__doc__)
    ap.add_argument("--minutes", type=float, default=40.0,
                    help="training time in all (a resumed run counts the time already trained)")
    ap.add_argument("--until", default=None, help="stop at this UTC time (HH:MM or ISO) if earlier")
    ap.add_argument("--out", default=os.path.join(REPO_ROOT, "models", "roadsigns.onnx"))
    ap.add_argument("--work", default=os.path.join(REPO_ROOT, "bench", "out", "train"),
                    help="checkpoints, cut views, history.json")
    ap.add_argument("--scenes", default=None, help="folder of the generated training scenes (default WORK/scenes)")
    ap.add_argument("--train-scenes", type=parse_scene_specs, default=None, metavar="PRESET:SEED,...",
                    help="the generated training scenes (default train.TRAIN_SCENES); seeds from "
                         "data.FIRST_TRAINING_SEED up, the bench's are below")
    ap.add_argument("--no-generate", action="store_true",
                    help="use only the training scenes already there (others join when they appear)")
    ap.add_argument("--device", default="auto", help="auto (CUDA when present), cpu, cuda, cuda:1, ...")
    ap.add_argument("--no-amp", action="store_true", help="no mixed precision on CUDA")
    ap.add_argument("--threads", type=int, default=2, help="CPU threads (torch.set_num_threads)")
    ap.add_argument("--workers", type=int, default=0,
                    help="processes drawing the training batches (0: this one); on a GPU, what keeps it fed")
    ap.add_argument("--batch", type=int, default=16)
    ap.add_argument("--crop", type=int, default=320)
    ap.add_argument("--lr", type=float, default=3e-3)
    ap.add_argument("--warmup", type=int, default=300, help="warm-up steps (not on --resume)")
    ap.add_argument("--validate-every", type=float, default=5.0, help="minutes")
    ap.add_argument("--checkpoint-every", type=float, default=10.0, help="minutes between WORK/last.pt saves")
    ap.add_argument("--val-images", type=int, default=60, help="images per validation set and round")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--ema-decay", type=float, default=0.998, help="EMA of the weights (lower follows faster)")
    ap.add_argument("--small-share", type=float, default=0.0,
                    help="share of pasted real signs drawn at 14-35 px (far signs), 0..1")
    ap.add_argument("--large-share", type=float, default=0.0,
                    help="share of the crops of generated views with a large sign that show it whole "
                         "(data.LARGE_SIGN_FILL of the crop), 0..1")
    ap.add_argument("--tall-share", type=float, default=0.0,
                    help="share of the crops of generated views taken round a sign seen nearly edge-on "
                         "(data.tall_sign_crop), among the views that show one, 0..1")
    ap.add_argument("--view-scales", type=parse_scale_range, default=None, metavar="LO,HI",
                    help="the scales crops of generated views are taken at, log-uniform "
                         "(default train.VIEW_CROP_SCALES; lower, the views' facades and overhead panels "
                         "are also seen at fewer pixels a degree)")
    ap.add_argument("--faces", type=int, default=None,
                    help="faces of many countries drawn at the start for faces_paste (default train.FACES; 0: none)")
    ap.add_argument("--source-weights", type=parse_shares, default=None, metavar="NAME=W,...",
                    help="override the data mix's shares, e.g. views=0.5,gtsdb=0.2 (names: gtsdb, gtsrb_paste, "
                         "drawn_paste, views, faces_paste, gtsdb_hard)")
    ap.add_argument("--resume", default=None, help="a checkpoint (WORK/last.pt) to go on from, with its "
                    "optimiser, EMA, step, training time and random states")
    ap.add_argument("--init", default=None, help="start weights only: a checkpoint (.pt) or an exported "
                    "model (.onnx, e.g. models/roadsigns.onnx: its folded batch norms are recovered)")
    ap.add_argument("--widths", default=None, metavar="C4,C8,C16,C32",
                    help="the backbone's widths at strides 4, 8, 16 and 32 (default: the start's, or 32,48,96,160); "
                         "wider than --init's, the start is widened keeping its function")
    ap.add_argument("--fpn", type=int, default=None, help="the pyramid's width (default: the start's, or 64)")
    ap.add_argument("--head", type=int, default=None, help="the head's width (default: the start's, or 32)")
    ap.add_argument("--teacher", default=None, metavar="MODEL",
                    help="distil from this detector (.onnx, e.g. models/roadsigns.onnx, or a .pt checkpoint): "
                         "the network also learns what the teacher computes on each batch, as a smaller "
                         "student (--widths, --fpn, --head) of it does; name it again on --resume")
    ap.add_argument("--distill-weight", type=float, default=None,
                    help="weight of the distillation loss beside the targets' (default train.DISTILL_WEIGHT)")
    ap.add_argument("--no-export", action="store_true", help="do not export at the end")
    ap.add_argument("--export-only", metavar="CKPT", help="only export this checkpoint (.pt) to --out")
    ap.add_argument("--operating-point", type=float, default=None, metavar="SCORE",
                    help="with --export-only: the raw score to map to the plugin's default confidence "
                         "(default: the checkpoint's validation best-F1 threshold)")
    ap.add_argument("--maps-to", type=float, default=None, metavar="SCORE",
                    help="with --export-only: the exported score the operating point becomes (default 0.4)")
    a = ap.parse_args(argv)
    from .train import DISTILL_WEIGHT, FACES, export_checkpoint, train
    if a.export_only:
        export_checkpoint(a.export_only, a.out, operating_point=a.operating_point, maps_to=a.maps_to)
        return 0
    train(a.out, a.minutes, a.work, a.scenes or os.path.join(a.work, "scenes"), generate_scenes=not a.no_generate,
          crop_px=a.crop, batch_size=a.batch, lr=a.lr, threads=a.threads, validate_every_min=a.validate_every,
          seed=a.seed, resume=a.resume, val_images=a.val_images, init=a.init, device=a.device,
          checkpoint_every_min=a.checkpoint_every, until=a.until, warmup_steps=a.warmup, amp=not a.no_amp,
          export=not a.no_export, ema_decay=a.ema_decay, small_share=a.small_share, large_share=a.large_share,
          tall_share=a.tall_share, faces=FACES if a.faces is None else a.faces,
          view_scales=a.view_scales, scenes=a.train_scenes,
          arch={k: v for k, v in (("widths", tuple(int(c) for c in a.widths.split(",")) if a.widths else None),
                                  ("fpn", a.fpn), ("head", a.head)) if v is not None} or None,
          source_weights=a.source_weights, workers=a.workers, teacher=a.teacher,
          distill_weight=DISTILL_WEIGHT if a.distill_weight is None else a.distill_weight)
    return 0


if __name__ == "__main__":
    sys.exit(main())
