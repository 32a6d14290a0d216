"""roadsigns:evaluate through qgis_process on hand-built layers and reference files."""
import html
import os

import pytest
from osgeo import ogr, osr

ALG = "roadsigns:evaluate"
REFERENCE = """sign_id,class,x,y,z,height,width,panel_height,azimuth
r1,stop,500000,5300000,102.0,2.0,0.6,0.6,90
r2,warning,500010,5300000,102.5,2.5,0.9,0.8,358
r3,mandatory,500020,5300000,102.0,2.0,0.6,0.6,180
"""


def write_signs(path, signs, epsg=32633, codes=None):
    """signs: (sign_id, class, x, y, z, height, azimuth); ``codes``: a field ``code`` with
    these values (None: NULL), else no such field."""
    driver = ogr.GetDriverByName("GPKG")
    ds = driver.CreateDataSource(path)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    layer = ds.CreateLayer("signs", srs, ogr.wkbPoint25D)
    for name, kind in (("sign_id", ogr.OFTString), ("class", ogr.OFTString),
                       ("height", ogr.OFTReal), ("azimuth", ogr.OFTReal), ("best_image", ogr.OFTString)):
        layer.CreateField(ogr.FieldDefn(name, kind))
    if codes is not None:
        layer.CreateField(ogr.FieldDefn("code", ogr.OFTString))
    for k, (sign_id, cls, x, y, z, height, azimuth) in enumerate(signs):
        feature = ogr.Feature(layer.GetLayerDefn())
        if codes is not None and codes[k] is not None:
            feature.SetField("code", codes[k])
        feature.SetField("sign_id", sign_id)
        feature.SetField("class", cls)
        feature.SetField("height", height)
        feature.SetField("azimuth", azimuth)
        feature.SetField("best_image", "pano_0001.jpg")
        point = ogr.Geometry(ogr.wkbPoint25D)
        point.AddPoint(x, y, z)
        feature.SetGeometry(point)
        layer.CreateFeature(feature)
    ds = None
    return path


@pytest.fixture
def reference_csv(tmp_path):
    path = tmp_path / "reference.csv"
    path.write_text(REFERENCE)
    return str(path)


def test_counts_errors_and_report(qgis_process, tmp_path, reference_csv):
    signs = write_signs(str(tmp_path / "signs.gpkg"), [
        ("s1", "stop", 500000.03, 5300000.04, 102.0, 2.02, 92.0),       # 5 cm off, right class
        ("s2", "prohibitory", 500010.0, 5300000.0, 102.6, 2.6, 2.0),   # 10 cm off, wrong class
        ("s9", "stop", 500050.0, 5300000.0, 102.0, 2.0, 0.0),          # false
    ])
    report = str(tmp_path / "report.html")
    run = qgis_process.run(ALG, SIGNS=signs, REFERENCE=reference_csv, MATCH_RADIUS=1.0,
                           OUTPUT_REPORT=report)
    assert run.returncode == 0, run.text
    out = run.json["results"]
    assert (out["TP"], out["FP"], out["FN"]) == (2, 1, 1)
    assert out["PRECISION"] == pytest.approx(2 / 3)
    assert out["RECALL"] == pytest.approx(2 / 3)
    assert out["F1"] == pytest.approx(2 / 3)
    assert out["CLASS_ACCURACY"] == pytest.approx(0.5)
    assert out["MEDIAN_ERROR"] == pytest.approx((0.05 + 0.1) / 2)
    assert out["MEDIAN_HEIGHT_ERROR"] == pytest.approx((0.02 + 0.1) / 2)
    assert out["MEDIAN_AZIMUTH_ERROR"] == pytest.approx(3.0)  # 92 vs 90 -> 2, 2 vs 358 -> 4 (wrap)
    # the sign layer has no width nor panel_height: its size error is undefined (NULL), not 0
    assert out["MEDIAN_SIZE_ERROR"] is None and out["P95_SIZE_ERROR"] is None
    text = open(report).read()
    for token in ("s1", "s2", "s9", "r1", "r2", "r3", "missed", "false"):
        assert token in text


def test_code_accuracy_and_confusions(qgis_process, tmp_path):
    # The generator's columns: faded, then code (empty: the panel has no code).
    reference = str(tmp_path / "reference_codes.csv")
    with open(reference, "w") as f:
        f.write("sign_id,class,x,y,z,height,width,panel_height,azimuth,faded,code\n"
                "r1,prohibitory,500000,5300000,102.0,2.0,0.6,0.6,90,0,DE:274[50]\n"
                "r2,information,500010,5300000,102.5,2.5,0.9,0.8,358,0,DE:306\n"
                "r3,prohibitory,500020,5300000,102.0,2.0,0.6,0.6,180,0,DE:274[50]\n"
                "r4,mandatory,500030,5300000,102.0,2.0,0.6,0.6,180,0,DE:209\n"
                "r5,information,500040,5300000,102.0,2.0,0.6,0.6,180,0,\n")
    rows = [("s{}".format(k), cls, 500000 + 10.0 * (k - 1), 5300000.0, 102.0, 2.0, 90.0)
            for k, cls in enumerate(("prohibitory", "information", "prohibitory", "mandatory", "information"), 1)]
    # s1 right, s2 right, s3 wrong speed, s4 without a code (NULL), s5 not compared (no reference code)
    signs = write_signs(str(tmp_path / "signs_codes.gpkg"), rows,
                        codes=["DE:274[50]", "DE:306", "DE:274[30]", None, "DE:306"])
    report = str(tmp_path / "report_codes.html")
    run = qgis_process.run(ALG, SIGNS=signs, REFERENCE=reference, MATCH_RADIUS=1.0, OUTPUT_REPORT=report)
    assert run.returncode == 0, run.text
    out = run.json["results"]
    assert out["TP"] == 5 and out["CLASS_ACCURACY"] == pytest.approx(1.0)
    assert out["CODE_ACCURACY"] == pytest.approx(0.5)          # 2 right of 4 compared
    assert (out["CODE_COMPARED"], out["NO_CODE"]) == (4, 1)
    assert out["CODE_CONFUSIONS"] == "DE:209 -> (none): 1; DE:274[50] -> DE:274[30]: 1"
    assert any("Code accuracy 0.500 of 4" in line and "DE:274[50] -> DE:274[30]: 1" in line
               for line in run.json["log"]["info"]), run.json["log"]
    text = open(report, encoding="utf-8").read()
    assert "Code confusions" in text and "DE:274[30]" in text and "wrongcode" in text

    # the same signs against the reference without its code column: no code figures, one line why
    plain = str(tmp_path / "reference_plain.csv")
    with open(plain, "w") as f:
        f.write("".join(line.rsplit(",", 2)[0] + "\n" for line in open(reference).read().splitlines()))
    run = qgis_process.run(ALG, SIGNS=signs, REFERENCE=plain, MATCH_RADIUS=1.0, OUTPUT_REPORT=report)
    assert run.returncode == 0, run.text
    out = run.json["results"]
    assert out["TP"] == 5
    assert out["CODE_ACCURACY"] is None and out["CODE_COMPARED"] is None and out["CODE_CONFUSIONS"] == ""
    note = "Code accuracy not computed: the reference has no 'code' column"
    assert any(note in line for line in run.json["log"]["info"]), run.json["log"]
    text = html.unescape(open(report, encoding="utf-8").read())
    assert note in text and "Code confusions" not in text


def test_reference_layer_in_another_crs_is_reprojected(qgis_process, tmp_path, reference_csv):
    from pyproj import Transformer
    to_geo = Transformer.from_crs("EPSG:32633", "EPSG:4326", always_xy=True)
    rows = [line.split(",") for line in REFERENCE.strip().splitlines()[1:]]
    reference = []
    for r in rows:
        lon, lat = to_geo.transform(float(r[2]), float(r[3]))
        reference.append((r[0], r[1], lon, lat, float(r[4]), float(r[5]), float(r[8])))
    reference_gpkg = write_signs(str(tmp_path / "reference.gpkg"), reference, epsg=4326)
    signs = write_signs(str(tmp_path / "signs.gpkg"), [
        (r[0].replace("r", "s"), r[1], float(r[2]) + 0.01, float(r[3]), float(r[4]), float(r[5]), float(r[8]))
        for r in rows])
    run = qgis_process.run(ALG, SIGNS=signs, REFERENCE=reference_gpkg, MATCH_RADIUS=0.5,
                           OUTPUT_REPORT=str(tmp_path / "r.html"))
    assert run.returncode == 0, run.text
    out = run.json["results"]
    assert (out["TP"], out["FP"], out["FN"]) == (3, 0, 0)
    assert out["MEDIAN_ERROR"] == pytest.approx(0.01, abs=1e-4)
    assert any("Reprojecting" in line for line in run.json["log"]["info"])


@pytest.mark.parametrize("case,message", [
    ("empty signs", "The sign layer is empty"),
    ("missing columns", "missing column(s) azimuth"),
    ("bad number", "line 3, field 'z'"),
])
def test_bad_input_leaves_no_report(qgis_process, tmp_path, reference_csv, case, message):
    signs = write_signs(str(tmp_path / "signs.gpkg"),
                        [] if case == "empty signs" else [("s1", "stop", 500000, 5300000, 102, 2, 90)])
    reference = reference_csv
    if case == "missing columns":
        reference = str(tmp_path / "ref_cols.csv")
        open(reference, "w").write("\n".join(line.rsplit(",", 1)[0] for line in REFERENCE.splitlines()) + "\n")
    elif case == "bad number":
        reference = str(tmp_path / "ref_bad.csv")
        open(reference, "w").write(REFERENCE.replace("102.5", "high"))
    report = tmp_path / "report.html"
    run = qgis_process.run(ALG, SIGNS=signs, REFERENCE=reference, OUTPUT_REPORT=str(report))
    assert run.returncode != 0
    assert message in run.text, run.text
    assert not report.exists()
    assert not [f for f in os.listdir(tmp_path) if f.endswith(".html") or ".tmp" in f]
