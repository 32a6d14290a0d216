"""The entry points of ground classification and the built-in engine on files.

Conventions:

* Methods and engines are names (:data:`~.params.METHODS`, :data:`~.params.ENGINES`).
* The input is any cloud :func:`~..cloudsource.open_cloud` reads: a LAS/LAZ file, a folder
  of tiles or a virtual point cloud, written as one file with the first tile's header, scales
  and offsets (:func:`~..cloudsource.conform`), or one file per tile (:mod:`.tiled`). PDAL
  takes tiles one by one with a halo of their neighbours' points (:mod:`.pdal_tiles`).
* Which engine runs: :func:`pdal_runner_for`; ``"auto"`` follows :data:`~.params.AUTO_ENGINES`
  (the engine measured faster for the method: today the built-in one for both).
* The built-in engine makes two passes and never holds the cloud in memory: pass 1 reads
  the cloud into the method's grid and keeps its (cropped) points uncompressed in a
  :class:`PointSpool` beside the output, pass 2 classifies and writes them, so a LAZ is
  decompressed once (where the disk has no room for the spool, pass 2 reads the cloud
  again). Chunks are read in one thread and cropped, taken and classified in a pool of
  :data:`CHUNK_THREADS`; the grid takes them and the writer writes them in reading order,
  so the output is the same with any number of threads. The output goes through
  :class:`~..pointcloud.CloudWriter` (a temporary file moved into place on success).
* A cloud wider or longer than a block (``block_m``, :data:`~.lattice.BLOCK_M`: a drive) goes
  block by block instead (:mod:`.blocks`): read once into a spool cut by block, then each
  block's grid over the block and its halo, so that no grid holds the drive; the classes are
  those of one grid, the output's points grouped by block. ``block_m=None``: one grid over
  the whole cloud, the points in their order.
* Ground is class 2 (:data:`~..pointcloud.GROUND_CLASS`); only the ``returns`` of the
  parameters are classified, the other points keep their class.
* Log messages are :class:`~..errors.Message` templates, reported through ``progress``.
"""
from __future__ import annotations

import contextlib
import os
import tempfile
from dataclasses import dataclass, field
from functools import partial
from typing import Any, Callable, Dict, Iterable, Iterator, List, Optional, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike

from ..cloudsource import CloudSource, conform, open_cloud
from ..drivewindows import Spool, map_in_order
from ..errors import SILENT, InputError, Message, Progress
from ..pointcloud import (
    DEFAULT_CHUNK_POINTS,
    LAS_SUFFIXES,
    CloudWriter,
    CropRegion,
    iter_chunks,
    output_header,
)
from .blocks import BlockPlan, classify_by_blocks
from .csf import csf_available
from .gridsteps import CHUNK_THREADS, classified, cropped, eligible_xyz, make_grid
from .lattice import BLOCK_M, BoundsXY, GroundGrid, OutsideGridError
from .params import AUTO_ENGINES, Params, engine_name, method_name, method_params
from .pdal import PdalError, PdalRunner, find_pdal_runner, run_pdal_engine


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


def classify_ground_arrays(xyz_world: ArrayLike, method: str = "csf", params: Optional[Params] = None,
                           tile_size_m: Optional[float] = None,
                           tile_buffer_m: Optional[float] = None,
                           progress: Progress = SILENT) -> np.ndarray:
    """Ground mask of in-memory points ``(n, 3)`` with the built-in engine (all points
    taken as eligible returns). Same grids and tiles as the file-based run."""
    params = method_params(method_name(method), params)
    xyz = np.asarray(xyz_world, dtype=np.float64).reshape(-1, 3)
    if len(xyz) == 0:
        return np.zeros(0, dtype=bool)
    bounds = (xyz[:, 0].min(), xyz[:, 1].min(), xyz[:, 0].max(), xyz[:, 1].max())
    grid = make_grid(params, bounds, float(xyz[:, 2].min()), tile_size_m, tile_buffer_m)
    grid.accumulate(xyz[:, 0], xyz[:, 1], xyz[:, 2])
    grid.finish(progress)
    return grid.classify(xyz[:, 0], xyz[:, 1], xyz[:, 2])


# --------------------------------------------------------------------------------------
# Built-in engine on files (two streaming passes)
# --------------------------------------------------------------------------------------

def grid_bounds(bounds_xy: BoundsXY, region: Optional[CropRegion]) -> Optional[BoundsXY]:
    """The part of ``bounds_xy`` a grid must cover: within the crop region's bounds; None when
    nothing is left."""
    if region is None:
        return bounds_xy
    rb = region.bounds
    if rb is None:  # an empty region
        return None
    xmin, ymin, xmax, ymax = bounds_xy
    out = (max(xmin, rb[0]), max(ymin, rb[1]), min(xmax, rb[2]), min(ymax, rb[3]))
    return None if out[0] > out[2] or out[1] > out[3] else out


#: Free disk space kept beyond a spool's size (bytes).
SPOOL_DISK_SLACK_BYTES = 512 * 1024 * 1024


def room_to_spool(n_points: int, point_size_bytes: int, folder: str) -> bool:
    """Whether ``folder`` has room for ``n_points`` uncompressed records of ``point_size_bytes``
    (a :class:`PointSpool`; a crop only makes it smaller) and some slack."""
    import shutil

    try:
        free = shutil.disk_usage(folder).free
    except OSError:
        return False
    return free >= int(n_points) * int(point_size_bytes) + SPOOL_DISK_SLACK_BYTES


class PointSpool:
    """The points pass 1 of the built-in engine read, kept uncompressed for pass 2 in a hidden
    temporary folder inside ``folder`` (beside the output), so the cloud is decompressed once;
    written in the background while pass 1 decompresses the next chunk.

    :meth:`add` takes each chunk (conformed to ``header``'s scales and offsets); :meth:`chunks`
    gives them back in order as laspy records of ``header``'s point format, deleting each file
    once read. A context manager: the folder is removed on exit, whatever happened.
    """

    KIND = "points"

    def __init__(self, header: Any, folder: str):
        self.header = header
        self.spool = Spool({self.KIND: header.point_format.dtype()}, folder=folder, prefix=".roadsigns-ground-",
                           background=True)
        self.n_chunks = 0

    def add(self, points: Any) -> None:
        self.spool.append(self.KIND, self.n_chunks, conform(points, self.header).array)
        self.n_chunks += 1

    def chunks(self, progress: Progress = SILENT) -> Iterator[Any]:
        import laspy

        h = self.header
        for k in range(self.n_chunks):
            progress.check()
            progress.step("Classifying and writing the points: part {n} of {count}", n=k + 1, count=self.n_chunks)
            rows = self.spool.read(self.KIND, k)
            self.spool.discard(self.KIND, k)
            yield laspy.ScaleAwarePointRecord(rows, h.point_format, h.scales, h.offsets)
            progress.report((k + 1) / self.n_chunks)

    def __enter__(self) -> "PointSpool":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self.spool.close()


#: What a ground filter's ``read`` yields: a chunk of laspy records, or a function without
#: arguments that returns one (its crop, run in :func:`two_passes`' pool).
ChunkSource = Union[Any, Callable[[], Any]]


def two_passes(read: Callable[[Progress, bool], Iterable[ChunkSource]], grid: GroundGrid, params: Params,
               reset_classes: bool, writer: CloudWriter, spool_folder: Optional[str], progress: Progress,
               add_to_grid: Optional[Callable[[GroundGrid], None]] = None,
               threads: Optional[int] = None) -> Tuple[int, int]:
    """The built-in engine's two passes over one cloud (or tile) into ``writer``:
    ``(eligible points, ground points)``.

    Pass 1 reads ``read(progress, again)`` (:data:`ChunkSource` items: chunks of laspy
    records, cropped, or the functions that crop them) into ``grid``, then
    ``add_to_grid(grid)`` (a tile's halo), and keeps the points in a :class:`PointSpool`
    in ``spool_folder`` (None: no room on the disk, and ``again`` tells ``read`` that the
    cloud is read a second time); pass 2 classifies them (from the spool, or ``read`` again)
    and writes them. The chunks are read in this thread and worked on ``threads`` at a time
    (default :data:`CHUNK_THREADS`; :func:`~..drivewindows.map_in_order`); the grid takes them
    and the writer writes them in reading order, so the output does not depend on ``threads``.
    :class:`~.lattice.OutsideGridError` comes from pass 1 only."""
    threads = CHUNK_THREADS if threads is None else threads

    def taken(item: ChunkSource) -> Tuple[Any, np.ndarray, np.ndarray, np.ndarray]:
        pts = item() if callable(item) else item
        _, x, y, z = eligible_xyz(pts, params)
        return pts, x, y, z

    with PointSpool(writer.header, spool_folder) if spool_folder else contextlib.nullcontext() as spool:
        n_eligible = n_ground = 0
        reading = progress.sub(0.0, 0.45)
        for pts, x, y, z in map_in_order(taken, read(reading, spool is None), threads, reading.check):
            n_eligible += len(x)
            grid.accumulate(x, y, z)
            if spool is not None:
                spool.add(pts)
            del pts, x, y, z
        if add_to_grid is not None:
            add_to_grid(grid)
        grid.finish(progress.sub(0.45, 0.55))
        writing = progress.sub(0.55, 1.0)
        second = spool.chunks(writing) if spool is not None else read(writing, True)

        def classify(item: ChunkSource) -> Tuple[Any, int]:
            pts = item() if callable(item) else item
            if not len(pts):
                return pts, 0
            pts, n = classified(pts, grid, params, reset_classes, classify=n_eligible > 0)
            return conform(pts, writer.header), n

        for pts, n in map_in_order(classify, second, threads, writing.check):
            if len(pts):
                writer.write(pts)
                n_ground += n
            del pts
    return n_eligible, n_ground


def _builtin_engine(source: CloudSource, output_path: str, params: Params,
                    region: Optional[CropRegion], header: Any, out_crs_wkt: Optional[str],
                    reset_classes: bool, chunk_points: int, tile_size_m: Optional[float],
                    tile_buffer_m: Optional[float], block_m: Optional[float],
                    progress: Progress) -> Tuple[int, int, List[str]]:
    """The built-in engine into ``output_path``: one grid over the cloud in two passes
    (:func:`two_passes`), or block by block (:mod:`.blocks`) when the cloud is larger than
    ``block_m`` and its points can be spooled. ``(points written, ground points, warnings)``."""
    warnings: List[str] = []
    bounds = grid_bounds(source.bounds_xy, region)
    area = None if region is None else region.geometry
    out_header = output_header(header, out_crs_wkt)
    spool_folder = os.path.dirname(output_path)
    has_work = bounds is not None and source.point_count > 0
    room = has_work and room_to_spool(source.point_count, header.point_format.size, spool_folder)
    run: Optional[Callable[[CloudWriter], Tuple[int, int]]] = None
    if room and block_m and bounds is not None and max(bounds[2] - bounds[0], bounds[3] - bounds[1]) > block_m:
        run = partial(_run_blocks, source, BlockPlan(params, bounds, block_m, tile_size_m, tile_buffer_m),
                      params, region, area, reset_classes, chunk_points, spool_folder, progress)
    elif has_work and bounds is not None:
        grid = make_grid(params, bounds, float(source.bounds[2]), tile_size_m, tile_buffer_m)
        if not room:
            progress.info("Not enough free disk space in {folder} to keep the points between the two passes: "
                          "the cloud is read twice", folder=spool_folder)
        run = partial(_run_two_passes, source, grid, params, region, area, reset_classes, chunk_points,
                      spool_folder if room else None, progress)
    n_eligible = n_ground = 0
    with CloudWriter(output_path, out_header) as writer:
        if run is not None:
            try:
                n_eligible, n_ground = run(writer)
            except OutsideGridError as e:
                raise InputError("Cannot read {path}: the file is corrupt ({detail})",
                                 path=source.path, detail=str(e))
        n_out = writer.point_count
    if n_out and not n_eligible:
        warnings.append(Message("No point of {path} has the returns '{returns}': nothing was "
                                "classified", path=source.path, returns=params.returns))
    return n_out, n_ground, warnings


def _run_two_passes(source: CloudSource, grid: GroundGrid, params: Params, region: Optional[CropRegion],
                    area: Any, reset_classes: bool, chunk_points: int, spool_folder: Optional[str],
                    progress: Progress, writer: CloudWriter) -> Tuple[int, int]:
    """One grid over the whole cloud (:func:`two_passes`), the cloud read twice when
    ``spool_folder`` is None: ``(eligible points, ground points)``."""
    # the crop of each chunk by its first point's cloud index, when the cloud is read a second
    # time (which may skip chunks wholly outside the area: CloudSource remembers chunk bounds)
    masks: Dict[int, np.ndarray] = {}

    def read(reading: Progress, again: bool) -> Iterator[ChunkSource]:
        """The chunks inside the region (the functions that crop them); with ``again``, each
        chunk's mask is kept for (or taken from) the second read."""
        for index, chunk in source.iter_indexed_chunks(chunk_points, reading, area=area):
            if region is None:
                yield chunk
            elif not again:
                yield partial(cropped, chunk, region)
            else:
                yield partial(crop_again, int(index[0]) if len(index) else -1, chunk)

    def crop_again(key: int, chunk: Any) -> Any:
        """``chunk`` cropped, its mask kept under ``key`` for the second read (or taken)."""
        assert region is not None
        if key not in masks:
            masks[key] = np.packbits(region.mask(chunk.x, chunk.y))
        return chunk[np.unpackbits(masks[key], count=len(chunk)).astype(bool)]

    return two_passes(read, grid, params, reset_classes, writer, spool_folder, progress)


def _run_blocks(source: CloudSource, plan: BlockPlan, params: Params, region: Optional[CropRegion],
                area: Any, reset_classes: bool, chunk_points: int, spool_folder: str, progress: Progress,
                writer: CloudWriter) -> Tuple[int, int]:
    """Block by block (:func:`.blocks.classify_by_blocks`; ``area``: the region's shape, which
    chooses the tiles and chunks read): ``(eligible points, ground points)``."""
    def read(reading: Progress) -> Iterator[Any]:
        for _, chunk in source.iter_indexed_chunks(chunk_points, reading, area=area):
            yield chunk

    return classify_by_blocks(read, plan, params, float(source.bounds[2]), reset_classes, writer, spool_folder,
                              chunk_points, region, progress)


# --------------------------------------------------------------------------------------
# Entry points
# --------------------------------------------------------------------------------------

def classify_ground(input_path: Union[str, CloudSource], output_path: str, method: str = "csf",
                    engine: str = "auto", params: Optional[Params] = None,
                    region: Optional[CropRegion] = None, crs_wkt: Optional[str] = None,
                    reset_classes: bool = False, pdal_executable: Optional[str] = None,
                    chunk_points: int = DEFAULT_CHUNK_POINTS,
                    tile_size_m: Optional[float] = None,
                    tile_buffer_m: Optional[float] = None,
                    block_m: Optional[float] = BLOCK_M,
                    progress: Progress = SILENT) -> GroundResult:
    """Crop the cloud ``input_path`` (a LAS/LAZ file, a folder of tiles or a ``.vpc``) to
    ``region`` and write it to ``output_path`` with ground as class 2, by ``engine``
    ("auto", "pdal", "builtin").

    ``crs_wkt`` replaces the file's CRS; without it the file must have one (an error
    otherwise: a CRS is never guessed). Which engine runs: :func:`pdal_runner_for`. When
    PDAL runs under "auto" and fails, the failure is a warning and the built-in engine runs
    (if it can run the method); under "pdal" its :class:`PdalError` is raised. The built-in
    engine works a cloud larger than ``block_m`` metres block by block (:mod:`.blocks`; None:
    one grid over the whole cloud).
    """
    output_path = os.path.abspath(os.fspath(output_path))
    method = method_name(method)
    engine = engine_name(engine)
    params = method_params(method, params)
    if os.path.splitext(output_path)[1].lower() not in LAS_SUFFIXES:
        raise InputError("Cannot write {path}: the output must end in .las or .laz",
                         path=output_path)
    source = open_cloud(input_path if isinstance(input_path, CloudSource) else os.fspath(input_path))
    input_path = source.path
    for tile in source.tiles:
        if os.path.exists(output_path) and os.path.samefile(tile.path, output_path):
            raise InputError("The output {path} must not be the input file", path=output_path)
    header = source.header
    file_crs = source.crs_wkt
    if crs_wkt:
        from ..crs import parse_crs

        parse_crs(crs_wkt, "point cloud CRS")
    elif not file_crs:
        raise InputError("{path} has no coordinate reference system: give the cloud's CRS "
                         "(it is never guessed)", path=input_path)
    result = GroundResult(output_path, method, "builtin", int(source.point_count), 0, 0,
                          crs_wkt or file_crs)

    runner = pdal_runner_for(engine, method, pdal_executable, progress)
    if runner is not None:
        try:
            if source.is_single_file:
                n_out, n_ground, pipeline, used = run_pdal_engine(
                    source.tiles[0].path, output_path, method, params, region, source.tile_header(0),
                    crs_wkt, reset_classes, runner.executable, chunk_points, progress)
            else:
                n_out, n_ground, pipeline, used = _pdal_tiles_into_one(
                    source, output_path, method, params, region, crs_wkt, reset_classes,
                    runner.executable, chunk_points, progress)
            result.n_output, result.n_ground, result.engine = n_out, n_ground, used
            result.pipeline_json = pipeline
            _warn_if_empty(result, input_path, progress)
            return result
        except PdalError as e:
            if engine == "pdal" or not builtin_available(method):
                raise
            result.warnings.append(progress.warning(
                "PDAL failed, the built-in engine was used instead: {error}", error=str(e)))

    n_out, n_ground, warnings = _builtin_engine(
        source, output_path, params, region, header, crs_wkt, reset_classes,
        chunk_points, tile_size_m, tile_buffer_m, block_m, progress)
    result.n_output, result.n_ground, result.engine = n_out, n_ground, "builtin"
    for w in warnings:
        result.warnings.append(w)
        progress.warning(w)
    _warn_if_empty(result, input_path, progress)
    return result


def builtin_available(method: str) -> bool:
    """Whether the built-in engine can run ``method`` here: CSF needs the Python package
    cloth-simulation-filter (module ``CSF``), SMRF nothing beyond numpy and scipy."""
    return method_name(method) != "csf" or csf_available()


def pdal_runner_for(engine: str, method: str, pdal_executable: Optional[str] = None,
                    progress: Progress = SILENT) -> Optional[PdalRunner]:
    """How to run PDAL for ``engine`` and ``method``, or ``None`` for the built-in engine.

    * "pdal": PDAL; :class:`InputError` when neither the bindings nor a ``pdal`` application is found;
    * "builtin": ``None``;
    * "auto": the engine :data:`~.params.AUTO_ENGINES` names for the method (the measured faster
      one); when that is the built-in engine but it cannot run the method here
      (:func:`builtin_available`), PDAL if found; when it is PDAL but PDAL is not found, the
      built-in engine. The log says which and why.
    """
    if engine == "builtin":
        return None
    if engine == "auto" and AUTO_ENGINES[method] == "builtin":
        if builtin_available(method):
            progress.info("Auto: the built-in engine, measured faster than PDAL for {method} (and it streams "
                          "the cloud in bounded memory)", method=method.upper())
            return None
        runner = find_pdal_runner(pdal_executable)
        if runner is not None:
            progress.info("Auto: PDAL, as the built-in {method} needs the Python package "
                          "cloth-simulation-filter, which is not installed", method=method.upper())
        return runner  # None: the built-in engine then says what is missing
    runner = find_pdal_runner(pdal_executable)
    if runner is None:
        if engine == "pdal":
            raise InputError("PDAL was asked for, but neither the pdal Python module nor "
                             "a pdal executable was found (PATH, QGIS's bin folder)")
        progress.info("PDAL not found: using the built-in engine")
    elif engine == "auto":
        progress.info("Auto: PDAL, measured faster than the built-in engine for {method}", method=method.upper())
    return runner


def _pdal_tiles_into_one(source: CloudSource, output_path: str, method: str, params: Params,
                         region: Optional[CropRegion], crs_wkt: Optional[str], reset_classes: bool,
                         executable: Optional[str], chunk_points: int,
                         progress: Progress) -> Tuple[int, int, str, str]:
    """The tiles of ``source`` through PDAL one by one with their halos (:mod:`.pdal_tiles`),
    gathered into ``output_path`` with the first tile's header, scales and offsets
    (:func:`~..cloudsource.conform`); ``(points, ground points, pipeline JSON, engine)``."""
    from .pdal_tiles import run_pdal_tiles

    area = None if region is None else region.geometry
    met = {t.path for t in source.tiles_in(area=area)}
    work = [k for k, t in enumerate(source.tiles) if t.point_count and t.path in met]
    n_ground = 0
    with tempfile.TemporaryDirectory(prefix=".roadsigns-pdal-tiles-", dir=os.path.dirname(output_path)) as folder:
        counts, pipeline, used = run_pdal_tiles(
            source, work, lambda k: os.path.join(folder, f"tile_{k}.las"), method, params, region, crs_wkt,
            reset_classes, executable, chunk_points, progress.sub(0.0, 0.8))
        gather = progress.sub(0.8, 1.0)
        with CloudWriter(output_path, output_header(source.header, crs_wkt)) as writer:
            for i, k in enumerate(work):
                gather.report(i / max(len(work), 1))
                if counts[k][0]:
                    for chunk in iter_chunks(os.path.join(folder, f"tile_{k}.las"), chunk_points):
                        writer.write(conform(chunk, writer.header))
                n_ground += counts[k][1]
            n_out = writer.point_count
    return n_out, n_ground, pipeline, used


def _warn_if_empty(result: GroundResult, input_path: str, progress: Progress) -> None:
    if result.n_output == 0:
        result.warnings.append(progress.warning(
            "No point of {path} is left after the crop: {output} has no points",
            path=input_path, output=result.output_path))


def crop_region(crop_polygons: Optional[Iterable[Any]], crop_buffer_m: float,
                progress: Progress = SILENT) -> Optional[CropRegion]:
    """The crop region of polygons (shapely, WKB or WKT) grown by ``crop_buffer_m``; None
    without polygons."""
    polygons = list(crop_polygons) if crop_polygons is not None else []
    if polygons:
        return CropRegion.from_polygons(polygons, crop_buffer_m)
    if crop_buffer_m:
        progress.info("No crop polygons: the crop buffer is ignored")
    return None


def run_ground_filter(input_path: Union[str, CloudSource], output_path: str, method: str = "csf", engine: str = "auto",
                      crop_polygons: Optional[Iterable[Any]] = None, crop_buffer_m: float = 0.0,
                      crs_wkt: Optional[str] = None, reset_classes: bool = False,
                      pdal_executable: Optional[str] = None, params: Optional[Params] = None,
                      chunk_points: int = DEFAULT_CHUNK_POINTS, block_m: Optional[float] = BLOCK_M,
                      progress: Progress = SILENT) -> GroundResult:
    """The ``roadsigns:groundfilter`` algorithm: crop by polygons (shapely, WKB or WKT in
    the cloud's CRS) grown by ``crop_buffer_m``, then classify ground.

    ``method``: a name of :data:`METHODS` ("csf", "smrf"); ``engine``: a name of
    :data:`ENGINES` ("auto", "pdal", "builtin"). Anything else (a list index included)
    raises :class:`InputError`.
    """
    region = crop_region(crop_polygons, crop_buffer_m, progress)
    return classify_ground(input_path, output_path, method=method, engine=engine,
                           params=params, region=region, crs_wkt=crs_wkt,
                           reset_classes=reset_classes, pdal_executable=pdal_executable,
                           chunk_points=chunk_points, block_m=block_m, progress=progress)
