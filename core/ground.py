"""Ground classification (class 2) of LAS/LAZ clouds: CSF or SMRF, by PDAL or built in.

One entry point, :func:`run_ground_filter` (what the ``roadsigns:groundfilter`` algorithm
calls), reads the input, crops it, classifies ground and writes LAS/LAZ:

* engine ``"pdal"``: a pipeline ``readers.las -> filters.crop -> filters.csf|filters.smrf
  -> writers.las`` (JSON from :func:`build_pdal_pipeline`), run by the ``pdal`` Python
  module when it imports, else by a ``pdal`` executable through ``pdal pipeline --stdin``;
* engine ``"builtin"``: the same stages in Python: CSF with the reference implementation
  (PyPI ``cloth-simulation-filter``, module ``CSF``) and SMRF (Pingel et al. 2013) on
  numpy/scipy, both with PDAL's option names and defaults (:class:`CsfParams`,
  :class:`SmrfParams`);
* engine ``"auto"``: PDAL when found, the built-in engine when PDAL is missing or fails.

The built-in engine never holds the cloud in memory. Pass 1 streams the points into a
grid (SMRF: lowest point per cell; CSF: the point nearest to each cloth node, which is
all the cloth simulation looks at), the grid is processed tile by tile with an overlap
buffer, and pass 2 streams the points again, classifies them against the ground surface
of their tile and writes them. Memory grows with the crop area, not the point count.

Ground is class 2. Other classes are kept unless ``reset_classes``: points the filter
finds off-ground that were class 2 become 1 (unclassified); with ``reset_classes`` every
non-ground point becomes 1. As in PDAL, only ``returns`` (default last and only returns)
are classified; the others keep their class.
"""
from __future__ import annotations

import contextlib
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass, field
from typing import Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from .errors import SILENT, InputError, Message, Progress
from .pointcloud import (DEFAULT_CHUNK_POINTS, LAS_SUFFIXES, CloudWriter, CropRegion,
                         crs_wkt_of_header, iter_chunks, output_header, read_header)

#: Method and engine names, in the order of the Processing enums (METHOD, ENGINE).
METHODS = ("csf", "smrf")
ENGINES = ("auto", "pdal", "builtin")
GROUND_CLASS = 2
UNCLASSIFIED_CLASS = 1
#: CSF tiles (core, buffer) in metres. The cloth is a global simulation: on slopes it
#: hangs off the ground more the larger the area (smoothing fixes most), so tiles are
#: kept small; on flat ground tiled and untiled runs differ by ~0.005 % of the points.
CSF_TILE_M, CSF_BUFFER_M = 32.0, 20.0
#: Temporary PDAL dimension holding the classes from before the filter.
_KEEP_CLASS_DIM = "RoadsignsClassBefore"


# --------------------------------------------------------------------------------------
# Parameters (PDAL option names and documented defaults)
# --------------------------------------------------------------------------------------

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


Params = Union[CsfParams, SmrfParams]


def default_params(method: str) -> Params:
    return CsfParams() if method == "csf" else SmrfParams()


@dataclass
class GroundResult:
    """What a ground filter run did."""
    output_path: str
    method: str
    engine: str                 # "pdal-python", "pdal-cli" or "builtin"
    n_input: int
    n_output: int
    n_ground: int
    crs_wkt: Optional[str]
    warnings: List[str] = field(default_factory=list)
    pipeline_json: Optional[str] = None


class PdalError(RuntimeError):
    """PDAL ran and failed; ``stderr`` holds PDAL's own message."""

    def __init__(self, message: str, stderr: str = ""):
        super().__init__(message)
        self.stderr = stderr


def _name_from(value, names: Sequence[str], what: str) -> str:
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        if 0 <= int(value) < len(names):
            return names[int(value)]
    elif isinstance(value, str):
        v = value.strip().lower().replace("-", "").replace("_", "")
        for n in names:
            if v == n.replace("-", ""):
                return n
    raise InputError("Unknown {what} {value!r}: expected one of {names}", what=what,
                     value=value, names=", ".join(names))


# --------------------------------------------------------------------------------------
# Return selection
# --------------------------------------------------------------------------------------

def returns_mask(return_number, number_of_returns, returns: str = "last,only") -> np.ndarray:
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


# --------------------------------------------------------------------------------------
# Grid shared by both built-in methods
# --------------------------------------------------------------------------------------

class _OutsideGrid(ValueError):
    pass


@dataclass
class _Lattice:
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
    def covering(cls, bounds_xy: Tuple[float, float, float, float], step: float,
                 pad: int = 2, max_cells: int = 80_000_000) -> "_Lattice":
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

    def local(self, x, y) -> Tuple[np.ndarray, np.ndarray]:
        """Coordinates in grid steps from node/cell corner (0, 0)."""
        return ((np.asarray(x, dtype=np.float64) - self.x0) / self.step,
                (np.asarray(y, dtype=np.float64) - self.y0) / self.step)

    def check(self, col: np.ndarray, row: np.ndarray) -> None:
        if col.size and (col.min() < 0 or row.min() < 0 or col.max() >= self.nx
                         or row.max() >= self.ny):
            raise _OutsideGrid("points outside the bounds in the file header")


def _tiles(shape: Tuple[int, int], core: int, halo: int):
    """Yield ``(core_slices, ext_slices)`` covering a grid with squares of ``core`` cells,
    each extended by ``halo`` cells (clipped at the grid edge)."""
    ny, nx = shape
    for r0 in range(0, ny, core):
        for c0 in range(0, nx, core):
            r1, c1 = min(r0 + core, ny), min(c0 + core, nx)
            er0, ec0 = max(r0 - halo, 0), max(c0 - halo, 0)
            er1, ec1 = min(r1 + halo, ny), min(c1 + halo, nx)
            yield (slice(r0, r1), slice(c0, c1)), (slice(er0, er1), slice(ec0, ec1))


def _group_first(keys: np.ndarray, order_by: np.ndarray) -> np.ndarray:
    """Indices of the element with the smallest ``order_by`` for each distinct key."""
    order = np.argsort(keys)
    k = keys[order]
    v = order_by[order]
    starts = np.flatnonzero(np.r_[True, k[1:] != k[:-1]])
    group_min = np.minimum.reduceat(v, starts)
    group = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(k)]))
    at_min = np.flatnonzero(v == group_min[group])
    first = np.r_[True, group[at_min[1:]] != group[at_min[:-1]]]
    return order[at_min[first]]


# --------------------------------------------------------------------------------------
# SMRF (Pingel, Clarke & McBride 2013), as PDAL's filters.smrf
# --------------------------------------------------------------------------------------

def _cross_step(a: np.ndarray, op) -> np.ndarray:
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


class _SmrfGrid:
    """SMRF in three steps: ``accumulate`` (lowest point per cell, streaming), ``finish``
    (the grid stage, tile by tile), ``classify`` (points against ZIpro)."""

    def __init__(self, bounds_xy, params: SmrfParams, tile_size_m: float = 1024.0):
        self.params = params
        self.lattice = _Lattice.covering(bounds_xy, params.cell)
        self.zmin = np.full((self.lattice.ny, self.lattice.nx), np.inf)
        self.tile_cells = max(16, int(round(tile_size_m / params.cell)))
        self.halo_cells = 2 * int(math.ceil(params.window / params.cell)) + 8 + (
            4 * int(math.ceil(params.cut / params.cell)) if params.cut > 0 else 0)
        self.zpro: Optional[np.ndarray] = None
        self.slope: Optional[np.ndarray] = None

    def accumulate(self, x, y, z) -> None:
        if len(x) == 0:
            return
        u, v = self.lattice.local(x, y)
        col = np.floor(u).astype(np.int64)
        row = np.floor(v).astype(np.int64)
        self.lattice.check(col, row)
        flat = row * self.lattice.nx + col
        z = np.asarray(z, dtype=np.float64)
        pick = _group_first(flat, z)
        cells = flat[pick]
        current = self.zmin.ravel()
        current[cells] = np.minimum(current[cells], z[pick])

    def finish(self, progress: Progress = SILENT) -> None:
        shape = self.zmin.shape
        self.zpro = np.full(shape, np.nan)
        self.slope = np.full(shape, np.nan, dtype=np.float32)
        tiles = list(_tiles(shape, self.tile_cells, self.halo_cells))
        for i, (core, ext) in enumerate(tiles):
            progress.report(i / len(tiles))
            if not np.isfinite(self.zmin[core]).any():
                continue
            zpro, slope = smrf_surface(self.zmin[ext], self.params,
                                       (ext[0].start, ext[1].start))
            inner = (slice(core[0].start - ext[0].start, core[0].stop - ext[0].start),
                     slice(core[1].start - ext[1].start, core[1].stop - ext[1].start))
            self.zpro[core] = zpro[inner]
            self.slope[core] = slope[inner]
        progress.report(1.0)

    def classify(self, x, y, z) -> np.ndarray:
        """Ground mask: ``|z - ZIpro(x, y)| <= threshold + scalar * slope`` with ZIpro
        interpolated bilinearly between cell centres and the slope of the point's cell."""
        lat, p = self.lattice, self.params
        u, v = lat.local(x, y)
        cu, cv = u - 0.5, v - 0.5  # cell-centre coordinates
        c0 = np.clip(np.floor(cu).astype(np.int64), 0, lat.nx - 2)
        r0 = np.clip(np.floor(cv).astype(np.int64), 0, lat.ny - 2)
        fu = np.clip(cu - c0, 0.0, 1.0)
        fv = np.clip(cv - r0, 0.0, 1.0)
        zp = self.zpro
        z_surface = (zp[r0, c0] * (1 - fu) * (1 - fv) + zp[r0, c0 + 1] * fu * (1 - fv)
                     + zp[r0 + 1, c0] * (1 - fu) * fv + zp[r0 + 1, c0 + 1] * fu * fv)
        col = np.clip(np.floor(u).astype(np.int64), 0, lat.nx - 1)
        row = np.clip(np.floor(v).astype(np.int64), 0, lat.ny - 1)
        nearest = zp[row, col]
        z_surface = np.where(np.isfinite(z_surface), z_surface, nearest)
        slope = np.nan_to_num(self.slope[row, col].astype(np.float64), nan=0.0)
        with np.errstate(invalid="ignore"):
            return np.abs(np.asarray(z, dtype=np.float64) - z_surface) <= (
                p.threshold + p.scalar * slope)


# --------------------------------------------------------------------------------------
# CSF (Zhang et al. 2016) with the reference implementation
# --------------------------------------------------------------------------------------

@contextlib.contextmanager
def _native_stdout_silenced():
    """The CSF library prints progress with std::cout; keep it off our stdout (which
    ``qgis_process --json`` owns)."""
    try:
        sys.stdout.flush()
        saved = os.dup(1)
    except (OSError, ValueError, AttributeError):
        yield
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


_OMP_SET_NUM_THREADS: List = []  # [function or None], looked up once


def _pin_csf_to_one_thread(csf_module) -> None:
    """The CSF wheel's OpenMP loops race (two runs on the same points can give cloths
    differing by 0.1 m); one OpenMP thread makes it deterministic. The wheel bundles its
    own OpenMP runtime, so this touches no other library. OpenMP settings are per
    calling thread (QGIS runs algorithms in worker threads): called before every run."""
    if not _OMP_SET_NUM_THREADS:
        import ctypes
        import glob

        found = None
        here = os.path.dirname(os.path.abspath(csf_module.__file__))
        for pattern in ("cloth_simulation_filter.libs/*omp*", ".dylibs/*omp*",
                        "cloth_simulation_filter/.dylibs/*omp*", "*omp*.dll"):
            for lib in glob.glob(os.path.join(here, pattern)):
                try:
                    found = ctypes.CDLL(lib).omp_set_num_threads
                    break
                except (OSError, AttributeError):
                    continue
            if found is not None:
                break
        _OMP_SET_NUM_THREADS.append(found)
    if _OMP_SET_NUM_THREADS[0] is not None:
        _OMP_SET_NUM_THREADS[0](1)


def _csf_module():
    try:
        import CSF  # PyPI: cloth-simulation-filter
    except ImportError as e:
        raise InputError("The built-in CSF needs the Python package cloth-simulation-filter "
                         "(module CSF): {detail}", detail=str(e))
    _pin_csf_to_one_thread(CSF)
    return CSF


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
    ground, off_ground = CSF.VecInt(), CSF.VecInt()
    with _native_stdout_silenced():
        csf.setPointCloud(np.ascontiguousarray(xyz, dtype=np.float64))
        csf.do_filtering(ground, off_ground, False)
        cloth = csf.do_cloth_export()
    return np.asarray(cloth, dtype=np.float64).reshape(-1, 3)


class _CsfGrid:
    """CSF in three steps, exact to the reference library on the tile's points.

    ``accumulate`` keeps, per cloth node, the point nearest to it: the only point CSF's
    rasterisation uses, so running CSF on these points gives the cloth of the full
    cloud. ``finish`` runs CSF tile by tile (core + buffer), each tile's cloth lattice
    pinned to the world grid by a sentinel point on the node just below-left of the
    tile, which becomes CSF's bounding-box corner. ``classify`` compares points with the
    cloth interpolated as CSF does (``|cloth - z| < threshold``).
    """

    def __init__(self, bounds_xy, z_ref: float, params: CsfParams,
                 tile_size_m: float = 32.0, tile_buffer_m: float = 20.0):
        self.params = params
        self.lattice = _Lattice.covering(bounds_xy, params.resolution)
        shape = (self.lattice.ny, self.lattice.nx)
        self.z_ref = float(z_ref)
        # nearest point per node: offset from the node (in steps) and height above z_ref
        self.rep_du = np.full(shape, np.nan, dtype=np.float32)
        self.rep_dv = np.full(shape, np.nan, dtype=np.float32)
        self.rep_z = np.full(shape, np.nan, dtype=np.float32)
        self.tile_nodes = max(8, int(round(tile_size_m / params.resolution)))
        self.halo_nodes = max(2, int(math.ceil(tile_buffer_m / params.resolution)))
        self.cloth: Optional[np.ndarray] = None
        self.tiles_run = 0

    def accumulate(self, x, y, z) -> None:
        if len(x) == 0:
            return
        u, v = self.lattice.local(x, y)
        col = np.floor(u + 0.5).astype(np.int64)
        row = np.floor(v + 0.5).astype(np.int64)
        self.lattice.check(col, row)
        du = (u - col).astype(np.float32)
        dv = (v - row).astype(np.float32)
        d2 = du * du + dv * dv
        flat = row * self.lattice.nx + col
        pick = _group_first(flat, d2)
        nodes = flat[pick]
        old_du = self.rep_du.ravel()[nodes]
        old_dv = self.rep_dv.ravel()[nodes]
        better = np.isnan(old_du) | (d2[pick] < old_du * old_du + old_dv * old_dv)
        nodes, pick = nodes[better], pick[better]
        self.rep_du.ravel()[nodes] = du[pick]
        self.rep_dv.ravel()[nodes] = dv[pick]
        self.rep_z.ravel()[nodes] = (np.asarray(z, dtype=np.float64)[pick]
                                     - self.z_ref).astype(np.float32)

    def _tile_points(self, ext) -> np.ndarray:
        have = ~np.isnan(self.rep_du[ext])
        rows, cols = np.nonzero(have)
        r_ext, c_ext = ext[0].start, ext[1].start
        step = self.lattice.step
        xs = (cols + c_ext + self.rep_du[ext][have].astype(np.float64)) * step
        ys = (rows + r_ext + self.rep_dv[ext][have].astype(np.float64)) * step
        zs = self.rep_z[ext][have].astype(np.float64)
        # sentinel on the node below-left of the tile: CSF's bbox corner = a world node
        sx, sy = (c_ext - 1) * step, (r_ext - 1) * step
        nearest = int(np.argmin((xs - sx) ** 2 + (ys - sy) ** 2))
        return np.column_stack([np.r_[xs, sx], np.r_[ys, sy], np.r_[zs, zs[nearest]]])

    def finish(self, progress: Progress = SILENT) -> None:
        lat = self.lattice
        self.cloth = np.full((lat.ny, lat.nx), np.nan)
        tiles = list(_tiles(self.cloth.shape, self.tile_nodes, self.halo_nodes))
        for i, (core, ext) in enumerate(tiles):
            progress.report(i / len(tiles))
            if not (~np.isnan(self.rep_du[core])).any():
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
            fill[fill] = np.isnan(self.cloth[rows[fill], cols[fill]])
            self.cloth[rows[in_core], cols[in_core]] = cloth[in_core, 2]
            self.cloth[rows[fill], cols[fill]] = cloth[fill, 2]
        progress.report(1.0)

    def classify(self, x, y, z) -> np.ndarray:
        lat = self.lattice
        u, v = lat.local(x, y)
        c0 = np.clip(np.floor(u).astype(np.int64), 0, lat.nx - 2)
        r0 = np.clip(np.floor(v).astype(np.int64), 0, lat.ny - 2)
        su, sv = u - c0, v - r0
        cz = self.cloth
        surface = (cz[r0, c0] * (1 - su) * (1 - sv) + cz[r0 + 1, c0] * (1 - su) * sv
                   + cz[r0 + 1, c0 + 1] * su * sv + cz[r0, c0 + 1] * su * (1 - sv))
        with np.errstate(invalid="ignore"):
            return np.abs(surface + self.z_ref - np.asarray(z, dtype=np.float64)) < (
                self.params.threshold)


def _make_grid(method: str, params: Params, bounds_xy, z_ref: float,
               tile_size_m: Optional[float], tile_buffer_m: Optional[float]):
    if method == "csf":
        return _CsfGrid(bounds_xy, z_ref, params,
                        tile_size_m=tile_size_m or CSF_TILE_M,
                        tile_buffer_m=CSF_BUFFER_M if tile_buffer_m is None else tile_buffer_m)
    # SMRF's buffer follows from its window (exact results across tiles)
    return _SmrfGrid(bounds_xy, params, tile_size_m=tile_size_m or 1024.0)


def classify_ground_arrays(xyz_world, method: str = "csf", params: Optional[Params] = None,
                           tile_size_m: Optional[float] = None,
                           tile_buffer_m: Optional[float] = None,
                           progress: Progress = SILENT) -> np.ndarray:
    """Ground mask of in-memory points ``(n, 3)`` with the built-in engine (all points
    taken as eligible returns). Same grids and tiles as the file-based run."""
    method = _name_from(method, METHODS, "ground method")
    params = params or default_params(method)
    xyz = np.asarray(xyz_world, dtype=np.float64).reshape(-1, 3)
    if len(xyz) == 0:
        return np.zeros(0, dtype=bool)
    bounds = (xyz[:, 0].min(), xyz[:, 1].min(), xyz[:, 0].max(), xyz[:, 1].max())
    grid = _make_grid(method, params, bounds, float(xyz[:, 2].min()), tile_size_m,
                      tile_buffer_m)
    grid.accumulate(xyz[:, 0], xyz[:, 1], xyz[:, 2])
    grid.finish(progress)
    return grid.classify(xyz[:, 0], xyz[:, 1], xyz[:, 2])


# --------------------------------------------------------------------------------------
# Built-in engine on files (two streaming passes)
# --------------------------------------------------------------------------------------

def _new_classes(classification: np.ndarray, eligible: np.ndarray, ground: np.ndarray,
                 reset_classes: bool) -> np.ndarray:
    cls = np.array(classification, dtype=np.uint8, copy=True)
    if reset_classes:
        cls[:] = UNCLASSIFIED_CLASS
    else:
        cls[eligible & ~ground & (cls == GROUND_CLASS)] = UNCLASSIFIED_CLASS
    cls[ground] = GROUND_CLASS
    return cls


def _builtin_engine(input_path: str, output_path: str, method: str, params: Params,
                    region: Optional[CropRegion], header, out_crs_wkt: Optional[str],
                    reset_classes: bool, chunk_points: int, tile_size_m, tile_buffer_m,
                    progress: Progress) -> Tuple[int, int, List[str]]:
    warnings: List[str] = []
    bounds = (header.mins[0], header.mins[1], header.maxs[0], header.maxs[1])
    if region is not None:
        if region.is_empty:
            bounds = None
        else:
            rb = region.bounds
            bounds = (max(bounds[0], rb[0]), max(bounds[1], rb[1]),
                      min(bounds[2], rb[2]), min(bounds[3], rb[3]))
            if bounds[0] > bounds[2] or bounds[1] > bounds[3]:
                bounds = None
    grid = None
    if bounds is not None and header.point_count > 0:
        grid = _make_grid(method, params, bounds, float(header.mins[2]), tile_size_m,
                          tile_buffer_m)

    def kept(chunk, masks, k):
        if region is None:
            return chunk
        if len(masks) <= k:
            masks.append(np.packbits(region.mask(chunk.x, chunk.y)))
        return chunk[np.unpackbits(masks[k], count=len(chunk)).astype(bool)]

    masks: List[np.ndarray] = []
    n_eligible = 0
    try:
        if grid is not None:
            for k, chunk in enumerate(iter_chunks(input_path, chunk_points,
                                                  progress.sub(0.0, 0.45))):
                pts = kept(chunk, masks, k)
                eligible = returns_mask(pts.return_number, pts.number_of_returns,
                                        params.returns)
                n_eligible += int(eligible.sum())
                grid.accumulate(np.asarray(pts.x)[eligible], np.asarray(pts.y)[eligible],
                                np.asarray(pts.z)[eligible])
            grid.finish(progress.sub(0.45, 0.55))
    except _OutsideGrid as e:
        raise InputError("Cannot read {path}: the file is corrupt ({detail})",
                         path=input_path, detail=str(e))
    n_out = n_ground = 0
    with CloudWriter(output_path, output_header(header, out_crs_wkt)) as writer:
        if grid is not None:
            for k, chunk in enumerate(iter_chunks(input_path, chunk_points,
                                                  progress.sub(0.55, 1.0))):
                pts = kept(chunk, masks, k)
                if len(pts) == 0:
                    continue
                eligible = returns_mask(pts.return_number, pts.number_of_returns,
                                        params.returns)
                ground = np.zeros(len(pts), dtype=bool)
                if n_eligible:
                    ground[eligible] = grid.classify(np.asarray(pts.x)[eligible],
                                                     np.asarray(pts.y)[eligible],
                                                     np.asarray(pts.z)[eligible])
                pts.classification = _new_classes(pts.classification, eligible, ground,
                                                  reset_classes)
                writer.write(pts)
                n_ground += int(ground.sum())
        n_out = writer.point_count
    if n_out and not n_eligible:
        warnings.append(Message("No point of {path} has the returns '{returns}': nothing was "
                                "classified", path=input_path, returns=params.returns))
    return n_out, n_ground, warnings


# --------------------------------------------------------------------------------------
# PDAL engine
# --------------------------------------------------------------------------------------

_PDAL_TYPES = {"i1": "int8", "u1": "uint8", "i2": "int16", "u2": "uint16", "i4": "int32",
               "u4": "uint32", "i8": "int64", "u8": "uint64", "f4": "float", "f8": "double"}


def pdal_extra_dims(header) -> List[str]:
    """``writers.las`` ``extra_dims`` entries (``name=type``) for the extra bytes of a
    header; array dimensions are named as PDAL reads them (``name0``, ``name1``, ...)."""
    entries = []
    for dim in header.point_format.extra_dimensions:
        dtype = np.dtype(dim.dtype)
        base = dtype.base if dtype.subdtype else dtype
        count = int(np.prod(dtype.shape)) if dtype.subdtype else 1
        pdal_type = _PDAL_TYPES.get(base.str.lstrip("<>|="))
        if pdal_type is None:
            continue
        names = [dim.name] if count == 1 else [f"{dim.name}{i}" for i in range(count)]
        entries.extend(f"{n}={pdal_type}" for n in names)
    return entries


def pdal_filter_stage(method: str, params: Optional[Params] = None) -> Dict:
    """The ``filters.csf`` / ``filters.smrf`` stage: every option by its PDAL name."""
    method = _name_from(method, METHODS, "ground method")
    params = params or default_params(method)
    return {"type": f"filters.{method}", **asdict(params)}


def build_pdal_pipeline(input_path: str, output_path: str, method: str = "csf",
                        params: Optional[Params] = None, crop_wkt: Optional[str] = None,
                        crs_wkt: Optional[str] = None, reset_classes: bool = False,
                        extra_dims: Sequence[str] = ()) -> str:
    """PDAL pipeline JSON: ``readers.las -> filters.crop -> filters.csf|smrf ->
    writers.las``, keeping classes (``filters.ferry`` + ``filters.assign``) unless
    ``reset_classes`` (then ``filters.assign`` sets every class to 1 first).

    The writer forwards the whole header, VLRs, scales and offsets (``forward: all``)
    and the input's extra bytes; ``crs_wkt`` overrides the reader's CRS and is written.
    """
    reader = {"type": "readers.las", "filename": input_path}
    if crs_wkt:
        reader["override_srs"] = crs_wkt
    stages: List[Dict] = [reader]
    if crop_wkt:
        stages.append({"type": "filters.crop", "polygon": crop_wkt})
    if reset_classes:
        stages.append({"type": "filters.assign",
                       "value": f"Classification = {UNCLASSIFIED_CLASS}"})
    else:
        stages.append({"type": "filters.ferry",
                       "dimensions": f"Classification => {_KEEP_CLASS_DIM}"})
    stages.append(pdal_filter_stage(method, params))
    if not reset_classes:
        stages.append({"type": "filters.assign", "value": [
            f"Classification = {_KEEP_CLASS_DIM} WHERE Classification == "
            f"{UNCLASSIFIED_CLASS} && {_KEEP_CLASS_DIM} != {GROUND_CLASS}"]})
    writer = {"type": "writers.las", "filename": output_path, "forward": "all"}
    if extra_dims:
        writer["extra_dims"] = ",".join(extra_dims)
    if output_path.lower().endswith(".laz"):
        writer["compression"] = "laszip"
    if crs_wkt:
        writer["a_srs"] = crs_wkt
    stages.append(writer)
    return json.dumps({"pipeline": stages}, indent=2)


def pdal_python_module():
    """The ``pdal`` Python bindings when they import, else ``None``."""
    try:
        import pdal  # noqa: F401
    except Exception:
        return None
    return pdal if hasattr(pdal, "Pipeline") else None


def _qgis_bin_dirs() -> List[str]:
    dirs = []
    prefix = os.environ.get("QGIS_PREFIX_PATH")
    if prefix:
        dirs.append(os.path.join(prefix, "bin"))
    exe_dir = os.path.dirname(sys.executable or "")
    dirs += [exe_dir, os.path.join(sys.prefix, "bin"),
             os.path.normpath(os.path.join(sys.prefix, "..", "..", "bin")),  # OSGeo4W
             os.path.normpath(os.path.join(exe_dir, "..", "bin"))]
    if ".app/Contents" in exe_dir:  # QGIS.app on macOS
        contents = exe_dir[:exe_dir.index(".app/Contents") + len(".app/Contents")]
        dirs += [os.path.join(contents, "MacOS", "bin"), os.path.join(contents, "MacOS")]
    seen, out = set(), []
    for d in dirs:
        if d and d not in seen:
            seen.add(d)
            out.append(d)
    return out


def find_pdal_executable(pdal_executable: Optional[str] = None) -> Optional[str]:
    """A ``pdal`` executable: the given file (or folder holding it), else on PATH, else in
    QGIS's own bin folder; ``None`` when there is none."""
    name = "pdal.exe" if os.name == "nt" else "pdal"
    if pdal_executable:
        path = os.fspath(pdal_executable)
        if os.path.isdir(path):
            path = os.path.join(path, name)
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        raise InputError("PDAL executable {path} not found or not executable", path=path)
    found = shutil.which(name)
    if found:
        return found
    for folder in _qgis_bin_dirs():
        candidate = os.path.join(folder, name)
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return None


def run_pdal_pipeline(pipeline_json: str, executable: Optional[str] = None,
                      progress: Progress = SILENT) -> str:
    """Run a pipeline with the given ``pdal`` executable (``pdal pipeline --stdin``), or
    with the Python module when ``executable`` is ``None``. Returns PDAL's log; raises
    :class:`PdalError` with PDAL's stderr on failure (the process is killed on cancel)."""
    if executable is None:
        pdal = pdal_python_module()
        if pdal is None:
            raise PdalError("The pdal Python module is not available")
        pipeline = pdal.Pipeline(pipeline_json)
        try:
            pipeline.execute()
        except Exception as e:
            log = getattr(pipeline, "log", "") or ""
            raise PdalError(f"PDAL failed: {e}\n{log}".strip(), stderr=f"{e}\n{log}".strip())
        return getattr(pipeline, "log", "") or ""
    proc = subprocess.Popen([executable, "pipeline", "--stdin"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    pending_input: Optional[str] = pipeline_json
    while True:
        try:
            out, err = proc.communicate(pending_input, timeout=0.5)
            break
        except subprocess.TimeoutExpired:
            pending_input = None
            try:
                progress.check()
            except BaseException:
                proc.kill()
                proc.communicate()
                raise
    if proc.returncode != 0:
        err = (err or "").strip()
        raise PdalError(f"PDAL ({executable}) failed with exit status {proc.returncode}: "
                        f"{err or '(no message on stderr)'}", stderr=err)
    return (out or "") + (err or "")


def _count_classes(path: str, chunk_points: int) -> Tuple[int, int]:
    n = ground = 0
    for chunk in iter_chunks(path, chunk_points):
        n += len(chunk)
        ground += int(np.count_nonzero(np.asarray(chunk.classification) == GROUND_CLASS))
    return n, ground


def _pdal_engine(input_path: str, output_path: str, method: str, params: Params,
                 region: Optional[CropRegion], header, crs_wkt: Optional[str],
                 reset_classes: bool, executable: Optional[str], chunk_points: int,
                 progress: Progress) -> Tuple[int, int, str, str]:
    folder = os.path.dirname(os.path.abspath(output_path))
    suffix = os.path.splitext(output_path)[1].lower()
    fd, temp_path = tempfile.mkstemp(prefix=".roadsigns-pdal-", suffix=suffix, dir=folder)
    os.close(fd)
    try:
        pipeline = build_pdal_pipeline(
            input_path, temp_path, method, params,
            crop_wkt=region.wkt if region is not None else None, crs_wkt=crs_wkt,
            reset_classes=reset_classes, extra_dims=pdal_extra_dims(header))
        progress.report(0.0)
        run_pdal_pipeline(pipeline, executable, progress)
        if os.path.getsize(temp_path) == 0:  # PDAL wrote nothing (no point left)
            with CloudWriter(temp_path, output_header(header, crs_wkt)):
                pass
        n_out, n_ground = _count_classes(temp_path, chunk_points)
        os.replace(temp_path, output_path)
    finally:
        if os.path.exists(temp_path):
            os.unlink(temp_path)
    progress.report(1.0)
    return n_out, n_ground, pipeline, "pdal-cli" if executable else "pdal-python"


# --------------------------------------------------------------------------------------
# Entry points
# --------------------------------------------------------------------------------------

def classify_ground(input_path: str, output_path: str, method: str = "csf",
                    engine: str = "auto", params: Optional[Params] = None,
                    region: Optional[CropRegion] = None, crs_wkt: Optional[str] = None,
                    reset_classes: bool = False, pdal_executable: Optional[str] = None,
                    chunk_points: int = DEFAULT_CHUNK_POINTS,
                    tile_size_m: Optional[float] = None,
                    tile_buffer_m: Optional[float] = None,
                    progress: Progress = SILENT) -> GroundResult:
    """Crop ``input_path`` to ``region`` and write it to ``output_path`` with ground as
    class 2, by ``engine`` ("auto", "pdal", "builtin").

    ``crs_wkt`` replaces the file's CRS; without it the file must have one (an error
    otherwise: a CRS is never guessed). Under "auto" a failing PDAL is reported as a
    warning and the built-in engine runs; under "pdal" its :class:`PdalError` is raised.
    """
    input_path = os.fspath(input_path)
    output_path = os.path.abspath(os.fspath(output_path))
    method = _name_from(method, METHODS, "ground method")
    engine = _name_from(engine, ENGINES, "engine")
    params = params or default_params(method)
    if not isinstance(params, CsfParams if method == "csf" else SmrfParams):
        raise InputError("Parameters {params} do not belong to method {method}",
                         params=type(params).__name__, method=method)
    if os.path.splitext(output_path)[1].lower() not in LAS_SUFFIXES:
        raise InputError("Cannot write {path}: the output must end in .las or .laz",
                         path=output_path)
    if os.path.exists(input_path) and os.path.exists(output_path) and os.path.samefile(
            input_path, output_path):
        raise InputError("The output {path} must not be the input file", path=output_path)
    header = read_header(input_path)
    file_crs = crs_wkt_of_header(header)
    if crs_wkt:
        from .crs import parse_crs

        parse_crs(crs_wkt, "point cloud CRS")
    elif not file_crs:
        raise InputError("{path} has no coordinate reference system: give the cloud's CRS "
                         "(it is never guessed)", path=input_path)
    result = GroundResult(output_path, method, "builtin", int(header.point_count), 0, 0,
                          crs_wkt or file_crs)

    if engine in ("auto", "pdal"):
        runner: Optional[Tuple[str, Optional[str]]] = None
        if pdal_executable:
            runner = ("cli", find_pdal_executable(pdal_executable))
        elif pdal_python_module() is not None:
            runner = ("python", None)
        else:
            exe = find_pdal_executable()
            runner = ("cli", exe) if exe else None
        if runner is None:
            if engine == "pdal":
                raise InputError("PDAL was asked for, but neither the pdal Python module nor "
                                 "a pdal executable was found (PATH, QGIS's bin folder)")
            progress.info("PDAL not found: using the built-in engine")
        else:
            try:
                n_out, n_ground, pipeline, used = _pdal_engine(
                    input_path, output_path, method, params, region, header, crs_wkt,
                    reset_classes, runner[1], chunk_points, progress)
                result.n_output, result.n_ground, result.engine = n_out, n_ground, used
                result.pipeline_json = pipeline
                _warn_if_empty(result, input_path, progress)
                return result
            except PdalError as e:
                if engine == "pdal":
                    raise
                result.warnings.append(progress.warning(
                    "PDAL failed, the built-in engine was used instead: {error}", error=str(e)))

    n_out, n_ground, warnings = _builtin_engine(
        input_path, output_path, method, params, region, header, crs_wkt, reset_classes,
        chunk_points, tile_size_m, tile_buffer_m, progress)
    result.n_output, result.n_ground, result.engine = n_out, n_ground, "builtin"
    for w in warnings:
        result.warnings.append(w)
        progress.warning(w)
    _warn_if_empty(result, input_path, progress)
    return result


def _warn_if_empty(result: GroundResult, input_path: str, progress: Progress) -> None:
    if result.n_output == 0:
        result.warnings.append(progress.warning(
            "No point of {path} is left after the crop: {output} has no points",
            path=input_path, output=result.output_path))


def run_ground_filter(input_path: str, output_path: str, method="csf", engine="auto",
                      crop_polygons: Optional[Iterable] = None, crop_buffer_m: float = 0.0,
                      crs_wkt: Optional[str] = None, reset_classes: bool = False,
                      pdal_executable: Optional[str] = None, params: Optional[Params] = None,
                      chunk_points: int = DEFAULT_CHUNK_POINTS,
                      progress: Progress = SILENT) -> GroundResult:
    """The ``roadsigns:groundfilter`` algorithm: crop by polygons (shapely, WKB or WKT in
    the cloud's CRS) grown by ``crop_buffer_m``, then classify ground.

    ``method``: "csf"/"smrf" or the METHOD index; ``engine``: "auto"/"pdal"/"builtin" or
    the ENGINE index.
    """
    region = None
    polygons = list(crop_polygons) if crop_polygons is not None else []
    if polygons:
        region = CropRegion.from_polygons(polygons, crop_buffer_m)
    elif crop_buffer_m:
        progress.info("No crop polygons: the crop buffer is ignored")
    return classify_ground(input_path, output_path, method=method, engine=engine,
                           params=params, region=region, crs_wkt=crs_wkt,
                           reset_classes=reset_classes, pdal_executable=pdal_executable,
                           chunk_points=chunk_points, progress=progress)
