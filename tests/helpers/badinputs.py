"""Inputs for the bad-input table (tests/qgis/test_bad_inputs.py): small good inputs for every
algorithm and, beside them, the bad ones, all written into one folder by :func:`build`.

Everything is tiny so that the whole table runs in well under two minutes: a 12 s analytic
drive with 64 x 32 panoramas (devtools/trajsample.py), a sign scene cut to its first 50 m
(helpers/signscene.py) with a handful of detections, a 20 m road cloud (helpers/cloudgen.py)
and a one-box ONNX "detector" (helpers/tinyonnx.py). Layers are written with OGR, without
QGIS; core is used only to make the good stations and candidates.
"""
from __future__ import annotations

import os
import struct
import zlib

import numpy as np

from devtools import trajsample

CLOUD_EPSG = 25833
PANO_W, PANO_H = 4096, 2048


# --- files -------------------------------------------------------------------------------

def write_text(folder, name, text, encoding="utf-8"):
    path = os.path.join(folder, name)
    with open(path, "w", encoding=encoding, newline="") as f:
        f.write(text)
    return path


def write_bytes(folder, name, data):
    path = os.path.join(folder, name)
    with open(path, "wb") as f:
        f.write(data)
    return path


def png_header(width, height):
    """A PNG whose header claims ``width`` x ``height`` pixels (a 1 x 1 image inside): Pillow
    reads the size from the header only, as the trajectory import does."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    idat = zlib.compress(b"\x00\x00\x00\x00")
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")


# --- layers (OGR) ------------------------------------------------------------------------

OGR_KINDS = {int: "OFTInteger", float: "OFTReal", str: "OFTString"}


def write_layer(path, fields, rows, geometry, epsg, kind, null_geometry=False):
    """A GeoPackage layer: ``fields`` (name, python kind), ``rows`` dicts (None = NULL),
    ``geometry(row)`` -> WKT (or None), in EPSG ``epsg`` (None: no CRS)."""
    from osgeo import ogr, osr

    if os.path.exists(path):
        os.remove(path)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    srs = None
    if epsg is not None:
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(epsg)
        srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    layer = ds.CreateLayer(os.path.splitext(os.path.basename(path))[0], srs, kind)
    for name, python_kind in fields:
        layer.CreateField(ogr.FieldDefn(name, getattr(ogr, OGR_KINDS[python_kind])))
    for row in rows:
        feature = ogr.Feature(layer.GetLayerDefn())
        for name, _ in fields:
            if row.get(name) is None:
                feature.SetFieldNull(name)
            else:
                feature.SetField(name, row[name])
        wkt = None if null_geometry else geometry(row)
        if wkt:
            feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(feature)
    ds = None
    return path


def point_z(row):
    return "POINT Z ({} {} {})".format(row["x"], row["y"], row["z"])


def ray_z(length_m=20.0):
    def wkt(row):
        return "LINESTRING Z ({x} {y} {z}, {x2} {y} {z})".format(
            x=row["x"], y=row["y"], z=row["z"], x2=row["x"] + length_m)
    return wkt


def schema_fields(schema):
    return [(f.name, f.kind) for f in schema]


# --- the inputs ---------------------------------------------------------------------------

def build(folder):
    """Write every input into ``folder``; returns {name: path}."""
    from osgeo import ogr

    from helpers import cloudgen, signscene
    from helpers.tinyonnx import make_model
    from roadsigns.core.detections import DETECTION_FIELDS, Detections
    from roadsigns.core.projection import CANDIDATE_FIELDS, project_detections
    from roadsigns.core.trajectory import STATION_FIELDS, import_stations

    os.makedirs(folder, exist_ok=True)
    d = {}

    # --- trajectory, image times, poses, panoramas
    drive = trajsample.make_sample(os.path.join(folder, "drive"))
    geo = trajsample.make_sample(os.path.join(folder, "drive_geo"), crs="geographic")
    d.update(trajectory=drive["trajectory_csv"], sbet=drive["sbet"], image_times=drive["image_times"],
             poses=drive["poses"], images=drive["images"], trajectory_lonlat=geo["trajectory_csv"],
             poses_lonlat=geo["poses"])
    with open(drive["trajectory_csv"]) as f:
        lines = f.read().splitlines()
    t0 = drive["times"][0]
    d["traj_empty"] = write_text(folder, "traj_empty.csv", "")
    d["traj_header_only"] = write_text(folder, "traj_header_only.csv", lines[0] + "\n")
    d["traj_columns"] = write_text(folder, "traj_columns.csv", "time;x;y;z\n1;2;3;4\n")
    nan_row = lines[3].split(",")
    nan_row[2] = "nan"
    d["traj_nan"] = write_text(folder, "traj_nan.csv", "\n".join(lines[:3] + [",".join(nan_row)] + lines[4:]))
    dup_row = lines[4].split(",")
    dup_row[0] = lines[3].split(",")[0]
    d["traj_dup"] = write_text(folder, "traj_dup.csv", "\n".join(lines[:4] + [",".join(dup_row)] + lines[5:]))
    # decimal commas in a comma-separated file: every row has more fields than the header
    decimal = [lines[0]] + [line.replace(".", ",", 1) for line in lines[1:]]
    d["traj_decimal_commas"] = write_text(folder, "traj_decimal_commas.csv", "\n".join(decimal))
    # decimal commas with a semicolon delimiter: fields that are not numbers
    semi = [lines[0].replace(",", ";")] + [line.replace(",", ";").replace(".", ",") for line in lines[1:]]
    d["traj_semicolon_decimal"] = write_text(folder, "traj_semicolon_decimal.csv", "\n".join(semi))
    d["traj_binary"] = write_bytes(folder, "traj_binary.csv", bytes(range(256)) * 8)
    d["traj_utf16"] = write_text(folder, "traj_utf16.csv", "\n".join(lines[:50]), encoding="utf-16")
    d["times_late"] = write_text(folder, "times_late.csv", "image,time\npano_0000.jpg,99999\n")
    d["times_gone"] = write_text(folder, "times_gone.csv", "image,time\ngone.jpg,{}\n".format(t0))
    d["times_dup"] = write_text(folder, "times_dup.csv", "image,time\npano_0000.jpg,{0}\npano_0000.jpg,{1}\n"
                                .format(t0, drive["times"][1]))
    # decimal commas in an image times file: "1000,513" is two fields
    d["times_extra"] = write_text(folder, "times_extra.csv", "image,time\npano_0000.jpg,{}\npano_0001.jpg,{}\n"
                                  .format(t0, "{:.3f}".format(drive["times"][1]).replace(".", ",")))
    with open(drive["poses"]) as f:
        pose_lines = f.read().splitlines()
    d["poses_extra"] = write_text(folder, "poses_extra.csv", "\n".join(
        pose_lines[:2] + [pose_lines[2] + ",0,5"] + pose_lines[3:]))
    wide = os.path.join(folder, "wide")
    os.makedirs(wide, exist_ok=True)
    from PIL import Image
    Image.new("RGB", (90, 30)).save(os.path.join(wide, "w.jpg"))
    d["wide_images"] = wide
    d["times_wide"] = write_text(folder, "times_wide.csv", "image,time\nw.jpg,{}\n".format(t0))
    # panoramas whose headers claim 30000 x 15000 (450 Mpx: legitimate) and 70000 x 35000 pixels
    big = os.path.join(folder, "big")
    os.makedirs(big, exist_ok=True)
    write_bytes(big, "pano_0000.png", png_header(30000, 15000))
    write_bytes(big, "pano_0001.png", png_header(70000, 35000))
    d["big_images"] = big
    d["times_big_ok"] = write_text(folder, "times_big_ok.csv", "image,time\npano_0000.png,{}\n".format(t0))
    d["times_big_bad"] = write_text(folder, "times_big_bad.csv", "image,time\npano_0001.png,{}\n".format(t0))
    sbet = open(drive["sbet"], "rb").read()
    d["sbet_cut"] = write_bytes(folder, "sbet_cut.out", sbet[:1000])
    d["sbet_garbage"] = write_bytes(folder, "sbet_garbage.out",
                                    np.random.default_rng(1).uniform(-1e6, 1e6, 17 * 50).astype("<f8").tobytes())

    # --- stations (core import, written with OGR)
    result = import_stations(drive["images"], "EPSG:32633", "EPSG:32633", drive["trajectory_csv"],
                             drive["image_times"])
    stations = result.stations.records()[:2]
    fields = schema_fields(STATION_FIELDS)
    d["stations"] = write_layer(os.path.join(folder, "stations.gpkg"), fields, stations, point_z, 32633,
                                ogr.wkbPoint25D)
    null_width = [dict(r) for r in stations]
    null_width[0]["width"] = None
    d["stations_null_width"] = write_layer(os.path.join(folder, "stations_null_width.gpkg"), fields,
                                           null_width, point_z, 32633, ogr.wkbPoint25D)
    d["stations_all_null"] = write_layer(os.path.join(folder, "stations_all_null.gpkg"), fields,
                                         [{} for _ in stations], point_z, 32633, ogr.wkbPoint25D,
                                         null_geometry=True)
    d["stations_empty"] = write_layer(os.path.join(folder, "stations_empty.gpkg"), fields, [], point_z,
                                      32633, ogr.wkbPoint25D)
    d["stations_no_pose"] = write_layer(os.path.join(folder, "stations_no_pose.gpkg"), fields[:3],
                                        stations, point_z, 32633, ogr.wkbPoint25D)
    lonlat = [dict(r, x=17.5 + 0.0001 * k, y=48.0, z=230.0) for k, r in enumerate(stations)]
    d["stations_4326"] = write_layer(os.path.join(folder, "stations_4326.gpkg"), fields, lonlat, point_z,
                                     4326, ogr.wkbPoint25D)
    # a one-box detector: [1, 4 + 1, 1] (YOLOv8 layout), class 'stop'
    d["model"] = make_model(os.path.join(folder, "tiny.onnx"),
                            np.array([[32.0, 32.0, 20.0, 20.0, 0.9]], np.float32).T[None],
                            meta={"names": "{0: 'stop'}"})
    d["model_text"] = write_text(folder, "not_a_model.onnx", "this is not an ONNX model\n")
    d["labels_empty"] = write_text(folder, "labels_empty.txt", "\n \n")

    # --- a sign scene: cloud, detections, candidates, panoramas for the review chips
    panels = [p for p in signscene.default_panels() if p.sign_id in (1, 9)]
    scene = signscene.make_scene(seed=5, panels=panels, road_length_m=40.0, ground_density=8.0,
                                 stations_x=np.arange(0.0, 30.0, 5.0))
    cloud = os.path.join(folder, "cloud.laz")
    signscene.write_las(scene, cloud)
    d["cloud"] = cloud
    d["cloud_nocrs"] = _las_without_crs(cloud, os.path.join(folder, "cloud_nocrs.laz"))
    raw = open(cloud, "rb").read()
    d["cloud_truncated"] = write_bytes(folder, "cloud_truncated.laz", raw[: len(raw) * 2 // 3])
    flipped = bytearray(raw)
    start = len(raw) // 2
    for k in range(start, start + 64):
        flipped[k] ^= 0xFF
    d["cloud_flipped"] = write_bytes(folder, "cloud_flipped.laz", bytes(flipped))
    d["cloud_text"] = write_text(folder, "cloud_text.laz", "x,y,z\n1,2,3\n")
    det_rows = []
    for r in scene.detections:
        row = {f.name: r.get(f.name) for f in DETECTION_FIELDS}
        row.update(n_views=1, time=None, heading=90.0)
        det_rows.append(row)
    det_fields = schema_fields(DETECTION_FIELDS)
    d["detections"] = write_layer(os.path.join(folder, "detections.gpkg"), det_fields, det_rows, ray_z(),
                                  CLOUD_EPSG, ogr.wkbLineString25D)
    d["detections_4326"] = write_layer(os.path.join(folder, "detections_4326.gpkg"), det_fields, det_rows,
                                       ray_z(), 4326, ogr.wkbLineString25D)
    d["detections_other_crs"] = write_layer(os.path.join(folder, "detections_other_crs.gpkg"), det_fields,
                                            det_rows, ray_z(), 32633, ogr.wkbLineString25D)
    d["detections_empty"] = write_layer(os.path.join(folder, "detections_empty.gpkg"), det_fields, [],
                                        ray_z(), CLOUD_EPSG, ogr.wkbLineString25D)
    d["detections_all_null"] = write_layer(os.path.join(folder, "detections_all_null.gpkg"), det_fields,
                                           [{} for _ in det_rows[:3]], ray_z(), CLOUD_EPSG,
                                           ogr.wkbLineString25D, null_geometry=True)
    candidates = project_detections(Detections.from_records(det_rows), cloud, max_range_m=30.0).records()
    cand_fields = schema_fields(CANDIDATE_FIELDS)

    def cand_point(row):
        return None if row["status"] != "ok" else "POINT Z ({} {} {})".format(
            row["cand_x"], row["cand_y"], row["cand_z"])

    d["candidates"] = write_layer(os.path.join(folder, "candidates.gpkg"), cand_fields, candidates, cand_point,
                                  CLOUD_EPSG, ogr.wkbPoint25D)
    d["candidates_4326"] = write_layer(os.path.join(folder, "candidates_4326.gpkg"), cand_fields, candidates,
                                       cand_point, 4326, ogr.wkbPoint25D)
    d["candidates_empty"] = write_layer(os.path.join(folder, "candidates_empty.gpkg"), cand_fields, [],
                                        cand_point, CLOUD_EPSG, ogr.wkbPoint25D)
    d["candidates_all_null"] = write_layer(os.path.join(folder, "candidates_all_null.gpkg"), cand_fields,
                                           [{} for _ in candidates[:3]], cand_point, CLOUD_EPSG,
                                           ogr.wkbPoint25D, null_geometry=True)
    text_fields = [(n, str if n == "cand_x" else k) for n, k in cand_fields]
    d["candidates_text"] = write_layer(os.path.join(folder, "candidates_text.gpkg"), text_fields,
                                       [dict(r, cand_x="abc") for r in candidates], lambda r: None, CLOUD_EPSG,
                                       ogr.wkbPoint25D)
    status_null = [dict(r, status=None) for r in candidates]
    d["candidates_null_status"] = write_layer(os.path.join(folder, "candidates_null_status.gpkg"), cand_fields,
                                              status_null, cand_point, CLOUD_EPSG, ogr.wkbPoint25D)
    panoramas = os.path.join(folder, "panoramas")
    os.makedirs(panoramas, exist_ok=True)
    grey = Image.new("RGB", (PANO_W, PANO_H), (90, 90, 90))
    for name in sorted({r["image"] for r in det_rows}):
        grey.save(os.path.join(panoramas, name), "JPEG", quality=50)
    d["panoramas"] = panoramas

    # --- a road cloud for the ground filter, crop layers
    road = cloudgen.road_scene(length_m=20.0, density_per_m2=20.0, seed=3)
    d["road"] = os.path.join(folder, "road.laz")
    cloudgen.write_scene(d["road"], road, crs_epsg=CLOUD_EPSG)
    d["road_nocrs"] = os.path.join(folder, "road_nocrs.laz")
    cloudgen.write_scene(d["road_nocrs"], road, crs_epsg=None)
    x0, y0, _ = cloudgen.ORIGIN
    d["road_local"] = os.path.join(folder, "road_local.laz")  # local coordinates labelled EPSG:25833
    local = cloudgen.Scene(road.xyz - np.asarray(cloudgen.ORIGIN), *(getattr(road, a) for a in (
        "is_ground", "semantic", "return_number", "number_of_returns", "gps_time", "intensity")))
    cloudgen.write_scene(d["road_local"], local, crs_epsg=CLOUD_EPSG)

    def polygon(x_min, y_min, x_max, y_max):
        return "POLYGON (({0} {1}, {2} {1}, {2} {3}, {0} {3}, {0} {1}))".format(x_min, y_min, x_max, y_max)

    d["crop_empty"] = write_layer(os.path.join(folder, "crop_empty.gpkg"), [("id", int)], [], None,
                                  CLOUD_EPSG, ogr.wkbPolygon)
    d["crop_null_geometry"] = write_layer(os.path.join(folder, "crop_null_geometry.gpkg"), [("id", int)],
                                          [{"id": 1}], lambda r: None, CLOUD_EPSG, ogr.wkbPolygon)
    d["crop_far"] = write_layer(os.path.join(folder, "crop_far.gpkg"), [("id", int)], [{"id": 1}],
                                lambda r: polygon(x0 + 5000, y0 + 5000, x0 + 5010, y0 + 5010), CLOUD_EPSG,
                                ogr.wkbPolygon)
    d["crop_points"] = write_layer(os.path.join(folder, "crop_points.gpkg"), [("id", int)], [{"id": 1}],
                                   lambda r: "POINT ({} {})".format(x0 + 5, y0), CLOUD_EPSG, ogr.wkbPoint)
    d["crop"] = write_layer(os.path.join(folder, "crop.gpkg"), [("id", int)], [{"id": 1}],
                            lambda r: polygon(x0 + 2, y0 - 4, x0 + 12, y0 + 4), CLOUD_EPSG, ogr.wkbPolygon)

    # --- signs and reference for evaluate
    sign_fields = [("sign_id", str), ("class", str), ("height", float), ("azimuth", float), ("best_image", str)]
    signs = [dict(sign_id="s1", cls="stop", x=500000.03, y=5300000.04, z=102.0, height=2.0, azimuth=92.0),
             dict(sign_id="s2", cls="warning", x=500010.0, y=5300000.0, z=102.6, height=2.6, azimuth=2.0)]
    for s in signs:
        s["class"] = s.pop("cls")
        s["best_image"] = "pano_0001.jpg"
    d["signs"] = write_layer(os.path.join(folder, "signs.gpkg"), sign_fields, signs, point_z, 32633,
                             ogr.wkbPoint25D)
    lonlat_signs = [dict(s, x=15.0 + 0.0001 * k, y=47.84, z=102.0) for k, s in enumerate(signs)]
    d["signs_4326"] = write_layer(os.path.join(folder, "signs_4326.gpkg"), sign_fields, lonlat_signs, point_z,
                                  4326, ogr.wkbPoint25D)
    d["signs_empty"] = write_layer(os.path.join(folder, "signs_empty.gpkg"), sign_fields, [], point_z, 32633,
                                   ogr.wkbPoint25D)
    d["signs_no_class"] = write_layer(os.path.join(folder, "signs_no_class.gpkg"), sign_fields[:1], signs,
                                      point_z, 32633, ogr.wkbPoint25D)
    d["signs_all_null"] = write_layer(os.path.join(folder, "signs_all_null.gpkg"), sign_fields,
                                      [{} for _ in signs], point_z, 32633, ogr.wkbPoint25D, null_geometry=True)
    header = "sign_id,class,x,y,z,height,width,panel_height,azimuth\n"
    d["reference"] = write_text(folder, "reference.csv", header +
                                "r1,stop,500000,5300000,102.0,2.0,0.6,0.6,90\n"
                                "r2,warning,500010,5300000,102.5,2.5,0.9,0.8,358\n")
    d["reference_extra"] = write_text(folder, "reference_extra.csv", header +
                                      "r1,stop,500000,5300000,102.0,2.0,0.6,0.6,90\n"
                                      "r2,warning,500010,5300000,102,5,2.5,0.9,0.8,358\n")
    d["reference_dup"] = write_text(folder, "reference_dup.csv", header +
                                    "r1,stop,500000,5300000,102.0,2.0,0.6,0.6,90\n"
                                    "r1,warning,500010,5300000,102.5,2.5,0.9,0.8,358\n")
    d["reference_lonlat"] = write_text(folder, "reference_lonlat.csv", header +
                                       "r1,stop,15.0,47.84,102.0,2.0,0.6,0.6,90\n"
                                       "r2,warning,15.0001,47.84,102.5,2.5,0.9,0.8,358\n")
    d["reference_far"] = write_text(folder, "reference_far.csv", header +
                                    "r1,stop,600000,5200000,102.0,2.0,0.6,0.6,90\n")
    ref_fields = [("sign_id", str), ("class", str), ("height", float), ("width", float),
                  ("panel_height", float), ("azimuth", float)]
    d["reference_all_null"] = write_layer(os.path.join(folder, "reference_all_null.gpkg"), ref_fields,
                                          [{}, {}], point_z, 32633, ogr.wkbPoint25D, null_geometry=True)
    d["missing"] = os.path.join(folder, "does_not_exist.csv")
    d["not_a_folder"] = os.path.join(folder, "no_such_folder")
    return d


def _las_without_crs(source, target):
    """A copy of ``source`` with its CRS records removed."""
    import laspy

    las = laspy.read(source)
    las.header.vlrs = laspy.vlrs.vlrlist.VLRList(
        [v for v in las.header.vlrs if type(v).__name__ not in (
            "WktCoordinateSystemVlr", "GeoKeyDirectoryVlr", "GeoAsciiParamsVlr", "GeoDoubleParamsVlr")])
    las.header.global_encoding.wkt = False
    las.write(target)
    return target
