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
* engine ``"auto"``: the engine measured faster for the method (:data:`AUTO_ENGINES`: today
  the built-in one for CSF and SMRF, bench/README.md), PDAL when the built-in engine cannot
  run the method here (the CSF package missing).

The input may be a LAS/LAZ file, a folder of tiles or a virtual point cloud
(:mod:`..cloudsource`), written into one output file or, with :func:`run_ground_filter_tiles`
(:mod:`.tiled`), one output tile per input tile; each tile is classified with a halo of its
neighbours' points (PDAL: one pipeline per tile, :mod:`.pdal_tiles`).

Methods and engines are given by name (:data:`METHODS`, :data:`ENGINES`); anything else
raises :class:`~..errors.InputError`.

The built-in engine never holds the cloud in memory. Pass 1 streams the points into a
grid (SMRF: lowest point per cell; CSF: the point nearest to each cloth node, which is
all the cloth simulation looks at), the grid is processed tile by tile with an overlap
buffer, and pass 2 streams the points again, classifies them against the ground surface
of their tile and writes them. A cloud wider or longer than a block (512 m, a drive) goes
block by block (:mod:`.blocks`): each chunk is reduced in pass 1 to what the grids keep of
it, and each block's grid covers the block and its halo only, so the memory follows a block,
not the drive; the classes are the same.

Ground is class 2. Other classes are kept unless ``reset_classes``: points the filter
finds off-ground that were class 2 become 1 (unclassified); with ``reset_classes`` every
non-ground point becomes 1. As in PDAL, only ``returns`` (default last and only returns)
are classified; the others keep their class.

Modules: ``lattice`` (the world-aligned grid and tiles both built-in methods use),
``smrf`` and ``csf`` (the methods), ``params`` (method/engine names, parameter sets),
``pdal`` (pipelines, finding and running PDAL, the PDAL engine), ``pdal_tiles`` (PDAL on
tiles, each with its halo), ``gridsteps`` (the steps the built-in engine's runs share),
``engine`` (the built-in engine on files, the engine choice and the entry points),
``blocks`` (the built-in engine block by block) and ``tiled`` (one output tile per input
tile).
"""
from .csf import CSF_BUFFER_M, CSF_TILE_M, CsfGrid, CsfParams, run_csf_cloth
from .engine import GroundResult, classify_ground, classify_ground_arrays, run_ground_filter
from .gridsteps import halo_m, make_grid, returns_mask
from .lattice import Lattice
from .params import AUTO_ENGINES, ENGINES, METHODS, Params, default_params, engine_name, method_name
from .pdal import (
    PdalError,
    build_pdal_pipeline,
    find_pdal_executable,
    pdal_extra_dims,
    pdal_filter_stage,
    pdal_python_module,
    run_pdal_pipeline,
)
from .smrf import SMRF_TILE_M, SmrfGrid, SmrfParams, smrf_surface
from .tiled import classify_ground_tiles, run_ground_filter_tiles

__all__ = [
    "AUTO_ENGINES", "CSF_BUFFER_M", "CSF_TILE_M", "ENGINES", "METHODS", "SMRF_TILE_M",
    "CsfGrid", "CsfParams", "GroundResult", "Lattice", "Params", "PdalError", "SmrfGrid", "SmrfParams",
    "build_pdal_pipeline", "classify_ground", "classify_ground_arrays", "classify_ground_tiles",
    "default_params", "engine_name", "find_pdal_executable", "halo_m", "make_grid", "method_name",
    "pdal_extra_dims", "pdal_filter_stage", "pdal_python_module", "returns_mask", "run_csf_cloth",
    "run_ground_filter", "run_ground_filter_tiles", "run_pdal_pipeline", "smrf_surface",
]
