"""Poles in a window of the cloud: sign poles, light poles, gantry posts, other poles.

Method (per window of non-ground points with their height above ground ``h``):

1. **Sections.** Points with ``h`` in ``[slice_bottom_m, slice_top_m]`` are cut into
   horizontal slices of ``slice_m``; in each slice, 2D clusters (8-connected cells of
   ``cluster_tolerance_m``, :func:`grid_clusters`) whose extent is at most
   ``max_diameter_m`` (plus a point spacing), with no other point of the slice within
   ``isolation_m``, none on two opposite sides within ``flank_m``, and round when wider than
   ``round_min_width_m`` (a straight piece is a wall's), are pole sections. Wide
   clusters (cars, walls, panels, crowns) and pieces of them are not.
2. **Chains.** Sections of consecutive slices (one missing slice allowed) whose centres
   are within ``link_m`` horizontally are chained; a chain covering at least
   ``min_run_m`` of height is a pole. Parked cars may hide a pole's lower part: the chain
   only needs to be that long somewhere.
3. **Axis.** A scanner sees the half of a pole facing it, so a section's centroid lies
   ``pi/4 r`` in front of the axis (points uniform across the visible width); each centre
   is moved back by that, away from the sensor, with the radius ``r`` from the section's
   width across the line of sight. Sections much wider than the chain's typical one (a
   panel's lower edge, a bracket) are left out. A line ``x(h), y(h)`` fitted to the
   centres gives the lean when it is significant (else the pole is vertical through their
   median) and the foot (the axis at the ground, ``z_foot`` from the ground model). A
   chain whose neighbours (within ``flank_m``, a slice below its top: not what it carries)
   lie on a straight line through it is the end of a wall sampled in stripes, not a pole.
4. **Top.** From the chain upwards, points within ``top_radius_m`` of the axis are
   followed while gaps stay under ``max_gap_m``: panels, brackets and lamp heads count,
   so a sign pole's top is its panel's top.
5. **Head.** Points within ``head_radius_m`` of the axis above ``head_from_share`` of the
   height: how far the structure connected to the axis reaches (an arm: light pole; a beam
   across the road: gantry, followed up to ``gantry_head_radius_m``) and whether the
   points connected to it form a crown (spread roundly about the axis, or mostly scattered
   foliage: a tree trunk, dropped unless it carries a sign; a neighbouring tree's crown is
   not connected to a pole; over a trunk at least ``trunk_min_diameter_m`` thick, whose
   crown's inside is hidden, the crown may be ``crown_link_m`` away and seen in a narrower
   sector, ``thick_crown_isotropy``). Whether a long head
   spans the road is decided by the caller, who knows the track (:attr:`Pole.spans_road`).

Kinds (:data:`POLE_KINDS`): ``gantry`` (the head reaches ``gantry_reach_m`` over the road
and is high, :meth:`Pole.is_gantry`; and the pole at the far end of such a beam,
:func:`promote_far_posts`),
``light_pole`` (at least ``light_pole_min_height_m``, as the height split of the Utah I-15
paper between signs and light poles), ``sign_pole`` (carries a sign),
``other``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from .schema import fields

SIGN_POLE, LIGHT_POLE, GANTRY, OTHER = "sign_pole", "light_pole", "gantry", "other"
POLE_KINDS = (SIGN_POLE, LIGHT_POLE, GANTRY, OTHER)

#: The pole layer's fields. ``sign_ids``: the carried signs' ``sign_id`` s, space separated.
POLE_FIELDS = fields(("pole_id", int), ("kind", str), ("x", float), ("y", float),
                     ("z_foot", float), ("height", float), ("diameter", float),
                     ("lean_deg", float), ("n_points", int), ("sign_ids", str))
#: A slice's points tested by :func:`_flanked` are taken from its tree this much beyond the
#: flank radius (then tested exactly), not from the whole slice.
FLANK_QUERY_PAD_M = 1e-3


@dataclass
class PoleParams:
    """Tuning of :func:`find_poles`; lengths in metres above the ground model."""

    slice_bottom_m: float = 0.3
    slice_top_m: float = 4.0
    slice_m: float = 0.25
    cluster_tolerance_m: float = 0.1
    max_diameter_m: float = 0.45
    min_radius_m: float = 0.035          # radius assumed when the measured one is smaller
    min_section_points: int = 3
    isolation_m: float = 0.2             # no other point of the slice this close to a section
    flank_m: float = 0.6                 # ... nor points this close on two opposite sides
    flank_angle_deg: float = 150.0
    round_min_width_m: float = 0.15      # sections this wide must be round (an arc, not a line):
    min_roundness: float = 0.06          # ... covariance eigenvalue ratio at least this
    min_line_points: int = 10            # points within flank_m beside a chain on a straight line ...
    line_max_ratio: float = 0.05         # (covariance eigenvalue ratio at most this) ...
    line_tolerance_m: float = 0.05       # ... that passes this close to a section: a wall's end
    link_m: float = 0.15
    min_run_m: float = 0.75
    max_width_jump_m: float = 0.1        # sections wider than the chain's typical one by more
                                         # (and twice as wide) are something else on the pole
    max_bottom_m: float = 1.75           # a chain starts this low at most (cars hide pole feet)
    top_radius_m: float = 0.35
    max_gap_m: float = 0.75
    max_height_m: float = 15.0
    min_height_m: float = 1.5
    head_radius_m: float = 8.0
    head_from_share: float = 0.5
    head_above_m: float = 2.5            # the head reaches this far above the followed top
    head_link_m: float = 0.2             # head points in adjacent cells of this are one structure
    crown_inner_m: float = 0.5           # head points beyond this from the axis: crown, arm, beam
    crown_outer_m: float = 3.0
    min_crown_points: int = 30
    crown_isotropy: float = 0.25         # their plan spread is round (l2/l1 above): a crown
    crown_min_depth_m: float = 0.8       # ... and this deep vertically
    trunk_min_diameter_m: float = 0.18   # a trunk this thick: its crown may be connected loosely
    crown_link_m: float = 0.5            # ... through cells of this
    thick_crown_isotropy: float = 0.1    # ... and seen in a narrower sector
    foliage_scattering: float = 0.12     # local PCA scattering above this: a foliage point
    foliage_share: float = 0.5           # crown points mostly foliage: a tree (either test)
    min_lean_run_m: float = 1.5          # a lean is only fitted to chains this long
    lean_significance: float = 3.0       # ... and kept when this many standard errors
    max_lean_deg: float = 15.0           # ... and at most this
    gantry_reach_m: float = 4.0
    gantry_head_radius_m: float = 16.0   # a gantry's head is followed this far (its beam)
    gantry_end_m: float = 0.6            # a pole this close to the far end of a beam is its post
    gantry_min_height_m: float = 4.5
    light_pole_min_height_m: float = 6.0


@dataclass
class Pole:
    """One pole: the foot of its axis, height, diameter, lean, kind and carried signs."""

    pole_id: int
    kind: str
    x: float
    y: float
    z_foot: float
    height: float
    diameter: float
    lean_deg: float
    n_points: int
    sign_ids: List[int] = field(default_factory=list)
    #: axis direction (unit, up) and the top of the pole, world
    axis: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))
    reach_m: float = 0.0
    crown: bool = False           # a crown around its top: a tree unless it carries a sign
    s_m: float = 0.0
    crown_isotropy: float = 0.0
    #: points of the structure at its top connected to the axis (arm, beam, panels); emptied by
    #: findsignsincloud once the pole's window is searched, but for gantries (the poles of a
    #: long drive would hold ~50 kB each)
    head_xyz: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    #: its head passes over the road (set by the caller, who knows the track)
    spans_road: bool = False

    def is_gantry(self, params: "PoleParams") -> bool:
        """A head reaching ``gantry_reach_m`` across the road, high enough."""
        return (self.reach_m >= params.gantry_reach_m and self.spans_road
                and self.height >= params.gantry_min_height_m)

    def beam_xyz(self, depth_m: float, min_distance_m: float = 1.0) -> np.ndarray:
        """The head's upper layer away from the axis (a gantry's beam, a lamp's arm):
        points at least ``min_distance_m`` from the axis within ``depth_m`` of the highest."""
        if len(self.head_xyz) == 0:
            return self.head_xyz
        d = np.linalg.norm(self.head_xyz[:, :2] - np.array([self.x, self.y]), axis=1)
        far = self.head_xyz[d >= min_distance_m]
        if len(far) == 0:
            return far
        return far[far[:, 2] >= far[:, 2].max() - depth_m]

    @property
    def foot_world(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z_foot])

    def axis_xy_at(self, z: float) -> np.ndarray:
        """The axis's horizontal position at height ``z`` (world)."""
        a = self.axis
        t = (z - self.z_foot) / max(a[2], 1e-6)
        return np.array([self.x + t * a[0], self.y + t * a[1]])

    def as_dict(self) -> dict:
        return {"pole_id": self.pole_id, "kind": self.kind, "x": self.x, "y": self.y,
                "z_foot": self.z_foot, "height": self.height, "diameter": self.diameter,
                "lean_deg": self.lean_deg, "n_points": self.n_points,
                "sign_ids": " ".join(str(i) for i in self.sign_ids)}


@dataclass
class _Section:
    k: int                 # slice index
    centre: np.ndarray     # xy of the axis (corrected)
    width: float
    n: int


def _sections(xyz: np.ndarray, h: np.ndarray, sensor: np.ndarray, params: PoleParams
              ) -> List[_Section]:
    out: List[_Section] = []
    n_slices = int(math.ceil((params.slice_top_m - params.slice_bottom_m) / params.slice_m))
    k_all = np.floor((h - params.slice_bottom_m) / params.slice_m).astype(np.int64)
    inside = (h >= params.slice_bottom_m) & (k_all < n_slices) & (k_all >= 0)
    order = np.flatnonzero(inside)
    order = order[np.argsort(k_all[order], kind="stable")]
    ks = k_all[order]
    starts = np.flatnonzero(np.r_[True, ks[1:] != ks[:-1]]) if len(ks) else np.zeros(0, np.int64)
    ends = np.r_[starts[1:], len(ks)] if len(ks) else np.zeros(0, np.int64)
    for s0, s1 in zip(starts, ends):
        rows = order[s0:s1]
        xy = xyz[rows, :2]
        labels = grid_clusters(xy, params.cluster_tolerance_m)
        slice_tree = cKDTree(xy)
        by_label = np.argsort(labels, kind="stable")     # each cluster's rows in ascending order
        sorted_labels = labels[by_label]
        bounds = np.flatnonzero(np.r_[True, sorted_labels[1:] != sorted_labels[:-1], True])
        for a, b in zip(bounds[:-1], bounds[1:]):
            if b - a < params.min_section_points:
                continue
            members = by_label[a:b]
            p = xy[members]
            mid = p.mean(axis=0)
            extent = float(np.max(np.linalg.norm(p - mid, axis=1))) * 2.0
            if extent > params.max_diameter_m + params.cluster_tolerance_m:
                continue
            around = slice_tree.query_ball_point(mid, 0.5 * extent + params.isolation_m,
                                                 return_length=True)
            if int(around) > b - a:
                continue                  # a piece of something wider
            flank_m = 0.5 * extent + params.flank_m
            near = np.sort(slice_tree.query_ball_point(mid, flank_m + FLANK_QUERY_PAD_M))
            near = near[labels[near] != labels[members[0]]]
            if _flanked(xy[near], mid, flank_m, params.flank_angle_deg):
                continue                  # one of a row of pieces (a wall sampled in stripes)
            if extent >= params.round_min_width_m and _roundness(p) < params.min_roundness:
                continue                  # a straight piece (of a wall), not the arc of a pole
            view = mid - sensor[rows[members], :2].mean(axis=0)
            view /= max(float(np.linalg.norm(view)), 1e-9)
            across = np.array([-view[1], view[0]])
            c = (p - mid) @ across
            width = float(np.percentile(c, 98) - np.percentile(c, 2)) if len(c) > 2 else 0.0
            radius = 0.5 * width
            centre = mid + (math.pi / 4.0) * radius * view
            out.append(_Section(int(ks[s0]), centre, width, int(b - a)))
    return out


def grid_clusters(xy: np.ndarray, cell_m: float) -> np.ndarray:
    """Connected groups of 2D points (labels 0..k-1): points in the same or in 8-adjacent
    cells of ``cell_m`` are connected (so points up to ~2.8 cells apart may join, points
    more than 2 cells apart in x or y never do). Much cheaper than pairwise links for
    the large slices of a window."""
    if len(xy) == 0:
        return np.zeros(0, np.int64)
    ij = np.floor((xy - xy.min(axis=0)) / cell_m).astype(np.int64)
    shape = tuple(ij.max(axis=0) + 1)
    grid = np.zeros(shape, bool)
    grid[ij[:, 0], ij[:, 1]] = True
    labels, _ = ndimage.label(grid, structure=np.ones((3, 3), bool))
    return labels[ij[:, 0], ij[:, 1]] - 1


def _ends_a_line(near: np.ndarray, centre: np.ndarray, params: PoleParams) -> bool:
    """Whether the points ``near`` a pole (in plan, over its chain's heights) lie on a
    straight line that passes through it (within ``line_tolerance_m``): the last stripes of
    a wall, not a pole beside a parked car (the car's side passes beside the pole)."""
    if len(near) < params.min_line_points:
        return False
    c = near.mean(axis=0)
    w, V = np.linalg.eigh(np.cov((near - c).T))
    if w[0] > params.line_max_ratio * w[1]:
        return False
    return abs(float((centre - c) @ V[:, 0])) <= params.line_tolerance_m


def _roundness(xy: np.ndarray) -> float:
    """Smaller over larger spread (2D covariance eigenvalues) of a section's points: a
    straight piece of wall ~0, the visible half of a round pole ~0.2 or more."""
    w = np.linalg.eigvalsh(np.cov((xy - xy.mean(axis=0)).T))
    return float(w[0] / max(w[1], 1e-12))


def _flanked(others_xy: np.ndarray, centre: np.ndarray, radius: float, angle_deg: float) -> bool:
    """Whether points within ``radius`` of ``centre`` lie on two opposite sides of it (at
    least ``angle_deg`` apart as seen from it): a piece of a wall or a hedge, not a pole
    beside a parked car."""
    rel = others_xy - centre
    d = np.linalg.norm(rel, axis=1)
    near = (d <= radius) & (d > 1e-6)
    if int(near.sum()) < 2:
        return False
    u = rel[near] / d[near, None]
    return float((u @ u.T).min()) <= math.cos(math.radians(angle_deg))


def _chains(sections: List[_Section], params: PoleParams) -> List[List[_Section]]:
    """Link sections of consecutive slices (one slice may be missing) into chains."""
    by_slice: dict = {}
    for sec in sections:
        by_slice.setdefault(sec.k, []).append(sec)
    chain_of: dict = {}
    chains: List[List[_Section]] = []
    for k in sorted(by_slice):
        for sec in by_slice[k]:
            best, best_d = None, params.link_m
            for dk in (1, 2):
                for prev in by_slice.get(k - dk, []):
                    d = float(np.linalg.norm(prev.centre - sec.centre))
                    if d <= best_d and chains[chain_of[id(prev)]][-1] is prev:
                        best, best_d = prev, d
                if best is not None:
                    break
            if best is None:
                chain_of[id(sec)] = len(chains)
                chains.append([sec])
            else:
                c = chain_of[id(best)]
                chains[c].append(sec)
                chain_of[id(sec)] = c
    return chains


def find_poles(xyz: np.ndarray, h: np.ndarray, sensor: np.ndarray, scattering: np.ndarray,
               ground_z, params: Optional[PoleParams] = None) -> List[Pole]:
    """Poles among a window's non-ground points.

    ``xyz`` ``(n, 3)`` world, ``h`` height above ground, ``sensor`` ``(n, 3)`` the scanner
    position of each point, ``scattering`` the local PCA scattering (``l3 / l1``) of each
    point, ``ground_z(xy) -> z`` the ground model. Returns poles with ids 0 (numbered by
    the caller); tree trunks among them have ``crown`` set.
    """
    params = params or PoleParams()
    if len(xyz) == 0:
        return []
    chains = [c for c in _chains(_sections(xyz, h, sensor, params), params)
              if (c[-1].k - c[0].k + 1) * params.slice_m >= params.min_run_m
              and params.slice_bottom_m + c[0].k * params.slice_m <= params.max_bottom_m]
    if not chains:
        return []
    tree = cKDTree(xyz[:, :2])
    poles: List[Pole] = []
    taken = np.zeros(len(chains), bool)
    centres = np.array([np.mean([s.centre for s in c], axis=0) for c in chains])
    for i, chain in enumerate(chains):
        if taken[i]:
            continue
        # chains of one pole broken by an occluded stretch: merge those on the same axis
        same = np.flatnonzero(~taken & (np.linalg.norm(centres - centres[i], axis=1) <= params.link_m))
        taken[same] = True
        secs = [s for j in same for s in chains[j]]
        pole = _pole_from_sections(secs, xyz, h, scattering, tree, ground_z, params)
        if pole is not None:
            poles.append(pole)
    return poles


def _pole_from_sections(secs: Sequence[_Section], xyz: np.ndarray, h: np.ndarray,
                        scattering: np.ndarray, tree: cKDTree, ground_z, params: PoleParams
                        ) -> Optional[Pole]:
    widths = np.array([s.width for s in secs])
    typical = float(np.median(widths))
    secs = [s for s in secs if s.width <= max(2.0 * typical, typical + params.max_width_jump_m)]
    hs = np.array([params.slice_bottom_m + (s.k + 0.5) * params.slice_m for s in secs])
    cs = np.array([s.centre for s in secs])
    foot_xy = np.median(cs, axis=0)
    slope = np.zeros(2)
    if len(secs) >= 4 and np.ptp(hs) >= params.min_lean_run_m:
        A = np.column_stack([np.ones_like(hs), hs])
        coef, res, *_ = np.linalg.lstsq(A, cs, rcond=None)
        resid = cs - A @ coef
        sigma2 = float(np.sum(resid ** 2)) / max(2 * (len(hs) - 2), 1)
        se = math.sqrt(sigma2 / max(float(np.sum((hs - hs.mean()) ** 2)), 1e-9))
        fitted = coef[1]
        if (float(np.linalg.norm(fitted)) > params.lean_significance * se
                and float(np.linalg.norm(fitted)) <= math.tan(math.radians(params.max_lean_deg))):
            foot_xy, slope = coef[0], fitted
    # the last stripes of a sparsely sampled wall line up with the "pole": not a pole
    side = np.asarray(tree.query_ball_point(foot_xy, 0.5 * typical + params.flank_m), dtype=np.int64)
    side = side[(h[side] >= params.slice_bottom_m) & (h[side] <= hs.max() - params.slice_m)]
    side = side[np.linalg.norm(xyz[side, :2] - foot_xy, axis=1) > 0.5 * typical + params.cluster_tolerance_m]
    if _ends_a_line(xyz[side, :2], foot_xy, params):
        return None
    z_foot = float(ground_z(foot_xy[None, :])[0])
    axis = np.array([slope[0], slope[1], 1.0])
    axis /= np.linalg.norm(axis)

    # follow the structure up from the chain's top, within top_radius_m of the axis
    near = np.asarray(tree.query_ball_point(foot_xy, params.top_radius_m + params.max_height_m
                                            * float(np.linalg.norm(slope))), dtype=np.int64)
    if len(near) == 0:
        return None
    rel_h = h[near]
    axis_xy = foot_xy[None, :] + rel_h[:, None] * slope[None, :]
    close = np.linalg.norm(xyz[near, :2] - axis_xy, axis=1) <= params.top_radius_m
    col_h = np.sort(rel_h[close])
    top = float(hs.max() + 0.5 * params.slice_m)
    for value in col_h[col_h > top]:
        if value - top > params.max_gap_m:
            break
        top = float(value)
    top = min(top, params.max_height_m)
    if top < params.min_height_m:
        return None
    n_points = int(np.count_nonzero(close & (rel_h <= top + 0.05)))

    # the head: how far the structure reaches from the axis, and is it a crown
    head = np.asarray(tree.query_ball_point(foot_xy, params.head_radius_m), dtype=np.int64)
    head = head[(h[head] >= params.head_from_share * top) & (h[head] <= top + params.head_above_m)]
    reach = 0.0
    has_crown = False
    isotropy = 0.0
    head_xyz = np.zeros((0, 3))
    if len(head):
        rel = xyz[head, :2] - (foot_xy[None, :] + h[head][:, None] * slope[None, :])
        d = np.linalg.norm(rel, axis=1)
        reach, connected = _connected_reach(xyz[head], d, params)
        head_xyz = xyz[head][connected]
        ring = connected & (d > params.crown_inner_m) & (d <= params.crown_outer_m)
        if int(ring.sum()) >= params.min_crown_points:
            has_crown, isotropy = _is_crown(rel[ring], h[head][ring], scattering[head][ring], params,
                                            params.crown_isotropy)
        thick = float(np.median([sec.width for sec in secs])) >= params.trunk_min_diameter_m
        if not has_crown and thick:          # a crown floating over a thick trunk (its inside hidden)
            _, loose = _connected_reach(xyz[head], d, params, params.crown_link_m)
            ring = loose & (d > params.crown_inner_m) & (d <= params.crown_outer_m)
            if int(ring.sum()) >= params.min_crown_points:
                has_crown, isotropy = _is_crown(rel[ring], h[head][ring], scattering[head][ring], params,
                                                params.thick_crown_isotropy)
    if reach >= params.gantry_reach_m:       # a gantry: its whole beam, for the far post
        wide = np.asarray(tree.query_ball_point(foot_xy, params.gantry_head_radius_m), dtype=np.int64)
        wide = wide[(h[wide] >= params.head_from_share * top) & (h[wide] <= top + params.head_above_m)]
        d_wide = np.linalg.norm(xyz[wide, :2] - (foot_xy[None, :] + h[wide][:, None] * slope[None, :]), axis=1)
        reach, connected = _connected_reach(xyz[wide], d_wide, params)
        head_xyz = xyz[wide][connected]
    diameter = float(np.median([s.width for s in secs]))
    return Pole(0, OTHER, float(foot_xy[0]), float(foot_xy[1]), z_foot, top, diameter,
                float(math.degrees(math.acos(min(1.0, axis[2])))), n_points, [], axis,
                reach, has_crown, 0.0, isotropy, head_xyz)


def _is_crown(rel_xy: np.ndarray, h: np.ndarray, scattering: np.ndarray, params: PoleParams,
              min_isotropy: float) -> Tuple[bool, float]:
    """Points around a pole's top that spread roundly about its axis in plan (second
    moments about the axis at least ``min_isotropy`` of each other) and in depth (a crown
    seen from one side is a half shell around the trunk), or that are mostly foliage;
    arms, beams and panels spread along a line, a neighbour's crown lies to one side."""
    w = np.linalg.eigvalsh(rel_xy.T @ rel_xy / len(rel_xy))
    isotropy = float(w[0] / max(w[1], 1e-12))
    if float(np.mean(scattering > params.foliage_scattering)) >= params.foliage_share:
        return True, isotropy
    return isotropy >= min_isotropy and float(np.ptp(h)) >= params.crown_min_depth_m, isotropy


def _connected_reach(head_xyz: np.ndarray, dist_axis: np.ndarray, params: PoleParams,
                     link_m: Optional[float] = None) -> Tuple[float, np.ndarray]:
    """Horizontal reach from the axis of the head points connected to the axis (an arm, a
    beam), not of unrelated objects within the head radius; and those points (mask).
    Connected: in 26-adjacent cells of ``link_m`` (``head_link_m``)."""
    on_axis = dist_axis <= params.top_radius_m
    if not on_axis.any():
        return 0.0, on_axis
    cell = params.head_link_m if link_m is None else link_m
    ijk = np.floor((head_xyz - head_xyz.min(axis=0)) / cell).astype(np.int64)
    grid = np.zeros(tuple(ijk.max(axis=0) + 1), bool)
    grid[ijk[:, 0], ijk[:, 1], ijk[:, 2]] = True
    labels, _ = ndimage.label(grid, structure=np.ones((3, 3, 3), bool))
    point_label = labels[ijk[:, 0], ijk[:, 1], ijk[:, 2]]
    connected = np.isin(point_label, np.unique(point_label[on_axis]))
    return float(dist_axis[connected].max()), connected


def promote_far_posts(poles: Sequence[Pole], params: Optional[PoleParams] = None) -> int:
    """Mark the post at the far end of each gantry's beam as a gantry post (its head may be
    hidden, by a crown for instance, so that it looked like a tree or a short pole): the
    pole nearest to the beam's far end, within ``gantry_end_m``. Returns how many."""
    params = params or PoleParams()
    promoted = 0
    for g in [p for p in poles if p.is_gantry(params) and not p.crown]:
        beam = g.beam_xyz(params.max_gap_m)
        if len(beam) == 0:
            continue
        far = beam[int(np.argmax(np.linalg.norm(beam[:, :2] - np.array([g.x, g.y]), axis=1)))]
        best, best_d = None, params.gantry_end_m
        for p in poles:
            if p is g or p.is_gantry(params):
                continue
            d = float(np.hypot(p.x - far[0], p.y - far[1]))
            if d <= best_d:
                best, best_d = p, d
        if best is not None:
            best.reach_m, best.head_xyz, best.crown, best.spans_road = g.reach_m, g.head_xyz, False, True
            best.height = max(best.height, float(far[2] - best.z_foot))
            promoted += 1
    return promoted


def classify_pole(pole: Pole, n_signs: int, params: Optional[PoleParams] = None) -> str:
    """The kind of a (non-tree) pole from its height, head reach and the signs it carries."""
    params = params or PoleParams()
    if pole.is_gantry(params):
        return GANTRY
    if pole.height >= params.light_pole_min_height_m:
        return LIGHT_POLE
    if n_signs > 0:
        return SIGN_POLE
    return OTHER


def pole_records(poles: Sequence[Pole]) -> List[dict]:
    """The pole layer's records (:data:`POLE_FIELDS`)."""
    return [p.as_dict() for p in poles]
