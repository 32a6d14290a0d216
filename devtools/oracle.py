"""Detections made from a generated scene's true boxes (a perfect detector), to measure the
cloud stages apart from the detector.

Reads the stations layer written by ``roadsigns:importtrajectory`` and the scene's
``scene.json`` (per image, each visible sign panel's box), and writes a detections layer
with the contract's fields (LineStringZ rays from the panorama centre through the box
centre). Only front faces at least ``min_box_px`` high and at most ``max_occlusion``
hidden are kept, as a good detector would see them.

    python -m devtools.oracle --scene DIR --stations stations.gpkg --out detections.gpkg
"""
from __future__ import annotations

import argparse
import json
import os

import numpy as np

from . import import_roadsigns

FIELDS = [("det_id", "int"), ("station_id", "int"), ("image", "str"), ("class", "str"),
          ("score", "float"), ("u0", "float"), ("v0", "float"), ("u1", "float"), ("v1", "float"),
          ("n_views", "int"), ("time", "float"), ("x", "float"), ("y", "float"), ("z", "float"),
          ("qw", "float"), ("qx", "float"), ("qy", "float"), ("qz", "float"), ("heading", "float"),
          ("width", "int"), ("height", "int")]


def oracle_detections(scene_dir: str, stations_path: str, out_path: str, min_box_px: float = 12.0,
                      max_occlusion: float = 0.5, ray_length_m: float = 50.0) -> int:
    """Write the oracle detections layer; returns the number of detections."""
    from osgeo import ogr, osr
    geometry = import_roadsigns("roadsigns.core.geometry")
    with open(os.path.join(scene_dir, "scene.json")) as f:
        scene = json.load(f)
    sign_class = {s["sign_id"]: s["class"] for s in scene["signs"]}
    boxes_by_image = {im["image"]: im["signs"] for im in scene["images"]}

    stations_ds = ogr.Open(stations_path)
    stations = stations_ds.GetLayer(0)
    srs = stations.GetSpatialRef()
    if os.path.exists(out_path):
        os.remove(out_path)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(out_path)
    layer = ds.CreateLayer("detections", srs.Clone() if srs else osr.SpatialReference(), ogr.wkbLineString25D)
    kinds = {"int": ogr.OFTInteger, "str": ogr.OFTString, "float": ogr.OFTReal}
    for name, kind in FIELDS:
        layer.CreateField(ogr.FieldDefn(name, kinds[kind]))
    det_id = 0
    for station in stations:
        q = np.array([station["qw"], station["qx"], station["qy"], station["qz"]], float)
        centre = np.array([station["x"], station["y"], station["z"]], float)
        for seen in boxes_by_image.get(station["image"], []):
            if seen["facing"] != "front" or not seen.get("visible_box") or seen["occlusion"] > max_occlusion:
                continue
            u0, v0, u1, v1 = (float(c) for c in seen["visible_box"])
            if v1 - v0 < min_box_px:
                continue
            det_id += 1
            ray = geometry.box_centre_ray_world(u0, v0, u1, v1, station["width"], station["height"], q)
            values = {"det_id": det_id, "station_id": station["station_id"], "image": station["image"],
                      "class": sign_class[seen["sign_id"]], "score": 1.0, "u0": u0, "v0": v0,
                      "u1": u1, "v1": v1, "n_views": 1}
            feature = ogr.Feature(layer.GetLayerDefn())
            for name, _ in FIELDS:
                value = values[name] if name in values else station[name]
                if value is not None:
                    feature.SetField(name, value)
            line = ogr.Geometry(ogr.wkbLineString25D)
            line.AddPoint(*centre)
            line.AddPoint(*(centre + ray_length_m * ray))
            feature.SetGeometry(line)
            layer.CreateFeature(feature)
    ds = None
    return det_id


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", required=True)
    parser.add_argument("--stations", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--min-box-px", type=float, default=12.0)
    args = parser.parse_args(argv)
    print(oracle_detections(args.scene, args.stations, args.out, args.min_box_px), "detections")


if __name__ == "__main__":
    main()
