"""The ground filter on a cloud of tiles (core/ground/tiled.py, and engine.py on a folder or a
.vpc): one tile per input tile, each classified with its neighbours' points around it, gives
the classes of a run on the whole cloud; one merged file from tiles too; nothing half
written when cancelled; the same through the real PDAL, tile by tile with a halo."""
import json
import os
import shutil

import laspy
import numpy as np
import pytest
from helpers import realpdal
from helpers.cloudtiles import (
    classes_by_point,
    hilly_street,
    same_classes_cases,
    split_into_tiles,
    street_crop,
    write_vpc,
)

from roadsigns.core import cloudsource as cs
from roadsigns.core import ground
from roadsigns.core import pointcloud as pc
from roadsigns.core.errors import Cancelled, InputError, Progress

#: The brief's bar for tiles against one file; the built-in engine reaches 100 %.
MIN_AGREEMENT = 0.999


@pytest.fixture(scope="module")
def hilly(tmp_path_factory):
    """A 120 m street on a 3 % slope, one LAZ, and the same split into 25 m tiles (whose
    edges do not fall on CSF's 32 m squares)."""
    return hilly_street(tmp_path_factory.mktemp("hilly"))


def agreement(single_out, tile_outs):
    k1, c1 = classes_by_point([single_out])
    k2, c2 = classes_by_point(tile_outs)
    np.testing.assert_array_equal(k1, k2)  # the same points
    return float((c1 == c2).mean())


@pytest.mark.parametrize("method, params, crop", same_classes_cases())
def test_tiles_get_the_classes_of_one_file(hilly, tmp_path, method, params, crop):
    crop_polygons = street_crop(hilly["single"]) if crop else None   # leaves two tiles out
    one = str(tmp_path / "one.laz")
    ground.run_ground_filter(hilly["single"], one, method, "builtin", params=params, crop_polygons=crop_polygons)
    out = tmp_path / "ground"
    res = ground.run_ground_filter_tiles(hilly["folder"], str(out), "ground.vpc", method, "builtin",
                                         params=params, crop_polygons=crop_polygons, chunk_points=20_000)
    written = sorted(p for p in out.iterdir() if p.suffix == ".laz")
    input_names = sorted(os.path.basename(t) for t in hilly["tiles"])
    if crop:
        assert 0 < len(written) < len(input_names)
        assert any("no output tile" in w for w in res.warnings)
    else:
        assert [p.name for p in written] == input_names
    share = agreement(one, [str(p) for p in written])
    print(f"\n{method} {params} crop={crop}: {share * 100:.3f} % of the points classed as in one file")
    assert share >= MIN_AGREEMENT
    assert res.n_output == pc.read_header(one).point_count
    assert res.output_path == str(out / "ground.vpc")
    # the .vpc lists the written tiles and reads back as the same cloud
    vpc = cs.open_cloud(res.output_path)
    assert [t.path for t in vpc.tiles] == [str(p) for p in written]
    assert vpc.point_count == res.n_output and cs.same_crs(vpc.crs_wkt, cs.open_cloud(hilly["single"]).crs_wkt)


def test_tiles_read_once_with_the_spool_same_tiles_as_twice(hilly, tmp_path, monkeypatch):
    """OUTPUT_TILES: each tile's points are kept in a spool between the passes (one read of
    the tile for both), or read twice without room on the disk; the same tiles either way."""
    from roadsigns.core.ground import tiled

    reads = []
    original = cs.CloudSource.iter_indexed_chunks

    def counted(self, *args, **kwargs):
        reads.append(tuple(t.path for t in kwargs.get("tiles") or ()))
        return original(self, *args, **kwargs)

    monkeypatch.setattr(cs.CloudSource, "iter_indexed_chunks", counted)
    written = {}
    for room in (True, False):
        monkeypatch.setattr(tiled, "room_to_spool", lambda n, size, folder, room=room: room)
        reads.clear()
        out = tmp_path / f"ground-{room}"
        ground.run_ground_filter_tiles(hilly["folder"], str(out), "g.vpc", "csf", "builtin", chunk_points=20_000)
        per_tile = [r for r in reads if len(r) == 1]
        assert len(per_tile) == len(hilly["tiles"]) * (1 if room else 2)
        written[room] = sorted(p for p in out.iterdir() if p.suffix == ".laz")
        assert not [p for p in out.iterdir() if p.name.startswith(".roadsigns")]
    assert [p.name for p in written[True]] == [p.name for p in written[False]]
    for a, b in zip(written[True], written[False]):
        assert np.array_equal(laspy.read(a).points.array, laspy.read(b).points.array)


def test_tiles_keep_their_own_headers(hilly, tmp_path):
    folder = tmp_path / "mixed"
    split_into_tiles(hilly["single"], str(folder), size_m=40.0, scales=[0.01, 0.01, 0.01],
                     offsets_shift=np.array([10.0, 20.0, 0.0]))
    out = tmp_path / "ground"
    ground.run_ground_filter_tiles(str(folder), str(out), "g.vpc", "smrf", "auto")
    for tile in sorted(folder.iterdir()):
        a, b = pc.read_header(str(tile)), pc.read_header(str(out / tile.name))
        assert np.array_equal(a.scales, b.scales) and np.array_equal(a.offsets, b.offsets)
        assert a.point_count == b.point_count and a.point_format.id == b.point_format.id


def test_one_file_from_tiles_and_from_a_vpc(hilly, tmp_path):
    one = str(tmp_path / "one.laz")
    ground.run_ground_filter(hilly["single"], one, "csf", "builtin")
    merged = str(tmp_path / "merged.laz")
    res = ground.run_ground_filter(hilly["folder"], merged, "csf", "auto")
    assert res.engine == "builtin" and res.n_output == res.n_input == len(hilly["scene"])
    assert agreement(one, [merged]) >= MIN_AGREEMENT
    vpc = write_vpc(str(tmp_path / "tiles.vpc"), hilly["tiles"])
    via_vpc = str(tmp_path / "via_vpc.laz")
    ground.run_ground_filter(vpc, via_vpc, "csf", "builtin")
    assert agreement(one, [via_vpc]) >= MIN_AGREEMENT


def test_auto_classifies_tiles_with_the_builtin_engine_and_says_why(hilly, tmp_path):
    infos = []
    res = ground.run_ground_filter(hilly["folder"], str(tmp_path / "o.laz"), "smrf", "auto",
                                   progress=Progress(on_info=infos.append))
    assert res.engine == "builtin" and any("Auto: the built-in engine" in m for m in infos), infos


def test_tiles_fall_back_to_the_builtin_engine_when_pdal_fails_under_auto(hilly, tmp_path, monkeypatch):
    """With PDAL as Auto's engine for the method (AUTO_ENGINES), a PDAL failing on a tile is a
    warning and the built-in engine writes every tile; what PDAL wrote before is gone."""
    import stat
    import sys
    import textwrap

    exe = tmp_path / "pdal"
    exe.write_text(f"#!{sys.executable}\n" + textwrap.dedent("""
        import json, sys, laspy
        stages = json.load(sys.stdin)["pipeline"]
        if "tile_00_00" not in stages[0]["filename"]:
            sys.stderr.write("PDAL: refused this tile\\n")
            sys.exit(1)
        las = laspy.read(stages[0]["filename"])
        las.classification[:] = 2
        las.write(stages[-1]["filename"])
    """))
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setitem(ground.AUTO_ENGINES, "smrf", "pdal")
    builtin = tmp_path / "builtin"
    ground.run_ground_filter_tiles(hilly["folder"], str(builtin), "g.vpc", "smrf", "builtin")
    out = tmp_path / "auto"
    res = ground.run_ground_filter_tiles(hilly["folder"], str(out), "g.vpc", "smrf", "auto", pdal_executable=str(exe))
    assert res.engine == "builtin" and any("refused this tile" in w for w in res.warnings)
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in builtin.iterdir())
    for p in sorted(builtin.glob("*.laz")):
        assert agreement(str(p), [str(out / p.name)]) == 1.0


@pytest.fixture(scope="module")
def real_pdal():
    return realpdal.require()


def _dimension_names(path):
    return list(pc.read_header(path).point_format.dimension_names)


@pytest.mark.parametrize("method", ["csf", "smrf"])
def test_tiles_through_real_pdal(real_pdal, hilly, tmp_path, method):
    """ENGINE=pdal on tiles: each tile alone through PDAL with its neighbours' points around
    it (core/ground/pdal_tiles.py), into one file (the pdal application, from the folder) and
    one file per tile (the bindings, from a .vpc): the same points as the built-in engine on
    the whole cloud, the same ground on >= 99.5 % of them, and on >= 99.5 % of those PDAL
    gives the one file; both outputs classed alike; no trace of the halo's mark."""
    builtin = str(tmp_path / "builtin.laz")
    ground.run_ground_filter(hilly["single"], builtin, method, "builtin")
    pdal_one_file = str(tmp_path / "pdal-one-file.laz")
    ground.run_ground_filter(hilly["single"], pdal_one_file, method, "pdal", pdal_executable=real_pdal.executable)
    merged = str(tmp_path / "merged.laz")
    res = ground.run_ground_filter(hilly["folder"], merged, method, "pdal", pdal_executable=real_pdal.executable)
    assert res.engine == "pdal-cli" and res.n_output == res.n_input == len(hilly["scene"])
    vpc = write_vpc(str(tmp_path / "tiles.vpc"), hilly["tiles"])
    out = tmp_path / "ground"
    res_tiles = ground.run_ground_filter_tiles(vpc, str(out), "ground.vpc", method, "pdal")
    assert res_tiles.engine == "pdal-python" and res_tiles.n_output == len(hilly["scene"])
    written = sorted(str(p) for p in out.iterdir() if p.suffix == ".laz")
    assert [os.path.basename(p) for p in written] == sorted(os.path.basename(t) for t in hilly["tiles"])
    to_builtin, to_pdal = agreement(builtin, [merged]), agreement(pdal_one_file, [merged])
    print(f"\n{method} tiles through PDAL: {to_builtin * 100:.3f} % as the built-in engine, "
          f"{to_pdal * 100:.3f} % as PDAL on one file")
    assert to_builtin >= 0.995 and to_pdal >= 0.995
    assert agreement(merged, written) == 1.0
    assert res.n_ground == res_tiles.n_ground == int((laspy.read(merged).classification == 2).sum())
    for path in [merged, *written]:
        assert ground.pdal.HALO_DIM not in _dimension_names(path)
    assert [t.path for t in cs.open_cloud(res_tiles.output_path).tiles] == written
    assert not [p for p in tmp_path.rglob(".roadsigns*")]


def test_pdal_tiles_keep_their_own_headers(real_pdal, hilly, tmp_path):
    folder = tmp_path / "mixed"
    split_into_tiles(hilly["single"], str(folder), size_m=40.0, scales=[0.01, 0.01, 0.01],
                     offsets_shift=np.array([10.0, 20.0, 0.0]))
    out = tmp_path / "ground"
    res = ground.run_ground_filter_tiles(str(folder), str(out), "g.vpc", "smrf", "pdal")
    assert res.engine == "pdal-python"
    for tile in sorted(folder.iterdir()):
        a, b = pc.read_header(str(tile)), pc.read_header(str(out / tile.name))
        assert np.array_equal(a.scales, b.scales) and np.array_equal(a.offsets, b.offsets)
        assert a.point_count == b.point_count and a.point_format.id == b.point_format.id
        assert cs.same_crs(a.parse_crs().to_wkt(), b.parse_crs().to_wkt())


def test_pdal_failing_on_a_tile_names_it_and_writes_nothing(real_pdal, hilly, tmp_path):
    """PDAL refuses a tile whose return numbers are 0 for some points only: the error names
    that tile, and neither output nor temporary file is left (one file, and a folder of tiles)."""
    folder = tmp_path / "tiles"
    shutil.copytree(hilly["folder"], folder)
    bad = sorted(folder.iterdir())[2]
    las = laspy.read(str(bad))
    las.return_number[:10] = 0
    las.number_of_returns[:10] = 0
    las.write(str(bad))
    outputs = tmp_path / "outputs"
    outputs.mkdir()
    with pytest.raises(ground.PdalError, match="NumberOfReturns") as e:
        ground.run_ground_filter(str(folder), str(outputs / "g.laz"), "csf", "pdal",
                                 pdal_executable=real_pdal.executable)
    assert str(bad) in str(e.value)
    with pytest.raises(ground.PdalError, match="NumberOfReturns") as e:
        ground.run_ground_filter_tiles(str(folder), str(outputs / "g"), "g.vpc", "csf", "pdal")
    assert str(bad) in str(e.value)
    assert os.listdir(outputs) == []


def test_copc_through_real_pdal(real_pdal, hilly, tmp_path):
    """A COPC file goes through PDAL as one file (readers.las reads it whole); the output is a
    plain LAZ (no COPC records carried over) with the built-in engine's points and classes."""
    import pdal

    copc = str(tmp_path / "street.copc.laz")
    pdal.Pipeline(json.dumps({"pipeline": [hilly["single"], {"type": "writers.copc", "filename": copc}]})).execute()
    assert cs.open_cloud(copc).tiles[0].copc
    builtin, through_pdal = str(tmp_path / "builtin.laz"), str(tmp_path / "pdal.laz")
    ground.run_ground_filter(copc, builtin, "csf", "builtin")
    res = ground.run_ground_filter(copc, through_pdal, "csf", "pdal", pdal_executable=real_pdal.executable)
    assert res.engine == "pdal-cli" and res.n_output == len(hilly["scene"])
    assert agreement(builtin, [through_pdal]) >= 0.995
    assert not cs.is_copc(pc.read_header(through_pdal))


def test_cancelled_tiles_leave_nothing(hilly, tmp_path):
    calls = []

    def cancelled():
        calls.append(1)
        return len(calls) > 25  # after some tiles are written

    out = tmp_path / "ground"
    with pytest.raises(Cancelled):
        ground.run_ground_filter_tiles(hilly["folder"], str(out), "g.vpc", "smrf", "builtin", chunk_points=5000,
                                       progress=Progress(is_cancelled=cancelled))
    assert len(calls) > 25
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("as_tiles", [True, False])
def test_cancelled_pdal_tiles_leave_nothing(real_pdal, hilly, tmp_path, as_tiles):
    """Cancelled while the tiles go through the pdal application one by one: the running
    pdal is stopped, and neither output, spool nor temporary file is left."""
    seen = []

    def cancelled():
        seen.append(1)
        return len(seen) > 40  # after the halos are spooled and some tiles are done
    out = tmp_path / "out"
    out.mkdir()
    before = realpdal.orphaned_pdal()
    with pytest.raises(Cancelled):
        if as_tiles:
            ground.run_ground_filter_tiles(hilly["folder"], str(out / "ground"), "g.vpc", "csf", "pdal",
                                           chunk_points=5000, pdal_executable=real_pdal.executable,
                                           progress=Progress(is_cancelled=cancelled))
        else:
            ground.run_ground_filter(hilly["folder"], str(out / "ground.laz"), "csf", "pdal", chunk_points=5000,
                                     pdal_executable=real_pdal.executable, progress=Progress(is_cancelled=cancelled))
    assert len(seen) > 40
    assert list(out.iterdir()) == []
    assert realpdal.orphaned_pdal() - before == set()


def test_output_folder_replaced_whole_but_never_the_input(hilly, tmp_path):
    out = tmp_path / "ground"
    out.mkdir()
    (out / "old.laz").write_text("an earlier run")
    ground.run_ground_filter_tiles(hilly["folder"], str(out), "g.vpc", "smrf", "builtin")
    assert not (out / "old.laz").exists() and (out / "g.vpc").exists()
    inside = tmp_path / "tiles"
    shutil.copytree(hilly["folder"], inside)
    with pytest.raises(InputError, match="holds the input tile"):
        ground.run_ground_filter_tiles(str(inside), str(tmp_path), "g.vpc", "smrf", "builtin")
    assert sorted(os.listdir(inside)) == sorted(os.path.basename(t) for t in hilly["tiles"])


def test_tiles_of_the_same_name_are_refused(hilly, tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    shutil.copy(hilly["tiles"][0], a / "t.laz")
    shutil.copy(hilly["tiles"][1], b / "t.laz")
    vpc = write_vpc(str(tmp_path / "two.vpc"), [str(a / "t.laz"), str(b / "t.laz")])
    with pytest.raises(InputError, match="same file name"):
        ground.run_ground_filter_tiles(vpc, str(tmp_path / "out"), "o.vpc", "smrf", "builtin")


def test_written_vpc_is_what_qgis_reads(hilly, tmp_path):
    """The members QGIS's and pdal_wrench's VPC readers use (vpc.cpp read(): type, features,
    stac_version 1.0.0, assets, properties with pc:count, proj:wkt2, proj:bbox, proj:geometry)."""
    ground.run_ground_filter_tiles(hilly["folder"], str(tmp_path / "g"), "g.vpc", "smrf", "builtin")
    data = json.loads((tmp_path / "g" / "g.vpc").read_text())
    assert data["type"] == "FeatureCollection" and len(data["features"]) == len(hilly["tiles"])
    for feature in data["features"]:
        assert feature["type"] == "Feature" and feature["stac_version"] == "1.0.0"
        props = feature["properties"]
        assert {"pc:count", "proj:wkt2", "proj:bbox", "proj:geometry", "pc:schemas", "datetime"} <= set(props)
        href = feature["assets"]["data"]["href"]
        assert href.startswith("./") and (tmp_path / "g" / href[2:]).exists()
        assert props["pc:count"] == pc.read_header(str(tmp_path / "g" / href[2:])).point_count
