"""LAS/LAZ point clouds larger than memory: chunked reading, faithful writing, crops, an index.

Conventions:

* Coordinates are world coordinates of the cloud's CRS (metres, x = East, y = North,
  z = Up); ``xyz_world`` arrays have shape ``(n, 3)`` and dtype float64.
* Clouds are read in chunks of ``chunk_points`` points (laspy, with the parallel lazrs
  backend for LAZ); nothing here loads a whole file.
* Written files keep the input's point format, version, every dimension, extra bytes,
  VLRs and EVLRs, scales and offsets and the CRS. Output goes to a temporary file in the
  destination folder that replaces the destination only on success (no partial files),
  with the user's normal permissions (0666 less the umask, see :mod:`.outputs`).
* Crops are 2D (x, y): a shapely geometry in the cloud's CRS, points on its boundary kept.
"""
from __future__ import annotations

import contextlib
import copy
import math
import os
import struct
import tempfile
import threading
from dataclasses import dataclass, field
from typing import Callable, Dict, Iterable, Iterator, List, Optional, Sequence, Tuple

import laspy
import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from .errors import SILENT, InputError, Progress
from .outputs import TEMP_PREFIX, set_default_mode
from .writebehind import WriteBehind

#: File name endings read and written as point clouds.
LAS_SUFFIXES = (".las", ".laz")
#: Points per chunk: about 60-100 MB of laspy records for the common point formats.
DEFAULT_CHUNK_POINTS = 1_000_000
#: Points per chunk where refinesigns reads the cloud around its candidates, keeping a small
#: part of each chunk: decoding half the points at a time took 55-69 MB off its peak on 1
#: and 9 km of drive, and no time (projectdetections' peak did not move).
READ_CHUNK_POINTS = 500_000
#: Cell size (m) of the quick inside/outside test of :meth:`CropRegion.mask`.
CROP_CELL_M = 1.0
#: ASPRS LAS classification codes the plugin reads or writes.
UNCLASSIFIED_CLASS = 1
GROUND_CLASS = 2

_NOT_LAS = "Cannot read {path}: expected a LAS or LAZ file ({detail})"
#: What damaged files make laspy and lazrs raise: any Exception, and lazrs's Rust panics,
#: which pyo3 raises as ``PanicException``, a BaseException.
_READ_ERRORS = BaseException
_NOT_READ_ERRORS = (KeyboardInterrupt, SystemExit, GeneratorExit)
_CORRUPT = "Cannot read {path}: the file is truncated or corrupt ({detail})"


# --------------------------------------------------------------------------------------
# Reading
# --------------------------------------------------------------------------------------

def laz_backends() -> Tuple[laspy.LazBackend, ...]:
    """Available LAZ backends, the parallel lazrs one first."""
    return tuple(laspy.LazBackend.detect_available())


def _check_signature(path: str) -> None:
    try:
        with open(path, "rb") as f:
            signature = f.read(4)
    except FileNotFoundError:
        raise InputError("Cannot read {path}: the file does not exist", path=path)
    except OSError as e:
        raise InputError("Cannot read {path}: {detail}", path=path, detail=str(e))
    if signature != b"LASF":
        raise InputError(_NOT_LAS, path=path,
                         detail="no LASF signature; is it another format?")
    _check_vlr_count(path)


#: Bytes of a VLR's header: a VLR count that cannot fit before the points is damage.
_VLR_HEADER_BYTES = 54


def _check_vlr_count(path: str) -> None:
    """Header counts that damage makes absurd, checked before laspy and lazrs read them: a
    VLR count that cannot fit between the header and the points (laspy would try to read
    billions of VLRs and hang), and a LAZ chunk count beyond the points or the file (lazrs
    would try to allocate it and abort the whole process, QGIS with it)."""
    try:
        size = os.path.getsize(path)
        with open(path, "rb") as f:
            head = f.read(375)
            if len(head) < 227:
                raise InputError(_CORRUPT, path=path, detail="the header is cut short")
            header_size, offset_to_points, n_vlrs = struct.unpack_from("<HII", head, 94)
            if n_vlrs * _VLR_HEADER_BYTES > max(offset_to_points - header_size, 0):
                raise InputError(_CORRUPT, path=path, detail=f"the header announces {n_vlrs} VLRs, "
                                 "more than fit before the points")
            if not head[104] & 0xC0:  # not compressed
                return
            n_points = struct.unpack_from("<I", head, 107)[0]
            if head[25] >= 4 and len(head) >= 255:  # LAS 1.4: the 64-bit count
                n_points = max(n_points, struct.unpack_from("<Q", head, 247)[0])
            f.seek(offset_to_points)
            table_offset = struct.unpack("<q", f.read(8).rjust(8, b"\xff"))[0]
            if table_offset == -1:  # written at the very end by writers that cannot seek back
                f.seek(max(size - 8, 0))
                table_offset = struct.unpack("<q", f.read(8).rjust(8, b"\xff"))[0]
            if 0 < table_offset <= size - 8:
                f.seek(table_offset)
                _, n_chunks = struct.unpack("<II", f.read(8))
                if n_chunks > min(n_points + 1, size):
                    raise InputError(_CORRUPT, path=path, detail=f"the LAZ chunk table announces "
                                     f"{n_chunks} chunks for {n_points} points")
    except OSError as e:
        raise InputError("Cannot read {path}: {detail}", path=path, detail=str(e))
    except struct.error:
        raise InputError(_CORRUPT, path=path, detail="the header is cut short")


@contextlib.contextmanager
def damage_named(path: str) -> Iterator[None]:
    """What damaged files make laspy and lazrs raise inside the block (any Exception, and
    lazrs's Rust panics) as :class:`InputError` naming ``path``."""
    try:
        yield
    except InputError:
        raise
    except _READ_ERRORS as e:  # laspy raises LaspyException, ValueError, struct.error, ...
        if isinstance(e, _NOT_READ_ERRORS):
            raise
        raise InputError(_CORRUPT, path=path, detail=f"{type(e).__name__}: {e}")


def open_reader(path: str) -> laspy.LasReader:
    """Open a LAS/LAZ file for chunked reading; :class:`InputError` when it is not one.

    The caller closes the reader (``with open_reader(p) as r: ...``).
    """
    path = os.fspath(path)
    _check_signature(path)
    with damage_named(path):
        return laspy.open(path, mode="r", laz_backend=laz_backends())


def read_header(path: str) -> laspy.LasHeader:
    """The header of a LAS/LAZ file (VLRs and EVLRs included)."""
    with open_reader(path) as reader:
        return copy.deepcopy(reader.header)


def crs_wkt_of_header(header: laspy.LasHeader) -> Optional[str]:
    """The CRS in a header's WKT or GeoTIFF records as WKT, ``None`` when there is none."""
    try:
        crs = header.parse_crs()
    except Exception:
        crs = None
    if crs is not None:
        return crs.to_wkt()
    # A WKT record pyproj could not parse is still the file's CRS: hand it on verbatim.
    for vlr_list in (header.vlrs, header.evlrs or []):
        for vlr in vlr_list:
            if isinstance(vlr, laspy.vlrs.known.WktCoordinateSystemVlr) and vlr.string:
                return vlr.string.strip("\x00").strip() or None
    return None


def read_crs_wkt(path: str) -> Optional[str]:
    """The CRS of a LAS/LAZ file as WKT, or ``None`` when the file has none (never guessed)."""
    return crs_wkt_of_header(read_header(path))


def iter_chunks(path: str, chunk_points: int = DEFAULT_CHUNK_POINTS,
                progress: Progress = SILENT) -> Iterator[laspy.ScaleAwarePointRecord]:
    """Yield the points of a LAS/LAZ file in chunks (laspy ``ScaleAwarePointRecord``).

    Reports progress as the fraction of points read; a truncated or corrupt file raises
    :class:`InputError` naming it.
    """
    path = os.fspath(path)
    with open_reader(path) as reader:
        total = reader.header.point_count
        done = 0
        progress.report(0.0)
        iterator = reader.chunk_iterator(max(1, int(chunk_points)))
        while True:
            with damage_named(path):
                chunk = next(iterator, None)
            if chunk is None or len(chunk) == 0:
                break
            done += len(chunk)
            yield chunk
            progress.report(done / total if total else 1.0)
        if done < total:
            raise InputError(_CORRUPT, path=path,
                             detail=f"header announces {total} points, {done} could be read")


def read_points_at(reader: laspy.LasReader, path: str, first: int, count: int
                   ) -> laspy.ScaleAwarePointRecord:
    """``count`` points from position ``first`` of the file ``path`` open in ``reader``
    (seeking there unless the reader is there already; a LAZ is decompressed from the start
    of the LAZ chunk holding ``first``); :class:`InputError` naming the file when it is
    damaged or shorter."""
    with damage_named(path):
        if reader.points_read != first:
            reader.seek(first)
        chunk = reader.read_points(count)
    if len(chunk) != count:
        raise InputError(_CORRUPT, path=path, detail=f"{count} points expected from point {first}, "
                         f"{len(chunk)} could be read")
    return chunk


def xyz_of(points) -> np.ndarray:
    """World coordinates ``(n, 3)`` float64 of a laspy point record."""
    return np.column_stack([np.asarray(points.x, dtype=np.float64),
                            np.asarray(points.y, dtype=np.float64),
                            np.asarray(points.z, dtype=np.float64)])


# --------------------------------------------------------------------------------------
# Writing
# --------------------------------------------------------------------------------------

def _crs_vlr_names() -> Tuple[str, ...]:
    return ("WktCoordinateSystemVlr", "GeoKeyDirectoryVlr", "GeoAsciiParamsVlr",
            "GeoDoubleParamsVlr")


def output_header(template: laspy.LasHeader, crs_wkt: Optional[str] = None) -> laspy.LasHeader:
    """A header for writing points like ``template``'s, optionally with another CRS.

    Everything of the template is kept (version, point format, extra bytes, scales,
    offsets, VLRs, EVLRs, ids, dates); counts and bounds are recomputed by the writer.
    With ``crs_wkt`` the CRS records are replaced (WKT for point formats >= 6, GeoTIFF
    keys otherwise, as laspy writes them).
    """
    header = copy.deepcopy(template)
    if crs_wkt:
        import pyproj  # only needed when a CRS is assigned

        crs = pyproj.CRS.from_user_input(crs_wkt)
        try:
            header.add_crs(crs)
        except Exception:  # GeoTIFF keys cannot express it: store the WKT record
            header.vlrs.append(laspy.vlrs.known.WktCoordinateSystemVlr(crs.to_wkt()))
            if header.version.minor >= 4:
                header.global_encoding.wkt = True
        if header.evlrs:
            names = _crs_vlr_names()
            header.evlrs = laspy.vlrs.vlrlist.VLRList([v for v in header.evlrs
                                          if type(v).__name__ not in names])
    return header


class CloudWriter:
    """Write a LAS/LAZ file in chunks; the destination appears only on :meth:`commit`.

    Points go to a temporary file in the destination folder, which ``commit`` moves over
    the destination with ``os.replace`` after giving it the umask's permissions (not
    mkstemp's 0600); ``abort`` (or leaving a ``with`` block by an exception) deletes it.
    LAZ when the path ends in ``.laz`` (lazrs, parallel). ``background``: each chunk is
    written (compressed) on a thread of its own while the caller prepares the next
    (:class:`.writebehind.WriteBehind`: in order, one at a time, errors raised by the next
    :meth:`write` or by :meth:`commit`); a chunk given to :meth:`write` must not change after.
    """

    def __init__(self, output_path: str, header: laspy.LasHeader, background: bool = True):
        self.output_path = os.path.abspath(os.fspath(output_path))
        suffix = os.path.splitext(self.output_path)[1].lower()
        if suffix not in LAS_SUFFIXES:
            raise InputError("Cannot write {path}: the output must end in .las or .laz",
                             path=self.output_path)
        folder = os.path.dirname(self.output_path)
        if not os.path.isdir(folder):
            raise InputError("Cannot write {path}: the folder does not exist",
                             path=self.output_path)
        self.compress = suffix == ".laz"
        self._evlrs = header.evlrs
        try:
            fd, self.temp_path = tempfile.mkstemp(prefix=TEMP_PREFIX, suffix=suffix, dir=folder)
        except OSError as e:
            raise InputError("Cannot write {path}: {error}", path=self.output_path,
                             error=e.strerror or str(e))
        self._file = os.fdopen(fd, "wb")
        self.point_count = 0
        self._behind = WriteBehind("roadsigns-las-write") if background else None
        try:
            self._writer = laspy.LasWriter(
                self._file, header, do_compress=self.compress,
                laz_backend=laz_backends() if self.compress else None, closefd=False)
        except Exception:
            if self._behind is not None:
                self._behind.abandon()
            self._file.close()
            os.unlink(self.temp_path)
            raise

    @property
    def header(self) -> laspy.LasHeader:
        return self._writer.header

    def write(self, points) -> None:
        """Append a point record (same point format as the header)."""
        if len(points):
            if self._behind is not None:
                self._behind.submit(self._writer.write_points, points)
            else:
                self._writer.write_points(points)
            self.point_count += len(points)

    def commit(self) -> None:
        """Finish the file and move it to the destination."""
        if self._writer is None:
            return
        try:
            if self._behind is not None:
                self._behind.close()
            if self._evlrs and self._writer.header.version.minor >= 4:
                self._writer.write_evlrs(self._evlrs)
            self._writer.close()
            self._file.close()
            set_default_mode(self.temp_path)
            os.replace(self.temp_path, self.output_path)
        except BaseException:
            self.abort()
            raise
        self._writer = None

    def abort(self) -> None:
        """Drop the temporary file; the destination is left untouched."""
        if self._behind is not None:
            self._behind.abandon()
        self._writer = None
        try:
            self._file.close()
        except Exception:
            pass
        if os.path.exists(self.temp_path):
            os.unlink(self.temp_path)

    def __enter__(self) -> "CloudWriter":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is None:
            self.commit()
        else:
            self.abort()


# --------------------------------------------------------------------------------------
# Crops
# --------------------------------------------------------------------------------------

#: geometries are buffered a block at a time before the union: GEOS buffers one multipoint
#: of thousands of stations slowly and through a heap of about a gigabyte that the process
#: keeps (7,392 stations of a 9 km drive at 25 m: 15 s and 1.2 GB); blocks of 16 give the
#: same polygon in 0.8 s and 48 MB
BUFFER_BLOCK = 16


def buffered_union(geometries: Sequence[BaseGeometry], buffer_m: float) -> BaseGeometry:
    """The union of ``geometries`` grown by ``buffer_m`` metres (the buffer of their union),
    buffered :data:`BUFFER_BLOCK` parts at a time, in the order given (keep neighbours
    together, as stations in drive order are)."""
    parts = shapely.get_parts(np.asarray(geometries, dtype=object))
    if not buffer_m:
        return shapely.union_all(parts)
    blocks = [shapely.union_all(parts[i:i + BUFFER_BLOCK]).buffer(float(buffer_m))
              for i in range(0, len(parts), BUFFER_BLOCK)]
    return shapely.union_all(blocks)


def _as_geometry(item) -> BaseGeometry:
    if isinstance(item, BaseGeometry):
        return item
    if isinstance(item, (bytes, bytearray, memoryview)):
        return shapely.from_wkb(bytes(item))
    if isinstance(item, str):
        return shapely.from_wkt(item)
    raise InputError("Cannot use {item!r} as a crop geometry: expected a shapely geometry, "
                     "WKB or WKT", item=type(item).__name__)


class CropRegion:
    """A 2D crop area (shapely geometry in the cloud's CRS) tested on many points at once.

    Points inside or on the boundary are kept. Build it with :meth:`from_polygons` or
    :meth:`corridor`; ``mask(x, y)`` is vectorised (a bounding-box test, then shapely's
    prepared ``intersects_xy`` on the rest).
    """

    def __init__(self, geometry: BaseGeometry):
        self.geometry = shapely.make_valid(geometry) if not geometry.is_valid else geometry
        shapely.prepare(self.geometry)
        self.bounds = tuple(self.geometry.bounds) if not self.geometry.is_empty else None
        self._owner = threading.get_ident()
        self._copies = threading.local()

    def _geometry_here(self) -> BaseGeometry:
        """The region's geometry for the calling thread. A GEOS prepared geometry builds its
        indexes lazily and is not thread-safe (libgeos/geos#825: two threads testing points
        against it at once can crash), so a thread other than the one that built the region
        tests against its own prepared copy, made once (and let go with the thread)."""
        if threading.get_ident() == self._owner:
            return self.geometry
        mine = getattr(self._copies, "geometry", None)
        if mine is None:
            mine = self._copies.geometry = shapely.from_wkb(shapely.to_wkb(self.geometry))
            shapely.prepare(mine)
        return mine

    @classmethod
    def from_polygons(cls, polygons: Iterable, buffer_m: float = 0.0) -> "CropRegion":
        """The union of polygons (shapely, WKB or WKT), grown by ``buffer_m`` metres."""
        geoms = [_as_geometry(p) for p in polygons]
        geoms = [g for g in geoms if g is not None and not g.is_empty]
        if not geoms:
            raise InputError("The crop layer has no geometry")
        return cls(buffered_union([shapely.make_valid(g) for g in geoms], buffer_m))

    @classmethod
    def corridor(cls, buffer_m: float, points_xy=None, lines_xy: Sequence = ()) -> "CropRegion":
        """Everything within ``buffer_m`` metres of stations ``points_xy`` ``(n, 2+)`` and/or
        polylines ``lines_xy`` (each ``(m, 2+)``: a trajectory, detection rays, ...)."""
        if not buffer_m or buffer_m <= 0:
            raise InputError("A corridor needs a positive buffer, got {buffer_m} m",
                             buffer_m=buffer_m)
        parts: List[BaseGeometry] = []
        if points_xy is not None and len(points_xy):
            pts = np.asarray(points_xy, dtype=float)[:, :2]
            parts.extend(shapely.points(pts))
        for line in lines_xy:
            xy = np.asarray(line, dtype=float)[:, :2]
            parts.append(shapely.linestrings(xy) if len(xy) >= 2 else shapely.points(xy[0]))
        if not parts:
            raise InputError("A corridor needs stations or lines")
        return cls(buffered_union(parts, buffer_m))

    @property
    def is_empty(self) -> bool:
        return self.bounds is None

    def mask(self, x, y) -> np.ndarray:
        """Boolean mask of the points ``(x, y)`` inside (or on the edge of) the region.

        Exact, and fast on large regions (the frusta of a whole drive): the points' cells of
        :data:`CROP_CELL_M` are classified first (cell inside the region: its points are in;
        cell apart from it: out), and only points in cells that the boundary crosses are
        tested one by one. No cells or points are cached, so memory does not grow with the
        region. Safe to call from several threads at once: each thread other than the
        region's own keeps a prepared copy of the region (:meth:`_geometry_here`)."""
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        inside = np.zeros(x.shape, dtype=bool)
        if self.bounds is None:
            return inside
        xmin, ymin, xmax, ymax = self.bounds
        candidates = np.flatnonzero((x >= xmin) & (x <= xmax) & (y >= ymin) & (y <= ymax))
        if not candidates.size:
            return inside
        cx = np.floor((x[candidates] - xmin) / CROP_CELL_M).astype(np.int64)
        cy = np.floor((y[candidates] - ymin) / CROP_CELL_M).astype(np.int64)
        cells, cell_of_point = np.unique(cx * (1 << 31) + cy, return_inverse=True)
        i, j = cells // (1 << 31), cells % (1 << 31)
        boxes = shapely.box(xmin + i * CROP_CELL_M, ymin + j * CROP_CELL_M,
                            xmin + (i + 1) * CROP_CELL_M, ymin + (j + 1) * CROP_CELL_M)
        geometry = self._geometry_here()
        cell_inside = shapely.contains(geometry, boxes)
        cell_crossed = shapely.intersects(geometry, boxes) & ~cell_inside
        whole, crossed = cell_inside[cell_of_point], cell_crossed[cell_of_point]
        inside[candidates[whole]] = True
        test = candidates[crossed]
        if test.size:
            inside[test] = shapely.intersects_xy(geometry, x[test], y[test])
        return inside

    @property
    def wkt(self) -> str:
        return self.geometry.wkt


@dataclass
class CropResult:
    output_path: str
    n_input: int
    n_output: int
    crs_wkt: Optional[str]
    warnings: List[str] = field(default_factory=list)


def crop_cloud(input_path: str, output_path: str, region: Optional[CropRegion] = None,
               crs_wkt: Optional[str] = None, chunk_points: int = DEFAULT_CHUNK_POINTS,
               progress: Progress = SILENT) -> CropResult:
    """Copy the points of ``input_path`` inside ``region`` (all of them with ``None``) to
    ``output_path`` in one streaming pass, keeping everything of the file.

    ``crs_wkt`` replaces the file's CRS; a cloud with no CRS and none given is an error.
    An empty result is a warning and a valid file with no points.
    """
    header = read_header(input_path)
    crs = crs_wkt or crs_wkt_of_header(header)
    if not crs:
        raise InputError("{path} has no coordinate reference system and none was given",
                         path=input_path)
    result = CropResult(output_path, int(header.point_count), 0, crs)
    with CloudWriter(output_path, output_header(header, crs_wkt)) as writer:
        for chunk in iter_chunks(input_path, chunk_points, progress):
            if region is not None:
                chunk = chunk[region.mask(chunk.x, chunk.y)]
            writer.write(chunk)
        result.n_output = writer.point_count
    if result.n_output == 0:
        result.warnings.append(progress.warning(
            "No point of {path} lies inside the crop area; {output} is empty",
            path=input_path, output=output_path))
    return result


# --------------------------------------------------------------------------------------
# Spatial index over a cropped cloud
# --------------------------------------------------------------------------------------

@dataclass
class PointSet:
    """Points returned by a query: ``xyz_world`` ``(n, 3)``, named attributes ``(n,)`` and
    ``point_index`` (position in the source file or input arrays), sorted by that index."""
    xyz_world: np.ndarray
    point_index: np.ndarray
    attributes: Dict[str, np.ndarray]

    def __len__(self) -> int:
        return len(self.point_index)

    def subset(self, mask) -> "PointSet":
        return PointSet(self.xyz_world[mask], self.point_index[mask],
                        {k: v[mask] for k, v in self.attributes.items()})


class TiledIndex:
    """Points of a (cropped) cloud in square tiles of ``tile_size_m`` with KD-trees built
    lazily per tile, for box, radius, cone and free-predicate queries.

    Only the points kept by the crop are stored (float64 xyz, int64 index, the requested
    attributes), so memory grows with the crop, not with the input file.
    """

    def __init__(self, xyz_world: np.ndarray, point_index: np.ndarray,
                 attributes: Optional[Dict[str, np.ndarray]] = None,
                 tile_size_m: float = 25.0, crs_wkt: Optional[str] = None):
        xyz_world = np.asarray(xyz_world, dtype=np.float64).reshape(-1, 3)
        self.tile_size_m = float(tile_size_m)
        if not self.tile_size_m > 0:
            raise ValueError("tile_size_m must be positive")
        self.crs_wkt = crs_wkt
        attributes = dict(attributes or {})
        # the points in tile order (column i, then row j; stable within a tile), by one int64
        # key a point: what is built on the way is ~16 bytes a point besides the sorted copy
        i = np.floor(xyz_world[:, 0] / self.tile_size_m).astype(np.int64)
        j = np.floor(xyz_world[:, 1] / self.tile_size_m).astype(np.int64)
        i0, j0 = (int(i.min()), int(j.min())) if len(i) else (0, 0)
        rows_j = int(j.max()) - j0 + 1 if len(j) else 1
        key = (i - i0) * rows_j + (j - j0)
        del i, j
        order = np.argsort(key, kind="stable")
        key = key[order]
        self.xyz_world = xyz_world[order]
        self.point_index = np.asarray(point_index, dtype=np.int64)[order]
        self.attributes = {k: np.asarray(v)[order] for k, v in attributes.items()}
        del order
        self._ranges: Dict[Tuple[int, int], Tuple[int, int]] = {}
        if len(key):
            starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
            ends = np.r_[starts[1:], len(key)]
            for s, e, k in zip(starts.tolist(), ends.tolist(), key[starts].tolist()):
                self._ranges[(i0 + k // rows_j, j0 + k % rows_j)] = (s, e)
        self._trees: Dict[Tuple[int, int], object] = {}

    # -- construction ------------------------------------------------------------------

    @classmethod
    def from_arrays(cls, xyz_world, attributes: Optional[Dict[str, np.ndarray]] = None,
                    region: Optional[CropRegion] = None, tile_size_m: float = 25.0,
                    crs_wkt: Optional[str] = None) -> "TiledIndex":
        """Index in-memory points (``point_index`` = row number), optionally cropped."""
        xyz_world = np.asarray(xyz_world, dtype=np.float64).reshape(-1, 3)
        keep = np.ones(len(xyz_world), bool) if region is None else region.mask(
            xyz_world[:, 0], xyz_world[:, 1])
        attrs = {k: np.asarray(v)[keep] for k, v in (attributes or {}).items()}
        return cls(xyz_world[keep], np.flatnonzero(keep), attrs, tile_size_m, crs_wkt)

    @classmethod
    def from_las(cls, path: str, region: Optional[CropRegion] = None,
                 dimensions: Sequence[str] = ("intensity", "classification", "gps_time"),
                 tile_size_m: float = 25.0, chunk_points: int = DEFAULT_CHUNK_POINTS,
                 progress: Progress = SILENT) -> "TiledIndex":
        """Index the points of one LAS/LAZ file inside ``region`` (streaming read). Tiles and
        virtual point clouds: :meth:`.cloudsource.CloudSource.index`."""
        header = read_header(path)
        names = set(header.point_format.dimension_names)
        missing = [d for d in dimensions if d not in names]
        if missing:
            raise InputError("{path} has no dimension {names} (point format {fmt})", path=path,
                             names=", ".join(missing), fmt=header.point_format.id)

        def indexed() -> Iterator[Tuple[np.ndarray, laspy.ScaleAwarePointRecord]]:
            offset = 0
            for chunk in iter_chunks(path, chunk_points, progress):
                yield np.arange(offset, offset + len(chunk), dtype=np.int64), chunk
                offset += len(chunk)

        return cls.from_chunks(indexed(), region, dimensions, tile_size_m, crs_wkt_of_header(header))

    @classmethod
    def from_chunks(cls, chunks: Iterable[Tuple[np.ndarray, laspy.ScaleAwarePointRecord]],
                    region: Optional[CropRegion] = None,
                    dimensions: Sequence[str] = ("intensity", "classification", "gps_time"),
                    tile_size_m: float = 25.0, crs_wkt: Optional[str] = None) -> "TiledIndex":
        """Index ``(point indices, points)`` chunks, keeping the points inside ``region``."""
        xyz_parts, index_parts = [], []
        attr_parts: Dict[str, List[np.ndarray]] = {d: [] for d in dimensions}
        for index, chunk in chunks:
            keep = (np.ones(len(chunk), bool) if region is None
                    else region.mask(chunk.x, chunk.y))
            kept = chunk[keep] if region is not None else chunk
            xyz_parts.append(xyz_of(kept))
            index_parts.append(np.asarray(index, dtype=np.int64)[keep])
            for d in dimensions:
                attr_parts[d].append(np.array(kept[d]))
        xyz = np.concatenate(xyz_parts) if xyz_parts else np.zeros((0, 3))
        index_all = np.concatenate(index_parts) if index_parts else np.zeros(0, np.int64)
        attrs = {d: (np.concatenate(p) if p else np.zeros(0)) for d, p in attr_parts.items()}
        del xyz_parts, index_parts, attr_parts
        return cls(xyz, index_all, attrs, tile_size_m, crs_wkt)

    # -- introspection -----------------------------------------------------------------

    def __len__(self) -> int:
        return len(self.point_index)

    @property
    def nbytes(self) -> int:
        """Memory held by the stored points (trees not counted)."""
        return (self.xyz_world.nbytes + self.point_index.nbytes
                + sum(v.nbytes for v in self.attributes.values()))

    @property
    def tile_keys(self) -> List[Tuple[int, int]]:
        return sorted(self._ranges)

    def tile_rows(self, key: Tuple[int, int]) -> Tuple[int, int]:
        """``(start, end)``: the rows of tile ``key`` (column, row) in the stored arrays, so
        ``xyz_world[start:end]`` is its points as a view (``(0, 0)`` for an empty tile)."""
        return self._ranges.get(key, (0, 0))

    # -- queries -----------------------------------------------------------------------

    def _tiles_in(self, xy_min, xy_max) -> Iterator[Tuple[Tuple[int, int], int, int]]:
        t = self.tile_size_m
        i0, j0 = (int(math.floor(v / t)) for v in xy_min[:2])
        i1, j1 = (int(math.floor(v / t)) for v in xy_max[:2])
        if (i1 - i0 + 1) * (j1 - j0 + 1) > len(self._ranges):
            keys = (k for k in self._ranges if i0 <= k[0] <= i1 and j0 <= k[1] <= j1)
        else:
            keys = ((i, j) for i in range(i0, i1 + 1) for j in range(j0, j1 + 1))
        for key in keys:
            r = self._ranges.get(key)
            if r is not None:
                yield key, r[0], r[1]

    def _gather(self, rows: List[np.ndarray]) -> PointSet:
        rows_all = np.concatenate(rows) if rows else np.zeros(0, np.int64)
        rows_all = rows_all[np.argsort(self.point_index[rows_all], kind="stable")]
        return PointSet(self.xyz_world[rows_all], self.point_index[rows_all],
                        {k: v[rows_all] for k, v in self.attributes.items()})

    def query_box(self, min_xyz, max_xyz) -> PointSet:
        """Points with ``min <= xyz <= max`` (use +-inf in z for a 2D box)."""
        lo = np.asarray(min_xyz, dtype=float)
        hi = np.asarray(max_xyz, dtype=float)
        rows = []
        for _, s, e in self._tiles_in(lo, hi):
            p = self.xyz_world[s:e]
            m = np.all((p >= lo) & (p <= hi), axis=1)
            rows.append(s + np.flatnonzero(m))
        return self._gather(rows)

    def query_predicate(self, min_xyz, max_xyz,
                        predicate: Callable[[np.ndarray], np.ndarray]) -> PointSet:
        """Points in the box ``[min, max]`` for which ``predicate(xyz_world) -> bool mask``
        holds (a frustum, a slab, ...); the box bounds the tiles visited."""
        lo = np.asarray(min_xyz, dtype=float)
        hi = np.asarray(max_xyz, dtype=float)
        rows = []
        for _, s, e in self._tiles_in(lo, hi):
            p = self.xyz_world[s:e]
            inside = np.flatnonzero(np.all((p >= lo) & (p <= hi), axis=1))
            if inside.size:
                keep = np.asarray(predicate(p[inside]), dtype=bool)
                rows.append(s + inside[keep])
        return self._gather(rows)

    def _tree(self, key, s, e):
        tree = self._trees.get(key)
        if tree is None:
            from scipy.spatial import cKDTree

            tree = cKDTree(self.xyz_world[s:e])
            self._trees[key] = tree
        return tree

    def query_radius(self, center_xyz, radius_m: float) -> PointSet:
        """Points within ``radius_m`` (3D distance) of ``center_xyz`` (tile KD-trees)."""
        c = np.asarray(center_xyz, dtype=float)
        rows = []
        for key, s, e in self._tiles_in(c - radius_m, c + radius_m):
            hits = self._tree(key, s, e).query_ball_point(c, radius_m)
            if hits:
                rows.append(s + np.asarray(hits, dtype=np.int64))
        return self._gather(rows)

    def query_cone(self, apex_xyz, direction, half_angle_deg: float,
                   max_range_m: float, min_range_m: float = 0.0) -> PointSet:
        """Points seen from ``apex_xyz`` within ``half_angle_deg`` of ``direction`` and at
        a distance in ``[min_range_m, max_range_m]`` (a frustum-like cone around a ray)."""
        a = np.asarray(apex_xyz, dtype=float)
        d = np.asarray(direction, dtype=float)
        d = d / np.linalg.norm(d)
        cos_max = math.cos(math.radians(half_angle_deg))

        def inside(p: np.ndarray) -> np.ndarray:
            v = p - a
            dist = np.linalg.norm(v, axis=1)
            along = v @ d
            return (dist >= min_range_m) & (dist <= max_range_m) & (along >= cos_max * dist)

        return self.query_predicate(a - max_range_m, a + max_range_m, inside)
