"""Trajectory, image times and per-image poses -> panorama stations with full pose.

Inputs follow ``docs/formats.md``: a trajectory CSV (``time,x,y,z,roll,pitch,heading``)
or an Applanix SBET, plus an image-times CSV (``image,time``); or a per-image pose CSV
(``image,x,y,z,roll,pitch,heading[,time]``). Attitudes are INS angles in degrees with a
TRUE heading; positions are in the trajectory CRS (lon/lat/ellipsoidal height for a
geographic one). Poses at image times: positions interpolated linearly (in the world
CRS, between the two bracketing samples), attitudes by SLERP (scipy ``Slerp``).

Each station's panorama frame then follows docs/formats.md:
``R_world_from_pano = R_enu_from_ned @ Rz(-gamma) @ R_ned_from_body @ R_body_from_pano`` with
gamma the meridian convergence at the station (grid heading = true heading - gamma), and
the panorama centre at ``C + R_enu_from_ned @ Rz(-gamma) @ R_ned_from_body @ t_lever``.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from . import geometry
from .crs import (
    WorldTransform,
    area_fields,
    check_positions,
    default_target_crs,
    horizontal_crs,
    parse_crs,
    plausible_extent,
    world_transform,
)
from .errors import SILENT, InputError, Message, Progress
from .panorama import check_equirectangular, read_image_size
from .schema import Schema, fields
from .tables import read_table

TRAJECTORY_COLUMNS = ("time", "x", "y", "z", "roll", "pitch", "heading")
POSE_COLUMNS = ("image", "x", "y", "z", "roll", "pitch", "heading")
SBET_RECORD_FLOATS = 17
SBET_RECORD_BYTES = SBET_RECORD_FLOATS * 8
SBET_EXTENSIONS = (".out", ".sbet")
#: SBETs are always WGS 84 geographic with ellipsoidal heights.
SBET_CRS = "EPSG:4979"


@dataclass
class Trajectory:
    """Body poses over time: position in the trajectory CRS, INS attitude (true heading)."""
    time_s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    roll_deg: np.ndarray
    pitch_deg: np.ndarray
    heading_deg: np.ndarray
    path: str
    #: where each sample came from, for messages: "line 12" or "record 12"
    locations: List[str] = field(default_factory=list)

    def __len__(self):
        return len(self.time_s)

    def rotations_ned_from_body(self) -> Rotation:
        return Rotation.from_euler("ZYX", np.column_stack(
            [self.heading_deg, self.pitch_deg, self.roll_deg]), degrees=True)


@dataclass(frozen=True)
class CameraMount:
    """Panorama camera on the vehicle: lever arm (body frame, m) and boresight (deg)."""
    lever_arm_m: Sequence[float] = (0.0, 0.0, 0.0)
    boresight_roll_deg: float = 0.0
    boresight_pitch_deg: float = 0.0
    boresight_yaw_deg: float = 0.0

    def R_body_from_pano(self) -> np.ndarray:
        return geometry.R_body_from_pano(self.boresight_roll_deg, self.boresight_pitch_deg,
                                         self.boresight_yaw_deg)


@dataclass
class Stations:
    """Panorama stations in the world CRS, one row per panorama, in input order.

    ``xyz_world`` is the panorama centre (E, N, U metres); ``q_world_from_pano_wxyz`` maps
    panorama-frame rays to world ENU; ``heading_deg`` is the azimuth of the panorama's
    forward axis, clockwise from grid north in [0, 360); ``time_s`` is NaN when unknown.
    """
    image: List[str]
    path: List[str]
    time_s: np.ndarray
    xyz_world: np.ndarray
    q_world_from_pano_wxyz: np.ndarray
    heading_deg: np.ndarray
    width_px: np.ndarray
    height_px: np.ndarray
    #: ids as written in the layer; 1, 2, ... in input order when not given
    station_id: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))

    def __post_init__(self) -> None:
        if len(self.station_id) != len(self.image):
            self.station_id = np.arange(1, len(self.image) + 1, dtype=np.int64)

    def __len__(self):
        return len(self.image)

    def records(self) -> List[Dict]:
        """One dict of :data:`STATION_FIELDS` per station (the stations layer)."""
        out = []
        for k in range(len(self)):
            time_s = float(self.time_s[k])
            out.append({"station_id": int(self.station_id[k]), "image": self.image[k],
                        "path": self.path[k], "time": None if math.isnan(time_s) else time_s,
                        **dict(zip(("x", "y", "z"), map(float, self.xyz_world[k]))),
                        **dict(zip(("qw", "qx", "qy", "qz"), map(float, self.q_world_from_pano_wxyz[k]))),
                        "heading": float(self.heading_deg[k]), "width": int(self.width_px[k]),
                        "height": int(self.height_px[k])})
        return out

    @classmethod
    def from_records(cls, rows: Sequence[Mapping[str, Any]], layer: str = "Panorama stations") -> "Stations":
        """Read back a stations layer: dicts with :data:`STATION_FIELDS` (``time`` may be NULL).
        :class:`InputError` naming the station and the field for any other NULL value."""
        rows = list(rows)
        for row in rows:
            for f in STATION_FIELDS:
                if f.name != "time" and row.get(f.name) is None:
                    raise InputError("{layer}: station {station} has no value in the field {field}; "
                                     "expected the output of Import trajectory", layer=layer,
                                     station=_station_label(row), field=f.name)

        def number(row, name, integer=False):
            try:
                value = float(row[name])
                if not math.isfinite(value) or (integer and (value != int(value) or abs(value) >= 2 ** 53)):
                    raise ValueError(value)
                return value
            except (TypeError, ValueError, OverflowError):
                raise InputError("{layer}: station {station}, field {field}: expected a finite number, "
                                 "found '{value}'; expected the output of Import trajectory", layer=layer,
                                 station=_station_label(row), field=name, value=str(row[name])[:60])

        def col(names, dtype=float):
            return np.array([[number(r, n, dtype is not float) for n in names] for r in rows],
                            dtype=dtype).reshape(len(rows), len(names))

        time_s = np.array([np.nan if r["time"] is None else number(r, "time") for r in rows])
        q = col(("qw", "qx", "qy", "qz"))
        with np.errstate(over="ignore"):  # a huge value gives an infinite norm: refused below
            norm = np.linalg.norm(q, axis=1)
        bad = np.flatnonzero(np.abs(norm - 1.0) > 1e-3)
        if bad.size:
            raise InputError("{layer}: station {station}: the quaternion qw, qx, qy, qz has norm {norm:.4f}, "
                             "not 1; expected the output of Import trajectory", layer=layer,
                             station=_station_label(rows[int(bad[0])]), norm=float(norm[bad[0]]))
        return cls([str(r["image"]) for r in rows], [str(r["path"]) for r in rows], time_s,
                   col(("x", "y", "z")), q, col(("heading",))[:, 0],
                   col(("width",), np.int64)[:, 0], col(("height",), np.int64)[:, 0],
                   col(("station_id",), np.int64)[:, 0])


def _station_label(row: Mapping[str, Any]) -> str:
    return "?" if row.get("station_id") is None else str(row["station_id"])


#: The stations layer (PointZ at the panorama centre), one row per :class:`Stations` row.
STATION_FIELDS: Schema = fields(
    ("station_id", int), ("image", str), ("path", str), ("time", float),
    ("x", float), ("y", float), ("z", float), ("qw", float), ("qx", float), ("qy", float),
    ("qz", float), ("heading", float), ("width", int), ("height", int))


@dataclass
class StationImport:
    """The result of :func:`import_stations`, with what the log should say."""
    stations: Stations
    target_crs_wkt: str
    messages: List[str]
    warnings: List[str]


# --- readers ----------------------------------------------------------------------------

def _check_increasing(time_s: np.ndarray, locations: Sequence[str], path: str, what: str):
    dt = np.diff(time_s)
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        kind = "is duplicated" if dt[k - 1] == 0 else "goes back in time"
        raise InputError("{what} file {path}, {location}: time {time} {kind} (previous {previous}); "
                         "times must increase strictly", what=what, path=path,
                         location=locations[k], time=repr(float(time_s[k])), kind=kind,
                         previous=repr(float(time_s[k - 1])))


def read_trajectory_csv(path: str) -> Trajectory:
    table = read_table(path, TRAJECTORY_COLUMNS, numeric=TRAJECTORY_COLUMNS, what="Trajectory")
    locations = ["line {}".format(n) for n in table["_line"]]
    trajectory = Trajectory(table["time"], table["x"], table["y"], table["z"], table["roll"],
                            table["pitch"], table["heading"], path, locations)
    _check_increasing(trajectory.time_s, locations, path, "Trajectory")
    return trajectory


def read_sbet(path: str) -> Trajectory:
    """Applanix SBET: 17 little-endian float64 per record, angles in radians.

    Returns lon/lat in degrees, ellipsoidal height, and TRUE heading
    (platform heading - wander angle) in degrees.
    """
    try:
        size = os.path.getsize(path)
        if size == 0:
            raise InputError("SBET file {path} is empty", path=path)
        if size % SBET_RECORD_BYTES:
            raise InputError("SBET file {path} is {size} bytes, not a multiple of {record} bytes "
                             "(17 float64 per record): truncated or not an SBET",
                             path=path, size=size, record=SBET_RECORD_BYTES)
        records = np.fromfile(path, dtype="<f8").reshape(-1, SBET_RECORD_FLOATS)
    except OSError as e:
        raise InputError("Cannot read SBET file {path}: {error}", path=path, error=str(e))
    bad = np.flatnonzero(~np.isfinite(records).all(axis=1))
    if bad.size:
        raise InputError("SBET file {path}, record {record}: non-finite value (NaN or infinity)",
                         path=path, record=int(bad[0]) + 1)
    t, lat, lon, alt = records[:, 0], records[:, 1], records[:, 2], records[:, 3]
    roll, pitch, platform_heading, wander = records[:, 7], records[:, 8], records[:, 9], records[:, 10]
    if np.abs(lat).max() > np.pi / 2 or np.abs(lon).max() > 2 * np.pi:
        raise InputError("SBET file {path}: latitude/longitude out of range for radians: "
                         "not an SBET, or wrong byte order", path=path)
    angles = np.abs(np.column_stack([roll, pitch, platform_heading, wander]))
    bad = np.flatnonzero((angles > 4 * np.pi).any(axis=1) | (np.abs(alt) > 1e5))
    if bad.size:
        raise InputError("SBET file {path}, record {record}: roll, pitch, heading or wander out of range "
                         "for radians, or the height beyond 100 km: not an SBET, or wrong byte order",
                         path=path, record=int(bad[0]) + 1)
    heading_true_deg = np.mod(np.degrees(platform_heading - wander), 360.0)
    locations = ["record {}".format(i + 1) for i in range(len(t))]
    trajectory = Trajectory(t, np.degrees(lon), np.degrees(lat), alt, np.degrees(roll),
                            np.degrees(pitch), heading_true_deg, path, locations)
    _check_increasing(t, locations, path, "SBET")
    return trajectory


def is_sbet_path(path: str) -> bool:
    return os.path.splitext(path)[1].lower() in SBET_EXTENSIONS


def read_trajectory(path: str) -> Trajectory:
    """A trajectory CSV, or an SBET when the file ends in .out or .sbet."""
    if not path or not os.path.isfile(path):
        raise InputError("Trajectory file not found: {path}", path=path)
    return read_sbet(path) if is_sbet_path(path) else read_trajectory_csv(path)


def read_image_times(path: str):
    """``image,time`` CSV -> (image names, times in s, locations)."""
    table = read_table(path, ("image", "time"), numeric=("time",), what="Image times")
    names = [str(n) for n in table["image"]]
    _check_names(names, table["_line"], path, "Image times")
    return names, table["time"], ["line {}".format(n) for n in table["_line"]]


def _check_names(names, lines, path, what):
    seen: Dict[str, int] = {}
    for name, line in zip(names, lines):
        if not name:
            raise InputError("{what} file {path}, line {line}, field 'image': empty image name",
                             what=what, path=path, line=int(line))
        if name in seen:
            raise InputError("{what} file {path}, line {line}: image '{image}' already listed on "
                             "line {first}", what=what, path=path, line=int(line), image=name,
                             first=seen[name])
        seen[name] = int(line)


# --- interpolation ------------------------------------------------------------------------

@dataclass
class BodyPoses:
    """Body poses at given instants; positions in the trajectory CRS (or already world)."""
    image: List[str]
    time_s: np.ndarray
    x0: np.ndarray  # the bracketing samples, for interpolation after the CRS transform
    y0: np.ndarray
    z0: np.ndarray
    x1: np.ndarray
    y1: np.ndarray
    z1: np.ndarray
    weight1: np.ndarray  # position = (1 - w) * p0 + w * p1
    rotation_ned_from_body_true: Rotation
    #: where each pose came from, for messages ("line 12"); empty when interpolated
    locations: List[str] = field(default_factory=list)


def interpolate_at(trajectory: Trajectory, names: List[str], times_s: np.ndarray,
                   locations: List[str], times_path: str, skip_outside: bool, max_gap_s: float,
                   warnings: List[str]) -> BodyPoses:
    """Interpolate the trajectory at image times.

    Image times outside the trajectory's span raise :class:`InputError` naming the first,
    unless ``skip_outside`` (then they are dropped with a count in ``warnings``). An image
    whose bracketing samples are more than ``max_gap_s`` apart adds a warning.
    """
    t = trajectory.time_s
    if len(t) < 2:
        raise InputError("Trajectory file {path} has {count} sample(s): at least 2 are needed",
                         path=trajectory.path, count=len(t))
    times_s = np.asarray(times_s, float)
    outside = (times_s < t[0]) | (times_s > t[-1])
    if outside.any():
        k = int(np.flatnonzero(outside)[0])
        if not skip_outside:
            raise InputError("Image times file {path}, {location}: time {time} of image '{image}' "
                             "is outside the trajectory's span [{start}, {end}] ({count} image(s) "
                             "outside in all; set the option to skip them)",
                             path=times_path, location=locations[k], time=repr(float(times_s[k])),
                             image=names[k], start=repr(float(t[0])), end=repr(float(t[-1])),
                             count=int(outside.sum()))
        warnings.append(Message("Skipped {count} image(s) whose time is outside the trajectory's "
                                "span [{start}, {end}], the first: {image}", count=int(outside.sum()),
                                start=t[0], end=t[-1], image=names[k]))
        keep = ~outside
        names = [n for n, k_ in zip(names, keep) if k_]
        times_s = times_s[keep]
    if len(times_s) == 0:
        raise InputError("No image time falls inside the trajectory's span [{start}, {end}]",
                         start=repr(float(t[0])), end=repr(float(t[-1])))

    i1 = np.clip(np.searchsorted(t, times_s, side="right"), 1, len(t) - 1)
    i0 = i1 - 1
    gap_s = t[i1] - t[i0]
    w = (times_s - t[i0]) / gap_s
    long_gaps = np.flatnonzero(gap_s > max_gap_s)
    if long_gaps.size:
        worst = int(long_gaps[np.argmax(gap_s[long_gaps])])
        warnings.append(Message("{count} image(s) fall in a trajectory gap longer than {max_gap} s; "
                                "the longest gap is {gap:.3f} s around image '{image}' at time "
                                "{time}", count=long_gaps.size, max_gap=max_gap_s,
                                gap=gap_s[worst], image=names[worst], time=times_s[worst]))
    slerp = Slerp(t, trajectory.rotations_ned_from_body())
    return BodyPoses(list(names), times_s,
                     trajectory.x[i0], trajectory.y[i0], trajectory.z[i0],
                     trajectory.x[i1], trajectory.y[i1], trajectory.z[i1], w, slerp(times_s))


def read_poses(path: str) -> BodyPoses:
    """Per-image pose CSV -> body poses (no interpolation; ``time`` optional)."""
    table = read_table(path, POSE_COLUMNS, numeric=POSE_COLUMNS[1:] + ("time",),
                       optional=("time",), what="Poses")
    names = [str(n) for n in table["image"]]
    _check_names(names, table["_line"], path, "Poses")
    n = len(names)
    time_s = table.get("time", np.full(n, np.nan))
    rotation = Rotation.from_euler("ZYX", np.column_stack(
        [table["heading"], table["pitch"], table["roll"]]), degrees=True)
    zeros = np.zeros(n)
    return BodyPoses(names, time_s, table["x"], table["y"], table["z"],
                     table["x"], table["y"], table["z"], zeros, rotation,
                     ["line {}".format(line) for line in table["_line"]])


# --- stations --------------------------------------------------------------------------------

def stations_from_body_poses(poses: BodyPoses, transform: WorldTransform,
                             mount: CameraMount) -> tuple:
    """World panorama centres, ``R_world_from_pano`` and forward azimuths for body poses."""
    e0, n0, u0 = transform.to_world(poses.x0, poses.y0, poses.z0)
    e1, n1, u1 = transform.to_world(poses.x1, poses.y1, poses.z1)
    w = poses.weight1
    C_body_world = np.column_stack([(1 - w) * e0 + w * e1, (1 - w) * n0 + w * n1,
                                    (1 - w) * u0 + w * u1])
    gamma_deg = transform.convergence_deg(C_body_world[:, 0], C_body_world[:, 1])
    R_ned_grid_from_body = geometry.rot_z(-gamma_deg) @ poses.rotation_ned_from_body_true.as_matrix()
    R_world_from_body = geometry.R_ENU_FROM_NED @ R_ned_grid_from_body
    lever = np.asarray(mount.lever_arm_m, float)
    C_pano_world = C_body_world + R_world_from_body @ lever
    R_world_from_pano = R_world_from_body @ mount.R_body_from_pano()
    return C_pano_world, R_world_from_pano, geometry.pano_forward_azimuth_deg(R_world_from_pano)


def _panorama_sizes(names: List[str], images_dir: str, fail_on_missing: bool,
                    warnings: List[str], progress: Progress):
    """Header sizes of each panorama; missing/unreadable ones skipped (or an error)."""
    keep, paths, widths, heights, skipped = [], [], [], [], []
    for k, name in enumerate(names):
        if k % 50 == 0:
            progress.report(k / max(len(names), 1))
        path = os.path.join(images_dir, name)
        try:
            width_px, height_px = read_image_size(path)
        except InputError as error:
            if fail_on_missing:
                raise
            skipped.append(str(error))
            continue
        check_equirectangular(path, width_px, height_px)
        keep.append(k)
        paths.append(path)
        widths.append(width_px)
        heights.append(height_px)
    if skipped:
        warnings.append(Message("Skipped {count} panorama(s) that are missing or unreadable; "
                                "the first: {path}", count=len(skipped), path=skipped[0]))
    return np.array(keep, dtype=np.int64), paths, np.array(widths), np.array(heights)


def import_stations(images_dir: str, target_crs=None, trajectory_crs=None,
                    trajectory_path: Optional[str] = None, image_times_path: Optional[str] = None,
                    poses_path: Optional[str] = None, mount: CameraMount = CameraMount(),
                    skip_outside: bool = False, max_gap_s: float = 0.5,
                    fail_on_missing_image: bool = False,
                    progress: Progress = SILENT) -> StationImport:
    """The whole import: read, interpolate, check panoramas, transform -> :class:`Stations`.

    Give either ``trajectory_path`` and ``image_times_path``, or ``poses_path``.
    ``target_crs`` must be projected (None: the trajectory CRS if projected, else its UTM
    zone); ``trajectory_crs`` is ignored for an SBET (WGS 84).
    """
    messages: List[str] = []
    warnings: List[str] = []
    if not images_dir or not os.path.isdir(images_dir):
        raise InputError("Panorama folder not found: {path}", path=images_dir)
    if poses_path:
        if trajectory_path or image_times_path:
            raise InputError("Give either a per-image pose file, or a trajectory with image times, "
                             "not both")
        poses = read_poses(poses_path)
        source_crs = trajectory_crs
        _check_source_positions(source_crs, poses.x0, poses.y0, "Poses", poses_path, poses.locations)
        progress.report(0.2)
    else:
        if not trajectory_path or not image_times_path:
            raise InputError("A trajectory file and an image times file are needed (or a "
                             "per-image pose file instead)")
        trajectory = read_trajectory(trajectory_path)
        if is_sbet_path(trajectory_path):
            source_crs = SBET_CRS
            messages.append(Message("SBET trajectory: WGS 84 geographic with ellipsoidal heights, "
                                    "{count} records", count=len(trajectory)))
        else:
            source_crs = trajectory_crs
            _check_source_positions(source_crs, trajectory.x, trajectory.y, "Trajectory",
                                    trajectory_path, trajectory.locations)
            messages.append(Message("Trajectory: {count} samples over {span:.1f} s",
                                    count=len(trajectory),
                                    span=trajectory.time_s[-1] - trajectory.time_s[0]))
        progress.report(0.1)
        names, times_s, locations = read_image_times(image_times_path)
        poses = interpolate_at(trajectory, names, times_s, locations, image_times_path,
                               skip_outside, max_gap_s, warnings)
        progress.report(0.2)

    if target_crs is None or (isinstance(target_crs, str) and not target_crs.strip()):
        target_crs = default_target_crs(source_crs, poses.x0[0], poses.y0[0])
        messages.append(Message("No target CRS given: using {crs}", crs=target_crs.name))
    transform = world_transform(source_crs, target_crs)
    messages.append(transform.height_note)

    keep, paths, widths, heights = _panorama_sizes(poses.image, images_dir, fail_on_missing_image,
                                                   warnings, progress.sub(0.2, 0.9))
    if keep.size == 0:
        raise InputError("None of the {count} panoramas listed was found in {folder}",
                         count=len(poses.image), folder=images_dir)
    poses = _select(poses, keep)
    C_pano_world, R_world_from_pano, heading_deg = stations_from_body_poses(poses, transform, mount)
    check_target_positions(poses.image, C_pano_world, transform.target)
    progress.report(1.0)
    stations = Stations(poses.image, paths, poses.time_s, C_pano_world,
                        geometry.quat_wxyz_from_matrix(R_world_from_pano), heading_deg,
                        widths, heights)
    return StationImport(stations, transform.target.to_wkt(), messages, warnings)


def _select(poses: BodyPoses, keep: np.ndarray) -> BodyPoses:
    return BodyPoses([poses.image[k] for k in keep], poses.time_s[keep], poses.x0[keep],
                     poses.y0[keep], poses.z0[keep], poses.x1[keep], poses.y1[keep],
                     poses.z1[keep], poses.weight1[keep], poses.rotation_ned_from_body_true[keep],
                     [poses.locations[k] for k in keep] if poses.locations else [])


def _check_source_positions(source_crs, x, y, what: str, path: str, locations: Sequence[str]) -> None:
    """The positions of a trajectory or pose file must be plausible in the CRS declared for
    them (lon/lat declared as a projected CRS lands a drive near the CRS's origin)."""
    crs = parse_crs(source_crs, "trajectory CRS")
    check_positions(crs, x, y, what, path, locations or ["line ?"] * len(np.atleast_1d(x)))


def check_target_positions(image: Sequence[str], xyz_world: np.ndarray, target_crs) -> None:
    """:class:`InputError` when panorama centres fall outside the target CRS's area of use
    (the target CRS of another region, whose projection distorts them badly)."""
    target = target_crs if not isinstance(target_crs, str) else parse_crs(target_crs, "target CRS")
    extent = plausible_extent(target)
    if extent is None or len(xyz_world) == 0:
        return
    x, y = xyz_world[:, 0], xyz_world[:, 1]
    bad = np.flatnonzero(~((x >= extent[0]) & (x <= extent[2]) & (y >= extent[1]) & (y <= extent[3])))
    if bad.size:
        k = int(bad[0])
        raise InputError("Panorama {image}: its position x {x}, y {y} in the target CRS lies outside the "
                         "area of use of {crs} (longitude {west} to {east}, latitude {south} to "
                         "{north}): choose the target CRS of the drive's region (e.g. its UTM zone)",
                         image=image[k], x=round(float(x[k]), 3), y=round(float(y[k]), 3),
                         **area_fields(horizontal_crs(target)))
