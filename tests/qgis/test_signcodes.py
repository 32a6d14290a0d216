"""Sign codes through qgis_process: detectsigns reads each detection's code with a sign-code
classifier (READ_CODES, CLASSIFIER, CODES_TABLE), refinesigns votes them per sign
(CODE_CONFIDENCE, CODES_TABLE) and styles the layer with them; bad classifiers and codes
tables end the run with one clear line.

The models are tiny real ONNX models built in the test: a detector that finds a box at the
centre of every view (tests/helpers/tinyonnx.py) and a classifier that reads a crop's mean
colour (tests/helpers/tinyclassifier.py: red DE:206, blue DE:215, grey other). The
panoramas are grey with a red disc at the centre of the forward view (azimuth 0) and a blue
one at the centre of the view 90 degrees to the left (azimuth 90)."""
import os

import cv2
import numpy as np
import pytest
from helpers import signscene
from helpers.badinputs import point_z, schema_fields, write_layer
from helpers.synthpano import paint_discs
from helpers.tinyclassifier import make_classifier
from helpers.tinyonnx import make_model
from osgeo import ogr

from devtools import trajsample

NAMES = "{0: 'stop', 1: 'yield'}"
WIDTH = 1024
RED, BLUE = (30, 30, 230), (230, 40, 30)  # BGR
TABLE = ("# a codes table of the test\ncode;name;class\nDE:206;stop;stop\nDE:215;roundabout;mandatory\n"
         "DE:274[50];speed limit 50;prohibitory\nDE:205;yield;yield\n")


def centre_box_detector(path):
    out = np.zeros((1, 6, 1), np.float32)
    out[0, :4, 0] = [32, 32, 10, 10]
    out[0, 4, 0] = 0.9
    return make_model(path, out, meta={"names": NAMES})


def features(path):
    dataset = ogr.Open(path)
    rows = [{k: f[k] for k in f.keys()} for f in dataset.GetLayer(0)]
    dataset = None
    return rows


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    return tmp_path_factory.mktemp("signcodes")


@pytest.fixture(scope="module")
def inputs(qgis_process, work):
    """Stations of two painted panoramas, the tiny detector, classifier and codes table."""
    drive = trajsample.make_sample(str(work / "drive"), width_px=WIDTH)
    names = drive["names"][:2]
    for name in names:
        pano = paint_discs([(0.0, 0.0, 8.0, RED), (90.0, 0.0, 8.0, BLUE)], WIDTH)
        cv2.imwrite(os.path.join(drive["images"], name), pano, [cv2.IMWRITE_JPEG_QUALITY, 95])
    times = work / "times.csv"
    times.write_text("image,time\n" + "".join("{},{}\n".format(n, t) for n, t in zip(names, drive["times"])))
    stations = str(work / "stations.gpkg")
    run = qgis_process.run("roadsigns:importtrajectory", TRAJECTORY=drive["trajectory_csv"], IMAGE_TIMES=str(times),
                           IMAGES=drive["images"], TRAJECTORY_CRS="EPSG:32633", TARGET_CRS="EPSG:32633",
                           LEVER_ARM_Z=-2.0, OUTPUT=stations)
    assert run.returncode == 0, run.text
    table = work / "codes.csv"
    table.write_text(TABLE)
    return dict(stations=stations, detector=centre_box_detector(work / "detector.onnx"),
                classifier=make_classifier(work / "classifier.onnx"), table=str(table))


def detect(qgis_process, inputs, out, **extra):
    # the detector boxes the centre of every view: 10 a panorama with the upward views
    parameters = dict(STATIONS=inputs["stations"], MODEL=inputs["detector"], CLASSIFIER=inputs["classifier"],
                      CODES_TABLE=inputs["table"], MIN_SIZE=0, UPWARD_VIEWS=True, OUTPUT=str(out))
    parameters.update(extra)
    return qgis_process.run("roadsigns:detectsigns", **{k: v for k, v in parameters.items() if v is not None})


def test_each_detection_gets_its_code(qgis_process, inputs, work):
    out = work / "detections.gpkg"
    run = detect(qgis_process, inputs, out, RESCUE_CONFIDENCE=1.0)   # codes read, no second look
    assert run.returncode == 0, run.text
    assert "classifier.onnx: 2 codes and 'other'" in run.text
    assert "Sign codes read in 4 of the 20 detections" in run.text
    rows = features(str(out))
    assert len(rows) == 2 * 10
    for r in rows:
        u, v = ((r["u0"] + r["u1"]) / 2) % WIDTH, (r["v0"] + r["v1"]) / 2
        expected = "other"
        if abs(v - WIDTH / 4) < 2 and abs(u - WIDTH / 2) < 2:
            expected = "DE:206"      # azimuth 0: the red disc
        elif abs(v - WIDTH / 4) < 2 and abs(u - 3 * WIDTH / 4) < 2:
            expected = "DE:215"      # azimuth 90: the blue one
        assert r["code"] == expected, r
        assert 0.5 < r["code_score"] <= 1.0


def test_the_second_look_drops_the_upward_views_lone_boxes_read_as_no_sign(qgis_process, inputs, work):
    """With the second look (on by default) a box an upward view found alone is dropped when
    the classifier reads ``other`` in it: here the model boxes every view's centre, and the
    upward views' centres (35 deg up) show no sign; the horizon views' boxes stay, ``other``
    or not."""
    out = work / "detections_second_look.gpkg"
    run = detect(qgis_process, inputs, out)
    assert run.returncode == 0, run.text
    rows = features(str(out))
    assert len(rows) == 2 * 8
    assert all(abs((r["v0"] + r["v1"]) / 2 - WIDTH / 4) < 2 for r in rows)     # all on the horizon
    assert [r["code"] for r in rows].count("other") == 2 * 6


def test_codes_can_be_switched_off(qgis_process, inputs, work):
    out = work / "detections_off.gpkg"
    run = detect(qgis_process, inputs, out, READ_CODES=False, CLASSIFIER=None, CODES_TABLE=None)
    assert run.returncode == 0, run.text
    assert "Sign codes are not read" in run.text
    rows = features(str(out))
    assert len(rows) == 20 and all(not r["code"] and r["code_score"] is None for r in rows)


@pytest.mark.parametrize("case,fragments", [
    ("classifier missing", ["Sign-code classifier not found", "no_such.onnx"]),
    ("input shape", ["bad_shape.onnx", "shape ['batch', 3, 32, 16]", "supported: float [batch, 3, S, S]"]),
    ("output shape", ["bad_output.onnx", "output of shape [1, 5]", "supported: [batch, C] with C = 3"]),
    ("names not in the table", ["unknown_names.onnx", "not in the sign codes table", "codes.csv", "DE:999"]),
    ("a detector as classifier", ["detector.onnx", "is a detect model", "classify"]),
    ("codes table line", ["bad_table.csv, line 3", "unknown class octagon for DE:206"]),
    ("codes table header", ["no_header.csv, line 1", "expected the header code;name;class"]),
])
def test_bad_classifiers_and_tables(qgis_process, inputs, work, tmp_path, case, fragments):
    extra = {}
    if case == "classifier missing":
        extra["CLASSIFIER"] = str(tmp_path / "no_such.onnx")
    elif case == "input shape":
        extra["CLASSIFIER"] = make_classifier(tmp_path / "bad_shape.onnx", input_shape=["batch", 3, 32, 16])
    elif case == "output shape":
        extra["CLASSIFIER"] = make_classifier(tmp_path / "bad_output.onnx", extra_outputs=2)
    elif case == "names not in the table":
        extra["CLASSIFIER"] = make_classifier(tmp_path / "unknown_names.onnx", names=("DE:999", "DE:215", "other"))
    elif case == "a detector as classifier":
        extra["CLASSIFIER"] = make_model(tmp_path / "detector.onnx", np.zeros((1, 6, 1), np.float32),
                                         meta={"names": NAMES, "task": "detect"})
    elif case == "codes table line":
        table = tmp_path / "bad_table.csv"
        table.write_text("# comment\ncode;name;class\nDE:206;stop;octagon\n")
        extra["CODES_TABLE"] = str(table)
    else:
        table = tmp_path / "no_header.csv"
        table.write_text("DE:206;stop;stop\n")
        extra["CODES_TABLE"] = str(table)
    out = tmp_path / "detections.gpkg"
    run = detect(qgis_process, inputs, out, **extra)
    assert run.returncode != 0
    for fragment in fragments:
        assert fragment in run.text, run.text
    assert "Traceback" not in run.text, run.text
    assert not out.exists()


# --- refinesigns: the vote per sign ---------------------------------------------------------

@pytest.fixture(scope="module")
def candidates(work):
    """The refine tests' scene (tests/helpers/signscene.py) as a LAS and a candidates layer
    whose detections read codes: the prohibitory panel DE:274[50], the yield DE:205, the
    stop out of reach DE:206, the mandatory panel 10 a sure stop sign seen by an unsure
    detector; the rest other. Also the same candidates without the code fields (a layer
    made before codes were read)."""
    from roadsigns.core import projection as P  # noqa: N812
    from roadsigns.core.pointcloud import TiledIndex

    scene = signscene.make_scene(seed=7)
    code_of = {1: "DE:274[50]", 7: "DE:205", 8: "DE:206", 10: "DE:206"}
    for d in scene.detections:
        d["code"] = code_of.get(d["truth_id"], "other")
        d["code_score"] = 0.99 if d["truth_id"] == 10 else 0.9
        if d["truth_id"] == 10:
            d["score"] = 0.5
    cloud = str(work / "scene.laz")
    signscene.write_las(scene, cloud)
    index = TiledIndex.from_arrays(scene.xyz_world, {"intensity": scene.intensity,
                                                     "classification": scene.classification}, tile_size_m=5.0)
    records = P.project_detections(P.Detections.from_records(scene.detections), index).records()

    def point(row):
        return point_z(dict(x=row["cand_x"], y=row["cand_y"], z=row["cand_z"])) if row["status"] == "ok" else None

    fields = schema_fields(P.CANDIDATE_FIELDS)
    with_codes = write_layer(str(work / "candidates.gpkg"), fields, records, point, 25833, ogr.wkbPoint25D)
    older = [(n, k) for n, k in fields if n not in ("code", "code_score")]
    without = write_layer(str(work / "candidates_old.gpkg"), older, records, point, 25833, ogr.wkbPoint25D)
    return dict(scene=scene, cloud=cloud, with_codes=with_codes, without=without)


def refine(qgis_process, inputs, candidates, out, layer="with_codes", **extra):
    parameters = dict(CANDIDATES=candidates[layer], POINT_CLOUD=candidates["cloud"], CODES_TABLE=inputs["table"],
                      OUTPUT=str(out))
    parameters.update(extra)
    return qgis_process.run("roadsigns:refinesigns", **{k: v for k, v in parameters.items() if v is not None})


def test_refine_votes_the_codes_and_checks_the_class(qgis_process, inputs, candidates, work):
    out = work / "signs.gpkg"
    run = refine(qgis_process, inputs, candidates, out)
    assert run.returncode == 0, run.text
    assert "of 10 signs have a sign code; 1 took their class from the code, 0 codes were dropped" in run.text
    signs = features(str(out))
    assert len(signs) == 10
    coded = {s["code"]: s for s in signs if s["code"]}
    assert set(coded) == {"DE:274[50]", "DE:205", "DE:206"}
    assert coded["DE:274[50]"]["code_name"] == "speed limit 50" and coded["DE:274[50]"]["class"] == "prohibitory"
    assert coded["DE:274[50]"]["code_score"] == pytest.approx(0.9) and coded["DE:274[50]"]["code_views"] >= 2
    stops = [s for s in signs if s["code"] == "DE:206"]
    assert len(stops) == 2 and all(s["class"] == "stop" for s in stops)
    assert sorted(s["code_check"] for s in stops) == ["", "class_from_code"]  # panel 10 was mandatory
    assert all(s["code_check"] == "" for s in signs if s["code"] != "DE:206")
    qml = (work / "signs.qml").read_text()
    assert "code_name" in qml and "regexp_substr" in qml  # the label says what the sign says


def test_refine_code_confidence(qgis_process, inputs, candidates, work):
    out = work / "signs_strict.gpkg"
    run = refine(qgis_process, inputs, candidates, out, CODE_CONFIDENCE=0.95)
    assert run.returncode == 0, run.text
    signs = features(str(out))
    assert {s["code"] for s in signs if s["code"]} == {"DE:206"}  # only panel 10's 0.99 reads are kept
    assert all(s["code_score"] is not None for s in signs)


def test_refine_reads_a_candidates_layer_without_codes(qgis_process, inputs, candidates, work):
    out = work / "signs_old.gpkg"
    run = refine(qgis_process, inputs, candidates, out, layer="without", CODES_TABLE=None)
    assert run.returncode == 0, run.text
    signs = features(str(out))
    assert len(signs) == 10
    assert all(not s["code"] and not s["code_name"] and s["code_views"] == 0 and s["code_score"] is None
               for s in signs)


@pytest.mark.parametrize("case,fragments", [
    ("code not in the table", ["Detection", "has the sign code DE:274[50], which is not in the sign codes table",
                               "small.csv"]),
    ("bad table", ["bad.csv, line 2", "expected 3 fields"]),
])
def test_refine_bad_codes_tables(qgis_process, inputs, candidates, tmp_path, case, fragments):
    table = tmp_path / ("small.csv" if case == "code not in the table" else "bad.csv")
    table.write_text("code;name;class\nDE:206;stop;stop\nDE:205;yield;yield\n" if case == "code not in the table"
                     else "code;name;class\nDE:206;stop\n")
    out = tmp_path / "signs.gpkg"
    run = refine(qgis_process, inputs, candidates, out, CODES_TABLE=str(table))
    assert run.returncode != 0
    for fragment in fragments:
        assert fragment in run.text, run.text
    assert "Traceback" not in run.text and not out.exists()
