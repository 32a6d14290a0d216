"""roadsigns:groundfilter through qgis_process on generated LAZ clouds.

The venv may hold PDAL's Python bindings (``make setup`` installs them where
``../shared/tools/pdal-2.9.2`` exists): tests of the plugin without PDAL hide them
(``no_pdal``); tests/qgis/test_pdal.py runs the PDAL engine with the real PDAL."""
import os
import stat
import sys
import textwrap

import laspy
import numpy as np
import pytest
import shapely
from helpers import cloudgen, realpdal
from osgeo import ogr, osr
from pyproj import Transformer

ALG = "roadsigns:groundfilter"


@pytest.fixture(scope="module")
def road(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cloud")
    scene = cloudgen.road_scene(slope=0.06, seed=2)
    path = str(folder / "road.laz")
    cloudgen.write_scene(path, scene, crs_epsg=25833)
    return path, scene


def write_layer(path, geometries_wkt, epsg, kind):
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    layer = ds.CreateLayer("crop", srs, kind)
    for wkt in geometries_wkt:
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(feature)
    ds = None
    return str(path)


def classes(path):
    las = laspy.read(path)
    return np.column_stack([las.x, las.y, las.z]), np.asarray(las.classification)


@pytest.mark.parametrize("method", [0, 1])
def test_ground_agrees_with_truth(qgis_process, road, tmp_path, method):
    path, scene = road
    out = str(tmp_path / "ground.laz")
    run = qgis_process.run(ALG, INPUT=path, METHOD=method, ENGINE=2, OUTPUT=out)
    assert run.returncode == 0, run.text
    results = run.json["results"]
    assert results["ENGINE_USED"] == "builtin"
    assert results["POINTS_IN"] == results["POINTS_OUT"] == len(scene)
    xyz, cls = classes(out)
    assert np.allclose(xyz, scene.xyz, atol=1e-3)  # same points, same order
    agreement = np.mean((cls == 2) == scene.is_ground)
    assert agreement >= 0.99, agreement
    assert results["GROUND_POINTS"] == int(np.sum(cls == 2))


def test_every_step_is_printed_through_qgis_process(qgis_process, road, tmp_path):
    """The steps reach qgis_process's output (printed without --json), the ground surface's
    too: it is fitted while the CSF library's own output is sent to devnull, and what
    qgis_process had buffered before is written first, not lost with it."""
    path, _ = road
    run = qgis_process("run", ALG, "--", f"INPUT={path}", "ENGINE=2", f"OUTPUT={tmp_path / 'g.laz'}")
    assert run.returncode == 0, run.text
    steps = [line.lstrip(".0123456789") for line in run.stdout.splitlines()]
    assert any(s.startswith("Reading road.laz: ") for s in steps), run.stdout
    assert any(s.startswith("Fitting the ground surface: tile 1 of ") for s in steps), run.stdout
    assert any(s.startswith("Classifying and writing the points: part 1 of ") for s in steps), run.stdout


@pytest.fixture
def no_pdal(qgis_process, tmp_path_factory, monkeypatch):
    """The shared qgis_process as a QGIS without PDAL (bindings hidden, no executable)."""
    monkeypatch.setattr(qgis_process, "env", dict(qgis_process.env))
    realpdal.hide_pdal(qgis_process.env, str(tmp_path_factory.mktemp("no-pdal")))
    return qgis_process


def test_without_pdal_auto_runs_the_builtin_engine(no_pdal, road, tmp_path):
    qgis_process = no_pdal
    out = str(tmp_path / "g.laz")
    run = qgis_process.run(ALG, INPUT=road[0], OUTPUT=out)
    assert run.returncode == 0, run.text
    assert run.json["results"]["ENGINE_USED"] == "builtin"
    assert any("Auto: the built-in engine" in line for line in run.json["log"]["info"])


def test_crop_polygon_in_another_crs(qgis_process, road, tmp_path):
    path, scene = road
    x0, y0, _ = cloudgen.ORIGIN
    to_geo = Transformer.from_crs("EPSG:25833", "EPSG:4326", always_xy=True)
    ring = [(x0 + 10, y0 - 5), (x0 + 30, y0 - 5), (x0 + 30, y0 + 5), (x0 + 10, y0 + 5)]
    ring_geo = [to_geo.transform(*p) for p in ring]
    wkt = "POLYGON(({}))".format(", ".join("{} {}".format(*p) for p in ring_geo + ring_geo[:1]))
    crop = write_layer(tmp_path / "crop.gpkg", [wkt], 4326, ogr.wkbPolygon)
    out = str(tmp_path / "g.laz")
    run = qgis_process.run(ALG, INPUT=path, CROP=crop, ENGINE=2, OUTPUT=out)
    assert run.returncode == 0, run.text
    xyz, _ = classes(out)
    back = Transformer.from_crs("EPSG:4326", "EPSG:25833", always_xy=True)
    polygon = shapely.Polygon([back.transform(*p) for p in ring_geo])
    inside = shapely.contains_xy(polygon.buffer(0.01), scene.xyz[:, 0], scene.xyz[:, 1])
    core = shapely.contains_xy(polygon.buffer(-0.01), scene.xyz[:, 0], scene.xyz[:, 1])
    assert core.sum() <= len(xyz) <= inside.sum()
    assert shapely.contains_xy(polygon.buffer(0.01), xyz[:, 0], xyz[:, 1]).all()


def test_corridor_around_points(qgis_process, road, tmp_path):
    path, scene = road
    x0, y0, _ = cloudgen.ORIGIN
    stations = ["POINT({} {})".format(x0 + 20, y0), "POINT({} {})".format(x0 + 25, y0)]
    crop = write_layer(tmp_path / "stations.gpkg", stations, 25833, ogr.wkbPoint)
    run = qgis_process.run(ALG, INPUT=path, CROP=crop, ENGINE=2, OUTPUT=str(tmp_path / "g.laz"))
    assert run.returncode != 0 and "crop buffer" in run.text  # points need a buffer
    out = str(tmp_path / "g.laz")
    run = qgis_process.run(ALG, INPUT=path, CROP=crop, CROP_BUFFER=4, ENGINE=2, OUTPUT=out)
    assert run.returncode == 0, run.text
    xyz, _ = classes(out)
    d = np.minimum(np.hypot(xyz[:, 0] - x0 - 20, xyz[:, 1] - y0), np.hypot(xyz[:, 0] - x0 - 25, xyz[:, 1] - y0))
    assert d.max() <= 4.0 + 1e-6 and len(xyz) > 1000
    d_all = np.minimum(np.hypot(scene.xyz[:, 0] - x0 - 20, scene.xyz[:, 1] - y0),
                       np.hypot(scene.xyz[:, 0] - x0 - 25, scene.xyz[:, 1] - y0))
    assert abs(len(xyz) - int(np.sum(d_all <= 4.0))) <= int(np.sum(np.abs(d_all - 4.0) < 0.01))


def fake_pdal(folder):
    path = folder / "pdal"
    path.write_text("#!{}\n".format(sys.executable) + textwrap.dedent("""
        import sys
        sys.stdin.read()
        sys.stderr.write("PDAL: readers.las: Invalid something in the fake\\n")
        sys.exit(1)
    """))
    path.chmod(path.stat().st_mode | stat.S_IEXEC)
    return str(path)


def test_failing_pdal_is_the_error_under_pdal_and_not_run_under_auto(qgis_process, road, tmp_path, monkeypatch):
    """ENGINE=pdal: PDAL's failure is the error; ENGINE=auto: the built-in engine, measured
    faster for both methods (AUTO_ENGINES), runs without calling PDAL and the log says why."""
    monkeypatch.setitem(qgis_process.env, "ROADSIGNS_PDAL_EXECUTABLE", fake_pdal(tmp_path))
    out = tmp_path / "g.laz"
    run = qgis_process.run(ALG, INPUT=road[0], ENGINE=1, OUTPUT=str(out))
    assert run.returncode != 0
    assert "Invalid something in the fake" in run.text
    assert not out.exists()
    for method in (0, 1):
        run = qgis_process.run(ALG, INPUT=road[0], METHOD=method, ENGINE=0, OUTPUT=str(out))
        assert run.returncode == 0, run.text
        assert run.json["results"]["ENGINE_USED"] == "builtin"
        assert "Invalid something in the fake" not in run.text and "PDAL failed" not in run.text
        assert any("Auto: the built-in engine, measured faster than PDAL" in line
                   for line in run.json["log"]["info"]), run.text


@pytest.mark.parametrize("case,message", [
    ("not las", "LAS"),
    ("truncated", "truncated.laz"),
    ("no crs", "has no coordinate reference system"),
    ("pdal asked", "PDAL was asked for"),
])
def test_bad_input(no_pdal, road, tmp_path, case, message):
    qgis_process = no_pdal
    parameters = dict(INPUT=road[0], ENGINE=2)
    if case == "not las":
        bad = tmp_path / "notes.laz"
        bad.write_text("this is not a point cloud")
        parameters["INPUT"] = str(bad)
    elif case == "truncated":
        bad = tmp_path / "truncated.laz"
        bad.write_bytes(open(road[0], "rb").read()[:20000])
        parameters["INPUT"] = str(bad)
    elif case == "no crs":
        scene = cloudgen.road_scene(length_m=10, density_per_m2=20, seed=5)
        bad = str(tmp_path / "nocrs.las")
        cloudgen.write_scene(bad, scene, crs_epsg=None)
        parameters["INPUT"] = bad
    else:
        parameters["ENGINE"] = 1
    out = tmp_path / "out.laz"
    run = qgis_process.run(ALG, OUTPUT=str(out), **parameters)
    assert run.returncode != 0
    assert message in run.text, run.text
    assert not out.exists()
    assert not [f for f in os.listdir(tmp_path) if f.startswith("out")]


@pytest.mark.parametrize("method", [0, 1])
def test_generated_street_scene(qgis_process, scene_tiny_cloud, tmp_path, method):
    """The ray-cast street scene (buildings, cars, trees, street furniture, curbs): the true
    classes are in the input, reset by the filter and compared afterwards."""
    source = os.path.join(scene_tiny_cloud, "cloud.laz")
    out = str(tmp_path / "g.laz")
    run = qgis_process.run(ALG, INPUT=source, METHOD=method, ENGINE=2, RESET_CLASSES=True, OUTPUT=out)
    assert run.returncode == 0, run.text
    truth = np.asarray(laspy.read(source).classification) == 2
    _, cls = classes(out)
    assert set(np.unique(cls)) <= {1, 2}
    agreement = np.mean((cls == 2) == truth)
    assert agreement >= 0.99, agreement
