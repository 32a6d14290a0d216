"""roadsigns:groundfilter's PDAL engine through qgis_process with the real PDAL 2.9.2
(``../shared/tools/pdal-2.9.2``, tests/helpers/realpdal.py), by both of its paths:

* ``pdal-cli``: the ``pdal`` application, found as a user's QGIS finds it: the provider
  setting (in a profile of its own) or the environment variable ROADSIGNS_PDAL_EXECUTABLE;
* ``pdal-python``: the Python bindings that ``make setup`` installs into the venv, whose
  site-packages is on qgis_process's PYTHONPATH.

Each is compared with the built-in engine on the same generated cloud (LAS 1.4, format
7, odd scales and offsets, extra bytes, a user VLR, other classes): the same points kept
by a crop layer in another CRS (EPSG:4326 for an EPSG:25833 cloud), the same ground on at
least 99.5 % of them, the header and every other dimension unchanged. Then failures, each
naming the file and leaving nothing behind: a truncated LAZ (refused before PDAL, which
hangs on it), an unwritable folder, and PDAL's own refusal of a cloud (ENGINE=pdal: the
error; ENGINE=auto: a warning, and the built-in engine in the same QGIS process).
Cancelling the ``pdal`` process is tested in tests/core/test_ground.py.

Without ``../shared/tools/pdal-2.9.2`` these tests are skipped, and fail under CI=true.
"""
import functools
import os
import signal
import subprocess

import laspy
import numpy as np
import pytest
import shapely
from helpers import cloudgen, realpdal
from osgeo import ogr, osr
from pyproj import Transformer

from devtools.qgisrun import QgisProcess
from roadsigns.core.cloudsource import open_cloud

ALG = "roadsigns:groundfilter"
METHOD = {"csf": 0, "smrf": 1}
ENGINE = {"auto": 0, "pdal": 1, "builtin": 2}
MIN_AGREEMENT = 0.995
#: crop, method and class handling of each compared case
CASES = {
    "polygon-csf": dict(method="csf", crop="polygon", reset=False),
    "corridor-smrf": dict(method="smrf", crop="corridor", reset=True),
}
PATHS = ("pdal-cli", "pdal-python")


@pytest.fixture(scope="module")
def real_pdal():
    return realpdal.require()


@pytest.fixture(scope="module")
def cloud(real_pdal, tmp_path_factory):
    """A 60 m street on a 3 % slope (~290 000 points) with a rich header (helpers.realpdal)."""
    folder = tmp_path_factory.mktemp("pdal-cloud")
    scene = cloudgen.road_scene(slope=0.03, seed=1)
    path = str(folder / "street.laz")
    realpdal.write_rich_cloud(path, scene)
    return path


def _layer(path, wkts, kind):
    """A GeoPackage layer in EPSG:4326 (the cloud is in EPSG:25833)."""
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(4326)
    srs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    layer = ds.CreateLayer("crop", srs, kind)
    for wkt in wkts:
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(feature)
    ds = None
    return str(path)


@pytest.fixture(scope="module")
def crops(tmp_path_factory):
    """The crop layers in EPSG:4326 and the areas they stand for in the cloud's CRS: an
    irregular polygon over most of the street, and a corridor of 8 m around four stations."""
    folder = tmp_path_factory.mktemp("pdal-crops")
    x0, y0, _ = cloudgen.ORIGIN
    to_geo = Transformer.from_crs("EPSG:25833", "EPSG:4326", always_xy=True)
    ring = [(x0 + x, y0 + y) for x, y in [(3, -13), (50, -14), (58, 0), (45, 13), (5, 11)]]
    ring_geo = [to_geo.transform(*p) for p in ring]
    polygon_wkt = shapely.Polygon(ring_geo).wkt
    stations = [(x0 + x, y0 + y) for x, y in [(5, 0), (20, 1), (35, -1), (50, 0)]]
    stations_geo = [to_geo.transform(*p) for p in stations]
    return {
        "polygon": (dict(CROP=_layer(folder / "polygon.gpkg", [polygon_wkt], ogr.wkbPolygon)),
                    shapely.Polygon(ring)),
        "corridor": (dict(CROP=_layer(folder / "stations.gpkg", [shapely.Point(p).wkt for p in stations_geo],
                                      ogr.wkbPoint), CROP_BUFFER=8),
                     shapely.MultiPoint(stations).buffer(8)),
    }


def qgis_with_setting(plugin_path, profile, executable):
    """qgis_process with a profile of its own whose provider setting names the pdal
    application (Processing > Options > Providers > Road sign inventory)."""
    qgis = QgisProcess(plugin_path, profile)
    qgis.env.pop(realpdal.PDAL_SETTING, None)
    realpdal.set_provider_setting(profile, executable)
    return qgis


@pytest.fixture(scope="module")
def runs(qgis_process, real_pdal, plugin_path, cloud, crops, tmp_path_factory):
    """run(case, engine) -> (Run, output path), each run once per module. ``builtin`` and
    ``pdal-python`` run in the shared profile (no setting, no environment variable: the
    bindings are found), ``pdal-cli`` in the profile with the provider setting."""
    folder = tmp_path_factory.mktemp("pdal-runs")
    done, setting = {}, []

    def run(case, engine):
        if (case, engine) not in done:
            spec = CASES[case]
            out = str(folder / f"{case}-{engine}.laz")
            if engine == "pdal-cli" and not setting:  # made when first needed (-k runs)
                setting.append(qgis_with_setting(plugin_path, str(tmp_path_factory.mktemp("pdal-setting")),
                                                 real_pdal.executable))
            qgis = setting[0] if engine == "pdal-cli" else qgis_process
            saved = qgis.env.pop(realpdal.PDAL_SETTING, None)
            try:
                result = qgis.run(ALG, INPUT=cloud, METHOD=METHOD[spec["method"]],
                                  ENGINE=ENGINE["builtin" if engine == "builtin" else "pdal"],
                                  RESET_CLASSES=spec["reset"], OUTPUT=out, timeout=600,
                                  **crops[spec["crop"]][0])
            finally:
                if saved is not None:
                    qgis.env[realpdal.PDAL_SETTING] = saved
            assert result.returncode == 0, result.text
            assert result.json["results"]["ENGINE_USED"] == engine, result.text
            print(f"\n{case} {engine}: {result.wall_s:.1f} s in qgis_process")
            done[case, engine] = (result, out)
        return done[case, engine]

    return run


@pytest.fixture(scope="module")
def source(cloud):
    """The input's points, and where each (X, Y, Z) record is in it."""
    las = laspy.read(cloud)
    index = {key: i for i, key in enumerate(zip(las.X.tolist(), las.Y.tolist(), las.Z.tolist()))}
    return las, index


@functools.lru_cache(maxsize=None)
def read(path):
    """An output, read once (several tests look at each)."""
    return laspy.read(path)


def rows_in_source(source, las):
    """Positions in the input of the points of an output (every one must be there)."""
    _, index = source
    rows = [index.get(key, -1) for key in zip(las.X.tolist(), las.Y.tolist(), las.Z.tolist())]
    rows = np.asarray(rows, dtype=np.int64)
    assert (rows >= 0).all(), "points not in the input"
    return rows


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("case", CASES)
def test_crop_keeps_the_builtin_points(runs, source, crops, case, path):
    builtin = read(runs(case, "builtin")[1])
    pdal = read(runs(case, path)[1])
    rows = rows_in_source(source, builtin)
    # the built-in crop is where the layer says, once reprojected to the cloud's CRS
    src, _ = source
    area = crops[CASES[case]["crop"]][1]
    inside = shapely.contains_xy(area.buffer(0.01), src.x, src.y)
    core = np.flatnonzero(shapely.contains_xy(area.buffer(-0.01), src.x, src.y))
    assert inside[rows].all() and np.isin(core, rows).all()
    assert 0.4 * len(src) < len(rows) < 0.95 * len(src)
    # PDAL keeps exactly the same points, in the same order
    assert len(pdal) == len(builtin)
    for dim in ("X", "Y", "Z"):
        np.testing.assert_array_equal(pdal[dim], builtin[dim])
    print(f"\n{case} {path}: kept {len(rows)} of {len(src)} points, as the built-in crop")


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("case", CASES)
def test_ground_agrees_with_the_builtin_engine(runs, case, path):
    run_b, out_b = runs(case, "builtin")
    run_p, out_p = runs(case, path)
    ground_b = np.asarray(read(out_b).classification) == 2
    ground_p = np.asarray(read(out_p).classification) == 2
    assert len(ground_p) == len(ground_b) and len(ground_b) > 100_000
    agreement = float(np.mean(ground_b == ground_p))
    print(f"\n{case} {path}: ground agrees with the built-in engine on {agreement:.3%} of "
          f"{len(ground_b)} points")
    assert agreement >= MIN_AGREEMENT, (case, path, agreement)
    assert run_p.json["results"]["GROUND_POINTS"] == int(ground_p.sum())
    assert run_p.json["results"]["POINTS_OUT"] == len(ground_p)


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("case", CASES)
def test_header_and_other_dimensions_survive(runs, source, case, path):
    src, _ = source
    out = read(runs(case, path)[1])
    rows = rows_in_source(source, out)
    h, hs = out.header, src.header
    assert (h.point_format.id, str(h.version)) == (7, "1.4") and h.are_points_compressed  # LAZ asked
    np.testing.assert_array_equal(h.scales, realpdal.RICH_SCALES)
    np.testing.assert_array_equal(h.offsets, realpdal.RICH_OFFSETS)
    assert h.parse_crs() == hs.parse_crs() and h.parse_crs().to_epsg() == 25833
    vlrs = {(v.user_id, v.record_id): getattr(v, "record_data", None) for v in h.vlrs}
    assert vlrs.get(realpdal.RICH_VLR[:2]) == realpdal.RICH_VLR[2], [v.user_id for v in h.vlrs]
    for dim in ("intensity", "gps_time", "return_number", "number_of_returns", "red", "green", "blue",
                "user_data", "point_source_id", "scan_angle", "range_m", "ring"):
        np.testing.assert_array_equal(out[dim], src[dim][rows], err_msg=dim)
    # PDAL writes the array extra bytes 'normal' (3 x f4) as normal0..normal2, same values
    names = set(out.point_format.extra_dimension_names)
    assert {"range_m", "ring"} <= names
    normal = np.column_stack([out[f"normal{i}"] for i in range(3)]) if "normal0" in names else out["normal"]
    np.testing.assert_array_equal(normal, src["normal"][rows])
    # classes, against the built-in engine's ground (same points, same order): ground 2;
    # with reset every other point 1; without, eligible returns (last and only) that were
    # 2 but are not ground become 1, every other point keeps its class
    builtin = read(runs(case, "builtin")[1])
    np.testing.assert_array_equal(builtin.X, out.X)
    ground_b = np.asarray(builtin.classification) == 2
    before = np.asarray(src.classification)[rows]
    cls = np.asarray(out.classification)
    rn, nr = np.asarray(out.return_number), np.asarray(out.number_of_returns)
    eligible = (rn == nr) | (rn == 0) | (nr == 0)
    if CASES[case]["reset"]:
        expected = np.where(ground_b & eligible, 2, 1)
    else:
        expected = np.where(~eligible, before, np.where(ground_b, 2, np.where(before == 2, 1, before)))
        assert {1, 2, 5, 6} <= set(np.unique(cls).tolist())
    assert (~eligible).sum() > 1000  # first returns in the tree crowns: untouched
    np.testing.assert_array_equal(cls[~eligible], expected[~eligible])
    kinds = {"ground": ground_b, "class 2, not ground": (before == 2) & ~ground_b,
             "other class, not ground": (before != 2) & ~ground_b}
    for kind, mask in kinds.items():  # each rule on its own, however few points it concerns
        selected = eligible & mask
        assert selected.sum() > 100, kind
        assert np.mean(cls[selected] == expected[selected]) >= 0.99, kind


# ----------------------------------------------------------------------------- failures

@pytest.fixture
def engine_env(qgis_process, real_pdal, monkeypatch):
    """Point the shared qgis_process at one PDAL path: ``pdal-cli`` through the
    environment variable ROADSIGNS_PDAL_EXECUTABLE, ``pdal-python`` through the bindings."""
    def use(path):
        if path == "pdal-cli":
            monkeypatch.setitem(qgis_process.env, realpdal.PDAL_SETTING, real_pdal.executable)
        else:
            monkeypatch.delitem(qgis_process.env, realpdal.PDAL_SETTING, raising=False)
        return qgis_process
    return use


def test_truncated_laz_is_refused_before_pdal(engine_env, cloud, tmp_path):
    """PDAL 2.9.2 waits forever on this file cut in half (points of more than 30 bytes):
    the engine must refuse it first, naming it (core/ground/pdal.py check_complete)."""
    qgis = engine_env("pdal-cli")
    bad = tmp_path / "truncated.laz"
    data = open(cloud, "rb").read()
    bad.write_bytes(data[:len(data) // 2])  # the header is whole: only the points are cut
    out = tmp_path / "ground.laz"
    before = realpdal.orphaned_pdal()
    try:
        run = qgis.run(ALG, INPUT=str(bad), ENGINE=ENGINE["pdal"], OUTPUT=str(out), timeout=120)
    except subprocess.TimeoutExpired:
        for pid in realpdal.orphaned_pdal() - before:  # the pdal that qgis_process left hanging
            os.kill(pid, signal.SIGKILL)
        pytest.fail("PDAL was given the truncated file and hung")
    assert run.returncode != 0
    assert f"Cannot read {bad}: the file is truncated or corrupt" in run.text, run.text
    assert "Traceback" not in run.text, run.text
    assert sorted(os.listdir(tmp_path)) == ["truncated.laz"]


def test_unwritable_folder_is_named_and_nothing_written(engine_env, cloud, tmp_path):
    qgis = engine_env("pdal-python")
    with realpdal.unwritable_folder(str(tmp_path / "read-only")) as folder:
        out = os.path.join(folder, "ground.laz")
        run = qgis.run(ALG, INPUT=cloud, ENGINE=ENGINE["pdal"], METHOD=METHOD["smrf"], OUTPUT=out)
        assert run.returncode != 0
        assert f"Cannot write {out}" in run.text, run.text
        assert "Traceback" not in run.text and ".roadsigns" not in run.text, run.text
        assert os.listdir(folder) == []


@pytest.fixture(scope="module")
def zero_returns(tmp_path_factory):
    """A small cloud whose first 50 points have return numbers 0, the others not: PDAL's
    filters refuse it ("Some NumberOfReturns or ReturnNumber values were 0, but not all");
    the built-in engine classifies those points as eligible returns."""
    scene = cloudgen.road_scene(length_m=15.0, seed=8)
    scene.return_number[:50] = 0
    scene.number_of_returns[:50] = 0
    path = str(tmp_path_factory.mktemp("pdal-zero") / "some-zero-returns.laz")
    cloudgen.write_scene(path, scene)
    return path, scene


def test_pdal_failure_is_named_and_nothing_written(engine_env, zero_returns, tmp_path):
    """ENGINE=pdal: PDAL's refusal is the error, naming the file; nothing is written."""
    qgis = engine_env("pdal-cli")
    src, _ = zero_returns
    run = qgis.run(ALG, INPUT=src, METHOD=METHOD["smrf"], ENGINE=ENGINE["pdal"],
                   OUTPUT=str(tmp_path / "ground.laz"))
    assert run.returncode != 0
    assert f"pdal ({qgis.env[realpdal.PDAL_SETTING]}) could not classify {src} into " in run.text, run.text
    assert "NumberOfReturns" in run.text and "Traceback" not in run.text, run.text
    assert os.listdir(tmp_path) == []


@pytest.fixture
def no_builtin_csf(qgis_process, tmp_path, monkeypatch):
    """The shared qgis_process as a QGIS whose Python lacks the built-in CSF's package
    (cloth-simulation-filter): a ``CSF`` module that fails to import shadows it."""
    stub = tmp_path / "no-csf"
    stub.mkdir()
    (stub / "CSF.py").write_text('raise ImportError("cloth-simulation-filter hidden by the tests")\n')
    monkeypatch.setitem(qgis_process.env, "PYTHONPATH",
                        os.pathsep.join(p for p in (str(stub), qgis_process.env.get("PYTHONPATH", "")) if p))
    monkeypatch.delitem(qgis_process.env, realpdal.PDAL_SETTING, raising=False)
    return qgis_process


def test_auto_runs_pdal_when_the_builtin_csf_is_missing(no_builtin_csf, cloud, zero_returns, tmp_path):
    """ENGINE=auto picks the built-in engine (AUTO_ENGINES), but without its CSF package it
    runs PDAL (here the bindings), saying why; when PDAL then refuses a cloud there is no
    engine to fall back on, and PDAL's refusal is the error, naming the file."""
    qgis = no_builtin_csf
    out = tmp_path / "ground.laz"
    run = qgis.run(ALG, INPUT=cloud, METHOD=METHOD["csf"], ENGINE=ENGINE["auto"], OUTPUT=str(out))
    assert run.returncode == 0, run.text
    assert run.json["results"]["ENGINE_USED"] == "pdal-python"
    assert any("needs the Python package cloth-simulation-filter" in line for line in run.json["log"]["info"])
    assert laspy.read(str(out)).header.point_count == run.json["results"]["POINTS_OUT"] > 100_000
    run = qgis.run(ALG, INPUT=cloud, METHOD=METHOD["smrf"], ENGINE=ENGINE["auto"], OUTPUT=str(out))
    assert run.returncode == 0 and run.json["results"]["ENGINE_USED"] == "builtin", run.text  # SMRF needs no CSF
    src, _ = zero_returns
    failed = tmp_path / "failed.laz"
    run = qgis.run(ALG, INPUT=src, METHOD=METHOD["csf"], ENGINE=ENGINE["auto"], OUTPUT=str(failed))
    assert run.returncode != 0
    assert f"PDAL's Python bindings could not classify {src} into " in run.text, run.text
    assert "NumberOfReturns" in run.text and "Traceback" not in run.text, run.text
    assert sorted(os.listdir(tmp_path)) == ["ground.laz", "no-csf"]


# ----------------------------------------------------------------------------- tiles, VPC, COPC

@pytest.fixture(scope="module")
def tiled_cloud(real_pdal, cloud, tmp_path_factory):
    """The rich cloud as 20 m tiles with a .vpc listing them, and as COPC (PDAL's writers.copc)."""
    import json

    import pdal
    from helpers.cloudtiles import split_into_tiles, write_vpc

    folder = tmp_path_factory.mktemp("pdal-tiles")
    tiles = split_into_tiles(cloud, str(folder / "tiles"), size_m=20.0)
    vpc = write_vpc(str(folder / "street.vpc"), tiles)
    copc = str(folder / "street.copc.laz")
    pdal.Pipeline(json.dumps({"pipeline": [cloud, {"type": "writers.copc", "filename": copc}]})).execute()
    return dict(tiles=tiles, vpc=vpc, copc=copc)


def _ground_by_point(paths):
    keys, ground = [], []
    for p in paths:
        las = laspy.read(p)
        keys.append(np.round(np.column_stack([las.x, las.y, las.z]) * 1000).astype(np.int64))
        ground.append(np.asarray(las.classification) == 2)
    k, g = np.concatenate(keys), np.concatenate(ground)
    order = np.lexsort(k.T[::-1])
    return k[order], g[order]


@pytest.mark.parametrize("kind, path, as_tiles", [
    ("vpc", "pdal-cli", True),
    ("vpc", "pdal-python", False),
    ("copc", "pdal-python", False),
])
def test_tiles_vpc_and_copc_go_through_pdal(engine_env, tiled_cloud, tmp_path, kind, path, as_tiles):
    """A .vpc of tiles (each tile through PDAL with its neighbours' points around it), into one
    file or one file per tile, and a COPC file: ENGINE=pdal runs PDAL by the given path, and
    its ground agrees with the built-in engine's on >= 99.5 % of the same points."""
    qgis = engine_env(path)
    src = tiled_cloud[kind]
    outputs = {}
    for engine in ("builtin", "pdal"):
        out = str(tmp_path / f"{engine}.laz")
        run = qgis.run(ALG, INPUT=src, METHOD=METHOD["csf"], ENGINE=ENGINE[engine], OUTPUT=out,
                       OUTPUT_TILES=as_tiles and engine == "pdal", timeout=600)
        assert run.returncode == 0, run.text
        assert run.json["results"]["ENGINE_USED"] == (path if engine == "pdal" else "builtin")
        result = run.json["results"]["OUTPUT"]
        outputs[engine] = [t.path for t in open_cloud(result).tiles] if result.endswith(".vpc") else [result]
    if as_tiles:
        assert sorted(os.path.basename(p) for p in outputs["pdal"]) == sorted(
            os.path.basename(t) for t in tiled_cloud["tiles"])
    kb, gb = _ground_by_point(outputs["builtin"])
    kp, gp = _ground_by_point(outputs["pdal"])
    np.testing.assert_array_equal(kb, kp)
    agreement = float(np.mean(gb == gp))
    print(f"\n{kind} {path} tiles={as_tiles}: {agreement:.3%} of {len(gb)} points as the built-in engine")
    assert agreement >= MIN_AGREEMENT and len(gb) > 100_000
