"""Sign codes in the chain: each detection's code read from its panorama (core.detections
read_codes, core.detector detect_drive), carried by the detections and candidates, voted
per sign with the class check (core.refine vote_code), kept by fusion, named in the
handover and shown in the review report. Classifiers are the tiny real ONNX models of
tests/helpers/tinyclassifier.py: a red crop reads DE:206 (stop), a blue one DE:215
(roundabout), a grey one other."""
import math
from types import SimpleNamespace

import cv2
import numpy as np
import pytest
from helpers import signscene
from helpers.synthpano import disc_pano_box, paint_discs
from helpers.tinyclassifier import make_classifier

from roadsigns.core import detections as D  # noqa: N812 (the tests' short module names)
from roadsigns.core import detector as DT  # noqa: N812
from roadsigns.core import panorama
from roadsigns.core import projection as P  # noqa: N812
from roadsigns.core import refine as R  # noqa: N812
from roadsigns.core import signcodes as SC  # noqa: N812
from roadsigns.core.errors import InputError
from roadsigns.core.fusion import fuse_signs
from roadsigns.core.handover import sign_name
from roadsigns.core.panorama import ViewSet
from roadsigns.core.pointcloud import TiledIndex
from roadsigns.core.review import write_review_report
from roadsigns.core.schema import names

RED, BLUE = (30, 30, 230), (230, 40, 30)  # BGR
TABLE_TEXT = ("code;name;class\nDE:206;stop;stop\nDE:215;roundabout;mandatory\n"
              "DE:274[50];speed limit 50;prohibitory\nDE:205;yield;yield\n")


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    path = tmp_path_factory.mktemp("table") / "codes.csv"
    path.write_text(TABLE_TEXT)
    return SC.read_codes_table(str(path))


@pytest.fixture(scope="module")
def classifier(tmp_path_factory, table):
    return SC.CodeClassifier(make_classifier(tmp_path_factory.mktemp("clf") / "c.onnx"), table)


def found_at(boxes):
    boxes = np.asarray(boxes, float).reshape(-1, 4)
    n = len(boxes)
    return DT.PanoramaDetections(np.zeros(n, np.int64), ["stop"] * n, np.full(n, 0.9), boxes[:, 0],
                                 boxes[:, 1], boxes[:, 2], boxes[:, 3], np.zeros(n, np.int64),
                                 np.ones(n, np.int64))


# --- one panorama ---------------------------------------------------------------------------

def test_each_detection_gets_the_code_read_in_its_crop(classifier):
    width = 1024
    discs = [(20.0, 5.0, 4.0, RED), (-90.0, 0.0, 5.0, BLUE), (180.0, 10.0, 4.0, RED)]  # the last across the seam
    pano = paint_discs(discs, width)
    boxes = [disc_pano_box(az, el, r, width) for az, el, r, _ in discs] + [[300.0, 200.0, 330.0, 230.0]]
    assert boxes[2][0] < width < boxes[2][2]  # the detections layer's form across the seam
    found = found_at(boxes)
    assert found.code == [""] * 4 and np.isnan(found.code_score).all()  # no classifier yet
    assert D.read_codes(classifier, pano, found) is found
    assert found.code == ["DE:206", "DE:215", "DE:206", "other"]  # BGR panorama, RGB crops: red stays red
    assert np.all((found.code_score > 0.5) & (found.code_score <= 1.0))


def test_no_detection_no_crop(classifier):
    found = found_at(np.zeros((0, 4)))
    assert D.read_codes(classifier, np.zeros((8, 16, 3), np.uint8), found).code == []


class CentreBoxDetector:
    """A detector that finds one 'stop' box at the centre of every view (whatever it shows)."""

    class_names = ["stop"]

    def detect(self, image, confidence, iou_threshold):
        h, w = image.shape[:2]
        return DT.ImageDetections(np.array([[0.45 * w, 0.45 * h, 0.55 * w, 0.55 * h]]), np.array([0.9]),
                                  np.zeros(1, np.int64))


def test_detect_drive_reads_the_codes_while_each_panorama_is_in_memory(tmp_path, classifier, monkeypatch):
    width = 1024
    views = ViewSet.default(size_px=64, upward=False)
    centres = DT.detect_panorama(CentreBoxDetector(), np.full((width // 2, width, 3), 90, np.uint8), views)
    assert len(centres) == 8
    u_centre = ((centres.u0 + centres.u1) / 2) % width
    az = (u_centre / width - 0.5) * 360.0
    el = (0.5 - (centres.v0 + centres.v1) / 2 / (width // 2)) * 180.0
    colours = [RED, BLUE]
    paths = []
    for k in range(2):  # panorama k: the sign at view k's centre is red, at view k + 1 blue
        pano = paint_discs([(az[k], el[k], 4.0, colours[0]), (az[k + 1], el[k + 1], 4.0, colours[1])], width)
        paths.append(str(tmp_path / "p{}.png".format(k)))
        cv2.imwrite(paths[-1], pano)
    reads = []
    original = panorama.read_panorama  # what detect_drive reads panoramas with
    monkeypatch.setattr(panorama, "read_panorama", lambda path: reads.append(path) or original(path))
    seen = []
    drive = DT.detect_drive(CentreBoxDetector(), paths, views, 0.5,
                            on_panorama=lambda pano, found: seen.append(pano.shape) or D.read_codes(
                                classifier, pano, found))
    assert reads == paths and len(seen) == 2  # each panorama read once, the codes read from it
    for k, found in enumerate(drive.per_image):
        assert len(found) == 8
        u = ((found.u0 + found.u1) / 2) % width
        expected = ["DE:206" if np.isclose(x, u_red) else "DE:215" if np.isclose(x, u_blue) else "other"
                    for x in u for u_red, u_blue in [(u_centre[k], u_centre[k + 1])]]
        assert found.code == expected and expected.count("other") == 6


# --- the layers -----------------------------------------------------------------------------

class Stations:
    station_id = np.array([1, 2])
    image = ["a.jpg", "b.jpg"]
    width_px = np.array([1024, 1024])
    height_px = np.array([512, 512])
    xyz_world = np.array([[0.0, 0.0, 2.0], [5.0, 0.0, 2.0]])
    q_world_from_pano_wxyz = np.array([[1.0, 0, 0, 0], [1.0, 0, 0, 0]])
    time_s = np.array([1.0, 2.0])
    heading_deg = np.array([90.0, 90.0])


def test_codes_go_through_the_detections_and_candidates_layers():
    a = found_at([[10, 10, 30, 30], [100, 10, 130, 40]])
    a.code, a.code_score = ["DE:206", "other"], np.array([0.9, 0.7])
    det = D.drive_detections(Stations(), [a, found_at([[50, 50, 60, 60]])])
    assert det.code == ["DE:206", "other", ""] and np.isnan(det.code_score[2])
    records = det.records()
    assert [r["code"] for r in records] == ["DE:206", "other", ""]
    assert [r["code_score"] for r in records] == [pytest.approx(0.9), pytest.approx(0.7), None]
    assert list(records[0]) == list(names(D.DETECTION_FIELDS))
    back = D.Detections.from_records(records)
    assert back.code == det.code and np.allclose(back.code_score[:2], [0.9, 0.7])
    assert back.take([1]).code == ["other"]
    assert "code" in names(P.CANDIDATE_FIELDS) and "code_score" in names(P.CANDIDATE_FIELDS)
    cand = P.ProjectionResult.unprojected(back)
    assert [r["code"] for r in cand.records()] == ["DE:206", "other", ""]
    # a layer written before codes were read (or by another tool): no code fields at all
    old = [{k: v for k, v in r.items() if k not in ("code", "code_score")} for r in records]
    older = D.Detections.from_records(old)
    assert older.code == ["", "", ""] and np.isnan(older.code_score).all()
    assert set(D.REQUIRED_POSE_FIELDS) == set(names(D.DETECTION_POSE_FIELDS)) - {"code", "code_score"}


# --- the vote per sign ------------------------------------------------------------------------

def views(rows):
    """A candidates stand-in (``.detections``) from (class, score, code, code_score, box side px)."""
    n = len(rows)
    side = np.array([r[4] for r in rows], float)
    boxes = np.column_stack([np.full(n, 500.0), np.full(n, 200.0), 500.0 + side, 200.0 + side])
    det = D.Detections(np.arange(1, n + 1), np.arange(1, n + 1), ["p{}.jpg".format(k) for k in range(n)],
                       [r[0] for r in rows], np.array([r[1] for r in rows], float), boxes,
                       np.tile([4096.0, 2048.0], (n, 1)), np.zeros((n, 3)), np.tile([1.0, 0, 0, 0], (n, 1)),
                       code=[r[2] for r in rows], code_score=np.array([r[3] for r in rows], float))
    return SimpleNamespace(detections=det), list(range(n))


def test_a_unanimous_code_agreeing_with_the_class(table):
    cand, rows = views([("prohibitory", 0.8, "DE:274[50]", 0.9, 40), ("prohibitory", 0.7, "DE:274[50]", 0.8, 30)])
    v = R.vote_code(cand, rows, "prohibitory", table)
    assert (v.code, v.name, v.views, v.check, v.klass) == ("DE:274[50]", "speed limit 50", 2, "", "prohibitory")
    w = np.array([0.8, 0.7]) * R.legible_side_px(cand.detections, rows)
    assert v.score == pytest.approx(float((w * [0.9, 0.8]).sum() / w.sum()))  # share 1 x mean probability
    assert v.fields() == {"code": "DE:274[50]", "code_name": "speed limit 50", "code_score": v.score,
                          "code_views": 2, "code_check": ""}


def test_crop_side_is_the_crop_cut_for_the_box():
    cand, rows = views([("stop", 0.9, "DE:206", 0.9, 40), ("stop", 0.9, "DE:206", 0.9, 1000)])
    sides = R.crop_side_px(cand.detections, rows)
    assert sides[0] == pytest.approx(40 * (1 + 2 * SC.DEFAULT_CROP_MARGIN), abs=1.5)
    assert sides[1] == 256  # clamped as cut_crop clamps it


def test_the_legible_side_is_the_crop_side_across_the_narrower_side_of_the_box():
    """Boxes on the horizon (v = 1024 of 2048): a square box keeps its crop side; one of a
    sign passed close by, 90 px high and 30 px wide, is read from a crop squeezed across
    to a third."""
    det = D.Detections(np.arange(1, 3), np.arange(1, 3), ["p0.jpg", "p1.jpg"], ["prohibitory"] * 2,
                       np.array([0.9, 0.9]), np.array([[500.0, 1004, 540, 1044], [500.0, 979, 530, 1069]]),
                       np.tile([4096.0, 2048.0], (2, 1)), np.zeros((2, 3)), np.tile([1.0, 0, 0, 0], (2, 1)),
                       code=["DE:274[50]"] * 2, code_score=np.array([0.9, 0.9]))
    crop = R.crop_side_px(det, [0, 1])
    np.testing.assert_allclose(R.box_aspect(det, [0, 1]), [1.0, 1 / 3], atol=0.01)
    np.testing.assert_allclose(R.legible_side_px(det, [0, 1]), crop * [1.0, 1 / 3], rtol=0.02)
    assert crop[1] > crop[0]  # the tall box's crop is larger, its legible side smaller


def test_a_close_view_seen_edge_on_does_not_outvote_the_face_on_views(table):
    """A speed limit passed close by, boxed 30 x 90 px, read as 30 (p 0.9), against two views
    face on at 40 px that read 50 (p 0.9): by crop side the tall box outweighs them (its crop
    is cut for its 90 px height); across its narrow side it does not."""
    det = D.Detections(np.arange(1, 4), np.arange(1, 4), ["p0.jpg", "p1.jpg", "p2.jpg"], ["prohibitory"] * 3,
                       np.array([0.9, 0.9, 0.9]),
                       np.array([[500.0, 979, 530, 1069], [900.0, 1004, 940, 1044], [1300.0, 1004, 1340, 1044]]),
                       np.tile([4096.0, 2048.0], (3, 1)), np.zeros((3, 3)), np.tile([1.0, 0, 0, 0], (3, 1)),
                       code=["DE:274[30]", "DE:274[50]", "DE:274[50]"], code_score=np.array([0.9, 0.9, 0.9]))
    sides = R.crop_side_px(det, [0, 1, 2])
    assert sides[0] > sides[1] + sides[2]
    v = R.vote_code(SimpleNamespace(detections=det), [0, 1, 2], "prohibitory", table, confidence=0.0)
    assert v.code == "DE:274[50]" and v.views == 2


def test_the_weightier_view_wins(table):
    """Detection score x crop side: one near, sharp view outvotes two small far ones."""
    cand, rows = views([("mandatory", 0.9, "DE:215", 0.9, 120), ("mandatory", 0.9, "DE:206", 0.9, 20),
                        ("mandatory", 0.9, "DE:206", 0.9, 20)])
    v = R.vote_code(cand, rows, "mandatory", table, confidence=0.0)
    assert v.code == "DE:215" and v.views == 1 and v.check == ""


@pytest.mark.parametrize("rows,why", [
    ([("stop", 0.9, "other", 0.95, 40), ("stop", 0.9, "other", 0.9, 40)], "other"),
    ([("stop", 0.9, "DE:206", 0.4, 40), ("stop", 0.9, "DE:206", 0.45, 40)], "weak"),
    ([("stop", 0.9, "DE:206", 0.9, 40), ("stop", 0.9, "DE:215", 0.9, 40)], "split"),
])
def test_other_and_weak_codes_are_left_empty(table, rows, why):
    cand, rows_ = views(rows)
    v = R.vote_code(cand, rows_, "stop", table, confidence=0.5)
    assert v.code == "" and v.name == "" and v.check == "" and v.klass == "stop"
    assert 0.0 < v.score < (1.0 if why == "other" else 0.5) and v.views >= 1  # the winner's support


def test_no_code_read_at_all(table):
    cand, rows = views([("stop", 0.9, "", math.nan, 40)])
    v = R.vote_code(cand, rows, "stop", table)
    assert (v.code, v.name, v.views, v.check, v.klass) == ("", "", 0, "", "stop") and math.isnan(v.score)


def test_a_better_supported_code_gives_the_class(table):
    """The detector calls it prohibitory, weakly and not unanimously; the classifier reads a
    stop sign in every view with certainty: the code's support beats the class's."""
    cand, rows = views([("prohibitory", 0.5, "DE:206", 0.97, 40), ("stop", 0.45, "DE:206", 0.95, 40),
                        ("prohibitory", 0.5, "DE:206", 0.96, 40)])
    klass, _ = R.vote_class(cand, rows)
    assert klass == "prohibitory"
    class_support = R.class_support(cand, rows, klass)
    assert class_support == pytest.approx(1.0 / 1.45 * 0.5)
    v = R.vote_code(cand, rows, klass, table)
    assert v.score > class_support
    assert (v.code, v.name, v.check, v.klass) == ("DE:206", "stop", R.CLASS_FROM_CODE, "stop")


def test_a_better_supported_class_drops_the_code(table):
    """Every view is a sure mandatory sign; the code is read as a stop sign at 0.6: dropped."""
    cand, rows = views([("mandatory", 0.95, "DE:206", 0.6, 40), ("mandatory", 0.9, "DE:206", 0.6, 40)])
    v = R.vote_code(cand, rows, "mandatory", table)
    assert R.class_support(cand, rows, "mandatory") == pytest.approx(0.925)
    assert (v.code, v.name, v.check, v.klass) == ("", "", R.CODE_DROPPED, "mandatory")
    assert v.score == pytest.approx(0.6) and v.views == 2  # what was dropped


def test_equal_support_keeps_the_class(table):
    cand, rows = views([("mandatory", 0.8, "DE:206", 0.8, 40)])
    assert R.vote_code(cand, rows, "mandatory", table).check == R.CODE_DROPPED


def test_classes_outside_the_six_are_not_checked_and_no_table_no_name(table):
    cand, rows = views([("sign", 0.9, "DE:206", 0.9, 40)])
    v = R.vote_code(cand, rows, "sign", table)
    assert (v.code, v.name, v.check, v.klass) == ("DE:206", "stop", "", "sign")
    v = R.vote_code(cand, rows, "sign", None)
    assert (v.code, v.name, v.check) == ("DE:206", "", "")


def test_a_code_not_in_the_table_is_an_error(table):
    cand, rows = views([("stop", 0.9, "FR:AB4", 0.9, 40)])
    with pytest.raises(InputError, match=r"Detection 1 has the sign code FR:AB4, which is not in the sign codes "
                                         r"table .*codes.csv"):
        R.vote_code(cand, rows, "stop", table)


def test_a_sign_whose_code_the_table_lacks_gets_no_code_and_no_error(table):
    """Views read as ``unlisted:prohibitory`` (a foreign no-parking sign): not a code of the
    table, yet no error; the sign keeps its class and no code, like ``other``."""
    cand, rows = views([("prohibitory", 0.9, SC.unlisted_code("prohibitory"), 0.95, 40),
                        ("prohibitory", 0.8, SC.unlisted_code("prohibitory"), 0.9, 40)])
    v = R.vote_code(cand, rows, "prohibitory", table)
    assert (v.code, v.name, v.check, v.klass, v.views) == ("", "", "", "prohibitory", 2)
    assert v.score > 0.9


# --- refine, fusion, handover, review --------------------------------------------------------

@pytest.fixture(scope="module")
def coded_scene():
    """The refine tests' scene, each detection with a code: the prohibitory panels read as
    DE:274[50], the mirror (detected as prohibitory) as other, the yield as DE:205 in all
    views, and the mandatory panel 10 as a stop sign with certainty in every view."""
    scene = signscene.make_scene(seed=7)
    code_of = {1: "DE:274[50]", 7: "DE:205", 10: "DE:206", 4: "DE:215", 5: "DE:215", 8: "DE:206"}
    for d in scene.detections:
        d["code"] = code_of.get(d["truth_id"], "other")
        d["code_score"] = 0.99 if d["truth_id"] == 10 else 0.9
        if d["truth_id"] == 10:
            d["score"] = 0.5  # an unsure detector
    index = TiledIndex.from_arrays(scene.xyz_world, {"intensity": scene.intensity,
                                                     "classification": scene.classification}, tile_size_m=5.0)
    return scene, P.project_detections(P.Detections.from_records(scene.detections), index), index


def test_refine_votes_the_codes_per_sign(coded_scene, table):
    scene, candidates, index = coded_scene
    result = R.refine_signs(candidates, index, merge_radius_m=1.0, codes_table=table)
    truth = {p.sign_id: p for p in scene.signs}
    by_truth = {}
    for k, s in enumerate(result.signs):
        ids = {candidates.detections.det_id[i] for i in np.flatnonzero(result.candidate_sign == k)}
        truth_ids = {d["truth_id"] for d in scene.detections if d["det_id"] in ids}
        assert len(truth_ids) == 1
        by_truth[truth_ids.pop()] = s
    assert by_truth[1].code == "DE:274[50]" and by_truth[1].code_name == "speed limit 50"
    assert by_truth[1].code_views == scene.n_views(1) and by_truth[1].code_check == ""
    assert by_truth[1].code_score == pytest.approx(0.9)
    assert by_truth[7].code == "DE:205" and by_truth[7].klass == "yield"
    assert by_truth[8].code == "DE:206" and by_truth[8].position_source == "image"
    assert by_truth[10].klass == "stop" and by_truth[10].code_check == R.CLASS_FROM_CODE  # was mandatory
    assert truth[10].cls == "mandatory"
    assert by_truth[4].code == "DE:215" and by_truth[4].code_check == ""
    for sign_id in (2, 3, 6, 9):  # read as other
        assert by_truth[sign_id].code == "" and by_truth[sign_id].code_check == ""
        assert by_truth[sign_id].code_score == pytest.approx(0.9)
    records = result.records()
    assert all(tuple(r) == names(R.SIGN_FIELDS) for r in records)
    assert names(R.SIGN_FIELDS)[:8] == ("sign_id", "class", "score", "code", "code_name", "code_score",
                                        "code_views", "code_check")


def test_refine_without_codes_leaves_the_code_fields_empty(table):
    scene = signscene.make_scene(seed=7)
    index = TiledIndex.from_arrays(scene.xyz_world, {"intensity": scene.intensity,
                                                     "classification": scene.classification}, tile_size_m=5.0)
    result = R.refine_signs(P.project_detections(P.Detections.from_records(scene.detections), index), index,
                            merge_radius_m=1.0, codes_table=table)
    assert result.signs and all(s.code == "" and s.code_views == 0 and math.isnan(s.code_score)
                                and s.code_check == "" for s in result.signs)
    assert all(r["code_score"] != r["code_score"] for r in result.records())  # NaN: written as NULL


def test_fusion_keeps_the_code_and_lidar_only_signs_have_none():
    sign = {f: None for f in names(R.SIGN_FIELDS)}
    sign.update(sign_id=1, x=0.0, y=0.0, z=2.0, azimuth=90.0, code="DE:206", code_name="stop", code_score=0.9,
                code_views=3, code_check="", **{"class": "stop"})
    panel = {"sign_id": 5, "x": 20.0, "y": 0.0, "z": 2.0, "azimuth": 90.0}
    fused = fuse_signs([sign], [panel]).signs
    assert (fused[0]["code"], fused[0]["code_name"], fused[0]["code_views"]) == ("DE:206", "stop", 3)
    assert fused[1]["source"] == "lidar"
    assert (fused[1]["code"], fused[1]["code_name"], fused[1]["code_score"], fused[1]["code_views"],
            fused[1]["code_check"]) == ("", "", None, 0, "")


def test_handover_name_from_the_code_name():
    sign = {"code": "DE:274[50]", "code_name": "speed limit 50", "class": "prohibitory"}
    assert sign_name(sign, "DE:274[50]", "prohibitory") == "speed limit 50"
    assert sign_name(sign, "DE:274[30]", "prohibitory") == "prohibitory"  # code changed in review
    assert sign_name(dict(sign, name="Tempo 50"), "DE:274[50]", "prohibitory") == "Tempo 50"
    assert sign_name({"class": "stop"}, None, "stop") == "stop"


def test_review_report_shows_the_code(tmp_path):
    sign = {f: None for f in names(R.SIGN_FIELDS)}
    sign.update(sign_id=3, code="DE:274[50]", code_name="speed limit 50", code_score=0.876, code_views=4,
                code_check="class_from_code", **{"class": "prohibitory"})
    path = tmp_path / "review.html"
    write_review_report([sign], [""], str(path))
    page = path.read_text()
    assert "Sign 3: DE:274[50] speed limit 50 (class_from_code)" in page
    assert "<th>code_score</th><td>0.876</td>" in page and "<th>code_views</th><td>4</td>" in page
