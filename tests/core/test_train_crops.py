"""Training crops of generated views (devtools/train/data.py): a large sign shown whole."""
import numpy as np

from devtools.train.data import LARGE_SIGN_FILL, Sample, crop_sample, whole_sign_crop


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
