"""PDAL on a cloud of several tiles (a folder of tiles, a ``.vpc``): tile by tile, with a halo.

PDAL holds everything a pipeline reads in memory (~150 bytes a point), so a cloud of
tiles is never given to one pipeline. Each tile runs alone:

1. one read of the cloud spools, for every tile, the points of its neighbours within
   :func:`pdal_halo_m` of it into a temporary LAS file (the tile's own header, scales and
   offsets);
2. per tile, one pipeline (:func:`.pdal.build_pdal_pipeline` with ``halo_path``) reads the
   tile and its halo, marks the halo's points (the temporary dimension
   :data:`~.pdal.HALO_DIM`), crops and classifies them together, and writes the tile's own
   points only.

So the classes near a tile's edge are those PDAL gives with the ground beyond the edge in
view, and memory is one tile and its halo. PDAL's CSF is one cloth over what it is given, not
the built-in engine's lattice of squares, so tiles through PDAL agree with PDAL on one file as
closely as two cloths over different extents do (the tests hold them to >= 99.5 % of the
built-in engine's classes, as for one file).

The outputs: one file per tile (``roadsigns:groundfilter`` with ``OUTPUT_TILES``), or one
file gathered from them (:func:`.engine.classify_ground`), through temporary names.
"""
from __future__ import annotations

import os
import tempfile
from typing import Any, Callable, Dict, List, Optional, Tuple

import laspy

from ..cloudsource import CloudSource, conform, grown_box, template_header
from ..errors import SILENT, Progress
from ..pointcloud import DEFAULT_CHUNK_POINTS, CropRegion
from .csf import CSF_BUFFER_M, CsfParams
from .params import Params
from .pdal import PdalError, run_pdal_engine
from .smrf import SmrfGrid


def pdal_halo_m(params: Params) -> float:
    """How far around a tile PDAL is shown its neighbours' points, in metres: CSF's buffer
    around a square of cloth (:data:`~.csf.CSF_BUFFER_M`), or SMRF's reach (its largest
    window, as the built-in SMRF grid works it out)."""
    if isinstance(params, CsfParams):
        return CSF_BUFFER_M
    return float(SmrfGrid((0.0, 0.0, 1.0, 1.0), params).halo_cells * params.cell)


def spool_pdal_halos(source: CloudSource, work: List[int], halo: float, folder: str,
                     chunk_points: int = DEFAULT_CHUNK_POINTS,
                     progress: Progress = SILENT) -> Tuple[Dict[int, str], Dict[int, List[int]]]:
    """Pass 1: for each tile number of ``work``, the points of the other tiles of ``work``
    within ``halo`` metres of its header bounds (:meth:`.cloudsource.CloudSource.points_near_tiles`),
    written to a LAS file in ``folder`` with that tile's header. Returns ``{tile number: file}``
    (tiles without neighbours have none) and ``{tile number: the tiles its halo's points come from}``."""
    boxes = {k: grown_box(source.tiles[k].bounds_xy, halo) for k in work}
    writers: Dict[int, Any] = {}
    paths: Dict[int, str] = {}
    came_from: Dict[int, List[int]] = {}
    try:
        for s, t, pts in source.points_near_tiles(boxes, chunk_points, progress):
            if t not in writers:
                paths[t] = os.path.join(folder, f"halo_{t}.las")
                writers[t] = laspy.open(paths[t], mode="w", header=template_header(source.tile_header(t)))
            writers[t].write_points(conform(pts, writers[t].header))
            if s not in came_from.setdefault(t, []):
                came_from[t].append(s)
    finally:
        for w in writers.values():
            w.close()
    return paths, came_from


def run_pdal_tiles(source: CloudSource, work: List[int], output_of: Callable[[int], str], method: str,
                   params: Params, region: Optional[CropRegion], crs_wkt: Optional[str], reset_classes: bool,
                   executable: Optional[str], chunk_points: int = DEFAULT_CHUNK_POINTS,
                   progress: Progress = SILENT) -> Tuple[Dict[int, Tuple[int, int]], str, str]:
    """Classify the tiles ``work`` (tile numbers of ``source``) with PDAL, each with its
    halo, tile ``k`` into ``output_of(k)`` (moved into place there when PDAL succeeds).

    Returns ``({tile: (points written, ground points)}, the pipeline JSON of the first
    tile, the engine used: "pdal-cli" or "pdal-python")``. Raises what
    :func:`.pdal.run_pdal_engine` raises, naming the tile; outputs already written are the
    caller's to remove."""
    halo = pdal_halo_m(params)
    counts: Dict[int, Tuple[int, int]] = {}
    pipeline, used = "", "pdal-python" if executable is None else "pdal-cli"
    with tempfile.TemporaryDirectory(prefix=".roadsigns-pdal-halo-") as spool_dir:
        spools, came_from = spool_pdal_halos(source, work, halo, spool_dir, chunk_points, progress.sub(0.0, 0.2))
        for k, share in source.tile_shares(work, progress.sub(0.2, 1.0)):
            tile = source.tiles[k]
            try:
                n_out, n_ground, json_text, used = run_pdal_engine(
                    tile.path, output_of(k), method, params, region, source.tile_header(k), crs_wkt,
                    reset_classes, executable, chunk_points, share, halo_path=spools.get(k))
            except PdalError as e:
                if not came_from.get(k):
                    raise
                around = ", ".join(source.tiles[s].path for s in came_from[k])
                raise PdalError(f"{e} (PDAL was given {tile.path} with the points of {around} within {halo:g} m "
                                "around it: the trouble may lie in either)", stderr=e.stderr) from e
            counts[k] = (n_out, n_ground)
            pipeline = pipeline or json_text
    return counts, pipeline, used
