"""CLI: ``python -m devtools.scenegen --preset tiny --seed 1 --out DIR``."""
from __future__ import annotations

import argparse
import resource
import sys
import time

from . import PRESETS, generate_scene
from .render import LOOKS


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m devtools.scenegen", description=__doc__)
    ap.add_argument("--preset", default="tiny", choices=sorted(PRESETS))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--crs", default="projected", choices=["projected", "geographic"],
                    help="CRS of trajectory.csv and poses.csv (the cloud and reference are EPSG:32633)")
    ap.add_argument("--no-panoramas", action="store_true")
    ap.add_argument("--no-lidar", action="store_true")
    ap.add_argument("--no-masks", action="store_true", help="do not write the sign-id mask PNGs")
    ap.add_argument("--pano-width", type=int, default=None, help="equirectangular width (height = width / 2)")
    ap.add_argument("--image-spacing", type=float, default=None,
                    help="metres between panorama exposures (default: the preset's)")
    ap.add_argument("--look", default="training", choices=sorted(LOOKS),
                    help="light and camera of the panoramas: training (every training and bench scene), or a "
                         "held-out look whose ranges the training never saw (dusk, glare)")
    ap.add_argument("--jobs", type=int, default=1,
                    help="processes rendering the panoramas (the same files as with one)")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    paths = generate_scene(a.preset, a.seed, a.out, crs=a.crs, panoramas=not a.no_panoramas, lidar=not a.no_lidar,
                           pano_width=a.pano_width, masks=not a.no_masks, verbose=True,
                           image_spacing_m=a.image_spacing, look=a.look, jobs=a.jobs)
    peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"[scenegen] wrote {a.out} in {time.perf_counter() - t0:.1f} s (peak memory {peak_mib:.0f} MiB)")
    for k, v in sorted(paths.items()):
        print(f"  {k}: {v}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
