"""Coordinate reference systems with pyproj: parsing, transforms, meridian convergence.

CRSs are given as anything ``pyproj.CRS.from_user_input`` takes (``"EPSG:32633"``, WKT,
PROJ strings). Transforms use ``always_xy`` order: x = easting or longitude,
y = northing or latitude, z = height.
"""
from __future__ import annotations

from dataclasses import dataclass

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
