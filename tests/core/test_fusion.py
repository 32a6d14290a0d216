"""Image signs + cloud panels -> fused signs (core.fusion)."""
import numpy as np
import pytest
import shapely

from roadsigns.core import fusion as F
from roadsigns.core import geometry
from roadsigns.core.errors import InputError
from roadsigns.core.schema import names
from roadsigns.core.trajectory import Stations


def image_sign(sign_id, x, y, z, azimuth, cls="stop", score=0.9, position_source="cloud"):
    rec = {k: None for k in F._sign_field_names()}
    rec.update({"sign_id": sign_id, "class": cls, "score": score, "x": x, "y": y, "z": z,
                "azimuth": azimuth, "height": 2.5, "width": 0.6, "panel_height": 0.6,
                "position_source": position_source, "n_views": 3})
    return rec


def panel(sign_id, x, y, z, azimuth, bright_share=1.0, support="pole", condition="good"):
    return {"sign_id": sign_id, "x": x, "y": y, "z": z, "azimuth": azimuth, "height": 2.6,
            "bottom_height": 2.3, "width": 0.62, "panel_height": 0.61, "n_points": 200,
            "bright_share": bright_share, "support": support, "condition": condition,
            "retro_index": 1.2, "intensity_median": 1.1}


def by_image(result, image_id):
    return next(r for r in result.signs if r["image_sign_id"] == image_id)


def test_sources_scores_and_review_flags():
    images = [image_sign(10, 0.0, 0.0, 2.0, 90.0), image_sign(11, 20.0, 0.0, 2.0, 90.0, score=0.8)]
    panels = [panel(1, 0.05, 0.02, 2.01, 92.0), panel(2, 40.0, 0.0, 2.0, 270.0, bright_share=0.0)]
    res = F.fuse_signs(images, panels)
    assert (res.n_both, res.n_image_only, res.n_lidar_only, res.n_unconfirmed) == (1, 1, 1, 1)
    both = by_image(res, 10)
    assert both["source"] == F.SOURCE_BOTH and both["score"] == 0.9 and both["review"] == 0
    assert both["cloud_sign_id"] == 1 and both["condition"] == "good" and both["class"] == "stop"
    alone = by_image(res, 11)
    assert alone["source"] == F.SOURCE_IMAGE and alone["review"] == 1
    assert alone["score"] == pytest.approx(0.8 * F.UNCONFIRMED_SCORE_FACTOR)
    lidar = next(r for r in res.signs if r["source"] == F.SOURCE_LIDAR)
    assert lidar["class"] == F.UNKNOWN_CLASS and lidar["review"] == 1 and lidar["cloud_sign_id"] == 2
    assert lidar["score"] == pytest.approx(F.LIDAR_BASE_SCORE + F.LIDAR_SUPPORT_SCORE)
    assert [r["sign_id"] for r in res.signs] == [1, 2, 3]
    assert all(tuple(r) == names(F.FUSED_SIGN_FIELDS) for r in res.signs)
    assert {r["source"] for r in res.signs} <= set(F.SOURCES)


def test_outside_the_searched_area_an_image_sign_keeps_its_score():
    coverage = shapely.box(-5, -5, 5, 5)
    res = F.fuse_signs([image_sign(1, 0.0, 0.0, 2.0, 90.0), image_sign(2, 50.0, 0.0, 2.0, 90.0)], [],
                       coverage=coverage.wkt)
    inside, outside = by_image(res, 1), by_image(res, 2)
    assert inside["score"] == pytest.approx(0.9 * F.UNCONFIRMED_SCORE_FACTOR) and inside["review"] == 1
    assert outside["score"] == 0.9 and outside["review"] == 0 and res.n_unconfirmed == 1


def test_back_to_back_signs_match_by_facing():
    images = [image_sign(1, 0.0, 0.0, 2.0, 90.0, cls="stop"), image_sign(2, 0.0, 0.01, 2.0, 270.0, cls="yield")]
    panels = [panel(7, 0.0, 0.0, 2.0, 268.0), panel(8, 0.01, 0.0, 2.0, 91.0)]
    res = F.fuse_signs(images, panels)
    assert by_image(res, 1)["cloud_sign_id"] == 8 and by_image(res, 2)["cloud_sign_id"] == 7
    assert res.n_lidar_only == 0


def test_null_azimuths_do_not_veto_a_match():
    img = image_sign(1, 0.0, 0.0, 2.0, 90.0)
    img["azimuth"] = None
    pan = panel(3, 0.1, 0.0, 2.0, 90.0)
    pan["azimuth"] = None
    res = F.fuse_signs([img], [pan])
    assert res.n_both == 1 and by_image(res, 1)["cloud_sign_id"] == 3


def test_too_far_or_facing_away_is_not_a_match():
    res = F.fuse_signs([image_sign(1, 0.0, 0.0, 2.0, 90.0)],
                       [panel(1, 1.5, 0.0, 2.0, 90.0), panel(2, 0.1, 0.0, 2.0, 200.0)])
    assert res.n_both == 0 and res.n_lidar_only == 2


def test_triangulated_position_is_replaced_by_the_panel():
    res = F.fuse_signs([image_sign(1, 0.3, 0.2, 2.2, 90.0, position_source=F.TRIANGULATED)],
                       [panel(5, 0.0, 0.0, 2.0, 90.0)])
    fused = by_image(res, 1)
    assert (fused["x"], fused["y"], fused["z"]) == (0.0, 0.0, 2.0) and fused["position_source"] == "lidar"
    assert fused["width"] == 0.62


def test_sign_without_position_is_an_error():
    bad = image_sign(1, 0.0, 0.0, 2.0, 90.0)
    bad["x"] = None
    with pytest.raises(InputError):
        F.fuse_signs([bad], [])


def _stations(centres, heading_deg=0.0, width=2048):
    n = len(centres)
    R = geometry.R_world_from_pano(0.0, 0.0, heading_deg, np.eye(3))
    q = np.repeat(geometry.quat_wxyz_from_matrix(R)[None, :], n, axis=0)
    return Stations(image=["p{}.jpg".format(i) for i in range(n)], path=[""] * n,
                    time_s=np.arange(n, dtype=float), xyz_world=np.asarray(centres, float),
                    q_world_from_pano_wxyz=q, heading_deg=np.full(n, heading_deg),
                    width_px=np.full(n, width), height_px=np.full(n, width // 2))


def test_panel_views_project_the_outline_and_skip_stations_behind_the_face():
    # a panel 10 m north of the first station, facing south (towards it); heading north
    corners = np.array([[-0.3, 10.0, 2.3], [0.3, 10.0, 2.3], [0.3, 10.0, 1.7], [-0.3, 10.0, 1.7]])
    st = _stations([[0.0, 0.0, 2.0], [0.0, 20.0, 2.0], [0.0, -60.0, 2.0]])
    views = F.panel_views(corners, st, normal_world=np.array([0.0, -1.0, 0.0]), max_range_m=40.0)
    assert [v["station"] for v in views] == [0]        # the second is behind the face, the third too far
    u0, v0, u1, v1 = views[0]["box"]
    W, H = 2048, 1024
    assert u0 < W / 2 < u1 and v0 < H / 2 < v1         # straight ahead, around the horizon
    assert (u1 - u0) == pytest.approx(W * 2 * np.degrees(np.arctan(0.3 / 10.0)) / 360.0, rel=0.02)
    assert views[0]["range_m"] == pytest.approx(10.0, abs=0.01)


def test_panel_views_unwrap_boxes_across_the_seam():
    # heading north: the seam (u = 0 / W) looks south; a panel straight behind the station
    corners = np.array([[-0.3, -10.0, 2.3], [0.3, -10.0, 2.3], [0.3, -10.0, 1.7], [-0.3, -10.0, 1.7]])
    views = F.panel_views(corners, _stations([[0.0, 0.0, 2.0]]))
    u0, _, u1, _ = views[0]["box"]
    assert 0 <= u0 < 2048 < u1 and (u1 - u0) < 100
