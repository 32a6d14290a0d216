"""CSF, the Cloth Simulation Filter (Zhang et al. 2016), with the reference implementation
(PyPI ``cloth-simulation-filter``, module ``CSF``), as PDAL's ``filters.csf``.

Conventions:

* :class:`CsfParams` holds PDAL's option names and defaults; lengths in metres.
* The cloth lives on a :class:`~.lattice.Lattice` of ``resolution`` metres: node (row, col)
  sits at ``(x0 + col*resolution, y0 + row*resolution)`` and takes the points that round
  to it. Heights on the grid are stored relative to ``z_ref`` (float32).
* The library prints to the process's stdout (silenced here: ``qgis_process --json`` owns
  it) and runs with one OpenMP thread (its parallel loops are not deterministic).
"""
from __future__ import annotations

import contextlib
import math
import os
import sys
import types
from dataclasses import dataclass
from typing import Any, ContextManager, Iterator, List, Optional

import numpy as np

from ..errors import SILENT, InputError, Progress
from .lattice import (
    MAX_PAGED_CELLS,
    BoundsXY,
    Lattice,
    PagedArray,
    Window,
    finished,
    fitting_tiles,
    group_first,
    windows_meet,
)

#: CSF tiles (core, buffer) in metres. The cloth is a global simulation: on slopes it
#: hangs off the ground more the larger the area (smoothing fixes most), so tiles are
#: kept small; on flat ground tiled and untiled runs differ by ~0.005 % of the points.
CSF_TILE_M, CSF_BUFFER_M = 32.0, 20.0
#: ``accumulate`` sorts the points within this distance of their node first (cloth steps)
NEAR_NODE_STEPS = 0.1
#: ``classify`` gathers the cloth from a dense copy of the chunk's window when it has at most
#: this many nodes (8 bytes each), else node by node from the pages
CLASSIFY_WINDOW_NODES = 4_000_000


@dataclass(frozen=True)
class CsfParams:
    """``filters.csf`` options (PDAL names and defaults), lengths in metres.

    ``hdiff`` is not offered: the reference CSF library fixes it (0.3 m) and PDAL
    versions differ in whether they accept it.
    """
    resolution: float = 1.0     # cloth resolution (node spacing)
    threshold: float = 0.5      # classification threshold (point-to-cloth distance)
    smooth: bool = True         # slope post-processing
    step: float = 0.65          # time step
    rigidness: int = 3
    iterations: int = 500
    returns: str = "last,only"  # return types classified: first, last, intermediate, only


@contextlib.contextmanager
def _native_stdout_silenced() -> Iterator[None]:
    """The CSF library prints progress with std::cout; keep it off our stdout (which
    ``qgis_process --json`` owns)."""
    try:
        sys.stdout.flush()
        _flush_c_streams()
        saved = os.dup(1)
    except (OSError, ValueError, AttributeError):
        yield
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        _flush_c_streams()  # the library's buffered output goes to devnull, not to our stdout
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


def _flush_c_streams() -> None:
    """Flush the C library's output streams (``fflush(NULL)``): what the host application
    (``qgis_process`` printing the progress text) has buffered is written before stdout is
    redirected, and not lost to devnull with the library's output."""
    import ctypes

    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):  # no C library to flush through (not POSIX)
        pass


def _one_openmp_thread() -> ContextManager[Any]:
    """Every OpenMP runtime loaded held to one thread in the calling thread, and given back its
    setting after (threadpoolctl).

    The CSF wheel's OpenMP loops race (two runs on the same points can give cloths differing
    by 0.1 m); one OpenMP thread makes it deterministic. The library's OpenMP calls bind to
    the first runtime the process loaded with global symbols, which is not always the one
    its wheel bundles (after torch, in a QGIS where another plugin imported it, they bind to
    torch's), so each one loaded is held, not only the wheel's. OpenMP settings are per
    calling thread (QGIS runs algorithms in worker threads): entered around every run."""
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1, user_api="openmp")


def _csf_module() -> types.ModuleType:
    try:
        import CSF  # PyPI: cloth-simulation-filter
    except ImportError as e:
        raise InputError("The built-in CSF needs the Python package cloth-simulation-filter "
                         "(module CSF): {detail}", detail=str(e))
    return CSF


def csf_available() -> bool:
    """Whether the reference CSF (PyPI ``cloth-simulation-filter``) imports here."""
    try:
        _csf_module()
    except InputError:
        return False
    return True


def run_csf_cloth(xyz: np.ndarray, params: CsfParams) -> np.ndarray:
    """Run the reference CSF on points ``(n, 3)`` and return its cloth nodes ``(m, 3)``
    (x, y, height), after the slope post-processing when ``params.smooth``."""
    CSF = _csf_module()
    csf = CSF.CSF()
    csf.params.bSloopSmooth = bool(params.smooth)
    csf.params.time_step = float(params.step)
    csf.params.class_threshold = float(params.threshold)
    csf.params.cloth_resolution = float(params.resolution)
    csf.params.rigidness = int(params.rigidness)
    csf.params.interations = int(params.iterations)
    # do_cloth_export runs the whole simulation itself (do_filtering would run it a second
    # time only to classify the points, which CsfGrid.classify does): the same cloth
    with _native_stdout_silenced(), _one_openmp_thread():
        csf.setPointCloud(np.ascontiguousarray(xyz, dtype=np.float64))
        cloth = csf.do_cloth_export()
    return np.asarray(cloth, dtype=np.float64).reshape(-1, 3)


#: A chunk's nearest point to a cloth node (:func:`node_candidates`): the node (flat index
#: ``row * nx + col`` on its lattice), the point's offset from it (steps) and its height above
#: the grid's ``z_ref`` (metres).
NODE_CANDIDATE_DTYPE = np.dtype([("node", "i8"), ("du", "f4"), ("dv", "f4"), ("z", "f4")])


def node_candidates(lattice: Lattice, x: np.ndarray, y: np.ndarray, z: np.ndarray, z_ref: float) -> np.ndarray:
    """The nearest of the points ``(x, y, z)`` to each cloth node of ``lattice`` they round to
    (the first of equally near ones), as :data:`NODE_CANDIDATE_DTYPE` rows in node order;
    :class:`~.lattice.OutsideGridError` when a point rounds to no node of the lattice.
    Needs the lattice only, so chunks can be reduced in parallel and merged later
    (:meth:`CsfGrid.merge`)."""
    if len(x) == 0:
        return np.zeros(0, NODE_CANDIDATE_DTYPE)
    u, v = lattice.local(x, y)
    col = np.floor(u + 0.5).astype(np.int64)
    row = np.floor(v + 0.5).astype(np.int64)
    lattice.check(col, row)
    du = (u - col).astype(np.float32)
    dv = (v - row).astype(np.float32)
    del u, v
    d2 = du * du
    d2 += dv * dv
    flat = row * lattice.nx
    flat += col
    del col, row
    pick = nearest_per_node(flat, d2)
    out = np.empty(len(pick), NODE_CANDIDATE_DTYPE)
    out["node"], out["du"], out["dv"] = flat[pick], du[pick], dv[pick]
    out["z"] = (np.asarray(z, dtype=np.float64)[pick] - z_ref).astype(np.float32)
    return out


def nearest_per_node(flat: np.ndarray, d2: np.ndarray) -> np.ndarray:
    """:func:`~.lattice.group_first` of ``(flat, d2)``: a node's nearest point is among its
    points within ``NEAR_NODE_STEPS`` when it has any (a few per cent of a dense cloud), so
    those are sorted first, and only the points of the nodes without one after them."""
    near = np.flatnonzero(d2 < NEAR_NODE_STEPS * NEAR_NODE_STEPS)
    if len(near) * 4 > len(d2):
        return group_first(flat, d2)
    pick = near[group_first(flat[near], d2[near])]
    covered = flat[pick]  # sorted: group_first answers in the order of the sorted keys
    at = np.minimum(np.searchsorted(covered, flat), len(covered) - 1)
    rest = np.flatnonzero(covered[at] != flat) if len(covered) else np.arange(len(flat))
    if len(rest):
        pick = np.concatenate([pick, rest[group_first(flat[rest], d2[rest])]])
    return pick


class CsfGrid:
    """CSF in three steps, exact to the reference library on the tile's points.

    ``accumulate`` keeps, per cloth node, the point nearest to it: the only point CSF's
    rasterisation uses, so running CSF on these points gives the cloth of the full
    cloud. ``finish`` runs CSF tile by tile (core + buffer), each tile's cloth lattice
    pinned to the world grid by a sentinel point on the node just below-left of the
    tile, which becomes CSF's bounding-box corner. ``classify`` compares points with the
    cloth interpolated as CSF does (``|cloth - z| < threshold``).
    """

    def __init__(self, bounds_xy: BoundsXY, z_ref: float, params: CsfParams,
                 tile_size_m: float = CSF_TILE_M, tile_buffer_m: float = CSF_BUFFER_M):
        self.params = params
        self.lattice = Lattice.covering(bounds_xy, params.resolution, max_cells=MAX_PAGED_CELLS)
        shape = self.lattice.shape
        self.z_ref = float(z_ref)
        # nearest point per node: offset from the node (in steps) and height above z_ref; paged,
        # so that a long drive's grid holds its corridor and not its bounding box
        self.rep_du = PagedArray(shape, np.float32, np.nan)
        self.rep_dv = PagedArray(shape, np.float32, np.nan)
        self.rep_z = PagedArray(shape, np.float32, np.nan)
        self.tile_nodes = max(8, int(round(tile_size_m / params.resolution)))
        self.halo_nodes = max(2, int(math.ceil(tile_buffer_m / params.resolution)))
        self.cloth: Optional[PagedArray] = None
        self.tiles_run = 0

    def accumulate(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> None:
        self.merge(node_candidates(self.lattice, x, y, z, self.z_ref))

    def merge(self, candidates: np.ndarray) -> None:
        """Take the nearest points per node of one or more chunks (:func:`node_candidates` on
        this lattice and ``z_ref``, in reading order): a node keeps the nearest of the point
        it had and the candidates, the earliest of equally near ones (so chunks merged in
        reading order give the first nearest point, as the reference CSF)."""
        if not len(candidates):
            return
        du, dv = candidates["du"], candidates["dv"]
        d2 = du * du
        d2 += dv * dv
        # several chunks' candidates at once: the first nearest of each node's, in their order
        pick = group_first(candidates["node"], d2)
        if len(pick) < len(candidates):
            first = np.sort(pick)    # in their reading order
            candidates, d2 = candidates[first], d2[first]
        rows, cols = np.divmod(candidates["node"], self.lattice.nx)
        old_du = self.rep_du.get(rows, cols)
        old_dv = self.rep_dv.get(rows, cols)
        better = np.isnan(old_du) | (d2 < old_du * old_du + old_dv * old_dv)
        rows, cols, kept = rows[better], cols[better], candidates[better]
        self.rep_du.set(rows, cols, kept["du"])
        self.rep_dv.set(rows, cols, kept["dv"])
        self.rep_z.set(rows, cols, kept["z"])


    def _tile_points(self, ext: Window) -> np.ndarray:
        du = self.rep_du.window(ext)
        have = ~np.isnan(du)
        rows, cols = np.nonzero(have)
        r_ext, c_ext = ext[0].start, ext[1].start
        step = self.lattice.step
        xs = (cols + c_ext + du[have].astype(np.float64)) * step
        ys = (rows + r_ext + self.rep_dv.window(ext)[have].astype(np.float64)) * step
        zs = self.rep_z.window(ext)[have].astype(np.float64)
        # sentinel on the node below-left of the tile: CSF's bbox corner = a world node
        sx, sy = (c_ext - 1) * step, (r_ext - 1) * step
        nearest = int(np.argmin((xs - sx) ** 2 + (ys - sy) ** 2))
        return np.column_stack([np.r_[xs, sx], np.r_[ys, sy], np.r_[zs, zs[nearest]]])

    def finish(self, progress: Progress = SILENT, only: Optional[Window] = None) -> None:
        lat = self.lattice
        self.cloth = cloth_all = PagedArray(lat.shape, np.float64, np.nan)
        for core, ext in fitting_tiles(lat.shape, self.tile_nodes, self.halo_nodes, progress):
            if only is not None and not windows_meet(core, only):
                continue
            if not self.rep_du.has_pages(core) or not (~np.isnan(self.rep_du.window(core))).any():
                continue
            pts = self._tile_points(ext)
            cloth = run_csf_cloth(pts, self.params)
            self.tiles_run += 1
            cols_f = cloth[:, 0] / lat.step
            rows_f = cloth[:, 1] / lat.step
            cols = np.rint(cols_f).astype(np.int64)
            rows = np.rint(rows_f).astype(np.int64)
            if np.abs(cols_f - cols).max() > 1e-6 or np.abs(rows_f - rows).max() > 1e-6:
                raise RuntimeError("CSF cloth is not aligned with the world grid")
            # core nodes always; a one-node ring (for interpolation) only where unset
            ring = ((rows >= core[0].start - 1) & (rows <= core[0].stop)
                    & (cols >= core[1].start - 1) & (cols <= core[1].stop)
                    & (rows >= 0) & (rows < lat.ny) & (cols >= 0) & (cols < lat.nx))
            in_core = ((rows >= core[0].start) & (rows < core[0].stop)
                       & (cols >= core[1].start) & (cols < core[1].stop))
            fill = ring & ~in_core
            fill[fill] = np.isnan(cloth_all.get(rows[fill], cols[fill]))
            cloth_all.set(rows[in_core], cols[in_core], cloth[in_core, 2])
            cloth_all.set(rows[fill], cols[fill], cloth[fill, 2])
        cloth_all.trim()
        progress.report(1.0)

    def _cloth_corners(self, r0: np.ndarray, c0: np.ndarray) -> List[np.ndarray]:
        """The cloth at the nodes (r0, c0), (r0+1, c0), (r0+1, c0+1) and (r0, c0+1)."""
        cloth = finished(self.cloth)
        if not len(r0):
            return [np.zeros(0)] * 4
        win = (slice(int(r0.min()), int(r0.max()) + 2), slice(int(c0.min()), int(c0.max()) + 2))
        nx = win[1].stop - win[1].start
        if (win[0].stop - win[0].start) * nx > CLASSIFY_WINDOW_NODES:  # a chunk spread far: by pages
            return [cloth.get(r0, c0), cloth.get(r0 + 1, c0), cloth.get(r0 + 1, c0 + 1), cloth.get(r0, c0 + 1)]
        cz = cloth.window(win).ravel()
        at = r0 - win[0].start
        at *= nx
        at += c0
        at -= win[1].start
        return [cz[at], cz[at + nx], cz[at + (nx + 1)], cz[at + 1]]

    def classify(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
        lat = self.lattice
        su, sv = lat.local(x, y)
        c0 = np.clip(np.floor(su).astype(np.int64), 0, lat.nx - 2)
        r0 = np.clip(np.floor(sv).astype(np.int64), 0, lat.ny - 2)
        su -= c0
        sv -= r0
        a, b, c, d = self._cloth_corners(r0, c0)
        del c0, r0
        # the cloth bilinearly at (su, sv) in the cell: ((a*(1-su))*(1-sv) + (b*(1-su))*sv)
        # + (c*su)*sv + (d*su)*(1-sv), in this order (the reference's arithmetic, bit for bit)
        osu, osv = 1 - su, 1 - sv
        surface = a * osu
        surface *= osv
        term = b * osu
        term *= sv
        surface += term
        np.multiply(c, su, out=term)
        term *= sv
        surface += term
        np.multiply(d, su, out=term)
        term *= osv
        surface += term
        surface += self.z_ref
        surface -= np.asarray(z, dtype=np.float64)
        with np.errstate(invalid="ignore"):
            return np.abs(surface, out=surface) < self.params.threshold
