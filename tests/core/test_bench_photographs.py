"""The photograph sets of bench/bench_detector.py and the rule scoring of
bench/tune_second_look.py: real signs pasted from held-out tracks, and what a rule keeps."""
import os
import sys

import numpy as np
import pytest

from devtools import REPO_ROOT
from devtools.train import data as train_data
from devtools.train.metrics import iou_matrix

sys.path.insert(0, os.path.join(REPO_ROOT, "bench"))
import bench_detector as bd  # noqa: E402
import tune_second_look as tune  # noqa: E402

pytestmark = pytest.mark.skipif(not os.path.isdir(os.path.join(train_data.DATA_DIR, "gtsrb-train")),
                                reason="needs the shared data folder beside the checkout")

FRAME_IDS = range(500, 504)


def test_heldout_tracks_are_pasted_beside_the_frames_own_signs_and_are_repeatable():
    frames = list(bd.heldout_track_frames(ids=FRAME_IDS, max_tracks=8))
    again = list(bd.heldout_track_frames(ids=FRAME_IDS, max_tracks=8))
    truth = train_data.read_gtsdb(FRAME_IDS)
    assert len(frames) == len(FRAME_IDS)
    pasted = 0
    for (image, boxes, classes, ignore, unlabelled, families), (_, own, _own_classes), (image2, boxes2, *_) in zip(
            frames, truth, again):
        np.testing.assert_array_equal(ignore, own)  # the frame's own signs: ignored, not counted
        assert unlabelled.shape == (0, 4) and families == ()
        assert len(boxes) == len(classes)
        if len(boxes) and len(own):
            assert iou_matrix(boxes, own).max() == 0.0  # pasted at free spots
        heights = boxes[:, 3] - boxes[:, 1]
        assert np.all((heights >= 0.5 * bd.TRACK_SIZES_PX[0][0]) & (heights <= 1.5 * bd.TRACK_SIZES_PX[-1][1]))
        np.testing.assert_array_equal(image, image2)
        np.testing.assert_array_equal(boxes, boxes2)
        pasted += len(boxes)
    # one sign per track and band, a few may find no free spot
    assert 0.75 * 8 * len(bd.TRACK_SIZES_PX) <= pasted <= 8 * len(bd.TRACK_SIZES_PX)


def test_the_pasted_tracks_are_the_heldout_split_and_each_half_pastes_half_of_them():
    import csv

    with open(os.path.join(train_data.DATA_DIR, "gtsrb-train", "GT-train.csv")) as f:
        every_track = {(int(r["ClassId"]), r["Track"]) for r in csv.DictReader(f, delimiter=";")}
    held = set(train_data.read_gtsrb_train("val")[2])
    assert held == train_data.gtsrb_track_split(
        [{"ClassId": c, "Track": t} for c, t in every_track]) and len(held) < len(every_track) / 5
    a = [len(f.boxes) for f in bd.heldout_track_frames(ids=FRAME_IDS, max_tracks=8, half=0)]
    b = [len(f.boxes) for f in bd.heldout_track_frames(ids=FRAME_IDS, max_tracks=8, half=1)]
    assert 0 < sum(a) <= 8 and 0 < sum(b) <= 8


def _row(gt, sure, cand_boxes, cand_scores, sheeting, probs):
    gt = np.asarray(gt, float).reshape(-1, 4)
    sb = np.asarray(sure, float).reshape(-1, 4)
    cb = np.asarray(cand_boxes, float).reshape(-1, 4)
    return {"gt": gt, "classes": np.zeros(len(gt), np.int64), "ignore": np.zeros((0, 4)),
            "sure": (sb, np.full(len(sb), 0.9), np.zeros(len(sb), np.int64)),
            "cand_boxes": cb, "cand_scores": np.asarray(cand_scores, float), "cand_ids": np.zeros(len(cb), np.int64),
            "sheeting": np.asarray(sheeting, float),
            "probs": np.asarray(probs, float)}


def test_a_rule_keeps_only_the_candidates_that_pass_every_check():
    reader = tune.Reader(other=1, column_class=[0, -2], n_classes=6)  # codes: one of class 0, and other
    two_signs = [[0, 0, 20, 20], [100, 100, 130, 130]]
    # one sign detected; a candidate on the other sign (read as a code at 0.8) and one on nothing
    row = _row(two_signs, [[0, 0, 20, 20]], [[100, 100, 130, 130], [300, 300, 330, 330]], [0.3, 0.3],
               [0.2, 0.2], [[0.8, 0.2], [0.85, 0.15]])
    reads = [reader.read(row["probs"], row["cand_ids"])]
    alone = tune.score_rule([row], reads, ("code", 2.0, 0.0, 0.0, 1.0), 0.5)
    assert (alone["hits"], alone["detections"], alone["P"], alone["R"]) == (1, 1, 1.0, 0.5)
    both = tune.score_rule([row], reads, ("code", 0.8, 16.0, 0.05, 0.05), 0.5)
    assert (both["hits"], both["detections"]) == (2, 3)
    assert both["R"] == 1.0 and both["P"] == pytest.approx(2 / 3)
    for failing in (("code", 0.9, 16.0, 0.05, 0.05),   # code probability under 0.9
                    ("code", 0.8, 40.0, 0.05, 0.05),   # boxes shorter than 40 px
                    ("code", 0.8, 16.0, 0.5, 0.05),    # too little sheeting
                    ("code", 0.8, 16.0, 0.05, 0.4)):   # scored under the floor
        assert tune.score_rule([row], reads, failing, 0.5)["detections"] == 1
    sign = tune.score_rule([row], reads, ("sign", 0.8, 16.0, 0.05, 0.05), 0.5)  # 1 - P(other) >= 0.8
    assert (sign["hits"], sign["detections"]) == (2, 3)



def test_a_rule_gates_small_candidates_as_the_plugin_does():
    """score_rule's size and colour checks are rescue.worth_reading's: a candidate under the
    plugin's ``small_box_px`` is kept only from ``small_min_score``, whatever the rule's side."""
    reader = tune.Reader(other=1, column_class=[0, -2], n_classes=6)
    rule = ("code", 0.8, 12.0, 0.05, 0.05)
    small = bd.rescue_mod.DEFAULT_RULE.small_min_score

    def kept(score):
        row = _row([[100, 100, 114, 114]], [], [[100, 100, 114, 114]], [score], [0.5], [[0.95, 0.05]])
        return tune.score_rule([row], [reader.read(row["probs"], row["cand_ids"])], rule, 0.5)["hits"]
    assert kept(small - 0.05) == 0 and kept(small + 0.05) == 1


def test_a_class_rule_adds_up_the_codes_of_a_class():
    """Two codes of class 2 (a speed limit whose digits are unsure) read 0.5 and 0.45: no code
    reaches 0.8, their class does (0.95) and is the class given; a crop read as other is not
    kept by either."""
    reader = tune.Reader(other=2, column_class=[2, 2, -2], n_classes=6)
    sign = [[100, 100, 130, 130]]
    row = _row(sign, [], [[100, 100, 130, 130], [300, 300, 330, 330]], [0.3, 0.3], [0.2, 0.2],
               [[0.5, 0.45, 0.05], [0.1, 0.1, 0.8]])
    row["classes"] = np.array([2])
    read = reader.read(row["probs"], row["cand_ids"])
    assert read["code"][0] == pytest.approx([0.5, 0.0]) and read["class"][0] == pytest.approx([0.95, 0.2])
    assert read["class"][1].tolist() == [2, 2]
    code = tune.score_rule([row], [read], ("code", 0.8, 16.0, 0.05, 0.05), 0.5)
    klass = tune.score_rule([row], [read], ("class", 0.8, 16.0, 0.05, 0.05), 0.5)
    assert (code["hits"], code["detections"]) == (0, 0)
    assert (klass["hits"], klass["detections"], klass["P"]) == (1, 1, 1.0)

def test_photo_candidates_are_merged_across_classes_best_first_and_off_the_detections():
    boxes = np.array([[0, 0, 20, 20],      # a detection
                      [2, 2, 22, 22],      # on the detection: no candidate
                      [100, 0, 120, 20],   # a candidate
                      [101, 1, 121, 21],   # on the better candidate: merged into it
                      [200, 0, 220, 20],   # a candidate
                      [300, 0, 320, 20]], float)  # under the floor
    scores = np.array([0.9, 0.3, 0.2, 0.3, 0.1, 0.01])
    sure, cands = bd.photo_candidates(boxes, scores, confidence=0.5, floor=0.05)
    assert sure.tolist() == [True, False, False, False, False, False]
    assert cands.tolist() == [3, 4]
    _, higher = bd.photo_candidates(boxes, scores, confidence=0.5, floor=0.15)
    assert higher.tolist() == [3]
    _, default = bd.photo_candidates(boxes, scores, confidence=0.5)   # the plugin's floor
    floor = bd.rescue_mod.DEFAULT_RESCUE_CONFIDENCE
    assert default.tolist() == [j for j in (3, 4) if scores[j] >= floor]


def test_photo_scales_are_the_view_densities_against_a_4096_px_panorama():
    panorama = bd.panorama_mod
    ring = panorama.ViewSet.default(size_px=(640, 384), upward=False, fore_aft=False)
    native_px_per_deg = bd.REFERENCE_PANORAMA_PX / 360.0
    centre_px_per_deg = 320.0 / np.tan(np.radians(40.0)) * np.pi / 180.0   # the 80 deg views' centres
    assert bd.view_scales(ring) == (round(centre_px_per_deg / native_px_per_deg, 2),) == (0.59,)
    assert bd.parse_scales("views:horizon", (640, 384)) == (0.59,)
    fore_aft = bd.parse_scales("views:horizon+fore-aft", (640, 384))
    assert len(fore_aft) == 2 and fore_aft[0] == 0.59 and 0.95 < fore_aft[1] < 1.05
    assert bd.parse_scales("1") == (1.0,) and bd.parse_scales("0.7+1.05") == (0.7, 1.05)
    for bad in ("0", "0.7+-1", "x"):
        with pytest.raises(ValueError):
            bd.parse_scales(bad)


@pytest.fixture(scope="module")
def detector():
    return bd.detector_mod.Detector(os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx"), threads=2)


def test_a_photograph_detected_at_several_scales_gives_its_boxes_in_its_own_pixels(detector):
    image, gt, classes, *_ = next(bd.gtsdb_frames(ids=[FRAME_IDS[0]]))
    h, w = image.shape[:2]
    one = bd.detect_scaled(detector, image, 0.05)
    sure = one[1] >= 0.5
    assert sure.any()
    # the same pass twice: every box comes back once, the same box, class and score
    twice = bd.detect_scaled(detector, image, 0.05, (1.0, 1.0))
    assert len(twice[0]) <= len(one[0])
    for box, score, cls in zip(one[0][sure], one[1][sure], one[2][sure]):
        same = (iou_matrix(box[None], twice[0])[0] > 0.99) & (twice[2] == cls)
        assert same.any() and twice[1][same].max() == pytest.approx(score)
    # at twice the density the signs found are found again, in the photograph's pixels
    big = bd.detect_scaled(detector, image, 0.05, (2.0,))
    assert big[0][:, [0, 2]].max() <= w + 1 and big[0][:, [1, 3]].max() <= h + 1
    found = gt[iou_matrix(gt, one[0][sure]).max(axis=1) >= 0.5]
    assert len(found) and (iou_matrix(found, big[0][big[1] >= 0.5]).max(axis=1) >= 0.5).all()


def test_the_unlabelled_signs_are_in_the_heldout_frames_and_on_no_labelled_sign():
    ids = sorted(bd.GTSDB_UNLABELLED_SIGNS)
    assert set(ids) <= set(bd.GTSDB_HELDOUT_IDS)
    frames = list(bd.gtsdb_frames(ids=ids))
    for frame_id, frame in zip(ids, frames):
        np.testing.assert_array_equal(frame.unlabelled, np.array(bd.GTSDB_UNLABELLED_SIGNS[frame_id], np.float32))
        assert frame.ignored.shape == (0, 4)
        h, w = frame.image.shape[:2]
        u = frame.unlabelled
        assert np.all((u[:, 0] < u[:, 2]) & (u[:, 1] < u[:, 3]) & (u[:, 2] <= w) & (u[:, 3] <= h))
        if len(frame.boxes):
            assert iou_matrix(u, frame.boxes).max() < 0.1   # a sign the truth leaves out, not one it has
    # frames not in the table have none
    assert all(len(f.unlabelled) == 0 for f in bd.gtsdb_frames(ids=[i for i in FRAME_IDS
                                                                      if i not in bd.GTSDB_UNLABELLED_SIGNS]))


def test_a_box_on_an_unlabelled_sign_is_ignored_and_a_false_alarm_only_as_labelled():
    from devtools.train.metrics import summarise

    frame = next(bd.gtsdb_frames(ids=[516]))
    assert len(frame.boxes) == 1 and len(frame.unlabelled) == 2
    no_entry = frame.unlabelled[1]
    assert no_entry[3] - no_entry[1] < bd.MIN_HEIGHT_PX   # under 20 px: the >= 20 px figure as labelled counts it too
    boxes = np.stack([frame.boxes[0], no_entry])
    scores = np.array([0.9, 0.8])
    ids = np.array([frame.classes[0], frame.classes[0]])
    m = bd.match_frame(boxes, scores, ids, frame)
    p = {k: summarise([v], bd.CLASSES, 0.5)["all"] for k, v in m.items()}
    assert p["all"]["precision"] == 1.0 and p["all"]["recall"] == 1.0
    assert p["20"]["precision"] == 1.0
    assert p["all_labelled"]["precision"] == 0.5 and p["all_labelled"]["recall"] == 1.0
    assert p["20_labelled"]["precision"] == 0.5
    # a box on nothing is a false alarm both ways
    m = bd.match_frame(np.array([[10.0, 10.0, 40.0, 40.0]]), np.array([0.9]), ids[:1], frame)
    assert all(summarise([v], bd.CLASSES, 0.5)["all"]["precision"] == 0.0 for v in m.values())


def test_sign_kinds_name_the_mount_oblique_views_and_gantries_above_the_views():
    """bench_detector.sign_kinds: a pole sign seen face-on is a pole sign; seen 80 deg off its
    face also oblique; a gantry panel whose box top is above the views' top elevation also
    "gantry above the views" (2048 px panorama: 1024 rows over 180 deg)."""
    pole = {"mount": "pole", "centre": [10.0, 0.0, 2.0], "normal": [-1.0, 0.0, 0.0]}
    seen = {"visible_box": [0, 500, 10, 520]}   # rows 500: elevation 2.1 deg
    assert bd.sign_kinds(pole, seen, [0.0, 0.0, 2.0], 2048, 26.7) == ["pole"]
    off = np.radians(80.0)
    edge_on = dict(pole, normal=[-np.cos(off), np.sin(off), 0.0])
    assert bd.sign_kinds(edge_on, seen, [0.0, 0.0, 2.0], 2048, 26.7) == ["pole", "oblique"]
    gantry = dict(pole, mount="gantry")
    high = {"visible_box": [0, 300, 10, 420]}   # rows 300: elevation 37.3 deg
    assert bd.sign_kinds(gantry, high, [0.0, 0.0, 2.0], 2048, 26.7) == ["gantry", "gantry above the views"]
    assert bd.sign_kinds(gantry, seen, [0.0, 0.0, 2.0], 2048, 26.7) == ["gantry"]
    assert bd.sign_kinds(pole, high, [0.0, 0.0, 2.0], 2048, 26.7) == ["pole"]   # only gantries


def test_reportable_signs_leave_out_slivers_and_oblique_views_only():
    """bench_detector.reportable_signs: a sign whose visible box is narrower (or lower) than
    MIN_SIZE, or that is seen oblique, cannot come out of detectsigns from that panorama; a
    sign of MIN_SIZE and more seen face-on can."""
    rows = np.array([[0, 0, 20, 40] + [0, 0, 20, 40],      # face-on, 20 x 40 px: reportable
                     [0, 0, 10, 90] + [0, 0, 10, 90],      # a sliver 10 px wide
                     [0, 0, 14, 14] + [0, 0, 14, 14],      # exactly MIN_SIZE
                     [0, 0, 30, 30] + [0, 0, 30, 30]], float)  # wide enough but oblique
    kinds = [["pole"], ["pole"], ["shared_pole"], ["pole", "oblique"]]
    assert bd.reportable_signs(rows, kinds, 14.0).tolist() == [True, False, True, False]
    assert bd.reportable_signs(rows, kinds, 25.0).tolist() == [False, False, False, False]
    assert bd.reportable_signs(np.zeros((0, 8)), [], 14.0).tolist() == []
