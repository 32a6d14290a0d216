"""Hard negatives mined from GTSDB's training frames (devtools/train/mine.py): which boxes
count as false alarms, the reviewed file's three parts, and how training frames take them."""
import json

import numpy as np
import pytest

from devtools.train import data, mine

GTSDB_FRAME_PX = (1360, 800)


def test_false_alarms_leave_out_boxes_on_truth_and_under_the_threshold():
    truth = np.array([[100, 100, 140, 140]], np.float32)
    boxes = np.array([[102, 101, 141, 139],     # on the sign
                      [500, 300, 530, 330],     # off it, scored high
                      [600, 300, 630, 330],     # off it, under the threshold
                      [135, 135, 175, 175]],    # touches the sign (IoU < 0.1)
                     np.float32)
    rows = mine.false_alarms(boxes, np.array([0.9, 0.5, 0.2, 0.7]), np.array([1, 2, 3, 0]), truth, 0.3)
    assert [r[:4] for r in rows] == [[135, 135, 175, 175], [500, 300, 530, 330]]
    assert [r[4] for r in rows] == pytest.approx([0.7, 0.5])
    assert [r[5] for r in rows] == [0, 2]


def test_false_alarms_without_truth_keep_every_box_over_the_threshold():
    rows = mine.false_alarms(np.array([[0, 0, 10, 10], [5, 5, 20, 20]], np.float32), np.array([0.4, 0.6]),
                             np.array([1, 1]), np.zeros((0, 4), np.float32), 0.5)
    assert len(rows) == 1 and rows[0][4] == pytest.approx(0.6)


def test_review_is_parsed_and_checked():
    named, ignored = mine.parse_review("3:information, 9:prohibitory", "4,7")
    assert named == {3: "information", 9: "prohibitory"} and ignored == {4, 7}
    with pytest.raises(ValueError, match="CLASS one of"):
        mine.parse_review("3:parking", "")
    with pytest.raises(ValueError, match=r"both in --signs and --ignore: \[4\]"):
        mine.parse_review("4:information", "4")


def test_label_frames_adds_signs_and_ignore_regions():
    rows = [("a.jpg", np.array([[1, 1, 20, 20]], np.float32), np.array([0])),
            ("b.jpg", np.zeros((0, 4), np.float32), np.zeros(0, np.int64))]
    sign = np.array([50, 50, 80, 80], np.float32)
    out = mine.label_frames(rows, [10, 11], {11: [(sign, data.CLASS_INDEX["information"])]},
                            {10: [np.array([5, 5, 9, 9], np.float32)]})
    assert out[0][1].tolist() == [[1, 1, 20, 20]] and out[0][2].tolist() == [0]
    assert out[0][3].tolist() == [[5, 5, 9, 9]]
    assert out[1][1].tolist() == [sign.tolist()] and out[1][2].tolist() == [data.CLASS_INDEX["information"]]
    assert out[1][3].shape == (0, 4)


def test_review_round_trip_partitions_every_mined_box(tmp_path):
    raw = {"3": [[10, 10, 40, 40, 0.8, 3], [100, 10, 130, 40, 0.4, 1]], "7": [[200, 200, 230, 230, 0.5, 2]]}
    cache = tmp_path / "raw.json"
    cache.write_text(json.dumps(raw))
    out = tmp_path / "mined.json"
    # numbers: frame 3 first (0, 1), then frame 7 (2)
    assert mine.main(["--model", "unused.onnx", "--cache", str(cache), "--out", str(out),
                      "--signs", "0:information", "--ignore", "2"]) == 0
    false_alarms, signs, ignored = mine.read_mined(str(out))
    assert {k: [b.tolist() for b in v] for k, v in false_alarms.items()} == {3: [[100, 10, 130, 40]]}
    assert [(b.tolist(), c) for b, c in signs[3]] == [([10, 10, 40, 40], data.CLASS_INDEX["information"])]
    assert {k: [b.tolist() for b in v] for k, v in ignored.items()} == {7: [[200, 200, 230, 230]]}
    assert json.loads(out.read_text())["counts"] == {"false_alarms": 1, "unlabelled_signs": 1, "ignored": 1}
    assert not (tmp_path / "mined.json.tmp").exists()


def test_missing_file_reads_as_nothing(tmp_path):
    assert mine.read_mined(str(tmp_path / "none.json")) == ({}, {}, {})


def test_committed_review_is_consistent():
    """The list training reads: training frames only, boxes inside the frame, the counts it
    states, and no box both a false alarm and a sign."""
    with open(mine.MINED_PATH) as f:
        doc = json.load(f)
    false_alarms, signs, ignored = mine.read_mined()
    assert doc["counts"] == {"false_alarms": sum(map(len, false_alarms.values())),
                             "unlabelled_signs": sum(map(len, signs.values())),
                             "ignored": sum(map(len, ignored.values()))}
    assert doc["counts"]["false_alarms"] > 0 and doc["counts"]["unlabelled_signs"] > 0
    w, h = GTSDB_FRAME_PX
    every = [(f, b) for part in (false_alarms, ignored) for f, v in part.items() for b in v]
    every += [(f, b) for f, v in signs.items() for b, _ in v]
    for frame_id, box in every:
        assert frame_id in data.GTSDB_TRAIN_IDS
        assert 0 <= box[0] < box[2] <= w + 1 and 0 <= box[1] < box[3] <= h + 1
    for frame_id, v in signs.items():
        for box, _ in v:
            others = np.array(false_alarms.get(frame_id, []), np.float32).reshape(-1, 4)
            assert not any(np.allclose(box, o) for o in others)


def test_contact_sheet_numbers_every_box(tmp_path):
    import cv2

    raw = {"0": [[100, 100, 140, 140, 0.5, 1]], "1": [[200, 200, 260, 250, 0.4, 3], [10, 10, 30, 30, 0.3, 0]]}
    path = str(tmp_path / "sheet.png")
    assert mine.contact_sheet(raw, path, cell_px=64, columns=2) == 3
    sheet = cv2.imread(path)
    assert sheet.shape == (2 * (64 + 14), 2 * 64, 3)
    assert sheet[64 + 14:2 * 64 + 14, 64:].min() == 255   # the fourth cell stays empty
    assert sheet[64 + 14:2 * 64 + 14, :64].std() > 0   # the third holds a crop
