"""The world-aligned grid and the tiling shared by the built-in SMRF and CSF.

Conventions:

* A :class:`Lattice` has its origin ``(x0, y0)`` on multiples of its ``step`` (metres, in
  the cloud's CRS), so grids built over overlapping areas share their nodes/cells.
  Arrays over a lattice have shape ``(ny, nx)`` and are indexed ``[row, col]``, row along
  y and col along x.
* A tile is a pair of windows ``(core, ext)`` of ``(row slice, col slice)``: the cores
  cover the grid once; ``ext`` is the core grown by a halo, clipped at the grid edge.
* A :class:`GroundGrid` is a built-in method in three steps: ``accumulate`` (pass 1,
  streaming the points), ``finish`` (the grid stage, tile by tile) and ``classify``
  (pass 2, a ground mask per point).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Iterator, Optional, Protocol, Tuple, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from ..errors import SILENT, InputError, Progress

#: ``(row slice, col slice)`` of a grid.
Window = Tuple[slice, slice]
#: A grid's bounds ``(xmin, ymin, xmax, ymax)`` in metres.
BoundsXY = Tuple[float, float, float, float]
_T = TypeVar("_T")


class OutsideGridError(ValueError):
    """Points outside the area the grid was built for (a header with wrong bounds)."""


@dataclass
class Lattice:
    """A world-aligned grid: node/cell (row, col) at ``(x0 + col*step, y0 + row*step)``.

    ``x0, y0`` are multiples of ``step``, so two grids over overlapping areas agree.
    SMRF cells are ``[x0 + col*step, x0 + (col+1)*step)``; CSF nodes sit on the points
    ``x0 + col*step`` and take the points that round to them.
    """
    x0: float
    y0: float
    step: float
    nx: int
    ny: int

    @classmethod
    def covering(cls, bounds_xy: BoundsXY, step: float, pad: int = 2,
                 max_cells: int = 80_000_000) -> "Lattice":
        xmin, ymin, xmax, ymax = bounds_xy
        x0 = (math.floor(xmin / step) - pad) * step
        y0 = (math.floor(ymin / step) - pad) * step
        nx = int(math.floor((xmax - x0) / step)) + 1 + pad
        ny = int(math.floor((ymax - y0) / step)) + 1 + pad
        if nx * ny > max_cells:
            raise InputError(
                "The area to classify ({w:.0f} m x {h:.0f} m) needs {cells} grid cells of "
                "{step} m, more than {limit}: crop the cloud or use a larger cell/resolution",
                w=xmax - xmin, h=ymax - ymin, cells=nx * ny, step=step, limit=max_cells)
        return cls(x0, y0, float(step), nx, ny)

    @property
    def shape(self) -> Tuple[int, int]:
        """``(ny, nx)``: the shape of an array over the grid."""
        return self.ny, self.nx

    def local(self, x: ArrayLike, y: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        """Coordinates in grid steps from node/cell corner (0, 0)."""
        return ((np.asarray(x, dtype=np.float64) - self.x0) / self.step,
                (np.asarray(y, dtype=np.float64) - self.y0) / self.step)

    def check(self, col: np.ndarray, row: np.ndarray) -> None:
        """Raise :class:`OutsideGridError` when an index falls outside the grid."""
        if col.size and (col.min() < 0 or row.min() < 0 or col.max() >= self.nx
                         or row.max() >= self.ny):
            raise OutsideGridError("points outside the bounds in the file header")


#: Side of a block of the built-in engine run block by block (metres; :mod:`.blocks`, the
#: engine's ``block_m``): the ground surface of one block and its halo is held at a time.
#: Large enough that a block's grid reaches its eight neighbours only (CSF: a 32 m square and
#: a buffer; SMRF: a halo of about 50 m at the defaults), small enough that a drive's grid is
#: cut into many: at CSF's 1 m cloth, a 512 m block of a 50 m corridor is a few MB of grid.
BLOCK_M = 512.0

#: Side of a :class:`PagedArray`'s pages (cells).
PAGE_CELLS = 64
#: The most cells a lattice of :class:`PagedArray` may span (its page table: 4 bytes a page,
#: 64 MB at most): a bounding box of 128 km x 128 km at 0.5 m. A dense grid stops at
#: :meth:`Lattice.covering`'s default.
MAX_PAGED_CELLS = 16_000_000 * PAGE_CELLS * PAGE_CELLS


class PagedArray:
    """A 2-D array of ``shape`` over a lattice, stored in square pages of ``page`` cells that
    are allocated when first written: its memory follows the cells that have data (a drive's
    corridor), not their bounding box. Cells of pages never written read as ``fill``.

    Cells are addressed by ``(rows, cols)`` index arrays (:meth:`get`, :meth:`set`) or by a
    :data:`Window` (:meth:`window`, :meth:`has_pages`). ``slot[page_row, page_col]`` is the
    page's place in the store (-1: none).
    """

    def __init__(self, shape: Tuple[int, int], dtype, fill, page: int = PAGE_CELLS):
        self.shape = (int(shape[0]), int(shape[1]))
        self.dtype = np.dtype(dtype)
        self.fill = fill
        self.page = int(page)
        self.slot = np.full((-(-self.shape[0] // self.page), -(-self.shape[1] // self.page)), -1, np.int32)
        self._store = np.empty((0, self.page, self.page), self.dtype)
        self.n_pages = 0

    @property
    def nbytes(self) -> int:
        """Bytes held: the pages (with the room reserved for more) and the page table."""
        return int(self._store.nbytes + self.slot.nbytes)

    def _allocate(self, page_rows: np.ndarray, page_cols: np.ndarray) -> None:
        """Pages for the (unique) page coordinates given that have none yet."""
        missing = self.slot[page_rows, page_cols] < 0
        if not missing.any():
            return
        keys = np.unique(page_rows[missing] * self.slot.shape[1] + page_cols[missing])
        n_new = len(keys)
        if self.n_pages + n_new > len(self._store):  # grow by half
            grown = np.empty((max(len(self._store) * 3 // 2, self.n_pages + n_new, 16), self.page, self.page),
                             self.dtype)
            grown[:self.n_pages] = self._store[:self.n_pages]
            self._store = grown
        self._store[self.n_pages:self.n_pages + n_new] = self.fill
        self.slot.ravel()[keys] = np.arange(self.n_pages, self.n_pages + n_new)
        self.n_pages += n_new

    def _locate(self, rows, cols, create: bool) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        rows = np.asarray(rows, np.int64)
        cols = np.asarray(cols, np.int64)
        page_rows, page_cols = rows // self.page, cols // self.page
        if create and rows.size:
            self._allocate(page_rows, page_cols)
        return self.slot[page_rows, page_cols], rows - page_rows * self.page, cols - page_cols * self.page

    def trim(self) -> None:
        """Give back the room reserved for more pages."""
        if len(self._store) > self.n_pages:
            self._store = self._store[:self.n_pages].copy()

    def get(self, rows, cols) -> np.ndarray:
        """The values at cells ``(rows, cols)`` (``fill`` where no page is)."""
        slots, r, c = self._locate(rows, cols, create=False)
        out = np.full(slots.shape, self.fill, self.dtype)
        have = slots >= 0
        out[have] = self._store[slots[have], r[have], c[have]]
        return out

    def set(self, rows, cols, values) -> None:
        """Write ``values`` at cells ``(rows, cols)`` (pages allocated as needed)."""
        slots, r, c = self._locate(rows, cols, create=True)
        self._store[slots, r, c] = values

    def has_pages(self, win: Window) -> bool:
        """Whether any page meets the window (else all of it reads ``fill``)."""
        p = self.page
        return bool((self.slot[win[0].start // p:-(-win[0].stop // p), win[1].start // p:-(-win[1].stop // p)]
                     >= 0).any())

    def window(self, win: Window) -> np.ndarray:
        """The window's cells as a dense array (a copy)."""
        r0, r1, c0, c1 = win[0].start, win[0].stop, win[1].start, win[1].stop
        out = np.full((r1 - r0, c1 - c0), self.fill, self.dtype)
        p = self.page
        for pr in range(r0 // p, -(-r1 // p)):
            for pc in range(c0 // p, -(-c1 // p)):
                k = self.slot[pr, pc]
                if k < 0:
                    continue
                a0, a1 = max(r0, pr * p), min(r1, (pr + 1) * p)
                b0, b1 = max(c0, pc * p), min(c1, (pc + 1) * p)
                out[a0 - r0:a1 - r0, b0 - c0:b1 - c0] = self._store[k, a0 - pr * p:a1 - pr * p, b0 - pc * p:b1 - pc * p]
        return out

    def dense(self) -> np.ndarray:
        """The whole array, dense (small grids: tests, checks)."""
        return self.window((slice(0, self.shape[0]), slice(0, self.shape[1])))


def tiles(shape: Tuple[int, int], core: int, halo: int) -> Iterator[Tuple[Window, Window]]:
    """Yield ``(core_window, ext_window)`` covering a grid with squares of ``core`` cells,
    each extended by ``halo`` cells (clipped at the grid edge)."""
    ny, nx = shape
    for r0 in range(0, ny, core):
        for c0 in range(0, nx, core):
            r1, c1 = min(r0 + core, ny), min(c0 + core, nx)
            er0, ec0 = max(r0 - halo, 0), max(c0 - halo, 0)
            er1, ec1 = min(r1 + halo, ny), min(c1 + halo, nx)
            yield (slice(r0, r1), slice(c0, c1)), (slice(er0, er1), slice(ec0, ec1))


def fitting_tiles(shape: Tuple[int, int], core: int, halo: int,
                  progress: Progress = SILENT) -> Iterator[Tuple[Window, Window]]:
    """:func:`tiles` for the grid stage of a ground filter (``finish``), with the progress and
    the current step reported before each tile."""
    windows = list(tiles(shape, core, halo))
    for i, pair in enumerate(windows):
        progress.report(i / len(windows))
        progress.step("Fitting the ground surface: tile {n} of {count}", n=i + 1, count=len(windows))
        yield pair


def on_lattice(lattice: Lattice, x: np.ndarray, y: np.ndarray, nodes: bool) -> np.ndarray:
    """Which points fall on ``lattice``: at a node (CSF, nearest node) or in a cell (SMRF)."""
    u, v = lattice.local(x, y)
    shift = 0.5 if nodes else 0.0
    col, row = np.floor(u + shift), np.floor(v + shift)
    return (col >= 0) & (col < lattice.nx) & (row >= 0) & (row < lattice.ny)


def windows_meet(a: Window, b: Window) -> bool:
    """Whether two windows of a grid share a cell."""
    return (a[0].start < b[0].stop and b[0].start < a[0].stop
            and a[1].start < b[1].stop and b[1].start < a[1].stop)


def inner_window(core: Window, ext: Window) -> Window:
    """``core`` in the coordinates of an array cut to ``ext``."""
    return (slice(core[0].start - ext[0].start, core[0].stop - ext[0].start),
            slice(core[1].start - ext[1].start, core[1].stop - ext[1].start))


def group_first(keys: np.ndarray, order_by: np.ndarray) -> np.ndarray:
    """Indices of the element with the smallest ``order_by`` for each distinct key (one
    index per key, in the order of the sorted keys); of equal smallest ones, the first (as
    the reference CSF, which keeps a node's first nearest point)."""
    if not len(keys):
        return np.zeros(0, np.int64)
    order = np.argsort(keys, kind="stable")
    k = keys[order]
    v = order_by[order]
    starts = np.flatnonzero(np.r_[True, k[1:] != k[:-1]])
    group_min = np.minimum.reduceat(v, starts)
    group = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(k)]))
    at_min = np.flatnonzero(v == group_min[group])
    first = np.r_[True, group[at_min[1:]] != group[at_min[:-1]]]
    return order[at_min[first]]


def finished(array: Optional[_T]) -> _T:
    """A grid's result array, which exists once ``finish`` has run."""
    if array is None:
        raise RuntimeError("the ground grid is classified before finish() ran")
    return array


class GroundGrid(Protocol):
    """A built-in ground method over a :class:`Lattice` (the SMRF and CSF grids)."""

    lattice: Lattice

    def accumulate(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> None:
        """Take a chunk of points (pass 1)."""

    def merge(self, candidates: np.ndarray) -> None:
        """Take what :meth:`accumulate` keeps of a chunk, found on this grid's lattice
        beforehand (pass 1 in parallel, :mod:`.blocks`)."""

    def finish(self, progress: Progress = SILENT, only: Optional[Window] = None) -> None:
        """Compute the ground surface, tile by tile (only the tiles that meet the window
        ``only`` when given: the cells the points to classify need)."""

    def classify(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Ground mask of a chunk of points (pass 2)."""
