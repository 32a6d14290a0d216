"""findsignsincloud and fusesigns through qgis_process on the generated tiny scene: with a
detector made to miss two of its eight signs (every detection of two classes removed from
the scene's true boxes), the fused layer finds them again from the cloud, reads their class
from the panoramas, and says which sources found each sign."""
import csv
import math
import os
import re

import pytest
from helpers.scenes import ground_and_oracle
from osgeo import ogr

MISSED_CLASSES = ("mandatory", "warning")


def rows(path):
    dataset = ogr.Open(path)
    return [{k: f[k] for k in f.keys()} for f in dataset.GetLayer(0)]


@pytest.fixture(scope="module")
def fused(qgis_process, scene_tiny, scene_tiny_stations, tmp_path_factory):
    scene_dir, _ = scene_tiny
    work = tmp_path_factory.mktemp("fusion")
    stations = scene_tiny_stations
    ground, detections = ground_and_oracle(qgis_process, scene_dir, stations, work)
    dataset = ogr.Open(detections, 1)
    layer = dataset.GetLayer(0)
    missed = [f.GetFID() for f in layer if f["class"] in MISSED_CLASSES]
    for fid in missed:
        layer.DeleteFeature(fid)
    dataset = None
    assert missed
    outputs = {name: str(work / (name + ".gpkg")) for name in ("candidates", "signs", "cloudsigns", "poles",
                                                                 "fused")}
    for algorithm, parameters in (
            ("projectdetections", dict(DETECTIONS=detections, POINT_CLOUD=ground, OUTPUT=outputs["candidates"])),
            ("refinesigns", dict(CANDIDATES=outputs["candidates"], POINT_CLOUD=ground, OUTPUT=outputs["signs"])),
            ("findsignsincloud", dict(POINT_CLOUD=ground, STATIONS=stations, OUTPUT=outputs["cloudsigns"],
                                      POLES=outputs["poles"])),
            ("fusesigns", dict(SIGNS=outputs["signs"], CLOUD_SIGNS=outputs["cloudsigns"], STATIONS=stations,
                               IMAGES=os.path.join(scene_dir, "images"), OUTPUT=outputs["fused"]))):
        run = qgis_process.run("roadsigns:" + algorithm, **parameters)
        assert run.returncode == 0, run.text
    return dict(outputs, scene_dir=scene_dir, work=work)


def evaluate(qgis_process, fused, signs):
    run = qgis_process.run("roadsigns:evaluate", SIGNS=signs,
                           REFERENCE=os.path.join(fused["scene_dir"], "reference_signs.csv"), MATCH_RADIUS=1.0,
                           OUTPUT_REPORT=str(fused["work"] / "evaluation.html"))
    assert run.returncode == 0, run.text
    return run.json["results"]


def test_the_cloud_finds_the_signs_the_images_missed(qgis_process, fused):
    before = evaluate(qgis_process, fused, fused["signs"])
    after = evaluate(qgis_process, fused, fused["fused"])
    assert before["RECALL"] <= 0.8  # the detector missed two signs of eight
    assert after["RECALL"] >= 0.98 and after["PRECISION"] >= 0.97
    signs = rows(fused["fused"])
    by_source = {s: [r for r in signs if r["source"] == s] for s in ("image", "lidar", "image+lidar")}
    assert len(by_source["lidar"]) >= 2 and by_source["image+lidar"]
    for record in by_source["lidar"]:
        assert record["class"] in MISSED_CLASSES + ("unknown",)
        assert (record["class"] == "unknown") == (record["review"] == 1)
        assert record["retro_index"] is not None and record["condition"] in ("good", "check", "poor")
    assert sum(r["class"] in MISSED_CLASSES for r in by_source["lidar"]) >= 1  # read from the panoramas
    for record in by_source["image+lidar"]:
        assert record["class"] not in MISSED_CLASSES and record["cloud_sign_id"] is not None


def reference_codes(scene_dir):
    """(x, y, code) of every true sign (the generator writes each sign's code)."""
    with open(os.path.join(scene_dir, "reference_signs.csv"), newline="") as f:
        return [(float(r["x"]), float(r["y"]), r["code"]) for r in csv.DictReader(f)]


def test_signs_found_in_the_cloud_alone_get_their_codes(fused):
    """fusesigns reads the codes of the signs the images missed (bundled classifier, crops
    around the detections in the views centred on each sign) and votes them like refine."""
    truth = reference_codes(fused["scene_dir"])
    recognised = [r for r in rows(fused["fused"]) if r["source"] == "lidar" and r["class"] != "unknown"]
    assert recognised
    coded = 0
    for record in recognised:
        x, y, code = min(truth, key=lambda t: math.hypot(t[0] - record["x"], t[1] - record["y"]))
        assert math.hypot(x - record["x"], y - record["y"]) < 1.0
        assert record["code_views"] >= 1 and 0.0 <= record["code_score"] <= 1.0
        if record["code"]:
            coded += 1
            assert record["code"] == code and record["code_name"]
            assert record["code_score"] >= 0.5  # the default minimum code confidence
        else:
            assert record["code_name"] == ""
    assert coded >= 1


def test_cloud_signs_and_poles_layers(qgis_process, fused):
    panels = rows(fused["cloudsigns"])
    poles = rows(fused["poles"])
    assert len(panels) >= 7 and poles
    assert {p["support"] for p in panels} <= {"pole", "gantry", "none"}
    carried = {int(i) for p in poles for i in re.findall(r"\d+", str(p["sign_ids"] or ""))}
    assert carried and carried <= {p["sign_id"] for p in panels}
