"""Point clouds as users receive them (core/cloudsource.py): one file, a folder of tiles, a
virtual point cloud (.vpc), COPC; the same points and indices whatever the form; reads
restricted to an area open only the tiles it needs; the errors name the files."""
import json
import os
import shutil

import laspy
import numpy as np
import pyproj
import pytest
import shapely
from helpers import cloudgen
from helpers.cloudtiles import split_into_tiles, write_vpc

from roadsigns.core import cloudsource as cs
from roadsigns.core import pointcloud as pc
from roadsigns.core.errors import Cancelled, InputError, Progress


@pytest.fixture(scope="module")
def street(tmp_path_factory):
    """A generated street (60 m x 30 m), as one LAZ, as 20 m tiles and as a .vpc of them."""
    folder = tmp_path_factory.mktemp("street")
    scene = cloudgen.road_scene(length_m=60.0, density_per_m2=40.0, seed=5)
    single = str(folder / "street.laz")
    classes = np.where(scene.is_ground, 2, 1).astype(np.uint8)
    cloudgen.write_scene(single, scene, point_format=6, classification=classes)
    tiles = split_into_tiles(single, str(folder / "tiles"))
    vpc = write_vpc(str(folder / "street.vpc"), tiles)
    return dict(single=single, folder=str(folder / "tiles"), tiles=tiles, vpc=vpc, n=len(scene))


def all_points(source, **kw):
    idx, xyz, cls = [], [], []
    for index, chunk in cs.open_cloud(source).iter_indexed_chunks(chunk_points=5000, **kw):
        idx.append(index)
        xyz.append(pc.xyz_of(chunk))
        cls.append(np.asarray(chunk.classification))
    return np.concatenate(idx), np.concatenate(xyz), np.concatenate(cls)


def sorted_rows(xyz, *cols):
    order = np.lexsort((xyz[:, 2], xyz[:, 1], xyz[:, 0]))
    return (xyz[order],) + tuple(c[order] for c in cols)


# --- the three forms give the same cloud --------------------------------------------------

def test_one_file_folder_and_vpc_are_the_same_cloud(street):
    single, folder, vpc = (cs.open_cloud(street[k]) for k in ("single", "folder", "vpc"))
    assert (single.kind, folder.kind, vpc.kind) == ("file", "folder", "vpc")
    assert len(single.tiles) == 1 and len(folder.tiles) == len(street["tiles"]) > 4
    assert [t.path for t in vpc.tiles] == [t.path for t in folder.tiles] == sorted(street["tiles"])
    assert single.point_count == folder.point_count == vpc.point_count == street["n"]
    np.testing.assert_allclose(folder.bounds, single.bounds, atol=1e-3)
    assert cs.same_crs(single.crs_wkt, folder.crs_wkt) and cs.same_crs(vpc.crs_wkt, single.crs_wkt)
    assert pyproj.CRS(folder.crs_wkt).to_epsg() == 25833
    # the tiles' first indices follow each other; a tile's points are its header's count
    firsts = [t.first_index for t in folder.tiles]
    assert firsts == list(np.cumsum([0] + [t.point_count for t in folder.tiles])[:-1])
    # the same points whatever the form
    a = sorted_rows(*all_points(street["single"])[1:])
    for form in ("folder", "vpc"):
        index, xyz, cls = all_points(street[form])
        np.testing.assert_array_equal(index, np.arange(street["n"]))
        b = sorted_rows(xyz, cls)
        np.testing.assert_allclose(b[0], a[0], atol=1e-6)
        np.testing.assert_array_equal(b[1], a[1])


def test_single_file_reading_is_unchanged(street):
    """``pointcloud.iter_chunks`` / ``read_header`` on one file, and a CloudSource of it,
    give the same chunks."""
    direct = np.concatenate([pc.xyz_of(c) for c in pc.iter_chunks(street["single"], 7000)])
    via = np.concatenate([pc.xyz_of(c) for c in cs.open_cloud(street["single"]).iter_chunks(7000)])
    np.testing.assert_array_equal(direct, via)
    assert pc.read_header(street["single"]).point_count == street["n"]


def test_restricted_read_opens_only_the_tiles_it_needs(street, monkeypatch):
    source = cs.open_cloud(street["folder"])
    x0, y0, _, x1, y1, _ = source.bounds
    bbox = (x0 + 5.0, y0 + 2.0, x0 + 12.0, y0 + 8.0)  # inside the first tile
    opened = []
    real = pc.iter_chunks
    monkeypatch.setattr(cs, "iter_chunks", lambda path, *a, **k: opened.append(path) or real(path, *a, **k))
    reports = []
    index, xyz, _ = all_points(street["folder"], bbox_xy=bbox, progress=Progress(on_progress=reports.append))
    assert opened == [source.tiles[0].path]
    assert len(index) == source.tiles[0].point_count < source.point_count / 2
    assert reports[-1] == 100.0 and np.all(np.diff(reports) >= 0)
    inside = (xyz[:, 0] >= bbox[0]) & (xyz[:, 0] <= bbox[2]) & (xyz[:, 1] >= bbox[1]) & (xyz[:, 1] <= bbox[3])
    full_index, full_xyz, _ = all_points(street["single"])
    full_inside = ((full_xyz[:, 0] >= bbox[0]) & (full_xyz[:, 0] <= bbox[2]) & (full_xyz[:, 1] >= bbox[1])
                   & (full_xyz[:, 1] <= bbox[3]))
    assert inside.sum() == full_inside.sum() > 100
    # the same indices as a whole read of the tiles
    whole_index, whole_xyz, _ = all_points(street["folder"])
    np.testing.assert_array_equal(whole_xyz[index], xyz)
    # an area (geometry) selects the same way; one far away selects nothing
    opened.clear()
    area = shapely.box(*bbox).buffer(1.0)
    assert [t.path for t in source.tiles_in(area=area)] == [source.tiles[0].path]
    assert source.tiles_in(area=[shapely.Point(x1 + 100, y1 + 100).buffer(1)]) == []
    assert len(source.tiles_in(bbox_xy=(x0, y0, x1, y1))) == len(source.tiles)


def test_a_file_read_whole_is_read_again_by_its_chunks_that_meet_the_area(tmp_path):
    """After one whole read, a CloudSource reads an area by the chunks that meet it (a
    drive's points come in acquisition order): the same points and indices as a fresh
    source's whole read gives there, from far fewer points decompressed."""
    rng = np.random.default_rng(2)
    n = 60000
    x = np.sort(rng.uniform(0.0, 300.0, n))            # along the drive, in acquisition order
    y = rng.uniform(-15.0, 15.0, n)
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales, header.offsets = [0.001] * 3, [500000.0, 5400000.0, 0.0]
    header.add_crs(pyproj.CRS.from_epsg(25833))
    las = laspy.LasData(header)
    las.x, las.y, las.z = x + 500000.0, y + 5400000.0, rng.normal(0.0, 0.1, n)
    las.intensity = np.arange(n) % 65536
    path = str(tmp_path / "drive.laz")
    las.write(path)
    area = shapely.box(500120.0, 5399990.0, 500140.0, 5400010.0)

    def read(source, **kw):
        got = [(i, pc.xyz_of(c)) for i, c in source.iter_indexed_chunks(chunk_points=4000, **kw)]
        return np.concatenate([i for i, _ in got]), np.concatenate([p for _, p in got])

    fresh_index, fresh_xyz = read(cs.open_cloud(path), area=area)
    assert len(fresh_index) == n                       # never read: the whole file
    source = cs.open_cloud(path)
    read(source)                                       # read whole once
    reports = []
    index, xyz = read(source, area=area, progress=Progress(on_progress=reports.append))
    assert len(index) <= 3 * 4000                      # the chunks around x 120-140 m only
    assert reports[-1] == 100.0
    inside = shapely.contains_xy(area, fresh_xyz[:, 0], fresh_xyz[:, 1])
    mine = shapely.contains_xy(area, xyz[:, 0], xyz[:, 1])
    assert inside.sum() > 1000
    np.testing.assert_array_equal(index[mine], fresh_index[inside])
    np.testing.assert_array_equal(xyz[mine], fresh_xyz[inside])
    # a cancelled whole read remembers nothing
    other = cs.open_cloud(path)
    it = other.iter_indexed_chunks(chunk_points=4000)
    next(it)
    it.close()
    assert len(read(other, area=area)[0]) == n


def test_index_of_tiles_equals_index_of_the_file(street):
    region = pc.CropRegion(shapely.box(street_x(street) + 15, -20 + 5.4e6, street_x(street) + 45, 5.4e6 + 20))
    single = cs.open_cloud(street["single"]).index(region, ("intensity", "classification"), 5.0)
    tiled = cs.open_cloud(street["vpc"]).index(region, ("intensity", "classification"), 5.0)
    assert len(single) == len(tiled) > 1000
    a = sorted_rows(single.xyz_world, single.attributes["classification"])
    b = sorted_rows(tiled.xyz_world, tiled.attributes["classification"])
    np.testing.assert_allclose(a[0], b[0], atol=1e-6)
    np.testing.assert_array_equal(a[1], b[1])
    # the file's own TiledIndex.from_las is the same as the CloudSource's index of it
    direct = pc.TiledIndex.from_las(street["single"], region, ("intensity", "classification"), 5.0)
    np.testing.assert_array_equal(np.sort(direct.point_index), np.sort(single.point_index))
    assert cs.open_cloud(street["vpc"]).index(pc.CropRegion(shapely.Polygon()), ("intensity",)).nbytes == 0


def street_x(street):
    return cs.open_cloud(street["single"]).bounds[0]


def test_scales_and_offsets_may_differ(street, tmp_path):
    paths = split_into_tiles(street["single"], str(tmp_path / "mixed"), scales=[0.01, 0.01, 0.001],
                             offsets_shift=np.array([100.0, -50.0, 3.0]))
    source = cs.open_cloud(str(tmp_path / "mixed"))
    assert len(paths) > 4 and source.point_count == street["n"]
    index, xyz, _ = all_points(str(tmp_path / "mixed"))
    ref_index, ref, _ = all_points(street["folder"])  # the same tiles with the file's scales and offsets
    np.testing.assert_array_equal(index, ref_index)
    np.testing.assert_allclose(xyz[:, 2], ref[:, 2], atol=1e-6)  # z keeps its scale: exact
    np.testing.assert_allclose(xyz[:, :2], ref[:, :2], atol=0.005 + 1e-6)  # x, y rounded to cm
    assert np.abs(xyz[:, :2] - ref[:, :2]).max() > 0.001  # ... in every other tile
    # written to one file with the first tile's scales and offsets, within half a centimetre
    header = source.header
    out = str(tmp_path / "merged.laz")
    with pc.CloudWriter(out, header) as w:
        for chunk in source.iter_chunks(5000):
            w.write(cs.conform(chunk, header))
    merged = laspy.read(out)
    back = np.column_stack([merged.x, merged.y, merged.z])
    np.testing.assert_allclose(back, ref, atol=0.005 + 1e-6)
    assert np.array_equal(merged.header.scales, header.scales)


def test_folder_skips_hidden_files_other_files_and_qgis_copc_indexes(street, tmp_path):
    folder = tmp_path / "tiles"
    shutil.copytree(street["folder"], folder)
    first = sorted(os.listdir(folder))[0]
    shutil.copy(folder / first, folder / (first[:-4] + ".copc.laz"))   # as QGIS indexes a file
    shutil.copy(folder / first, folder / ".roadsigns-partial.laz")
    (folder / "notes.txt").write_text("not a cloud")
    (folder / "sub").mkdir()
    shutil.copy(folder / first, folder / "sub" / "deeper.laz")
    source = cs.open_cloud(str(folder))
    assert [t.name for t in source.tiles] == sorted(os.path.basename(p) for p in street["tiles"])


# --- COPC -----------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def copc(tmp_path_factory):
    """A street of 430 000 points as COPC (an octree of 7 nodes), written by PDAL's
    writers.copc: laspy reads COPC but cannot write it."""
    pdal = pytest.importorskip("pdal", reason="COPC needs PDAL's writers.copc to be written (laspy only "
                                              "reads COPC): the pdal Python module is not installed")
    folder = tmp_path_factory.mktemp("copc")
    scene = cloudgen.road_scene(length_m=160.0, density_per_m2=150.0, seed=6)
    las = str(folder / "street.laz")
    cloudgen.write_scene(las, scene)
    path = str(folder / "street.copc.laz")
    pipeline = pdal.Pipeline(json.dumps({"pipeline": [las, {"type": "writers.copc", "filename": path}]}))
    try:
        pipeline.execute()
    except RuntimeError as e:
        pytest.skip(f"this PDAL cannot write COPC ({e})")
    return path, len(scene)


def test_copc_is_read_whole_and_by_area(copc):
    path, n = copc
    source = cs.open_cloud(path)
    assert source.tiles[0].copc and source.point_count == n
    # the header to write with is not COPC any more
    assert not cs.is_copc(source.header)
    whole_index, whole_xyz, _ = all_points(path)
    np.testing.assert_array_equal(whole_index, np.arange(n))
    x0, y0, _, _, _, _ = source.bounds
    bbox = (x0 + 20.0, y0 + 5.0, x0 + 26.0, y0 + 11.0)
    reports = []
    index, xyz, _ = all_points(path, bbox_xy=bbox, progress=Progress(on_progress=reports.append))
    assert len(index) < n / 2, "a COPC read by area reads only the octree nodes there"
    assert reports[-1] == 100.0 and len(reports) > 2
    # the points of a read by area have the indices of the sequential read
    np.testing.assert_array_equal(whole_xyz[index], xyz)
    inside = lambda p: ((p[:, 0] >= bbox[0]) & (p[:, 0] <= bbox[2]) & (p[:, 1] >= bbox[1])  # noqa: E731
                        & (p[:, 1] <= bbox[3]))
    assert inside(xyz).sum() == inside(whole_xyz).sum() > 50


def test_copc_written_to_plain_laz_is_not_copc(copc, tmp_path):
    source = cs.open_cloud(copc[0])
    out = str(tmp_path / "plain.laz")
    with pc.CloudWriter(out, pc.output_header(source.header)) as w:
        for chunk in source.iter_chunks():
            w.write(chunk)
    header = pc.read_header(out)
    assert not cs.is_copc(header) and header.point_count == source.point_count
    assert len(laspy.read(out).x) == source.point_count


# --- writing a .vpc -----------------------------------------------------------------------

def test_written_vpc_reads_back(street, tmp_path):
    headers = [(t, pc.read_header(t)) for t in street["tiles"]]
    crs = cs.open_cloud(street["folder"]).crs_wkt
    path = tmp_path / "out.vpc"
    path.write_text(cs.vpc_text(headers, crs, street["folder"]))
    moved = tmp_path / "tiles"
    shutil.copytree(street["folder"], moved)
    # hrefs are relative to the .vpc: it must sit where the folder it was written for is
    (tmp_path / "out2.vpc").write_text(cs.vpc_text(headers, crs, str(tmp_path)).replace(
        os.path.relpath(street["folder"], str(tmp_path)).replace(os.sep, "/"), "tiles"))
    data = json.loads(path.read_text())
    feature = data["features"][0]
    assert feature["stac_version"] == "1.0.0" and feature["assets"]["data"]["href"].startswith("./")
    assert len(feature["properties"]["proj:bbox"]) == 6 and feature["properties"]["pc:count"] > 0
    lon, lat = feature["geometry"]["coordinates"][0][0]
    assert 13 < lon < 16 and 48 < lat < 49.5  # UTM 33N, 500 km east, 5400 km north
    assert cs.open_cloud(str(tmp_path / "out2.vpc")).point_count == street["n"]


# --- bad inputs -----------------------------------------------------------------------------

def test_empty_folder_is_refused(tmp_path):
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "readme.txt").write_text("x")
    with pytest.raises(InputError) as e:
        cs.open_cloud(str(tmp_path / "empty"))
    assert "holds no LAS or LAZ file" in str(e.value) and str(tmp_path / "empty") in str(e.value)


def test_tiles_in_different_crs_are_refused_naming_both(street, tmp_path):
    paths = split_into_tiles(street["single"], str(tmp_path / "crs"), crs_epsg=32633)
    with pytest.raises(InputError) as e:
        cs.open_cloud(str(tmp_path / "crs"))
    text = str(e.value)
    assert "different CRSs" in text and paths[0] in text and paths[-1] in text
    assert "EPSG:25833" in text and "EPSG:32633" in text


def test_same_crs_written_differently_is_one_crs():
    a = pyproj.CRS.from_epsg(25833)
    assert cs.same_crs(a.to_wkt(), a.to_wkt("WKT1_GDAL"))
    assert cs.same_crs(a.to_wkt(), "EPSG:25833")
    assert not cs.same_crs(a.to_wkt(), "EPSG:32633")
    assert not cs.same_crs(a.to_wkt(), None) and cs.same_crs(None, None)


def test_tiles_of_different_point_formats_are_refused(street, tmp_path):
    paths = split_into_tiles(street["single"], str(tmp_path / "fmt"))
    other = laspy.read(paths[1])
    converted = laspy.convert(other, point_format_id=7)
    converted.write(paths[1])
    with pytest.raises(InputError) as e:
        cs.open_cloud(str(tmp_path / "fmt"))
    assert "point format 6" in str(e.value) and "point format 7" in str(e.value)
    assert paths[0] in str(e.value) and paths[1] in str(e.value)


def test_tile_missing_from_a_vpc_is_named(street, tmp_path):
    folder = tmp_path / "t"
    shutil.copytree(street["folder"], folder)
    tiles = sorted(str(p) for p in folder.iterdir())
    vpc = write_vpc(str(tmp_path / "c.vpc"), tiles)
    os.remove(tiles[2])
    with pytest.raises(InputError) as e:
        cs.open_cloud(vpc)
    assert tiles[2] in str(e.value) and "feature 3" in str(e.value) and "does not exist" in str(e.value)


def test_unreadable_tile_is_named(street, tmp_path):
    folder = tmp_path / "t"
    shutil.copytree(street["folder"], folder)
    bad = sorted(folder.iterdir())[1]
    bad.write_bytes(b"this is not a point cloud at all" * 20)
    with pytest.raises(InputError) as e:
        cs.open_cloud(str(folder))
    assert str(bad) in str(e.value) and "LAS or LAZ" in str(e.value)


@pytest.mark.parametrize("text, words", [
    ("{not json", "not valid JSON"),
    ('{"type": "Feature", "features": []}', "FeatureCollection"),
    ('[1, 2]', "not an object"),
    ('{"type": "FeatureCollection", "features": [{"properties": {}}]}', "feature 1 has no 'assets'"),
    ('{"type": "FeatureCollection", "features": [{"assets": {"data": {"roles": ["data"]}}}]}', "href"),
    ('{"type": "FeatureCollection", "features": []}', "lists no tile"),
    ('{"type": "FeatureCollection", "features": [{"assets": {"data": {"href": "https://x.org/a.copc.laz"}}}]}',
     "remote tile"),
])
def test_bad_vpc_says_what_was_expected(tmp_path, text, words):
    path = tmp_path / "bad.vpc"
    path.write_text(text)
    with pytest.raises(InputError) as e:
        cs.open_cloud(str(path))
    assert words in str(e.value) and str(path) in str(e.value)


def test_vpc_tolerates_missing_optional_members(street, tmp_path):
    """Only assets.*.href is needed: bounds and counts come from the tiles' headers, and an
    absolute href works too."""
    features = [{"type": "Feature", "assets": {"points": {"href": t}}} for t in street["tiles"]]
    path = tmp_path / "minimal.vpc"
    path.write_text(json.dumps({"type": "FeatureCollection", "features": features}))
    source = cs.open_cloud(str(path))
    assert source.point_count == street["n"] and len(source.tiles) == len(street["tiles"])
    assert source.tiles[0].maxs[0] > source.tiles[0].mins[0]


def test_vpc_crs_is_used_for_tiles_without_one(street, tmp_path):
    scene = cloudgen.road_scene(length_m=20.0, density_per_m2=10.0, seed=2)
    tile = str(tmp_path / "nocrs.laz")
    cloudgen.write_scene(tile, scene, crs_epsg=None)
    assert cs.open_cloud(tile).crs_wkt is None
    vpc = write_vpc(str(tmp_path / "c.vpc"), [tile])
    assert pyproj.CRS(cs.open_cloud(vpc).crs_wkt).to_epsg() == 25833


def test_reading_tiles_can_be_cancelled(street):
    source = cs.open_cloud(street["folder"])
    calls = []
    with pytest.raises(Cancelled):
        for _ in source.iter_chunks(1000, Progress(is_cancelled=lambda: calls.append(1) or len(calls) > 3)):
            pass


def test_points_too_far_for_the_first_tiles_scale_are_refused(street):
    chunk = next(cs.open_cloud(street["single"]).iter_chunks(100))
    header = laspy.LasHeader(point_format=chunk.point_format.id, version="1.4")
    header.scales = np.array([0.0001, 0.0001, 0.0001])
    header.offsets = np.array([0.0, 0.0, 0.0])  # 500 km / 0.1 mm does not fit in 32 bits
    with pytest.raises(InputError, match="too far"):
        cs.conform(chunk, header)
    header.offsets = np.floor(np.array([chunk.x.min(), chunk.y.min(), chunk.z.min()]))
    moved = cs.conform(chunk, header)
    np.testing.assert_allclose(np.asarray(moved.x), np.asarray(chunk.x), atol=1e-4)
    assert np.array_equal(moved.intensity, chunk.intensity)


def test_a_pass_over_the_cloud_gives_the_freed_heap_back_as_it_reads(street, monkeypatch):
    """Every TRIM_EVERY_POINTS points read, the heap the finished chunks freed is given back,
    so a pass keeps no more of it on a long drive than on a short one."""
    calls = []
    monkeypatch.setattr(cs, "release_freed_memory", lambda: calls.append(1) or True)
    monkeypatch.setattr(cs, "TRIM_EVERY_POINTS", 4000)
    n = sum(len(chunk) for _, chunk in cs.open_cloud(street["folder"]).iter_indexed_chunks(chunk_points=1000))
    assert n == street["n"]
    # at least one return per 4000 points read (a tile's last chunk may be short), and never
    # more than one per chunk
    assert n // 4000 - len(street["tiles"]) <= len(calls) <= n // 1000 + len(street["tiles"])
    assert len(calls) >= 2


def test_a_pass_lets_go_of_its_area_once_the_reads_are_planned(street):
    """The shapes that choose the tiles (a drive's frustum footprints) are not held while
    the pass reads: the caller's last reference is its own."""
    import sys

    source = cs.open_cloud(street["folder"])
    x0, y0, _, x1, y1, _ = source.bounds
    area = [shapely.box(x0, y0, x1, y1)]
    held = sys.getrefcount(area)
    chunks = source.iter_indexed_chunks(chunk_points=5000, area=area)
    index, _ = next(chunks)
    assert len(index) > 0
    assert sys.getrefcount(area) == held
    rest = sum(len(i) for i, _ in chunks)
    assert len(index) + rest == street["n"]     # the area still chose the tiles: all of them


def test_a_read_says_how_far_it_is_in_each_tile(street):
    """One step a chunk: the tile read and the millions of points read of those to read."""
    from roadsigns.core.errors import Progress

    steps = []
    n = sum(len(chunk) for _, chunk in cs.open_cloud(street["folder"]).iter_indexed_chunks(
        chunk_points=4000, progress=Progress(on_step=steps.append)))
    assert len(steps) >= len(street["tiles"])
    assert {s.fields["name"] for s in steps} == {os.path.basename(t) for t in street["tiles"]}
    done = [s.fields["done"] for s in steps]
    assert done == sorted(done) and done[-1] * 1e6 == pytest.approx(n)
    assert all(s.fields["total"] * 1e6 == pytest.approx(street["n"]) for s in steps)
    assert steps[-1] == "Reading {}: {:.1f} of {:.1f} million points".format(
        os.path.basename(street["tiles"][-1]), n / 1e6, street["n"] / 1e6)
