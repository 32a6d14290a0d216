"""roadsigns:exporthandover through ``qgis_process``: the package read back field by field
(GeoPackage with OGR, CSV, OSM XML), a round trip of the OpenStreetMap nodes against a test
road (beside it, on the sign's side, with the expected tags), the GeoJSON variant and road
ids from feature ids, and the bad inputs (missing fields named, an unwritable folder refused
before any work). The variants run in one more ``qgis_process`` start
(``helpers/processing_runner.py``)."""
import csv
import json
import math
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest
from helpers import reviewdata
from helpers.badinputs import write_layer
from helpers.reviewdata import EPSG, SIGNS, X0, Y0, Z0
from pyproj import Geod, Transformer

pytestmark = pytest.mark.qgis
RUNNER = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "helpers",
                      "processing_runner.py")
AT = "2024-03-15T08:00:00+00:00"
#: sign_id -> (status, reviewed_class, reviewed_code, reviewed_at)
REVIEW = {1: ("accepted", None, None, AT), 2: ("corrected", None, "274", AT), 3: ("rejected", None, None, AT),
          4: (None, None, None, None), 5: ("accepted", None, None, AT)}
ROAD_Y = Y0 + 1.75   # the road's centre line: 1.75 m left of the drive
#: the test road: two segments along the drive and a side road
ROADS = [("R1", [(X0 - 10.0, ROAD_Y), (X0 + 30.0, ROAD_Y)]), ("R2", [(X0 + 30.0, ROAD_Y), (X0 + 80.0, ROAD_Y)]),
         ("S9", [(X0 + 20.0, ROAD_Y + 5.0), (X0 + 20.0, ROAD_Y + 60.0)])]
TO_LONLAT = Transformer.from_crs("EPSG:{}".format(EPSG), "EPSG:4326", always_xy=True)
TO_UTM = Transformer.from_crs("EPSG:4326", "EPSG:{}".format(EPSG), always_xy=True)


def true_azimuth(x, y, grid_deg):
    """The geodesic azimuth of the grid direction ``grid_deg`` at (x, y), whole degrees."""
    a = math.radians(grid_deg)
    lon0, lat0 = TO_LONLAT.transform(x, y)
    lon1, lat1 = TO_LONLAT.transform(x + 50 * math.sin(a), y + 50 * math.cos(a))
    return int(round(Geod(ellps="WGS84").inv(lon0, lat0, lon1, lat1)[0] % 360.0)) % 360


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    folder = str(tmp_path_factory.mktemp("handover-data"))
    paths = reviewdata.build(folder, panoramas=False, review=REVIEW)

    def line(row):
        return "LINESTRING ({})".format(", ".join("{!r} {!r}".format(*p) for p in row["points"]))

    in_4326 = [dict(wvk_id=name, points=[TO_LONLAT.transform(*p) for p in points]) for name, points in ROADS]
    paths["roads_4326"] = write_layer(os.path.join(folder, "roads_4326.gpkg"), [("wvk_id", str)], in_4326, line,
                                      4326, _ogr("wkbLineString"))
    in_utm = [dict(kind="road", points=points) for _, points in ROADS]
    paths["roads_utm"] = write_layer(os.path.join(folder, "roads_utm.gpkg"), [("kind", str)], in_utm, line, EPSG,
                                     _ogr("wkbLineString"))
    return paths


def _ogr(name):
    from osgeo import ogr
    return getattr(ogr, name)


@pytest.fixture(scope="module")
def package(qgis_process, data, tmp_path_factory):
    """One export as a user would run it: roads in WGS 84 with an id field, true north."""
    out = str(tmp_path_factory.mktemp("handover") / "package")
    run = qgis_process.run("roadsigns:exporthandover", SIGNS=data["signs"], STATIONS=data["stations"],
                           ROADS=data["roads_4326"], ROAD_ID_FIELD="wvk_id", SURVEY_DATE="2024-03-14", COUNTRY="DE",
                           OUTPUT_FOLDER=out)
    assert run.returncode == 0, run.text
    return out, run.json


def read_gpkg(path):
    from osgeo import ogr
    dataset = ogr.Open(path)
    layer = dataset.GetLayerByName("handover")
    rows = {}
    for feature in layer:
        row = {layer.GetLayerDefn().GetFieldDefn(k).GetName(): feature.GetField(k)
               for k in range(feature.GetFieldCount())}
        row["geometry"] = feature.GetGeometryRef().ExportToIsoWkt()
        rows[row["sign_id"]] = row
    srs = layer.GetSpatialRef().GetAuthorityCode(None)
    return rows, srs


def test_the_package_files_and_the_log(package):
    out, result = package
    assert sorted(os.listdir(out)) == ["handover.csv", "handover.gpkg", "osm_signs.osm"]
    assert result["results"]["GEOPACKAGE"] == os.path.join(out, "handover.gpkg")
    info = "\n".join(result["log"]["info"])
    assert "The road network is in EPSG:4326: reprojected to EPSG:32633" in info
    assert "3 of 5 signs handed over (review states accepted, corrected); left out: 1 rejected, 1 unreviewed" in info


def test_geopackage_field_by_field(package):
    from roadsigns.core.handover import HANDOVER_FIELDS
    rows, srs = read_gpkg(os.path.join(package[0], "handover.gpkg"))
    assert srs == str(EPSG) and sorted(rows) == [1, 2, 5]
    one = rows[1]
    assert list(one)[:-1] == [f.name for f in HANDOVER_FIELDS]
    klass, dx, dy, height, azimuth, code, _ = SIGNS[1]
    lon, lat = TO_LONLAT.transform(X0 + dx, Y0 + dy)
    expected = dict(sign_id=1, code="206", name="prohibitory", **{"class": "prohibitory"}, x=X0 + dx, y=Y0 + dy,
                    z=Z0 + height, lon=lon, lat=lat, height=height, bottom_height=height - 0.3, width=0.6,
                    panel_height=0.6, azimuth=true_azimuth(X0 + dx, Y0 + dy, azimuth), azimuth_north="true",
                    side="right", offset_m=5.0, chainage_m=15.0, facing_traffic="drive", road_id="R1",
                    road_fraction=25.0 / 40.0, road_distance_m=6.75, condition="good", pole=None,
                    survey_date="2024-03-14", first_seen="2024-03-14T11:59:42Z", last_seen="2024-03-14T11:59:43Z",
                    first_seen_s=reviewdata.T0, last_seen_s=reviewdata.T0 + 1.0, n_views=3,
                    source_images="p00.jpg;p01.jpg;p02.jpg", best_image="p02.jpg", score=0.83,
                    position_source="lidar", review_status="accepted", reviewed_at=AT)
    for name, value in expected.items():
        assert one[name] == (pytest.approx(value, abs=1e-6) if isinstance(value, float) else value), name
    assert one["geometry"].startswith("POINT Z (")
    assert [float(v) for v in one["geometry"][9:-1].split()] == [X0 + dx, Y0 + dy, Z0 + height]
    # corrected: the new code, the class as it was; over the road: right of the drive, 0.4 m
    two, five = rows[2], rows[5]
    assert (two["code"], two["class"], two["review_status"], two["condition"]) == ("274", "warning", "corrected",
                                                                                   "poor")
    assert (two["side"], two["offset_m"], two["road_id"]) == ("right", pytest.approx(5.5), "R1")
    assert (five["code"], five["side"], five["offset_m"], five["chainage_m"]) == \
        ("C3", "right", pytest.approx(0.4), pytest.approx(55.0))
    assert (five["road_id"], five["road_fraction"], five["road_distance_m"]) == \
        ("R2", pytest.approx(0.5, abs=1e-4), pytest.approx(2.15, abs=1e-3))
    assert five["azimuth"] == true_azimuth(X0 + 55.0, Y0 - 0.4, 270.0) != 270


def test_csv_matches_the_geopackage(package):
    rows, _ = read_gpkg(os.path.join(package[0], "handover.gpkg"))
    with open(os.path.join(package[0], "handover.csv"), encoding="utf-8", newline="") as f:
        table = list(csv.DictReader(f))
    assert [int(r["sign_id"]) for r in table] == [1, 2, 5]
    for row in table:
        expected = rows[int(row["sign_id"])]
        for name, text in row.items():
            value = expected[name]
            if value is None:
                assert text == "", name
            elif isinstance(value, float):
                assert float(text) == pytest.approx(value, abs=2e-3), name
            else:
                assert text == str(value), name


def test_osm_round_trip_beside_the_road(package):
    """OSM nodes read back: every one beside the test road (2 m or more from every road
    line), on its sign's side, with the sign's tags; the one over the road moved off it."""
    root = ET.parse(os.path.join(package[0], "osm_signs.osm")).getroot()
    assert root.tag == "osm" and root.get("version") == "0.6"
    nodes = {-int(n.get("id")): n for n in root.findall("node")}
    assert sorted(nodes) == [1, 2, 5]
    expected_tags = {1: "DE:206", 2: "DE:274", 5: "DE:C3"}
    for sign_id, node in nodes.items():
        _, dx, dy, _, azimuth, _, _ = SIGNS[sign_id]
        x, y = TO_UTM.transform(float(node.get("lon")), float(node.get("lat")))
        tags = {t.get("k"): t.get("v") for t in node.findall("tag")}
        assert tags == {"traffic_sign": expected_tags[sign_id], "survey:date": "2024-03-14",
                        "direction": str(true_azimuth(X0 + dx, Y0 + dy, azimuth))}
        assert abs(y - ROAD_Y) >= 2.0 - 1e-3 and (y - ROAD_Y) * ((Y0 + dy) - ROAD_Y) > 0   # beside, same side
        assert abs(y - Y0) >= 2.0 - 1e-3 and (y - Y0) * dy > 0                              # off the drive too
        assert abs(x - (X0 + dx)) < 0.01
        if sign_id != 5:
            assert y == pytest.approx(Y0 + dy, abs=0.01)                                   # not moved
    _, y5 = TO_UTM.transform(float(nodes[5].get("lon")), float(nodes[5].get("lat")))
    assert y5 == pytest.approx(Y0 - 2.0, abs=0.01)


# --- variants and bad inputs, in one qgis_process ----------------------------------------------

@pytest.fixture(scope="module")
def table(qgis_process, data, tmp_path_factory):
    work = tmp_path_factory.mktemp("handover-table")
    locked = work / "locked"
    locked.mkdir()
    os.chmod(locked, 0o555)
    immutable = subprocess.run(["chattr", "+i", str(locked)], capture_output=True).returncode == 0
    common = dict(SIGNS=data["signs"], STATIONS=data["stations"], OUTPUT_FOLDER="{out}/package")
    rows = [
        dict(id="geojson_grid_fid", algorithm="roadsigns:exporthandover",
             parameters=dict(common, ROADS=data["roads_utm"], STATES=[0, 1, 2, 3, 4], NORTH=1, OSM_FORMAT=1,
                             TIME_BASE=0)),
        dict(id="missing_fields", algorithm="roadsigns:exporthandover",
             parameters=dict(common, SIGNS=data["bare"])),
        dict(id="missing_review_status", algorithm="roadsigns:exporthandover",
             parameters=dict(common, SIGNS=reviewdata.build(str(work / "unreviewed"), panoramas=False)["signs"])),
        dict(id="unwritable_first", algorithm="roadsigns:exporthandover",
             parameters=dict(common, SIGNS=data["bare"], OUTPUT_FOLDER=str(locked / "package"))),
        dict(id="bad_date", algorithm="roadsigns:exporthandover", parameters=dict(common, SURVEY_DATE="14/03/2024")),
        dict(id="no_state_matches", algorithm="roadsigns:exporthandover", parameters=dict(common, STATES=[3])),
    ]
    table_path, results_path = str(work / "table.json"), str(work / "results.json")
    with open(table_path, "w") as f:
        json.dump({"work": str(work / "rows"), "rows": rows}, f)
    try:
        writable = os.access(str(locked), os.W_OK) and not immutable
        run = qgis_process("run", RUNNER, "--", "TABLE=" + table_path, "RESULTS=" + results_path, timeout=600)
    finally:
        if immutable:
            subprocess.run(["chattr", "-i", str(locked)], check=True)
        os.chmod(locked, 0o755)
    assert run.returncode == 0 and os.path.exists(results_path), run.text
    with open(results_path) as f:
        results = json.load(f)["rows"]
    results["work"], results["locked_writable"], results["locked"] = str(work / "rows"), writable, str(locked)
    return results


def test_geojson_grid_north_and_feature_ids(table):
    row = table["geojson_grid_fid"]
    assert row["ok"], row["error"]
    folder = os.path.join(table["work"], "geojson_grid_fid", "package")
    assert sorted(os.listdir(folder)) == ["handover.csv", "handover.gpkg", "osm_signs.geojson"]
    rows, _ = read_gpkg(os.path.join(folder, "handover.gpkg"))
    assert sorted(rows) == [1, 2, 3, 4, 5]
    assert {k: r["review_status"] for k, r in rows.items()} == \
        {1: "accepted", 2: "corrected", 3: "rejected", 4: "unreviewed", 5: "accepted"}
    assert (rows[1]["azimuth"], rows[3]["azimuth"], rows[1]["azimuth_north"]) == (270, 90, "grid")
    assert (rows[1]["road_id"], rows[5]["road_id"]) == ("1", "2")          # feature ids of the GeoPackage
    assert (rows[3]["road_id"], rows[3]["road_distance_m"], rows[3]["side"]) == ("2", pytest.approx(4.25), "left")
    assert rows[1]["survey_date"] is None and rows[1]["first_seen"] is None  # no survey date given
    seen = "\n".join(text for _, text in row["seen"])
    assert "No road segment id field chosen: the road ids are the feature ids." in seen
    assert "give the survey date" in seen and "reprojected" not in seen
    with open(os.path.join(folder, "osm_signs.geojson")) as f:
        collection = json.load(f)
    features = {f["id"]: f for f in collection["features"]}
    assert sorted(features) == [1, 2, 3, 4, 5]
    assert features[4]["properties"] == {"traffic_sign": "stop", "direction": str(true_azimuth(X0 + 45, Y0 - 5, 270))}
    lon, lat = features[1]["geometry"]["coordinates"]
    assert TO_UTM.transform(lon, lat) == (pytest.approx(X0 + 15.0, abs=0.01), pytest.approx(Y0 - 5.0, abs=0.01))


def test_missing_fields_are_named(table):
    row = table["missing_fields"]
    assert not row["ok"]
    assert "missing field(s) sign_id, height, width, panel_height, azimuth, source_images, review_status" in \
        row["error"]
    assert table["missing_review_status"]["error"].startswith("Reviewed sign layer: missing field(s) review_status")
    for name in ("missing_fields", "missing_review_status"):
        assert table[name]["files"] == [], name


def test_an_unwritable_folder_is_refused_before_any_work(table):
    if table["locked_writable"]:
        pytest.skip("cannot make a folder unwritable here")
    row = table["unwritable_first"]
    assert not row["ok"]
    # the folder is checked first: the sign layer's missing fields are not even read
    assert row["error"].startswith("Cannot write the handover package to {}".format(
        os.path.join(table["locked"], "package"))) and "is not writable" in row["error"]
    assert not os.path.exists(os.path.join(table["locked"], "package"))


def test_other_bad_inputs(table):
    assert "Survey date '14/03/2024' is not a date" in table["bad_date"]["error"]
    error = table["no_state_matches"]["error"]
    assert "No sign has the review state(s) unsure (2 accepted, 1 corrected, 1 rejected, 1 unreviewed)" in error
    for name in ("bad_date", "no_state_matches"):
        assert table[name]["files"] == [], name
