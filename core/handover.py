"""The reviewed sign layer -> a handover package for a road authority and for OpenStreetMap
(``roadsigns:exporthandover``; the schema is documented in ``docs/formats.md``, section 4.9).

* **Selection**: the signs whose review state (:mod:`.reviewstate`) is one of those asked
  for (default: accepted and corrected).
* **Code, class, name**: after review (``reviewed_code`` / ``reviewed_class`` over ``code`` /
  ``class``); the code is empty when the layer has no ``code`` field and nobody gave one;
  the name is the layer's ``name`` field, else its ``code_name`` (the codes table's name of
  ``code``, written by ``roadsigns:refinesigns``) when the code was not changed in review,
  else the class (:func:`sign_name`).
* **Position**: x, y, z in the sign layer's CRS, WGS 84 longitude and latitude (pyproj).
* **Facing**: the sign's azimuth (the direction its face looks towards) as whole degrees,
  0-359, from grid north or from true north (true = grid + meridian convergence, see
  :mod:`.crs`); the column ``azimuth_north`` says which.
* **Along the drive**: the stations, in drive order (time, else station id), are the
  track. Each sign is projected on it horizontally, on the part of the track between the
  stations that saw it (with :attr:`HandoverParams.track_window_m` either side), so a drive
  passing the same place twice links each sign to the pass that saw it: ``chainage_m``
  (along the track from its first station), ``offset_m`` (horizontal distance from the
  track) and ``side`` (``left`` / ``right`` of the direction of travel). ``facing_traffic``:
  ``drive`` when the face looks against the direction of travel (read by traffic driving
  as the survey vehicle did), ``opposite`` when it looks along it, ``crossing`` otherwise
  (more than :attr:`HandoverParams.facing_tolerance_deg` from both).
* **Road network** (optional lines in the sign layer's CRS): the nearest line's id, the
  fraction along it (0 at its first vertex, 1 at its last) and the distance to it.
* **Times**: first and last seen are the times of the earliest and latest station that saw
  the sign, in seconds of the trajectory's time base and, when the base allows, as UTC
  date and time (GPS seconds of the week need the survey date: the week is the one holding
  that date; GPS time is UTC + :func:`gps_utc_offset_s`).
* **OpenStreetMap**: one node per sign with ``traffic_sign=*`` (the code, prefixed with the
  country, ``DE:206``; without a code ``stop`` and ``give_way`` for those classes, else
  ``yes`` with a ``fixme``), ``direction=*`` (true azimuth, 0-359: OpenStreetMap is
  geographic) and ``survey:date``. The node stands **beside the road**: at the sign, moved
  away from the track to at least :attr:`HandoverParams.osm_offset_m` on the sign's side
  (signs over the road, on gantries, would otherwise sit on it), and as far from the
  nearest road line when a network is given.
"""
from __future__ import annotations

import csv
import json
import math
import os
import tempfile
from dataclasses import dataclass, field
from datetime import date, datetime, timedelta, timezone
from typing import Dict, List, Optional, Sequence, Tuple
from xml.sax.saxutils import quoteattr

import numpy as np
from pyproj import Transformer

from .crs import check_metric, horizontal_crs, parse_crs, world_transform
from .errors import SILENT, InputError, Message, Progress
from .outputs import TEMP_PREFIX
from .reviewstate import (
    CODE_FIELD,
    CONDITION_FIELD,
    DEFAULT_HANDOVER_STATES,
    NAME_FIELD,
    POLE_FIELDS,
    REVIEW_STATUS,
    REVIEWED_AT,
    STATES,
    UNREVIEWED,
    effective_class,
    effective_code,
    image_names_of,
    state_of,
)
from .schema import fields, typed_record

#: The handover table (GeoPackage layer ``handover`` and CSV ``handover.csv``), in order.
HANDOVER_FIELDS = fields(
    ("sign_id", int), ("code", str), ("name", str), ("class", str),
    ("x", float), ("y", float), ("z", float), ("lon", float), ("lat", float),
    ("height", float), ("bottom_height", float), ("width", float), ("panel_height", float),
    ("azimuth", int), ("azimuth_north", str), ("side", str), ("offset_m", float), ("chainage_m", float),
    ("facing_traffic", str), ("road_id", str), ("road_fraction", float), ("road_distance_m", float),
    ("condition", str), ("pole", str), ("survey_date", str), ("first_seen", str), ("last_seen", str),
    ("first_seen_s", float), ("last_seen_s", float), ("n_views", int), ("source_images", str),
    ("best_image", str), ("score", float), ("position_source", str), ("review_status", str),
    ("reviewed_at", str))
#: The sign layer's field with the name of its code (``roadsigns:refinesigns``).
CODE_NAME_FIELD = "code_name"
#: Sign layer fields the export needs (others are used when present).
SIGN_REQUIRED = ("sign_id", "class", "height", "width", "panel_height", "azimuth", "source_images")
#: Stations layer fields the export needs (``time`` is used when present).
STATION_REQUIRED = ("station_id", "image", "x", "y")
#: File names in the package folder.
GPKG_NAME, CSV_NAME, LAYER_NAME = "handover.gpkg", "handover.csv", "handover"
OSM_NAMES = {"osm": "osm_signs.osm", "geojson": "osm_signs.geojson"}

NORTH_GRID, NORTH_TRUE = "grid", "true"
TIME_GPS_WEEK, TIME_GPS, TIME_UNIX = "gps_week_seconds", "gps", "unix"
TIME_BASES = (TIME_GPS_WEEK, TIME_GPS, TIME_UNIX)
LEFT, RIGHT = "left", "right"
FACING_DRIVE, FACING_OPPOSITE, FACING_CROSSING = "drive", "opposite", "crossing"
#: OpenStreetMap values of classes that have one (without a code)
OSM_CLASS_VALUES = {"stop": "stop", "yield": "give_way"}
#: (first UTC day it applies, GPS - UTC in seconds); 13 s before 2006
GPS_LEAP_SECONDS = ((date(2006, 1, 1), 14), (date(2009, 1, 1), 15), (date(2012, 7, 1), 16),
                    (date(2015, 7, 1), 17), (date(2017, 1, 1), 18))
GPS_EPOCH = datetime(1980, 1, 6, tzinfo=timezone.utc)
UNIX_EPOCH = datetime(1970, 1, 1, tzinfo=timezone.utc)
#: decimals written to the CSV (others: 3)
CSV_DECIMALS = {"lon": 8, "lat": 8, "score": 3, "road_fraction": 4}


@dataclass(frozen=True)
class HandoverParams:
    """What to export and how; lengths in metres, angles in degrees."""

    states: Tuple[str, ...] = DEFAULT_HANDOVER_STATES
    north: str = NORTH_TRUE
    survey_date: Optional[date] = None
    time_base: str = TIME_GPS_WEEK
    osm_offset_m: float = 2.0
    country: str = ""
    facing_tolerance_deg: float = 60.0
    track_window_m: float = 100.0


@dataclass
class Road:
    """One road-network line: its id and its parts, ``(n, 2)`` vertices in the signs' CRS."""

    road_id: str
    parts: List[np.ndarray]


@dataclass
class OsmNode:
    """One OpenStreetMap node: ``sign_id``, WGS 84 position and tags (in order)."""

    sign_id: int
    lon: float
    lat: float
    tags: Dict[str, str]
    x: float = math.nan
    y: float = math.nan


@dataclass
class HandoverResult:
    records: List[Dict]
    nodes: List[OsmNode]
    counts: Dict[str, int]                 # signs per review state in the layer
    messages: List[Message] = field(default_factory=list)


# --- the track and the road network ---------------------------------------------------------

@dataclass
class TrackPoint:
    chainage_m: float
    offset_m: float          # signed: positive left of the direction of travel
    foot: np.ndarray         # (2,) closest point of the track
    heading_deg: float       # grid azimuth of the track there


class Track:
    """The drive as a polyline through the stations (x, y in drive order)."""

    def __init__(self, xy: np.ndarray):
        self.xy = np.asarray(xy, float).reshape(-1, 2)
        if len(self.xy) < 2 or not np.any(np.linalg.norm(np.diff(self.xy, axis=0), axis=1) > 0):
            raise InputError("The stations layer has fewer than two stations at different places: the export "
                             "needs the drive's track (chainage, side and offset of each sign)")
        self.start, self.vec = self.xy[:-1], np.diff(self.xy, axis=0)
        self.length = np.linalg.norm(self.vec, axis=1)
        self.chainage = np.concatenate([[0.0], np.cumsum(self.length)])

    def project(self, point, window: Optional[Tuple[float, float]] = None) -> TrackPoint:
        """The closest point of the track to ``point`` (x, y), among the segments that
        overlap the chainage ``window`` when given (all when none does)."""
        p = np.asarray(point, float)[:2]
        t, dist = _segment_feet(self.start, self.vec, p)
        usable = self.length > 0
        if window is not None:
            near = usable & (self.chainage[1:] >= window[0]) & (self.chainage[:-1] <= window[1])
            if np.any(near):
                usable = near
        k = int(np.flatnonzero(usable)[np.argmin(dist[usable])])
        foot = self.start[k] + t[k] * self.vec[k]
        d = self.vec[k] / self.length[k]
        cross = d[0] * (p[1] - foot[1]) - d[1] * (p[0] - foot[0])
        offset = float(np.linalg.norm(p - foot))
        return TrackPoint(float(self.chainage[k] + t[k] * self.length[k]), math.copysign(offset, cross) if offset
                          else 0.0, foot, float(math.degrees(math.atan2(d[0], d[1])) % 360.0))


def _segment_feet(start: np.ndarray, vec: np.ndarray, p: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Per segment, the parameter (0-1) of the point closest to ``p`` and its distance."""
    len2 = np.einsum("ij,ij->i", vec, vec)
    t = np.clip(np.einsum("ij,ij->i", p - start, vec) / np.where(len2 > 0, len2, 1.0), 0.0, 1.0)
    foot = start + t[:, None] * vec
    return t, np.linalg.norm(foot - p, axis=1)


def track_from_stations(stations: Sequence[Dict]) -> Tuple[Track, Dict[str, int]]:
    """The track (stations in drive order: by time when every station has one, else by
    station id) and each image's index on it."""
    rows = list(stations)
    if rows and all(r.get("time") is not None for r in rows):
        rows.sort(key=lambda r: (float(r["time"]), int(r["station_id"])))
    else:
        rows.sort(key=lambda r: int(r["station_id"]))
    xy = np.array([[float(r["x"]), float(r["y"])] for r in rows]).reshape(-1, 2)
    return Track(xy), {str(r["image"]): k for k, r in enumerate(rows)}


def nearest_road(point, roads: Sequence[Road]) -> Optional[Tuple[str, float, float, np.ndarray]]:
    """``(road id, fraction along it, distance, closest point)`` of the road line nearest
    to ``point`` (x, y); None without roads. The fraction runs along the line's parts in
    order (0 at the first vertex, 1 at the last)."""
    p = np.asarray(point, float)[:2]
    best = None
    for road in roads:
        done, total = 0.0, sum(float(np.linalg.norm(np.diff(part, axis=0), axis=1).sum()) for part in road.parts)
        for part in road.parts:
            part = np.asarray(part, float).reshape(-1, 2)
            if len(part) < 2:
                continue
            vec = np.diff(part, axis=0)
            length = np.linalg.norm(vec, axis=1)
            t, dist = _segment_feet(part[:-1], vec, p)
            k = int(np.argmin(dist))
            if best is None or dist[k] < best[2]:
                along = done + float(np.sum(length[:k])) + float(t[k] * length[k])
                best = (road.road_id, along / total if total > 0 else 0.0, float(dist[k]),
                        part[k] + t[k] * vec[k], vec[k] / max(float(length[k]), 1e-12))
            done += float(length.sum())
    if best is None:
        return None
    return best[0], best[1], best[2], best[3]


def _road_direction(point, roads: Sequence[Road]) -> Optional[np.ndarray]:
    """Unit direction of the nearest road segment to ``point``."""
    p = np.asarray(point, float)[:2]
    best, best_d = None, math.inf
    for road in roads:
        for part in road.parts:
            part = np.asarray(part, float).reshape(-1, 2)
            if len(part) < 2:
                continue
            vec = np.diff(part, axis=0)
            t, dist = _segment_feet(part[:-1], vec, p)
            k = int(np.argmin(dist))
            if dist[k] < best_d and np.linalg.norm(vec[k]) > 0:
                best, best_d = vec[k] / np.linalg.norm(vec[k]), float(dist[k])
    return best


def beside_the_road(xy, track: Track, at: TrackPoint, roads: Sequence[Road], min_offset_m: float) -> np.ndarray:
    """Where the OpenStreetMap node of a sign at ``xy`` goes: moved away from the track, on
    the sign's side (``at``: its projection), to at least ``min_offset_m``; then, with a road
    network, away from the nearest road line, on the side the point is on, as far."""
    p = np.asarray(xy, float)[:2].copy()
    heading = math.radians(at.heading_deg)
    left = np.array([-math.cos(heading), math.sin(heading)])  # left of travel direction (d = sin, cos)
    side = 1.0 if at.offset_m > 0 else -1.0
    if abs(at.offset_m) < min_offset_m:
        p = at.foot + side * min_offset_m * left
    if roads:
        near = nearest_road(p, roads)
        direction = _road_direction(p, roads)
        if near is not None and direction is not None and near[2] < min_offset_m:
            normal = np.array([-direction[1], direction[0]])
            away = np.sign(float(np.dot(p - near[3], normal))) or side * float(np.sign(np.dot(left, normal)) or 1.0)
            p = near[3] + away * min_offset_m * normal
    return p


# --- times ----------------------------------------------------------------------------------

def gps_utc_offset_s(day: date) -> int:
    """GPS time minus UTC (leap seconds) on ``day``."""
    offset = 13
    for start, seconds in GPS_LEAP_SECONDS:
        if day >= start:
            offset = seconds
    return offset


def station_time_utc(seconds: Optional[float], base: str, survey_date: Optional[date]) -> Optional[datetime]:
    """A station time in the trajectory's time base as UTC; None when unknown (no time, or
    GPS seconds of the week without the survey date)."""
    if seconds is None or not math.isfinite(float(seconds)):
        return None
    if base == TIME_UNIX:
        return UNIX_EPOCH + timedelta(seconds=float(seconds))
    if base == TIME_GPS:
        gps = GPS_EPOCH + timedelta(seconds=float(seconds))
        return gps - timedelta(seconds=gps_utc_offset_s(gps.date()))
    if base == TIME_GPS_WEEK:
        if survey_date is None:
            return None
        week_start = datetime(survey_date.year, survey_date.month, survey_date.day, tzinfo=timezone.utc) - \
            timedelta(days=(survey_date.weekday() + 1) % 7)  # GPS weeks start on Sunday
        gps = week_start + timedelta(seconds=float(seconds))
        return gps - timedelta(seconds=gps_utc_offset_s(gps.date()))
    raise InputError("Unknown time base {base}: expected one of {bases}", base=base, bases=", ".join(TIME_BASES))


def _iso(moment: Optional[datetime]) -> Optional[str]:
    return None if moment is None else moment.isoformat(timespec="seconds").replace("+00:00", "Z")


# --- the package ----------------------------------------------------------------------------

def check_output_folder(folder: str) -> None:
    """:class:`InputError` unless files can be created in ``folder`` (or, when it does not
    exist yet, in its nearest existing parent): tried with a probe file, which works for
    every user, root included."""
    if not folder:
        raise InputError("No output folder given for the handover package")
    path = os.path.abspath(folder)
    existing = path
    while not os.path.exists(existing) and os.path.dirname(existing) != existing:
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing):
        raise InputError("Cannot write the handover package to {folder}: {path} is a file, not a folder",
                         folder=folder, path=existing)
    try:
        handle, probe = tempfile.mkstemp(prefix=TEMP_PREFIX + "probe-", dir=existing)
        os.close(handle)
        os.remove(probe)
    except OSError as error:
        raise InputError("Cannot write the handover package to {folder}: the folder {path} is not writable "
                         "({error})", folder=folder, path=existing, error=error.strerror or str(error))


def sign_name(sign: Dict, code: Optional[str], klass: Optional[str]) -> Optional[str]:
    """The handover ``name`` of a sign whose code and class after review are ``code`` and
    ``klass``: the layer's ``name`` field, else its ``code_name`` when ``code`` is still the
    layer's ``code`` (a code changed in review has no name here), else the class."""
    name = str(sign.get(NAME_FIELD) or "").strip()
    if name:
        return name
    code_name = str(sign.get(CODE_NAME_FIELD) or "").strip()
    if code_name and code and code == str(sign.get(CODE_FIELD) or "").strip():
        return code_name
    return klass


def osm_sign_value(code: Optional[str], klass: Optional[str], country: str) -> Tuple[str, Optional[str]]:
    """``(traffic_sign value, fixme or None)`` of a sign: its code (prefixed ``COUNTRY:``
    unless it has a prefix), else the value of its class, else ``yes`` with a fixme."""
    if code:
        prefix = country.strip().upper()
        return (code if ":" in code or not prefix else "{}:{}".format(prefix, code)), None
    if klass in OSM_CLASS_VALUES:
        return OSM_CLASS_VALUES[klass], None
    return "yes", "sign code unknown: {} sign".format(klass or "unclassified")


def _number(value) -> Optional[float]:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def _angle_between(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


def facing_traffic(sign_azimuth: Optional[float], track_heading: float, tolerance_deg: float) -> Optional[str]:
    """``drive``, ``opposite`` or ``crossing`` (see the module doc); None without azimuth."""
    if sign_azimuth is None:
        return None
    if _angle_between(sign_azimuth, track_heading + 180.0) <= tolerance_deg:
        return FACING_DRIVE
    if _angle_between(sign_azimuth, track_heading) <= tolerance_deg:
        return FACING_OPPOSITE
    return FACING_CROSSING


def build_handover(signs: Sequence[Dict], stations: Sequence[Dict], crs, roads: Optional[Sequence[Road]] = None,
                   params: HandoverParams = HandoverParams(), progress: Progress = SILENT) -> HandoverResult:
    """The handover records (:data:`HANDOVER_FIELDS`) and OpenStreetMap nodes of the signs
    (sign layer records with ``x, y, z`` of their position) whose review state is in
    ``params.states``; ``stations``: stations layer records; ``crs``: the CRS of both (and
    of ``roads``), projected."""
    unknown = [s for s in params.states if s not in STATES]
    if unknown or not params.states:
        raise InputError("Unknown review state(s) {states}: expected some of {known}",
                         states=", ".join(unknown) or "-", known=", ".join(STATES))
    if params.north not in (NORTH_GRID, NORTH_TRUE):
        raise InputError("Unknown north {north}: expected grid or true", north=params.north)
    source_crs = parse_crs(crs, "sign layer CRS")
    check_metric(source_crs, "The sign layer")
    track, station_index = track_from_stations(stations)
    times = {str(r["image"]): _number(r.get("time")) for r in stations}
    counts = {state: 0 for state in STATES}
    chosen = []
    for sign in signs:
        state = state_of(sign.get(REVIEW_STATUS.name))
        counts[state] = counts.get(state, 0) + 1
        if state in params.states:
            chosen.append(sign)
    result = HandoverResult([], [], counts)
    if not chosen:
        raise InputError("No sign has the review state(s) {states} ({counts}): review the signs with the "
                         "review panel, or choose other states", states=", ".join(params.states),
                         counts=", ".join("{} {}".format(n, s) for s, n in counts.items() if n) or "no signs")
    if params.time_base == TIME_GPS_WEEK and params.survey_date is None and any(t is not None for t in times.values()):
        result.messages.append(progress.warning(
            "The station times are GPS seconds of the week: give the survey date to get first and last "
            "seen as dates and times (first_seen_s and last_seen_s are written)"))
    xyz = np.array([[float(s["x"]), float(s["y"]), float(s.get("z") or 0.0)] for s in chosen])
    to_lonlat = Transformer.from_crs(horizontal_crs(source_crs), "EPSG:4326", always_xy=True)
    lon, lat = (np.asarray(a, float) for a in to_lonlat.transform(xyz[:, 0], xyz[:, 1]))
    gamma = np.asarray(world_transform(source_crs, source_crs).convergence_deg(xyz[:, 0], xyz[:, 1]),
                       float).reshape(-1)
    road_list = list(roads or [])
    for k, sign in enumerate(chosen):
        progress.report(k / len(chosen))
        progress.step("Preparing the handover: sign {n} of {count}", n=k + 1, count=len(chosen))
        images = image_names_of(sign)
        seen = [station_index[name] for name in images if name in station_index]
        window = None
        if seen:
            window = (float(track.chainage[min(seen)]) - params.track_window_m,
                      float(track.chainage[max(seen)]) + params.track_window_m)
        at = track.project(xyz[k, :2], window)
        grid_azimuth = _number(sign.get("azimuth"))
        azimuth = None
        true_azimuth = None
        if grid_azimuth is not None:
            true_azimuth = (grid_azimuth + float(gamma[k])) % 360.0
            azimuth = int(round(true_azimuth if params.north == NORTH_TRUE else grid_azimuth)) % 360
        seen_times = [t for t in (times.get(name) for name in images) if t is not None]
        first_s = min(seen_times) if seen_times else None
        last_s = max(seen_times) if seen_times else None
        first = station_time_utc(first_s, params.time_base, params.survey_date)
        last = station_time_utc(last_s, params.time_base, params.survey_date)
        survey = first.date() if first is not None else params.survey_date
        code = effective_code(sign)
        klass = effective_class(sign)
        road = nearest_road(xyz[k, :2], road_list) if road_list else None
        pole = next((sign.get(name) for name in POLE_FIELDS if sign.get(name) not in (None, "")), None)
        record = {
            "sign_id": sign.get("sign_id"), "code": code or "", "class": klass,
            "name": sign_name(sign, code, klass),
            "x": xyz[k, 0], "y": xyz[k, 1], "z": sign.get("z") if sign.get("z") is not None else None,
            "lon": float(lon[k]), "lat": float(lat[k]),
            "height": sign.get("height"), "bottom_height": sign.get("bottom_height"), "width": sign.get("width"),
            "panel_height": sign.get("panel_height"), "azimuth": azimuth, "azimuth_north": params.north,
            "side": LEFT if at.offset_m > 0 else RIGHT, "offset_m": abs(at.offset_m), "chainage_m": at.chainage_m,
            "facing_traffic": facing_traffic(grid_azimuth, at.heading_deg, params.facing_tolerance_deg),
            "road_id": road[0] if road else None, "road_fraction": road[1] if road else None,
            "road_distance_m": road[2] if road else None,
            "condition": sign.get(CONDITION_FIELD), "pole": pole,
            "survey_date": survey.isoformat() if survey is not None else None,
            "first_seen": _iso(first), "last_seen": _iso(last), "first_seen_s": first_s, "last_seen_s": last_s,
            "n_views": sign.get("n_views") if sign.get("n_views") is not None else len(images) or None,
            "source_images": ";".join(images) or None, "best_image": sign.get("best_image"),
            "score": sign.get("score"), "position_source": sign.get("position_source"),
            "review_status": state_of(sign.get(REVIEW_STATUS.name)), "reviewed_at": sign.get(REVIEWED_AT.name)}
        result.records.append(typed_record(HANDOVER_FIELDS, record))
        node_xy = beside_the_road(xyz[k, :2], track, at, road_list, params.osm_offset_m)
        node_lon, node_lat = to_lonlat.transform(float(node_xy[0]), float(node_xy[1]))
        value, fixme = osm_sign_value(code, klass, params.country)
        tags = {"traffic_sign": value}
        if true_azimuth is not None:
            tags["direction"] = str(int(round(true_azimuth)) % 360)
        if survey is not None:
            tags["survey:date"] = survey.isoformat()
        if fixme:
            tags["fixme"] = fixme
        result.nodes.append(OsmNode(int(sign.get("sign_id") or k + 1), float(node_lon), float(node_lat), tags,
                                    float(node_xy[0]), float(node_xy[1])))
    progress.report(1.0)
    left = {s: n for s, n in counts.items() if n and s not in params.states}
    result.messages.append(progress.info(
        "{n} of {total} signs handed over (review states {states}); left out: {left}", n=len(result.records),
        total=len(signs), states=", ".join(params.states),
        left=", ".join("{} {}".format(n, s) for s, n in left.items()) or "none"))
    return result


# --- writers --------------------------------------------------------------------------------

def _csv_value(name: str, value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return "{:.{}f}".format(value, CSV_DECIMALS.get(name, 3))
    return str(value)


def write_csv(path: str, records: Sequence[Dict]) -> None:
    """The handover table as CSV: UTF-8, comma, a header row of :data:`HANDOVER_FIELDS`,
    NULL as an empty cell."""
    with open(path, "w", encoding="utf-8", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow([f.name for f in HANDOVER_FIELDS])
        for record in records:
            writer.writerow([_csv_value(f.name, record.get(f.name)) for f in HANDOVER_FIELDS])


def write_osm_xml(path: str, nodes: Sequence[OsmNode], generator: str = "Road Sign Inventory") -> None:
    """OpenStreetMap XML (API 0.6) that JOSM opens: new nodes (negative ids, ``-sign_id``)."""
    lines = ["<?xml version='1.0' encoding='UTF-8'?>",
             "<osm version='0.6' generator={}>".format(quoteattr(generator))]
    if nodes:
        lines.append("  <bounds minlat='{:.7f}' minlon='{:.7f}' maxlat='{:.7f}' maxlon='{:.7f}'/>".format(
            min(n.lat for n in nodes), min(n.lon for n in nodes), max(n.lat for n in nodes),
            max(n.lon for n in nodes)))
    used = set()
    for k, node in enumerate(nodes):
        node_id = -abs(node.sign_id) if node.sign_id and -abs(node.sign_id) not in used else -(10 ** 6 + k)
        used.add(node_id)
        lines.append("  <node id='{}' visible='true' lat='{:.8f}' lon='{:.8f}'>".format(node_id, node.lat, node.lon))
        lines += ["    <tag k={} v={}/>".format(quoteattr(key), quoteattr(value)) for key, value in node.tags.items()]
        lines.append("  </node>")
    lines.append("</osm>")
    with open(path, "w", encoding="utf-8", newline="\n") as stream:
        stream.write("\n".join(lines) + "\n")


def write_osm_geojson(path: str, nodes: Sequence[OsmNode]) -> None:
    """The nodes as GeoJSON (RFC 7946: WGS 84 longitude, latitude): one Point feature per
    sign, ``id`` its sign_id, the OpenStreetMap tags as properties."""
    collection = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": node.sign_id,
         "geometry": {"type": "Point", "coordinates": [round(node.lon, 8), round(node.lat, 8)]},
         "properties": dict(node.tags)} for node in nodes]}
    with open(path, "w", encoding="utf-8", newline="\n") as stream:
        json.dump(collection, stream, ensure_ascii=False, indent=1)
        stream.write("\n")


def parse_states(values: Sequence[str]) -> Tuple[str, ...]:
    """Review state names (any case) in the order of :data:`STATES`; ``unreviewed`` for
    blank ones."""
    wanted = {state_of(v) if str(v).strip() else UNREVIEWED for v in values}
    return tuple(s for s in STATES if s in wanted) + tuple(sorted(wanted - set(STATES)))
