"""Chunked LAS/LAZ I/O, faithful writing, crops and the tiled spatial index."""

import laspy
import numpy as np
import pyproj
import pytest
import shapely
from helpers import cloudgen  # noqa: E402
from scipy.spatial import cKDTree
from shapely.geometry import Polygon, box

from roadsigns.core import pointcloud as pc  # noqa: E402
from roadsigns.core.errors import InputError  # noqa: E402

CRS = pyproj.CRS.from_epsg(25833)


def _rich_las(path, point_format, n=5000, seed=0, with_crs=True):
    """A LAS/LAZ with every dimension of the format set, extra bytes (scalar and array),
    a custom VLR, an EVLR (LAS 1.4), odd scales/offsets and a CRS."""
    rng = np.random.default_rng(seed)
    version = "1.4" if point_format >= 6 else "1.2"
    header = laspy.LasHeader(point_format=point_format, version=version)
    header.scales = np.array([0.0025, 0.001, 0.0005])
    header.offsets = np.array([499000.0, 5399000.0, -12.5])
    header.system_identifier = "roadsigns test"
    header.add_extra_dims([
        laspy.ExtraBytesParams(name="range_m", type=np.float32, description="range"),
        laspy.ExtraBytesParams(name="ring", type=np.uint16),
        laspy.ExtraBytesParams(name="normal", type="3f8"),
    ])
    header.vlrs.append(laspy.VLR(user_id="roadsigns", record_id=4242,
                                 description="custom", record_data=b"hello \x00\x01 vlr"))
    if with_crs:
        header.add_crs(CRS)
    if version == "1.4":
        header.evlrs = laspy.vlrs.vlrlist.VLRList([laspy.VLR(
            user_id="roadsigns", record_id=99, description="evlr", record_data=b"E" * 300)])
    las = laspy.LasData(header)
    las.x = 500000 + rng.uniform(0, 200, n)
    las.y = 5400000 + rng.uniform(0, 100, n)
    las.z = 100 + rng.uniform(-5, 20, n)
    for dim in las.point_format.dimensions:
        if dim.name in ("X", "Y", "Z"):
            continue
        arr = np.asarray(las[dim.name])
        if dim.kind == laspy.DimensionKind.BitField:
            maxv = (1 << dim.num_bits) - 1
            las[dim.name] = rng.integers(0, maxv + 1, n).astype(arr.dtype)
        elif np.issubdtype(arr.dtype, np.floating):
            las[dim.name] = rng.normal(0, 100, arr.shape).astype(arr.dtype)
        else:
            info = np.iinfo(arr.dtype)
            las[dim.name] = rng.integers(info.min, info.max, arr.shape,
                                         endpoint=True).astype(arr.dtype)
    las.write(path)
    return path


def _assert_same_cloud(a_path, b_path, keep=None):
    a, b = laspy.read(a_path), laspy.read(b_path)
    ha, hb = a.header, b.header
    assert hb.point_format.id == ha.point_format.id
    assert str(hb.version) == str(ha.version)
    np.testing.assert_array_equal(hb.scales, ha.scales)
    np.testing.assert_array_equal(hb.offsets, ha.offsets)
    assert hb.system_identifier == ha.system_identifier
    assert list(b.point_format.dimension_names) == list(a.point_format.dimension_names)
    rows = slice(None) if keep is None else keep
    for name in a.point_format.dimension_names:
        np.testing.assert_array_equal(np.asarray(b[name]), np.asarray(a[name])[rows],
                                      err_msg=name)
    def vlrs(h):
        return sorted((v.user_id, v.record_id, bytes(getattr(v, "record_data", b"") or b""))
                      for v in h.vlrs if v.user_id != "laszip encoded")

    assert vlrs(hb) == vlrs(ha)
    if ha.evlrs:
        assert [(v.user_id, v.record_id, bytes(v.record_data)) for v in hb.evlrs] == \
               [(v.user_id, v.record_id, bytes(v.record_data)) for v in ha.evlrs]
    assert pc.crs_wkt_of_header(hb) == pc.crs_wkt_of_header(ha)


@pytest.mark.parametrize("point_format", [1, 3, 6, 7, 8])
@pytest.mark.parametrize("suffix", [".las", ".laz"])
def test_round_trip_keeps_everything(tmp_path, point_format, suffix):
    src = _rich_las(str(tmp_path / f"in{suffix}"), point_format)
    out = str(tmp_path / f"out{suffix}")
    result = pc.crop_cloud(src, out, None, chunk_points=1234)
    assert result.n_output == result.n_input == 5000
    _assert_same_cloud(src, out)
    assert pyproj.CRS.from_wkt(pc.read_crs_wkt(out)).to_epsg() == 25833
    if suffix == ".laz":
        with laspy.open(out) as r:
            assert r.header.are_points_compressed


def test_chunks_cover_file_in_order(tmp_path):
    src = _rich_las(str(tmp_path / "c.laz"), 6, n=10007)
    full = laspy.read(src)
    parts = list(pc.iter_chunks(src, chunk_points=1000))
    assert [len(p) for p in parts] == [1000] * 10 + [7]
    np.testing.assert_array_equal(np.concatenate([p.gps_time for p in parts]), full.gps_time)
    xyz = np.concatenate([pc.xyz_of(p) for p in parts])
    np.testing.assert_allclose(xyz[:, 0], full.x)


def test_not_las_is_named(tmp_path):
    bad = tmp_path / "cloud.laz"
    bad.write_text("x,y,z\n1,2,3\n")
    with pytest.raises(InputError, match="expected a LAS or LAZ file") as e:
        pc.read_header(str(bad))
    assert str(bad) in str(e.value)
    with pytest.raises(InputError, match="does not exist"):
        pc.read_header(str(tmp_path / "missing.las"))


@pytest.mark.parametrize("suffix", [".las", ".laz"])
def test_truncated_file_fails_without_output(tmp_path, suffix):
    src = _rich_las(str(tmp_path / f"full{suffix}"), 3, n=20000)
    data = open(src, "rb").read()
    cut = tmp_path / f"cut{suffix}"
    cut.write_bytes(data[: len(data) * 2 // 3])
    out = tmp_path / f"out{suffix}"
    with pytest.raises(InputError, match="truncated or corrupt") as e:
        pc.crop_cloud(str(cut), str(out), None, chunk_points=3000)
    assert str(cut) in str(e.value)
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".roadsigns")] == []


def test_existing_output_survives_failure(tmp_path):
    src = _rich_las(str(tmp_path / "full.las"), 3, n=5000)
    cut = tmp_path / "cut.las"
    cut.write_bytes(open(src, "rb").read()[:4000])
    out = tmp_path / "out.las"
    out.write_bytes(b"previous result")
    with pytest.raises(InputError):
        pc.crop_cloud(str(cut), str(out), None)
    assert out.read_bytes() == b"previous result"


def test_no_crs_is_an_error_unless_given(tmp_path):
    src = _rich_las(str(tmp_path / "nocrs.las"), 6, with_crs=False)
    assert pc.read_crs_wkt(src) is None
    with pytest.raises(InputError, match="no coordinate reference system"):
        pc.crop_cloud(src, str(tmp_path / "o.las"))
    given = CRS.to_wkt()
    pc.crop_cloud(src, str(tmp_path / "o.las"), crs_wkt=given)
    assert pyproj.CRS.from_wkt(pc.read_crs_wkt(str(tmp_path / "o.las"))).to_epsg() == 25833


def test_polygon_crop_streams_and_matches_shapely(tmp_path):
    src = _rich_las(str(tmp_path / "in.laz"), 6, n=20000)
    poly1 = Polygon([(500020, 5400010), (500090, 5400015), (500060, 5400070)])
    poly2 = box(500150, 5400050, 500190, 5400099)
    region = pc.CropRegion.from_polygons([poly1, shapely.to_wkb(poly2)])
    out = str(tmp_path / "crop.laz")
    res = pc.crop_cloud(src, out, region, chunk_points=3000)
    full = laspy.read(src)
    expected = shapely.intersects_xy(shapely.union_all([poly1, poly2]), full.x, full.y)
    assert res.n_output == expected.sum() > 1000
    _assert_same_cloud(src, out, keep=expected)


def test_crop_buffer_grows_polygons():
    region = pc.CropRegion.from_polygons([box(0, 0, 10, 10)], buffer_m=2.0)
    x = np.array([5.0, 11.9, 12.1, -1.5, 11.5])
    y = np.array([5.0, 5.0, 5.0, 5.0, 11.5])
    np.testing.assert_array_equal(region.mask(x, y), [True, True, False, True, False])


def test_corridor_around_stations_and_rays():
    stations = np.array([[0.0, 0.0], [10.0, 0.0]])
    rays = [np.array([[10.0, 0.0, 2.0], [10.0, 30.0, 4.0]])]
    region = pc.CropRegion.corridor(3.0, points_xy=stations, lines_xy=rays)
    x = np.array([0.0, 2.9, 5.0, 12.5, 6.5, 13.1, 10.0])
    y = np.array([2.9, 0.0, 0.0, 20.0, 25.0, 10.0, 32.9])
    np.testing.assert_array_equal(region.mask(x, y),
                                  [True, True, False, True, False, False, True])
    with pytest.raises(InputError):
        pc.CropRegion.corridor(0.0, points_xy=stations)


def test_buffered_union_in_blocks_is_the_buffer_of_the_union():
    """Stations of a winding 3 km drive (more than one block), a polygon and a line: the
    blockwise buffer is the buffer of the whole union (up to rounding), and the crop from
    station points keeps what lies within the buffer of any station."""
    s = np.linspace(0.0, 3000.0, 2000)
    stations = np.column_stack([s, 200.0 * np.sin(s / 300.0)])
    extra = [box(500.0, 400.0, 520.0, 430.0), shapely.linestrings([[0.0, -300.0], [50.0, -250.0]])]
    geometries = list(shapely.points(stations)) + extra
    assert len(geometries) > 10 * pc.BUFFER_BLOCK
    blockwise = pc.buffered_union(geometries, 25.0)
    whole = shapely.union_all(geometries).buffer(25.0)
    assert shapely.symmetric_difference(blockwise, whole).area < 1e-6 * whole.area
    assert pc.buffered_union(geometries, 0.0).equals(shapely.union_all(geometries))
    region = pc.CropRegion.corridor(25.0, points_xy=stations)
    rng = np.random.default_rng(3)
    x = rng.uniform(-50.0, 3050.0, 20000)
    y = rng.uniform(-260.0, 260.0, 20000)
    d, _ = cKDTree(stations).query(np.column_stack([x, y]))
    sure = (d < 24.8) | (d > 25.0)  # away from the buffer's polygonal edge (32 segments a circle)
    np.testing.assert_array_equal(region.mask(x, y)[sure], (d < 25.0)[sure])


def test_empty_crop_warns_and_writes_valid_file(tmp_path):
    src = _rich_las(str(tmp_path / "in.las"), 6, n=1000)
    region = pc.CropRegion.from_polygons([box(0, 0, 1, 1)])
    warnings = []
    from roadsigns.core.errors import Progress

    res = pc.crop_cloud(src, str(tmp_path / "empty.laz"), region,
                        progress=Progress(on_warning=warnings.append))
    assert res.n_output == 0 and warnings and res.warnings
    empty = laspy.read(str(tmp_path / "empty.laz"))
    assert len(empty.points) == 0
    assert empty.header.point_format.id == 6
    assert pc.read_crs_wkt(str(tmp_path / "empty.laz")) is not None


def test_tiled_index_queries_equal_brute_force(tmp_path):
    scene = cloudgen.road_scene(length_m=40.0, density_per_m2=40.0, seed=3)
    path = str(tmp_path / "scene.laz")
    cloudgen.write_scene(path, scene)
    full = laspy.read(path)
    xyz = np.column_stack([full.x, full.y, full.z])
    o = np.array(cloudgen.ORIGIN)
    region = pc.CropRegion.corridor(8.0, lines_xy=[np.array([o[:2] + [0, 0], o[:2] + [40, 0]])])
    index = pc.TiledIndex.from_las(path, region, tile_size_m=7.0, chunk_points=9000)
    inside = region.mask(xyz[:, 0], xyz[:, 1])
    assert len(index) == inside.sum() < len(xyz)
    assert index.nbytes < 0.8 * len(xyz) * (24 + 8 + 2 + 1 + 8)  # grows with the crop

    rng = np.random.default_rng(0)
    for _ in range(15):
        c = o + [rng.uniform(0, 40), rng.uniform(-9, 9), rng.uniform(0, 4)]
        r = rng.uniform(0.5, 4.0)
        got = index.query_radius(c, r)
        want = np.flatnonzero(inside & (np.linalg.norm(xyz - c, axis=1) <= r))
        np.testing.assert_array_equal(got.point_index, want)
        np.testing.assert_allclose(got.xyz_world, xyz[want])
        np.testing.assert_array_equal(got.attributes["intensity"], full.intensity[want])
        np.testing.assert_array_equal(got.attributes["gps_time"], full.gps_time[want])

        lo = c - rng.uniform(0.5, 6, 3)
        hi = c + rng.uniform(0.5, 6, 3)
        got = index.query_box(lo, hi)
        want = np.flatnonzero(inside & np.all((xyz >= lo) & (xyz <= hi), axis=1))
        np.testing.assert_array_equal(got.point_index, want)

        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        got = index.query_cone(c, d, 15.0, 12.0, 1.0)
        v = xyz - c
        dist = np.linalg.norm(v, axis=1)
        cone = (dist >= 1.0) & (dist <= 12.0) & (v @ d >= np.cos(np.radians(15.0)) * dist)
        np.testing.assert_array_equal(got.point_index, np.flatnonzero(inside & cone))


def test_tiled_index_from_arrays():
    rng = np.random.default_rng(1)
    xyz = rng.uniform(-50, 50, (3000, 3))
    idx = pc.TiledIndex.from_arrays(xyz, {"i": np.arange(3000)}, tile_size_m=9.0)
    got = idx.query_radius([1.0, 2.0, 3.0], 20.0)
    want = np.flatnonzero(np.linalg.norm(xyz - [1, 2, 3], axis=1) <= 20.0)
    np.testing.assert_array_equal(got.point_index, want)
    np.testing.assert_array_equal(got.attributes["i"], want)
    assert len(idx.query_box([100, 100, 100], [200, 200, 200])) == 0


def test_crop_mask_by_cells_equals_the_exact_test():
    """The cell-first mask gives exactly shapely's answer: on a union of thin wedges (the
    frusta of a drive), for random points and for points on the boundary and the cells' edges."""
    rng = np.random.default_rng(4)
    wedges = [Polygon([(x0, 0), (x0 + 30, 4 + k % 3), (x0 + 30, -3 - k % 5)]) for k, x0 in
              enumerate(np.arange(0.0, 400.0, 7.3))]
    region = pc.CropRegion(shapely.union_all(wedges))
    x = np.concatenate([rng.uniform(-5, 440, 200_000), np.repeat(np.arange(0.0, 430.0, 1.0), 3)])
    y = np.concatenate([rng.uniform(-10, 10, 200_000), np.tile([0.0, 4.0, -3.0], 430)])
    boundary = np.asarray(shapely.get_coordinates(region.geometry.boundary))
    x, y = np.concatenate([x, boundary[:, 0]]), np.concatenate([y, boundary[:, 1]])
    exact = shapely.intersects_xy(region.geometry, x, y)
    assert 0.1 < exact.mean() < 0.9
    assert np.array_equal(region.mask(x, y), exact)


def test_a_crop_region_is_tested_from_several_threads_at_once():
    """The ground filter crops its chunks in a pool of threads with one region. A GEOS
    prepared geometry builds its indexes lazily and is not thread-safe (libgeos/geos#825;
    this crashed the interpreter): each other thread tests against its own prepared copy,
    and the masks are the region's own, whichever thread computed them."""
    from concurrent.futures import ThreadPoolExecutor

    rng = np.random.default_rng(5)
    wedges = [Polygon([(x0, 0), (x0 + 30, 4 + k % 3), (x0 + 30, -3 - k % 5)]) for k, x0 in
              enumerate(np.arange(0.0, 400.0, 7.3))]
    x, y = rng.uniform(-5, 440, 100_000), rng.uniform(-10, 10, 100_000)
    exact = shapely.intersects_xy(shapely.union_all(wedges), x, y)
    parts = np.array_split(np.arange(len(x)), 16)
    for _ in range(4):
        region = pc.CropRegion(shapely.union_all(wedges))     # fresh: nothing built yet
        with ThreadPoolExecutor(max_workers=4) as pool:
            masks = list(pool.map(lambda rows: region.mask(x[rows], y[rows]), parts))
        assert np.array_equal(np.concatenate(masks), exact)
    with ThreadPoolExecutor(max_workers=1) as pool:
        theirs = pool.submit(region._geometry_here).result()
    assert theirs is not region.geometry and shapely.equals_exact(theirs, region.geometry, 0.0)
    assert region._geometry_here() is region.geometry


@pytest.mark.parametrize("offset", [(0.0, 0.0), (-130.0, -47.0), (350_000.0, 5_600_000.0)])
def test_tiled_index_orders_its_points_by_tile_column_then_row(offset):
    """The index's order: tile column i, then row j, the input order within a tile (as
    numpy's stable lexsort gives it), and each tile's range of rows, on either side of 0."""
    rng = np.random.default_rng(4)
    xyz = np.column_stack([rng.uniform(-60, 60, 5000) + offset[0], rng.uniform(-40, 40, 5000) + offset[1],
                           rng.uniform(0, 5, 5000)])
    xyz[:50, :2] = np.floor(xyz[:50, :2] / 10.0) * 10.0        # points on tile edges
    idx = pc.TiledIndex(xyz, np.arange(len(xyz)) * 3, {"intensity": np.arange(len(xyz))}, tile_size_m=10.0)
    tiles = np.floor(xyz[:, :2] / 10.0).astype(np.int64)
    order = np.lexsort((tiles[:, 1], tiles[:, 0]))
    np.testing.assert_array_equal(idx.xyz_world, xyz[order])
    np.testing.assert_array_equal(idx.point_index, order * 3)
    np.testing.assert_array_equal(idx.attributes["intensity"], order)
    keys = {tuple(t) for t in tiles.tolist()}
    assert idx.tile_keys == sorted(keys)
    for key in keys:
        s, e = idx._ranges[key]
        assert np.array_equal(np.sort(order[s:e]), np.flatnonzero((tiles == key).all(axis=1)))
    assert len(pc.TiledIndex(np.zeros((0, 3)), np.zeros(0, np.int64))) == 0
