"""Scene presets: size of the road, sensors' rates, image size."""
from __future__ import annotations

from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Preset:
    """Everything that sets a scene's size; lengths in metres, rates in Hz."""

    name: str
    road_length_m: float          # length of the furnished road (images from s = 0 to here)
    curvature_per_m: float        # signed road curvature, + = left turn
    sign_spacing_m: float         # mean distance between sign groups along the road
    gantry_every_m: float         # one overhead gantry per this length (at least one)
    image_spacing_m: float = 5.0  # distance between panorama exposures
    pano_width: int = 4096        # equirectangular width W (height W/2)
    speed_mps: float = 10.0       # mean vehicle speed
    scan_lines_per_s: float = 250.0
    points_per_line: int = 1500
    lead_in_m: float = 15.0       # driving before s = 0 and after the road's end
    scenery_margin_m: float = 40.0  # furnished road beyond both ends


PRESETS = {
    "tiny": Preset("tiny", road_length_m=36.0, curvature_per_m=1 / 400.0, sign_spacing_m=6.0,
                   gantry_every_m=1e9, image_spacing_m=5.0, pano_width=2048, points_per_line=1000,
                   lead_in_m=10.0, scenery_margin_m=25.0),
    "default": Preset("default", road_length_m=300.0, curvature_per_m=1 / 900.0,
                      sign_spacing_m=8.5, gantry_every_m=150.0),
    "large": Preset("large", road_length_m=2000.0, curvature_per_m=1 / 2500.0,
                    sign_spacing_m=9.0, gantry_every_m=300.0, speed_mps=8.0),
    # Drives of the size of Balado et al. 2020's seed-004 (9.2 km, 350 M points, 7,392
    # panoramas), for bench/bench_drive.py (devtools/scenegen/drive.py renders only a first
    # stretch of their panoramas). One sign group every ~20 m (the test presets: ~9 m);
    # 6.5 m/s with 250 lines of 1500 rays gives ~38,000 points per metre (~350 M on 9.2 km);
    # one panorama every 1.2447 m gives 7,392 on 9.2 km.
    "drive9k": Preset("drive9k", road_length_m=9200.0, curvature_per_m=1 / 6000.0,
                      sign_spacing_m=20.0, gantry_every_m=1500.0, image_spacing_m=1.2447,
                      speed_mps=6.5),
    "drive1k": Preset("drive1k", road_length_m=1000.0, curvature_per_m=1 / 6000.0,
                      sign_spacing_m=20.0, gantry_every_m=1500.0, image_spacing_m=1.2447,
                      speed_mps=6.5),
    # the smoke check of bench_drive.py: the same kind of drive, short, sparse panoramas
    "drivesmoke": Preset("drivesmoke", road_length_m=150.0, curvature_per_m=1 / 6000.0,
                         sign_spacing_m=20.0, gantry_every_m=1500.0, image_spacing_m=5.0,
                         pano_width=2048, speed_mps=8.0, points_per_line=1000),
}


def get_preset(name: str, **overrides) -> Preset:
    """The named preset with some fields replaced (``None`` values are ignored)."""
    if name not in PRESETS:
        raise ValueError(f"unknown preset {name!r}; choose one of {sorted(PRESETS)}")
    return replace(PRESETS[name], **{k: v for k, v in overrides.items() if v is not None})
