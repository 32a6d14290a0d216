"""roadsigns:detectsigns through qgis_process with tiny real ONNX models built in the test.

The model's output is a constant box at the centre of every view, so each panorama gives
one detection per view, whose ray must point at that view's centre; the rays are checked
against the contract's pixel -> ray formula written out in the test.
"""
import os
import shutil

import numpy as np
import pytest
from helpers.contract import quat_to_matrix
from helpers.tinyonnx import make_model
from osgeo import ogr

ALG = "roadsigns:detectsigns"
NAMES = "{0: 'stop', 1: 'yield'}"


def yolov8_centre_box(n_classes=2, size=64):
    out = np.zeros((1, 4 + n_classes, 1), np.float32)
    out[0, :4, 0] = [size / 2, size / 2, 10, 10]
    out[0, 4, 0] = 0.9
    return out


@pytest.fixture(scope="module")
def stations(qgis_process, drive_projected, tmp_path_factory):
    folder = tmp_path_factory.mktemp("det")
    images = folder / "images"
    shutil.copytree(drive_projected["images"], images)
    names = drive_projected["names"][:3]
    shutil.copy(images / drive_projected["names"][3], images / "broken.jpg")  # readable at import
    times = folder / "times.csv"
    times.write_text("image,time\n" + "".join("{},{}\n".format(n, t) for n, t in
                                              zip(names + ["broken.jpg"], drive_projected["times"][:4])))
    out = str(folder / "stations.gpkg")
    run = qgis_process.run("roadsigns:importtrajectory", TRAJECTORY=drive_projected["trajectory_csv"],
                           IMAGE_TIMES=str(times), IMAGES=str(images), TRAJECTORY_CRS="EPSG:32633",
                           TARGET_CRS="EPSG:32633", LEVER_ARM_Z=-2.0, OUTPUT=out)
    assert run.returncode == 0, run.text
    (images / "broken.jpg").write_bytes(b"\xff\xd8 not really a jpeg")  # corrupt after import
    return out


def read_rays(path):
    dataset = ogr.Open(path)
    layer = dataset.GetLayer(0)
    rows = []
    for feature in layer:
        g = feature.GetGeometryRef()
        row = {k: feature[k] for k in feature.keys()}
        row["points"] = np.array([g.GetPoint(i) for i in range(g.GetPointCount())])
        row["type"] = ogr.GeometryTypeToName(g.GetGeometryType())
        rows.append(row)
    return rows


def contract_ray_world(row):
    W, H = row["width"], row["height"]
    u = ((row["u0"] + row["u1"]) / 2) % W
    v = (row["v0"] + row["v1"]) / 2
    alpha, eps = 2 * np.pi * (u / W - 0.5), np.pi * (0.5 - v / H)
    d = np.array([np.cos(eps) * np.cos(alpha), np.cos(eps) * np.sin(alpha), -np.sin(eps)])
    return quat_to_matrix([row["qw"], row["qx"], row["qy"], row["qz"]]) @ d


def test_one_ray_per_view_along_the_box_centre(qgis_process, stations, tmp_path):
    model = make_model(tmp_path / "m.onnx", yolov8_centre_box(), meta={"names": NAMES})
    out = str(tmp_path / "detections.gpkg")
    run = qgis_process.run(ALG, STATIONS=stations, MODEL=model, CONFIDENCE=0.5, MAX_RANGE=30, MIN_SIZE=0,
                           UPWARD_VIEWS=True, RESCUE_CONFIDENCE=1.0, OUTPUT=out)   # no second look: every box
    assert run.returncode == 0, run.text
    assert run.json["results"]["SKIPPED_IMAGES"] == 1
    assert "broken.jpg" in run.text
    rows = read_rays(out)
    per_image = {}
    for r in rows:
        per_image.setdefault(r["image"], []).append(r)
    assert len(per_image) == 3
    assert all(len(v) == 10 for v in per_image.values())  # 8 horizon + 2 upward views
    assert run.json["results"]["DETECTIONS"] == len(rows) == 30
    for r in rows:
        assert r["class"] == "stop" and r["score"] == pytest.approx(0.9)
        assert r["type"] == "3D Line String"
        start, end = r["points"]
        assert start == pytest.approx([r["x"], r["y"], r["z"]])
        assert np.linalg.norm(end - start) == pytest.approx(30.0)
        assert (end - start) / 30.0 == pytest.approx(contract_ray_world(r), abs=1e-6)
    horizon = sorted(((r["u0"] + r["u1"]) / 2) % r["width"] for r in per_image["pano_0000.jpg"]
                     if (r["v0"] + r["v1"]) / 2 == pytest.approx(16, abs=0.5))
    assert horizon == pytest.approx(sorted((32 + k * 8) % 64 for k in range(8)), abs=0.2)


def test_a_ring_of_six_horizon_views_turned_by_thirty_degrees(qgis_process, stations, tmp_path):
    """HORIZON_VIEWS' second option: 6 horizon views at yaws 30 + 60 k, one ray each."""
    model = make_model(tmp_path / "m.onnx", yolov8_centre_box(), meta={"names": NAMES})
    out = str(tmp_path / "detections.gpkg")
    run = qgis_process.run(ALG, STATIONS=stations, MODEL=model, CONFIDENCE=0.5, MIN_SIZE=0, UPWARD_VIEWS=False,
                           FORE_AFT_VIEWS=False, HORIZON_VIEWS=1, RESCUE_CONFIDENCE=1.0, OUTPUT=out)
    assert run.returncode == 0, run.text
    assert "6 views each" in run.text
    rows = [r for r in read_rays(out) if r["image"] == "pano_0000.jpg"]
    centres_u = sorted(((r["u0"] + r["u1"]) / 2) % r["width"] for r in rows)
    # yaw 0 is the panorama's centre column (32 of 64); 60 deg is 64 / 6 columns
    assert centres_u == pytest.approx(sorted((32 + 64 * (30 + 60 * k) / 360) % 64 for k in range(6)), abs=0.2)
    for r in rows:
        start, end = r["points"]
        assert (end - start) / np.linalg.norm(end - start) == pytest.approx(contract_ray_world(r), abs=1e-6)


def test_the_horizon_as_one_band_needs_a_model_of_any_size_and_maps_its_box_linearly(qgis_process, stations,
                                                                                      tmp_path):
    """HORIZON_VIEWS' third option: the horizon as one band of 3264 x 448 px, run at its own
    size. The model's one box, at band pixel (32, 32), is azimuth 32 / 8.5 - 180 - 12 deg and
    elevation (224 - 32) / 8.5 deg: one detection a panorama, its ray there. A model whose
    input size is fixed is refused before any panorama is read, naming the model."""
    model = make_model(tmp_path / "any.onnx", yolov8_centre_box(), input_shape=["batch", 3, "h", "w"],
                       meta={"names": NAMES, "imgsz": "[64, 64]"})
    out = str(tmp_path / "detections.gpkg")
    run = qgis_process.run(ALG, STATIONS=stations, MODEL=model, CONFIDENCE=0.5, MIN_SIZE=0, UPWARD_VIEWS=False,
                           FORE_AFT_VIEWS=False, HORIZON_VIEWS=2, RESCUE_CONFIDENCE=1.0, OUTPUT=out)
    assert run.returncode == 0, run.text
    assert "1 views each" in run.text
    rows = read_rays(out)
    assert sorted(r["image"] for r in rows) == ["pano_0000.jpg", "pano_0001.jpg", "pano_0002.jpg"]
    density = 3264 / 384.0
    az_deg, el_deg = 32 / density - 192.0, (224 - 32) / density
    for r in rows:
        W, H = r["width"], r["height"]
        assert ((r["u0"] + r["u1"]) / 2) % W == pytest.approx(((az_deg / 360.0 + 0.5) * W) % W, abs=0.05)
        assert (r["v0"] + r["v1"]) / 2 == pytest.approx((0.5 - el_deg / 180.0) * H, abs=0.05)
        start, end = r["points"]
        assert (end - start) / np.linalg.norm(end - start) == pytest.approx(contract_ray_world(r), abs=1e-6)
    fixed = make_model(tmp_path / "fixed.onnx", yolov8_centre_box(), meta={"names": NAMES})
    refused = str(tmp_path / "refused.gpkg")
    run = qgis_process.run(ALG, STATIONS=stations, MODEL=fixed, UPWARD_VIEWS=False, HORIZON_VIEWS=2, OUTPUT=refused)
    assert run.returncode != 0
    assert "fixed.onnx takes 64 x 64 px images only; the horizon seen as one band (3264 x 448 px)" in run.text
    assert not os.path.exists(refused)


def test_names_from_a_labels_file(qgis_process, stations, tmp_path):
    model = make_model(tmp_path / "m.onnx", yolov8_centre_box())
    labels = tmp_path / "names.txt"
    labels.write_text("warning\nmandatory\n")
    out = str(tmp_path / "d.gpkg")
    run = qgis_process.run(ALG, STATIONS=stations, MODEL=model, LABELS=str(labels), UPWARD_VIEWS=False,
                           MIN_SIZE=0, OUTPUT=out)
    assert run.returncode == 0, run.text
    rows = read_rays(out)
    assert len(rows) == 3 * 8 and {r["class"] for r in rows} == {"warning"}


def test_boxes_under_min_size_are_dropped(qgis_process, stations, tmp_path):
    model = make_model(tmp_path / "m.onnx", yolov8_centre_box(), meta={"names": NAMES})

    def sizes(min_size):
        out = str(tmp_path / "d{}.gpkg".format(min_size))
        run = qgis_process.run(ALG, STATIONS=stations, MODEL=model, MIN_SIZE=min_size, UPWARD_VIEWS=True,
                               RESCUE_CONFIDENCE=1.0, OUTPUT=out)   # no second look: every box
        assert run.returncode == 0, run.text
        return sorted(min(r["u1"] - r["u0"], r["v1"] - r["v0"]) for r in read_rays(out))
    every = sizes(0)
    assert len(every) == 3 * 10 and every[0] < every[-1]  # upward views' boxes are taller
    cut = 0.5 * (every[0] + every[-1])
    kept = sizes(cut)
    assert kept == [s for s in every if s >= cut] and 0 < len(kept) < len(every)


@pytest.mark.parametrize("case,message", [
    ("not onnx", "is not an ONNX model"),
    ("layout", "[1, 9, 8]"),
    ("no names", "names no classes"),
])
def test_bad_models(qgis_process, stations, tmp_path, case, message):
    if case == "not onnx":
        model = tmp_path / "model.onnx"
        model.write_text("hello")
    elif case == "layout":
        model = make_model(tmp_path / "m.onnx", np.zeros((1, 9, 8), np.float32), meta={"names": NAMES})
    else:
        model = make_model(tmp_path / "m.onnx", yolov8_centre_box())
    out = tmp_path / "d.gpkg"
    run = qgis_process.run(ALG, STATIONS=stations, MODEL=str(model), OUTPUT=str(out))
    assert run.returncode != 0
    assert message in run.text, run.text
    assert not out.exists()


def test_stations_between_ones_within_the_spacing_are_skipped(qgis_process, stations, tmp_path):
    model = make_model(tmp_path / "m.onnx", yolov8_centre_box(), meta={"names": NAMES})
    dataset = ogr.Open(stations)  # kept: the layer dies with it
    xyz = {f["image"]: np.array([f["x"], f["y"], f["z"]]) for f in dataset.GetLayer(0)}
    dataset = None
    order = sorted(xyz, key=lambda name: (name == "broken.jpg", name))  # the drive's order
    # the second station is skipped: the third stands within the spacing of the first; the
    # third is kept: the fourth (the last, always kept) stands farther than that from the first
    to_third, to_fourth = (float(np.linalg.norm(xyz[order[k]] - xyz[order[0]])) for k in (2, 3))
    assert to_third < to_fourth
    spacing = 0.5 * (to_third + to_fourth)

    def images(spacing_m):
        out = str(tmp_path / "d{}.gpkg".format(spacing_m))
        run = qgis_process.run(ALG, STATIONS=stations, MODEL=model, MIN_SIZE=0, UPWARD_VIEWS=False,
                               STATION_SPACING_M=spacing_m, OUTPUT=out)
        assert run.returncode == 0, run.text
        return run, sorted({r["image"] for r in read_rays(out)})
    run, every = images(0)
    assert every == order[:3] and run.json["results"]["SKIPPED_IMAGES"] == 1
    run, spaced = images(spacing)
    assert spaced == [order[0], order[2]]
    assert run.json["results"]["SKIPPED_IMAGES"] == 1   # the last station, kept, cannot be read
    assert "of the 4 panoramas" in run.text


def test_the_current_panorama_is_the_progress_text(qgis_process, stations, tmp_path):
    """A long detection says which panorama it is on (the dialog's progress text, which
    qgis_process prints without --json); the same kind of step at most every few seconds,
    so the panoramas of this short run after the first are not shown."""
    model = make_model(tmp_path / "m.onnx", yolov8_centre_box(), meta={"names": NAMES})
    run = qgis_process("run", ALG, "--", f"STATIONS={stations}", f"MODEL={model}", "RESCUE_CONFIDENCE=1.0",
                       f"OUTPUT={tmp_path / 'detections.gpkg'}")
    assert run.returncode == 0, run.text
    steps = [line for line in run.stdout.splitlines() if line.startswith("Detecting signs: panorama")]
    assert steps[0] == "Detecting signs: panorama 1 of 4 (pano_0000.jpg)"
    assert len(steps) < 4
    assert run.stdout.index(steps[0]) < run.stdout.index("detections in 3 panoramas (1 skipped)")
