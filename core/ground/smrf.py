"""SMRF, the Simple Morphological Filter (Pingel, Clarke & McBride 2013), as PDAL's
``filters.smrf``, on numpy/scipy.

Conventions:

* :class:`SmrfParams` holds PDAL's option names and defaults; lengths in metres, ``slope``
  as rise over run.
* The grid is a :class:`~.lattice.Lattice` of ``cell`` metres: cell (row, col) covers
  ``[x0 + col*cell, x0 + (col+1)*cell) x [y0 + row*cell, y0 + (row+1)*cell)`` and keeps
  the lowest point. Surfaces are ``(ny, nx)`` float arrays, NaN where nothing is known.
* Tiles overlap by the reach of the morphology, so tiled and untiled runs agree exactly.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from ..errors import SILENT, Progress
from .lattice import BoundsXY, Lattice, Window, finished, fitting_tiles, group_first, inner_window, windows_meet

#: SMRF tile size (core) in metres; the buffer follows from the window.
SMRF_TILE_M = 1024.0


@dataclass(frozen=True)
class SmrfParams:
    """``filters.smrf`` options (PDAL names and defaults), lengths in metres."""
    cell: float = 1.0           # cell size
    scalar: float = 1.25        # elevation scalar (threshold grows with slope)
    slope: float = 0.15         # slope (rise over run)
    threshold: float = 0.5      # elevation threshold
    window: float = 18.0        # max window size (radius)
    cut: float = 0.0            # cut net size (0 = no net cutting)
    returns: str = "last,only"


def _cross_step(a: np.ndarray, op: np.ufunc) -> np.ndarray:
    """One erosion (op=np.minimum) or dilation (np.maximum) by the 3x3 cross; cells past
    the grid edge are ignored. Repeated r times it is the diamond of radius r."""
    out = a.copy()
    op(out[1:], a[:-1], out=out[1:])
    op(out[:-1], a[1:], out=out[:-1])
    op(out[:, 1:], a[:, :-1], out=out[:, 1:])
    op(out[:, :-1], a[:, 1:], out=out[:, :-1])
    return out


def _progressive_filter(surface: np.ndarray, void: np.ndarray, cell: float, slope: float,
                        max_window: float) -> np.ndarray:
    """Object cells of a surface: openings by diamonds of radius 1..ceil(max_window/cell),
    flagging cells that drop by more than ``slope * cell * radius`` from the last surface.

    ``void`` cells (far from any data) take no part: +inf in erosions, -inf in dilations.
    """
    max_radius = int(math.ceil(max_window / cell))
    objects = np.zeros(surface.shape, dtype=bool)
    last_surface = np.where(void, np.nan, surface)
    erosion = np.where(void, np.inf, surface)
    with np.errstate(invalid="ignore"):
        for radius in range(1, max_radius + 1):
            erosion = _cross_step(erosion, np.minimum)
            erosion[void] = np.inf
            opening = np.where(void, -np.inf, erosion)
            for _ in range(radius):
                opening = _cross_step(opening, np.maximum)
                opening[void] = -np.inf
            opening[void] = np.nan
            objects |= (last_surface - opening) > slope * cell * radius
            last_surface = opening
    return objects


def _inpaint_knn(z: np.ndarray, zone: np.ndarray, k: int = 8) -> np.ndarray:
    """Fill the NaN cells of ``zone`` with the mean of the ``k`` nearest filled cells
    (Pingel's KNN inpainting); cells outside ``zone`` become NaN."""
    out = np.where(zone, z, np.nan)
    filled = zone & np.isfinite(out)
    holes = zone & ~filled
    n_src = int(filled.sum())
    if n_src == 0 or not holes.any():
        return out
    src_rc = np.argwhere(filled)
    dst_rc = np.argwhere(holes)
    kk = min(k, n_src)
    _, idx = cKDTree(src_rc).query(dst_rc, k=kk)
    values = out[filled]
    idx = np.asarray(idx).reshape(len(dst_rc), kk)
    out[holes] = values[idx].mean(axis=1)
    return out


def smrf_surface(zmin: np.ndarray, params: SmrfParams,
                 net_origin_rc: Tuple[int, int] = (0, 0)) -> Tuple[np.ndarray, np.ndarray]:
    """Provisional DEM ``ZIpro`` and its slope (rise/run) from the lowest point per cell.

    ``zmin``: float grid, NaN/inf where a cell has no point. Only cells within the reach
    of the morphology (``2*radius_max + 4`` cells) of data are computed; others are NaN.
    ``net_origin_rc`` is the global (row, col) of ``zmin[0, 0]`` so net cutting lines fall
    on the same cells in every tile.
    """
    cell = params.cell
    data = np.isfinite(zmin)
    if not data.any():
        nan = np.full(zmin.shape, np.nan)
        return nan, nan.copy()
    radius_max = int(math.ceil(params.window / cell))
    reach = 2 * radius_max + 4
    zone = ndimage.binary_dilation(data, structure=np.ones((3, 3), bool), iterations=reach)
    void = ~zone
    zi = _inpaint_knn(np.where(data, zmin, np.nan), zone)
    low = _progressive_filter(-zi, void, cell, 5.0, 1.0)
    net = np.zeros(zi.shape, dtype=bool)
    zi_net = zi
    if params.cut > 0:
        spacing = int(math.ceil(params.cut / cell))
        big_open = np.where(void, np.inf, zi)
        for _ in range(2 * spacing):
            big_open = _cross_step(big_open, np.minimum)
            big_open[void] = np.inf
        big_open[void] = -np.inf
        for _ in range(2 * spacing):
            big_open = _cross_step(big_open, np.maximum)
            big_open[void] = -np.inf
        rows = (np.arange(zi.shape[0]) + net_origin_rc[0]) % spacing == 0
        cols = (np.arange(zi.shape[1]) + net_origin_rc[1]) % spacing == 0
        net = (rows[:, None] | cols[None, :]) & zone
        zi_net = np.where(net, big_open, zi)
    objects = _progressive_filter(zi_net, void, cell, params.slope, params.window)
    zpro = _inpaint_knn(np.where(objects | low | net, np.nan, zi), zone)
    with np.errstate(invalid="ignore"):
        grad_row, grad_col = np.gradient(zpro / cell)
        slope = np.hypot(grad_row, grad_col)
    return zpro, slope


#: A chunk's lowest point in a cell (:func:`cell_candidates`): the cell (flat index
#: ``row * nx + col`` on its lattice) and the point's height (metres).
CELL_CANDIDATE_DTYPE = np.dtype([("cell", "i8"), ("z", "f8")])


def cell_candidates(lattice: Lattice, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """The lowest height of the points ``(x, y, z)`` in each cell of ``lattice`` they fall in, as
    :data:`CELL_CANDIDATE_DTYPE` rows; :class:`~.lattice.OutsideGridError` when a point falls
    in no cell. Needs the lattice only (:meth:`SmrfGrid.merge` takes them)."""
    if len(x) == 0:
        return np.zeros(0, CELL_CANDIDATE_DTYPE)
    u, v = lattice.local(x, y)
    col = np.floor(u).astype(np.int64)
    row = np.floor(v).astype(np.int64)
    lattice.check(col, row)
    flat = row * lattice.nx + col
    zs = np.asarray(z, dtype=np.float64)
    pick = group_first(flat, zs)
    out = np.empty(len(pick), CELL_CANDIDATE_DTYPE)
    out["cell"], out["z"] = flat[pick], zs[pick]
    return out


class SmrfGrid:
    """SMRF in three steps: ``accumulate`` (lowest point per cell, streaming), ``finish``
    (the grid stage, tile by tile), ``classify`` (points against ZIpro)."""

    def __init__(self, bounds_xy: BoundsXY, params: SmrfParams, tile_size_m: float = SMRF_TILE_M):
        self.params = params
        self.lattice = Lattice.covering(bounds_xy, params.cell)
        self.zmin = np.full((self.lattice.ny, self.lattice.nx), np.inf)
        self.tile_cells = max(16, int(round(tile_size_m / params.cell)))
        self.halo_cells = 2 * int(math.ceil(params.window / params.cell)) + 8 + (
            4 * int(math.ceil(params.cut / params.cell)) if params.cut > 0 else 0)
        self.zpro: Optional[np.ndarray] = None
        self.slope: Optional[np.ndarray] = None

    def accumulate(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> None:
        self.merge(cell_candidates(self.lattice, x, y, z))

    def merge(self, candidates: np.ndarray) -> None:
        """Take the lowest points per cell of one or more chunks (:func:`cell_candidates` on
        this lattice)."""
        if not len(candidates):
            return
        cells, z = candidates["cell"], candidates["z"]
        pick = group_first(cells, z)  # several chunks' candidates at once: the lowest of each cell's
        if len(pick) < len(cells):
            cells, z = cells[pick], z[pick]
        current = self.zmin.ravel()
        current[cells] = np.minimum(current[cells], z)

    def finish(self, progress: Progress = SILENT, only: Optional[Window] = None) -> None:
        shape = (int(self.zmin.shape[0]), int(self.zmin.shape[1]))
        self.zpro = zpro_all = np.full(shape, np.nan)
        self.slope = slope_all = np.full(shape, np.nan, dtype=np.float32)
        for core, ext in fitting_tiles(shape, self.tile_cells, self.halo_cells, progress):
            if (only is not None and not windows_meet(core, only)) or not np.isfinite(self.zmin[core]).any():
                continue
            zpro, slope = smrf_surface(self.zmin[ext], self.params,
                                       (ext[0].start, ext[1].start))
            inner = inner_window(core, ext)
            zpro_all[core] = zpro[inner]
            slope_all[core] = slope[inner]
        progress.report(1.0)

    def classify(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Ground mask: ``|z - ZIpro(x, y)| <= threshold + scalar * slope`` with ZIpro
        interpolated bilinearly between cell centres and the slope of the point's cell."""
        lat, p = self.lattice, self.params
        u, v = lat.local(x, y)
        cu, cv = u - 0.5, v - 0.5  # cell-centre coordinates
        c0 = np.clip(np.floor(cu).astype(np.int64), 0, lat.nx - 2)
        r0 = np.clip(np.floor(cv).astype(np.int64), 0, lat.ny - 2)
        fu = np.clip(cu - c0, 0.0, 1.0)
        fv = np.clip(cv - r0, 0.0, 1.0)
        zp = finished(self.zpro)
        z_surface = (zp[r0, c0] * (1 - fu) * (1 - fv) + zp[r0, c0 + 1] * fu * (1 - fv)
                     + zp[r0 + 1, c0] * (1 - fu) * fv + zp[r0 + 1, c0 + 1] * fu * fv)
        col = np.clip(np.floor(u).astype(np.int64), 0, lat.nx - 1)
        row = np.clip(np.floor(v).astype(np.int64), 0, lat.ny - 1)
        nearest = zp[row, col]
        z_surface = np.where(np.isfinite(z_surface), z_surface, nearest)
        slope = np.nan_to_num(finished(self.slope)[row, col].astype(np.float64), nan=0.0)
        with np.errstate(invalid="ignore"):
            return np.abs(np.asarray(z, dtype=np.float64) - z_surface) <= (
                p.threshold + p.scalar * slope)
