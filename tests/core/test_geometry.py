"""core.geometry against hand-worked answers, scipy's Rotation and round trips."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from roadsigns.core import geometry as g

W, H = 4096, 2048
angles = st.floats(-180, 180, allow_nan=False)


def station(heading_deg=0.0, roll_deg=0.0, pitch_deg=0.0, boresight=(0.0, 0.0, 0.0)):
    return g.R_world_from_pano(roll_deg, pitch_deg, heading_deg, g.R_body_from_pano(*boresight))


def test_ned_to_enu_swap_is_a_proper_rotation():
    assert np.allclose(g.R_ENU_FROM_NED @ [1, 2, 3], [2, 1, -3])
    assert np.isclose(np.linalg.det(g.R_ENU_FROM_NED), 1.0)


def test_point_to_the_right_lands_at_three_quarters_width():
    for heading in (0.0, 37.0, 271.5):
        R = station(heading)
        h = np.radians(heading)
        right_enu = np.array([np.cos(h), -np.sin(h), 0.0])  # heading + 90 deg, clockwise
        u, v, rng = g.world_to_pixel(10.0 * right_enu, np.zeros(3), R, W, H)
        assert u == pytest.approx(0.75 * W, abs=1e-6)
        assert v == pytest.approx(0.5 * H, abs=1e-6)
        assert rng == pytest.approx(10.0)


def test_forward_is_centre_column_and_up_is_top():
    R = station(90.0)  # facing east
    u, v, _ = g.world_to_pixel([5.0, 0.0, 0.0], np.zeros(3), R, W, H)
    assert (u, v) == pytest.approx((W / 2, H / 2))
    u, v, _ = g.world_to_pixel([5.0, 0.0, 5.0], np.zeros(3), R, W, H)  # 45 deg up
    assert v == pytest.approx(H / 4)
    u, v, _ = g.world_to_pixel([0.0, -5.0, 0.0], np.zeros(3), R, W, H)  # south = right of east
    assert u == pytest.approx(0.75 * W)


def test_lever_arm_moves_the_centre_in_the_body_frame():
    C = np.array([100.0, 200.0, 10.0])
    # heading 90 (east), level: body x = east, y = south, z = down
    centre = g.pano_centre_world(C, 0.0, 0.0, 90.0, [1.0, 0.5, -2.0])
    assert centre == pytest.approx(C + [1.0, -0.5, 2.0])
    # a point 10 m east of C at C's height, seen from 2 m up and 1 m forward: 9 m ahead, below
    R = station(90.0)
    u, v, rng = g.world_to_pixel(C + [10.0, -0.5, 0.0], centre, R, W, H)
    eps = -np.arctan2(2.0, 9.0)
    assert u == pytest.approx(W / 2)
    assert v == pytest.approx(H * (0.5 - eps / np.pi))
    assert rng == pytest.approx(np.hypot(9.0, 2.0))


def test_boresight_yaw_and_pitch_move_a_ray():
    # yaw 90: the panorama's forward axis looks to the vehicle's right
    R = station(0.0, boresight=(0.0, 0.0, 90.0))
    u, v, _ = g.world_to_pixel([10.0, 0.0, 0.0], np.zeros(3), R, W, H)  # east = right of north
    assert (u, v) == pytest.approx((W / 2, H / 2))
    # pitch +10: panorama forward tilted up, so a horizon point ahead appears 10 deg low
    R = station(0.0, boresight=(0.0, 10.0, 0.0))
    u, v, _ = g.world_to_pixel([0.0, 10.0, 0.0], np.zeros(3), R, W, H)
    assert u == pytest.approx(W / 2)
    assert v == pytest.approx(H * (0.5 + 10.0 / 180.0))
    # roll +5 (right side down): a point 10 m to the right appears 5 deg up... of the right side
    R = station(0.0, boresight=(5.0, 0.0, 0.0))
    u, v, _ = g.world_to_pixel([10.0, 0.0, 0.0], np.zeros(3), R, W, H)
    assert u == pytest.approx(0.75 * W)
    assert v == pytest.approx(H * (0.5 - 5.0 / 180.0))


def test_vehicle_roll_is_right_side_down_and_pitch_nose_up():
    R = station(0.0, roll_deg=5.0)
    _, v, _ = g.world_to_pixel([10.0, 0.0, 0.0], np.zeros(3), R, W, H)
    assert v == pytest.approx(H * (0.5 - 5.0 / 180.0))  # right side lowered: a level point looks up
    R = station(0.0, pitch_deg=5.0)
    _, v, _ = g.world_to_pixel([0.0, 10.0, 0.0], np.zeros(3), R, W, H)
    assert v == pytest.approx(H * (0.5 + 5.0 / 180.0))  # nose up: a level point ahead looks down


def test_pixel_centres_and_seam():
    d = g.pixel_to_ray(0.5, H / 2, W, H)
    alpha, _ = g.ray_to_angles_rad(d)
    assert np.degrees(alpha) == pytest.approx(-180.0 + 180.0 / W)
    u, _ = g.ray_to_pixel([-1.0, -1e-12, 0.0], W, H)
    assert 0 <= u < W


@given(st.floats(0, W, exclude_max=True), st.floats(0.5, H - 0.5))
@settings(max_examples=300, deadline=None)
def test_pixel_ray_pixel_round_trip(u, v):
    d = g.pixel_to_ray(u, v, W, H)
    assert np.linalg.norm(d) == pytest.approx(1.0)
    u2, v2 = g.ray_to_pixel(d, W, H)
    du = (u2 - u + W / 2) % W - W / 2  # the seam: u = 0 and u = W are the same column
    assert abs(du) < 1e-6 and abs(v2 - v) < 1e-6


@given(angles, st.floats(-89, 89), angles)
@settings(max_examples=200, deadline=None)
def test_euler_zyx_matches_scipy(roll, pitch, yaw):
    R = g.euler_zyx_matrix(roll, pitch, yaw)
    assert np.allclose(R, Rotation.from_euler("ZYX", [yaw, pitch, roll], degrees=True).as_matrix())
    assert np.allclose(R, Rotation.from_euler("xyz", [roll, pitch, yaw], degrees=True).as_matrix())
    assert np.allclose(R @ R.T, np.eye(3)) and np.isclose(np.linalg.det(R), 1.0)


def _hamilton(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


@given(angles, st.floats(-89, 89), angles, st.lists(st.floats(-1, 1), min_size=3, max_size=3))
@settings(max_examples=200, deadline=None)
def test_quaternion_is_hamilton_scalar_first(roll, pitch, heading, vector):
    R = station(heading, roll, pitch, boresight=(0.3, -0.7, 1.1))
    q = g.quat_wxyz_from_matrix(R)
    assert q[0] >= 0 and np.linalg.norm(q) == pytest.approx(1.0)
    v = np.asarray(vector)
    rotated = _hamilton(_hamilton(q, np.r_[0.0, v]), q * [1, -1, -1, -1])[1:]
    assert np.allclose(rotated, R @ v, atol=1e-9)
    assert np.allclose(g.matrix_from_quat_wxyz(q), R, atol=1e-9)


def test_world_pano_round_trip_vectorised():
    rng = np.random.default_rng(3)
    R = station(123.0, 2.0, -1.0, boresight=(0.5, 0.2, -0.4))
    C = np.array([5.0, -3.0, 2.0])
    X = rng.normal(size=(1000, 3)) * 20
    d, r = g.world_to_pano_ray(X, C, R)
    assert np.allclose(g.pano_ray_to_world(d, r, C, R), X)
    u, v = g.ray_to_pixel(d, W, H)
    assert np.allclose(g.pixel_to_ray(u, v, W, H), d, atol=1e-9)


def test_forward_azimuth():
    assert g.pano_forward_azimuth_deg(station(0.0)) == pytest.approx(0.0)
    assert g.pano_forward_azimuth_deg(station(350.0, boresight=(0, 0, 20.0))) == pytest.approx(10.0)
    assert g.azimuth_deg_of_enu([-1.0, 0.0, 0.0]) == pytest.approx(270.0)
