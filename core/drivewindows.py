"""The drive as an axis: arc length along the track, a corridor, and windows spooled to disk.

Cloud stages that must hold neighbourhoods of points (planes, poles) but never the whole
cloud use this module: points are read in chunks, each is located on the drive (arc length
``s_m`` of its nearest track position, signed offset ``offset_m``, positive to the right
of the driving direction), those kept are appended to the window of ``window_m`` metres of
drive that holds them, and to its neighbours when within ``margin_m`` of the boundary, in
files of a temporary folder. Windows are then read back one at a time; an object found in
a window is reported only by the window whose core range holds its centre, so objects that
straddle a boundary are found whole (in the margin) and once. :func:`map_in_order` works on
windows (or blocks) a few at a time in threads.

Conventions: world coordinates of the cloud's CRS (metres, E, N, U); ``xyz_world`` arrays
``(n, 3)``; the track is the sensor's positions in driving order, with times in the same
time base as the cloud's ``gps_time`` when known.
"""
from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections import deque
from concurrent.futures import Future, ThreadPoolExecutor, wait
from dataclasses import dataclass
from typing import Callable, Deque, Dict, Iterable, Iterator, List, Optional, Tuple, TypeVar

import numpy as np
from scipy.spatial import cKDTree

from .errors import InputError
from .memory import release_freed_memory
from .writebehind import WriteBehind

#: Spacing of the densified track used to locate points on the drive, metres.
AXIS_STEP_M = 0.5
#: Bytes of rows buffered in memory, all windows together, before they are appended to the
#: files. Small beside a chunk's arrays: a drive too short to fill the buffer would otherwise
#: peak lower than a long one only because its buffer never filled (32 MB of 1 M projection
#: rows were 13 MB of the 9 x drive's heap peak over 1 x, bench/README.md).
SPOOL_FLUSH_BYTES = 4 * 2**20


@dataclass
class Track:
    """Sensor positions along the drive: ``xyz_world`` ``(n, 3)`` in driving order and,
    when known, ``time_s`` ``(n,)`` (increasing, the cloud's ``gps_time`` base)."""

    xyz_world: np.ndarray
    time_s: Optional[np.ndarray] = None

    def __post_init__(self) -> None:
        self.xyz_world = np.asarray(self.xyz_world, dtype=np.float64).reshape(-1, 3)
        if self.time_s is not None:
            t = np.asarray(self.time_s, dtype=np.float64).reshape(-1)
            if len(t) != len(self.xyz_world):
                raise InputError("The track has {n} positions but {m} times", n=len(self.xyz_world),
                                 m=len(t))
            ok = np.isfinite(t)
            self.time_s = t if ok.all() and np.all(np.diff(t) > 0) else None
        if len(self.xyz_world) < 2 or not np.isfinite(self.xyz_world).all():
            raise InputError("The track needs at least 2 finite positions, got {n}",
                             n=len(self.xyz_world))

    @classmethod
    def from_stations(cls, stations, height_offset_m: float = 0.0) -> "Track":
        """The track of panorama ``Stations`` (centres and times), raised by ``height_offset_m``
        (the scanner above the camera; 0 when unknown)."""
        xyz = np.asarray(stations.xyz_world, dtype=np.float64).copy()
        xyz[:, 2] += height_offset_m
        return cls(xyz, np.asarray(stations.time_s, dtype=np.float64))

    @classmethod
    def from_polyline(cls, xyz_world) -> "Track":
        """A track without times (a drawn trajectory line): sensor positions are the nearest
        points of the line."""
        return cls(np.asarray(xyz_world, dtype=np.float64), None)



def as_track(track) -> Track:
    """A :class:`Track` from a track, from panorama ``Stations`` (centres and times) or from
    an ``(n, 3)`` array of positions (a trajectory line without times)."""
    if isinstance(track, Track):
        return track
    if hasattr(track, "xyz_world"):
        return Track.from_stations(track)
    return Track.from_polyline(np.asarray(track, dtype=np.float64))


class DriveAxis:
    """Arc length, lateral offset, direction and sensor position along a :class:`Track`.

    The track is densified every ``step_m``; a point is located at its nearest densified
    vertex (``s_m``, the signed lateral ``offset_m``: right of the driving direction is
    positive, the unit ``tangent_xy`` there). Repeated passes over the same road take the
    nearest pass.
    """

    def __init__(self, track: Track, step_m: float = AXIS_STEP_M):
        self.track = track
        xyz = track.xyz_world
        seg = np.linalg.norm(np.diff(xyz[:, :2], axis=0), axis=1)
        s_vertex = np.r_[0.0, np.cumsum(seg)]
        keep = np.r_[True, seg > 1e-6]          # duplicate positions would give no direction
        xyz, s_vertex = xyz[keep], s_vertex[keep]
        self.times = track.time_s[keep] if track.time_s is not None else None
        if len(xyz) < 2:
            raise InputError("The track does not move: all its positions are at one place")
        self.length_m = float(s_vertex[-1])
        n = max(2, int(np.ceil(self.length_m / step_m)) + 1)
        self.s_m = np.linspace(0.0, self.length_m, n)
        self.xyz_world = np.column_stack([np.interp(self.s_m, s_vertex, xyz[:, k]) for k in range(3)])
        d = np.gradient(self.xyz_world[:, :2], axis=0)
        self.tangent_xy = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-12)
        self._vertex_s = s_vertex
        self._vertex_xyz = xyz
        self._tree = cKDTree(self.xyz_world[:, :2])

    def locate(self, xy: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(s_m, offset_m, index)`` of points ``xy`` ``(n, 2+)``: arc length and signed
        lateral offset at the nearest densified vertex (its index into :attr:`s_m`)."""
        xy = np.asarray(xy, dtype=np.float64)[:, :2]
        if len(xy) == 0:
            return np.zeros(0), np.zeros(0), np.zeros(0, np.int64)
        _, idx = self._tree.query(xy, workers=-1)
        rel = xy - self.xyz_world[idx, :2]
        t = self.tangent_xy[idx]
        along = np.einsum("ij,ij->i", rel, t)
        offset = rel[:, 0] * t[:, 1] - rel[:, 1] * t[:, 0]   # right of the direction: +
        return self.s_m[idx] + along, offset, idx

    def has_times(self) -> bool:
        return self.times is not None

    def sensor_positions(self, xyz_world: np.ndarray, time_s: Optional[np.ndarray]) -> np.ndarray:
        """The sensor's position ``(n, 3)`` when each point was measured: the track
        interpolated at the point's time when both have times and the time lies on the track
        (within 1 s), else the nearest densified track position."""
        xyz_world = np.asarray(xyz_world, dtype=np.float64)
        out = np.empty_like(xyz_world)
        by_time = np.zeros(len(xyz_world), bool)
        if self.times is not None and time_s is not None:
            t = np.asarray(time_s, dtype=np.float64)
            by_time = (t >= self.times[0] - 1.0) & (t <= self.times[-1] + 1.0)
            if by_time.any():
                tt = t[by_time]
                for k in range(3):
                    out[by_time, k] = np.interp(tt, self.times, self._vertex_xyz[:, k])
        rest = ~by_time
        if rest.any():
            _, idx = self._tree.query(xyz_world[rest, :2], workers=-1)
            out[rest] = self.xyz_world[idx]
        return out

    def times_overlap(self, time_min: float, time_max: float) -> bool:
        """Whether the cloud's time span ``[time_min, time_max]`` meets the track's."""
        if self.times is None:
            return False
        return bool(time_max >= self.times[0] and time_min <= self.times[-1])


@dataclass(frozen=True)
class Window:
    """Window ``index`` of the drive: core arc lengths ``[s0_m, s1_m)``."""

    index: int
    s0_m: float
    s1_m: float

    def owns(self, s_m) -> np.ndarray:
        s = np.asarray(s_m, dtype=np.float64)
        return (s >= self.s0_m) & (s < self.s1_m)


def make_windows(length_m: float, window_m: float) -> List[Window]:
    """Windows of ``window_m`` covering ``[0, length_m]``; the first and last own everything
    before and after the drive's ends."""
    n = max(1, int(np.ceil(length_m / window_m)))
    edges = np.linspace(0.0, length_m, n + 1)
    edges[0], edges[-1] = -np.inf, np.inf
    return [Window(k, float(edges[k]), float(edges[k + 1])) for k in range(n)]


def split_window(window: Window, s_m: np.ndarray, margin_m: float, max_points: int,
                 min_core_m: float) -> List[Tuple[Window, np.ndarray]]:
    """``window`` in parts of at most ``max_points`` points where it can: ``(part, rows)``
    in drive order, ``rows`` indexing ``s_m`` (the arc lengths of the window's points, core
    and margins). A part holding more is cut in two at the median of its core's points,
    each half keeping the points within ``margin_m`` of its own core, while its core is
    longer than ``min_core_m``. The parts' cores tile the window's core and keep its index,
    so an object is still reported once, by the part whose core holds it, and found whole
    in that part's margins. The densest window of a longer drive is denser; its parts are
    not."""
    s = np.asarray(s_m, dtype=np.float64)
    done: List[Tuple[Window, np.ndarray]] = []
    todo = [(window, np.arange(len(s)))]
    while todo:
        part, rows = todo.pop()
        s_rows = s[rows]
        core = s_rows[part.owns(s_rows)]
        lo = part.s0_m if np.isfinite(part.s0_m) else (core.min() if len(core) else 0.0)
        hi = part.s1_m if np.isfinite(part.s1_m) else (core.max() if len(core) else 0.0)
        if len(rows) <= max_points or hi - lo <= min_core_m or len(core) < 2:
            done.append((part, rows))
            continue
        cut = float(np.clip(np.median(core), lo + 0.5 * min_core_m, hi - 0.5 * min_core_m))
        first, second = Window(part.index, part.s0_m, cut), Window(part.index, cut, part.s1_m)
        todo.append((second, rows[s_rows >= cut - margin_m]))   # popped after the first
        todo.append((first, rows[s_rows < cut + margin_m]))
    return done


#: Windows or blocks worked on at once by the cloud stages (:func:`map_in_order`; the
#: machines this is measured on have two cores).
BLOCK_THREADS = 2

_ItemT = TypeVar("_ItemT")
_ResultT = TypeVar("_ResultT")


def map_in_order(work: Callable[[_ItemT], _ResultT], items: Iterable[_ItemT], threads: int,
                 check: Callable[[], None]) -> Iterator[_ResultT]:
    """``work(item)`` for every item (windows, blocks), ``threads`` at a time (1: in this
    thread), yielded in the items' order; at most ``threads`` items are worked on at once,
    and ``items`` (which may read its blocks lazily) is advanced in this thread. For work
    whose time is spent in numpy and scipy, which release the GIL. ``check`` (raising
    :class:`~.errors.Cancelled`) runs before each item is started and while waiting: on
    cancel, items not started are dropped and the running ones are waited for. The memory
    freed by each item is given back to the system (:func:`.memory.release_freed_memory`)."""
    todo = iter(items)
    if threads <= 1:
        for item in todo:
            check()
            result = work(item)
            del item
            release_freed_memory()
            yield result
        return
    with ThreadPoolExecutor(max_workers=threads, thread_name_prefix="roadsigns-block") as pool:
        pending: Deque[Future] = deque()
        exhausted = False
        try:
            while True:
                while not exhausted and len(pending) < threads:
                    check()
                    try:
                        item = next(todo)
                    except StopIteration:
                        exhausted = True
                        break
                    pending.append(pool.submit(work, item))
                if not pending:
                    return
                head = pending[0]
                while not head.done():
                    check()
                    wait([head], timeout=0.2)
                pending.popleft()
                result = head.result()
                del head
                release_freed_memory()
                yield result
        finally:
            for f in pending:
                f.cancel()


_SpoolT = TypeVar("_SpoolT", bound="Spool")


class Spool:
    """Rows of structured dtypes appended per key (``kind``, integer index) to files in a
    temporary folder, and read back whole.

    ``dtypes``: the dtype of each kind. At most ``flush_bytes`` of rows wait in memory (then
    they are appended to their files); :meth:`read` flushes first. Use as a context manager
    (the folder is deleted on exit, or by :meth:`close`). ``background``: the files are
    written on a thread of their own while the caller goes on (:class:`.writebehind.WriteBehind`;
    one flush at a time, so up to twice ``flush_bytes`` in memory; a write's error is
    raised by the next flush, :meth:`read` or :meth:`discard`). Rows given to :meth:`append`
    must not change after, either way. The first :meth:`read` ends the writing pass: the
    memory that pass freed (the cloud's chunks) is given back to the system then
    (:func:`.memory.release_freed_memory`), so the windows or blocks read back do not stack on
    its heap.
    """

    def __init__(self, dtypes: Dict[str, np.dtype], folder: Optional[str] = None,
                 flush_bytes: int = SPOOL_FLUSH_BYTES, prefix: str = "roadsigns-spool-", background: bool = False):
        self.dtypes = {k: np.dtype(v) for k, v in dtypes.items()}
        self.folder = tempfile.mkdtemp(prefix=prefix, dir=folder)
        self.flush_bytes = int(flush_bytes)
        self._pending: Dict[Tuple[str, int], List[np.ndarray]] = {}
        self._pending_bytes = 0
        self._behind = WriteBehind("roadsigns-spool-write") if background else None
        self._read_back = False

    def _path(self, kind: str, index: int) -> str:
        return os.path.join(self.folder, "{}-{:06d}.bin".format(kind, index))

    def append(self, kind: str, index: int, rows: np.ndarray) -> None:
        """Append ``rows`` (dtype of ``kind``) to the file of ``(kind, index)``."""
        if len(rows):
            rows = np.asarray(rows, dtype=self.dtypes[kind])
            self._pending.setdefault((kind, index), []).append(rows)
            self._pending_bytes += rows.nbytes
            if self._pending_bytes >= self.flush_bytes:
                self.flush()

    def flush(self) -> None:
        """Append the rows waiting in memory to their files (in the background: start to)."""
        if not self._pending:
            return
        pending, self._pending, self._pending_bytes = self._pending, {}, 0
        if self._behind is not None:
            self._behind.submit(self._write, pending)
        else:
            self._write(pending)

    def _write(self, pending: Dict[Tuple[str, int], List[np.ndarray]]) -> None:
        for (kind, k), parts in pending.items():
            with open(self._path(kind, k), "ab") as f:
                for part in parts:
                    part.tofile(f)

    def _settle(self) -> None:
        """Flush, and wait until the files hold every row appended."""
        self.flush()
        if self._behind is not None:
            self._behind.wait()

    def read(self, kind: str, index: int, rows: Optional[np.ndarray] = None) -> np.ndarray:
        """All rows of ``kind`` appended to ``index``, or only those at the positions
        ``rows`` (an index array into them, read through a memory map of the file: the
        other rows are not copied into memory)."""
        self._settle()
        if not self._read_back:      # the writing pass is over: give its heap back
            self._read_back = True
            release_freed_memory()
        path = self._path(kind, index)
        if not os.path.exists(path) or os.path.getsize(path) == 0:     # nothing appended
            empty = np.zeros(0, dtype=self.dtypes[kind])
            return empty if rows is None else empty[np.asarray(rows, dtype=np.int64)]
        if rows is None:
            return np.fromfile(path, dtype=self.dtypes[kind])
        # fancy indexing copies the rows out of the map, which is let go with this expression
        return np.memmap(path, dtype=self.dtypes[kind], mode="r")[np.asarray(rows, dtype=np.int64)].view(np.ndarray)

    def read_parts(self, kind: str, index: int, part_rows: int = 65536) -> Iterator[np.ndarray]:
        """The rows of ``kind`` appended to ``index``, read ``part_rows`` at a time (a pass
        that keeps a few of them holds one part, not the file)."""
        self._settle()
        path = self._path(kind, index)
        if not os.path.exists(path):
            return
        with open(path, "rb") as f:
            while True:
                part = np.fromfile(f, dtype=self.dtypes[kind], count=part_rows)
                if not len(part):
                    return
                yield part

    def count(self, kind: str, index: int) -> int:
        """How many rows of ``kind`` have been appended to ``index``."""
        self._settle()
        path = self._path(kind, index)
        return os.path.getsize(path) // self.dtypes[kind].itemsize if os.path.exists(path) else 0

    def discard(self, kind: str, index: int) -> None:
        """Delete the rows of ``(kind, index)`` (read them first)."""
        self._pending_bytes -= sum(part.nbytes for part in self._pending.pop((kind, index), []))
        if self._behind is not None:
            self._behind.wait()
        with contextlib.suppress(FileNotFoundError):
            os.remove(self._path(kind, index))

    def close(self) -> None:
        """Delete the folder and what it holds (a write under way is waited for, its error dropped)."""
        if self._behind is not None:
            self._behind.abandon()
        self._pending.clear()
        shutil.rmtree(self.folder, ignore_errors=True)

    def __enter__(self: _SpoolT) -> _SpoolT:
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self.close()


class WindowSpool(Spool):
    """A :class:`Spool` per window of the drive: :meth:`add` takes rows and their arc lengths;
    a row goes to every window whose core range grown by ``margin_m`` holds it."""

    def __init__(self, windows: List[Window], margin_m: float, dtypes: Dict[str, np.dtype],
                 folder: Optional[str] = None, flush_bytes: int = SPOOL_FLUSH_BYTES):
        super().__init__(dtypes, folder, flush_bytes, prefix="roadsigns-windows-")
        self.windows = windows
        self.margin_m = float(margin_m)
        self._lo = np.array([w.s0_m for w in windows]) - self.margin_m
        self._hi = np.array([w.s1_m for w in windows]) + self.margin_m

    def add(self, kind: str, s_m: np.ndarray, rows: np.ndarray) -> None:
        """Append ``rows`` (dtype of ``kind``) located at arc lengths ``s_m``."""
        if len(rows) == 0:
            return
        rows = np.asarray(rows, dtype=self.dtypes[kind])
        s_m = np.asarray(s_m, dtype=np.float64)
        first = np.searchsorted(self._hi, s_m, side="right")   # first window whose end > s
        last = np.searchsorted(self._lo, s_m, side="right") - 1  # last window whose start <= s
        for k in range(int(first.min(initial=len(self.windows))),
                       int(min(last.max(initial=-1), len(self.windows) - 1)) + 1):
            mine = (first <= k) & (last >= k)
            if mine.any():
                self.append(kind, k, rows[mine])
