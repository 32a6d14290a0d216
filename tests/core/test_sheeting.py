"""Sign sheeting colours (core.sheeting): the share of them in a box, and a box much taller
than wide (a sign seen nearly edge-on) narrowed to the columns that show them; through
core.detector the fit applies to a panorama's detections, across its seam too."""
import numpy as np
import pytest

from roadsigns.core import detector as DT  # noqa: N812 (the tests' short module names)
from roadsigns.core import sheeting

RED, BLUE, WHITE, DARK, WALL = (30, 30, 230), (230, 40, 30), (245, 245, 245), (40, 40, 40), (120, 120, 120)  # BGR


def test_sheeting_fraction_counts_sign_colours_and_wraps_the_seam():
    pano = np.full((100, 200, 3), 120, np.uint8)
    pano[20:40, 10:30] = RED
    pano[20:40, 190:200] = BLUE
    pano[20:40, 0:10] = BLUE
    pano[60:80, 50:70] = DARK
    assert sheeting.sheeting_fraction(pano, (10, 20, 30, 40)) == 1.0
    assert sheeting.sheeting_fraction(pano, (0, 20, 40, 40)) == pytest.approx(0.75)  # 20 red + 10 blue of 40
    assert sheeting.sheeting_fraction(pano, (50, 60, 70, 80)) == 0.0                 # dark grey is no sheeting
    assert sheeting.sheeting_fraction(pano, (190, 20, 210, 40), wrap=True) == 1.0    # blue on both sides
    assert sheeting.sheeting_fraction(pano, (190, 20, 210, 40)) == 1.0               # clipped: the right part
    assert sheeting.sheeting_fraction(pano, (180, 20, 210, 40), wrap=True) == pytest.approx(20 / 30)
    assert sheeting.sheeting_fraction(pano, (30, 20, 30, 40)) == 0.0                 # empty box


def _edge_on_sign(image, u0, v0, u1, v1):
    """A white face with a red rim, seen edge-on: a sliver ``u0:u1`` beside a grey pole."""
    image[v0:v1, u0:u1] = WHITE
    image[v0:v1, u0:u0 + 2] = RED
    image[v0:v1, u1 - 2:u1] = RED
    image[v0:v0 + 3, u0:u1] = RED
    image[v0 - 10:v1 + 40, u0 - 6:u0 - 2] = DARK        # the pole, left of the face


def test_a_tall_box_is_narrowed_to_the_columns_that_show_sheeting():
    image = np.full((200, 400, 3), WALL, np.uint8)
    _edge_on_sign(image, 50, 40, 62, 130)                    # a sliver 12 px wide, 90 px high
    image[40:130, 150:200] = BLUE                            # a blue panel seen face-on
    image[40:130, 250:262] = RED                             # a red sliver filling its box
    image[40:130, 300:325] = (40, 120, 30)                   # a green panel (no sheeting colour) ...
    image[40:130, 300] = BLUE                                # ... with one blue column: 4 % of the box
    image[40:130, 343:367] = BLUE                            # a blue panel over 80 % of its box
    boxes = np.array([[38, 38, 74, 132],                     # the network's box: 3 x too wide
                      [140, 35, 210, 135],                   # not tall: as it was
                      [250, 40, 262, 130],                   # every column sheeting: as it was
                      [100, 40, 110, 130],                   # tall, no sheeting: as it was
                      [300, 40, 325, 130],                   # under 8 % sheeting: as it was
                      [340, 40, 370, 130]], float)           # would keep 80 % of its width: as it was
    fitted = sheeting.fit_tall_boxes(image, boxes)
    np.testing.assert_array_equal(fitted[0], [50, 38, 62, 132])   # only the columns move
    np.testing.assert_array_equal(fitted[1:], boxes[1:])
    assert sheeting.fit_tall_boxes(image, np.zeros((0, 4))).shape == (0, 4)


def test_a_tall_box_is_fitted_across_the_panoramas_seam():
    """A box past the seam (u1 > W) reads the columns from the panorama's other side; the
    detections keep u0 in [0, W)."""
    pano = np.full((256, 512, 3), WALL, np.uint8)
    _edge_on_sign(pano, 2, 80, 12, 170)                      # just right of the seam
    boxes = np.array([[500, 78, 530, 172]], float)           # from 12 px left of the seam
    np.testing.assert_array_equal(sheeting.fit_tall_boxes(pano, boxes, wrap=True), [[514, 78, 524, 172]])
    found = DT.PanoramaDetections(np.zeros(1, np.int64), ["warning"], np.array([0.9]), *boxes.T.copy(),
                                  np.zeros(1, np.int64), np.ones(1, np.int64))
    DT.fit_tall_boxes(pano, found)
    np.testing.assert_array_equal(found.boxes(), [[2, 78, 12, 172]])


class WideBoxDetector:
    """Boxes the red pixels of a view three times as wide as they are, as the network boxes a
    sign seen edge-on (the pole and the wall beside it included)."""
    class_names = ["warning"]

    def detect(self, image, confidence, iou_threshold):
        rows, cols = np.nonzero(np.all(image == RED, axis=2))
        if len(cols) < 4:
            return DT.ImageDetections(np.zeros((0, 4)), np.zeros(0), np.zeros(0, np.int64))
        u0, u1, w = cols.min(), cols.max() + 1, cols.max() + 1 - cols.min()
        box = [[u0 - w, rows.min(), u1 + w, rows.max() + 1]]
        return DT.ImageDetections(np.array(box, float), np.array([0.9]), np.zeros(1, np.int64))


def test_detect_panorama_fits_the_tall_boxes_unless_told_not_to():
    from roadsigns.core.panorama import ViewSet

    pano = np.full((1024, 2048, 3), WALL, np.uint8)
    pano[450:560, 1020:1032] = RED                       # a red sliver straight ahead
    views = ViewSet.default(size_px=256, upward=False)
    fitted = DT.detect_panorama(WideBoxDetector(), pano, views, 0.5)
    wide = DT.detect_panorama(WideBoxDetector(), pano, views, 0.5, fit_tall=False)
    assert len(fitted) == len(wide) == 1
    assert wide.u1[0] - wide.u0[0] > 30                  # about three times the sliver's 12 px
    np.testing.assert_allclose([fitted.u0[0], fitted.u1[0]], [1020, 1032], atol=1)
    np.testing.assert_array_equal([fitted.v0, fitted.v1], [wide.v0, wide.v1])
