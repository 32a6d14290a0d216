"""The second look (core.rescue): boxes the detector scores under its confidence are kept
when the sign-code classifier reads a class of signs in them (the class's codes added up;
and they are big and coloured enough);
the detections themselves stay as they were. The classifier is the tiny real ONNX model of
tests/helpers/tinyclassifier.py (red crop: DE:206 stop, blue: DE:215 roundabout, grey: other)."""
from dataclasses import replace

import cv2
import numpy as np
import pytest
from helpers.synthpano import paint_discs
from helpers.tinyclassifier import make_classifier

from roadsigns.core import detector as DT  # noqa: N812 (the tests' short module names)
from roadsigns.core import rescue
from roadsigns.core import signcodes as SC  # noqa: N812
from roadsigns.core.panorama import ViewSet

RED, BLUE, DARK = (30, 30, 230), (230, 40, 30), (40, 40, 40)  # BGR
CLASSES = ("warning", "prohibitory", "mandatory", "information", "stop", "yield")
TABLE_TEXT = "code;name;class\nDE:206;stop;stop\nDE:215;roundabout;mandatory\n"
#: the tiny classifier's probabilities on a disc's crop are ~0.7: the rule's bar is set under them
RULE = rescue.RescueRule(min_class_score=0.6, min_box_px=16.0, min_sheeting=0.05)


@pytest.fixture(scope="module")
def classifier(tmp_path_factory):
    path = tmp_path_factory.mktemp("table") / "codes.csv"
    path.write_text(TABLE_TEXT)
    table = SC.read_codes_table(str(path))
    return SC.CodeClassifier(make_classifier(tmp_path_factory.mktemp("clf") / "c.onnx"), table)


class ColourBlobDetector:
    """Boxes the blobs of each colour in a view: red ones sure (0.9, class stop), blue and dark
    ones low (0.2, class stop: the detector's class is wrong for blue)."""
    class_names = list(CLASSES)
    SCORES = {RED: 0.9, BLUE: 0.2, DARK: 0.2}

    def detect(self, image, confidence, iou_threshold):
        boxes, scores = [], []
        for colour, score in self.SCORES.items():
            mask = np.all(np.abs(image.astype(int) - colour) < 25, axis=2).astype(np.uint8)
            n, _, stats, _ = cv2.connectedComponentsWithStats(mask)
            for x, y, w, h, area in stats[1:]:
                if area >= 4 and score >= confidence:
                    boxes.append([x, y, x + w, y + h])
                    scores.append(score)
        return DT.ImageDetections(np.array(boxes, float).reshape(-1, 4), np.array(scores, float),
                                  np.full(len(scores), CLASSES.index("stop"), np.int64))


def _panorama(width=1024):
    # red (sure), big blue (read as a roundabout), dark grey (other), small blue (under 16 px)
    return paint_discs([(0.0, 0.0, 4.0, RED), (90.0, 0.0, 4.0, BLUE), (-90.0, 0.0, 4.0, DARK),
                        (45.0, 0.0, 1.2, BLUE)], width)


def test_the_rule_needs_size_colour_and_a_confident_class():
    boxes = np.array([[0, 0, 20, 20], [0, 0, 15, 40], [0, 0, 20, 20]], float)
    np.testing.assert_array_equal(rescue.worth_reading(boxes, [0.5, 0.5, 0.01], [0.3, 0.3, 0.3], RULE),
                                  [True, False, False])
    np.testing.assert_array_equal(rescue.confirmed([0.95, 0.9, 0.89, 0.0, np.nan]),
                                  [True, True, False, False, False])


def test_the_class_reading_adds_up_the_codes_of_each_class(tmp_path):
    """Two speed limits of one class, unsure of the digits, make a sure class; ``other`` is
    no class; codes of a class the detector lacks (here warning) add up apart and leave the
    detector's class (-1)."""
    path = tmp_path / "codes.csv"
    path.write_text("code;name;class\nDE:274[30];30;prohibitory\nDE:274[50];50;prohibitory\n"
                    "DE:206;stop;stop\nDE:101;danger;warning\n")
    table = SC.read_codes_table(str(path))
    names = ["DE:274[30]", "DE:274[50]", "DE:206", "DE:101", "other"]
    detector_classes = ("prohibitory", "stop")
    probs = np.array([[0.45, 0.47, 0.03, 0.0, 0.05],    # an unsure speed limit: prohibitory, 0.92
                      [0.1, 0.1, 0.1, 0.0, 0.7],        # other wins: the best class is prohibitory, 0.2
                      [0.0, 0.0, 0.05, 0.9, 0.05]])     # a code of a class the detector lacks
    columns = rescue.code_classes(names, table, detector_classes)
    assert columns.tolist() == [0, 0, 1, rescue.UNMAPPED_COLUMN, rescue.OTHER_COLUMN]
    best, score = rescue.class_reading(probs, columns, len(detector_classes))
    assert best.tolist() == [0, 0, -1]
    np.testing.assert_allclose(score, [0.92, 0.2, 0.9])
    assert rescue.confirmed(score).tolist() == [True, False, True]
    assert rescue.class_reading(np.zeros((0, 5)), columns, len(detector_classes))[0].tolist() == []


def test_a_sign_whose_code_the_table_lacks_counts_for_its_class(tmp_path):
    """A foreign no-parking sign read as ``unlisted:prohibitory`` adds to the prohibitory
    codes; ``unlisted:`` of a class the detector lacks adds up apart, like such a code."""
    path = tmp_path / "codes.csv"
    path.write_text("code;name;class\nDE:274[30];30;prohibitory\nDE:206;stop;stop\n")
    table = SC.read_codes_table(str(path))
    names = ["DE:274[30]", "DE:206", SC.unlisted_code("prohibitory"), SC.unlisted_code("warning"), "other"]
    detector_classes = ("prohibitory", "stop")
    columns = rescue.code_classes(names, table, detector_classes)
    assert columns.tolist() == [0, 1, 0, rescue.UNMAPPED_COLUMN, rescue.OTHER_COLUMN]
    probs = np.array([[0.05, 0.0, 0.9, 0.0, 0.05],     # a prohibitory sign without a code
                      [0.0, 0.0, 0.05, 0.05, 0.9]])    # a look-alike
    best, score = rescue.class_reading(probs, columns, len(detector_classes))
    assert best.tolist() == [0, 0] and rescue.confirmed(score).tolist() == [True, False]
    np.testing.assert_allclose(score, [0.95, 0.05])


def test_class_of_a_code(classifier):
    assert rescue.class_of_code("DE:215", classifier.table, CLASSES) == "mandatory"
    assert rescue.class_of_code("DE:215", classifier.table, ["sign"]) is None   # a detector without it
    assert rescue.class_of_code("DE:999", classifier.table, CLASSES) is None
    assert rescue.class_of_code("DE:206", None, CLASSES) is None


def test_candidates_leave_the_detections_as_they_were():
    pano = _panorama()
    views = ViewSet.default(size_px=128, upward=False)
    plain = DT.detect_panorama(ColourBlobDetector(), pano, views, 0.5)
    both = DT.detect_panorama(ColourBlobDetector(), pano, views, 0.5, candidate_confidence=0.1)
    assert len(plain) == 1 and not plain.candidate.any()
    sure = both.subset(~both.candidate)
    for name in ("class_id", "score", "u0", "v0", "u1", "v1", "view_index", "n_views"):
        np.testing.assert_array_equal(getattr(sure, name), getattr(plain, name))
    cands = both.subset(both.candidate)
    assert len(cands) == 3  # blue, dark, small blue: each once, merged across overlapping views
    centres = ((cands.u0 + cands.u1) / 2) % 1024
    np.testing.assert_allclose(np.sort(centres), [256.0, 640.0, 768.0], atol=3.0)
    # a low box on a detection (another class) is no candidate
    over = DT.detect_panorama(ColourBlobDetector(), paint_discs([(0.0, 0.0, 4.0, RED)], 1024), views, 0.5,
                              candidate_confidence=0.1)
    assert not over.candidate.any()
    # a panorama with low boxes only: candidates only
    low_only = DT.detect_panorama(ColourBlobDetector(), paint_discs([(90.0, 0.0, 4.0, BLUE)], 1024), views, 0.5,
                                  candidate_confidence=0.1)
    assert len(low_only) == 1 and low_only.candidate.all()


def test_second_look_keeps_the_read_candidates_with_their_codes_class(tmp_path, classifier):
    path = str(tmp_path / "p.png")
    cv2.imwrite(path, _panorama())
    views = ViewSet.default(size_px=128, upward=False)
    read = []

    class Counting:
        table, crop_margin = classifier.table, classifier.crop_margin

        def cut_crop(self, pano, box):
            return classifier.cut_crop(pano, box)

        names = classifier.names

        def probabilities(self, crops):
            read.append(len(crops))
            return classifier.probabilities(crops)

    def look(pano, found):
        return rescue.second_look(Counting(), pano, found, CLASSES, RULE)

    drive = DT.detect_drive(ColourBlobDetector(), [path], views, 0.5, on_panorama=look, candidate_confidence=0.1)
    found = drive.per_image[0]
    assert read == [2]  # the red detection and the big blue candidate; the dark one (no sign colours)
    # and the small one (under 16 px) are dropped unread
    assert found.class_name == ["stop", "mandatory"] and found.code == ["DE:206", "DE:215"]
    np.testing.assert_allclose(found.score, [0.9, 0.2])   # the candidate keeps its own score
    assert found.class_id[1] == CLASSES.index("mandatory") and not found.candidate.any()
    # with a stricter bar the blue candidate is not kept; without a second look none is
    strict = DT.detect_drive(ColourBlobDetector(), [path], views, 0.5, candidate_confidence=0.1,
                             on_panorama=lambda p, f: rescue.second_look(classifier, p, f, CLASSES))
    assert strict.per_image[0].class_name == ["stop"]
    bare = DT.detect_drive(ColourBlobDetector(), [path], views, 0.5, candidate_confidence=0.1)
    assert bare.per_image[0].class_name == ["stop"] and not bare.per_image[0].candidate.any()


def test_a_box_an_upward_view_found_alone_and_read_other_is_dropped(classifier):
    """The upward views look over the road for panels overhead; beside it they may box a
    facade's dark window. What one of them boxed alone and the classifier reads ``other`` is
    dropped; what it reads as a sign stays, and so does a box read ``other`` that a horizon
    view found (a sign whose legend the table lacks reads ``other`` too)."""
    class SureBlobs(ColourBlobDetector):
        SCORES = {RED: 0.9, BLUE: 0.9, DARK: 0.9}

    horizon = ViewSet.ring(8, 0.0, 80.0, (320, 192))          # up to +26.7 deg
    views = horizon + ViewSet.ring(2, 35.0, 90.0, (320, 192))
    # overhead: red (a sign) ahead, dark (a window) behind; on the horizon: dark at the side;
    # red at 20 deg yaw, 22 deg up: seen by a horizon view and an upward one
    pano = paint_discs([(0.0, 42.0, 4.0, RED), (180.0, 42.0, 4.0, DARK), (-90.0, 0.0, 4.0, DARK),
                        (20.0, 22.0, 3.0, RED)], 2048)
    found = DT.detect_panorama(SureBlobs(), pano, views, 0.5)
    assert len(found) == 4
    yaw_deg = (((found.u0 + found.u1) / 2 / 2048) * 360.0 - 180.0).round()
    by_yaw = {int(y): k for k, y in enumerate(yaw_deg)}
    assert sorted(by_yaw) == [-90, 0, 20, 180]
    assert [bool(found.lone_upward[by_yaw[y]]) for y in (-90, 0, 20, 180)] == [False, True, False, True]
    assert found.n_views[by_yaw[20]] >= 2                      # horizon views boxed it too

    def codes_by_yaw(rule):
        copy = found.subset(np.arange(len(found)))      # second_look sets the codes in place
        kept = rescue.second_look(classifier, pano, copy, CLASSES, rule)
        yaws = (((kept.u0 + kept.u1) / 2 / 2048) * 360.0 - 180.0).round().astype(int)
        return dict(zip(yaws.tolist(), kept.code))

    assert codes_by_yaw(RULE) == {-90: "other", 0: "DE:206", 20: "DE:206"}
    assert codes_by_yaw(replace(RULE, drop_lone_upward_other=False)) == {
        -90: "other", 0: "DE:206", 20: "DE:206", 180: "other"}


def test_a_small_candidate_needs_a_higher_detector_score():
    """Under ``small_box_px`` on its shorter side a candidate is read only when the detector
    scored it at least ``small_min_score``; under ``min_box_px`` never; from ``small_box_px``
    up the score plays no part."""
    rule = rescue.RescueRule(min_box_px=12.0, small_box_px=16.0, small_min_score=0.35)
    boxes = np.array([[0, 0, 14, 20],    # small, scored high enough
                      [0, 0, 14, 20],    # small, scored low
                      [0, 0, 11, 20],    # under min_box_px, scored high
                      [0, 0, 16, 16],    # not small, scored low
                      [0, 0, 12, 30]], float)  # exactly min_box_px, scored at the floor
    scores = [0.4, 0.3, 0.45, 0.2, 0.35]
    np.testing.assert_array_equal(rescue.worth_reading(boxes, np.full(5, 0.5), scores, rule),
                                  [True, False, False, True, True])


class WideSliverDetector:
    """Boxes the red pixels of a view three times as wide as they are, scored 0.3 (a candidate
    at confidence 0.5), as the network boxes a sign seen edge-on."""
    class_names = list(CLASSES)

    def detect(self, image, confidence, iou_threshold):
        rows, cols = np.nonzero(np.all(image == RED, axis=2))
        if len(cols) < 4 or confidence > 0.3:
            return DT.ImageDetections(np.zeros((0, 4)), np.zeros(0), np.zeros(0, np.int64))
        u0, u1, w = cols.min(), cols.max() + 1, cols.max() + 1 - cols.min()
        box = [[u0 - w, rows.min(), u1 + w, rows.max() + 1]]
        return DT.ImageDetections(np.array(box, float), np.array([0.3]), np.array([CLASSES.index("stop")]))


def test_a_candidate_is_judged_on_the_networks_box_and_read_and_kept_fitted(classifier):
    """A sign seen edge-on: the network's box is about three times the face's 12 px. Fitted
    before the second look it would fall under the rule's small-box floor; judged on the
    network's box it is read and kept, fitted like a detection. (The tiny classifier reads colour
    shares, and the wide box is mostly wall: here it reads what the real one reads on such a
    sign, the stop code, so that the test is of the boxes.)"""

    class ReadsStop:
        names, table, crop_margin = classifier.names, classifier.table, classifier.crop_margin

        def cut_crop(self, pano, box):
            return classifier.cut_crop(pano, box)

        def probabilities(self, crops):
            return np.tile(np.array([[0.95, 0.0, 0.05]]), (len(crops), 1))

    pano = np.full((1024, 2048, 3), (120, 120, 120), np.uint8)
    pano[450:560, 1020:1032] = RED
    views = ViewSet.default(size_px=256, upward=False)
    found = DT.detect_panorama(WideSliverDetector(), pano, views, 0.5, candidate_confidence=0.2)
    assert len(found) == 1 and found.candidate[0]
    assert found.u1[0] - found.u0[0] > 30          # a candidate keeps the network's box
    rule = replace(RULE, min_box_px=12.0, small_box_px=16.0, small_min_score=0.35)
    kept = rescue.second_look(ReadsStop(), pano, found, CLASSES, rule)
    assert len(kept) == 1 and not kept.candidate.any() and kept.code == ["DE:206"]
    np.testing.assert_allclose([kept.u0[0], kept.u1[0]], [1020, 1032], atol=1)
    # unfitted (the bench's "--fit-tall off") the kept box stays the network's
    wide = DT.detect_panorama(WideSliverDetector(), pano, views, 0.5, candidate_confidence=0.2, fit_tall=False)
    loose = rescue.second_look(ReadsStop(), pano, wide, CLASSES, rule, fit_tall=False)
    assert len(loose) == 1 and loose.u1[0] - loose.u0[0] > 30
    # fitted first (as before), the candidate is 12 px wide and scored 0.3: under the floor
    fitted_first = DT.fit_tall_boxes(pano, DT.detect_panorama(WideSliverDetector(), pano, views, 0.5,
                                                              candidate_confidence=0.2, fit_tall=False))
    assert len(rescue.second_look(ReadsStop(), pano, fitted_first, CLASSES, rule)) == 0


GREEN = (40, 200, 40)  # BGR: what the classifier with a ``back`` name reads as the back of a sign


def test_a_detection_read_as_the_back_of_a_sign_is_dropped(tmp_path, classifier):
    """A sure detection whose crop reads ``back`` (the classifier's name for a sign's plain
    back, :data:`.signcodes.BACK_CODE`) is dropped; a sure one read as a sign stays. A weak
    ``back`` reading (under ``min_back_score``) keeps the box, and so does a rule without
    ``drop_backs``. ``back`` confirms no candidate: it counts for no class."""
    names = ("DE:206", "DE:215", SC.BACK_CODE, "other")
    weights = np.array([[10.0, 0.0, 0.0, 0.0],      # R -> stop
                        [0.0, 0.0, 10.0, 0.0],      # G -> back
                        [0.0, 10.0, 0.0, 0.0]])     # B -> roundabout
    with_back = SC.CodeClassifier(make_classifier(tmp_path / "back.onnx", names=names, weights=weights,
                                                  bias=np.array([0.0, 0.0, 0.0, 5.0])), classifier.table)

    class SureBlobs(ColourBlobDetector):
        SCORES = {RED: 0.9, GREEN: 0.9, BLUE: 0.2}

    views = ViewSet.ring(8, 0.0, 80.0, (320, 192))
    pano = paint_discs([(0.0, 0.0, 4.0, RED), (90.0, 0.0, 4.0, GREEN), (-90.0, 0.0, 4.0, BLUE)], 2048)
    found = DT.detect_panorama(SureBlobs(), pano, views, 0.5, candidate_confidence=0.1)
    assert len(found) == 3 and found.candidate.sum() == 1

    def codes_by_yaw(rule):
        copy = found.subset(np.arange(len(found)))      # second_look sets the codes in place
        kept = rescue.second_look(with_back, pano, copy, CLASSES, rule)
        yaws = (((kept.u0 + kept.u1) / 2 / 2048) * 360.0 - 180.0).round().astype(int)
        return dict(zip(yaws.tolist(), kept.code))

    assert RULE.drop_backs
    assert codes_by_yaw(RULE) == {0: "DE:206", -90: "DE:215"}
    assert codes_by_yaw(replace(RULE, drop_backs=False)) == {0: "DE:206", 90: SC.BACK_CODE, -90: "DE:215"}
    back_probability = with_back.probabilities([with_back.cut_crop(pano, found.boxes()[k]) for k in range(3)])[:, 2]
    assert 0.5 < back_probability.max() < 0.99
    assert codes_by_yaw(replace(RULE, min_back_score=0.99)) == {0: "DE:206", 90: SC.BACK_CODE, -90: "DE:215"}
    columns = rescue.code_classes(names, classifier.table, CLASSES)
    assert columns[2] == columns[3] == rescue.OTHER_COLUMN
