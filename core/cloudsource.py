"""Point clouds as users receive them: one LAS/LAZ file (COPC included), a folder of LAS/LAZ
tiles, or a virtual point cloud (``.vpc``), read as one cloud.

:func:`open_cloud` takes any of these and returns a :class:`CloudSource`: its tiles (a single
file is one tile), its CRS, a header to write points like its own, its point count and
bounds, and chunked reading of the tiles that a bounding box or an area needs.

Conventions:

* **Forms.** A path ending in ``.vpc`` (any case) is a virtual point cloud: a STAC
  ItemCollection (GeoJSON ``FeatureCollection``) as QGIS's *Build virtual point cloud* and
  ``pdal_wrench build_vpc`` write it, each feature a tile whose ``assets`` hold its file
  (``assets.data.href``, else the first asset with an ``href``), relative to the ``.vpc`` or
  absolute; the feature's ``properties`` may give ``proj:wkt2`` / ``proj:projjson`` /
  ``proj:epsg`` (used for a tile whose file records no CRS), ``proj:bbox`` and ``pc:count``
  (not needed: bounds and counts are read from each tile's header, which a stale ``.vpc``
  cannot contradict). A folder is every ``*.las`` / ``*.laz`` in it (any case, not in
  subfolders, hidden files skipped), sorted by name; where QGIS left a ``NAME.copc.laz``
  index beside ``NAME.las`` or ``NAME.laz``, the original is read and the index skipped.
  Anything else is one LAS/LAZ file.
* **One cloud.** The tiles must share the point format (its id and its extra dimensions) and
  the CRS (compared as CRSs, not as text; a tile without a CRS among tiles with one is an
  error). Scales, offsets and LAS versions may differ: coordinates are read as doubles, and
  points written to one file take the first tile's scales and offsets (:func:`conform`).
* **Point indices.** A point's index is its position in the cloud: the points of the tiles
  before its own (in the order above) plus its position in its file. Reads restricted to
  an area give the same indices as a whole read.
* **Restricted reads.** ``bbox_xy`` ``(minx, miny, maxx, maxy)`` and ``area`` (a shapely
  geometry, or a sequence of them) select the tiles whose header bounds meet them; other
  tiles are not opened. A COPC tile is read by the octree nodes that meet them (laspy's COPC
  hierarchy and lazrs), a plain LAS/LAZ tile whole, except where this :class:`CloudSource`
  has read it whole before: it remembers the bounds of every chunk it read (``_ChunkBox``)
  and then reads only the chunks that meet them, seeking past the others (a drive's
  cloud is stored in acquisition order, so a chunk is a short stretch of road). Points
  outside the box or area may still come: callers filter.
* Errors are :class:`~.errors.InputError` naming the file (and the tile) and saying what was
  expected.
"""
from __future__ import annotations

import copy
import json
import math
import os
from dataclasses import dataclass
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import laspy
import numpy as np
import shapely

from .errors import SILENT, InputError, Message, Progress
from .memory import release_freed_memory
from .pointcloud import (
    DEFAULT_CHUNK_POINTS,
    LAS_SUFFIXES,
    CropRegion,
    TiledIndex,
    crs_wkt_of_header,
    damage_named,
    iter_chunks,
    open_reader,
    read_header,
    read_points_at,
)

#: The file name ending of a virtual point cloud.
VPC_SUFFIX = ".vpc"
#: The file name ending of a COPC file (also found by its ``copc`` VLR).
COPC_SUFFIX = ".copc.laz"
#: ``(minx, miny, maxx, maxy)``
BBoxXY = Tuple[float, float, float, float]
#: A geometry, or several, that a restricted read must cover.
Area = Union[Any, Sequence[Any]]

_VPC_EXPECTED = ("expected a virtual point cloud: a JSON FeatureCollection (STAC ItemCollection) whose "
                 "features each have assets.data.href (the tile's file, relative to the .vpc) and properties, "
                 "as QGIS's Build virtual point cloud writes it")
_STAC_EXTENSIONS = ["https://stac-extensions.github.io/pointcloud/v1.0.0/schema.json",
                    "https://stac-extensions.github.io/projection/v1.1.0/schema.json"]


@dataclass(frozen=True)
class Tile:
    """One file of a cloud: ``mins`` / ``maxs`` ``(x, y, z)`` from its header, its point
    count, the cloud index of its first point and whether it is COPC."""

    path: str
    mins: Tuple[float, float, float]
    maxs: Tuple[float, float, float]
    point_count: int
    first_index: int = 0
    copc: bool = False

    @property
    def bounds_xy(self) -> BBoxXY:
        return (self.mins[0], self.mins[1], self.maxs[0], self.maxs[1])

    @property
    def name(self) -> str:
        return os.path.basename(self.path)


# --------------------------------------------------------------------------------------
# Headers, CRSs, point formats
# --------------------------------------------------------------------------------------

_HEADERS: Dict[Tuple[str, int, int], laspy.LasHeader] = {}
_HEADER_CACHE_SIZE = 4096
#: Points read between two returns of the freed heap to the system while a stage walks the
#: cloud (:func:`.memory.release_freed_memory`): each chunk's arrays are freed when the next
#: comes, and without it the heap a pass keeps grows with the number of chunks read.
TRIM_EVERY_POINTS = 2_000_000


def tile_header(path: str) -> laspy.LasHeader:
    """The header of a LAS/LAZ file, read once per version of the file (path, size and
    modification time); callers must not change it (copy it first)."""
    try:
        st = os.stat(path)
    except OSError:
        return read_header(path)  # the error names the file
    key = (os.path.abspath(path), st.st_size, st.st_mtime_ns)
    header = _HEADERS.get(key)
    if header is None:
        header = read_header(path)
        if len(_HEADERS) >= _HEADER_CACHE_SIZE:
            _HEADERS.clear()
        _HEADERS[key] = header
    return header


def is_copc(header: laspy.LasHeader) -> bool:
    """Whether a header has the COPC info record (user id ``copc``, record 1)."""
    return any(getattr(v, "user_id", "") == "copc" and getattr(v, "record_id", None) == 1
               for v in header.vlrs)


def template_header(header: laspy.LasHeader) -> laspy.LasHeader:
    """A copy of ``header`` to write plain LAS/LAZ with: the COPC and LASzip records dropped
    (a file written from it is not COPC; laspy writes its own LASzip record)."""
    out = copy.deepcopy(header)
    drop = ("copc", "laszip encoded")
    out.vlrs = laspy.vlrs.vlrlist.VLRList([v for v in out.vlrs if getattr(v, "user_id", "") not in drop])
    if out.evlrs:
        out.evlrs = laspy.vlrs.vlrlist.VLRList([v for v in out.evlrs
                                                if getattr(v, "user_id", "") not in drop])
    return out


def format_label(header: laspy.LasHeader) -> str:
    """``6``, or ``6 + a (f4), b (u2)`` with extra dimensions: what must agree between tiles."""
    extra = [f"{d.name} ({d.dtype.str.lstrip('<|')})" for d in header.point_format.extra_dimensions]
    fmt = str(header.point_format.id)
    return f"{fmt} + {', '.join(extra)}" if extra else fmt


def crs_label(wkt: Optional[str]) -> str:
    """``EPSG:25833 (ETRS89 / UTM zone 33N)`` or the CRS's name; ``no CRS`` for None."""
    if not wkt:
        return Message("no CRS")
    try:
        import pyproj

        crs = pyproj.CRS.from_user_input(wkt)
        auth = crs.to_authority(min_confidence=90)
        return f"{auth[0]}:{auth[1]} ({crs.name})" if auth else crs.name
    except Exception:
        return wkt[:80]


def same_crs(a: Optional[str], b: Optional[str]) -> bool:
    """Whether two CRSs (WKT or any pyproj input) are the same CRS; None only equals None."""
    if not a or not b:
        return not a and not b
    if a == b:
        return True
    try:
        import pyproj

        ca, cb = pyproj.CRS.from_user_input(a), pyproj.CRS.from_user_input(b)
    except Exception:
        return False
    if ca.equals(cb, ignore_axis_order=True):
        return True
    ea, eb = ca.to_authority(min_confidence=90), cb.to_authority(min_confidence=90)
    return ea is not None and ea == eb


# --------------------------------------------------------------------------------------
# The cloud
# --------------------------------------------------------------------------------------

class CloudSource:
    """A cloud of one or more LAS/LAZ tiles read as one (see the module doc).

    ``path``: what the user gave (a file, a folder or a ``.vpc``); ``kind``: ``"file"``,
    ``"folder"`` or ``"vpc"``; ``tiles``: the :class:`Tile` s in cloud order; ``crs_wkt``:
    the CRS as WKT (None when no tile has one); ``header``: a template for writing points of
    this cloud (the first tile's, COPC records dropped).
    """

    def __init__(self, path: str, kind: str, tiles: List[Tile], headers: List[laspy.LasHeader],
                 crs_wkt: Optional[str]):
        self.path = path
        self.kind = kind
        self.tiles = tiles
        self._headers = headers
        self.crs_wkt = crs_wkt
        self.header = template_header(headers[0])
        #: the chunks of each plain tile read whole by this source: {tile path: chunks}
        self._chunk_boxes: Dict[str, List[_ChunkBox]] = {}

    def __repr__(self) -> str:
        return f"CloudSource({self.path!r}, {self.kind}, {len(self.tiles)} tiles, {self.point_count} points)"

    @property
    def is_single_file(self) -> bool:
        return len(self.tiles) == 1

    @property
    def point_count(self) -> int:
        return sum(t.point_count for t in self.tiles)

    @property
    def bounds(self) -> Tuple[float, float, float, float, float, float]:
        """``(minx, miny, minz, maxx, maxy, maxz)`` over the tiles' header bounds."""
        mins = np.min([t.mins for t in self.tiles], axis=0)
        maxs = np.max([t.maxs for t in self.tiles], axis=0)
        return (float(mins[0]), float(mins[1]), float(mins[2]),
                float(maxs[0]), float(maxs[1]), float(maxs[2]))

    @property
    def bounds_xy(self) -> BBoxXY:
        b = self.bounds
        return (b[0], b[1], b[3], b[4])

    def tile_header(self, k: int) -> laspy.LasHeader:
        """The header of tile ``k`` as read at opening (not to be changed)."""
        return self._headers[k]

    def dimension_names(self) -> List[str]:
        return list(self.header.point_format.dimension_names)

    def check_dimensions(self, dimensions: Sequence[str]) -> None:
        """:class:`InputError` naming the cloud when it lacks one of ``dimensions``."""
        names = set(self.dimension_names())
        missing = [d for d in dimensions if d not in names]
        if missing:
            raise InputError("{path} has no dimension {names} (point format {fmt})", path=self.path,
                             names=", ".join(missing), fmt=self.header.point_format.id)

    # -- selecting tiles ----------------------------------------------------------------

    def tiles_in(self, bbox_xy: Optional[BBoxXY] = None, area: Optional[Area] = None) -> List[Tile]:
        """The tiles whose header bounds meet ``bbox_xy`` and ``area`` (all without them)."""
        boxes = np.array([t.bounds_xy for t in self.tiles], dtype=np.float64).reshape(-1, 4)
        keep = _boxes_meet(boxes, bbox_xy, area)
        return [t for t, k in zip(self.tiles, keep) if k]

    def tile_shares(self, tiles: Sequence[int], progress: Progress) -> Iterator[Tuple[int, Progress]]:
        """Each tile number of ``tiles`` with its share of ``progress``, by point count."""
        total = max(sum(self.tiles[k].point_count for k in tiles), 1)
        done = 0
        for k in tiles:
            n = self.tiles[k].point_count
            yield k, progress.sub(done / total, (done + n) / total)
            done += n

    def points_near_tiles(self, boxes: Dict[int, BBoxXY], chunk_points: int = DEFAULT_CHUNK_POINTS,
                          progress: Progress = SILENT
                          ) -> Iterator[Tuple[int, int, laspy.ScaleAwarePointRecord]]:
        """One read of the tiles ``boxes`` names (tile number: a box around it): for each
        tile ``t``, the points of the *other* tiles ``s`` of ``boxes`` inside ``boxes[t]`` (its
        halo), as ``(s, t, points)`` chunk by chunk. Only tiles whose header bounds meet
        another tile's box are read."""
        near = {s: [t for t, b in boxes.items() if t != s and _box_meets(self.tiles[s].bounds_xy, b)]
                for s in boxes}
        readers = [self.tiles[s] for s in boxes if near[s]]
        if not readers:
            progress.report(1.0)
            return
        for index, chunk in self.iter_indexed_chunks(chunk_points, progress, tiles=readers):
            s = int(self.tile_of_index(index[:1])[0])
            x, y = np.asarray(chunk.x), np.asarray(chunk.y)
            for t in near[s]:
                x0, y0, x1, y1 = boxes[t]
                inside = (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
                if inside.any():
                    yield s, t, chunk[inside]

    def tile_of_index(self, index: np.ndarray) -> np.ndarray:
        """The tile number (position in :attr:`tiles`) of each cloud point index."""
        starts = np.array([t.first_index for t in self.tiles], dtype=np.int64)
        return np.searchsorted(starts, np.asarray(index, dtype=np.int64), side="right") - 1

    # -- reading ------------------------------------------------------------------------

    def iter_indexed_chunks(self, chunk_points: int = DEFAULT_CHUNK_POINTS, progress: Progress = SILENT,
                            bbox_xy: Optional[BBoxXY] = None, area: Optional[Area] = None,
                            tiles: Optional[Sequence[Tile]] = None
                            ) -> Iterator[Tuple[np.ndarray, laspy.ScaleAwarePointRecord]]:
        """``(cloud indices (n,) int64, points)`` chunk by chunk, over the tiles ``bbox_xy``
        and ``area`` need (or the ``tiles`` given); progress over the points read. ``area`` is
        let go once the reads are planned. The heap freed is given back every
        :data:`TRIM_EVERY_POINTS` points."""
        restricted = bbox_xy is not None or area is not None
        chosen = list(tiles) if tiles is not None else self.tiles_in(bbox_xy, area)
        number = {t.path: k for k, t in enumerate(self.tiles)}
        plans: List[Tuple[Tile, Optional[List[Any]]]] = []
        for tile in chosen:
            parts: Optional[List[Any]] = None
            if restricted and tile.copc:
                parts = _copc_nodes(tile, bbox_xy, area)
            elif restricted and tile.path in self._chunk_boxes:
                boxes = self._chunk_boxes[tile.path]
                keep = _boxes_meet(np.array([b.bounds_xy for b in boxes]).reshape(-1, 4), bbox_xy, area)
                parts = [b for b, k in zip(boxes, keep) if k]
            plans.append((tile, parts))
        del area, chosen          # planned: a drive's shapes are not held through the reading
        total = sum(t.point_count if parts is None else sum(n.point_count for n in parts)
                    for t, parts in plans)
        done = since_trim = 0
        progress.report(0.0)
        for tile, parts in plans:
            if parts is None:
                chunks = _plain_chunks(tile, chunk_points, None if tile.copc else self._chunk_boxes)
            elif tile.copc:
                chunks = _copc_chunks(tile, parts, self._headers[number[tile.path]])
            else:
                chunks = _chosen_chunks(tile, parts)
            for index, chunk in chunks:
                done += len(chunk)
                since_trim += len(chunk)
                progress.step("Reading {name}: {done:.1f} of {total:.1f} million points",
                              name=os.path.basename(tile.path), done=done / 1e6, total=total / 1e6)
                yield index, chunk
                del index, chunk
                if since_trim >= TRIM_EVERY_POINTS:
                    release_freed_memory()
                    since_trim = 0
                progress.report(done / total if total else 1.0)
        progress.report(1.0)

    def iter_chunks(self, chunk_points: int = DEFAULT_CHUNK_POINTS, progress: Progress = SILENT,
                    bbox_xy: Optional[BBoxXY] = None, area: Optional[Area] = None
                    ) -> Iterator[laspy.ScaleAwarePointRecord]:
        """The points of the tiles ``bbox_xy`` / ``area`` need, in chunks (laspy
        ``ScaleAwarePointRecord``, as :func:`.pointcloud.iter_chunks` yields them)."""
        for _, chunk in self.iter_indexed_chunks(chunk_points, progress, bbox_xy, area):
            yield chunk

    def index(self, region: Optional[CropRegion] = None,
              dimensions: Sequence[str] = ("intensity", "classification", "gps_time"),
              tile_size_m: float = 25.0, chunk_points: int = DEFAULT_CHUNK_POINTS,
              progress: Progress = SILENT) -> TiledIndex:
        """A :class:`~.pointcloud.TiledIndex` of the points inside ``region`` (all without
        one) with ``dimensions``; only the tiles the region meets are read."""
        self.check_dimensions(dimensions)
        area = None if region is None else region.geometry
        if region is not None and region.is_empty:
            return TiledIndex(np.zeros((0, 3)), np.zeros(0, np.int64),
                              {d: np.zeros(0) for d in dimensions}, tile_size_m, self.crs_wkt)
        return TiledIndex.from_chunks(self.iter_indexed_chunks(chunk_points, progress, area=area),
                                      region, dimensions, tile_size_m, self.crs_wkt)


def grown_box(box: BBoxXY, by_m: float) -> BBoxXY:
    """``box`` grown by ``by_m`` on every side."""
    return (box[0] - by_m, box[1] - by_m, box[2] + by_m, box[3] + by_m)


def _box_meets(a: BBoxXY, b: BBoxXY) -> bool:
    return a[0] <= b[2] and a[2] >= b[0] and a[1] <= b[3] and a[3] >= b[1]


def _boxes_meet(boxes: np.ndarray, bbox_xy: Optional[BBoxXY], area: Optional[Area]) -> np.ndarray:
    """Which 2D boxes ``(n, 4)`` meet ``bbox_xy`` and ``area`` (edges included)."""
    keep = np.ones(len(boxes), dtype=bool)
    if bbox_xy is not None:
        x0, y0, x1, y1 = (float(v) for v in bbox_xy)
        keep &= (boxes[:, 0] <= x1) & (boxes[:, 2] >= x0) & (boxes[:, 1] <= y1) & (boxes[:, 3] >= y0)
    if area is not None and keep.any():
        geoms = [g for g in (area if isinstance(area, (list, tuple, np.ndarray)) else [area])
                 if g is not None and not shapely.is_empty(g)]
        hit = np.zeros(len(boxes), dtype=bool)
        if geoms:
            rows = np.flatnonzero(keep)
            cells = shapely.box(boxes[rows, 0], boxes[rows, 1], boxes[rows, 2], boxes[rows, 3])
            found = shapely.STRtree(geoms).query(cells, predicate="intersects")
            hit[rows[np.unique(found[0])]] = True
        keep &= hit
    return keep


@dataclass
class _ChunkBox:
    """A chunk of a plain tile as it was read: ``first`` (its first point's position in the
    file), ``point_count`` and the 2D bounds of its points."""
    first: int
    point_count: int
    bounds_xy: BBoxXY


def _chunk_bounds(chunk: laspy.ScaleAwarePointRecord) -> BBoxXY:
    """The 2D bounds of a chunk's points, from the stored integers (no scaled copies)."""
    X, Y = np.asarray(chunk.X), np.asarray(chunk.Y)
    sx, sy = (float(v) for v in chunk.scales[:2])
    ox, oy = (float(v) for v in chunk.offsets[:2])
    xs = sorted((int(X.min()) * sx + ox, int(X.max()) * sx + ox))
    ys = sorted((int(Y.min()) * sy + oy, int(Y.max()) * sy + oy))
    return (xs[0], ys[0], xs[1], ys[1])


def _plain_chunks(tile: Tile, chunk_points: int, memo: Optional[Dict[str, List[_ChunkBox]]] = None
                  ) -> Iterator[Tuple[np.ndarray, laspy.ScaleAwarePointRecord]]:
    """The points of a plain tile, whole, in chunks; with ``memo``, the chunks' bounds are
    stored in it under the tile's path once the last chunk has been read."""
    offset = tile.first_index
    boxes: List[_ChunkBox] = []
    for chunk in iter_chunks(tile.path, chunk_points):
        n = len(chunk)
        if memo is not None and n:
            boxes.append(_ChunkBox(offset - tile.first_index, n, _chunk_bounds(chunk)))
        yield np.arange(offset, offset + n, dtype=np.int64), chunk
        offset += n
    if memo is not None:
        memo[tile.path] = boxes


def _chosen_chunks(tile: Tile, chosen: List[_ChunkBox]
                   ) -> Iterator[Tuple[np.ndarray, laspy.ScaleAwarePointRecord]]:
    """The chunks ``chosen`` of a plain tile read whole before: each read after a seek to it
    (lazrs decompresses from the LAZ chunk that holds its first point)."""
    if not chosen:
        return
    with open_reader(tile.path) as reader:
        for box in chosen:
            chunk = read_points_at(reader, tile.path, box.first, box.point_count)
            start = tile.first_index + box.first
            yield np.arange(start, start + len(chunk), dtype=np.int64), chunk


# --------------------------------------------------------------------------------------
# COPC: reading only the octree nodes an area needs
# --------------------------------------------------------------------------------------

@dataclass
class _Node:
    offset: int          # byte offset of its compressed chunk
    byte_size: int
    point_count: int
    first: int           # position of its first point in the file
    bounds_xy: BBoxXY


def _copc_nodes(tile: Tile, bbox_xy: Optional[BBoxXY], area: Optional[Area]) -> Optional[List[_Node]]:
    """The nodes of a COPC tile that meet ``bbox_xy`` / ``area``, with their points' file
    positions; None when the hierarchy cannot be read this way (the tile is then read whole)."""
    try:
        from laspy.copc import load_octree_for_query

        with laspy.CopcReader.open(tile.path) as reader:
            nodes = load_octree_for_query(reader.source, reader.copc_info, reader.root_page)
    except Exception:
        return None
    nodes = sorted((n for n in nodes if n.point_count > 0), key=lambda n: n.offset)
    firsts = np.cumsum([0] + [int(n.point_count) for n in nodes])[:-1]
    if int(sum(int(n.point_count) for n in nodes)) != tile.point_count:
        return None  # not the layout assumed for the positions: read it whole
    out = [_Node(int(n.offset), int(n.byte_size), int(n.point_count), int(f),
                 (float(n.bounds.mins[0]), float(n.bounds.mins[1]), float(n.bounds.maxs[0]),
                  float(n.bounds.maxs[1]))) for n, f in zip(nodes, firsts)]
    if not out:
        return out
    keep = _boxes_meet(np.array([n.bounds_xy for n in out]), bbox_xy, area)
    return [n for n, k in zip(out, keep) if k]


def _copc_chunks(tile: Tile, nodes: List[_Node], header: laspy.LasHeader
                 ) -> Iterator[Tuple[np.ndarray, laspy.ScaleAwarePointRecord]]:
    """The points of ``nodes`` of a COPC tile, one chunk per node."""
    import lazrs

    with open_reader(tile.path):  # the signature and counts checks of any LAS/LAZ read
        pass
    selection = laspy.DecompressionSelection.all().to_lazrs()
    point_size = header.point_format.size
    with laspy.CopcReader.open(tile.path) as reader:
        laszip = reader.laszip_vlr.record_data
        for node in nodes:
            with damage_named(tile.path):
                reader.source.seek(node.offset)
                data = reader.source.read(node.byte_size)
                raw = np.zeros(node.point_count * point_size, dtype=np.uint8)
                lazrs.decompress_points_with_chunk_table(data, laszip, raw, [(node.point_count, node.byte_size)],
                                                         selection)
            packed = laspy.PackedPointRecord.from_buffer(raw, header.point_format)
            points = laspy.ScaleAwarePointRecord(packed.array, header.point_format, header.scales, header.offsets)
            first = tile.first_index + node.first
            yield np.arange(first, first + node.point_count, dtype=np.int64), points


# --------------------------------------------------------------------------------------
# Opening
# --------------------------------------------------------------------------------------

def open_cloud(path: Union[str, "os.PathLike[str]", CloudSource]) -> CloudSource:
    """The cloud at ``path``: a LAS/LAZ file (COPC too), a folder of LAS/LAZ tiles or a
    ``.vpc`` (see the module doc); a :class:`CloudSource` is returned as it is."""
    if isinstance(path, CloudSource):
        return path
    path = os.fspath(path)
    if os.path.isdir(path):
        files = folder_tiles(path)
        return _from_files(path, "folder", [(f, None) for f in files])
    if path.lower().endswith(VPC_SUFFIX):
        return _from_files(path, "vpc", read_vpc(path))
    return _from_files(path, "file", [(path, None)])


def folder_tiles(folder: str) -> List[str]:
    """The LAS/LAZ files of ``folder`` (see the module doc); :class:`InputError` when none."""
    try:
        names = sorted(os.listdir(folder))
    except OSError as e:
        raise InputError("Cannot read the folder {path}: {detail}", path=folder, detail=e.strerror or str(e))
    files = [n for n in names if not n.startswith(".") and n.lower().endswith(LAS_SUFFIXES)
             and os.path.isfile(os.path.join(folder, n))]
    lower = {n.lower() for n in files}
    files = [n for n in files if not (n.lower().endswith(COPC_SUFFIX) and any(
        (n[:-len(COPC_SUFFIX)] + suffix).lower() in lower for suffix in LAS_SUFFIXES))]
    if not files:
        raise InputError("The folder {path} holds no LAS or LAZ file (*.las, *.laz); expected a point cloud "
                         "file, a folder of LAS/LAZ tiles or a virtual point cloud (.vpc)", path=folder)
    return [os.path.join(folder, n) for n in files]


def _crs_of_properties(props: Dict[str, Any]) -> Optional[str]:
    """The CRS a STAC item's ``properties`` give (``proj:wkt2``, ``proj:projjson``,
    ``proj:epsg``), as WKT; None without one."""
    wkt = props.get("proj:wkt2")
    if isinstance(wkt, str) and wkt.strip():
        return wkt
    for key in ("proj:projjson", "proj:epsg"):
        value = props.get(key)
        if value in (None, "", {}):
            continue
        try:
            import pyproj

            crs = pyproj.CRS.from_user_input(json.dumps(value) if isinstance(value, dict) else
                                             f"EPSG:{int(value)}")
            return str(crs.to_wkt())
        except Exception:
            continue
    return None


def read_vpc(path: str) -> List[Tuple[str, Optional[str]]]:
    """``(tile file, CRS the .vpc gives for it or None)`` for each feature of a ``.vpc``."""
    try:
        with open(path, "rb") as f:
            text = f.read()
    except FileNotFoundError:
        raise InputError("Cannot read {path}: the file does not exist", path=path)
    except OSError as e:
        raise InputError("Cannot read {path}: {detail}", path=path, detail=e.strerror or str(e))
    try:
        data = json.loads(text.decode("utf-8-sig"))
    except (UnicodeDecodeError, ValueError) as e:
        raise InputError("Cannot read {path}: it is not valid JSON ({detail}); {expected}", path=path,
                         detail=str(e)[:120], expected=Message(_VPC_EXPECTED))

    expected = Message(_VPC_EXPECTED)
    if not isinstance(data, dict):
        raise InputError("Cannot read {path}: the JSON is not an object; {expected}", path=path, expected=expected)
    features = data.get("features")
    if data.get("type") != "FeatureCollection" or not isinstance(features, list):
        raise InputError("Cannot read {path}: it is not a 'FeatureCollection' with a 'features' list; {expected}",
                         path=path, expected=expected)
    if not features:
        raise InputError("The virtual point cloud {path} lists no tile", path=path)
    base = os.path.dirname(os.path.abspath(path))
    out: List[Tuple[str, Optional[str]]] = []
    seen: Dict[str, int] = {}
    for k, feature in enumerate(features, start=1):
        assets = feature.get("assets") if isinstance(feature, dict) else None
        if not isinstance(assets, dict) or not assets:
            raise InputError("Cannot read {path}: feature {feature} has no 'assets' object; {expected}", path=path,
                             feature=k, expected=expected)
        asset = assets.get("data")
        if not (isinstance(asset, dict) and isinstance(asset.get("href"), str)):
            asset = next((a for a in assets.values() if isinstance(a, dict) and isinstance(a.get("href"), str)
                          and "data" in (a.get("roles") or [])), None) or \
                next((a for a in assets.values() if isinstance(a, dict) and isinstance(a.get("href"), str)), None)
        if asset is None or not asset["href"].strip():
            raise InputError("Cannot read {path}: feature {feature} has no asset with an 'href' (assets.data.href); "
                             "{expected}", path=path, feature=k, expected=expected)
        href = asset["href"].strip()
        if "://" in href and not href.lower().startswith("file://"):
            raise InputError("The virtual point cloud {path} lists the remote tile {href}: only local files are "
                             "read; download the tiles and build the virtual point cloud again", path=path, href=href)
        if href.lower().startswith("file://"):
            href = href[7:]
        tile = os.path.normpath(href if os.path.isabs(href) else os.path.join(base, href))
        if tile in seen:
            raise InputError("The virtual point cloud {path} lists the tile {tile} twice (features {first} and "
                             "{second})", path=path, tile=tile, first=seen[tile], second=k)
        seen[tile] = k
        if not os.path.isfile(tile):
            raise InputError("The virtual point cloud {path} lists the tile {tile} (feature {feature}), which does "
                             "not exist", path=path, tile=tile, feature=k)
        props = feature.get("properties")
        out.append((tile, _crs_of_properties(props) if isinstance(props, dict) else None))
    return out


def _from_files(path: str, kind: str, files: List[Tuple[str, Optional[str]]]) -> CloudSource:
    tiles: List[Tile] = []
    headers: List[laspy.LasHeader] = []
    crss: List[Optional[str]] = []
    first = 0
    for tile_path, listed_crs in files:
        header = tile_header(tile_path)
        if headers and header.point_format != headers[0].point_format:
            raise InputError("The tiles of {path} cannot be read as one cloud: {tile_a} has point format {fmt_a}, "
                             "{tile_b} point format {fmt_b}; every tile needs the same point format (convert "
                             "them to one, e.g. with PDAL's translate)", path=path, tile_a=tiles[0].path,
                             fmt_a=format_label(headers[0]), tile_b=tile_path, fmt_b=format_label(header))
        crs = crs_wkt_of_header(header) or listed_crs
        if crss and not same_crs(crss[0], crs):
            raise InputError("The tiles of {path} are in different CRSs: {tile_a} in {crs_a}, {tile_b} in {crs_b}; "
                             "every tile must be in the same CRS (reproject them to one first)", path=path,
                             tile_a=tiles[0].path, crs_a=crs_label(crss[0]), tile_b=tile_path, crs_b=crs_label(crs))
        count = int(header.point_count)
        lo, hi = [float(v) for v in header.mins], [float(v) for v in header.maxs]
        tiles.append(Tile(tile_path, (lo[0], lo[1], lo[2]), (hi[0], hi[1], hi[2]), count, first, is_copc(header)))
        headers.append(header)
        crss.append(crs)
        first += count
    return CloudSource(path, kind, tiles, headers, crss[0])


# --------------------------------------------------------------------------------------
# Writing points of several tiles to one file, and virtual point clouds
# --------------------------------------------------------------------------------------

def conform(points: laspy.ScaleAwarePointRecord, header: laspy.LasHeader) -> laspy.ScaleAwarePointRecord:
    """``points`` with ``header``'s scales and offsets (the same record when they already
    have them); :class:`InputError` when a coordinate cannot be stored with them."""
    if np.array_equal(points.scales, header.scales) and np.array_equal(points.offsets, header.offsets):
        return points
    out = laspy.ScaleAwarePointRecord.zeros(len(points), header=header)
    for name in points.point_format.dimension_names:
        if name not in ("X", "Y", "Z"):
            out[name] = points[name]
    for axis, big, k in (("x", "X", 0), ("y", "Y", 1), ("z", "Z", 2)):
        raw = np.round((np.asarray(getattr(points, axis), dtype=np.float64) - header.offsets[k])
                       / header.scales[k])
        if raw.size and (raw.min() < np.iinfo(np.int32).min or raw.max() > np.iinfo(np.int32).max):
            raise InputError("The points cannot be written with the first tile's scale {scale} and offset "
                             "{offset} in {axis}: their coordinates are too far from it", scale=header.scales[k],
                             offset=header.offsets[k], axis=axis)
        out[big] = raw.astype(np.int32)
    return out


def _wgs84_ring(bounds_xy: BBoxXY, crs_wkt: Optional[str]) -> Optional[List[List[float]]]:
    if not crs_wkt:
        return None
    try:
        import pyproj

        to_wgs84 = pyproj.Transformer.from_crs(pyproj.CRS.from_user_input(crs_wkt), "EPSG:4326", always_xy=True)
        x0, y0, x1, y1 = bounds_xy
        xs, ys = to_wgs84.transform([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0])
        if not all(math.isfinite(v) for v in list(xs) + list(ys)):
            return None
        return [[float(x), float(y)] for x, y in zip(xs, ys)]
    except Exception:
        return None


def vpc_text(tiles: Sequence[Tuple[str, laspy.LasHeader]], crs_wkt: Optional[str], folder: str) -> str:
    """A virtual point cloud (STAC ItemCollection, as QGIS's *Build virtual point cloud*
    writes it) listing ``tiles`` (file, header) with hrefs relative to ``folder``."""
    features = []
    for tile_path, header in tiles:
        mins, maxs = [float(v) for v in header.mins], [float(v) for v in header.maxs]
        native = [[mins[0], mins[1]], [maxs[0], mins[1]], [maxs[0], maxs[1]], [mins[0], maxs[1]], [mins[0], mins[1]]]
        ring = _wgs84_ring((mins[0], mins[1], maxs[0], maxs[1]), crs_wkt) or native
        lon, lat = [p[0] for p in ring], [p[1] for p in ring]
        href = "./" + os.path.relpath(os.path.abspath(tile_path), os.path.abspath(folder)).replace(os.sep, "/")
        date = header.creation_date
        features.append({
            "type": "Feature", "stac_version": "1.0.0", "stac_extensions": _STAC_EXTENSIONS,
            "id": os.path.splitext(os.path.basename(tile_path))[0],
            "geometry": {"type": "Polygon", "coordinates": [ring]},
            "bbox": [min(lon), min(lat), mins[2], max(lon), max(lat), maxs[2]],
            "properties": {
                "datetime": (f"{date.isoformat()}T00:00:00Z" if date else "1970-01-01T00:00:00Z"),
                "pc:count": int(header.point_count), "pc:type": "lidar", "pc:encoding": "?",
                "pc:schemas": [{"name": d.name, "size": int(d.num_bits // 8 or 1),
                                "type": "floating" if d.kind == laspy.DimensionKind.FloatingPoint else
                                "signed" if d.kind == laspy.DimensionKind.SignedInteger else "unsigned"}
                               for d in header.point_format.dimensions],
                "proj:wkt2": crs_wkt or "",
                "proj:bbox": mins + maxs,
                "proj:geometry": {"type": "Polygon", "coordinates": [native]},
            },
            "links": [],
            "assets": {"data": {"href": href, "roles": ["data"]}},
        })
    return json.dumps({"type": "FeatureCollection", "features": features}, indent=2) + "\n"
