"""Coordinate reference systems with pyproj: parsing, transforms, meridian convergence.

CRSs are given as anything ``pyproj.CRS.from_user_input`` takes (``"EPSG:32633"``, WKT,
PROJ strings). Transforms use ``always_xy`` order: x = easting or longitude,
y = northing or latitude, z = height.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np
from pyproj import CRS, Proj, Transformer
from pyproj.exceptions import CRSError

from .errors import InputError, Message


def parse_crs(user_input, role: str = "CRS") -> CRS:
    """Parse a CRS or raise :class:`InputError` naming its ``role`` ("trajectory CRS", ...)."""
    if user_input is None or (isinstance(user_input, str) and not user_input.strip()):
        raise InputError("No {role} given: expected an EPSG code, WKT or PROJ string", role=role)
    try:
        return CRS.from_user_input(user_input)
    except CRSError as e:
        raise InputError("Unknown {role} '{crs}': {error}", role=role, crs=str(user_input)[:200],
                         error=str(e))


def horizontal_crs(crs: CRS) -> CRS:
    """The horizontal part of a compound CRS (the CRS itself otherwise)."""
    if crs.is_compound:
        for sub in crs.sub_crs_list:
            if not sub.is_vertical:
                return sub
    return crs


def is_projected(crs: CRS) -> bool:
    return horizontal_crs(crs).is_projected


def has_vertical(crs: CRS) -> bool:
    """True for a compound CRS (or a 3D one) whose heights a transform may change."""
    return crs.is_compound or crs.is_vertical


def utm_crs_for(lon_deg: float, lat_deg: float) -> CRS:
    """The WGS 84 / UTM zone CRS containing the point."""
    zone = int(np.floor((lon_deg + 180.0) / 6.0)) % 60 + 1
    return CRS.from_epsg((32600 if lat_deg >= 0 else 32700) + zone)


@dataclass
class WorldTransform:
    """Positions from a source CRS to the projected target (world) CRS, plus convergence.

    ``gamma_deg`` gives the meridian convergence (grid north relative to true north) of the
    target's horizontal projection at the given points: grid heading = true heading - gamma.
    """
    source: CRS
    target: CRS
    heights_transformed: bool

    def __post_init__(self):
        if self.heights_transformed and self.source.is_geographic and len(self.source.axis_info) == 2:
            self.source = self.source.to_3d()  # lon/lat + ellipsoidal height, as docs/formats.md states
        self._to_target = Transformer.from_crs(self.source, self.target, always_xy=True)
        if not self.heights_transformed:
            self.height_note = Message("Heights: pass through unchanged (the target CRS has no "
                                       "vertical datum)")
        elif "ballpark vertical" in self._to_target.description.lower():
            self.height_note = Message("Heights: the geoid grid for {crs} is not installed: heights "
                                       "stay as they are (ellipsoidal), only the horizontal "
                                       "position is transformed", crs=self.target.name)
        else:
            self.height_note = Message("Heights: transformed to {crs}: {operation}",
                                       crs=self.target.name,
                                       operation=self._to_target.description)
        target_h = horizontal_crs(self.target)
        self._target_proj = Proj(target_h)
        self._target_to_geographic = Transformer.from_crs(target_h, target_h.geodetic_crs,
                                                          always_xy=True)

    def to_world(self, x, y, z):
        """Source coordinates -> world (E, N, U) arrays; raises InputError on failure."""
        x, y, z = (np.asarray(a, float) for a in (x, y, z))
        try:
            e, n, u = self._to_target.transform(x, y, z, errcheck=True)
        except Exception as error:  # pyproj raises ProjError with PROJ's message
            raise InputError("Cannot transform positions from {source} to {target}: {error}",
                             source=self.source.to_string(), target=self.target.to_string(),
                             error=str(error))
        e, n, u = (np.asarray(a, float) for a in (e, n, u))
        if not (np.isfinite(e).all() and np.isfinite(n).all() and np.isfinite(u).all()):
            raise InputError("Transforming positions from {source} to {target} gave invalid "
                             "values (outside the CRS's area, or a missing vertical grid)",
                             source=self.source.to_string(), target=self.target.to_string())
        if not self.heights_transformed:
            u = z.copy()
        return e, n, u

    def convergence_deg(self, e_world, n_world):
        """Meridian convergence gamma (degrees) at world points, pyproj's sign convention."""
        lon, lat = self._target_to_geographic.transform(np.asarray(e_world, float),
                                                        np.asarray(n_world, float))
        factors = self._target_proj.get_factors(lon, lat)
        return np.asarray(factors.meridian_convergence, float)


def default_target_crs(source_crs, x, y) -> CRS:
    """The target when the user gives none: the source if projected, else its UTM zone at (x, y)."""
    source = source_crs if isinstance(source_crs, CRS) else parse_crs(source_crs, "trajectory CRS")
    if is_projected(source):
        return source
    to_lonlat = Transformer.from_crs(horizontal_crs(source), "EPSG:4326", always_xy=True)
    lon, lat = to_lonlat.transform(float(x), float(y))
    return utm_crs_for(lon, lat)


def world_transform(source_crs, target_crs) -> WorldTransform:
    """Build the transform to a projected target; heights change only for a vertical target."""
    source = parse_crs(source_crs, "trajectory CRS") if not isinstance(source_crs, CRS) else source_crs
    target = parse_crs(target_crs, "target CRS") if not isinstance(target_crs, CRS) else target_crs
    if not is_projected(target):
        raise InputError("The target CRS {crs} is not projected: expected a projected CRS in "
                         "metres (e.g. a UTM zone)", crs=target.name)
    return WorldTransform(source, target, heights_transformed=has_vertical(target))


# --- plausibility: positions against the CRS's area of use ------------------------------

#: Margins around a CRS's area of use inside which positions are still plausible: a tenth
#: of the area's size on each side plus this much (a drive just across a zone border).
AREA_MARGIN_DEG = 0.5
AREA_MARGIN_M = 10_000.0


def _as_crs(crs, role: str = "CRS") -> CRS:
    return crs if isinstance(crs, CRS) else parse_crs(crs, role)


def area_of_use_lonlat(crs) -> Optional[Tuple[float, float, float, float]]:
    """``(west, south, east, north)`` in degrees of the CRS's area of use, None if unknown."""
    crs = _as_crs(crs)
    area = crs.area_of_use or horizontal_crs(crs).area_of_use
    if area is None:
        return None
    return float(area.west), float(area.south), float(area.east), float(area.north)


def plausible_extent(crs) -> Optional[Tuple[float, float, float, float]]:
    """``(xmin, ymin, xmax, ymax)`` in the CRS's own x, y (easting/northing or lon/lat) where
    positions are plausible: its area of use with a margin. None when the CRS has no
    area of use, or one that cannot be expressed as a box (across the antimeridian)."""
    crs = _as_crs(crs)
    bounds = area_of_use_lonlat(crs)
    if bounds is None:
        return None
    west, south, east, north = bounds
    h = horizontal_crs(crs)
    if h.is_geographic:
        if west > east:
            return None
        xmin, ymin, xmax, ymax, margin = west, south, east, north, AREA_MARGIN_DEG
    elif h.is_projected:
        try:
            to_crs = Transformer.from_crs(h.geodetic_crs, h, always_xy=True)
            xmin, ymin, xmax, ymax = to_crs.transform_bounds(west, south, east, north, densify_pts=21)
        except Exception:  # PROJ cannot project the area (exotic projections): no check
            return None
        margin = AREA_MARGIN_M
    else:
        return None
    if not (np.isfinite([xmin, ymin, xmax, ymax]).all() and xmin < xmax and ymin < ymax):
        return None
    dx, dy = 0.1 * (xmax - xmin) + margin, 0.1 * (ymax - ymin) + margin
    if h.is_geographic:
        return xmin - dx, max(ymin - dy, -90.0), xmax + dx, min(ymax + dy, 90.0)
    return xmin - dx, ymin - dy, xmax + dx, ymax + dy


def looks_like_lonlat(x, y) -> bool:
    """All positions within longitude/latitude ranges (the usual mistake: lon/lat declared
    in a projected CRS)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return bool(x.size and (np.abs(x) <= 360.0).all() and (np.abs(y) <= 90.0).all())


def area_fields(crs: CRS) -> dict:
    """Message fields naming ``crs`` and its area of use: crs, west, south, east, north."""
    west, south, east, north = area_of_use_lonlat(crs) or (np.nan,) * 4
    return dict(crs=crs.name, west=round(west, 2), south=round(south, 2), east=round(east, 2),
                north=round(north, 2))


def check_positions(crs, x, y, what: str, path: str, locations: Sequence[str]) -> None:
    """:class:`InputError` naming the file and line of the first position (x, y in the
    CRS's own order, ``always_xy``) that is implausible for ``crs``: not a longitude/latitude
    for a geographic CRS, or outside the CRS's area of use (with a margin). ``what`` and
    ``locations`` as in the readers ("Trajectory", ["line 2", ...])."""
    crs = _as_crs(crs)
    x, y = np.asarray(x, float).reshape(-1), np.asarray(y, float).reshape(-1)
    if horizontal_crs(crs).is_geographic:
        bad = np.flatnonzero(~((np.abs(y) <= 90.0) & (x >= -180.0) & (x <= 360.0)))
        if bad.size:
            k = int(bad[0])
            raise InputError("{what} file {path}, {location}: x {x}, y {y} is not a longitude/latitude, "
                             "but {crs} is a geographic CRS: are these projected coordinates? Give "
                             "the CRS the positions are in", what=what, path=path,
                             location=locations[k], x=round(float(x[k]), 3), y=round(float(y[k]), 3),
                             crs=crs.name)
    extent = plausible_extent(crs)
    if extent is None:
        return
    xmin, ymin, xmax, ymax = extent
    bad = np.flatnonzero(~((x >= xmin) & (x <= xmax) & (y >= ymin) & (y <= ymax)))
    if not bad.size:
        return
    k = int(bad[0])
    fields = dict(what=what, path=path, location=locations[k], x=round(float(x[k]), 3),
                  y=round(float(y[k]), 3), **area_fields(crs))
    if not horizontal_crs(crs).is_geographic and looks_like_lonlat(x, y):
        raise InputError("{what} file {path}, {location}: x {x}, y {y} lies outside the area of use "
                         "of {crs} (longitude {west} to {east}, latitude {south} to {north}) and "
                         "looks like a longitude/latitude: give a geographic CRS (e.g. EPSG:4326) "
                         "for these positions", **fields)
    raise InputError("{what} file {path}, {location}: x {x}, y {y} lies outside the area of use of "
                     "{crs} (longitude {west} to {east}, latitude {south} to {north}): is {crs} the "
                     "CRS of these positions?", **fields)


def check_extent(crs, bounds: Sequence[float], label: str) -> None:
    """:class:`InputError` when the box ``bounds`` (xmin, ymin, xmax, ymax) of a cloud or a
    layer (``label``: its file or name) does not lie within the area of use of ``crs``."""
    crs = _as_crs(crs)
    xmin, ymin, xmax, ymax = (float(v) for v in bounds[:4])
    if not np.isfinite([xmin, ymin, xmax, ymax]).all():
        return
    extent = plausible_extent(crs)
    if extent is None:
        return
    if xmin >= extent[0] and ymin >= extent[1] and xmax <= extent[2] and ymax <= extent[3]:
        return
    fields = dict(label=label, xmin=round(xmin, 3), xmax=round(xmax, 3), ymin=round(ymin, 3),
                  ymax=round(ymax, 3), **area_fields(crs))
    if not horizontal_crs(crs).is_geographic and looks_like_lonlat([xmin, xmax], [ymin, ymax]):
        raise InputError("{label}: x {xmin} to {xmax}, y {ymin} to {ymax} lie outside the area of use "
                         "of {crs} (longitude {west} to {east}, latitude {south} to {north}) and look "
                         "like longitudes/latitudes: is {crs} the CRS of these coordinates?", **fields)
    raise InputError("{label}: x {xmin} to {xmax}, y {ymin} to {ymax} lie outside the area of use of "
                     "{crs} (longitude {west} to {east}, latitude {south} to {north}): is {crs} the "
                     "CRS of these coordinates?", **fields)


def check_metric(crs, label: str) -> None:
    """:class:`InputError` unless ``crs`` is projected (metres), for the stages that measure
    distances (``label``: the layer or file it belongs to)."""
    crs = _as_crs(crs)
    if not is_projected(crs):
        raise InputError("{label} is in {crs}, a geographic CRS (degrees): this needs a projected CRS "
                         "in metres, the CRS of the point cloud (e.g. a UTM zone)", label=label,
                         crs=crs.name)
