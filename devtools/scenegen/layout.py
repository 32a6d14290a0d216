"""Scene layout: where signs, poles, trees, buildings, cars and distractors stand.

Everything is drawn from one ``numpy.random.Generator`` in a fixed order, so a seed fixes
the scene. Coordinates are local ENU metres (world = local + origin); see ``road.py`` for the
road coordinates (s, t).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import textures as tx
from .primitives import Box, Crown, Cylinder, Panel
from .road import Road

#: LAS classification codes written to cloud.laz (ASPRS 2/5/6, user codes from 64)
CLASS_CODES = {
    "ground": 2,             # road, markings, parking strip, curbs, sidewalk, grass verge
    "high_vegetation": 5,    # tree crowns and trunks
    "building": 6,
    "sign_panel": 64,        # every reference sign panel (front and back face)
    "sign_support": 65,      # sign poles and the overhead gantry structure
    "pole": 66,              # lamp posts, billboard legs, mirror poles
    "car": 67,
    "billboard": 68,
    "traffic_mirror": 69,
    "street_furniture": 70,  # bins, containers, hydrants (red and blue distractors)
}

#: LiDAR reflectance in [0, 1] per material (scaled to the 16-bit intensity)
REFLECTANCE = {
    "asphalt": 0.08, "marking": 0.55, "parking": 0.10, "sidewalk": 0.25, "curb": 0.30, "grass": 0.18,
    "building": 0.30, "foliage": 0.22, "trunk": 0.15, "pole": 0.35, "car": 0.25,
    "sign_face": 0.95, "sign_face_faded": 0.22, "sign_back": 0.30, "billboard": 0.40,
    "mirror": 0.55, "furniture": 0.20,
}

METAL = (0.62, 0.63, 0.66)
CAR_COLOURS = [(0.75, 0.08, 0.08), (0.1, 0.2, 0.6), (0.85, 0.85, 0.87), (0.1, 0.1, 0.11),
               (0.5, 0.52, 0.55), (0.6, 0.05, 0.05), (0.15, 0.35, 0.7)]
BUILDING_COLOURS = [(0.85, 0.78, 0.62), (0.78, 0.72, 0.70), (0.9, 0.88, 0.82), (0.72, 0.55, 0.45),
                    (0.8, 0.82, 0.85), (0.65, 0.7, 0.62)]
CLASSES = ["warning", "prohibitory", "mandatory", "information", "stop", "yield"]


@dataclass
class SignInfo:
    """One reference sign panel (local ENU; world = local + origin)."""

    sign_id: int
    cls: str
    variant: str
    panel: Panel
    height_above_ground: float
    mount: str        # pole, shared_pole, gantry, lamp_post
    facing: str       # oncoming (faces the survey vehicle's approach) or away
    faded: bool
    near_tree: bool


#: kinds of :class:`PoleInfo` (``reference_poles.csv``)
POLE_KINDS = ("sign_pole", "light_pole", "gantry", "other")


@dataclass
class PoleInfo:
    """One vertical support (local ENU): its axis foot on the ground and what it carries.

    ``kind``: ``sign_pole`` (carries signs only), ``light_pole`` (lamp post, maybe with a
    sign), ``gantry`` (one post of an overhead gantry; both posts list the gantry's signs),
    ``other`` (traffic-mirror pole, billboard leg). Tree trunks are not poles.
    """

    pole_id: int
    kind: str
    foot: np.ndarray          # axis at ground level (local ENU)
    height: float             # top of the pole above ``foot``
    diameter: float
    sign_ids: list = field(default_factory=list)
    structure_id: int = 0     # posts of one gantry (or legs of one billboard) share it


@dataclass
class Scene:
    road: Road
    prims: list = field(default_factory=list)
    signs: list = field(default_factory=list)
    distractors: list = field(default_factory=list)   # dicts: kind, local xyz
    poles: list = field(default_factory=list)         # PoleInfo


class _Occupancy:
    """Busy intervals of s per side of the road, to keep roadside objects apart."""

    def __init__(self):
        self.busy = {1: [], -1: []}

    def free(self, side, s, half):
        return all(abs(s - s0) > half + h0 for s0, h0 in self.busy[side])

    def take(self, side, s, half):
        self.busy[side].append((s, half))


class _Builder:
    def __init__(self, preset, rng):
        self.p, self.rng = preset, rng
        grad_dir = rng.uniform(0, 2 * np.pi)
        grad = rng.uniform(0.015, 0.04)
        self.road = Road(curvature=preset.curvature_per_m * (1 if rng.random() < 0.5 else -1),
                         start_angle_rad=rng.uniform(0, 2 * np.pi),
                         gradient=(grad * np.cos(grad_dir), grad * np.sin(grad_dir)))
        self.scene = Scene(self.road)
        self.occ = _Occupancy()
        self.parking = _Occupancy()
        self.s_lo = -preset.scenery_margin_m
        self.s_hi = preset.road_length_m + preset.scenery_margin_m
        self.class_cycle = []
        self.texture_cache = {}

    # --- helpers -----------------------------------------------------------------
    def frame(self, s):
        """Unit tangent (driving direction) and right normal at s, as 3-vectors."""
        b = self.road.tangent_angle(s)
        return np.array([np.cos(b), np.sin(b), 0.0]), np.array([np.sin(b), -np.cos(b), 0.0])

    def at(self, s, t, height_above_ground=0.0):
        xy = self.road.point(s, t)
        return np.array([xy[0], xy[1], float(self.road.ground_z(xy[0], xy[1])) + height_above_ground])

    def next_class(self):
        if not self.class_cycle:
            self.class_cycle = list(self.rng.permutation(CLASSES))
        return self.class_cycle.pop()

    def add_pole(self, kind, base_xy, radius, top_z, sign_ids=(), structure_id=0):
        """Record a pole's truth (no random draw: the layout stays the same for a seed)."""
        foot = np.array([base_xy[0], base_xy[1], float(self.road.ground_z(base_xy[0], base_xy[1]))])
        pole = PoleInfo(len(self.scene.poles) + 1, kind, foot, float(top_z) - foot[2], 2.0 * float(radius),
                        list(sign_ids), structure_id or len(self.scene.poles) + 1)
        self.scene.poles.append(pole)
        return pole

    def textures(self, key, make):
        if key not in self.texture_cache:
            self.texture_cache[key] = tx.pyramid(make())
        return self.texture_cache[key]

    def add_sign(self, cls, centre, normal, mount, facing, faded=False, variant=None, size=None, near_tree=False):
        variant = variant or tx.VARIANTS[cls][int(self.rng.integers(len(tx.VARIANTS[cls])))]
        w, h = size or ((1.0, 0.6) if variant == "direction" else tx.PANEL_SIZE[cls])
        key = ("sign", cls, variant, faded)
        levels = self.textures(key, lambda: (tx.faded if faded else (lambda x: x))(tx.sign_texture(cls, variant)))
        sign_id = len(self.scene.signs) + 1
        panel = Panel(centre, normal, w, h, levels, back_rgb=METAL,
                      front_reflectance=REFLECTANCE["sign_face_faded" if faded else "sign_face"],
                      back_reflectance=REFLECTANCE["sign_back"], class_code=CLASS_CODES["sign_panel"],
                      sign_id=sign_id, retroreflective=not faded)
        ground = float(self.road.ground_z(centre[0], centre[1]))
        self.scene.signs.append(SignInfo(sign_id, cls, variant, panel, float(centre[2]) - ground,
                                         mount, facing, faded, near_tree))
        self.scene.prims.append(panel)
        return panel

    def sign_normal(self, s, side, facing):
        """Face normal: against (oncoming) or along (away) the driving direction, turned ~6 deg to the road."""
        T, N = self.frame(s)
        along = -T if facing == "oncoming" else T
        n = along - side * N * np.tan(np.radians(self.rng.uniform(3, 9)))
        return n / np.linalg.norm(n)

    # --- furniture ---------------------------------------------------------------
    def pole_group(self, s, side, facing, classes, mount="pole", faded=False, near_tree=False):
        """One pole with panels stacked downwards from the top (first class on top)."""
        t = side * self.rng.uniform(5.85, 6.2)
        normal = self.sign_normal(s, side, facing)
        base = self.at(s, t)
        bottom = self.rng.uniform(2.0, 2.4)
        sizes = [tx.PANEL_SIZE[c] for c in classes]
        top = bottom + sum(h for _, h in sizes) + 0.08 * (len(classes) - 1)
        z = base[2] + top
        pole_xy = base[:2] - 0.06 * normal[:2]
        carried = []
        for cls, (w, h) in zip(classes, sizes):
            centre = np.array([base[0], base[1], z - h / 2])
            carried.append(self.add_sign(cls, centre, normal, mount, facing, faded=faded, near_tree=near_tree).sign_id)
            z -= h + 0.08
        self.scene.prims.append(Cylinder(pole_xy, 0.035, base[2] - 0.3, base[2] + top + 0.05, METAL,
                                         REFLECTANCE["pole"], CLASS_CODES["sign_support"]))
        self.add_pole("sign_pole", pole_xy, 0.035, base[2] + top + 0.05, carried)
        self.occ.take(side, s, 1.0)

    def tree(self, s, side, t=None, crown_r=None, crown_z=None):
        t = side * (t if t is not None else self.rng.uniform(8.3, 9.0))
        base = self.at(s, t)
        crown_r = crown_r or self.rng.uniform(1.6, 2.4)
        crown_z = crown_z or self.rng.uniform(crown_r + 1.6, crown_r + 2.6)
        self.scene.prims.append(Cylinder(base[:2], self.rng.uniform(0.12, 0.2), base[2] - 0.3, base[2] + crown_z,
                                         (0.35, 0.26, 0.18), REFLECTANCE["trunk"], CLASS_CODES["high_vegetation"]))
        green = np.array([0.22, 0.42, 0.16]) * self.rng.uniform(0.8, 1.2)
        self.scene.prims.append(Crown(base + [0, 0, crown_z], crown_r, green, REFLECTANCE["foliage"],
                                      CLASS_CODES["high_vegetation"], phase=self.rng.uniform(0, 100)))
        self.occ.take(side, s, crown_r)

    def gantry(self, s):
        T, N = self.frame(s)
        posts = []
        structure = len(self.scene.poles) + 1
        for side in (1, -1):
            b = self.at(s, side * 6.6)
            posts.append(b)
            self.scene.prims.append(Cylinder(b[:2], 0.15, b[2] - 0.3, b[2] + 6.6, METAL, REFLECTANCE["pole"],
                                             CLASS_CODES["sign_support"]))
            self.add_pole("gantry", b[:2], 0.15, b[2] + 6.6, structure_id=structure)
            self.occ.take(side, s, 1.5)
        mid = self.at(s, 0.0)
        z_beam = max(p[2] for p in posts) + 6.3
        axes = np.array([T, -N, [0, 0, 1.0]])
        self.scene.prims.append(Box([mid[0], mid[1], z_beam], axes, [0.15, 6.8, 0.15], METAL, REFLECTANCE["pole"],
                                    CLASS_CODES["sign_support"]))
        normal = -T
        texts = [["WIEN 12", "LINZ 180"], ["ST. POLTEN 45", "GRAZ 190"], ["FLUGHAFEN", "A4 BUDAPEST"]]
        for k, t in enumerate((1.75, -1.75)):
            c = self.at(s, t)
            centre = np.array([c[0], c[1], z_beam - 0.15 - 0.75]) + 0.2 * normal
            key = ("gantry", k)
            lines = texts[int(self.rng.integers(len(texts)))]
            self.texture_cache.setdefault(key, tx.pyramid(tx.gantry_texture(lines)))
            sign_id = len(self.scene.signs) + 1
            panel = Panel(centre, normal, 3.0, 1.5, self.texture_cache[key], METAL, REFLECTANCE["sign_face"],
                          REFLECTANCE["sign_back"], CLASS_CODES["sign_panel"], sign_id, retroreflective=True)
            ground = float(self.road.ground_z(centre[0], centre[1]))
            self.scene.signs.append(SignInfo(sign_id, "information", "gantry", panel, float(centre[2]) - ground,
                                             "gantry", "oncoming", False, False))
            self.scene.prims.append(panel)
            for pole in self.scene.poles[-2:]:
                pole.sign_ids.append(sign_id)

    def lamp_post(self, s, side, with_sign=False):
        t = side * 6.9
        base = self.at(s, t)
        T, N = self.frame(s)
        self.scene.prims.append(Cylinder(base[:2], 0.08, base[2] - 0.3, base[2] + 8.0, (0.45, 0.47, 0.5),
                                         REFLECTANCE["pole"], CLASS_CODES["pole"]))
        lamp = self.add_pole("light_pole", base[:2], 0.08, base[2] + 8.0)
        arm_c = base + [0, 0, 7.9] - side * N * 0.9
        axes = np.array([T, -N, [0, 0, 1.0]])
        self.scene.prims.append(Box(arm_c, axes, [0.05, 0.9, 0.05], (0.45, 0.47, 0.5),
                                    REFLECTANCE["pole"], CLASS_CODES["pole"]))
        head_c = base + [0, 0, 7.8] - side * N * 1.7
        self.scene.prims.append(Box(head_c, axes, [0.15, 0.3, 0.08], (0.3, 0.3, 0.32),
                                    REFLECTANCE["pole"], CLASS_CODES["pole"]))
        if with_sign:
            facing = "oncoming" if side > 0 else "away"
            normal = self.sign_normal(s, side, facing)
            cls = self.next_class()
            h = tx.PANEL_SIZE[cls][1]
            centre = base + [0, 0, self.rng.uniform(2.3, 2.7) + h / 2] + normal * 0.13
            lamp.sign_ids.append(self.add_sign(cls, centre, normal, "lamp_post", facing).sign_id)
        self.occ.take(side, s, 1.0)

    def billboard(self, s, side):
        T, N = self.frame(s)
        t = side * 9.5
        base = self.at(s, t)
        normal = -T * np.cos(0.5) - side * N * np.sin(0.5)
        centre = base + [0, 0, 3.5]
        self.scene.prims.append(Panel(centre, normal, 3.0, 2.0, tx.pyramid(tx.billboard_texture(self.rng)),
                                      (0.4, 0.4, 0.42), REFLECTANCE["billboard"], REFLECTANCE["billboard"],
                                      CLASS_CODES["billboard"]))
        right = np.cross(-normal, [0, 0, 1.0])
        structure = len(self.scene.poles) + 1
        for k in (-1, 1):
            leg = base[:2] + k * 1.2 * right[:2] - 0.05 * normal[:2]
            self.scene.prims.append(Cylinder(leg, 0.06, base[2] - 0.3, base[2] + 3.5, METAL, REFLECTANCE["pole"],
                                             CLASS_CODES["pole"]))
            self.add_pole("other", leg, 0.06, base[2] + 3.5, structure_id=structure)
        self.scene.distractors.append({"kind": "billboard", "xyz": centre})
        self.occ.take(side, s, 2.5)

    def mirror(self, s, side):
        T, N = self.frame(s)
        base = self.at(s, side * 6.4)
        normal = -T * np.cos(0.6) - side * N * np.sin(0.6)
        centre = base + [0, 0, 2.6]
        self.scene.prims.append(Panel(centre, normal, 0.8, 0.8, self.textures(("mirror",), tx.mirror_texture),
                                      (0.25, 0.25, 0.27), REFLECTANCE["mirror"], REFLECTANCE["sign_back"],
                                      CLASS_CODES["traffic_mirror"]))
        self.scene.prims.append(Cylinder(base[:2] - 0.08 * normal[:2], 0.04, base[2] - 0.3, base[2] + 3.0,
                                         (0.8, 0.8, 0.8), REFLECTANCE["pole"], CLASS_CODES["pole"]))
        self.add_pole("other", base[:2] - 0.08 * normal[:2], 0.04, base[2] + 3.0)
        self.scene.distractors.append({"kind": "traffic_mirror", "xyz": centre})
        self.occ.take(side, s, 1.0)

    def bin_or_container(self, s, side):
        rng = self.rng
        if rng.random() < 0.5:
            base = self.at(s, side * 7.1)
            col = (0.8, 0.1, 0.1) if rng.random() < 0.6 else (0.1, 0.25, 0.7)
            self.scene.prims.append(Cylinder(base[:2], 0.3, base[2] - 0.1, base[2] + 0.95, col,
                                             REFLECTANCE["furniture"], CLASS_CODES["street_furniture"]))
            self.scene.distractors.append({"kind": "bin", "xyz": base + [0, 0, 0.5]})
        else:
            T, N = self.frame(s)
            base = self.at(s, side * 9.3)
            col = (0.1, 0.3, 0.75) if rng.random() < 0.6 else (0.75, 0.12, 0.1)
            axes = np.array([T, -N, [0, 0, 1.0]])
            self.scene.prims.append(Box(base + [0, 0, 0.7], axes, [1.0, 0.75, 0.75], col,
                                        REFLECTANCE["furniture"], CLASS_CODES["street_furniture"]))
            self.scene.distractors.append({"kind": "container", "xyz": base + [0, 0, 0.75]})
        self.occ.take(side, s, 1.2)

    def car(self, s, side):
        T, N = self.frame(s)
        base = self.at(s, side * 4.5)
        col = CAR_COLOURS[int(self.rng.integers(len(CAR_COLOURS)))]
        axes = np.array([T, -N, [0, 0, 1.0]])
        self.scene.prims.append(Box(base + [0, 0, 0.6], axes, [2.15, 0.88, 0.45], col, REFLECTANCE["car"],
                                    CLASS_CODES["car"]))
        self.scene.prims.append(Box(base + [0, 0, 1.3] - 0.15 * T, axes, [1.2, 0.78, 0.25], col, REFLECTANCE["car"],
                                    CLASS_CODES["car"], style="car_cabin"))
        self.parking.take(side, s, 2.6)

    def building(self, s0, s1, side):
        rng = self.rng
        sm = 0.5 * (s0 + s1)
        T, N = self.frame(sm)
        front = rng.uniform(11.0, 13.0)
        depth = rng.uniform(8.0, 14.0)
        height = rng.uniform(6.0, 18.0)
        c = self.at(sm, side * (front + depth / 2))
        # the road curves: widen the box so the front corners keep ~front from the centre line
        half_len = 0.5 * (s1 - s0)
        corner_z = [float(self.road.base_z(*self.road.point(s, side * t)))
                    for s in (s0, s1) for t in (front, front + depth)]
        z_lo = min(corner_z) - 1.0
        z_hi = float(self.road.base_z(c[0], c[1])) + height
        axes = np.array([T, -N, [0, 0, 1.0]])
        col = BUILDING_COLOURS[int(rng.integers(len(BUILDING_COLOURS)))]
        self.scene.prims.append(Box([c[0], c[1], 0.5 * (z_lo + z_hi)], axes, [half_len, depth / 2, 0.5 * (z_hi - z_lo)],
                                    col, REFLECTANCE["building"], CLASS_CODES["building"], style="building"))


def build_scene(preset, rng: np.random.Generator) -> Scene:
    """Lay out a scene for ``preset``; consumes ``rng`` in a fixed order."""
    b = _Builder(preset, rng)
    L = preset.road_length_m
    # gantries first (at least one)
    n_gantry = max(1, int(L // preset.gantry_every_m))
    gantry_s = [L * (k + 0.55) / n_gantry for k in range(n_gantry)]
    for s in gantry_s:
        b.gantry(s)
    road = b.road
    road.crossing_s = (float(L * 0.3),)
    # sign groups along the road, a schedule of kinds so every preset has each of them
    schedule = ["single", "shared", "left_away", "tree", "faded", "lamp", "single", "right_away", "single", "shared"]
    s = 3.0
    k = 0
    stop_lines = []
    while s < L - 1.0:
        if all(abs(s - g) > 3.0 for g in gantry_s):
            kind = schedule[k % len(schedule)]
            k += 1
            if kind == "single":
                cls = b.next_class()
                b.pole_group(s, 1, "oncoming", [cls])
                if cls == "stop":
                    stop_lines.append(s - 2.0)
            elif kind == "shared":
                b.pole_group(s, 1, "oncoming", [b.next_class(), b.next_class()], mount="shared_pole")
            elif kind == "left_away":
                b.pole_group(s, -1, "away", [b.next_class()])
            elif kind == "right_away":
                b.pole_group(s, 1, "away", [b.next_class()])
            elif kind == "tree":
                b.pole_group(s, 1, "oncoming", [b.next_class()], near_tree=True)
                b.tree(s - 3.0, 1, t=6.6, crown_r=1.8, crown_z=3.8)
            elif kind == "faded":
                b.pole_group(s, 1, "oncoming", [b.next_class()], faded=True)
            elif kind == "lamp":
                b.lamp_post(s, 1, with_sign=True)
        s += preset.sign_spacing_m * rng.uniform(0.75, 1.25)
    road.stop_line_s = tuple(stop_lines)
    # distractors: billboards, mirrors, red and blue furniture
    for s in np.arange(b.s_lo + 10.0, b.s_hi - 5.0, 60.0) + rng.uniform(0, 20.0):
        side = 1 if rng.random() < 0.5 else -1
        if b.occ.free(side, s, 2.5):
            b.billboard(s, side)
    for s in np.arange(b.s_lo + 15.0, b.s_hi - 5.0, 45.0) + rng.uniform(0, 15.0):
        side = -1 if rng.random() < 0.7 else 1
        if b.occ.free(side, s, 1.0):
            b.mirror(s, side)
    for s in np.arange(b.s_lo + 5.0, b.s_hi, 18.0) + rng.uniform(0, 10.0):
        side = 1 if rng.random() < 0.5 else -1
        if b.occ.free(side, s, 1.2):
            b.bin_or_container(s, side)
    # lamp posts and trees
    for i, s in enumerate(np.arange(b.s_lo + 8.0, b.s_hi, 30.0)):
        side = 1 if i % 2 == 0 else -1
        if b.occ.free(side, s, 1.0):
            b.lamp_post(s, side)
    s = b.s_lo
    while s < b.s_hi:
        for side in (1, -1):
            if rng.random() < 0.55 and b.occ.free(side, s, 2.4):
                b.tree(s, side)
        s += rng.uniform(9.0, 16.0)
    # parked cars in the parking strips
    s = b.s_lo
    while s < b.s_hi:
        side = 1 if rng.random() < 0.5 else -1
        if b.parking.free(side, s, 2.6):
            b.car(s, side)
        s += rng.uniform(6.0, 18.0)
    # buildings
    for side in (1, -1):
        s = b.s_lo - 10.0
        while s < b.s_hi + 10.0:
            length = rng.uniform(8.0, 25.0)
            b.building(s, s + length, side)
            s += length + rng.uniform(2.0, 8.0)
    return b.scene
