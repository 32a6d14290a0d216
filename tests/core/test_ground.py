"""Ground classification: built-in CSF/SMRF accuracy, tiling, classes, PDAL plumbing."""
import json
import stat
import sys
import textwrap

import laspy
import numpy as np
import pyproj
import pytest
import shapely
from shapely.geometry import box

from helpers import cloudgen  # noqa: E402

from roadsigns.core import ground  # noqa: E402
from roadsigns.core import pointcloud as pc  # noqa: E402
from roadsigns.core.errors import InputError, Progress  # noqa: E402

#: Options documented for each PDAL stage (pdal.io stage pages / doc/stages/*.rst).
PDAL_DOCUMENTED = {
    "readers.las": {"filename", "extra_dims", "compression", "override_srs", "default_srs",
                    "spatialreference", "count", "nosrs", "use_eb_vlr", "ignore_vlr"},
    "filters.crop": {"bounds", "polygon", "outside", "point", "distance", "a_srs"},
    "filters.csf": {"resolution", "ignore", "returns", "threshold", "hdiff", "smooth", "step",
                    "rigidness", "iterations"},
    "filters.smrf": {"cell", "classbits", "cut", "dir", "ignore", "returns", "scalar",
                     "slope", "threshold", "window"},
    "filters.assign": {"assignment", "condition", "value"},
    "filters.ferry": {"dimensions"},
    "writers.las": {"filename", "forward", "minor_version", "software_id", "creation_doy",
                    "creation_year", "dataformat_id", "system_id", "a_srs", "global_encoding",
                    "project_id", "compression", "scale_x", "scale_y", "scale_z", "offset_x",
                    "offset_y", "offset_z", "filesource_id", "discard_high_return_numbers",
                    "extra_dims", "pdal_metadata", "vlrs"},
}
PDAL_DEFAULTS = {
    "filters.csf": dict(resolution=1.0, threshold=0.5, smooth=True, step=0.65, rigidness=3,
                        iterations=500, returns="last,only"),
    "filters.smrf": dict(cell=1.0, scalar=1.25, slope=0.15, threshold=0.5, window=18.0,
                         cut=0.0, returns="last,only"),
}

AGREEMENT = {}


@pytest.fixture(scope="module")
def scenes():
    return {"flat": cloudgen.road_scene(slope=0.0, seed=1),
            "slope6": cloudgen.road_scene(slope=0.06, seed=2)}


def _classes(path):
    return np.asarray(laspy.read(path).classification)


@pytest.mark.parametrize("terrain", ["flat", "slope6"])
@pytest.mark.parametrize("method", ["csf", "smrf"])
def test_builtin_agreement_with_truth(tmp_path, scenes, method, terrain):
    scene = scenes[terrain]
    src = str(tmp_path / "scene.laz")
    cloudgen.write_scene(src, scene, point_format=6)
    out = str(tmp_path / "ground.laz")
    res = ground.run_ground_filter(src, out, method=ground.METHODS.index(method),
                                   engine=2, chunk_points=70_000)
    assert res.engine == "builtin" and res.n_output == len(scene)
    predicted = _classes(out) == 2
    assert res.n_ground == predicted.sum()
    agreement = float((predicted == scene.is_ground).mean())
    AGREEMENT[(method, terrain)] = agreement
    print(f"\n{method} {terrain}: agreement {agreement * 100:.2f}% on {len(scene)} points")
    assert agreement >= 0.990


def test_tiles_match_untiled(scenes):
    scene = cloudgen.road_scene(length_m=120.0, slope=0.0, density_per_m2=60.0, seed=4)
    eligible = ground.returns_mask(scene.return_number, scene.number_of_returns)
    xyz = scene.xyz[eligible]
    # SMRF: the buffer covers the morphology's reach, so tiles give the untiled result
    untiled = ground.classify_ground_arrays(xyz, "smrf", tile_size_m=10_000)
    tiled = ground.classify_ground_arrays(xyz, "smrf", tile_size_m=17.0)
    np.testing.assert_array_equal(tiled, untiled)
    # CSF: one cloth over everything vs 20 m tiles with a 20 m buffer, flat road
    untiled = ground.classify_ground_arrays(xyz, "csf", tile_size_m=10_000)
    tiled = ground.classify_ground_arrays(xyz, "csf", tile_size_m=20.0, tile_buffer_m=20.0)
    assert (tiled != untiled).mean() < 1e-3
    # ... and no seam: points within 1 m of a tile edge are classified as well as others
    truth = scene.is_ground[eligible]
    x0 = np.floor(xyz[:, 0].min()) - 2
    near_edge = np.abs((xyz[:, 0] - x0 + 10.0) % 20.0 - 10.0) < 1.0
    ok = tiled == truth
    assert ok[near_edge].mean() >= ok[~near_edge].mean() - 0.003


def test_csf_thinning_gives_the_full_cloth():
    """The nearest point per cloth node carries all CSF needs: same cloth as all points."""
    rng = np.random.default_rng(0)
    n = 40000
    xyz = np.column_stack([rng.uniform(0, 30, n), rng.uniform(0, 20, n), np.zeros(n)])
    xyz[:, 2] = 0.06 * xyz[:, 0] + rng.normal(0, 0.02, n)
    xyz[0, :2] = 0.0  # the bounding-box corner on a node of the world grid, as in tiles
    car = (xyz[:, 0] > 10) & (xyz[:, 0] < 14) & (xyz[:, 1] > 5) & (xyz[:, 1] < 7)
    xyz[car, 2] += 1.4
    params = ground.CsfParams()
    full = ground.run_csf_cloth(xyz, params)
    grid = ground._CsfGrid((0, 0, 30, 20), 0.0, params, tile_size_m=1000)
    grid.accumulate(xyz[:, 0], xyz[:, 1], xyz[:, 2])
    have = ~np.isnan(grid.rep_du)
    rows, cols = np.nonzero(have)
    lat = grid.lattice
    reps = np.column_stack([lat.x0 + (cols + grid.rep_du[have]) * lat.step,
                            lat.y0 + (rows + grid.rep_dv[have]) * lat.step,
                            grid.rep_z[have] + grid.z_ref])
    # keep the extremes that set CSF's bounding box
    ext = [xyz[:, k].argmin() for k in range(3)] + [xyz[:, k].argmax() for k in range(3)]
    thinned = ground.run_csf_cloth(np.vstack([reps, xyz[ext]]), params)
    assert thinned.shape == full.shape
    np.testing.assert_allclose(thinned, full, atol=1e-5)


def test_classes_kept_or_reset(tmp_path):
    scene = cloudgen.road_scene(length_m=40.0, density_per_m2=60.0, seed=7)
    initial = np.where(scene.semantic == 6, 6, 0).astype(np.uint8)
    initial[::50] = 2                      # stale ground marks, also on objects
    src = str(tmp_path / "in.las")
    cloudgen.write_scene(src, scene, point_format=3, classification=initial)
    eligible = ground.returns_mask(scene.return_number, scene.number_of_returns)

    out = str(tmp_path / "kept.las")
    ground.run_ground_filter(src, out, "smrf", "builtin")
    cls = _classes(out)
    g = cls == 2
    assert np.all(cls[~eligible] == initial[~eligible])          # first returns untouched
    assert np.all(cls[eligible & ~g & (initial == 6)] == 6)       # building kept
    assert np.all(cls[eligible & ~g & (initial == 2)] == 1)       # stale ground cleared
    assert np.all(cls[eligible & ~g & (initial == 0)] == 0)

    out = str(tmp_path / "reset.las")
    ground.run_ground_filter(src, out, "smrf", "builtin", reset_classes=True)
    cls = _classes(out)
    assert set(np.unique(cls)) == {1, 2}


def test_crop_polygon_with_buffer(tmp_path):
    scene = cloudgen.road_scene(length_m=40.0, density_per_m2=40.0, seed=8)
    src = str(tmp_path / "in.laz")
    cloudgen.write_scene(src, scene)
    o = cloudgen.ORIGIN
    poly = box(o[0] + 5, o[1] - 2, o[0] + 25, o[1] + 2)
    out = str(tmp_path / "out.laz")
    res = ground.run_ground_filter(src, out, "csf", "builtin", crop_polygons=[shapely.to_wkb(poly)],
                                   crop_buffer_m=3.0)
    las = laspy.read(out)
    full = laspy.read(src)  # stored (mm-rounded) coordinates
    inside = shapely.intersects_xy(poly.buffer(3.0), full.x, full.y)
    assert res.n_output == len(las.points) == inside.sum()
    assert shapely.intersects_xy(poly.buffer(3.0 + 1e-3), las.x, las.y).all()
    truth = scene.is_ground[inside]
    assert ((np.asarray(las.classification) == 2) == truth).mean() > 0.98


def test_empty_crop_warns_and_writes_empty_file(tmp_path):
    scene = cloudgen.road_scene(length_m=20.0, density_per_m2=20.0, seed=9)
    src = str(tmp_path / "in.las")
    cloudgen.write_scene(src, scene)
    warnings = []
    out = str(tmp_path / "out.laz")
    res = ground.run_ground_filter(src, out, "smrf", "builtin", crop_polygons=[box(0, 0, 1, 1)],
                                   progress=Progress(on_warning=warnings.append))
    assert res.n_output == 0 and warnings and res.warnings
    assert len(laspy.read(out).points) == 0


def test_crs_never_guessed(tmp_path):
    scene = cloudgen.road_scene(length_m=20.0, density_per_m2=20.0, seed=10)
    src = str(tmp_path / "nocrs.las")
    cloudgen.write_scene(src, scene, crs_epsg=None)
    out = tmp_path / "out.las"
    with pytest.raises(InputError, match="no coordinate reference system"):
        ground.run_ground_filter(src, str(out), engine="builtin")
    assert not out.exists()
    res = ground.run_ground_filter(src, str(out), engine="builtin",
                                   crs_wkt=pyproj.CRS.from_epsg(25832).to_wkt())
    assert pyproj.CRS.from_wkt(pc.read_crs_wkt(str(out))).to_epsg() == 25832
    assert pyproj.CRS.from_wkt(res.crs_wkt).to_epsg() == 25832


def test_bad_inputs_named(tmp_path):
    txt = tmp_path / "cloud.las"
    txt.write_text("not a point cloud")
    with pytest.raises(InputError, match="expected a LAS or LAZ file"):
        ground.run_ground_filter(str(txt), str(tmp_path / "o.las"))
    scene = cloudgen.road_scene(length_m=20.0, density_per_m2=40.0, seed=11)
    src = str(tmp_path / "in.laz")
    cloudgen.write_scene(src, scene)
    cut = tmp_path / "cut.laz"
    data = open(src, "rb").read()
    cut.write_bytes(data[: len(data) // 2])
    out = tmp_path / "o.laz"
    with pytest.raises(InputError, match="truncated or corrupt") as e:
        ground.run_ground_filter(str(cut), str(out), "csf", "builtin", chunk_points=5000)
    assert str(cut) in str(e.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cloud.las", "cut.laz", "in.laz"]
    with pytest.raises(InputError, match="Unknown engine"):
        ground.run_ground_filter(src, str(out), engine=7)


def test_returns_mask():
    rn = np.array([1, 1, 2, 1, 2, 3, 0])
    nr = np.array([1, 2, 2, 3, 3, 3, 0])
    np.testing.assert_array_equal(ground.returns_mask(rn, nr, "last,only"),
                                  [1, 0, 1, 0, 0, 1, 1])
    np.testing.assert_array_equal(ground.returns_mask(rn, nr, "first"), [0, 1, 0, 1, 0, 0, 1])
    np.testing.assert_array_equal(ground.returns_mask(rn, nr, "intermediate"),
                                  [0, 0, 0, 0, 1, 0, 1])


# ----------------------------------------------------------------------------- PDAL

@pytest.mark.parametrize("method", ["csf", "smrf"])
@pytest.mark.parametrize("reset", [False, True])
def test_pdal_pipeline_uses_documented_names(method, reset):
    crop = box(0, 0, 10, 10).wkt
    text = ground.build_pdal_pipeline("/data/in.las", "/data/out.laz", method, crop_wkt=crop,
                                      crs_wkt="EPSG:25833", reset_classes=reset,
                                      extra_dims=["range_m=float", "ring=uint16"])
    stages = json.loads(text)["pipeline"]
    types = [s["type"] for s in stages]
    assert types[0] == "readers.las" and types[1] == "filters.crop"
    assert types[-2 if reset else -3] == f"filters.{method}" and types[-1] == "writers.las"
    for stage in stages:
        assert stage["type"] in PDAL_DOCUMENTED, stage["type"]
        assert set(stage) - {"type"} <= PDAL_DOCUMENTED[stage["type"]], stage
    filt = next(s for s in stages if s["type"] == f"filters.{method}")
    assert {k: v for k, v in filt.items() if k != "type"} == PDAL_DEFAULTS[filt["type"]]
    assert stages[1]["polygon"] == crop
    assert stages[0]["override_srs"] == "EPSG:25833"
    writer = stages[-1]
    assert writer["forward"] == "all" and writer["compression"] == "laszip"
    assert writer["extra_dims"] == "range_m=float,ring=uint16"
    if reset:
        assert {"type": "filters.assign", "value": "Classification = 1"} in stages
    else:
        assert "filters.ferry" in types and types.count("filters.assign") == 1


def test_pdal_extra_dims_from_header(tmp_path):
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.add_extra_dims([laspy.ExtraBytesParams("range_m", np.float32),
                           laspy.ExtraBytesParams("normal", "3f8")])
    assert ground.pdal_extra_dims(header) == ["range_m=float", "normal0=double",
                                              "normal1=double", "normal2=double"]


def _fake_pdal(folder, body):
    path = folder / "pdal"
    path.write_text(f"#!{sys.executable}\n" + textwrap.dedent(body))
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return str(path)


@pytest.fixture
def small_cloud(tmp_path):
    scene = cloudgen.road_scene(length_m=30.0, density_per_m2=30.0, seed=12)
    src = str(tmp_path / "in.laz")
    cloudgen.write_scene(src, scene)
    return src, scene


def test_failing_pdal_stderr_reaches_the_message(tmp_path, small_cloud):
    """Our subprocess plumbing with a stand-in ``pdal`` (not PDAL itself): the pipeline
    goes to ``pdal pipeline --stdin`` and PDAL's stderr ends up in the error."""
    src, scene = small_cloud
    record = tmp_path / "stdin.json"
    exe = _fake_pdal(tmp_path, f"""
        import sys
        open({str(record)!r}, "w").write(" ".join(sys.argv[1:]) + "\\n" + sys.stdin.read())
        sys.stderr.write("PDAL: filters.csf: Some NumberOfReturns values were 0\\n")
        sys.exit(1)
    """)
    out = tmp_path / "out.laz"
    with pytest.raises(ground.PdalError, match="NumberOfReturns values were 0") as e:
        ground.run_ground_filter(src, str(out), "csf", "pdal", pdal_executable=exe,
                                 crop_polygons=[box(0, 0, 1e7, 1e7)])
    assert "NumberOfReturns" in e.value.stderr
    args, pipeline = record.read_text().split("\n", 1)
    assert args == "pipeline --stdin"
    stages = json.loads(pipeline)["pipeline"]
    assert stages[0] == {"type": "readers.las", "filename": src}
    assert [s["type"] for s in stages if s["type"].startswith("filters.c")] == [
        "filters.crop", "filters.csf"]
    assert not out.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".roadsigns")]

    # ENGINE=auto: the failure becomes a warning and the built-in engine runs
    warnings = []
    res = ground.run_ground_filter(src, str(out), "csf", "auto", pdal_executable=exe,
                                   progress=Progress(on_warning=warnings.append))
    assert res.engine == "builtin" and out.exists()
    assert any("NumberOfReturns values were 0" in w for w in warnings + res.warnings)


def test_pdal_success_path_moves_output_in_place(tmp_path, small_cloud):
    """A stand-in ``pdal`` that copies the input and marks every point ground: checks the
    temporary output, the move into place and the counts (plumbing, not PDAL)."""
    src, scene = small_cloud
    exe = _fake_pdal(tmp_path, """
        import json, sys, laspy
        stages = json.load(sys.stdin)["pipeline"]
        las = laspy.read(stages[0]["filename"])
        las.classification[:] = 2
        las.write(stages[-1]["filename"])
    """)
    out = tmp_path / "out.las"
    res = ground.run_ground_filter(src, str(out), "smrf", "pdal", pdal_executable=exe)
    assert res.engine == "pdal-cli" and res.n_output == res.n_ground == len(scene)
    assert json.loads(res.pipeline_json)["pipeline"][-1]["type"] == "writers.las"
    assert len(laspy.read(str(out)).points) == len(scene)


def test_pdal_requested_but_missing(tmp_path, small_cloud, monkeypatch):
    src, _ = small_cloud
    monkeypatch.setattr(ground, "pdal_python_module", lambda: None)
    monkeypatch.setattr(ground, "find_pdal_executable", lambda exe=None: None)
    with pytest.raises(InputError, match="PDAL was asked for"):
        ground.run_ground_filter(src, str(tmp_path / "o.las"), engine="pdal")
    res = ground.run_ground_filter(src, str(tmp_path / "o.las"), engine="auto")
    assert res.engine == "builtin"


def test_cancel_leaves_nothing(tmp_path, small_cloud):
    from roadsigns.core.errors import Cancelled

    src, _ = small_cloud
    calls = []

    def cancelled():
        calls.append(1)
        return len(calls) > 6  # somewhere in the second pass

    out = tmp_path / "out.laz"
    with pytest.raises(Cancelled):
        ground.run_ground_filter(src, str(out), "smrf", "builtin", chunk_points=2000,
                                 progress=Progress(is_cancelled=cancelled))
    assert not out.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".roadsigns")]


def test_smrf_net_cutting_option(scenes):
    scene = scenes["flat"]
    eligible = ground.returns_mask(scene.return_number, scene.number_of_returns)
    g = ground.classify_ground_arrays(scene.xyz[eligible], "smrf", ground.SmrfParams(cut=10.0))
    assert (g == scene.is_ground[eligible]).mean() > 0.98
