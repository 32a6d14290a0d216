"""The ONNX detector: decoders on tiny models built here with onnx.helper, letterboxing,
NMS, class names, errors; merging across views and a sign across the +-180 deg seam.

The tiny models (``helpers.tinyonnx``) output a constant tensor: the decoders see exactly
the candidates written here.
"""
import os

import cv2
import numpy as np
import pytest
from helpers.synthpano import disc_pano_box, paint_discs
from helpers.tinyonnx import make_model

from devtools import REPO_ROOT
from roadsigns.core import detector as det
from roadsigns.core import geometry
from roadsigns.core.detector import Detector, ImageDetections, detect_panorama, merge_view_detections
from roadsigns.core.errors import InputError
from roadsigns.core.panorama import ViewSet

NAMES2 = "{0: 'warning', 1: 'stop'}"  # as Ultralytics writes metadata


def v8_output(rows):
    """Candidates (cx, cy, w, h, score_0, ..., score_nc-1) -> [1, 4+nc, N]."""
    return np.asarray(rows, np.float32).T[None]


V8_ROWS = [[20, 20, 10, 10, 0.9, 0.1],    # warning
           [21, 20, 10, 10, 0.8, 0.05],   # duplicate of the first: removed by NMS
           [40, 30, 8, 12, 0.1, 0.7],     # stop
           [50, 50, 6, 6, 0.1, 0.2],      # below the confidence
           [20, 20, 10, 10, 0.1, 0.6]]    # same box, other class: kept (per-class NMS)


def xyxy(cx, cy, w, h):
    return [cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2]


def image(w=64, h=64):
    return np.zeros((h, w, 3), np.uint8)


def test_yolov8_layout(tmp_path):
    d = Detector(make_model(tmp_path / "v8.onnx", v8_output(V8_ROWS), meta={"names": NAMES2}))
    assert (d.layout, d.class_names, d.names_source) == ("yolov8", ["warning", "stop"], "metadata")
    assert d.input_size == (64, 64)
    found = d.detect(image(), confidence=0.25)
    assert found.scores.tolist() == pytest.approx([0.9, 0.7, 0.6])
    assert found.class_ids.tolist() == [0, 1, 1]
    assert found.boxes_xyxy == pytest.approx(np.array([xyxy(20, 20, 10, 10), xyxy(40, 30, 8, 12),
                                                       xyxy(20, 20, 10, 10)]))
    assert len(d.detect(image(), confidence=0.25, iou_threshold=0.99)) == 4  # no suppression


def test_sessions_do_not_spin(tmp_path):
    """onnxruntime's threads wait without spinning (core.detector.SPIN_WAIT): on two cores a
    spinning thread holds the core that decoding and cutting crops need."""
    d = Detector(make_model(tmp_path / "v8.onnx", v8_output(V8_ROWS), meta={"names": NAMES2}), threads=2)
    options = d.session.get_session_options()
    assert options.get_session_config_entry("session.intra_op.allow_spinning") == ("1" if det.SPIN_WAIT else "0")
    assert det.SPIN_WAIT is False


def test_letterbox_is_undone_on_a_wide_image(tmp_path):
    d = Detector(make_model(tmp_path / "v8.onnx", v8_output(V8_ROWS), meta={"names": NAMES2}))
    found = d.detect(image(128, 64))  # scale 0.5, 16 px of padding above and below
    want = (np.array(xyxy(40, 30, 8, 12)) - [0, 16, 0, 16]) / 0.5
    assert found.boxes_xyxy[1] == pytest.approx(want)
    assert found.boxes_xyxy[0] == pytest.approx([30, 0, 50, 18])  # clipped at the top
    boxed, transform = det.letterbox(np.full((64, 128, 3), 7, np.uint8), 64, 64)
    assert boxed.shape == (64, 64, 3) and transform == (0.5, 0.0, 16.0)
    assert (boxed[:16] == 114).all() and (boxed[16:48] == 7).all() and (boxed[48:] == 114).all()


def test_yolov5_layout_score_is_objectness_times_class(tmp_path):
    rows = np.zeros((20, 8), np.float32)  # nc = 3
    rows[0] = [30, 30, 10, 20, 0.9, 0.1, 0.8, 0.1]
    rows[1] = [10, 10, 4, 4, 0.2, 0.0, 0.0, 1.0]  # objectness below the confidence
    d = Detector(make_model(tmp_path / "v5.onnx", rows[None]), class_names=["a", "b", "c"])
    assert d.layout == "yolov5" and d.names_source == "caller"
    found = d.detect(image())
    assert found.class_ids.tolist() == [1] and found.scores.tolist() == pytest.approx([0.72])
    assert found.boxes_xyxy[0] == pytest.approx(xyxy(30, 30, 10, 20))


def test_nms_layout(tmp_path):
    rows = [[5, 6, 25, 30, 0.95, 2], [40, 40, 50, 60, 0.5, 0], [0, 0, 1, 1, 0.1, 1]]
    d = Detector(make_model(tmp_path / "nms.onnx", np.array(rows)[None]), class_names=["a", "b", "c"])
    assert d.layout == "nms"
    found = d.detect(image())
    assert found.class_ids.tolist() == [2, 0] and found.scores.tolist() == pytest.approx([0.95, 0.5])
    assert found.boxes_xyxy == pytest.approx(np.array([[5, 6, 25, 30], [40, 40, 50, 60]]))


def test_one_class_n_by_6_is_yolov5_only_for_an_anchor_grid_count(tmp_path):
    # 64 px input: 3 anchors x (8x8 + 4x4 + 2x2) = 252 candidates in a YOLOv5 head
    assert det.yolov5_anchor_counts(64, 64) >= {252}
    dense = np.zeros((252, 6), np.float32)
    dense[7] = [32, 32, 10, 10, 0.9, 0.5]
    d = Detector(make_model(tmp_path / "v5one.onnx", dense[None]), class_names=["sign"])
    assert d.layout == "yolov5"
    assert d.detect(image()).scores.tolist() == pytest.approx([0.45])
    post = np.array([[10, 10, 30, 30, 0.8, 0]], np.float32)[None]
    d = Detector(make_model(tmp_path / "nmsone.onnx", post), class_names=["sign"])
    assert d.layout == "nms"
    assert d.detect(image()).boxes_xyxy.tolist() == [[10, 10, 30, 30]]
    post = np.array([[20, 20, 10, 10, 0.9, 1.0]], np.float32)[None]  # class 1 of 1: nothing as nms
    assert len(Detector(make_model(tmp_path / "post.onnx", post), class_names=["sign"]).detect(image())) == 0
    d = Detector(make_model(tmp_path / "post.onnx", post), class_names=["sign"], layout="yolov5")
    assert d.layout == "yolov5"  # forced: read as cx, cy, w, h, objectness, class probability
    assert d.detect(image()).boxes_xyxy.tolist() == [xyxy(20, 20, 10, 10)]


def test_choose_layout_prefers_the_long_axis_as_candidates():
    assert det.choose_layout([1, 6, 8400], 2, 640, 640) == "yolov8"
    assert det.choose_layout([1, 84, 8400], 80, 640, 640) == "yolov8"
    assert det.choose_layout([1, 7, 8], 3, 640, 640) == "yolov8"  # both fit: the longer axis is N
    assert det.choose_layout([1, 300, 6], 2, 640, 640) == "nms"
    assert det.choose_layout([1, 6, 6], 2, 640, 640) == "nms"
    assert det.choose_layout([1, 25200, 85], 80, 640, 640) == "yolov5"
    assert det.choose_layout([1, 25200, 6], 1, 640, 640) == "yolov5"
    assert det.choose_layout([1, 300, 6], 1, 640, 640) == "nms"


def test_unsupported_output_shape_is_named(tmp_path):
    path = make_model(tmp_path / "odd.onnx", np.zeros((1, 9, 5)), meta={"names": NAMES2})
    with pytest.raises(InputError) as e:
        Detector(path)
    message = str(e.value)
    assert "[1, 9, 5]" in message and "odd.onnx" in message
    assert all(layout in message for layout in ("[1, 4+nc, N]", "[1, N, 5+nc]", "[1, N, 6]"))
    with pytest.raises(InputError, match="does not fit"):
        Detector(make_model(tmp_path / "v8.onnx", v8_output(V8_ROWS), meta={"names": NAMES2}),
                 layout="yolov5")


def test_class_names_from_labels_files(tmp_path):
    output = v8_output(V8_ROWS)
    path = make_model(tmp_path / "signs.onnx", output)
    (tmp_path / "labels.txt").write_text("first\nsecond\n")
    assert Detector(path).class_names == ["first", "second"]
    (tmp_path / "signs.labels.txt").write_text("warning\n\nstop\n")
    d = Detector(path)
    assert d.class_names == ["warning", "stop"] and d.names_source.endswith("signs.labels.txt")
    meta = make_model(tmp_path / "meta.onnx", output, meta={"names": "{0: 'a', 1: 'b'}"})
    assert Detector(meta).class_names == ["a", "b"]  # metadata before labels.txt
    assert Detector(meta, class_names=["x", "y"]).class_names == ["x", "y"]


def test_parse_names():
    assert det.parse_names("{0: 'warning', 1: 'stop'}") == ["warning", "stop"]
    assert det.parse_names('["a", "b"]') == ["a", "b"]
    assert det.parse_names('{"0": "a", "2": "c"}') == ["a", "class_1", "c"]
    assert det.parse_names("__import__('os').system('true')") is None
    assert det.parse_names("not names") is None


def test_model_errors(tmp_path):
    with pytest.raises(InputError, match="no labels file|names no classes"):
        Detector(make_model(tmp_path / "bare.onnx", v8_output(V8_ROWS)))
    text = tmp_path / "notes.onnx"
    text.write_text("this is not a model")
    with pytest.raises(InputError, match="notes.onnx is not an ONNX model"):
        Detector(str(text))
    with pytest.raises(InputError, match="Model not found"):
        Detector(str(tmp_path / "absent.onnx"))
    seg = make_model(tmp_path / "seg.onnx", v8_output(V8_ROWS), meta={"names": NAMES2, "task": "segment"})
    with pytest.raises(InputError, match="segment model"):
        Detector(seg)


def test_dynamic_input_size_and_batches(tmp_path):
    path = make_model(tmp_path / "dyn.onnx", v8_output(V8_ROWS), input_shape=["batch", 3, "h", "w"],
                      meta={"names": NAMES2, "imgsz": "[48, 96]"})
    assert Detector(path).max_batch == 1  # on the CPU
    d = Detector(path, max_batch=4)
    assert d.input_size == (96, 48) and d.max_batch == 4
    assert Detector(path, input_size_px=128).input_size == (128, 128)
    results = d.detect_many([image(96, 48)] * 11)
    assert len(results) == 11 and all(len(r) == 3 for r in results)
    info = det.model_info(path)
    assert info.layout == "yolov8" and "CPUExecutionProvider" in info.providers
    assert "YOLOv8/11" in info.describe()


def test_providers_preference():
    assert det.choose_providers(["AzureExecutionProvider", "CPUExecutionProvider", "CUDAExecutionProvider",
                                 "DmlExecutionProvider"]) == ["CUDAExecutionProvider", "DmlExecutionProvider",
                                                              "CPUExecutionProvider"]


# --- merging across views and the seam ---------------------------------------------------

def test_merge_prefers_complete_boxes_and_joins_cut_ones():
    W = 1000
    boxes = np.array([[100, 50, 130, 80],    # cut at a view edge, high score
                      [90, 50, 130, 80],     # complete, lower score: wins
                      [95, 50, 128, 80],     # other class: separate
                      [990, 10, 1010, 30],   # across the seam, cut
                      [2, 12, 15, 30]])      # the same sign seen wrapped, cut too
    scores = np.array([0.9, 0.6, 0.5, 0.7, 0.8])
    ids = np.array([0, 0, 1, 0, 0])
    complete = np.array([False, True, True, False, False])
    kept, merged, counts = merge_view_detections(boxes, scores, ids, complete, np.zeros(5), W)
    assert sorted(kept.tolist()) == [1, 2, 4]
    by_index = dict(zip(kept.tolist(), merged))
    assert by_index[1].tolist() == [90, 50, 130, 80]
    assert by_index[4].tolist() == [990, 10, 1015, 30]  # union across the seam, u0 < W < u1
    assert dict(zip(kept.tolist(), counts.tolist())) == {1: 2, 2: 1, 4: 2}


def test_merge_fuses_complete_boxes_by_score_across_the_seam():
    W = 1000
    boxes = np.array([[990, 20, 1010, 40],   # complete in one view, score 0.75
                      [-6, 22, 18, 42],      # the same sign, complete in the next view, 0.25
                      [996, 21, 1006, 39],   # the same sign cut by a view edge: not averaged
                      [500, 20, 520, 40]])   # another sign, alone: unchanged
    scores = np.array([0.75, 0.25, 0.9, 0.5])
    ids = np.zeros(4, np.int64)
    complete = np.array([True, True, False, True])
    kept, merged, counts = merge_view_detections(boxes, scores, ids, complete, np.zeros(4), W)
    by_index = dict(zip(kept.tolist(), merged.tolist()))
    assert sorted(by_index) == [0, 3]
    expected = 0.75 * np.array([990, 20, 1010, 40]) + 0.25 * np.array([994, 22, 1018, 42])
    assert np.allclose(by_index[0], expected)
    assert 0 <= by_index[0][0] < W < by_index[0][2]
    assert by_index[3] == [500, 20, 520, 40]
    assert dict(zip(kept.tolist(), counts.tolist())) == {0: 3, 3: 1}


def test_boxes_merged_across_classes_keep_the_best_ones_place():
    """Candidates are merged whatever their class (``class_ids`` alike), but only the boxes of
    the kept one's own class (``fuse_class_ids``) move its box: a neighbouring sign boxed in
    another class joins the count without dragging the box towards itself."""
    W = 1000
    boxes = np.array([[100, 50, 116, 64],    # a warning sign, best score
                      [107, 51, 125, 65],    # the yield sign beside it: 0.52 of the smaller box overlaps
                      [101, 50, 117, 64]])   # the warning sign again, another view
    scores = np.array([0.46, 0.41, 0.30])
    complete = np.ones(3, bool)
    anyclass = np.zeros(3, np.int64)
    kept, merged, counts = merge_view_detections(boxes, scores, anyclass, complete, np.zeros(3), W,
                                                 fuse_class_ids=np.array([0, 1, 0]))
    assert kept.tolist() == [0] and counts.tolist() == [3]
    expected = (0.46 * boxes[0] + 0.30 * boxes[2]) / 0.76   # the warning sign's boxes only
    assert np.allclose(merged[0], expected)
    _, fused_all, _ = merge_view_detections(boxes, scores, anyclass, complete, np.zeros(3), W)
    assert fused_all[0][2] > expected[2] + 1   # without it the yield box pulls the box right


class ColourBlobDetector:
    """Stands in for a model on the views: each red blob is a 'warning' sign."""

    class_names = ["warning", "stop"]

    def detect(self, image, confidence, iou_threshold):
        mask = ((image[:, :, 2] > 170) & (image[:, :, 1] < 90)).astype(np.uint8)
        n, _, stats, _ = cv2.connectedComponentsWithStats(mask)
        boxes = np.array([[x, y, x + w, y + h] for x, y, w, h, _ in stats[1:]], float).reshape(-1, 4)
        return ImageDetections(boxes, np.full(n - 1, 0.9), np.zeros(n - 1, np.int64))


def test_sign_across_the_seam_is_found_once_in_the_right_place():
    W, H = 2048, 1024
    pano = paint_discs([(180.0, 5.0, 6.0, (0, 0, 255)), (60.0, -3.0, 3.0, (0, 0, 255))], W)
    views = ViewSet.ring(8, 0.0, 80.0, 320)
    reports = []
    from roadsigns.core.errors import Progress
    found = detect_panorama(ColourBlobDetector(), pano, views, progress=Progress(on_progress=reports.append))
    assert reports[-1] == pytest.approx(100.0)
    assert len(found) == 2 and found.class_name == ["warning", "warning"]
    seam = int(np.argmax(found.u1 - found.u0))
    u0, v0, u1, v1 = found.boxes()[seam]
    assert 0 <= u0 < W < u1  # the contract's unwrapped form
    assert 0.5 * (u0 + u1) == pytest.approx(W, abs=2.0)
    assert 0.5 * (v0 + v1) == pytest.approx((0.5 - 5.0 / 180.0) * H, abs=2.0)
    want = disc_pano_box(180.0, 5.0, 6.0, W)
    assert u1 - u0 == pytest.approx(want[2] - want[0], abs=4.0)
    assert found.view_index[seam] == 4 and found.n_views[seam] >= 2  # yaw 180 wins over the cut ones
    other = 1 - seam
    assert 0.5 * (found.u0[other] + found.u1[other]) == pytest.approx((60 / 360 + 0.5) * W, abs=2.0)


def test_the_horizon_as_one_band_finds_a_sign_across_the_seam_once_in_the_right_place():
    """The band (``HORIZON_BAND``) holds a sign across the +-180 deg seam whole at one end and
    cut at the other: one detection, where the ring puts it."""
    from roadsigns.core.panorama import HORIZON_BAND, BandView
    W = 2048
    pano = paint_discs([(180.0, 5.0, 6.0, (0, 0, 255)), (60.0, -3.0, 3.0, (0, 0, 255))], W)
    band = ViewSet((BandView(1568, 224, 12.0),))
    found = detect_panorama(ColourBlobDetector(), pano, band)
    ring = detect_panorama(ColourBlobDetector(), pano, ViewSet.ring(8, 0.0, 80.0, 320))
    assert len(found) == 2 and len(ring) == 2
    order = np.argsort(found.u0)[::-1], np.argsort(ring.u0)[::-1]
    assert np.allclose(found.boxes()[order[0]], ring.boxes()[order[1]], atol=W / 360.0)   # within a degree
    seam = int(np.argmax(found.u1 - found.u0))
    assert 0 <= found.u0[seam] < W < found.u1[seam]
    assert found.n_views[seam] == 2          # the whole copy and the cut one at the other end
    # the plugin's set: the band first, then the fore-and-aft and upward views
    views = ViewSet.default((640, 384), horizon_views=HORIZON_BAND)
    assert views[0].own_size and len(views) == 5
    assert det.view_batches(views, 3) == [[0], [1, 2, 3], [4]]      # the band alone, the rest batched
    assert det.view_batches(ViewSet.default((640, 384)), 8) == [list(range(8)), list(range(8, 12))]


def test_a_model_of_any_input_size_runs_an_image_at_its_own_size_and_a_fixed_one_says_it_cannot(tmp_path):
    dyn = Detector(make_model(tmp_path / "dyn.onnx", v8_output(V8_ROWS), input_shape=["batch", 3, "h", "w"],
                              meta={"names": NAMES2, "imgsz": "[48, 96]"}))
    fixed_path = make_model(tmp_path / "fixed.onnx", v8_output(V8_ROWS), meta={"names": NAMES2})
    fixed = Detector(fixed_path)
    assert dyn.takes_any_size and not fixed.takes_any_size
    dyn.check_runs(3264, 448)
    fixed.check_runs(64, 64)                      # its own input size
    (result,) = dyn.detect_many([image(200, 70)], 0.25, own_size=True)
    assert len(result) == 3                       # padded to 224 x 96, not fitted into 96 x 48
    assert np.allclose(result.boxes_xyxy[0], xyxy(20, 20, 10, 10) - np.array([12, 13, 12, 13]))
    for call in (lambda: fixed.check_runs(3264, 448), lambda: fixed.detect_many([image(200, 70)], own_size=True)):
        with pytest.raises(InputError, match=r"fixed\.onnx takes 64 x 64 px images only; the horizon seen as one band"):
            call()


def test_an_upward_view_drops_what_it_cuts_at_its_sides_and_keeps_the_rest():
    """An upward view looks over the road for panels overhead: a sign it cuts at its left or
    right side stands beside the road (the horizon views see it whole from the stations
    before), and its box alone would lie on part of the sign only: it is dropped unless
    another view's box joins it. A sign whole in the view stays."""
    W = 2048
    horizon = ViewSet.ring(8, 0.0, 80.0, (320, 192))          # up to +26.7 deg
    upward = ViewSet.ring(2, 35.0, 90.0, (320, 192))
    for row_px, horizon_sees_it in ((96.0, True), (30.0, False)):   # on the right side, lower and higher
        side = upward[0].pixel_to_ray(np.array([320.0]), np.array([row_px]))[0]
        side_yaw, side_pitch = (float(np.degrees(a)) for a in geometry.ray_to_angles_rad(side))
        pano = paint_discs([(0.0, 40.0, 5.0, (0, 0, 255)), (side_yaw, side_pitch, 4.0, (0, 0, 255))], W)
        seen = ColourBlobDetector().detect(upward[0].cut(pano), 0.5, 0.5)
        assert len(seen) == 2 and np.count_nonzero(upward[0].touches_side(seen.boxes_xyxy)) == 1
        from_horizon = detect_panorama(ColourBlobDetector(), pano, horizon)
        assert len(from_horizon) == int(horizon_sees_it)
        found = detect_panorama(ColourBlobDetector(), pano, horizon + upward)
        assert len(found) == 1 + int(horizon_sees_it)
        if horizon_sees_it:     # the horizon views cut it at their top: the upward box joins theirs
            k = int(np.argmax(found.view_index < len(horizon)))
            assert found.n_views[k] == from_horizon.n_views[0] + 1
        overhead = found.subset(found.view_index >= len(horizon))    # whole in the upward view: kept
        assert len(overhead) == 1
        assert 0.5 * (overhead.v0[0] + overhead.v1[0]) == pytest.approx((0.5 - 40.0 / 180.0) * W / 2, abs=3.0)
        assert 0.5 * (overhead.u0[0] + overhead.u1[0]) == pytest.approx(0.5 * W, abs=3.0)


def test_boxes_under_the_minimum_size_are_dropped():
    W = 2048  # discs of 6 deg and 2 deg radius: about 68 px and 23 px across
    pano = paint_discs([(-90.0, 0.0, 6.0, (0, 0, 255)), (90.0, 0.0, 2.0, (0, 0, 255))], W)
    views = ViewSet.ring(8, 0.0, 80.0, 320)
    boxes = detect_panorama(ColourBlobDetector(), pano, views).boxes()
    sizes = np.sort(np.minimum(boxes[:, 2] - boxes[:, 0], boxes[:, 3] - boxes[:, 1]))
    assert len(sizes) == 2 and 15 < sizes[0] < 30 < 60 < sizes[1]
    kept = detect_panorama(ColourBlobDetector(), pano, views, min_box_px=30.0)
    assert len(kept) == 1
    assert min(kept.u1[0] - kept.u0[0], kept.v1[0] - kept.v0[0]) == pytest.approx(sizes[1])
    assert 0.5 * (kept.u0[0] + kept.u1[0]) == pytest.approx(0.25 * W, abs=2.0)


# --- int8 models (devtools/train/quantize.py) ------------------------------------------

def _brightness_model(path):
    """A float 'detector': score = the brightest 3 x 3 patch's response, one fixed box."""
    import onnx
    from onnx import TensorProto, helper, numpy_helper

    rng = np.random.default_rng(0)
    w1 = (np.abs(rng.normal(0, 0.1, (8, 3, 3, 3))) + 0.02).astype(np.float32)
    w2 = np.full((1, 8, 1, 1), 1.0 / (8 * 3 * 9 * 0.1), np.float32)
    graph = helper.make_graph(
        [helper.make_node("Conv", ["images", "w1", "b1"], ["c1"], pads=[1, 1, 1, 1], name="/net/stem/Conv"),
         helper.make_node("Relu", ["c1"], ["r1"]),
         helper.make_node("Conv", ["r1", "w2", "b2"], ["c2"], name="/net/heatmap/Conv"),
         helper.make_node("GlobalMaxPool", ["c2"], ["peak"]),
         helper.make_node("Reshape", ["peak", "shape"], ["score"]),
         helper.make_node("Expand", ["box", "bshape"], ["boxes"]),
         helper.make_node("Expand", ["cls", "bshape1"], ["classes"]),
         helper.make_node("Concat", ["boxes", "score", "classes"], ["output0"], axis=2)],
        "brightness",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, ["batch", 3, 64, 64])],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, ["batch", 1, 6])],
        [numpy_helper.from_array(w1, "w1"), numpy_helper.from_array(np.zeros(8, np.float32), "b1"),
         numpy_helper.from_array(w2, "w2"), numpy_helper.from_array(np.zeros(1, np.float32), "b2"),
         numpy_helper.from_array(np.array([-1, 1, 1], np.int64), "shape"),
         numpy_helper.from_array(np.array([[[10, 12, 30, 40]]], np.float32), "box"),
         numpy_helper.from_array(np.array([[[1]]], np.float32), "cls"),
         numpy_helper.from_array(np.array([1, 1, 4], np.int64), "bshape"),
         numpy_helper.from_array(np.array([1, 1, 1], np.int64), "bshape1")])
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    helper.set_model_props(model, {"names": NAMES2, "task": "detect"})
    onnx.save(model, str(path))
    return str(path)


@pytest.mark.parametrize("fmt", ["qdq", "qoperator"])
def test_int8_model_runs_like_the_float_one(tmp_path, fmt):
    """A statically quantised model (int8 convolutions, float head kept) loads and decodes
    like the float file, with the same metadata, and scores within quantisation error."""
    pytest.importorskip("onnxruntime.quantization")
    import onnx

    from devtools.train import quantize

    src = _brightness_model(tmp_path / "float.onnx")
    rng = np.random.default_rng(1)
    calib = []  # representative: flat grey images with a patch, as the checks below
    for v in rng.integers(0, 256, 12):
        img = np.full((64, 64, 3), v, np.uint8)
        img[10:40, 30:50] = 255 - v
        calib.append(img)
    out = quantize.quantize(src, str(tmp_path / f"int8-{fmt}.onnx"), calib, fmt=fmt)
    q = onnx.load(out)
    ops = {n.op_type for n in q.graph.node}
    assert ("QLinearConv" in ops) if fmt == "qoperator" else ("DequantizeLinear" in ops)
    head = [n for n in q.graph.node if n.name == "/net/heatmap/Conv"]
    assert head and head[0].op_type == "Conv"  # the output layer stays float
    meta = {p.key: p.value for p in q.metadata_props}
    assert meta["names"] == NAMES2 and fmt in meta["quantization"]
    f, i8 = Detector(src, threads=1), Detector(out, threads=1)
    assert i8.layout == f.layout == "nms" and i8.class_names == ["warning", "stop"]
    for value in (40, 128, 230):
        img = np.full((64, 64, 3), value, np.uint8)
        img[20:30, 20:30] = 255 - value
        a, b = f.detect(img, 0.0), i8.detect(img, 0.0)
        assert b.class_ids.tolist() == [1] and b.boxes_xyxy == pytest.approx(a.boxes_xyxy)
        assert b.scores[0] == pytest.approx(a.scores[0], rel=0.05, abs=0.02)


def test_the_shipped_int8_detector_is_the_float_one_quantised():
    """models/roadsigns-int8.onnx (what detectsigns runs by default) is models/roadsigns.onnx
    quantised (devtools/train/quantize.py): the same classes, training record, score
    calibration and network widths (what ``devtools.train --init`` reads), int8 weights,
    and on one of GTSDB's photographs the same boxes and classes, scores within
    quantisation error."""
    import onnx

    from roadsigns.algorithms.paths import BUNDLED_FLOAT_MODEL, BUNDLED_MODEL
    assert os.path.basename(BUNDLED_MODEL) == "roadsigns-int8.onnx"
    meta = [{p.key: p.value for p in onnx.load(path).metadata_props} for path in (BUNDLED_FLOAT_MODEL, BUNDLED_MODEL)]
    for key in ("names", "training", "score_calibration", "imgsz", "input_height", "architecture"):
        assert meta[0][key] == meta[1][key], key
    assert Detector(BUNDLED_MODEL, threads=1).input_size == (640, 384)   # views that skip sky and road
    assert "int8 static" in meta[1]["quantization"] and "quantization" not in meta[0]
    assert os.path.getsize(BUNDLED_MODEL) < 0.35 * os.path.getsize(BUNDLED_FLOAT_MODEL)
    photo = os.path.join(REPO_ROOT, "..", "shared", "data", "gtsdb-train", "images", "00505.jpg")
    if not os.path.isfile(photo):
        (pytest.fail if os.environ.get("CI", "").lower() == "true" else pytest.skip)(f"{photo} is not there")
    # a band of the photograph at the model's input size (640 x 384) holding two mandatory signs
    image = np.ascontiguousarray(cv2.cvtColor(cv2.imread(photo), cv2.COLOR_BGR2RGB)[288:672, 240:880])
    f, q = Detector(BUNDLED_FLOAT_MODEL, threads=1), Detector(BUNDLED_MODEL, threads=1)
    a, b = f.detect(image, 0.3), q.detect(image, 0.3)
    # compared box by box in image order: scores within quantisation error may swap ranks
    ia, ib = (np.lexsort(d.boxes_xyxy.T[::-1]) for d in (a, b))
    assert len(a.scores) >= 2 and b.class_ids[ib].tolist() == a.class_ids[ia].tolist()
    assert b.boxes_xyxy[ib] == pytest.approx(a.boxes_xyxy[ia], abs=3.0)
    assert b.scores[ib] == pytest.approx(a.scores[ia], abs=0.05)


def test_a_detector_set_to_a_lower_input_finds_the_same_boxes_in_the_band(tmp_path, scene_tiny):
    """devtools.train.inputsize: the float detector set to 640 x 384 (its decoder reads the
    feature map's size from the graph; the bundled files are) runs on the plugin's 640 x 384
    views, whose pixels are the middle band of the square views (same focal length), and
    finds there the boxes and classes the square model (640 x 640, as trained) finds."""
    from devtools.train.inputsize import set_input_height
    from roadsigns.algorithms.paths import BUNDLED_FLOAT_MODEL
    from roadsigns.core.panorama import read_panorama
    square_path, low = str(tmp_path / "square.onnx"), str(tmp_path / "low.onnx")
    set_input_height(BUNDLED_FLOAT_MODEL, square_path, 640)   # as trained
    set_input_height(square_path, low, 384)                   # as shipped
    with pytest.raises(SystemExit):
        set_input_height(BUNDLED_FLOAT_MODEL, str(tmp_path / "bad.onnx"), 390)   # not a multiple of 32
    square, banded = Detector(square_path, threads=1), Detector(low, threads=1)
    assert square.input_size == (640, 640) and banded.input_size == (640, 384)
    views_sq = ViewSet.default(size_px=square.input_size, upward=False)
    views_lo = ViewSet.default(size_px=banded.input_size, upward=False)
    assert {(v.width_px, v.height_px) for v in views_lo.views} == {(640, 384)}
    assert views_lo.views[0].vfov_deg == pytest.approx(53.45, abs=0.01)      # +-26.7 deg, not +-40
    folder, _ = scene_tiny
    images = sorted(f for f in os.listdir(os.path.join(folder, "images")) if f.endswith(".jpg"))
    compared = 0
    for name in images[::3]:
        pano = read_panorama(os.path.join(folder, "images", name))
        for v_sq, v_lo in zip(views_sq.views, views_lo.views):
            a = square.detect(v_sq.cut(pano), 0.4)
            b = banded.detect(v_lo.cut(pano), 0.4)
            inside = (a.boxes_xyxy[:, 1] >= 128 + 16) & (a.boxes_xyxy[:, 3] <= 512 - 16)
            for box, klass in zip(a.boxes_xyxy[inside], a.class_ids[inside]):
                d = np.abs(b.boxes_xyxy - (box - [0, 128, 0, 128])).max(axis=1) if len(b.scores) else [np.inf]
                assert np.min(d) <= 4.0 and b.class_ids[int(np.argmin(d))] == klass, (name, box)
                compared += 1
    assert compared >= 5


def test_the_bundled_detectors_take_any_size_and_a_fixed_file_made_so_gives_the_same_outputs(tmp_path):
    """devtools.train.inputsize --any-size: the input's height and width declared symbolic,
    the graph otherwise the same. The bundled files are so (the horizon band runs on them at
    3264 x 448); their views are still cut at their imgsz, 640 x 384."""
    from devtools.train.inputsize import take_any_size
    from roadsigns.algorithms.paths import BUNDLED_FLOAT_MODEL, BUNDLED_MODEL
    for path in (BUNDLED_MODEL, BUNDLED_FLOAT_MODEL):
        d = Detector(path, threads=1)
        assert d.takes_any_size and d.input_size == (640, 384)
        d.check_runs(3264, 448)
    fixed_path, any_path = str(tmp_path / "fixed.onnx"), str(tmp_path / "any.onnx")
    from devtools.train.inputsize import set_input_height
    set_input_height(BUNDLED_MODEL, fixed_path, 384)
    take_any_size(fixed_path, any_path)
    fixed, free = Detector(fixed_path, threads=1), Detector(any_path, threads=1)
    assert not fixed.takes_any_size and free.takes_any_size
    view = np.random.default_rng(3).integers(0, 256, (384, 640, 3), dtype=np.uint8)
    a, b = fixed.run_raw([view])[0], free.run_raw([view])[0]
    assert np.array_equal(a, b)
    wide = free.run_raw([np.zeros((448, 3264, 3), np.uint8)], own_size=True)[0]
    assert wide.shape[0] == 1 and wide.shape[-1] == 6


# --- a drive: decoding the next panorama while this one is detected ----------------------

class MeanGreyDetector:
    """One box in the middle of each view, scored by the view's mean grey / 255: the score
    says which panorama a result came from."""
    class_names = ["sign"]

    def detect(self, image, confidence, iou_threshold):
        h, w = image.shape[:2]
        return ImageDetections(np.array([[0.4 * w, 0.4 * h, 0.6 * w, 0.6 * h]]),
                               np.array([image.mean() / 255.0]), np.zeros(1, np.int64))


def _grey_panoramas(tmp_path, n=5, corrupt=()):
    paths = []
    for k in range(n):
        path = tmp_path / f"p{k}.png"
        if k in corrupt:
            path.write_bytes(b"not an image at all")
        else:
            cv2.imwrite(str(path), np.full((64, 128, 3), 20 + 40 * k, np.uint8))
        paths.append(str(path))
    return paths


@pytest.mark.parametrize("prefetch", [False, True])
def test_detect_drive_keeps_the_order_and_skips_a_corrupt_panorama(tmp_path, monkeypatch, prefetch):
    import time

    from roadsigns.core import panorama
    from roadsigns.core.errors import Progress

    paths = _grey_panoramas(tmp_path, 5, corrupt=(2,))
    original = panorama.read_panorama
    delays = {paths[0]: 0.05, paths[1]: 0.0, paths[3]: 0.08}  # reads finishing out of turn

    def slow_read(path):
        time.sleep(delays.get(path, 0.0))
        return original(path)

    monkeypatch.setattr(panorama, "read_panorama", slow_read)
    warnings, seen, fractions = [], [], []
    views = ViewSet.ring(2, 0.0, 90.0, 32)
    drive = det.detect_drive(MeanGreyDetector(), paths, views, 0.0,
                             progress=Progress(fractions.append, on_warning=warnings.append),
                             on_panorama=lambda pano, found: seen.append(int(pano[0, 0, 0])),
                             prefetch=prefetch)
    assert seen == [20, 60, 140, 180]  # each detected panorama handed on, in order
    assert [None if d is None else round(float(d.score.max()) * 255) for d in drive.per_image] == \
        [20, 60, None, 140, 180]
    assert [p for p, _ in drive.skipped] == [paths[2]] and "corrupt" in drive.skipped[0][1]
    assert len(warnings) == 1 and paths[2] in str(warnings[0])
    assert fractions == sorted(fractions) and fractions[-1] == 100.0


def test_detect_drive_prefetch_cancels_without_waiting_for_the_read_in_flight(tmp_path, monkeypatch):
    import time

    from roadsigns.core import panorama
    from roadsigns.core.errors import Cancelled, Progress

    paths = _grey_panoramas(tmp_path, 4)
    original = panorama.read_panorama
    started = []

    def slow_read(path):
        started.append(path)
        if path != paths[0]:
            time.sleep(1.5)
        return original(path)

    monkeypatch.setattr(panorama, "read_panorama", slow_read)
    cancel_at = []  # set once the first panorama is detected and the second one's read began

    def on_panorama(pano, found):
        deadline = time.perf_counter() + 5.0
        while len(started) < 2 and time.perf_counter() < deadline:
            time.sleep(0.01)
        cancel_at.append(time.perf_counter())

    with pytest.raises(Cancelled):
        det.detect_drive(MeanGreyDetector(), paths, ViewSet.ring(2, 0.0, 90.0, 32), 0.0,
                         progress=Progress(is_cancelled=lambda: bool(cancel_at)),
                         on_panorama=on_panorama, prefetch=True)
    assert time.perf_counter() - cancel_at[0] < 0.5  # not held by the 1.5 s read of panorama 1
    time.sleep(1.8)
    assert started == paths[:2]  # nothing read after the cancel


@pytest.mark.parametrize("prefetch", [False, True])
def test_detect_drive_cuts_the_next_panoramas_views_with_its_decoding(tmp_path, monkeypatch, prefetch):
    """With ``prefetch`` the views of every panorama are cut in the reader thread, beside the
    detection of the one before (``cv2.remap`` releases the GIL); without it in the calling
    thread; each panorama's views are cut once, and the results are the same."""
    import threading

    from roadsigns.core import panorama

    original = panorama.ViewSet.cut_all
    cut_in = []

    def spy(self, pano):
        cut_in.append(threading.get_ident())
        return original(self, pano)

    monkeypatch.setattr(panorama.ViewSet, "cut_all", spy)
    paths = _grey_panoramas(tmp_path, 4)
    drive = det.detect_drive(MeanGreyDetector(), paths, ViewSet.ring(2, 0.0, 90.0, 32), 0.0, prefetch=prefetch)
    assert [round(float(d.score.max()) * 255) for d in drive.per_image] == [20, 60, 100, 140]
    assert len(cut_in) == 4
    main = threading.get_ident()
    assert all((ident != main) == prefetch for ident in cut_in)


def test_spaced_stations_keeps_the_fewest_stations_no_farther_apart_than_the_spacing():
    xyz = np.array([[0, 0, 0], [1, 0, 0], [2.5, 0, 0], [3, 0, 0], [5, 0, 0], [5, 0, 3], [5, 0, 3.5]], float)
    assert det.spaced_stations(xyz, 0.0).tolist() == [0, 1, 2, 3, 4, 5, 6]
    # 3 m: station 3 is kept as station 4 stands 5 m from station 0, station 4 as station 5
    # stands 3.6 m from station 3, station 5 as station 6 stands 3.5 m from station 4; the
    # last is always kept
    assert det.spaced_stations(xyz, 3.0).tolist() == [0, 3, 4, 5, 6]
    assert det.spaced_stations(xyz, 5.0).tolist() == [0, 4, 6]
    assert det.spaced_stations(xyz, 10.0).tolist() == [0, 6]
    assert det.spaced_stations(xyz[:2], 10.0).tolist() == [0, 1]
    assert det.spaced_stations(np.zeros((0, 3)), 2.0).tolist() == []


def test_spaced_stations_keeps_one_station_of_a_stop_and_every_station_of_a_sparse_gap():
    stop = np.column_stack([np.r_[np.arange(4.0), np.full(20, 4.0), np.arange(5.0, 11.0)],
                            np.zeros(30), np.zeros(30)])
    kept = det.spaced_stations(stop, 2.0)
    assert stop[kept, 0].tolist() == [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]   # the twenty panoramas at 4 m: one
    sparse = np.array([[0, 0, 0], [1, 0, 0], [9, 0, 0], [10, 0, 0]], float)
    assert det.spaced_stations(sparse, 2.0).tolist() == [0, 1, 2, 3]  # the 8 m gap: both ends


@pytest.mark.parametrize("gap_m", [0.5, 1.2447, 1.9, 2.4, 2.5, 3.0, 5.0, 7.0])
def test_default_spacing_detects_at_least_every_5_m_and_skips_nothing_on_sparse_drives(gap_m):
    rng = np.random.default_rng(int(gap_m * 100))
    s = np.cumsum(np.r_[0.0, np.full(400, gap_m) + rng.uniform(-0.05, 0.05, 400) * gap_m])
    xyz = np.column_stack([s, 0.1 * np.sin(s / 30.0), np.zeros_like(s)])
    kept = det.spaced_stations(xyz, det.DEFAULT_STATION_SPACING_M)
    kept_gaps = np.linalg.norm(np.diff(xyz[kept], axis=0), axis=1)
    steps = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
    assert kept_gaps.max() <= max(det.DEFAULT_STATION_SPACING_M, steps.max()) + 1e-9
    assert kept[0] == 0 and kept[-1] == len(xyz) - 1
    if gap_m * 0.95 > det.DEFAULT_STATION_SPACING_M / 2:
        # no two consecutive steps fit in 5 m: every panorama kept
        assert len(kept) == len(xyz)
    else:
        # as few as the spacing allows: skipping one more station would leave a gap over 5 m
        after_next = np.linalg.norm(xyz[np.minimum(kept[1:-1] + 1, len(xyz) - 1)] - xyz[kept[:-2]], axis=1)
        assert (after_next > det.DEFAULT_STATION_SPACING_M).all()
    if steps.max() < det.DEFAULT_STATION_SPACING_M:
        # each kept station stands more than the spacing less one step beyond the one before it
        # (else the next station would have been in reach): at most length / (5 m - step) of them
        length_m = float(np.sum(steps))
        assert len(kept) <= length_m / (det.DEFAULT_STATION_SPACING_M - steps.max()) + 2
    if gap_m < 1.3:
        assert len(kept) <= len(xyz) / 3                # a dense drive: a third of the panoramas or fewer


def test_an_int8_model_takes_the_views_uint8_bgr_pixels(tmp_path):
    """devtools.train.rawinput: the QDQ file's input quantised at once (scale 1/255) becomes
    the views' uint8 BGR pixels, channels last. Detector feeds them as they are and finds
    exactly what it finds with the float input; read as RGB the channels would be swapped."""
    pytest.importorskip("onnxruntime.quantization")
    import onnx

    from devtools.train import quantize
    from devtools.train.rawinput import CHANNEL_ORDER_KEY, take_uint8_bgr

    src = _brightness_model(tmp_path / "float.onnx")
    calib = [np.full((64, 64, 3), v, np.uint8) for v in range(0, 256, 20)]
    floating = quantize.quantize(src, str(tmp_path / "float-input.onnx"), calib, uint8_input=False)
    pixels = str(tmp_path / "pixels.onnx")
    take_uint8_bgr(floating, pixels)
    model = onnx.load(pixels)
    tensor = model.graph.input[0].type.tensor_type
    assert tensor.elem_type == onnx.TensorProto.UINT8
    assert [d.dim_value or d.dim_param for d in tensor.shape.dim] == ["batch", 64, 64, 3]
    assert "QuantizeLinear" not in {n.op_type for n in model.graph.node if "images" in n.input}
    assert {p.key: p.value for p in model.metadata_props}[CHANNEL_ORDER_KEY] == "BGR"
    a, b = Detector(floating, threads=1), Detector(pixels, threads=1)
    assert (a.channels_last, b.channels_last, b.input_bgr, b.input_size) == (False, True, True, (64, 64))
    rng = np.random.default_rng(2)
    for k in range(4):
        image = rng.integers(0, 256, (48 + 8 * k, 64, 3), dtype=np.uint8)   # letterboxed, channels unequal
        image[10:20, 5:15] = (255, 40 * k, 0)                                  # a blue patch
        da, db = a.detect(image, 0.0), b.detect(image, 0.0)
        assert db.scores.tolist() == da.scores.tolist() and np.array_equal(db.boxes_xyxy, da.boxes_xyxy)
    # the same file read as RGB: the first layer's weights meet the channels swapped
    meta = {p.key: p for p in model.metadata_props}
    meta[CHANNEL_ORDER_KEY].value = "RGB"
    onnx.save(model, str(tmp_path / "rgb.onnx"))
    rgb = Detector(str(tmp_path / "rgb.onnx"), threads=1)
    assert not rgb.input_bgr and rgb.detect(image, 0.0).scores[0] != pytest.approx(da.scores[0], abs=1e-4)
    # a file that does not begin by quantising its input is refused, nothing written
    for other in (src, quantize.quantize(src, str(tmp_path / "qop.onnx"), calib, fmt="qoperator")):
        with pytest.raises(SystemExit):
            take_uint8_bgr(other, str(tmp_path / "refused.onnx"))
    assert not os.path.exists(tmp_path / "refused.onnx")
    # the shipped int8 detector takes them so (models/README.md, "The views' pixels as they are")
    from roadsigns.algorithms.paths import BUNDLED_MODEL
    shipped = Detector(BUNDLED_MODEL, threads=1)
    assert shipped.channels_last and shipped.input_bgr


def test_a_channels_last_model_with_other_than_three_channels_is_refused(tmp_path):
    import onnx
    from onnx import TensorProto, helper

    graph = helper.make_graph(
        [helper.make_node("Cast", ["images"], ["f"], to=TensorProto.FLOAT),
         helper.make_node("ReduceMean", ["f"], ["output0"], axes=[3], keepdims=0)],
        "four", [helper.make_tensor_value_info("images", TensorProto.UINT8, ["batch", 64, 64, 4])],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, ["batch", 64, 64])])
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    helper.set_model_props(model, {"names": NAMES2, "task": "detect"})
    onnx.save(model, str(tmp_path / "four.onnx"))
    with pytest.raises(InputError, match=r"uint8 \[batch, height, width, 3\]"):
        Detector(str(tmp_path / "four.onnx"), threads=1)


def test_detect_drive_says_which_panorama_it_is_on(tmp_path):
    """One step a panorama, in order, the unreadable one too: the Processing dialog's
    progress text."""
    from roadsigns.core.errors import Progress

    paths = _grey_panoramas(tmp_path, 3, corrupt=(1,))
    steps = []
    det.detect_drive(MeanGreyDetector(), paths, ViewSet.ring(2, 0.0, 90.0, 32), 0.0,
                     progress=Progress(on_step=steps.append))
    assert steps == ["Detecting signs: panorama {} of 3 ({})".format(k + 1, os.path.basename(p))
                     for k, p in enumerate(paths)]
