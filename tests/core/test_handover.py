"""The handover package's core: selection by review state, track and road measures, true and
grid azimuths, times, OpenStreetMap nodes beside the road, the writers and the checks."""
import csv
import json
import math
import os
import subprocess
import xml.etree.ElementTree as ET
from datetime import date, datetime

import numpy as np
import pytest
from pyproj import Geod, Transformer

from roadsigns.core import handover as H
from roadsigns.core.errors import InputError
from roadsigns.core.schema import names

CRS = "EPSG:32633"
#: east of the central meridian (15 E) at about 17.4 E, 48 N: meridian convergence ~ +1.8 deg
X0, Y0 = 680000.0, 5320000.0
T0 = 388800.0   # GPS seconds of the week: Thursday 12:00


def _stations(n=41, step=5.0):
    """A drive due east along y = Y0, one station every 5 m and 0.5 s."""
    return [dict(station_id=k + 1, image="p{:03d}.jpg".format(k), x=X0 + step * k, y=Y0, z=300.0,
                 time=T0 + 0.5 * k) for k in range(n)]


def _sign(sign_id, dx, dy, azimuth, status="accepted", images=(8, 9, 10), **extra):
    record = dict(sign_id=sign_id, x=X0 + dx, y=Y0 + dy, z=303.0, height=2.5, bottom_height=2.2, width=0.6,
                  panel_height=0.6, azimuth=azimuth, n_views=len(images), best_image="p{:03d}.jpg".format(images[-1]),
                  source_images=";".join("p{:03d}.jpg".format(k) for k in images), score=0.9,
                  position_source="lidar", review_status=status, reviewed_at="2024-03-15T08:00:00+00:00")
    record["class"] = extra.pop("klass", "prohibitory")
    record.update(extra)
    return record


@pytest.fixture(scope="module")
def signs():
    return [
        _sign(1, 50.0, -6.0, 270.0, images=(4, 6, 8), code="206"),     # right, faces the drive
        _sign(2, 100.0, 5.0, 90.0, images=(21, 22, 23)),                # left, faces the other way
        _sign(3, 150.0, -0.5, 270.0, status="corrected", images=(24, 26, 28), reviewed_code="C3",
              klass="information", reviewed_class="warning"),           # on a gantry, over the road
        _sign(4, 60.0, -6.0, 270.0, status="rejected"),
        _sign(5, 70.0, -6.0, 0.0, status=None, klass="stop"),
    ]


@pytest.fixture(scope="module")
def road():
    """The road's centre line, 1.75 m left of the drive, from 10 m before the first station."""
    return [H.Road("A1", [np.array([[X0 - 10.0, Y0 + 1.75], [X0 + 100.0, Y0 + 1.75], [X0 + 210.0, Y0 + 1.75]])]),
            H.Road("B7", [np.array([[X0 + 50.0, Y0 + 40.0], [X0 + 50.0, Y0 + 200.0]])])]


def _by_id(result):
    return {r["sign_id"]: r for r in result.records}


def test_selection_by_review_state(signs):
    result = H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(survey_date=date(2024, 3, 14)))
    assert [r["sign_id"] for r in result.records] == [1, 2, 3]      # accepted and corrected
    assert result.counts == {"accepted": 2, "corrected": 1, "rejected": 1, "unsure": 0, "unreviewed": 1}
    assert "3 of 5 signs handed over" in result.messages[-1] and "1 rejected, 1 unreviewed" in result.messages[-1]
    only = H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(states=("rejected", "unreviewed")))
    assert [r["sign_id"] for r in only.records] == [4, 5]
    assert only.records[1]["review_status"] == "unreviewed"
    with pytest.raises(InputError, match="No sign has the review state"):
        H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(states=("unsure",)))
    with pytest.raises(InputError, match="Unknown review state"):
        H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(states=("maybe",)))


def test_fields_side_offset_chainage_facing_code(signs):
    result = H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(north="grid"))
    by_id = _by_id(result)
    assert set(by_id[1]) == set(names(H.HANDOVER_FIELDS))
    one, two, three = by_id[1], by_id[2], by_id[3]
    assert (one["side"], one["offset_m"], one["chainage_m"]) == ("right", pytest.approx(6.0), pytest.approx(50.0))
    assert (two["side"], two["offset_m"], two["chainage_m"]) == ("left", pytest.approx(5.0), pytest.approx(100.0))
    assert (three["side"], three["offset_m"]) == ("right", pytest.approx(0.5))
    assert (one["facing_traffic"], two["facing_traffic"]) == ("drive", "opposite")
    assert (one["azimuth"], two["azimuth"], one["azimuth_north"]) == (270, 90, "grid")
    assert (one["code"], one["class"], one["name"]) == ("206", "prohibitory", "prohibitory")
    assert (two["code"], three["code"], three["class"]) == ("", "C3", "warning")
    assert (three["review_status"], one["reviewed_at"]) == ("corrected", "2024-03-15T08:00:00+00:00")
    assert (one["height"], one["bottom_height"], one["width"], one["panel_height"]) == (2.5, 2.2, 0.6, 0.6)
    assert one["source_images"] == "p004.jpg;p006.jpg;p008.jpg" and one["n_views"] == 3
    assert one["road_id"] is None and one["condition"] is None and one["pole"] is None
    lon, lat = Transformer.from_crs(CRS, "EPSG:4326", always_xy=True).transform(X0 + 50.0, Y0 - 6.0)
    assert (one["lon"], one["lat"]) == (pytest.approx(lon, abs=1e-9), pytest.approx(lat, abs=1e-9))
    assert 17.0 < one["lon"] < 18.0 and 47.0 < one["lat"] < 49.0


def test_true_azimuth_is_the_geodesic_direction_of_the_face(signs):
    """True = grid + convergence, checked against the geodesic azimuth of the grid direction."""
    grid = _by_id(H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(north="grid")))
    true = _by_id(H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(north="true")))
    to_lonlat = Transformer.from_crs(CRS, "EPSG:4326", always_xy=True)
    for sign in signs[:3]:
        a = math.radians(sign["azimuth"])
        lon0, lat0 = to_lonlat.transform(sign["x"], sign["y"])
        lon1, lat1 = to_lonlat.transform(sign["x"] + 50 * math.sin(a), sign["y"] + 50 * math.cos(a))
        geodesic = Geod(ellps="WGS84").inv(lon0, lat0, lon1, lat1)[0] % 360.0
        assert true[sign["sign_id"]]["azimuth"] == int(round(geodesic)) % 360
        assert true[sign["sign_id"]]["azimuth_north"] == "true"
    assert true[1]["azimuth"] - grid[1]["azimuth"] == 2            # 270 + 1.8 -> 272


def test_a_drive_passing_twice_links_each_sign_to_the_pass_that_saw_it():
    out = [dict(station_id=k + 1, image="o{}.jpg".format(k), x=X0 + 5.0 * k, y=Y0, z=0.0, time=float(k))
           for k in range(21)]
    back = [dict(station_id=22 + k, image="b{}.jpg".format(k), x=X0 + 100.0 - 5.0 * k, y=Y0 + 8.0, z=0.0,
                 time=21.0 + k) for k in range(21)]
    # between the two passes, 3 m from the outward one, seen from the way back: its left side
    sign = _sign(1, 40.0, 3.0, 270.0, images=(0,))
    sign["source_images"] = "b10.jpg;b11.jpg"
    record = H.build_handover([sign], out + back, CRS).records[0]
    assert record["side"] == "left" and record["offset_m"] == pytest.approx(5.0)
    assert record["chainage_m"] == pytest.approx(100.0 + 8.0 + 60.0)   # 100 out, 8 across, 60 back
    assert record["first_seen_s"] == 31.0 and record["last_seen_s"] == 32.0


def test_road_network_link(signs, road):
    result = H.build_handover(signs, _stations(), CRS, roads=road)
    by_id = _by_id(result)
    assert by_id[1]["road_id"] == "A1"
    assert by_id[1]["road_fraction"] == pytest.approx(60.0 / 220.0)
    assert by_id[1]["road_distance_m"] == pytest.approx(7.75)
    assert by_id[2]["road_distance_m"] == pytest.approx(3.25)
    assert H.nearest_road((X0 + 50.0, Y0 + 100.0), road)[:3] == ("B7", pytest.approx(60 / 160), pytest.approx(0.0))
    assert H.nearest_road((0, 0), []) is None


def test_times_in_each_time_base(signs):
    assert H.gps_utc_offset_s(date(2024, 3, 14)) == 18 and H.gps_utc_offset_s(date(2010, 1, 1)) == 15
    # GPS seconds of the week: the week of the survey date (Sunday 10 March 2024)
    assert H.station_time_utc(T0, H.TIME_GPS_WEEK, date(2024, 3, 14)).isoformat() == "2024-03-14T11:59:42+00:00"
    assert H.station_time_utc(T0, H.TIME_GPS_WEEK, date(2024, 3, 10)).isoformat() == "2024-03-14T11:59:42+00:00"
    assert H.station_time_utc(T0, H.TIME_GPS_WEEK, None) is None
    assert H.station_time_utc(1710417600.0, H.TIME_UNIX, None).isoformat() == "2024-03-14T12:00:00+00:00"
    gps_seconds = (datetime(2024, 3, 14, 12) - datetime(1980, 1, 6)).total_seconds()   # Thursday 12:00 GPS
    assert H.station_time_utc(gps_seconds, H.TIME_GPS, None).isoformat() == "2024-03-14T11:59:42+00:00"
    assert H.station_time_utc(None, H.TIME_UNIX, None) is None
    result = H.build_handover(signs, _stations(), CRS, params=H.HandoverParams(survey_date=date(2024, 3, 14)))
    one = _by_id(result)[1]
    assert (one["first_seen_s"], one["last_seen_s"]) == (T0 + 2.0, T0 + 4.0)
    assert (one["first_seen"], one["last_seen"], one["survey_date"]) == \
        ("2024-03-14T11:59:44Z", "2024-03-14T11:59:46Z", "2024-03-14")
    undated = H.build_handover(signs, _stations(), CRS)
    assert _by_id(undated)[1]["first_seen"] is None and _by_id(undated)[1]["survey_date"] is None
    assert any("give the survey date" in m for m in undated.messages)


def test_osm_nodes_beside_the_road_with_tags(signs, road):
    result = H.build_handover(signs, _stations(), CRS, roads=road,
                              params=H.HandoverParams(country="de", survey_date=date(2024, 3, 14), osm_offset_m=2.0))
    nodes = {n.sign_id: n for n in result.nodes}
    assert nodes[1].tags == {"traffic_sign": "DE:206", "direction": "272", "survey:date": "2024-03-14"}
    assert nodes[2].tags["traffic_sign"] == "yes" and "prohibitory" in nodes[2].tags["fixme"]
    assert nodes[3].tags["traffic_sign"] == "DE:C3"
    # sign 1 is 6 m right of the drive: it stays where it is
    assert (nodes[1].x, nodes[1].y) == (pytest.approx(X0 + 50.0), pytest.approx(Y0 - 6.0))
    # sign 3 hangs over the lane, 0.5 m right of the drive: its node goes 2 m right of it
    assert (nodes[3].x, nodes[3].y) == (pytest.approx(X0 + 150.0), pytest.approx(Y0 - 2.0))
    # sign 2 is 5 m left of the drive but 3.25 m from the road line: stays; every node >= 2 m from the road
    for node in nodes.values():
        assert H.nearest_road((node.x, node.y), road)[2] >= 2.0 - 1e-9
    # a sign right on the road's centre line goes to the side of the drive it is on
    on_road = _sign(9, 80.0, 1.75, 270.0)
    node = H.build_handover([on_road], _stations(), CRS, roads=road).nodes[0]
    assert node.y - (Y0 + 1.75) == pytest.approx(2.0) and node.x == pytest.approx(X0 + 80.0)


def test_osm_values_without_a_code():
    assert H.osm_sign_value(None, "stop", "") == ("stop", None)
    assert H.osm_sign_value("", "yield", "NL") == ("give_way", None)
    assert H.osm_sign_value("NL:B6", "yield", "DE") == ("NL:B6", None)
    assert H.osm_sign_value("206", "stop", "") == ("206", None)


def test_writers_round_trip(tmp_path, signs, road):
    result = H.build_handover(signs, _stations(), CRS, roads=road,
                              params=H.HandoverParams(country="DE", survey_date=date(2024, 3, 14)))
    H.write_csv(str(tmp_path / "h.csv"), result.records)
    with open(tmp_path / "h.csv", encoding="utf-8", newline="") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == list(names(H.HANDOVER_FIELDS))
    assert rows[0]["code"] == "206" and rows[0]["azimuth"] == "272" and rows[0]["condition"] == ""
    assert float(rows[0]["x"]) == pytest.approx(X0 + 50.0) and rows[1]["side"] == "left"
    H.write_osm_xml(str(tmp_path / "s.osm"), result.nodes)
    root = ET.parse(str(tmp_path / "s.osm")).getroot()
    assert root.tag == "osm" and root.get("version") == "0.6"
    xml_nodes = root.findall("node")
    assert [n.get("id") for n in xml_nodes] == ["-1", "-2", "-3"]
    assert {t.get("k"): t.get("v") for t in xml_nodes[0].findall("tag")}["traffic_sign"] == "DE:206"
    assert float(xml_nodes[0].get("lat")) == pytest.approx(result.nodes[0].lat, abs=1e-8)
    H.write_osm_geojson(str(tmp_path / "s.geojson"), result.nodes)
    with open(tmp_path / "s.geojson") as f:
        collection = json.load(f)
    feature = collection["features"][2]
    assert feature["id"] == 3 and feature["properties"]["traffic_sign"] == "DE:C3"
    node = result.nodes[2]
    assert feature["geometry"]["coordinates"] == [pytest.approx(node.lon), pytest.approx(node.lat)]


def test_bad_inputs(tmp_path, signs):
    with pytest.raises(InputError, match="fewer than two stations"):
        H.build_handover(signs, _stations(n=1), CRS)
    with pytest.raises(InputError, match="geographic CRS"):
        H.build_handover(signs, _stations(), "EPSG:4326")
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match="is a file, not a folder"):
        H.check_output_folder(str(tmp_path / "file" / "out"))
    H.check_output_folder(str(tmp_path / "new" / "deeper"))        # made when written
    assert not os.path.exists(tmp_path / "new")
    locked = tmp_path / "locked"
    locked.mkdir()
    os.chmod(locked, 0o555)
    immutable = subprocess.run(["chattr", "+i", str(locked)], capture_output=True).returncode == 0
    try:
        if os.access(locked, os.W_OK) and not immutable:
            pytest.skip("cannot make a folder unwritable here")
        with pytest.raises(InputError, match="is not writable"):
            H.check_output_folder(str(locked / "package"))
    finally:
        if immutable:
            subprocess.run(["chattr", "-i", str(locked)], check=True)
        os.chmod(locked, 0o755)


def test_parse_states():
    assert H.parse_states(["Rejected", "accepted"]) == ("accepted", "rejected")
    assert H.parse_states([""]) == ("unreviewed",)
