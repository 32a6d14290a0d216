"""The steps the built-in engine's runs share, over one grid, tiles (:mod:`.tiled`) or blocks
(:mod:`.blocks`): a method's grid, the returns it classifies, a chunk cropped and classified,
and the bounds of a tile's or a block's grid.

Conventions: as :mod:`.engine`'s. A tile's or block's grid is cut from the lattice of the
whole cloud's grid (:func:`tile_grid`), so its points get the classes a whole-cloud run gives.
"""
from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np
from numpy.typing import ArrayLike

from ..cloudsource import BBoxXY
from ..drivewindows import BLOCK_THREADS
from ..errors import InputError
from ..pointcloud import GROUND_CLASS, UNCLASSIFIED_CLASS, CropRegion
from .csf import CSF_BUFFER_M, CSF_TILE_M, CsfGrid, CsfParams
from .lattice import MAX_PAGED_CELLS, BoundsXY, GroundGrid, Lattice
from .params import Params
from .smrf import SMRF_TILE_M, SmrfGrid


def returns_mask(return_number: ArrayLike, number_of_returns: ArrayLike,
                 returns: str = "last,only") -> np.ndarray:
    """Points of the given return types (PDAL's ``returns``: first, last, intermediate, only).

    Points whose return numbers are 0 (not recorded) are always selected.
    """
    rn = np.asarray(return_number).astype(np.int16)
    nr = np.asarray(number_of_returns).astype(np.int16)
    kinds = {k.strip() for k in returns.split(",") if k.strip()}
    unknown = kinds - {"first", "last", "intermediate", "only"}
    if unknown:
        raise InputError("Unknown return type {kinds} in '{returns}'",
                         kinds=", ".join(sorted(unknown)), returns=returns)
    selected = (rn == 0) | (nr == 0)
    if "only" in kinds:
        selected |= nr == 1
    if "first" in kinds:
        selected |= (rn == 1) & (nr > 1)
    if "last" in kinds:
        selected |= (rn == nr) & (nr > 1)
    if "intermediate" in kinds:
        selected |= (rn > 1) & (rn < nr)
    return selected


def make_grid(params: Params, bounds_xy: BoundsXY, z_ref: float,
              tile_size_m: Optional[float] = None,
              tile_buffer_m: Optional[float] = None) -> GroundGrid:
    """The built-in grid of the method ``params`` belong to, over ``bounds_xy``; tiles of
    ``tile_size_m`` (default per method) and, for CSF, a buffer of ``tile_buffer_m``."""
    if isinstance(params, CsfParams):
        return CsfGrid(bounds_xy, z_ref, params,
                       tile_size_m=tile_size_m or CSF_TILE_M,
                       tile_buffer_m=CSF_BUFFER_M if tile_buffer_m is None else tile_buffer_m)
    # SMRF's buffer follows from its window (exact results across tiles)
    return SmrfGrid(bounds_xy, params, tile_size_m=tile_size_m or SMRF_TILE_M)


def _new_classes(classification: np.ndarray, eligible: np.ndarray, ground: np.ndarray,
                 reset_classes: bool) -> np.ndarray:
    cls = np.array(classification, dtype=np.uint8, copy=True)
    if reset_classes:
        cls[:] = UNCLASSIFIED_CLASS
    else:
        cls[eligible & ~ground & (cls == GROUND_CLASS)] = UNCLASSIFIED_CLASS
    cls[ground] = GROUND_CLASS
    return cls


def eligible_xyz(pts: Any, params: Params) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The returns the method classifies (a mask) and their coordinates ``x, y, z``
    (contiguous float64 arrays; the chunk's own when every point is eligible)."""
    eligible = returns_mask(pts.return_number, pts.number_of_returns, params.returns)
    coords = (np.asarray(pts.x), np.asarray(pts.y), np.asarray(pts.z))
    if eligible.all():
        return (eligible, *coords)
    x, y, z = (c[eligible] for c in coords)
    return eligible, x, y, z


def classified(pts: Any, grid: GroundGrid, params: Params, reset_classes: bool,
               classify: bool = True) -> Tuple[Any, int]:
    """``pts`` with their new classes (ground from ``grid``), and their number of ground points."""
    eligible, x, y, z = eligible_xyz(pts, params)
    ground = np.zeros(len(pts), dtype=bool)
    if classify and len(x):
        ground[eligible] = grid.classify(x, y, z)
    pts.classification = _new_classes(pts.classification, eligible, ground, reset_classes)
    return pts, int(ground.sum())


#: Chunks worked on at once by :func:`.engine.two_passes` and :mod:`.blocks` (cropped and their returns taken in pass 1,
#: classified in pass 2); the grid is filled and the output written in reading order.
CHUNK_THREADS = BLOCK_THREADS


def cropped(chunk: Any, region: Optional[CropRegion]) -> Any:
    """The points of ``chunk`` inside ``region`` (all of them without one)."""
    return chunk if region is None else chunk[region.mask(chunk.x, chunk.y)]


def csf_square_nodes(params: CsfParams, tile_size_m: Optional[float] = None,
                     tile_buffer_m: Optional[float] = None) -> Tuple[int, int]:
    """CSF's squares of cloth as :class:`~.csf.CsfGrid` cuts them: ``(side, buffer)`` in nodes,
    for squares of ``tile_size_m`` and buffers of ``tile_buffer_m`` (default: CSF's)."""
    probe = CsfGrid((0.0, 0.0, 1.0, 1.0), 0.0, params, tile_size_m=tile_size_m or CSF_TILE_M,
                    tile_buffer_m=CSF_BUFFER_M if tile_buffer_m is None else tile_buffer_m)
    return probe.tile_nodes, probe.halo_nodes


def halo_m(params: Params, tile_buffer_m: Optional[float] = None) -> float:
    """How far SMRF's grid reaches beyond the cells it classifies (its halo), or CSF's
    buffer around a square of cloth, in metres."""
    if isinstance(params, CsfParams):
        return float(csf_square_nodes(params, tile_buffer_m=tile_buffer_m)[1] * params.resolution)
    return float(SmrfGrid((0.0, 0.0, 1.0, 1.0), params).halo_cells * params.cell)


def tile_grid(params: Params, cloud_bounds: BBoxXY, tile_box: BBoxXY,
              tile_buffer_m: Optional[float] = None, tile_size_m: Optional[float] = None) -> Optional[BBoxXY]:
    """The bounds to build tile ``tile_box``'s grid over (:func:`make_grid`), for a
    cloud whose whole-cloud grid covers ``cloud_bounds`` (the cloud's bounds within the crop)
    with CSF squares of ``tile_size_m`` and buffers of ``tile_buffer_m`` (default: the
    method's); None when the tile is outside them. See :mod:`.tiled`'s doc."""
    x0, y0, x1, y1 = cloud_bounds
    box = (max(tile_box[0], x0), max(tile_box[1], y0), min(tile_box[2], x1), min(tile_box[3], y1))
    if box[0] > box[2] or box[1] > box[3]:
        return None
    if not isinstance(params, CsfParams):
        h = halo_m(params)
        return (max(box[0] - h, x0), max(box[1] - h, y0), min(box[2] + h, x1), min(box[3] + h, y1))
    whole = Lattice.covering(cloud_bounds, params.resolution, max_cells=MAX_PAGED_CELLS)  # its numbers only
    core, buffer_nodes = csf_square_nodes(params, tile_size_m, tile_buffer_m)
    reach = -(-buffer_nodes // core)  # squares of buffer
    step = whole.step

    def span(lo: float, hi: float, origin: float, n: int) -> Tuple[int, int]:
        first = min(max(int(np.floor((lo - origin) / step + 0.5)), 0), n - 1)
        last = min(max(int(np.floor((hi - origin) / step + 0.5)), 0), n - 1)
        return max(0, (first // core - reach) * core), min(n, (last // core + 1 + reach) * core)

    c0, c1 = span(box[0], box[2], whole.x0, whole.nx)
    r0, r1 = span(box[1], box[3], whole.y0, whole.ny)
    # bounds that Lattice.covering (2 nodes of padding) turns into exactly these nodes
    return (whole.x0 + (c0 + 2.5) * step, whole.y0 + (r0 + 2.5) * step,
            whole.x0 + (c1 - 2.5) * step, whole.y0 + (r1 - 2.5) * step)


