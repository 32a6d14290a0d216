"""The built-in engine block by block: a cloud larger than a block is classified one block at a
time, so the memory follows a block and not the drive.

Conventions:

* Blocks are squares of ``block_m`` metres (:data:`BLOCK_M`) on a grid whose origin is a
  multiple of ``block_m`` (world-aligned); a point belongs to the block whose half-open box
  ``[x0, x0 + block_m) x [y0, y0 + block_m)`` holds it.
* A block's ground grid covers its box as a tile's does (:func:`.gridsteps.tile_grid`): whole
  squares of the whole-cloud run's CSF tiling with their buffers, or SMRF's halo, so that
  its points get the classes a run over the whole cloud gives them.
* Pass 1 reads the cloud once (cropped, in a pool of :data:`~.gridsteps.CHUNK_THREADS`): each
  point is spooled to its block's file, uncompressed, with the output's scales and offsets;
  each chunk's eligible returns are reduced, on the grid of every block they fall on, to what
  that grid keeps of them (CSF: the nearest point per cloth node, :func:`.csf.node_candidates`;
  SMRF: the lowest per cell, :func:`.smrf.cell_candidates`), spooled to that block's file of
  candidates. No grid is held: the candidates are a few per cent of the points.
* Pass 2, block by block in the order the reading first met them: the block's candidates
  merged into its grid in reading order (as one grid over the whole cloud takes the chunks);
  the grid's surface where the block's points need it; the block's points classified and
  written; its files deleted. The output's points are grouped by block.
* Blocks are numbered from 0 in that order; files are per block number.
"""
from __future__ import annotations

import math
from typing import Any, Callable, Dict, Iterator, List, Optional, Tuple

import numpy as np

from ..cloudsource import BBoxXY, conform
from ..drivewindows import Spool, map_in_order
from ..errors import SILENT, Progress
from ..pointcloud import CloudWriter, CropRegion
from .csf import NODE_CANDIDATE_DTYPE, CsfParams, node_candidates
from .gridsteps import (
    CHUNK_THREADS,
    classified,
    cropped,
    csf_square_nodes,
    halo_m,
    make_grid,
    returns_mask,
    tile_grid,
)
from .lattice import BLOCK_M, MAX_PAGED_CELLS, BoundsXY, Lattice, OutsideGridError, Window, on_lattice
from .params import Params, grid_step_m
from .smrf import CELL_CANDIDATE_DTYPE, cell_candidates

#: A block's points need the ground surface this many grid steps around the block (a point's
#: cell corners, one node; the squares whose ring may fill such a node in, one more).
NEEDED_STEPS = 2.0

#: Eligible returns reduced to candidates at a time in pass 1 (the rest of a chunk waits).
CANDIDATE_POINTS = 262_144

_POINTS, _REPS = "points", "candidates"

BlockKey = Tuple[int, int]


def grid_reach_m(params: Params, tile_size_m: Optional[float] = None,
                 tile_buffer_m: Optional[float] = None) -> float:
    """At most how far (metres) :func:`.gridsteps.tile_grid` reaches beyond the box it is given, grown
    by :data:`NEEDED_STEPS`: for CSF, the square the box's edge falls in and the squares of its
    buffer; for SMRF, its halo; and the lattice's padding."""
    step = grid_step_m(params)
    halo = halo_m(params, tile_buffer_m)
    if isinstance(params, CsfParams):
        square_m = csf_square_nodes(params, tile_size_m, tile_buffer_m)[0] * step
        halo = square_m * (1 + math.ceil(halo / square_m))
    return halo + (NEEDED_STEPS + 3.0) * step


class BlockPlan:
    """The blocks of a cloud whose whole-cloud grid covers ``whole`` (its bounds within the
    crop), with CSF squares of ``tile_size_m`` and buffers of ``tile_buffer_m`` (default: the
    method's): which block holds a point, and each block's grid bounds."""

    def __init__(self, params: Params, whole: BoundsXY, block_m: float = BLOCK_M,
                 tile_size_m: Optional[float] = None, tile_buffer_m: Optional[float] = None):
        self.params = params
        self.whole = whole
        self.block_m = float(block_m)
        self.tile_size_m, self.tile_buffer_m = tile_size_m, tile_buffer_m
        self.i0 = int(math.floor(whole[0] / self.block_m))
        self.j0 = int(math.floor(whole[1] / self.block_m))
        self.ni = int(math.floor(whole[2] / self.block_m)) - self.i0 + 1
        self.nj = int(math.floor(whole[3] / self.block_m)) - self.j0 + 1
        self._grids: Dict[BlockKey, Optional[BBoxXY]] = {}
        self._lattices: Dict[BlockKey, Optional[Lattice]] = {}
        #: how far (metres) a block's grid may reach beyond the block, and in blocks (1: its
        #: eight neighbours)
        self.reach_m = grid_reach_m(params, tile_size_m, tile_buffer_m)
        self.reach = max(1, int(math.ceil(self.reach_m / self.block_m)))

    @property
    def n_blocks(self) -> int:
        """Blocks of the grid over ``whole`` (most hold no point of a drive)."""
        return self.ni * self.nj

    def box(self, key: BlockKey) -> BBoxXY:
        i, j = key
        b = self.block_m
        return (i * b, j * b, (i + 1) * b, (j + 1) * b)

    def grid_bounds(self, key: BlockKey) -> Optional[BBoxXY]:
        """The bounds of block ``key``'s grid (:func:`.gridsteps.tile_grid`); None when the block is
        outside ``whole``."""
        if key not in self._grids:
            step = grid_step_m(self.params)   # the squares of the needed window are whole squares of the grid
            box = self.box(key)
            grown = (box[0] - NEEDED_STEPS * step, box[1] - NEEDED_STEPS * step,
                     box[2] + NEEDED_STEPS * step, box[3] + NEEDED_STEPS * step)
            self._grids[key] = tile_grid(self.params, self.whole, grown, self.tile_buffer_m, self.tile_size_m)
        return self._grids[key]

    def needed_window(self, lattice: Lattice, key: BlockKey) -> Window:
        """The nodes or cells of ``lattice`` (block ``key``'s grid) whose surface its points
        need: the block grown by :data:`NEEDED_STEPS` grid steps (a point's cell corners, and
        the squares that fill in a cloth node that no square of its own holds)."""
        x0, y0, x1, y1 = self.box(key)
        grow = NEEDED_STEPS * lattice.step
        u0, v0 = lattice.local(x0 - grow, y0 - grow)
        u1, v1 = lattice.local(x1 + grow, y1 + grow)
        rows = slice(max(int(np.floor(v0)), 0), min(int(np.ceil(v1)) + 1, lattice.ny))
        cols = slice(max(int(np.floor(u0)), 0), min(int(np.ceil(u1)) + 1, lattice.nx))
        return rows, cols

    def lattice(self, key: BlockKey) -> Optional[Lattice]:
        """The lattice of block ``key``'s grid (as :func:`.gridsteps.make_grid` builds it over
        :meth:`grid_bounds`); None when the block is outside ``whole``."""
        if key not in self._lattices:
            bounds = self.grid_bounds(key)
            self._lattices[key] = None if bounds is None else Lattice.covering(
                bounds, grid_step_m(self.params), max_cells=MAX_PAGED_CELLS)
        return self._lattices[key]

    def code_of(self, key: BlockKey) -> int:
        """The code :meth:`keys_of` gives the points of block ``key``."""
        return (key[0] - self.i0 + 1) * (self.nj + 2) + (key[1] - self.j0 + 1)

    def keys_of(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Each point's block as one int64 code (:meth:`key_of_code` gives the key back)."""
        i = np.floor(np.asarray(x, dtype=np.float64) / self.block_m).astype(np.int64) - self.i0
        j = np.floor(np.asarray(y, dtype=np.float64) / self.block_m).astype(np.int64) - self.j0
        # points outside the blocks over ``whole`` (a header with wrong bounds) go to the ring of
        # blocks around them, which pass 2 refuses (OutsideGridError), as the whole-cloud grid does
        np.clip(i, -1, self.ni, out=i)
        np.clip(j, -1, self.nj, out=j)
        return (i + 1) * (self.nj + 2) + (j + 1)

    def key_of_code(self, code: int) -> BlockKey:
        i, j = divmod(int(code), self.nj + 2)
        return i - 1 + self.i0, j - 1 + self.j0

    def neighbours(self, key: BlockKey) -> List[BlockKey]:
        """The blocks whose grids may reach into block ``key`` (itself not included)."""
        r = self.reach
        return [(key[0] + di, key[1] + dj) for di in range(-r, r + 1) for dj in range(-r, r + 1) if di or dj]


class _Blocks:
    """Block numbers in the order pass 1 met them, and how many points each holds."""

    def __init__(self) -> None:
        self.number: Dict[BlockKey, int] = {}
        self.keys: List[BlockKey] = []
        self.points: List[int] = []

    def of(self, key: BlockKey) -> int:
        if key not in self.number:
            self.number[key] = len(self.keys)
            self.keys.append(key)
            self.points.append(0)
        return self.number[key]


def candidates(params: Params, lattice: Lattice, x: np.ndarray, y: np.ndarray, z: np.ndarray,
               z_ref: float) -> np.ndarray:
    """What the method's grid over ``lattice`` keeps of the points (:func:`.csf.node_candidates`,
    :func:`.smrf.cell_candidates`)."""
    if isinstance(params, CsfParams):
        return node_candidates(lattice, x, y, z, z_ref)
    return cell_candidates(lattice, x, y, z)


def classify_by_blocks(read: Callable[[Progress], Iterator[Any]], plan: BlockPlan, params: Params,
                       z_ref: float, reset_classes: bool, writer: CloudWriter, spool_folder: str,
                       chunk_points: int, region: Optional[CropRegion] = None,
                       progress: Progress = SILENT, threads: Optional[int] = None) -> Tuple[int, int]:
    """The built-in engine block by block (the module doc) into ``writer``: ``(eligible
    points, ground points)``.

    ``read(progress)`` yields the cloud's chunks (laspy records), cropped here to ``region``;
    the spool lives in a hidden temporary folder inside ``spool_folder``. :class:`~.lattice.
    OutsideGridError` when a point lies outside the cloud's bounds."""
    import laspy

    threads = CHUNK_THREADS if threads is None else threads
    header = writer.header
    nodes = isinstance(params, CsfParams)
    blocks = _Blocks()

    def records(part: np.ndarray) -> Any:
        return laspy.ScaleAwarePointRecord(part, header.point_format, header.scales, header.offsets)

    def split(chunk: Any) -> Tuple[List[Tuple[BlockKey, np.ndarray]], List[Tuple[BlockKey, np.ndarray]], int]:
        """A chunk cropped and conformed: its rows cut by block (a chunk of one block: its rows
        uncopied), the candidates of its eligible returns per block grid they fall on, and
        how many returns are eligible."""
        pts = cropped(chunk, region)
        if not len(pts):
            return [], [], 0
        eligible = returns_mask(pts.return_number, pts.number_of_returns, params.returns)
        # the coordinates as one grid over the whole cloud takes them: with the tile's own
        # scales and offsets (the rows are spooled with the output's)
        x, y = np.asarray(pts.x), np.asarray(pts.y)
        codes = plan.keys_of(x, y)
        one_block = codes.min() == codes.max()
        order = None if one_block else np.argsort(codes, kind="stable")   # the rows by block
        by_block = codes if order is None else codes[order]
        starts = np.flatnonzero(np.r_[True, by_block[1:] != by_block[:-1], True])
        owners = [plan.key_of_code(c) for c in by_block[starts[:-1]]]
        reps = []
        z = np.asarray(pts.z)
        if eligible.all():
            xe, ye, ze, codes_e = x, y, z, codes
        else:
            xe, ye, ze, codes_e = x[eligible], y[eligible], z[eligible], codes[eligible]
        rows = conform(pts, header).array
        del pts, z
        for a in range(0, len(xe), CANDIDATE_POINTS):    # in slices: two chunks are split at once
            b = a + CANDIDATE_POINTS
            reps.extend(block_candidates(owners, one_block, xe[a:b], ye[a:b], ze[a:b], codes_e[a:b]))
        n_eligible = len(xe)
        del x, y, xe, ye, ze, codes_e
        if order is not None:
            rows = rows[order]
        pieces = [(key, rows[a:b]) for key, a, b in zip(owners, starts[:-1], starts[1:])]
        return pieces, reps, n_eligible

    def block_candidates(owners: List[BlockKey], one_block: bool, x: np.ndarray, y: np.ndarray, z: np.ndarray,
                         codes: np.ndarray) -> List[Tuple[BlockKey, np.ndarray]]:
        """The candidates of eligible returns ``(x, y, z)`` (of blocks ``codes``) on every block
        grid they fall on: their own blocks' and the neighbours' that reach them."""
        if not len(x):
            return []
        out = []
        if one_block:     # most chunks: all on their block's grid (node_candidates refuses any off it)
            lat = plan.lattice(owners[0])
            if lat is None:   # points outside the header's bounds
                raise OutsideGridError("points outside the bounds in the file header")
            out.append((owners[0], candidates(params, lat, x, y, z, z_ref)))
            # the neighbours' grids reach only the points near the block's edges
            x0, y0, x1, y1 = plan.box(owners[0])
            near = np.flatnonzero((x < x0 + plan.reach_m) | (x >= x1 - plan.reach_m)
                                  | (y < y0 + plan.reach_m) | (y >= y1 - plan.reach_m))
            x, y, z = x[near], y[near], z[near]
            if not len(x):
                return out
        box = (x.min(), y.min(), x.max(), y.max())
        reached = set() if one_block else set(owners)
        for key in owners:
            for other in plan.neighbours(key):
                lat = plan.lattice(other)
                if lat is not None and lat.x0 - lat.step <= box[2] and lat.x0 + lat.nx * lat.step >= box[0] \
                        and lat.y0 - lat.step <= box[3] and lat.y0 + lat.ny * lat.step >= box[1]:
                    reached.add(other)
        for key in sorted(reached):
            lat = plan.lattice(key)
            if lat is None:
                if key in owners:     # points outside the header's bounds
                    raise OutsideGridError("points outside the bounds in the file header")
                continue
            on = on_lattice(lat, x, y, nodes)
            if key in owners and not on[codes == plan.code_of(key)].all():
                raise OutsideGridError("points outside the bounds in the file header")
            if on.any():
                out.append((key, candidates(params, lat, x[on], y[on], z[on], z_ref)))
        return out

    rep_dtype = NODE_CANDIDATE_DTYPE if nodes else CELL_CANDIDATE_DTYPE
    n_eligible = n_ground = 0
    with Spool({_POINTS: header.point_format.dtype(), _REPS: rep_dtype}, folder=spool_folder,
               prefix=".roadsigns-ground-blocks-", background=True) as spool:
        reading = progress.sub(0.0, 0.45)
        for pieces, reps, n_e in map_in_order(split, read(reading), threads, reading.check):
            n_eligible += n_e
            for key, rows in pieces:
                k = blocks.of(key)
                spool.append(_POINTS, k, rows)
                blocks.points[k] += len(rows)
            for key, found in reps:
                spool.append(_REPS, blocks.of(key), found)
            del pieces, reps

        todo = [k for k in range(len(blocks.keys)) if blocks.points[k]]
        total = max(sum(blocks.points[k] for k in todo), 1)
        done = 0
        for n, k in enumerate(todo):
            key = blocks.keys[k]
            share = progress.sub(0.45 + 0.55 * done / total, 0.45 + 0.55 * (done + blocks.points[k]) / total)
            share.step("Classifying the ground block by block: block {n} of {count}", n=n + 1, count=len(todo))
            bounds = plan.grid_bounds(key)
            if bounds is None:  # never: split refused the points of such a block
                raise OutsideGridError("points outside the bounds in the file header")
            grid = make_grid(params, bounds, z_ref, plan.tile_size_m, plan.tile_buffer_m)
            if grid.lattice != plan.lattice(key):
                raise RuntimeError("a block's grid is not on the lattice its candidates were found on")
            for part in spool.read_parts(_REPS, k, chunk_points):
                share.check()
                grid.merge(part)
            grid.finish(share.sub(0.0, 0.3), only=plan.needed_window(grid.lattice, key))
            writing = share.sub(0.3, 1.0)

            def classify(part: np.ndarray, grid: Any = grid) -> Tuple[Any, int]:
                return classified(records(part), grid, params, reset_classes)

            for pts, n_g in map_in_order(classify, spool.read_parts(_POINTS, k, chunk_points), threads,
                                         writing.check):
                writer.write(pts)
                n_ground += n_g
                del pts
            spool.discard(_POINTS, k)
            spool.discard(_REPS, k)
            del grid
            done += blocks.points[k]
            writing.report(1.0)
    return n_eligible, n_ground
