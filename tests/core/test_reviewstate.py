"""Review states, verdict values, the review order and the sign views of the review panel."""
import math
from datetime import datetime, timezone

import numpy as np
import pytest
from helpers.synthpano import paint_discs

from roadsigns.core import reviewstate as rs
from roadsigns.core.signviews import PanoramaCache, context_view, sign_views

NOW = datetime(2024, 3, 14, 12, 30, 5, tzinfo=timezone.utc)


def test_states_of_status_values():
    assert rs.state_of(None) == rs.UNREVIEWED
    assert rs.state_of("  ") == rs.UNREVIEWED
    assert rs.state_of("Accepted ") == rs.ACCEPTED
    assert rs.state_of("odd") == "odd"
    assert rs.tally([None, "accepted", "rejected", "", "accepted"]) == {
        "accepted": 2, "corrected": 0, "rejected": 1, "unsure": 0, "unreviewed": 2}


def test_missing_fields_are_named_in_order():
    assert rs.missing_fields(["class", "score", "x"]) == ["sign_id", "source_images"]
    assert rs.missing_fields(["sign_id", "class", "score", "source_images", "chip"]) == []
    assert rs.missing_review_fields(["review_status", "class"]) == ["reviewed_class", "reviewed_code", "reviewed_at"]


def test_verdict_values():
    sign = {"class": "warning", "code": "101"}
    assert rs.verdict_values("accepted", sign, now=NOW) == {"review_status": "accepted",
                                                             "reviewed_at": "2024-03-14T12:30:05+00:00"}
    assert rs.verdict_values("rejected", sign, now=NOW)["review_status"] == "rejected"
    changed = rs.verdict_values("corrected", sign, new_class="prohibitory", new_code="206", now=NOW)
    assert changed == {"review_status": "corrected", "reviewed_at": "2024-03-14T12:30:05+00:00",
                       "reviewed_class": "prohibitory", "reviewed_code": "206"}
    # a "change" that changes nothing is an accept
    same = rs.verdict_values("corrected", sign, new_class="warning", new_code="101", now=NOW)
    assert same["review_status"] == "accepted" and same["reviewed_class"] is None
    code_only = rs.verdict_values("corrected", sign, new_class="warning", new_code="102", now=NOW)
    assert (code_only["reviewed_class"], code_only["reviewed_code"]) == (None, "102")
    with pytest.raises(ValueError):
        rs.verdict_values("maybe", sign)


def test_effective_class_and_code():
    assert rs.effective_class({"class": "warning", "reviewed_class": "stop"}) == "stop"
    assert rs.effective_class({"class": "warning", "reviewed_class": " "}) == "warning"
    assert rs.effective_code({"class": "warning"}) is None
    assert rs.effective_code({"code": 101}) == "101"
    assert rs.effective_code({"code": "101", "reviewed_code": "102"}) == "102"


def test_review_order_and_stepping():
    signs = [{"fid": 10, "sign_id": 3}, {"fid": 11, "sign_id": 1}, {"fid": 12, "sign_id": None},
             {"fid": 13, "sign_id": 2}]
    order = rs.review_order(signs)
    assert order == [11, 13, 10, 12]
    assert rs.step(order, 11) == 13
    assert rs.step(order, 12) == 11              # wraps round
    assert rs.step(order, 11, -1) == 12
    assert rs.step(order, 99) == 11
    assert rs.step([], 1) is None
    states = {11: "accepted", 13: None, 10: "rejected", 12: ""}
    assert rs.next_unreviewed(order, states, 11) == 13
    assert rs.next_unreviewed(order, states, 13) == 12    # skips the rejected one
    assert rs.next_unreviewed(order, states, 12) == 13    # wraps round
    assert rs.next_unreviewed(order, states, 12, -1) == 13
    assert rs.next_unreviewed(order, states, None) == 13
    assert rs.next_unreviewed(order, {k: "accepted" for k in order}, 11) is None


def test_image_names():
    assert rs.image_names("a.jpg; b.jpg;a.jpg;;") == ["a.jpg", "b.jpg"]
    assert rs.image_names(None) == []


# --- views of a sign ---------------------------------------------------------------------------

#: panorama forward = east, right = south, down = down (docs/formats.md 2.7)
Q_EAST = dict(qw=0.0, qx=1.0, qy=0.0, qz=0.0)


def _station(image, x, y=0.0, z=2.0, **extra):
    return dict(image=image, x=x, y=y, z=z, path="/nowhere/" + image, **Q_EAST, **extra)


def test_sign_views_best_first_and_centred_on_the_sign(tmp_path):
    import cv2

    sign = dict(x=20.0, y=-6.0, z=3.0, width=0.6, panel_height=0.6, azimuth=270.0,
                source_images="p0.jpg;p1.jpg;p2.jpg;p9.jpg", best_image="p1.jpg")
    stations = [_station("p0.jpg", 0.0), _station("p1.jpg", 5.0), _station("p2.jpg", 12.0),
                _station("p3.jpg", 15.0)]
    views = sign_views(sign, stations, folder=str(tmp_path))
    assert [v.image for v in views] == ["p1.jpg", "p2.jpg", "p0.jpg"]   # best, then range / cos
    assert views[0].best and views[0].path == str(tmp_path / "p1.jpg")
    assert views[1].range_m == pytest.approx(math.sqrt(8 ** 2 + 6 ** 2 + 1), rel=1e-9)
    # the pano of p2 with a red disc where the sign is: azimuth right of forward, above the horizon
    dx, dy, dz = 8.0, 6.0, 1.0   # east, south (right), up
    az, el = math.degrees(math.atan2(dy, dx)), math.degrees(math.atan2(dz, math.hypot(dx, dy)))
    pano = paint_discs([(az, el, 1.5, (0, 0, 255))], 1024)
    cv2.imwrite(str(tmp_path / "p2.jpg"), pano)
    chip = PanoramaCache().cut(views[1])
    assert chip.shape == (256, 256, 3)
    centre = chip[118:138, 118:138].reshape(-1, 3).mean(axis=0)
    assert centre[2] > 200 and centre[0] < 60                        # red in BGR
    assert chip[5, 5].tolist() != chip[128, 128].tolist()             # margin around it
    view, box = context_view(sign, stations[2], folder=str(tmp_path))
    x0, y0, x1, y1 = box
    assert (x0 + x1) / 2 == pytest.approx(480, abs=1) and (y0 + y1) / 2 == pytest.approx(270, abs=1)
    assert x1 > x0 and y1 > y0
    wide = PanoramaCache().cut(view)
    assert wide.shape == (540, 960, 3)


def test_signs_found_in_the_cloud_alone_are_shown_from_the_stations_in_front():
    sign = dict(x=20.0, y=-6.0, z=3.0, azimuth=270.0, source_images="", best_image=None)
    stations = [_station("p0.jpg", 0.0), _station("p1.jpg", 30.0), _station("far.jpg", -60.0)]
    views = sign_views(sign, stations)
    assert [v.image for v in views] == ["p0.jpg"]     # p1 is behind the face, far.jpg too far
    assert np.isfinite(views[0].incidence_deg)


def test_panorama_cache_keeps_the_last_ones(tmp_path):
    import cv2

    for k in range(3):
        cv2.imwrite(str(tmp_path / "{}.png".format(k)), np.full((8, 16, 3), k, np.uint8))
    cache = PanoramaCache(size=2)
    first = cache.get(str(tmp_path / "0.png"))
    assert cache.get(str(tmp_path / "0.png")) is first
    cache.get(str(tmp_path / "1.png"))
    cache.get(str(tmp_path / "2.png"))
    assert cache.get(str(tmp_path / "0.png")) is not first
