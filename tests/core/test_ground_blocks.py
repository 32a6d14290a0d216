"""The built-in ground filter block by block (core/ground/blocks.py): a cloud larger than a block
is read once and classified one block at a time, each block's grid over the block and its
halo only, and its points get the classes of one grid over the whole cloud."""
import os

import laspy
import numpy as np
import pytest
from helpers.cloudtiles import classes_by_point, hilly_street, same_classes_cases, street_crop

from roadsigns.core import cloudsource as cs
from roadsigns.core import ground
from roadsigns.core.errors import Cancelled, InputError, Progress
from roadsigns.core.ground import blocks, lattice

#: Blocks smaller than the 120 m street, so that it is cut into several (BLOCK_M is 512 m).
SMALL_BLOCK_M = 40.0


@pytest.fixture(scope="module")
def hilly(tmp_path_factory):
    """A 120 m street on a 3 % slope: one LAZ, and the same as 25 m tiles."""
    return hilly_street(tmp_path_factory.mktemp("hilly-blocks"))


def by_point(path):
    """The points of ``path`` sorted by their coordinates (mm): ``(keys, classes)``."""
    return classes_by_point([path])


@pytest.mark.parametrize("method, params, crop", same_classes_cases())
def test_blocks_give_the_classes_of_one_grid(hilly, tmp_path, method, params, crop):
    crop_polygons = street_crop(hilly["single"]) if crop else None
    one, cut = str(tmp_path / "one.laz"), str(tmp_path / "blocks.laz")
    whole = ground.run_ground_filter(hilly["single"], one, method, "builtin", params=params,
                                     crop_polygons=crop_polygons, block_m=None)
    by_blocks = ground.run_ground_filter(hilly["single"], cut, method, "builtin", params=params,
                                         crop_polygons=crop_polygons, block_m=SMALL_BLOCK_M, chunk_points=20_000)
    k1, c1 = by_point(one)
    k2, c2 = by_point(cut)
    np.testing.assert_array_equal(k1, k2)      # the same points
    np.testing.assert_array_equal(c1, c2)      # with the same classes, every one
    assert (by_blocks.n_output, by_blocks.n_ground) == (whole.n_output, whole.n_ground)
    assert 0 < whole.n_ground < whole.n_output
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".roadsigns")]


def test_no_grid_spans_more_than_a_block_and_its_halo(hilly, tmp_path, monkeypatch):
    """What the memory follows: every grid built covers one block and its halo, never the
    cloud (CSF squares of 8 m with buffers of 4 m, so that a 40 m block's halo is small
    beside the 120 m street), and the classes are still those of one grid."""
    built = []
    original = blocks.make_grid

    def recorded(params, bounds_xy, *args, **kwargs):
        grid = original(params, bounds_xy, *args, **kwargs)
        built.append(grid.lattice)
        return grid

    monkeypatch.setattr(blocks, "make_grid", recorded)
    sizes = dict(tile_size_m=8.0, tile_buffer_m=4.0)
    one, cut = str(tmp_path / "one.laz"), str(tmp_path / "blocks.laz")
    ground.classify_ground(hilly["single"], one, "csf", "builtin", block_m=None, **sizes)
    assert not built
    ground.classify_ground(hilly["single"], cut, "csf", "builtin", block_m=SMALL_BLOCK_M, **sizes)
    x0, y0, x1, y1 = cs.open_cloud(hilly["single"]).bounds_xy
    assert len(built) >= 3                     # the 120 m street in blocks of 40 m
    for lat in built:                          # a block, a square on each side, its buffer, the padding
        assert max(lat.nx, lat.ny) * lat.step <= SMALL_BLOCK_M + 2 * (8.0 + 8.0) + 8 * lat.step
    assert max(lat.nx * lat.step for lat in built) < 0.6 * (x1 - x0)
    k1, c1 = by_point(one)
    k2, c2 = by_point(cut)
    np.testing.assert_array_equal(k1, k2)
    np.testing.assert_array_equal(c1, c2)


def test_blocks_read_the_cloud_once(hilly, tmp_path, monkeypatch):
    reads = []
    original = cs.CloudSource.iter_indexed_chunks

    def counted(self, *args, **kwargs):
        reads.append(1)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(cs.CloudSource, "iter_indexed_chunks", counted)
    ground.run_ground_filter(hilly["folder"], str(tmp_path / "g.laz"), "csf", "builtin", block_m=SMALL_BLOCK_M)
    assert len(reads) == 1


def test_blocks_from_tiles_match_one_file(hilly, tmp_path):
    """A folder of tiles (whose edges are not the blocks') gives the classes of the file."""
    one, cut = str(tmp_path / "one.laz"), str(tmp_path / "blocks.laz")
    ground.run_ground_filter(hilly["single"], one, "csf", "builtin", block_m=None)
    ground.run_ground_filter(hilly["folder"], cut, "csf", "builtin", block_m=SMALL_BLOCK_M, chunk_points=7_000)
    k1, c1 = by_point(one)
    k2, c2 = by_point(cut)
    np.testing.assert_array_equal(k1, k2)
    np.testing.assert_array_equal(c1, c2)


def test_small_clouds_keep_their_point_order(hilly, tmp_path):
    """A cloud within one block is classified in one grid and written in its own order."""
    out = str(tmp_path / "g.laz")
    ground.run_ground_filter(hilly["single"], out, "csf", "builtin")     # the default block: BLOCK_M
    a, b = laspy.read(hilly["single"]), laspy.read(out)
    np.testing.assert_array_equal(np.asarray(a.X), np.asarray(b.X))
    np.testing.assert_array_equal(np.asarray(a.Y), np.asarray(b.Y))


def test_blocks_say_which_block_they_are_on(hilly, tmp_path):
    steps = []
    ground.run_ground_filter(hilly["single"], str(tmp_path / "g.laz"), "csf", "builtin", block_m=SMALL_BLOCK_M,
                             progress=Progress(on_step=steps.append))
    on_blocks = [s for s in steps if s.template.startswith("Classifying the ground block by block")]
    assert len(on_blocks) >= 4
    assert [s.fields["n"] for s in on_blocks] == list(range(1, len(on_blocks) + 1))
    assert on_blocks[-1].fields["n"] == on_blocks[-1].fields["count"]
    assert steps[0].template.startswith("Reading")


@pytest.mark.parametrize("cancel_after", [3, 150])   # in the reading (71 checks); in the blocks
def test_cancelled_blocks_leave_nothing(hilly, tmp_path, cancel_after):
    calls = []

    def cancelled():
        calls.append(1)
        return len(calls) > cancel_after

    out = tmp_path / "g.laz"
    with pytest.raises(Cancelled):
        ground.run_ground_filter(hilly["single"], str(out), "csf", "builtin", block_m=SMALL_BLOCK_M,
                                 chunk_points=5_000, progress=Progress(is_cancelled=cancelled))
    assert not out.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".roadsigns")]


def test_points_outside_the_header_bounds_are_a_corrupt_file(hilly, tmp_path):
    """A header whose bounds leave points out: the file is named as corrupt, nothing written."""
    bad = str(tmp_path / "bad.las")
    las = laspy.read(hilly["single"])
    las.update_header()
    las.write(bad)
    with open(bad, "r+b") as f:       # max X (LAS 1.2 public header) 30 m short of the points
        f.seek(179)
        max_x = np.frombuffer(f.read(8), "<f8")[0]
        f.seek(179)
        f.write(np.array([max_x - 30.0], "<f8").tobytes())
    out = tmp_path / "g.laz"
    with pytest.raises(InputError, match="corrupt") as e:
        ground.run_ground_filter(bad, str(out), "csf", "builtin", block_m=SMALL_BLOCK_M)
    assert e.value.fields["path"] == os.path.abspath(bad)
    assert not out.exists()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".roadsigns")]


def test_block_keys_and_neighbours():
    plan = blocks.BlockPlan(ground.CsfParams(), (1000.0, 2000.0, 2100.0, 2600.0), 512.0)
    assert (plan.ni, plan.nj) == (4, 3) and plan.n_blocks == 12
    codes = plan.keys_of(np.array([1000.0, 1535.9, 1536.0, 2100.0]), np.array([2000.0, 2047.9, 2048.0, 2600.0]))
    assert [plan.key_of_code(c) for c in codes] == [(1, 3), (2, 3), (3, 4), (4, 5)]
    assert plan.box((2, 3)) == (1024.0, 1536.0, 1536.0, 2048.0)
    assert plan.reach == 1 and len(plan.neighbours((2, 3))) == 8
    # a block's grid covers the block and reaches no further than its neighbours
    gb = plan.grid_bounds((2, 3))
    box = plan.box((2, 3))
    assert gb[0] <= box[0] and gb[2] >= box[2] and gb[3] >= box[3]
    assert box[0] - gb[0] < 512.0 and gb[2] - box[2] < 512.0
    # a point far outside the bounds goes to the ring around the blocks, whose grid is None
    far = plan.key_of_code(plan.keys_of(np.array([9000.0]), np.array([2100.0]))[0])
    assert far == (5, 4) and plan.grid_bounds(far) is None


def test_lattice_points_on_nodes_and_in_cells():
    lat = lattice.Lattice(0.0, 0.0, 1.0, 4, 3)
    x = np.array([-0.6, -0.4, 3.4, 3.6, 0.0])
    y = np.array([0.0, 0.0, 0.0, 0.0, 2.6])
    assert lattice.on_lattice(lat, x, y, nodes=True).tolist() == [False, True, True, False, False]
    assert lattice.on_lattice(lat, x, y, nodes=False).tolist() == [False, False, True, True, True]


def test_merging_many_chunks_at_once_is_merging_them_one_by_one():
    """Pass 2 merges a block's candidates as the spool gives them back, several chunks at a
    time: the grid is the one that takes the chunks one by one, the first of equally near
    points kept (the same point twice, in two chunks, at two heights: the first height)."""
    rng = np.random.default_rng(3)
    chunks = []
    for k in range(4):
        xy = rng.uniform(0.0, 30.0, (3000, 2))
        z = rng.normal(0.0, 0.05, 3000) + k
        chunks.append((xy[:, 0], xy[:, 1], z))
    twin = (chunks[0][0][:50], chunks[0][1][:50], chunks[0][2][:50] + 7.0)   # exactly as near, later
    chunks.append(twin)
    bounds = (0.0, 0.0, 30.0, 30.0)
    for params in (ground.CsfParams(), ground.SmrfParams()):
        one_by_one = ground.make_grid(params, bounds, -1.0)
        at_once = ground.make_grid(params, bounds, -1.0)
        found = []
        for x, y, z in chunks:
            one_by_one.accumulate(x, y, z)
            found.append(blocks.candidates(params, at_once.lattice, x, y, z, -1.0))
        merged = np.concatenate(found)
        assert len(np.unique(merged[merged.dtype.names[0]])) < len(merged)     # nodes met in several chunks
        at_once.merge(merged)
        if isinstance(params, ground.CsfParams):
            for name in ("rep_du", "rep_dv", "rep_z"):
                np.testing.assert_array_equal(getattr(at_once, name).dense(), getattr(one_by_one, name).dense())
            assert np.nanmax(one_by_one.rep_z.dense()) < 6.0     # the later twins, 7 m up, were not kept
        else:
            np.testing.assert_array_equal(at_once.zmin, one_by_one.zmin)


def test_blocks_of_a_cloud_too_large_for_one_grid():
    """A 9 km drive at the algorithm's 0.5 m cloth: one grid over its bounding box would need
    more cells than one grid may have, a block's grid does not (nor a tile's)."""
    params = ground.CsfParams(resolution=0.5, threshold=0.2)
    whole = (500_000.0, 5_400_000.0, 508_100.0, 5_402_938.0)           # 8.1 km x 2.9 km: 95 M cells
    with pytest.raises(InputError, match="grid cells"):
        lattice.Lattice.covering(whole, 0.5)
    plan = blocks.BlockPlan(params, whole)
    key = plan.key_of_code(plan.keys_of(np.array([504_000.0]), np.array([5_401_000.0]))[0])
    lat = plan.lattice(key)
    assert lat is not None and lat.nx * lat.ny < 2_000 * 2_000
    box = plan.box(key)
    assert lat.x0 <= box[0] and lat.x0 + lat.nx * lat.step >= box[2]


def test_blocks_write_the_same_file_with_one_thread_or_two(hilly, tmp_path, monkeypatch):
    outputs = []
    for threads in (1, 2):
        monkeypatch.setattr(blocks, "CHUNK_THREADS", threads)
        out = str(tmp_path / f"g{threads}.laz")
        ground.run_ground_filter(hilly["single"], out, "csf", "builtin", block_m=SMALL_BLOCK_M, chunk_points=7_000)
        outputs.append(laspy.read(out).points.array)
    assert len(outputs[0]) == len(laspy.read(hilly["single"]).points)
    assert np.array_equal(outputs[0], outputs[1])
