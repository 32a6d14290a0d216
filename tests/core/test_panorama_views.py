"""Perspective views cut from equirectangular panoramas, and boxes mapped back.

Synthetic panoramas carry coloured discs painted at known (azimuth, elevation); the
expected view positions are computed longhand from the contract (pinhole looking along
the view's ray, image x right, y down) and checked against what ``cv2.remap`` produced.
"""
import cv2
import numpy as np
import pytest
from helpers.synthpano import disc_pano_box as _disc_pano_box
from helpers.synthpano import paint_discs as _paint_discs
from helpers.synthpano import ray

from roadsigns.core.errors import InputError
from roadsigns.core.panorama import (
    DEFAULT_FORE_AFT_VIEWS,
    DEFAULT_HORIZON_VIEWS,
    DEFAULT_UPWARD_VIEWS,
    FORE_AFT_HFOV_DEG,
    HORIZON_BAND,
    HORIZON_BAND_MARGIN_DEG,
    HORIZON_BAND_SIZE_PX,
    HORIZON_CHOICES,
    HORIZON_HFOV_DEG,
    UPWARD_HFOV_DEG,
    UPWARD_PITCH_DEG,
    UPWARD_RING_VIEWS,
    BandView,
    PerspectiveView,
    ViewSet,
    horizon_choice,
    read_panorama,
)

W, H = 2048, 1024
RED = (0, 0, 255)  # BGR


def paint_discs(discs):
    return _paint_discs(discs, W)


def disc_pano_box(az, el, radius):
    return _disc_pano_box(az, el, radius, W)


def pinhole(view_yaw, view_pitch, hfov, size, az, el):
    """Longhand projection of ray (az, el) into a view: forward, right = horizontal +90 deg,
    down = forward x right."""
    f_axis = ray(view_yaw, view_pitch)
    r_axis = ray(view_yaw + 90.0, 0.0)
    d_axis = np.cross(f_axis, r_axis)
    d = ray(az, el)
    focal = 0.5 * size / np.tan(np.radians(0.5 * hfov))
    z = d @ f_axis
    return 0.5 * size + focal * (d @ r_axis) / z, 0.5 * size + focal * (d @ d_axis) / z


def red_blob(image):
    """Centroid and pixel box (x0, y0, x1, y1: edges) of the red pixels."""
    mask = (image[:, :, 2] > 170) & (image[:, :, 1] < 90)
    ys, xs = np.nonzero(mask)
    assert len(xs), "no red pixels in the view"
    box = np.array([xs.min(), ys.min(), xs.max() + 1, ys.max() + 1], float)
    return (xs.mean() + 0.5, ys.mean() + 0.5), box


@pytest.fixture(scope="module")
def pano():
    return paint_discs([(100.0, 10.0, 4.0, RED), (30.0, 40.0, 4.0, (255, 0, 0)),
                        (180.0, 0.0, 5.0, (0, 255, 0))])


def test_disc_appears_where_the_pinhole_puts_it(pano):
    view = PerspectiveView(yaw_deg=90.0, pitch_deg=0.0, hfov_deg=80.0, width_px=320, height_px=320)
    image = view.cut(pano)
    assert image.shape == (320, 320, 3)
    centroid, _ = red_blob(image)
    assert centroid == pytest.approx(pinhole(90.0, 0.0, 80.0, 320, 100.0, 10.0), abs=1.0)
    # the view's own projection agrees with the longhand one
    x, y, front = view.ray_to_pixel(ray(100.0, 10.0))
    assert front and (x, y) == pytest.approx(pinhole(90.0, 0.0, 80.0, 320, 100.0, 10.0), abs=1e-9)


def test_upward_view(pano):
    view = PerspectiveView(0.0, 35.0, 90.0, 320, 320)
    image = view.cut(pano)
    blue = (image[:, :, 0] > 170) & (image[:, :, 2] < 90)
    ys, xs = np.nonzero(blue)
    want = pinhole(0.0, 35.0, 90.0, 320, 30.0, 40.0)
    assert (xs.mean() + 0.5, ys.mean() + 0.5) == pytest.approx(want, abs=1.0)
    assert want[0] > 160  # right of centre: azimuth is clockwise


def test_disc_across_the_seam_is_whole_in_the_backward_view(pano):
    view = PerspectiveView(180.0, 0.0, 80.0, 320, 320)
    image = view.cut(pano)
    green = (image[:, :, 1] > 170) & (image[:, :, 2] < 90)
    ys, xs = np.nonzero(green)
    assert (xs.mean() + 0.5, ys.mean() + 0.5) == pytest.approx((160.0, 160.0), abs=0.5)
    assert xs.max() - xs.min() > 25  # both halves, not one half
    assert abs((xs.max() + 1 - 160) - (160 - xs.min())) <= 1  # symmetric about the seam


@pytest.mark.parametrize("yaw, az, el, radius", [(90.0, 100.0, 10.0, 4.0),
                                                 (180.0, 180.0, 0.0, 5.0),
                                                 (-150.0, -178.0, 12.0, 6.0)])
def test_view_box_maps_back_around_the_disc(yaw, az, el, radius):
    pano = paint_discs([(az, el, radius, RED)])
    view = PerspectiveView(yaw, 0.0, 80.0, 320, 320)
    _, box = red_blob(view.cut(pano))
    got = view.boxes_to_pano(box[None], W, H)[0]
    want = disc_pano_box(az, el, radius)
    want[[0, 2]] -= np.floor(want[0] / W) * W  # the contract's form: u0 in [0, W)
    # Contains the disc's extent (one view pixel is ~1.7 panorama pixels here) and is not
    # much larger: off the view's centre the view rectangle's corners reach beyond the disc.
    tol = 2.0
    assert 0 <= got[0] < W and got[0] < got[2] and got[1] < got[3]
    assert got[0] < want[0] + tol and got[1] < want[1] + tol, (got, want)
    assert got[2] > want[2] - tol and got[3] > want[3] - tol, (got, want)
    size, want_size = got[2:] - got[:2], want[2:] - want[:2]
    assert np.all(size < 1.2 * want_size), (got, want)
    if want[2] > W:  # across the seam: unwrapped
        assert got[0] < W < got[2]


def test_whole_view_holding_the_zenith_spans_all_columns():
    view = PerspectiveView(0.0, 70.0, 90.0, 64, 64)
    u0, v0, u1, v1 = view.boxes_to_pano([[0, 0, 64, 64]], W, H)[0]
    assert (u0, v0, u1) == (0.0, 0.0, W) and v1 > 0


def test_maps_are_cached_per_view_and_size():
    view = PerspectiveView(45.0, 0.0, 80.0, 64, 64)
    assert view.remap_maps(W, H) is view.remap_maps(W, H)
    assert PerspectiveView(45.0, 0.0, 80.0, 64, 64).remap_maps(W, H) is view.remap_maps(W, H)
    assert view.remap_maps(W // 2, H // 2) is not view.remap_maps(W, H)


def test_view_sets():
    views = ViewSet.default(640, upward=True, fore_aft=False)
    assert len(views) == 10 and [v.yaw_deg for v in views][:8] == [k * 45.0 for k in range(8)]
    assert len(ViewSet.default(640, upward=False, fore_aft=False)) == 8
    hfov = views[0].hfov_deg
    assert hfov - 45.0 >= 20.0  # neighbours overlap by at least 20 deg
    assert views.working_width(4096) == 4096
    assert 4000 <= views.working_width(8192) < 4200
    assert hash(views) == hash(ViewSet.default(640, upward=True, fore_aft=False))
    assert len(ViewSet.default(640)) == 8 + 2 * DEFAULT_UPWARD_VIEWS + 2 * DEFAULT_FORE_AFT_VIEWS  # the plugin's
    # fore and aft: two narrower views straight ahead and behind, after the horizon ring
    fa = ViewSet.default(640, upward=False, fore_aft=True)
    assert len(fa) == 10 and fa[:8] == ViewSet.default(640, upward=False, fore_aft=False)[:8]
    assert [(v.yaw_deg, v.pitch_deg) for v in fa[8:]] == [(0.0, 0.0), (180.0, 0.0)]
    assert all(v.hfov_deg == FORE_AFT_HFOV_DEG < 0.7 * views[0].hfov_deg for v in fa[8:])
    both = ViewSet.default(640, upward=True, fore_aft=True)
    assert len(both) == 12 and both[:10] == fa[:10]
    # upward: two views over the road ahead and behind
    assert [(v.yaw_deg, v.pitch_deg, v.hfov_deg) for v in both[10:]] == [
        (0.0, UPWARD_PITCH_DEG, UPWARD_HFOV_DEG), (180.0, UPWARD_PITCH_DEG, UPWARD_HFOV_DEG)]
    # training cuts the default views and the whole upward ring
    training = ViewSet.training(640)
    assert training[:len(ViewSet.default(640, upward=False))] == ViewSet.default(640, upward=False).views
    assert len(training) == len(ViewSet.default(640, upward=False)) + UPWARD_RING_VIEWS
    assert sorted(v.yaw_deg for v in training if v.looks_up) == [k * 60.0 for k in range(UPWARD_RING_VIEWS)]


def test_a_view_stretched_across_shows_a_disc_twice_as_wide_as_tall_where_the_pinhole_puts_it():
    pano = paint_discs([(95.0, 5.0, 3.0, RED)])
    square = PerspectiveView(90.0, 0.0, 50.0, 320, 320)
    stretched = PerspectiveView(90.0, 0.0, 50.0, 320, 320, stretch=2.0)
    assert stretched.focal_px == square.focal_px and stretched.focal_y_px == pytest.approx(square.focal_px / 2)
    assert stretched.vfov_deg > 1.5 * square.vfov_deg
    (cx, cy), box = red_blob(stretched.cut(pano))
    _, square_box = red_blob(square.cut(pano))
    # across as in the square view; up and down at half its density
    want_x, want_y = pinhole(90.0, 0.0, 50.0, 320, 95.0, 5.0)
    assert cx == pytest.approx(want_x, abs=1.0) and cy == pytest.approx(160.0 + 0.5 * (want_y - 160.0), abs=1.0)
    width, height = box[2] - box[0], box[3] - box[1]
    assert width == pytest.approx(square_box[2] - square_box[0], abs=1.0)
    assert width == pytest.approx(2.0 * height, rel=0.15)
    # rays round-trip, and the disc's box maps back around the disc in the panorama
    xs, ys = np.array([3.0, 160.0, 317.0]), np.array([5.0, 160.0, 300.0])
    x, y, front = stretched.ray_to_pixel(stretched.pixel_to_ray(xs, ys))
    assert front.all() and np.allclose(x, xs) and np.allclose(y, ys)
    got = stretched.boxes_to_pano(box[None], W, H)[0]
    want = disc_pano_box(95.0, 5.0, 3.0)
    assert np.all(np.abs(got - want) < 2.5), (got, want)


def test_a_ring_of_six_horizon_views_is_turned_so_its_seams_fall_in_the_fore_and_aft_views():
    assert DEFAULT_HORIZON_VIEWS == 8
    assert ViewSet.default(640, horizon_views=8) == ViewSet.default(640)
    six = ViewSet.default(640, upward=True, fore_aft=True, horizon_views=6)
    eight = ViewSet.default(640, upward=True, fore_aft=True)
    assert len(six) == len(eight) - 2
    assert [v.yaw_deg for v in six[:6]] == [30.0 + 60.0 * k for k in range(6)]
    assert all(v.hfov_deg == HORIZON_HFOV_DEG and v.pitch_deg == 0.0 for v in six[:6])
    assert six[6:] == eight[8:]                        # the fore-and-aft and upward views as before
    # the seams ahead and behind (0 and 180 deg) lie inside the fore-and-aft views
    fore, aft = six[6], six[7]
    for seam_deg, view in ((0.0, fore), (180.0, aft)):
        assert abs((seam_deg - view.yaw_deg + 180.0) % 360.0 - 180.0) < 0.5 * FORE_AFT_HFOV_DEG
    # neighbouring views still overlap by 20 deg
    yaws = [v.yaw_deg for v in six[:6]] + [six[0].yaw_deg + 360.0]
    assert all(HORIZON_HFOV_DEG - step >= 20.0 for step in np.diff(yaws))
    with pytest.raises(ValueError, match="7 views"):
        ViewSet.default(640, horizon_views=7)


def test_the_horizon_as_one_band_replaces_the_ring_and_keeps_the_other_views():
    assert HORIZON_CHOICES == (8, 6, HORIZON_BAND)
    assert [horizon_choice(t) for t in ("8", "6", "band")] == list(HORIZON_CHOICES)
    with pytest.raises(ValueError, match="horizon views '7'"):
        horizon_choice("7")
    band = ViewSet.default((640, 384), horizon_views=HORIZON_BAND)
    eight = ViewSet.default((640, 384))
    assert band[0] == BandView(*HORIZON_BAND_SIZE_PX, HORIZON_BAND_MARGIN_DEG)
    assert band[1:] == eight[8:]                       # the fore-and-aft and upward views as before
    assert band[0].own_size and not any(v.own_size for v in eight)
    b = band[0]
    assert b.width_px % 32 == 0 and b.height_px % 32 == 0
    # one density both ways, at least the ring's at its views' centres, and the ring's elevations
    assert b.density_px_per_deg == pytest.approx(b.width_px / (360.0 + 2 * HORIZON_BAND_MARGIN_DEG))
    assert b.density_px_per_deg >= eight[0].focal_px * np.pi / 180.0
    assert b.vfov_deg / 2.0 >= np.degrees(np.arctan(0.5 * eight[0].height_px / eight[0].focal_px)) - 0.5


@pytest.mark.parametrize("az, el", [(0.0, 0.0), (37.0, 12.0), (-120.0, -15.0), (179.0, 5.0), (-178.0, -3.0)])
def test_the_band_shows_a_disc_where_its_azimuth_and_elevation_say_and_maps_its_box_back(az, el):
    """A disc painted on the sphere: its centroid in the band at the linear azimuth and
    elevation position, its band box mapped back onto the disc's panorama box; near the
    +-180 deg seam the disc is in the band twice, whole at one end and at the other."""
    band = BandView(1568, 224, 12.0)                   # 4 px a degree, +-28 deg
    radius = 3.0
    image = band.cut(paint_discs([(az, el, radius, RED)]))
    assert image.shape == (224, 1568, 3)
    mask = (image[:, :, 2] > 170) & (image[:, :, 1] < 90)
    n_labels, labels = cv2.connectedComponents(mask.astype(np.uint8))
    k = band.density_px_per_deg
    copies = 2 if abs(az) > 180.0 - HORIZON_BAND_MARGIN_DEG + radius else 1
    assert n_labels - 1 == copies
    expected = disc_pano_box(az, el, radius)
    for label in range(1, n_labels):
        ys, xs = np.nonzero(labels == label)
        x_centre = xs.mean() + 0.5
        # at the azimuth (or its copy 360 deg on) and the elevation
        az_seen = x_centre / k - 180.0 - 12.0
        assert min(abs(az_seen - az), abs(az_seen - az - 360.0), abs(az_seen - az + 360.0)) < 0.3
        assert (0.5 * band.height_px - (ys.mean() + 0.5)) / k == pytest.approx(el, abs=0.3)
        box = np.array([[xs.min(), ys.min(), xs.max() + 1, ys.max() + 1]], float)
        pano_box = band.boxes_to_pano(box, W, H)[0]
        assert 0.0 <= pano_box[0] < W and pano_box[2] > pano_box[0]
        shift = W * np.round((pano_box[0] - expected[0]) / W)
        assert np.allclose(pano_box - [shift, 0, shift, 0], expected, atol=W / 360.0)   # within a degree
    # the copy in a margin ranks under the one that is not
    if copies == 2:
        boxes = [[xs.min(), 0, xs.max() + 1, 1] for xs in (np.nonzero(labels == lab)[1] for lab in (1, 2))]
        central = band.centrality(np.array(boxes, float))
        from_end = [min(0.5 * (b[0] + b[2]), band.width_px - 0.5 * (b[0] + b[2])) for b in boxes]
        assert np.argmax(central) == np.argmax(from_end) and central.max() > central.min()
        assert band.centrality(np.array([[780.0, 0, 790, 1], [0, 0, 0, 1]])).tolist() == [1.0, 0.0]
        assert band.touches_side(np.array([[0.0, 50, 20, 60], [700, 50, 720, 60], [1560, 50, 1568, 60]])).tolist() \
            == [True, False, True]


def test_the_band_is_round_trip_exact_between_its_pixels_and_rays():
    band = BandView(*HORIZON_BAND_SIZE_PX, HORIZON_BAND_MARGIN_DEG)
    x = np.array([200.0, 1632.0, 3000.0])
    y = np.array([10.0, 224.0, 440.0])
    x_back, y_back, front = band.ray_to_pixel(band.pixel_to_ray(x, y))
    assert front.all()
    assert np.allclose(x_back, x) and np.allclose(y_back, y)
    assert band.centre_u_px(W) == W / 2 and not band.looks_up


def test_denser_views_do_not_change_how_the_others_are_cut_from_a_large_panorama():
    """An 8K panorama: the 80 deg ring needs half its pixels and is cut from it reduced by 2
    (not aliased); the fore-and-aft views need nearly all of them and are cut from the
    panorama itself. Adding them leaves the ring's images as they were."""
    rng = np.random.default_rng(5)
    big = cv2.resize(rng.integers(0, 255, (256, 512, 3), dtype=np.uint8), (8192, 4096),
                     interpolation=cv2.INTER_NEAREST)
    ring = ViewSet.default((640, 384), upward=False, fore_aft=False)
    both = ViewSet.default((640, 384), upward=False, fore_aft=True)
    assert ring.working_width(8192) == 4096 and both.working_width(8192) == 8192
    ring_images, both_images = list(ring.cut_all(big)), list(both.cut_all(big))
    for a, b in zip(ring_images, both_images[:8]):
        np.testing.assert_array_equal(a, b)
    for view, image in zip(both[8:], both_images[8:]):
        np.testing.assert_array_equal(image, view.cut(big))


def test_large_panorama_is_reduced_before_cutting_and_boxes_stay_in_its_pixels(pano):
    views = ViewSet.ring(8, 0.0, 80.0, 160)  # needs ~1020 px of width: 2048 is reduced
    assert views.working_width(W) < W / 1.5
    images = list(views.cut_all(pano))
    view = views[2]  # yaw 90
    centroid, box = red_blob(images[2])
    assert centroid == pytest.approx(pinhole(90.0, 0.0, 80.0, 160, 100.0, 10.0), abs=1.0)
    got = view.boxes_to_pano(box[None], W, H)[0]
    assert np.all(np.abs(got - disc_pano_box(100.0, 10.0, 4.0)) < 5.0)


def test_read_panorama(tmp_path):
    good = tmp_path / "pano é.png"  # a non-ASCII name
    cv2.imencode(".png", np.zeros((8, 16, 3), np.uint8))[1].tofile(str(good))
    assert read_panorama(str(good)).shape == (8, 16, 3)
    with pytest.raises(InputError, match="not found.*missing.jpg"):
        read_panorama(str(tmp_path / "missing.jpg"))
    bad = tmp_path / "corrupt.jpg"
    bad.write_text("not an image")
    with pytest.raises(InputError, match="corrupt.jpg"):
        read_panorama(str(bad))
    square = tmp_path / "square.png"
    cv2.imencode(".png", np.zeros((8, 8, 3), np.uint8))[1].tofile(str(square))
    with pytest.raises(InputError, match="twice as wide"):
        read_panorama(str(square))
    assert read_panorama(str(square), require_equirectangular=False).shape == (8, 8, 3)
