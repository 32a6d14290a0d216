"""Everything PDAL: the pipeline JSON, finding PDAL (Python bindings or a ``pdal``
executable) and running it, and the PDAL engine.

Conventions:

* Pipelines use PDAL's documented stage and option names only (``readers.las ->
  filters.crop -> filters.csf|filters.smrf -> writers.las``); :func:`build_pdal_pipeline`
  returns the JSON text that is run and reported. Every stage and option is in PDAL 2.2
  and later (the newest one: ``filters.assign``'s ``value`` expressions, PDAL 2.2); QGIS's
  installers ship PDAL 2.6-2.8, the tests run PDAL 2.9 (README, "PDAL").
* A pipeline runs with the ``pdal`` Python module when no executable is given, else with
  the executable through ``pdal pipeline --stdin``. PDAL's failures raise
  :class:`PdalError` naming the input and output files, with PDAL's own stderr.
  Cancelling kills the ``pdal`` process; the Python bindings cannot be interrupted, so
  there cancelling takes effect when the pipeline returns. Either way nothing is written.
* PDAL writes to a temporary file in the destination folder, moved into place only on
  success (no partial output, :mod:`..outputs`); PDAL's messages name the destination,
  not that file. Inputs cut short are refused before PDAL sees them (:func:`check_complete`).
* LAS arrays of extra bytes (``3f8``: LAS 1.4 deprecated them) come back from PDAL as one
  extra dimension per element (``normal0``, ``normal1``, ...) with the same values.
"""
from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
import sys
import types
from dataclasses import asdict
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Set, Tuple

import numpy as np

from ..errors import SILENT, InputError, Progress
from ..outputs import move_into_place, remove, temp_path_beside
from ..pointcloud import GROUND_CLASS, UNCLASSIFIED_CLASS, CloudWriter, CropRegion, iter_chunks, output_header
from .params import Params, method_name, method_params

#: Temporary PDAL dimension holding the classes from before the filter.
_KEEP_CLASS_DIM = "RoadsignsClassBefore"
#: Temporary PDAL dimension marking the points of a tile's halo (1; the tile's own: 0).
HALO_DIM = "RoadsignsHalo"
#: the message of a file cut short (as core/pointcloud.py words it)
_CORRUPT = "Cannot read {path}: the file is truncated or corrupt ({detail})"


class PdalError(RuntimeError):
    """PDAL ran and failed; ``stderr`` holds PDAL's own message."""

    def __init__(self, message: str, stderr: str = ""):
        super().__init__(message)
        self.stderr = stderr


# --------------------------------------------------------------------------------------
# Pipeline
# --------------------------------------------------------------------------------------

_PDAL_TYPES = {"i1": "int8", "u1": "uint8", "i2": "int16", "u2": "uint16", "i4": "int32",
               "u4": "uint32", "i8": "int64", "u8": "uint64", "f4": "float", "f8": "double"}


def pdal_extra_dims(header: Any) -> List[str]:
    """``writers.las`` ``extra_dims`` entries (``name=type``) for the extra bytes of a
    header; array dimensions are named as PDAL reads them (``name0``, ``name1``, ...)."""
    entries: List[str] = []
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


def pdal_filter_stage(method: str, params: Optional[Params] = None) -> Dict[str, Any]:
    """The ``filters.csf`` / ``filters.smrf`` stage: every option by its PDAL name."""
    method = method_name(method)
    params = method_params(method, params)
    return {"type": f"filters.{method}", **asdict(params)}


def build_pdal_pipeline(input_path: str, output_path: str, method: str = "csf",
                        params: Optional[Params] = None, crop_wkt: Optional[str] = None,
                        crs_wkt: Optional[str] = None, reset_classes: bool = False,
                        extra_dims: Sequence[str] = (), halo_path: Optional[str] = None) -> str:
    """PDAL pipeline JSON: ``readers.las -> filters.crop -> filters.csf|smrf ->
    writers.las``, keeping classes (``filters.ferry`` + ``filters.assign``) unless
    ``reset_classes`` (then ``filters.assign`` sets every class to 1 first).

    The writer forwards the whole header, VLRs, scales and offsets (``forward: all``)
    and the input's extra bytes; ``crs_wkt`` overrides the reader's CRS and is written.

    ``halo_path``: a LAS file of points around the input (a tile's neighbours, :mod:`.pdal_tiles`),
    read beside it, marked (:data:`HALO_DIM` = 1 by ``filters.ferry`` + ``filters.assign``),
    merged (``filters.merge``), classified with it and dropped before the writer
    (``filters.range``).
    """
    reader: Dict[str, Any] = {"type": "readers.las", "filename": input_path}
    if crs_wkt:
        reader["override_srs"] = crs_wkt
    stages: List[Dict[str, Any]] = [reader]
    if halo_path:
        reader["tag"] = "tile"
        halo: Dict[str, Any] = {"type": "readers.las", "filename": halo_path, "tag": "halo"}
        if crs_wkt:
            halo["override_srs"] = crs_wkt
        stages += [halo,
                   {"type": "filters.ferry", "dimensions": f"=> {HALO_DIM}", "inputs": ["halo"],
                    "tag": "halo_dimension"},
                   {"type": "filters.assign", "value": f"{HALO_DIM} = 1", "inputs": ["halo_dimension"],
                    "tag": "halo_marked"},
                   {"type": "filters.merge", "inputs": ["tile", "halo_marked"]}]
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
    if halo_path:
        stages.append({"type": "filters.range", "limits": f"{HALO_DIM}[0:0]"})
    writer: Dict[str, Any] = {"type": "writers.las", "filename": output_path, "forward": "all"}
    if extra_dims:
        writer["extra_dims"] = ",".join(extra_dims)
    if output_path.lower().endswith(".laz"):
        writer["compression"] = "true"  # LAZ in every PDAL 2.x ("laszip"/"lazperf": legacy)
    if crs_wkt:
        writer["a_srs"] = crs_wkt
    stages.append(writer)
    return json.dumps({"pipeline": stages}, indent=2)


# --------------------------------------------------------------------------------------
# Finding and running PDAL
# --------------------------------------------------------------------------------------

def pdal_python_module() -> Optional[types.ModuleType]:
    """The ``pdal`` Python bindings when they import, else ``None``."""
    try:
        import pdal  # the bindings (absolute import), not this module
    except Exception:
        return None
    return pdal if hasattr(pdal, "Pipeline") else None


def _qgis_bin_dirs() -> List[str]:
    dirs: List[str] = []
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
    seen: Set[str] = set()
    out: List[str] = []
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


class PdalRunner(NamedTuple):
    """How PDAL is run: ``kind`` "python" (the bindings) or "cli" (``executable``)."""
    kind: str
    executable: Optional[str]


def find_pdal_runner(pdal_executable: Optional[str] = None) -> Optional[PdalRunner]:
    """The given ``pdal`` executable, else the Python bindings, else a ``pdal`` executable
    on PATH or in QGIS's bin folder; ``None`` when there is no PDAL."""
    if pdal_executable:
        return PdalRunner("cli", find_pdal_executable(pdal_executable))
    if pdal_python_module() is not None:
        return PdalRunner("python", None)
    exe = find_pdal_executable()
    return PdalRunner("cli", exe) if exe else None


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


def _laszip_vlr(f: Any) -> Optional[bytes]:
    """The LASzip VLR's data, read from the file's own VLRs (laspy hides that one)."""
    f.seek(94)
    header_size, _, n_vlrs = struct.unpack("<HII", f.read(10))
    f.seek(header_size)
    for _ in range(n_vlrs):
        head = f.read(54)
        if len(head) < 54:
            return None
        record_id, length = struct.unpack_from("<HH", head, 18)
        data = f.read(length)
        if head[2:18].rstrip(b"\0") == b"laszip encoded" and record_id == 22204:
            return data
    return None


def check_complete(path: str, header: Any) -> None:
    """:class:`InputError` when ``path`` lacks its end: a LAS shorter than its points, a LAZ
    whose chunk table is not whole or does not end where its chunks do.

    PDAL is never given such a file: PDAL 2.9.2 fails cleanly on some LAZ files cut short,
    but on others ``pdal`` waits forever with no CPU (points of more than 30 bytes, a chunk
    table cut in the middle) or crashes (SIGSEGV), which through the Python bindings
    would hang or crash QGIS."""
    try:
        size = os.path.getsize(path)
        start = int(header.offset_to_point_data)
        if not header.are_points_compressed:
            end = start + int(header.point_count) * int(header.point_format.size)
            if size < end:
                raise InputError(_CORRUPT, path=path, detail=f"{size} bytes, the points need {end}")
            return
        with open(path, "rb") as f:
            f.seek(start)
            table = struct.unpack("<q", f.read(8).ljust(8, b"\0"))[0]
            if table == -1:  # LASzip's streaming writers put the offset at the very end
                f.seek(max(size - 8, 0))
                table = struct.unpack("<q", f.read(8).ljust(8, b"\0"))[0]
            if not start + 8 <= table <= size - 8:
                raise InputError(_CORRUPT, path=path, detail=f"its LAZ chunk table would be at byte "
                                 f"{table} of {size}: the end of the file is missing")
            chunks = _read_chunk_table(f, start)
    except OSError as e:
        raise InputError("Cannot read {path}: {detail}", path=path, detail=str(e))
    except struct.error:
        raise InputError(_CORRUPT, path=path, detail="the header is cut short")
    if isinstance(chunks, str):
        raise InputError(_CORRUPT, path=path, detail=f"its LAZ chunk table cannot be read ({chunks})")
    if chunks is not None and start + 8 + sum(n_bytes for _, n_bytes in chunks) != table:
        raise InputError(_CORRUPT, path=path, detail="its LAZ chunks do not end where their table begins")


def _read_chunk_table(f: Any, start: int) -> Any:
    """The LAZ chunk table ``[(points, bytes), ...]`` (lazrs), its error as a string, or
    ``None`` when it cannot be looked at (no lazrs, no LASzip VLR)."""
    try:
        import lazrs
    except ImportError:
        return None
    vlr = _laszip_vlr(f)
    if vlr is None:
        return None
    f.seek(start)
    try:
        return lazrs.read_chunk_table(f, lazrs.LazVlr(vlr))
    except (KeyboardInterrupt, SystemExit, GeneratorExit):
        raise
    except BaseException as e:  # LazrsError, or a Rust panic (PanicException)
        return f"{type(e).__name__}: {e}"


def _pdal_failure(error: PdalError, input_path: str, output_path: str, temp_path: str,
                  executable: Optional[str]) -> PdalError:
    """``error`` told from the user's side: which files, which PDAL, and PDAL's own words
    with the temporary file called by the destination's name."""
    detail = (error.stderr or str(error)).replace(temp_path, output_path).strip()
    runner = f"pdal ({executable})" if executable else "PDAL's Python bindings"
    return PdalError(f"{runner} could not classify {input_path} into {output_path}: "
                     f"{detail or '(no message)'}", stderr=detail)


def run_pdal_engine(input_path: str, output_path: str, method: str, params: Params,
                    region: Optional[CropRegion], header: Any, crs_wkt: Optional[str],
                    reset_classes: bool, executable: Optional[str], chunk_points: int,
                    progress: Progress, halo_path: Optional[str] = None) -> Tuple[int, int, str, str]:
    """Crop and classify ``input_path`` into ``output_path`` with PDAL (``executable``, or
    the Python module when ``None``). Returns ``(points written, ground points, pipeline
    JSON, engine used: "pdal-cli" or "pdal-python")``; the JSON names ``output_path``.

    Raises :class:`PdalError` naming both files when PDAL fails, :class:`InputError` when
    the input is cut short (:func:`check_complete`) or the output cannot be written, and
    :class:`~..errors.Cancelled` when cancelled; neither the output nor a temporary file
    is left then. ``halo_path``: points around the input classified with it and not
    written (:func:`build_pdal_pipeline`)."""
    input_path = os.path.abspath(os.fspath(input_path))
    output_path = os.path.abspath(os.fspath(output_path))
    check_complete(input_path, header)
    extra_dims = pdal_extra_dims(header)

    def pipeline_to(path: str) -> str:
        return build_pdal_pipeline(input_path, path, method, params,
                                   crop_wkt=region.wkt if region is not None else None,
                                   crs_wkt=crs_wkt, reset_classes=reset_classes,
                                   extra_dims=extra_dims, halo_path=halo_path)

    temp_path = temp_path_beside(output_path)  # InputError naming output_path if unwritable
    try:
        pipeline = pipeline_to(temp_path)
        progress.report(0.0)
        try:
            run_pdal_pipeline(pipeline, executable, progress)
        except PdalError as e:
            raise _pdal_failure(e, input_path, output_path, temp_path, executable) from e
        progress.check()  # the Python bindings cannot be interrupted: cancelled meanwhile?
        if os.path.getsize(temp_path) == 0:  # PDAL wrote nothing (no point left)
            with CloudWriter(temp_path, output_header(header, crs_wkt)):
                pass
        n_out, n_ground = _count_classes(temp_path, chunk_points)
        progress.report(1.0)  # the last chance to cancel: nothing may appear after it
        move_into_place(temp_path, output_path)  # with the umask's permissions, not 0600
    finally:
        remove(temp_path)
    return n_out, n_ground, pipeline_to(output_path), "pdal-cli" if executable else "pdal-python"
