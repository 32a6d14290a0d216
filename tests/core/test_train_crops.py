"""Training crops of generated views (devtools/train/data.py): a large sign shown whole, a
sign seen edge-on shown at the plugin's scales."""
import numpy as np

from devtools.train.data import (
    LARGE_SIGN_FILL,
    TALL_CROP_SCALES,
    Sample,
    crop_sample,
    tall_boxes,
    tall_sign_crop,
    whole_sign_crop,
)


def test_a_large_sign_is_shown_whole_and_a_small_one_is_left_to_the_ordinary_crops():
    rng = np.random.default_rng(3)
    view = np.full((384, 640, 3), 90, np.uint8)
    panel = np.array([[60.0, 40.0, 560.0, 200.0]], np.float32)     # 500 px across: a gantry panel overhead
    sign = np.array([[300.0, 180.0, 340.0, 220.0]], np.float32)
    sample = Sample(view, np.concatenate([sign, panel]), np.array([1, 3]))
    for _ in range(200):
        scale, centre = whole_sign_crop(sample.boxes, 320, rng)
        crop = crop_sample(sample, 320, scale, centre, flip=False)
        kept = crop.boxes[crop.classes == 3]
        assert len(kept) == 1                      # the panel is a labelled sign, not an ignore region
        w, h = kept[0, 2] - kept[0, 0], kept[0, 3] - kept[0, 1]
        assert LARGE_SIGN_FILL[0] * 320 - 1 <= max(w, h) <= LARGE_SIGN_FILL[1] * 320 + 1
        assert abs(max(w, h) - 500.0 * scale) < 0.5         # whole: not clipped at the crop's edge
    assert whole_sign_crop(sign, 320, rng) is None          # 40 px: the ordinary crops show it whole
    assert whole_sign_crop(np.zeros((0, 4)), 320, rng) is None


def test_a_sign_seen_edge_on_is_cropped_round_labelled_and_whole_at_the_views_scales():
    rng = np.random.default_rng(5)
    view = np.full((384, 640, 3), 90, np.uint8)
    sliver = np.array([[600.0, 150.0, 606.0, 190.0]], np.float32)   # 6 x 40 px near the view's right edge
    disc = np.array([[100.0, 100.0, 130.0, 130.0]], np.float32)     # face-on
    tiny = np.array([[300.0, 100.0, 302.0, 110.0]], np.float32)     # tall but under TALL_SIGN_MIN_PX
    boxes = np.concatenate([disc, sliver, tiny])
    assert tall_boxes(boxes).tolist() == [1]
    sample = Sample(view, boxes, np.array([2, 1, 0]))
    scales = []
    for _ in range(200):
        scale, centre = tall_sign_crop(sample.boxes, 320, rng)
        scales.append(scale)
        crop = crop_sample(sample, 320, scale, centre, flip=bool(rng.random() < 0.5))
        kept = crop.boxes[crop.classes == 1]
        assert len(kept) == 1                            # labelled, not an ignore region
        w, h = kept[0, 2] - kept[0, 0], kept[0, 3] - kept[0, 1]
        assert abs(h - 40.0 * scale) < 0.5 and abs(w - 6.0 * scale) < 0.5    # whole: not cut by the crop
        assert kept[0, 0] >= 320 / 6 - 6 * scale - 1 and kept[0, 2] <= 320 - 320 / 6 + 6 * scale + 1
    assert TALL_CROP_SCALES[0] <= min(scales) and max(scales) <= TALL_CROP_SCALES[1]
    assert max(scales) / min(scales) > 1.5                 # drawn over the range, not one scale
    assert tall_sign_crop(disc, 320, rng) is None
    assert tall_sign_crop(np.zeros((0, 4)), 320, rng) is None
