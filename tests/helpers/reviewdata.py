"""A small reviewed drive for the review panel and handover tests: a straight drive due east
in EPSG:32633 (east of the central meridian, so grid and true north differ by ~1.8 deg),
13 panorama stations 5 m apart, five signs beside it, their review chips and, on request,
1024 x 512 panoramas with a coloured disc where each sign is (seen from each station).

Written with OGR and OpenCV, without QGIS; positions and the expected values are plain
numbers here, independent of ``roadsigns.core``.
"""
import math
import os

import numpy as np

from helpers.badinputs import point_z, write_layer
from helpers.synthpano import paint_discs

EPSG = 32633
X0, Y0, Z0 = 680000.0, 5320000.0, 300.0
CAMERA_Z = 2.4
STATION_STEP_M, N_STATIONS = 5.0, 13
T0 = 388800.0          # GPS seconds of the week (Thursday 12:00)
PANO_W = 1024
#: sign_id -> (class, dx east, dy north, height of the centre, azimuth (grid), code, colour BGR)
SIGNS = {
    1: ("prohibitory", 15.0, -5.0, 2.5, 270.0, "206", (0, 0, 255)),
    2: ("warning", 25.0, -5.5, 2.4, 270.0, None, (0, 200, 255)),
    3: ("mandatory", 35.0, 6.0, 2.6, 90.0, None, (255, 80, 0)),
    4: ("stop", 45.0, -5.0, 2.2, 270.0, None, (0, 0, 160)),
    5: ("information", 55.0, -0.4, 5.5, 270.0, "C3", (255, 255, 255)),   # over the road, on a gantry
}
SIGN_SCHEMA = [("sign_id", int), ("class", str), ("score", float), ("height", float), ("bottom_height", float),
               ("width", float), ("panel_height", float), ("azimuth", float), ("n_views", int), ("n_points", int),
               ("source_images", str), ("best_image", str), ("mean_intensity", float), ("planarity", float),
               ("position_source", str), ("x", float), ("y", float), ("z", float), ("chip", str), ("code", str),
               ("condition", str)]
REVIEW_SCHEMA = [("review_status", str), ("reviewed_class", str), ("reviewed_code", str), ("reviewed_at", str)]
STATION_SCHEMA = [("station_id", int), ("image", str), ("path", str), ("time", float), ("x", float), ("y", float),
                  ("z", float), ("qw", float), ("qx", float), ("qy", float), ("qz", float), ("heading", float),
                  ("width", int), ("height", int)]


def image_name(k):
    return "p{:02d}.jpg".format(k)


def stations(images_dir):
    """Station records: panorama forward = east, right = south (quaternion (0, 1, 0, 0))."""
    return [dict(station_id=k + 1, image=image_name(k), path=os.path.join(images_dir, image_name(k)),
                 time=T0 + 0.5 * k, x=X0 + STATION_STEP_M * k, y=Y0, z=Z0 + CAMERA_Z, qw=0.0, qx=1.0, qy=0.0,
                 qz=0.0, heading=90.0, width=PANO_W, height=PANO_W // 2) for k in range(N_STATIONS)]


def seen_from(dx):
    """The stations (indices) 4 to 20 m before a sign at ``dx`` along the drive."""
    return [k for k in range(N_STATIONS) if 4.0 <= dx - STATION_STEP_M * k <= 20.0]


def sign_records(review=None):
    """Sign layer records; ``review``: sign_id -> (status, class, code, at)."""
    out = []
    for sign_id, (klass, dx, dy, height, azimuth, code, _) in SIGNS.items():
        seen = seen_from(dx) or [N_STATIONS - 1]
        record = dict(sign_id=sign_id, score=0.8 + 0.03 * sign_id, height=height, bottom_height=height - 0.3,
                      width=0.6, panel_height=0.6, azimuth=azimuth, n_views=len(seen), n_points=120,
                      source_images=";".join(image_name(k) for k in seen), best_image=image_name(seen[-1]),
                      mean_intensity=30000.0, planarity=0.97, position_source="lidar", x=X0 + dx, y=Y0 + dy,
                      z=Z0 + height, chip="signs_chips/sign_{}.jpg".format(sign_id) if sign_id <= 3 else None,
                      code=code, condition="good" if sign_id != 2 else "poor")
        record["class"] = klass
        if review and sign_id in review:
            record.update(zip(("review_status", "reviewed_class", "reviewed_code", "reviewed_at"), review[sign_id]))
        out.append(record)
    return out


def _paint_panoramas(folder):
    for station in stations(folder):
        discs = []
        for klass, dx, dy, height, azimuth, code, colour in SIGNS.values():
            east, north, up = X0 + dx - station["x"], Y0 + dy - station["y"], Z0 + height - station["z"]
            rng = math.sqrt(east ** 2 + north ** 2 + up ** 2)
            # panorama frame: x forward = east, y right = south, z down
            az, el = math.degrees(math.atan2(-north, east)), math.degrees(math.atan2(up, math.hypot(east, north)))
            discs.append((az, el, math.degrees(math.atan2(0.3, rng)), colour))
        import cv2
        cv2.imwrite(station["path"], paint_discs(discs, PANO_W), [cv2.IMWRITE_JPEG_QUALITY, 92])


def _write_chips(folder):
    import cv2
    os.makedirs(os.path.join(folder, "signs_chips"), exist_ok=True)
    for sign_id, spec in SIGNS.items():
        if sign_id <= 3:
            chip = np.full((256, 256, 3), 120, np.uint8)
            cv2.circle(chip, (128, 128), 70, spec[6], -1)
            cv2.imwrite(os.path.join(folder, "signs_chips", "sign_{}.jpg".format(sign_id)), chip)


def build(folder, panoramas=True, review=None):
    """Write ``signs.gpkg`` (+ chips), ``stations.gpkg``, ``images/`` (with ``panoramas``) and
    ``bare.gpkg`` (a point layer with only a class field) into ``folder``."""
    os.makedirs(folder, exist_ok=True)
    images = os.path.join(folder, "images")
    os.makedirs(images, exist_ok=True)
    if panoramas:
        _paint_panoramas(images)
    _write_chips(folder)
    schema = SIGN_SCHEMA + (REVIEW_SCHEMA if review else [])
    paths = dict(folder=folder, images=images,
                 signs=write_layer(os.path.join(folder, "signs.gpkg"), schema, sign_records(review), point_z, EPSG,
                                   _ogr_point_z()),
                 stations=write_layer(os.path.join(folder, "stations.gpkg"), STATION_SCHEMA, stations(images),
                                      point_z, EPSG, _ogr_point_z()),
                 bare=write_layer(os.path.join(folder, "bare.gpkg"), [("class", str)], [{"class": "stop", "x": X0,
                                                                                      "y": Y0, "z": Z0}],
                                  point_z, EPSG, _ogr_point_z()))
    return paths


def _ogr_point_z():
    from osgeo import ogr
    return ogr.wkbPoint25D
