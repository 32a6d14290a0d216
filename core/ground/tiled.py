"""Ground classification tile by tile: one output tile per input tile, and a virtual point
cloud listing them (``roadsigns:groundfilter`` with ``OUTPUT_TILES``).

Each input tile is classified with the built-in engine on a grid over the tile and a halo
around it (:func:`tile_grid`), so that its points get the classes a run on the whole cloud
gives them, and written alone, with its own header, scales and offsets, under its own file
name:

* SMRF: the tile grown by SMRF's halo (the morphology's reach; SMRF's result does not
  depend on its tiling, so the classes are those of the whole cloud);
* CSF: the cloth is simulated in squares of ``CSF_TILE_M`` with a buffer, on a lattice that
  starts at the cloud's corner. The grid of a tile is cut from that same lattice, whole
  squares of it: those holding the tile's points, and enough around them for their
  buffers. Every square of the tile then sees the points it sees in a whole-cloud run and
  gets the same cloth.

Passes over the cloud, memory bounded by one tile and its halo:

0. one read of the tiles that have neighbours: the eligible points (returns) of each within
   the halo of another tile are spooled to that tile's file in a temporary folder;
1. per tile: its own points and its spooled halo into the grid; the grid's ground surface;
2. per tile: its points classified and written.

The output folder appears whole or not at all: tiles and the ``.vpc`` are written into a
temporary folder beside it, moved into place at the end (:class:`~..outputs.StagedOutputs`).
Input tiles without a point inside the crop area give no output tile (the log says so).
When PDAL runs (``engine="pdal"``, or Auto choosing it: :func:`.engine.pdal_runner_for`),
each tile goes through PDAL alone with its neighbours' points around it (:mod:`.pdal_tiles`).
"""
from __future__ import annotations

import os
import tempfile
from functools import partial
from typing import Any, Dict, Iterable, Iterator, List, Optional, Tuple, Union

import numpy as np

from ..cloudsource import BBoxXY, CloudSource, Tile, grown_box, open_cloud, template_header, vpc_text
from ..errors import SILENT, InputError, Progress
from ..outputs import StagedOutputs, remove
from ..pointcloud import DEFAULT_CHUNK_POINTS, CloudWriter, CropRegion, output_header, read_header
from .csf import CsfParams
from .engine import (
    ChunkSource,
    GroundResult,
    builtin_available,
    crop_region,
    grid_bounds,
    pdal_runner_for,
    room_to_spool,
    two_passes,
)
from .gridsteps import cropped, eligible_xyz, make_grid, tile_grid
from .lattice import OutsideGridError, on_lattice
from .params import Params, engine_name, grid_step_m, method_name, method_params
from .pdal import PdalError

#: Spooled halo points: world coordinates only (the grids need nothing else).
_HALO_DTYPE = np.dtype([("x", "f8"), ("y", "f8"), ("z", "f8")])


def output_tile_names(source: CloudSource, folder: str) -> List[str]:
    """One output file per tile, named as it; :class:`InputError` when two tiles share a name
    or the output folder holds an input tile (it is replaced as a whole)."""
    names: Dict[str, str] = {}
    folder = os.path.abspath(folder)
    for tile in source.tiles:
        if os.path.commonpath([os.path.abspath(tile.path), folder]) == folder:
            raise InputError("The output folder {folder} holds the input tile {tile}: choose another folder "
                             "(the output folder is replaced as a whole)", folder=folder, tile=tile.path)
        if tile.name.lower() in names:
            raise InputError("Two tiles of {path} have the same file name, {name} ({first} and {second}): the "
                             "output tiles are named as the input tiles, so their names must differ",
                             path=source.path, name=tile.name, first=names[tile.name.lower()], second=tile.path)
        names[tile.name.lower()] = tile.path
    return [t.name for t in source.tiles]


def classify_ground_tiles(input_path: Union[str, CloudSource], output_folder: str, vpc_name: str,
                          method: str = "csf", engine: str = "builtin", params: Optional[Params] = None,
                          region: Optional[CropRegion] = None, crs_wkt: Optional[str] = None,
                          reset_classes: bool = False, chunk_points: int = DEFAULT_CHUNK_POINTS,
                          tile_buffer_m: Optional[float] = None, pdal_executable: Optional[str] = None,
                          progress: Progress = SILENT) -> GroundResult:
    """Classify the ground of every tile of ``input_path`` (a file, a folder of tiles or a
    ``.vpc``) into ``output_folder`` (created or replaced whole): one tile per input tile,
    same name, and ``vpc_name`` listing them. ``GroundResult.output_path`` is the ``.vpc``.

    ``engine``: "auto", "pdal" or "builtin" (:func:`.engine.pdal_runner_for` says which runs;
    PDAL runs tile by tile with a halo, :mod:`.pdal_tiles`). ``crs_wkt`` replaces the tiles'
    CRS; without it the cloud must have one.
    """
    method = method_name(method)
    engine = engine_name(engine)
    params = method_params(method, params)
    if not vpc_name.lower().endswith(".vpc") or os.sep in vpc_name:
        raise InputError("The virtual point cloud's name {name} must be a file name ending in .vpc",
                         name=vpc_name)
    source = open_cloud(input_path if isinstance(input_path, CloudSource) else os.fspath(input_path))
    output_folder = os.path.abspath(os.fspath(output_folder))
    names = output_tile_names(source, output_folder)
    if crs_wkt:
        from ..crs import parse_crs

        parse_crs(crs_wkt, "point cloud CRS")
    elif not source.crs_wkt:
        raise InputError("{path} has no coordinate reference system: give the cloud's CRS "
                         "(it is never guessed)", path=source.path)
    out_crs = crs_wkt or source.crs_wkt
    area = None if region is None else region.geometry
    met = {t.path for t in source.tiles_in(area=area)}
    whole = grid_bounds(source.bounds_xy, region)
    grown: Dict[int, BBoxXY] = {}
    for k, t in enumerate(source.tiles):
        bounds = tile_grid(params, whole, t.bounds_xy, tile_buffer_m) if whole is not None else None
        if t.point_count and t.path in met and bounds is not None:
            grown[k] = bounds
    work = sorted(grown)
    skipped = [t.path for k, t in enumerate(source.tiles) if k not in grown]
    result = GroundResult(os.path.join(output_folder, vpc_name), method, "builtin", source.point_count, 0, 0,
                          out_crs)
    staged = StagedOutputs()
    temporary = staged.folder(output_folder)
    written: List[Tuple[str, Any]] = []
    runner = pdal_runner_for(engine, method, pdal_executable, progress)
    try:
        counts: Optional[Dict[int, Tuple[int, int]]] = None
        if runner is not None:
            from .pdal_tiles import run_pdal_tiles

            try:
                counts, result.pipeline_json, result.engine = run_pdal_tiles(
                    source, work, lambda k: os.path.join(temporary, names[k]), method, params, region, crs_wkt,
                    reset_classes, runner.executable, chunk_points, progress)
            except PdalError as e:
                if engine == "pdal" or not builtin_available(method):
                    raise
                result.warnings.append(progress.warning(
                    "PDAL failed, the built-in engine was used instead: {error}", error=str(e)))
                for name in os.listdir(temporary):
                    remove(os.path.join(temporary, name))
        if counts is None:
            counts = _builtin_tiles(source, work, grown, names, temporary, region, params,
                                    out_crs if crs_wkt else None, reset_classes, chunk_points, tile_buffer_m,
                                    progress)
        for k in work:
            n_out, n_ground = counts[k]
            path = os.path.join(temporary, names[k])
            result.n_output += n_out
            result.n_ground += n_ground
            if n_out:
                written.append((os.path.join(output_folder, names[k]), read_header(path)))
            else:
                remove(path)  # PDAL writes an empty file, the built-in engine none
                skipped.append(source.tiles[k].path)
        for path in skipped:
            result.warnings.append(progress.info("No point of the tile {tile} lies inside the crop area: no "
                                                 "output tile for it", tile=path))
        headers = [(os.path.join(temporary, os.path.basename(p)), h) for p, h in written]
        with open(os.path.join(temporary, vpc_name), "w", encoding="utf-8", newline="\n") as f:
            f.write(vpc_text(headers, out_crs, temporary))
        progress.report(1.0)
        staged.commit()
    except BaseException:
        staged.rollback()
        raise
    if result.n_output == 0:
        result.warnings.append(progress.warning(
            "No point of {path} is left after the crop: {output} lists no tile", path=source.path,
            output=result.output_path))
    progress.info("{n} tiles written to {folder}, listed in {vpc}", n=len(written), folder=output_folder,
                  vpc=vpc_name)
    return result


def _builtin_tiles(source: CloudSource, work: List[int], grown: Dict[int, BBoxXY], names: List[str],
                   folder: str, region: Optional[CropRegion], params: Params, crs_wkt: Optional[str],
                   reset_classes: bool, chunk_points: int, tile_buffer_m: Optional[float],
                   progress: Progress) -> Dict[int, Tuple[int, int]]:
    """The tiles ``work`` with the built-in engine into ``folder`` (file ``names[k]``, none when
    empty); ``{tile: (points written, ground points)}``."""
    counts: Dict[int, Tuple[int, int]] = {}
    with tempfile.TemporaryDirectory(prefix=".roadsigns-halo-") as spool_dir:
        spools = _spool_halos(source, work, grown, region, params, spool_dir, chunk_points,
                              progress.sub(0.0, 0.3))
        for k, share in source.tile_shares(work, progress.sub(0.3, 1.0)):
            counts[k] = _classify_tile(source, k, grown[k], spools.get(k), os.path.join(folder, names[k]), region,
                                       params, crs_wkt, reset_classes, chunk_points, tile_buffer_m, share)
    return counts


def _spool_halos(source: CloudSource, work: List[int], grown: Dict[int, BBoxXY],
                 region: Optional[CropRegion], params: Params, folder: str, chunk_points: int,
                 progress: Progress) -> Dict[int, str]:
    """Pass 0: the eligible points of each tile near another tile's grid (``grown``, a few
    cells more), appended to that tile's file in ``folder``; {tile number: file}."""
    step = grid_step_m(params)
    boxes = {k: grown_box(grown[k], 3.0 * step) for k in work}
    spools: Dict[int, str] = {}
    for _, t, pts in source.points_near_tiles(boxes, chunk_points, progress):
        _, x, y, z = eligible_xyz(cropped(pts, region), params)
        if len(x):
            rows = np.zeros(len(x), _HALO_DTYPE)
            rows["x"], rows["y"], rows["z"] = x, y, z
            path = spools.setdefault(t, os.path.join(folder, f"halo_{t}.bin"))
            with open(path, "ab") as f:
                rows.tofile(f)
    return spools


def _classify_tile(source: CloudSource, k: int, bounds: BBoxXY, spool_path: Optional[str], path: str,
                   region: Optional[CropRegion], params: Params, crs_wkt: Optional[str], reset_classes: bool,
                   chunk_points: int, tile_buffer_m: Optional[float], progress: Progress) -> Tuple[int, int]:
    """Passes 1 and 2 of one tile into ``path`` (:func:`~.engine.two_passes`, its halo's
    points from the file ``spool_path`` added to the grid); ``(points written, ground
    points)``; no file when no point is kept."""
    tile: Tile = source.tiles[k]
    grid = make_grid(params, bounds, float(source.bounds[2]), None, tile_buffer_m)
    header = output_header(template_header(source.tile_header(k)), crs_wkt)
    folder = os.path.dirname(path)
    room = room_to_spool(tile.point_count, header.point_format.size, folder)

    def read(reading: Progress, again: bool) -> Iterator[ChunkSource]:
        return (partial(cropped, chunk, region) for chunk in _tile_chunks(source, tile, chunk_points, reading))

    def add_halo(grid: Any) -> None:
        if spool_path is not None:
            halo = np.fromfile(spool_path, dtype=_HALO_DTYPE)
            on = on_lattice(grid.lattice, halo["x"], halo["y"], isinstance(params, CsfParams))
            grid.accumulate(halo["x"][on], halo["y"][on], halo["z"][on])

    writer = CloudWriter(path, header)
    try:
        _, n_ground = two_passes(read, grid, params, reset_classes, writer, folder if room else None, progress,
                                 add_to_grid=add_halo)
    except OutsideGridError as e:
        writer.abort()
        raise InputError("Cannot read {path}: the file is corrupt ({detail})", path=tile.path, detail=str(e))
    except BaseException:
        writer.abort()
        raise
    n_out = writer.point_count
    if n_out:
        writer.commit()
    else:
        writer.abort()
    return n_out, n_ground


def _tile_chunks(source: CloudSource, tile: Tile, chunk_points: int, progress: Progress) -> Iterable[Any]:
    for _, chunk in source.iter_indexed_chunks(chunk_points, progress, tiles=[tile]):
        yield chunk


def run_ground_filter_tiles(input_path: Union[str, CloudSource], output_folder: str, vpc_name: str,
                            method: str = "csf", engine: str = "auto",
                            crop_polygons: Optional[Iterable[Any]] = None, crop_buffer_m: float = 0.0,
                            crs_wkt: Optional[str] = None, reset_classes: bool = False,
                            params: Optional[Params] = None, chunk_points: int = DEFAULT_CHUNK_POINTS,
                            pdal_executable: Optional[str] = None, progress: Progress = SILENT) -> GroundResult:
    """:func:`classify_ground_tiles` with the crop of :func:`.engine.run_ground_filter`."""
    region = crop_region(crop_polygons, crop_buffer_m, progress)
    return classify_ground_tiles(input_path, output_folder, vpc_name, method=method, engine=engine,
                                 params=params, region=region, crs_wkt=crs_wkt, reset_classes=reset_classes,
                                 chunk_points=chunk_points, pdal_executable=pdal_executable,
                                 progress=progress)
