"""roadsigns:importtrajectory through qgis_process: every input kind, and bad input."""
import os

import numpy as np
import pytest
from helpers.contract import angle_between_deg, expected_stations, quat_to_matrix
from osgeo import ogr

ALG = "roadsigns:importtrajectory"
FIELDS = ["station_id", "image", "path", "time", "x", "y", "z", "qw", "qx", "qy", "qz", "heading",
          "width", "height"]
MOUNT = dict(LEVER_ARM_X=0.4, LEVER_ARM_Y=-0.1, LEVER_ARM_Z=-1.8, BORESIGHT_ROLL=0.3,
             BORESIGHT_PITCH=-0.5, BORESIGHT_YAW=1.2)


def read_stations(path):
    ds = ogr.Open(path)
    layer = ds.GetLayer(0)
    definition = layer.GetLayerDefn()
    names = [definition.GetFieldDefn(i).GetName() for i in range(definition.GetFieldCount())]
    rows = []
    for feature in layer:
        geometry = feature.GetGeometryRef()
        row = {n: feature.GetField(n) for n in names}
        row["geometry"] = (geometry.GetX(), geometry.GetY(), geometry.GetZ())
        row["geometry_type"] = ogr.GeometryTypeToName(geometry.GetGeometryType())
        rows.append(row)
    epsg = layer.GetSpatialRef().GetAuthorityCode(None)
    return names, rows, epsg


def check_output(path, sample, with_time=True):
    names, rows, epsg = read_stations(path)
    assert names == FIELDS
    assert epsg == "32633"
    assert [r["image"] for r in rows] == sample["names"]
    assert [r["station_id"] for r in rows] == list(range(1, len(rows) + 1))
    assert all(r["geometry_type"] == "3D Point" for r in rows)
    assert all(os.path.samefile(r["path"], os.path.join(sample["images"], r["image"])) for r in rows)
    assert all((r["width"], r["height"]) == (64, 32) for r in rows)
    centres, rotations = expected_stations(
        sample["drive"], sample["times"], (MOUNT["LEVER_ARM_X"], MOUNT["LEVER_ARM_Y"], MOUNT["LEVER_ARM_Z"]),
        (MOUNT["BORESIGHT_ROLL"], MOUNT["BORESIGHT_PITCH"], MOUNT["BORESIGHT_YAW"]))
    xyz = np.array([[r["x"], r["y"], r["z"]] for r in rows])
    assert np.abs(xyz - centres).max() < 1e-3
    assert np.abs(np.array([r["geometry"] for r in rows]) - centres).max() < 1e-3
    R = np.array([quat_to_matrix([r["qw"], r["qx"], r["qy"], r["qz"]]) for r in rows])
    assert angle_between_deg(R, rotations).max() < 1e-3
    heading = np.degrees(np.arctan2(rotations[:, 0, 0], rotations[:, 1, 0])) % 360
    assert np.abs((np.array([r["heading"] for r in rows]) - heading + 180) % 360 - 180).max() < 1e-3
    assert all(0 <= r["heading"] < 360 for r in rows)
    if with_time:
        assert np.allclose([r["time"] for r in rows], sample["times"], atol=1e-6)


def test_projected_trajectory_csv(qgis_process, drive_projected, tmp_path):
    out = str(tmp_path / "stations.gpkg")
    run = qgis_process.run(ALG, TRAJECTORY=drive_projected["trajectory_csv"],
                           IMAGE_TIMES=drive_projected["image_times"], IMAGES=drive_projected["images"],
                           TRAJECTORY_CRS="EPSG:32633", TARGET_CRS="EPSG:32633", OUTPUT=out, **MOUNT)
    assert run.returncode == 0, run.text
    assert run.json["results"]["OUTPUT"] == out
    check_output(out, drive_projected)


def test_geographic_trajectory_csv(qgis_process, drive_geographic, tmp_path):
    out = str(tmp_path / "stations.gpkg")
    run = qgis_process.run(ALG, TRAJECTORY=drive_geographic["trajectory_csv"],
                           IMAGE_TIMES=drive_geographic["image_times"], IMAGES=drive_geographic["images"],
                           TRAJECTORY_CRS="EPSG:4326", TARGET_CRS="EPSG:32633", OUTPUT=out, **MOUNT)
    assert run.returncode == 0, run.text
    check_output(out, drive_geographic)


def test_sbet(qgis_process, drive_projected, tmp_path):
    out = str(tmp_path / "stations.gpkg")
    run = qgis_process.run(ALG, TRAJECTORY=drive_projected["sbet"], IMAGE_TIMES=drive_projected["image_times"],
                           IMAGES=drive_projected["images"], TARGET_CRS="EPSG:32633", OUTPUT=out, **MOUNT)
    assert run.returncode == 0, run.text
    assert any("SBET" in line for line in run.json["log"]["info"])
    check_output(out, drive_projected)


def test_per_image_poses_without_target_crs(qgis_process, drive_geographic, tmp_path):
    out = str(tmp_path / "stations.gpkg")
    run = qgis_process.run(ALG, POSES=drive_geographic["poses"], IMAGES=drive_geographic["images"],
                           TRAJECTORY_CRS="EPSG:4326", OUTPUT=out, **MOUNT)
    assert run.returncode == 0, run.text
    assert any("UTM zone 33N" in line for line in run.json["log"]["info"])
    check_output(out, drive_geographic)


# --- bad input: non-zero exit, a message naming what is wrong, no output ---------------------

def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def head(path, n):
    with open(path) as f:
        return [f.readline().rstrip("\n") for _ in range(n)]


def bad_cases(sample, tmp_path):
    lines = head(sample["trajectory_csv"], 6)
    nan_row = lines[3].split(",")
    nan_row[2] = "nan"
    dup_row = lines[4].split(",")
    dup_row[0] = lines[3].split(",")[0]
    cut_sbet = tmp_path / "cut.out"
    cut_sbet.write_bytes(open(sample["sbet"], "rb").read()[:1000])
    wide = tmp_path / "wide"
    wide.mkdir()
    from PIL import Image
    Image.new("RGB", (90, 30)).save(wide / "w.jpg")
    t0 = sample["times"][0]
    return {
        "empty": (dict(TRAJECTORY=write(tmp_path, "empty.csv", "")), ["empty.csv", "is empty"]),
        "missing columns": (dict(TRAJECTORY=write(tmp_path, "cols.csv", "time;x;y;z\n1;2;3;4\n")),
                            ["missing column(s) roll, pitch, heading", "found time, x, y, z"]),
        "nan": (dict(TRAJECTORY=write(tmp_path, "nan.csv", "\n".join(lines[:3] + [",".join(nan_row)]))),
                ["nan.csv, line 4, field 'y'", "finite number"]),
        "duplicate time": (dict(TRAJECTORY=write(tmp_path, "dup.csv", "\n".join(lines[:4] + [",".join(dup_row)]))),
                           ["dup.csv, line 5", "duplicated"]),
        "outside span": (dict(IMAGE_TIMES=write(tmp_path, "late.csv", "image,time\npano_0000.jpg,99999\n")),
                         ["late.csv, line 2", "outside the trajectory's span"]),
        "missing image": (dict(IMAGE_TIMES=write(tmp_path, "gone.csv", "image,time\ngone.jpg,{}\n".format(t0)),
                               FAIL_ON_MISSING_IMAGE=True), ["gone.jpg"]),
        "not 2:1": (dict(IMAGE_TIMES=write(tmp_path, "w.csv", "image,time\nw.jpg,{}\n".format(t0)),
                         IMAGES=str(wide)), ["w.jpg is 90 x 30 pixels", "twice as wide"]),
        "sbet size": (dict(TRAJECTORY=str(cut_sbet)), ["cut.out", "not a multiple of 136 bytes"]),
        "unknown crs": (dict(TARGET_CRS="EPSG:4326"), ["is not projected"]),
        "no trajectory": (dict(TRAJECTORY=""), ["A trajectory file and an image times file are needed"]),
    }


@pytest.mark.parametrize("case", ["empty", "missing columns", "nan", "duplicate time", "outside span",
                                  "missing image", "not 2:1", "sbet size", "unknown crs",
                                  "no trajectory"])
def test_bad_input(qgis_process, drive_projected, tmp_path, case):
    overrides, messages = bad_cases(drive_projected, tmp_path)[case]
    parameters = dict(TRAJECTORY=drive_projected["trajectory_csv"], IMAGE_TIMES=drive_projected["image_times"],
                      IMAGES=drive_projected["images"], TRAJECTORY_CRS="EPSG:32633",
                      TARGET_CRS="EPSG:32633", OUTPUT=str(tmp_path / "out.gpkg"))
    parameters.update(overrides)
    parameters = {k: v for k, v in parameters.items() if v != ""}
    run = qgis_process.run(ALG, **parameters)
    assert run.returncode != 0
    for message in messages:
        assert message in run.text, run.text
    assert not os.path.exists(tmp_path / "out.gpkg")


def test_skips_are_logged(qgis_process, drive_projected, tmp_path):
    times = write(tmp_path, "t.csv", "image,time\ngone.jpg,{}\npano_0001.jpg,{}\nlate.jpg,99999\n".format(
        drive_projected["times"][0], drive_projected["times"][1]))
    out = str(tmp_path / "out.gpkg")
    run = qgis_process.run(ALG, TRAJECTORY=drive_projected["trajectory_csv"], IMAGE_TIMES=times,
                           IMAGES=drive_projected["images"], TRAJECTORY_CRS="EPSG:32633",
                           TARGET_CRS="EPSG:32633", SKIP_OUTSIDE=True, OUTPUT=out)
    assert run.returncode == 0, run.text
    log = run.json["log"]
    warnings = " ".join(log.get("warning", []) + log.get("info", []))
    assert "Skipped 1 image(s)" in warnings and "Skipped 1 panorama(s)" in warnings
    _, rows, _ = read_stations(out)
    assert [r["image"] for r in rows] == ["pano_0001.jpg"]
