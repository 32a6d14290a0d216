"""Candidates -> signs (core.refine) on a scene of known sign panels."""
import dataclasses
import math
import os

import numpy as np
import pytest
from helpers import signscene
from scipy.optimize import linear_sum_assignment

from roadsigns.core import projection as P  # noqa: N812 (the tests' short module names)
from roadsigns.core import refine as R  # noqa: N812 (the tests' short module names)
from roadsigns.core.errors import Message, Progress
from roadsigns.core.pointcloud import PointSet, TiledIndex, read_header
from roadsigns.core.schema import names


def make_index(scene, classification=None):
    cls = scene.classification if classification is None else classification
    return TiledIndex.from_arrays(scene.xyz_world, {"intensity": scene.intensity,
                                                    "classification": cls}, tile_size_m=5.0)


@pytest.fixture(scope="module")
def scene():
    return signscene.make_scene(seed=7)


@pytest.fixture(scope="module")
def index(scene):
    return make_index(scene)


@pytest.fixture(scope="module")
def candidates(scene, index):
    return P.project_detections(P.Detections.from_records(scene.detections), index)


@pytest.fixture(scope="module")
def refined(candidates, index):
    return R.refine_signs(candidates, index, merge_radius_m=1.0)


def match(signs, truth, radius=0.5):
    """Hungarian matching on 3D distance within ``radius``: {truth sign_id: sign}."""
    d = np.linalg.norm(np.array([s.xyz_world for s in signs])[:, None]
                       - np.array([p.centre_world for p in truth])[None], axis=2)
    rows, cols = linear_sum_assignment(np.where(d <= radius, d, 1e6))
    return {truth[c].sign_id: signs[r] for r, c in zip(rows, cols) if d[r, c] <= radius}


def test_signs_match_the_truth(scene, refined):
    truth = scene.signs
    matched = match(refined.signs, truth)
    precision, recall = len(matched) / len(refined.signs), len(matched) / len(truth)
    errors = {"position": [], "height": [], "azimuth": [], "width": [], "panel_height": []}
    for p in truth:
        s = matched[p.sign_id]
        assert s.klass == p.cls
        assert s.n_views == scene.n_views(p.sign_id)
        if s.position_source == "image":
            continue
        errors["position"].append(np.linalg.norm(s.xyz_world - p.centre_world))
        errors["height"].append(abs(s.height - p.height_above_ground))
        errors["azimuth"].append(abs((s.azimuth - p.azimuth_deg + 180) % 360 - 180))
        errors["width"].append(abs(s.width - p.width))
        errors["panel_height"].append(abs(s.panel_height - p.height))
    print(f"\nprecision {precision:.3f} recall {recall:.3f}; "
          + "; ".join(f"{k} median {np.median(v):.3f} max {np.max(v):.3f}" for k, v in errors.items()))
    assert precision == 1.0 and recall == 1.0   # the convex mirror is not a sign
    assert max(errors["position"]) < 0.05
    assert max(errors["height"]) < 0.05
    assert max(errors["azimuth"]) < 5.0
    assert max(errors["width"]) < 0.05 and max(errors["panel_height"]) < 0.05


def test_stacked_panels_stay_apart(scene, refined):
    matched = match(refined.signs, scene.signs)
    for upper, lower in ((2, 3), (4, 5)):  # different classes; the same class
        a, b = matched[upper], matched[lower]
        assert a.sign_id != b.sign_id and a.z > b.z + 0.5


def test_out_of_reach_sign_is_triangulated(scene, refined):
    p = next(p for p in scene.signs if not p.has_points)
    s = match(refined.signs, [p])[p.sign_id]
    assert np.linalg.norm(s.xyz_world - p.centre_world) < 0.3
    assert s.position_source == "image" and s.n_points == 0 and s.n_views == 3
    assert sum(x.position_source == "image" for x in refined.signs) == 1


def test_records_follow_the_contract(refined, scene):
    for rec, s, outline in zip(refined.records(), refined.signs, refined.outlines_world):
        assert tuple(rec) == names(R.SIGN_FIELDS)
        assert 0.0 <= rec["azimuth"] < 360.0 and 0.0 < rec["score"] <= 1.0
        images = rec["source_images"].split(";")
        assert len(images) == rec["n_views"] and rec["best_image"] in images
        assert rec["bottom_height"] == pytest.approx(rec["height"] - rec["panel_height"] / 2, abs=0.02)
        if rec["position_source"] == "lidar":
            assert outline.shape == (4, 3) and rec["n_points"] > 50 and rec["planarity"] > 0.9
            assert rec["mean_intensity"] > 0
    assert refined.ground_source == [R.GROUND_POINTS] * len(refined.signs)
    # the best view of sign 1 is the nearest station in front of it
    p = scene.signs[0]
    s = match(refined.signs, [p])[p.sign_id]
    assert s.best_image == "pano_00003.jpg"


def test_faded_face_keeps_its_points_and_the_bright_one_drops_the_pole(scene, refined):
    matched = match(refined.signs, scene.signs)
    bright, faded = matched[1], matched[7]
    assert faded.mean_intensity < 0.4 * bright.mean_intensity
    assert faded.n_points > 100
    rows = refined.signs.index(bright)
    z = scene.xyz_world[refined.point_index[rows], 2]
    p = scene.signs[0]
    assert z.min() > p.centre_world[2] - p.height / 2 - 0.03  # no pole below the panel


def test_a_misclassified_view_is_outvoted(scene, index):
    rows = [dict(d) for d in scene.detections]
    first = next(k for k, d in enumerate(rows) if d["truth_id"] == 1)
    rows[first]["class"], rows[first]["score"] = "mandatory", 0.3
    out = R.refine_signs(P.project_detections(P.Detections.from_records(rows), index), index)
    p = scene.signs[0]
    s = match(out.signs, [p])[p.sign_id]
    assert s.klass == "prohibitory" and s.n_views == scene.n_views(1)
    assert len(out.signs) == len(scene.signs)


def test_one_panel_given_two_classes_is_one_sign(scene, index):
    """The detector boxes one panel twice in each image, with two classes (per-class NMS
    keeps both): still one sign, with the class of the stronger boxes."""
    rows = [dict(d) for d in scene.detections]
    doubles = [dict(d, det_id=10000 + n, score=0.35) for n, d in enumerate(rows) if d["truth_id"] == 1]
    for d in doubles:
        d["class"] = "mandatory"
    assert len(doubles) >= 2
    rows += doubles
    out = R.refine_signs(P.project_detections(P.Detections.from_records(rows), index), index)
    p = scene.signs[0]
    near = [s for s in out.signs if np.linalg.norm(s.xyz_world - p.centre_world) < 0.5]
    assert len(near) == 1 and near[0].klass == "prohibitory"
    assert len(out.signs) == len(scene.signs)


def test_a_panel_too_large_for_its_class_is_dropped(scene, candidates, index):
    p = scene.signs[0]
    small = R.RefineParams(max_panel_side_default_m=0.9 * max(p.width, p.height))
    out = R.refine_signs(candidates, index, params=small)
    kept = [s for s in out.signs if np.linalg.norm(s.xyz_world - p.centre_world) < 0.5]
    assert kept == [] and len(out.signs) < len(scene.signs)


def test_ground_fallbacks_are_reported(scene, candidates):
    cls = scene.classification.copy()
    p = scene.signs[0]
    near = np.hypot(*(scene.xyz_world[:, :2] - p.centre_world[:2]).T) < 4.0
    cls[near & (cls == 2)] = 1  # the ground below sign 1 unclassified: its pole reaches down
    warnings = []
    out = R.refine_signs(candidates, make_index(scene, cls),
                         progress=Progress(on_warning=warnings.append))
    k = out.signs.index(match(out.signs, [p])[p.sign_id])
    assert out.ground_source[k] == R.LOWEST_POINTS
    assert abs(out.signs[k].height - p.height_above_ground) < 0.1
    assert any("lowest points" in w for w in warnings)


def test_triangulation_needs_an_angle_between_the_rays():
    C = np.array([[0.0, 0, 0], [5.0, 0, 0]])
    target = np.array([10.0, 8.0, 1.0])
    D = (target - C) / np.linalg.norm(target - C, axis=1, keepdims=True)
    np.testing.assert_allclose(R.intersect_rays(C, D), target, atol=1e-9)
    assert np.allclose(R.ray_distance(target, C, D), 0.0)


def test_empty_candidates_give_an_empty_layer(index):
    warnings = []
    out = R.refine_signs(P.ProjectionResult.unprojected(P.Detections.empty()), index,
                         progress=Progress(on_warning=warnings.append))
    assert out.signs == [] and out.records() == [] and warnings


def test_from_a_las_file_with_the_sign_points(scene, candidates, tmp_path):
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    back = P.ProjectionResult.from_records(candidates.records())  # as read from the layer
    out = R.refine_signs(back, las)
    assert len(match(out.signs, scene.signs)) == len(scene.signs) == len(out.signs)
    n = R.write_sign_points(las, str(tmp_path / "signs.las"), out.point_index)
    assert n == sum(len(p) for p in out.point_index) > 0
    assert read_header(str(tmp_path / "signs.las")).point_count == n


@pytest.mark.parametrize("below,kept", [(0.05, False), (-0.05, True), (-0.5, True)])
def test_a_sign_seen_once_needs_a_confident_detection(scene, index, below, kept):
    """Just under ``min_single_view_score`` the lone view is dropped; at it or above, kept."""
    score = R.RefineParams().min_single_view_score - below
    one = dict(next(d for d in scene.detections if d["truth_id"] == 1), score=score)
    out = R.refine_signs(P.project_detections(P.Detections.from_records([one]), index), index)
    assert len(out.signs) == (1 if kept else 0)


def _oncoming(x, y, h):
    normal = np.array([-1.0, np.tan(np.radians(6)), 0.0])
    return np.array([x, y, float(signscene.ground_z_local(x, y)) + h]), normal / np.linalg.norm(normal)


def test_a_picture_on_a_billboard_is_not_a_sign_but_a_sign_on_a_wall_is():
    """A red circle printed on a 3 x 2 m billboard is boxed as a prohibitory sign: its plane
    goes on around it, no brighter, so it is dropped. A retroreflective sign screwed onto a
    wall 1.5 cm in front of it is kept, like a sign on a pole."""
    Panel = signscene.TruthPanel
    board, n = _oncoming(30, -6.0, 3.0)
    wall, n2 = _oncoming(60, -6.0, 2.5)
    on_pole, n3 = _oncoming(90, -6.0, 2.5)
    panels = [
        Panel(1, "prohibitory", "circle", board + 0.4 * np.cross(n, [0, 0, 1]), n, 0.6, 0.6,
              is_sign=False, has_points=False, pole=False),
        Panel(2, "billboard", "rect", board, n, 3.0, 2.0, is_sign=False, detected=False,
              pole=False, reflectance=0.4),
        Panel(3, "mandatory", "circle", wall + 0.015 * n2, n2, 0.6, 0.6, pole=False),
        Panel(4, "wall", "rect", wall, n2, 5.0, 3.0, is_sign=False, detected=False, pole=False,
              reflectance=0.3),
        Panel(5, "warning", "triangle_up", on_pole, n3, 0.9, 0.78),
    ]
    scene = signscene.make_scene(seed=3, panels=panels, road_length_m=110.0,
                                 stations_x=np.arange(0.0, 105.0, 5.0))
    index = make_index(scene)
    messages = []
    out = R.refine_signs(P.project_detections(P.Detections.from_records(scene.detections), index),
                         index, progress=Progress(on_info=messages.append))
    matched = match(out.signs, scene.signs)
    assert sorted(matched) == [3, 5] and len(out.signs) == 2
    assert matched[3].position_source == "lidar" and matched[3].n_points > 50
    assert any(R.LARGER_SURFACE in m for m in messages)


def _views_from(scene, panel, stations):
    """Detections of ``panel`` from the stations ``stations`` (indices), numbered after the
    scene's own."""
    far = signscene.TruthPanel(**{**panel.__dict__, "seen_from": list(stations)})
    probe = signscene.SignScene(scene.xyz_world[:0], scene.classification[:0], scene.intensity[:0],
                                scene.station_centre_world, scene.station_q_wxyz,
                                scene.station_images, [far])
    rows = signscene.make_detections(probe, 1.0, np.random.default_rng(5))
    first = max(d["det_id"] for d in scene.detections) + 1
    return [dict(d, det_id=first + n) for n, d in enumerate(rows)]


def test_views_beyond_the_scanners_reach_join_their_sign(scene, index):
    """Sign 10 (x = 145 m) boxed from the first stations, 120-145 m away: no points within
    the projection's range there. The views join the sign found by the near stations; their
    nearly parallel rays are not triangulated into a second sign."""
    p = next(q for q in scene.signs if q.sign_id == 10)
    far = _views_from(scene, p, range(0, 5))
    cand = P.project_detections(P.Detections.from_records(scene.detections + far), index)
    assert all(s != P.STATUS_OK for s in cand.status[-len(far):])
    out = R.refine_signs(cand, index)
    s = match(out.signs, [p])[p.sign_id]
    assert s.n_views == scene.n_views(10) + len(far)
    assert len(out.signs) == len(scene.signs)


def test_nearly_parallel_rays_place_no_sign(scene, index):
    """A sign 120-145 m ahead with no points and no nearer view: its rays meet at angles of
    a degree or two, too uncertain in depth to place it."""
    p = next(q for q in scene.signs if q.sign_id == 10)
    far = _views_from(scene, p, range(0, 5))
    alone = P.project_detections(P.Detections.from_records(far), index)
    assert R.refine_signs(alone, index).signs == []
    # the same rays, near and wide apart, do place it (as the out-of-reach sign 8 shows)
    C = scene.station_centre_world[:5]
    D = p.centre_world - C
    D /= np.linalg.norm(D, axis=1, keepdims=True)
    x = R.intersect_rays(C, D)
    sin_max = np.linalg.norm(np.cross(D[0], D[-1]))
    assert R.depth_sigma_m(x, C, R.ray_distance(x, C, D), sin_max, R.RefineParams()) > \
        R.RefineParams().max_depth_sigma_m


def _scanned_in_lines(lines_s, seed):
    """A mandatory sign whose face the scanner crossed in a few vertical profiles only (a
    face seen at a grazing angle), and a warning sign scanned whole."""
    Panel = signscene.TruthPanel
    centre, normal = _oncoming(30, -6.0, 2.6)
    panels = [Panel(1, "mandatory", "circle", centre, normal, 0.6, 0.6, scan_lines_s=lines_s),
              Panel(2, "warning", "triangle_up", _oncoming(60, -6.0, 2.5)[0], normal, 0.9, 0.78)]
    scene = signscene.make_scene(seed=seed, panels=panels, road_length_m=80.0,
                                 stations_x=np.arange(0.0, 75.0, 5.0))
    index = make_index(scene)
    out = R.refine_signs(P.project_detections(P.Detections.from_records(scene.detections), index), index)
    return scene, panels[0], match(out.signs, scene.signs)


def test_a_face_scanned_in_a_few_profiles_keeps_its_points():
    """Each point of a profile has a linear neighbourhood, like a pole's: the filter that
    drops the pole must not take most of the panel with it."""
    scene, panel, matched = _scanned_in_lines([-0.15, 0.0, 0.15], seed=2)
    rel = scene.xyz_world - panel.centre_world
    on_face = ((np.abs(rel @ panel.normal) < 0.04) & (np.abs(rel @ panel.right) < 0.31)
               & (np.abs(rel @ panel.up) < 0.31) & (scene.classification != 2))
    sign = matched[1]
    assert sign.n_points >= 0.8 * on_face.sum()
    assert np.linalg.norm(sign.xyz_world - panel.centre_world) < 0.05


def test_a_face_scanned_in_one_profile_faces_the_way_of_its_views():
    """The points of one profile are a line: their plane is undefined, so the sign takes
    the normal its views found, not an arbitrary one."""
    _, panel, matched = _scanned_in_lines([0.2], seed=1)
    true_azimuth = np.degrees(np.arctan2(panel.normal[0], panel.normal[1])) % 360
    assert abs((matched[1].azimuth - true_azimuth + 180) % 360 - 180) < 30.0


# --------------------------------------------------------------------------------------
# The steps of refine_signs, one by one
# --------------------------------------------------------------------------------------

def truth(scene, sign_id):
    return next(p for p in scene.panels if p.sign_id == sign_id)


def views_of(scene, candidates, sign_id, status=P.STATUS_OK):
    """Candidate rows of the detections of truth panel ``sign_id`` with that status."""
    return np.array([k for k, d in enumerate(scene.detections)
                     if d["truth_id"] == sign_id and candidates.status[k] == status], np.int64)


def point_set(xyz, intensity=None, classification=None, first_index=0):
    xyz = np.asarray(xyz, float).reshape(-1, 3)
    n = len(xyz)
    return PointSet(xyz, first_index + np.arange(n, dtype=np.int64),
                    {"intensity": np.full(n, 20000, np.uint16) if intensity is None else intensity,
                     "classification": np.ones(n, np.uint8) if classification is None
                     else classification})


def face_points(scene, panel):
    """The scene's points of a retroreflective face (not its pole behind it)."""
    rel = scene.xyz_world - panel.centre_world
    m = ((np.abs(rel @ panel.normal) < 0.04) & panel.inside(rel @ panel.right, rel @ panel.up)
         & (scene.classification != 2) & (scene.intensity > 0.6 * signscene.SCALE))
    return PointSet(scene.xyz_world[m], np.flatnonzero(m),
                    {"intensity": scene.intensity[m], "classification": scene.classification[m]})


def grid(centre, right, up, half_w, half_h, step):
    """Points on a regular grid in the plane spanned by ``right`` and ``up``."""
    s, t = np.meshgrid(np.arange(-half_w, half_w + 1e-9, step), np.arange(-half_h, half_h + 1e-9, step))
    return (np.asarray(centre, float) + np.multiply.outer(s.ravel(), right)
            + np.multiply.outer(t.ravel(), up))


def a_panel(centre, normal, points=None):
    normal = np.asarray(normal, float) / np.linalg.norm(normal)
    right, up = R.panel_frame(normal)
    corners = np.array([centre + a * 0.3 * right + b * 0.3 * up
                        for a, b in ((-1, 1), (1, 1), (1, -1), (-1, -1))])
    return R.Panel(np.asarray(centre, float), normal, 0.6, 0.6, corners,
                   point_set(np.zeros((0, 3))) if points is None else points, 0.95)


def changed(candidates, k, **fields):
    """The candidates with the fields of row ``k`` changed (as read back from the layer)."""
    rows = candidates.records()
    rows[k] = dict(rows[k], **fields)
    return P.ProjectionResult.from_records(rows)


EAST, NORTH, UP = np.eye(3)


def test_points_near_views_are_off_the_ground_in_a_slab_around_the_plane(scene, candidates):
    p, params = truth(scene, 1), R.RefineParams()
    face = grid(p.centre_world, p.right, p.up, 0.25, 0.25, 0.05)
    n = len(face)
    xyz = np.concatenate([face, face - (params.slab_m - 0.1) * p.normal,   # kept
                          face - (params.slab_m + 0.1) * p.normal,         # beyond the slab
                          face + 0.05 * p.normal,                          # ground class
                          face + 3.0 * p.right])                           # beyond reach
    cls = np.ones(len(xyz), np.uint8)
    cls[3 * n:4 * n] = 2
    index = TiledIndex.from_arrays(xyz, {"intensity": np.zeros(len(xyz), np.uint16),
                                         "classification": cls}, tile_size_m=5.0)
    out = R.points_near_views(candidates, views_of(scene, candidates, 1), index, p.centre_world,
                              p.normal, params)
    assert sorted(out.point_index.tolist()) == list(range(2 * n))


def test_points_in_boxes_need_half_the_views(scene, candidates):
    p, params = truth(scene, 1), R.RefineParams()
    face = face_points(scene, p)
    rel = face.xyz_world - p.centre_world
    face = face.subset(np.hypot(rel @ p.right, rel @ p.up) < 0.2)   # inside every view's box
    beside = point_set(face.xyz_world + 1.5 * p.right, first_index=len(scene.xyz_world))
    pts = PointSet(np.concatenate([face.xyz_world, beside.xyz_world]),
                   np.concatenate([face.point_index, beside.point_index]),
                   {k: np.concatenate([face.attributes[k], beside.attributes[k]])
                    for k in face.attributes})
    rows, far = views_of(scene, candidates, 1), views_of(scene, candidates, 6)
    assert len(face) > 50 and len(far) > len(rows)
    kept = R.points_in_boxes(candidates, rows, pts, params)
    assert set(kept.point_index.tolist()) == set(face.point_index.tolist())
    # the views of a sign 60 m away as many as the face's: half the views see the face
    half = R.points_in_boxes(candidates, np.r_[rows, far[:len(rows)]], pts, params)
    assert set(half.point_index.tolist()) == set(face.point_index.tolist())
    assert len(R.points_in_boxes(candidates, np.r_[rows, far[:len(rows) + 1]], pts, params)) == 0


def test_seeded_clusters_keep_the_candidates_clusters_and_large_ones():
    centre = signscene.ORIGIN + [10.0, -6.0, 2.5]
    seeded = grid(centre, EAST, UP, 0.15, 0.15, 0.02)
    large = grid(centre + 1.0 * EAST, EAST, UP, 0.15, 0.15, 0.02)   # a panel split by a scan gap
    small = grid(centre - 1.0 * EAST, EAST, UP, 0.02, 0.02, 0.02)   # something else nearby
    pts = point_set(np.concatenate([seeded, large, small]))
    groups = np.repeat([0, 1, 2], [len(seeded), len(large), len(small)])
    params = R.RefineParams()
    assert len(small) < params.major_cluster_share * len(pts) <= len(large)
    out = R.seeded_clusters(pts, centre[None], params)
    assert sorted(out.point_index.tolist()) == np.flatnonzero(groups < 2).tolist()
    out = R.seeded_clusters(pts, np.array([centre, centre - 1.0 * EAST]), params)
    assert len(out) == len(pts)


@pytest.mark.parametrize("dark,light,bright,filtered", [
    (10000, 60000, 30000, True),    # a retroreflective face on a darker pole
    (10000, 20000, 30000, False),   # a faded face: two modes, neither bright for this cloud
    (40000, 60000, 30000, False),   # both modes bright: no darker thing to filter out
])
def test_retroreflective_mask_keeps_a_bright_mode_only(dark, light, bright, filtered):
    rng = np.random.default_rng(0)
    inten = np.concatenate([rng.normal(dark, 500, 60), rng.normal(light, 500, 100)])
    mask = R.retroreflective_mask(inten, bright, R.RefineParams())
    assert mask.tolist() == ([False] * 60 + [True] * 100 if filtered else [True] * 160)
    # too few points (23) to tell modes apart, though the bright one has min_panel_points (12)
    few = np.r_[inten[:12], inten[-12:]][1:]
    assert R.retroreflective_mask(few, bright, R.RefineParams()).all()


def test_points_on_plane_keep_the_back_face_not_the_pole_nor_points_off_the_plane():
    rng = np.random.default_rng(1)
    base = signscene.ORIGIN + [10.0, -6.0, 0.0]
    face = grid(base + 2.3 * UP, EAST, UP, 0.3, 0.3, 0.02)             # bright
    back = grid(base + 0.65 * EAST + 2.15 * UP, EAST, UP, 0.15, 0.15, 0.02)  # dark, on the plane
    pole = base + np.multiply.outer(np.arange(0.5, 1.8, 0.01), UP)     # dark line on the plane
    off = grid(base + 2.3 * UP + 0.2 * NORTH, EAST, UP, 0.3, 0.3, 0.05)  # bright, 20 cm in front
    xyz = np.concatenate([face, back, pole, off])
    xyz = xyz + rng.normal(0, 0.002, xyz.shape)
    part = np.repeat([0, 1, 2, 3], [len(face), len(back), len(pole), len(off)])
    pts = point_set(xyz)
    out = R.points_on_plane(pts, (part == 0) | (part == 3), 0.02, R.RefineParams())
    assert out is not None
    kept, plane = out
    assert sorted(kept.point_index.tolist()) == np.flatnonzero(part <= 1).tolist()
    assert abs(plane.normal @ NORTH) > 0.99
    assert R.points_on_plane(pts, np.arange(len(pts)) < 5, 0.02, R.RefineParams()) is None


def test_a_faded_face_with_a_few_bright_specks_is_fitted_through_all_its_points():
    # the 9.2 km drive's sign 18: 17 of its 670 points bright, and the plane through them
    # 28 degrees off its face, so only a strip was kept and the rest read as a larger surface
    rng = np.random.default_rng(2)
    base = signscene.ORIGIN + [10.0, -6.0, 0.0]
    face = grid(base + 2.3 * UP, EAST, UP, 0.8, 0.7, 0.02)             # faded: dark
    specks = base + 2.3 * UP + np.outer(np.linspace(0.0, 0.7, 17), UP)  # a vertical line of them
    specks = specks + np.outer(np.linspace(-0.03, 0.03, 17), NORTH + 0.5 * EAST)
    xyz = np.concatenate([face, specks]) + rng.normal(0, 0.002, (len(face) + 17, 3))
    bright = np.arange(len(xyz)) >= len(face)
    pts = point_set(xyz)
    params = R.RefineParams()
    alone = R.fit_plane_ransac(xyz[bright], params.plane_threshold_m, params.max_tilt_deg)
    assert abs(alone.normal @ NORTH) < np.cos(np.radians(params.max_bright_plane_turn_deg))  # the failure
    kept, plane = R.points_on_plane(pts, bright, 0.02, params, NORTH)
    assert abs(plane.normal @ NORTH) > 0.99
    assert len(kept) >= 0.95 * len(face)
    # without the views' normal, the bright points' plane stands (the behaviour before)
    kept_before, plane_before = R.points_on_plane(pts, bright, 0.02, params)
    assert abs(plane_before.normal @ NORTH) < 0.99 and len(kept_before) < 0.5 * len(face)


def test_drop_linear_points_drops_the_pole_but_not_most_of_the_panel():
    base = signscene.ORIGIN + [10.0, -6.0, 0.0]
    params = R.RefineParams()
    panel = grid(base + 2.3 * UP, EAST, UP, 0.3, 0.3, 0.02)
    pole = base + np.multiply.outer(np.arange(1.0, 2.0, 0.01), UP)
    out = R.drop_linear_points(point_set(np.concatenate([panel, pole])), 0.02, params)
    kept = set(out.point_index.tolist())
    reach = params.pca_radius_m
    far_pole = len(panel) + np.flatnonzero(pole[:, 2] < base[2] + 2.0 - reach)
    assert not kept & set(far_pole.tolist())
    assert len(kept & set(range(len(panel)))) >= 0.98 * len(panel)
    # a face scanned in three vertical profiles (and a small patch above): linear nearly
    # everywhere, it stays whole
    profiles = np.concatenate([base + x * EAST + np.multiply.outer(np.arange(2.0, 2.6, 0.005), UP)
                               for x in (-0.2, 0.0, 0.2)] + [grid(base + 2.85 * UP, EAST, UP, 0.05, 0.05, 0.01)])
    assert len(R.drop_linear_points(point_set(profiles), 0.02, params)) == len(profiles)


def test_panel_normal_faces_the_views_and_falls_back_when_the_points_cannot_tell():
    params = R.RefineParams()
    n = np.array([-1.0, 0.1, 0.0]) / np.linalg.norm([-1.0, 0.1, 0.0])
    right, up = R.panel_frame(n)
    centre = signscene.ORIGIN + [10.0, -6.0, 2.5]
    _, ev, V = P.pca(grid(centre, right, up, 0.3, 0.3, 0.02))
    np.testing.assert_allclose(R.panel_normal(ev, V, n, n, params), n, atol=1e-9)
    np.testing.assert_allclose(R.panel_normal(ev, V, n, -n, params), -n, atol=1e-9)
    # the points lean 45 degrees: the RANSAC plane (near-vertical), towards the views
    leaning = (up - n) / np.sqrt(2)
    _, ev, V = P.pca(grid(centre, right, leaning, 0.3, 0.3, 0.02))
    np.testing.assert_allclose(R.panel_normal(ev, V, -n, n, params), n, atol=1e-9)
    # a line (one scan profile): the views' normal
    _, ev, V = P.pca(grid(centre, right, up, 0.005, 0.3, 0.005))
    views = np.array([-0.9, 0.4, 0.0]) / np.linalg.norm([-0.9, 0.4, 0.0])
    np.testing.assert_allclose(R.panel_normal(ev, V, n, views, params), views)


def test_panel_outline_widens_the_points_to_the_boxes_within_an_allowance(scene, candidates):
    p, params = truth(scene, 1), R.RefineParams()
    face, rows = face_points(scene, p), views_of(scene, candidates, 1)
    centroid = face.xyz_world.mean(axis=0)
    panel, spacing = R.panel_outline(candidates, rows, face, centroid, p.normal, 0.93, params)
    assert 0 < spacing < 0.05 and panel.planarity == 0.93 and panel.points is face
    assert abs(panel.width_m - p.width) < 0.03 and abs(panel.height_m - p.height) < 0.03
    assert np.linalg.norm(panel.centre_world - p.centre_world) < 0.02
    tl, tr, br, bl = panel.corners_world
    np.testing.assert_allclose((panel.corners_world - centroid) @ p.normal, 0.0, atol=1e-9)
    assert (tr - tl) @ p.right == pytest.approx(panel.width_m)
    assert (tl - bl) @ p.up == pytest.approx(panel.height_m) and br @ p.up == pytest.approx(bl @ p.up)
    # only the left half of the face scanned: the boxes reach 0.3 m further, beyond the
    # allowance: the outline keeps to the points
    s = (face.xyz_world - p.centre_world) @ p.right
    left = face.subset(s < 0)
    half, _ = R.panel_outline(candidates, rows, left, left.xyz_world.mean(axis=0), p.normal, 0.9,
                              params)
    assert half.width_m < 0.5 * p.width + 0.05


def test_cloud_around_candidates(scene, candidates, index, tmp_path):
    assert R.cloud_around_candidates(candidates, index, 1.0) is index
    assert R.cloud_around_candidates(candidates, None, 1.0) is None
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    near = R.cloud_around_candidates(candidates, las, 2.0)
    ok = candidates.xyz_world[np.array(candidates.status) == P.STATUS_OK]
    buffer_m = 2.0 + 2.5
    dist = np.min(np.linalg.norm(scene.xyz_world[:, None, :2] - ok[None, :, :2], axis=2), axis=1)
    got = np.zeros(len(scene.xyz_world), bool)
    got[near.point_index] = True
    assert np.all(dist[got] <= buffer_m + 1e-3)
    assert np.all(got[dist < 0.99 * buffer_m]) and got.sum() < 0.5 * len(got)
    no_ok = P.ProjectionResult.unprojected(candidates.detections)
    assert R.cloud_around_candidates(no_ok, las, 2.0) is None


def test_extract_signs_drops_non_signs_and_keeps_groups_without_a_panel(candidates, index,
                                                                        monkeypatch):
    groups = R.merge_candidates(candidates, 1.0)
    det, panel = candidates.detections, a_panel(np.zeros(3), EAST)
    outcomes = {int(groups[0][0]): (None, R.CURVED_SURFACE),
                int(groups[1][0]): (None, Message("too few points"))}
    monkeypatch.setattr(R, "extract_panel",
                        lambda cand, rows, *_: outcomes.get(int(rows[0]), (panel, "")))
    messages, reports = [], []
    drafts = R.extract_signs(candidates, groups, index, 0.0, R.RefineParams(),
                             Progress(on_progress=reports.append, on_info=messages.append))
    assert [d.rows.tolist() for d in drafts] == [g.tolist() for g in groups[1:]]
    assert drafts[0].panel is None and all(d.panel is panel for d in drafts[1:])
    assert messages == [f"Candidates {det.det_id[groups[0]].tolist()} dropped: {R.CURVED_SURFACE}",
                        f"Candidates {det.det_id[groups[1]].tolist()}: too few points; placed at "
                        "the candidates' median"]
    assert reports[-1] == pytest.approx(100.0)
    messages.clear()
    drafts = R.extract_signs(candidates, groups, None, 0.0, R.RefineParams(),
                             Progress(on_info=messages.append))
    assert len(drafts) == len(groups) and all(d.panel is None for d in drafts)
    assert len(messages) == len(groups) and all("no point cloud" in m for m in messages)


def test_sign_centres_and_classes_come_from_the_signs_own_views(scene, candidates):
    rows1, rows2 = views_of(scene, candidates, 1), views_of(scene, candidates, 2)
    p2 = truth(scene, 2)
    drafts = [R.SignDraft(rows1, joined=list(rows2)), R.SignDraft(rows2, a_panel(p2.centre_world, p2.normal))]
    centres = R.sign_centres(candidates, drafts)
    np.testing.assert_allclose(centres[0], np.median(candidates.xyz_world[rows1], axis=0))
    np.testing.assert_allclose(centres[1], p2.centre_world)
    assert R.sign_classes(candidates, drafts).tolist() == ["prohibitory", "warning"]
    assert R.sign_centres(candidates, []).shape == (0, 3)


@pytest.mark.parametrize("klass,in_front_m,joins", [
    ("prohibitory", 0.0, True), ("prohibitory", 2.0, True),   # same class: at any range
    ("mandatory", 0.0, True),     # another class, the sign on its surface (a stray part)
    ("mandatory", 2.0, False),    # another class, the sign 2 m behind its surface
])
def test_a_lone_view_joins_the_sign_found_by_several_in_its_box(scene, candidates, klass,
                                                                 in_front_m, joins):
    rows = views_of(scene, candidates, 1)
    k = int(rows[0])
    station = candidates.detections.centre_world[k]
    ray = candidates.xyz_world[k] - station
    rng = float(np.linalg.norm(ray))
    xyz = station + (rng - in_front_m) * ray / rng
    cand = changed(candidates, k, **{"class": klass, "range_m": rng - in_front_m,
                                     "cand_x": xyz[0], "cand_y": xyz[1], "cand_z": xyz[2]})
    several, lone = R.SignDraft(rows[1:]), R.SignDraft(rows[:1])
    R.join_lone_views(cand, [several, lone])
    assert (several.joined, lone.absorbed) == (([k], True) if joins else ([], False))


def test_a_lone_view_does_not_join_another_lone_view(scene, candidates):
    rows = views_of(scene, candidates, 1)
    drafts = [R.SignDraft(rows[:1]), R.SignDraft(rows[1:2])]
    R.join_lone_views(candidates, drafts)
    assert [(d.joined, d.absorbed) for d in drafts] == [([], False), ([], False)]


@pytest.mark.parametrize("offset_m,normal,joins", [
    (0.1, EAST, True), (0.1, -EAST, True),   # the normals agree, either way
    (0.1, NORTH, False),                      # they do not
    (0.5, EAST, False),                       # too far apart
])
def test_two_signs_on_one_panel_are_one(candidates, offset_m, normal, joins):
    centre = signscene.ORIGIN + [10.0, -6.0, 2.5]
    more = R.SignDraft(np.array([0, 1, 2]), a_panel(centre, EAST))
    fewer = R.SignDraft(np.array([3, 4]), a_panel(centre + offset_m * UP, normal), joined=[5])
    drafts = [fewer, more]
    R.join_signs_on_one_panel(candidates, drafts, R.RefineParams())
    if joins:
        assert more.joined == [3, 4, 5] and fewer.absorbed and fewer.joined == []
    else:
        assert more.joined == [] and not fewer.absorbed and fewer.joined == [5]


def test_a_sign_without_a_panel_joins_any_on_its_place(scene, candidates):
    rows = views_of(scene, candidates, 1)
    fewer = R.SignDraft(rows[:1])
    more = R.SignDraft(rows[1:], a_panel(np.median(candidates.xyz_world[rows[:1]], axis=0), NORTH))
    R.join_signs_on_one_panel(candidates, [fewer, more], R.RefineParams())
    assert fewer.absorbed and more.joined == rows[:1].tolist()


def test_views_without_a_surface_join_the_sign_in_their_box(scene, index):
    p = truth(scene, 10)
    far = _views_from(scene, p, range(0, 5))
    cand = P.project_detections(P.Detections.from_records(scene.detections + far), index)
    far_rows = list(range(len(scene.detections), len(cand)))
    no_surface = np.flatnonzero(np.array(cand.status) != P.STATUS_OK).tolist()
    assert set(far_rows) < set(no_surface)
    drafts = [R.SignDraft(views_of(scene, cand, 10), a_panel(p.centre_world, p.normal))]
    unplaced = R.join_views_without_surface(cand, drafts)
    assert drafts[0].joined == far_rows    # of their class, 120-145 m away
    assert sorted(unplaced.tolist()) == sorted(set(no_surface) - set(far_rows))
    # of another class they join only a sign within 60 m
    other = P.project_detections(P.Detections.from_records(
        scene.detections + [dict(d, **{"class": "warning"}) for d in far]), index)
    drafts = [R.SignDraft(views_of(scene, other, 10), a_panel(p.centre_world, p.normal))]
    assert sorted(R.join_views_without_surface(other, drafts).tolist()) == no_surface
    assert drafts[0].joined == []


def test_image_only_signs_are_triangulated_from_views_without_points(scene, candidates):
    p = truth(scene, 8)
    rows = views_of(scene, candidates, 8, P.STATUS_NO_POINTS)
    unplaced = np.flatnonzero(np.array(candidates.status) != P.STATUS_OK)
    assert len(rows) == 3 and len(unplaced) > len(rows)
    drafts = R.triangulate_image_only(candidates, unplaced, R.RefineParams())
    assert len(drafts) == 1 and sorted(drafts[0].rows.tolist()) == rows.tolist()
    assert drafts[0].panel is None and np.linalg.norm(drafts[0].x_image - p.centre_world) < 0.3
    # the same views, had their rays met points without a surface: no image-only sign
    cand = candidates
    for k in rows:
        cand = changed(cand, int(k), status=P.STATUS_NO_SURFACE)
    assert R.triangulate_image_only(cand, unplaced, R.RefineParams()) == []


def test_placement_of_a_panel_of_the_views_median_and_of_a_triangulated_point(scene, candidates):
    p1, p8 = truth(scene, 1), truth(scene, 8)
    rows1, rows8 = views_of(scene, candidates, 1), views_of(scene, candidates, 8, P.STATUS_NO_POINTS)
    face = face_points(scene, p1)
    panel = a_panel(p1.centre_world, p1.normal, face)
    place = R.placement(candidates, R.SignDraft(rows1, panel))
    assert place.centre is panel.centre_world and place.outline is panel.corners_world
    assert place.bottom_z == pytest.approx(p1.centre_world[2] - 0.3)
    assert place.point_index is face.point_index and place.source == "lidar"
    assert place.mean_intensity == pytest.approx(float(np.mean(face.attributes["intensity"])))
    # no panel: at the views' median surface point, sized by the boxes
    place = R.placement(candidates, R.SignDraft(rows1))
    np.testing.assert_allclose(place.centre, np.median(candidates.xyz_world[rows1], axis=0))
    assert np.linalg.norm(place.centre - p1.centre_world) < 0.15
    assert abs(place.width_m - p1.width) < 0.1 and abs(place.height_m - p1.height) < 0.1
    assert place.bottom_z == pytest.approx(place.centre[2] - place.height_m / 2)
    assert np.linalg.norm(place.normal) == pytest.approx(1.0) and place.normal @ p1.normal > 0.95
    assert place.outline is None and len(place.point_index) == 0 and place.source == "lidar"
    assert np.isnan(place.mean_intensity) and np.isnan(place.planarity)
    # triangulated: facing the stations that saw it, horizontally
    place = R.placement(candidates, R.SignDraft(rows8, x_image=p8.centre_world))
    np.testing.assert_allclose(place.centre, p8.centre_world)
    stations = candidates.detections.centre_world[rows8].mean(axis=0)
    assert place.source == "image" and place.normal[2] == 0.0
    assert np.linalg.norm(place.normal) == pytest.approx(1.0)
    assert place.normal @ (stations - place.centre) > 0
    assert abs(place.width_m - p8.width) < 0.1 and abs(place.height_m - p8.height) < 0.1


def test_source_images_are_listed_once_in_the_order_of_the_detections(scene, candidates):
    rows2, rows3 = views_of(scene, candidates, 2), views_of(scene, candidates, 3)
    det = candidates.detections
    images = [det.image[k] for k in rows2]
    assert sorted(images) == sorted(det.image[k] for k in rows3)   # one pole, the same stations
    assert R.source_images(candidates, list(rows3[::-1]) + list(rows2)) == sorted(images)


@pytest.mark.parametrize("klass,width,n_images,score,kept,says", [
    ("prohibitory", 0.6, 3, 0.7, True, None),
    ("prohibitory", 2.0, 3, 0.7, False, "too large for a prohibitory sign"),
    ("information", 2.0, 3, 0.7, True, None),
    ("prohibitory", 0.6, 1, 0.35, False, "seen in one panorama only, with a score of 0.35"),
    ("prohibitory", 0.6, 1, 0.45, True, None),
    ("prohibitory", 0.6, 2, 0.1, True, None),
])
def test_plausible_signs(candidates, klass, width, n_images, score, kept, says):
    place = R.Placement(np.zeros(3), EAST, width, 0.6, -0.3, np.zeros(0, np.int64), np.nan,
                        np.nan, "lidar", None)
    messages = []
    images = [f"pano_{k:05d}.jpg" for k in range(n_images)]
    assert R.plausible(candidates, [0, 1], klass, score, place, images, R.RefineParams(),
                       Progress(on_info=messages.append)) == kept
    assert messages == ([] if kept else [messages[0]])
    if says:
        assert says in messages[0] and str(candidates.detections.det_id[[0, 1]].tolist()) in messages[0]


def test_add_sign_appends_a_numbered_record_unless_implausible(scene, candidates, index):
    p1 = truth(scene, 1)
    rows1, rows7 = views_of(scene, candidates, 1), views_of(scene, candidates, 7)
    result = R.RefineResult([], [], [], [], np.full(len(candidates), -1, np.int64))
    R.add_sign(result, candidates, R.SignDraft(rows1), index, R.RefineParams())
    R.add_sign(result, candidates, R.SignDraft(rows7), index,
               R.RefineParams(max_panel_side_default_m=0.1))
    R.add_sign(result, candidates, R.SignDraft(rows7[:2], joined=list(rows7[2:])), index,
               R.RefineParams())
    assert [s.sign_id for s in result.signs] == [1, 2]
    assert [s.klass for s in result.signs] == ["prohibitory", "yield"]
    assert [s.n_views for s in result.signs] == [len(rows1), len(rows7)]
    assert result.ground_source == [R.GROUND_POINTS] * 2 and result.outlines_world == [None, None]
    assert abs(result.signs[0].height - p1.height_above_ground) < 0.15
    expected = np.full(len(candidates), -1)
    expected[rows1], expected[rows7] = 0, 1
    assert result.candidate_sign.tolist() == expected.tolist()


def test_ground_fallbacks_are_counted_in_one_warning_each():
    result = R.RefineResult([], [], [], [R.GROUND_POINTS, R.CAMERA_HEIGHT, R.LOWEST_POINTS,
                                         R.CAMERA_HEIGHT], np.zeros(0, np.int64))
    warnings = []
    R.warn_ground_fallbacks(result, R.RefineParams(camera_height_m=2.1),
                            Progress(on_warning=warnings.append))
    assert result.warnings == warnings and len(warnings) == 2
    assert warnings[0].startswith("1 sign(s)") and "the lowest points below the sign" in warnings[0]
    assert warnings[1].startswith("2 sign(s)") and "stations' height minus 2.1 m" in warnings[1]
    result = R.RefineResult([], [], [], [R.GROUND_POINTS], np.zeros(0, np.int64))
    R.warn_ground_fallbacks(result, R.RefineParams(), Progress(on_warning=warnings.append))
    assert result.warnings == [] and len(warnings) == 2


def test_refine_params_are_frozen():
    params = R.RefineParams()
    with pytest.raises(dataclasses.FrozenInstanceError):
        params.min_panel_points = 3
    assert dataclasses.replace(params, min_panel_points=3).min_panel_points == 3
    assert params.min_panel_points == R.RefineParams().min_panel_points


def _same_result(a, b):
    """Block-wise and one-block results are the same: records, outlines, points, views."""
    assert len(a.signs) == len(b.signs)
    for s, t in zip(a.signs, b.signs):
        ds, dt = s.as_dict(), t.as_dict()
        assert {k: v for k, v in ds.items() if not isinstance(v, float)} == \
            {k: v for k, v in dt.items() if not isinstance(v, float)}
        floats = [k for k, v in ds.items() if isinstance(v, float)]
        assert [ds[k] for k in floats] == pytest.approx([dt[k] for k in floats], nan_ok=True)
    assert [s.klass for s in a.signs] == [s.klass for s in b.signs]
    assert len(a.point_index) == len(b.point_index)
    for p, q in zip(a.point_index, b.point_index):
        assert np.array_equal(np.sort(p), np.sort(q))
    assert np.array_equal(a.candidate_sign, b.candidate_sign)
    assert a.ground_source == b.ground_source


@pytest.mark.parametrize("block_m", [20.0, 7.0])
def test_refining_block_by_block_gives_the_one_block_result(scene, candidates, index, block_m):
    one = R.refine_signs(candidates, index, block_m=float("inf"))
    with R.CloudBlocks(candidates, R.merge_candidates(candidates, 1.0), index, 1.0, block_m,
                       R.RefineParams()) as blocks:
        assert len(blocks.blocks) >= 6      # the 160 m scene spans many blocks
    _same_result(R.refine_signs(candidates, index, block_m=block_m), one)
    assert len(one.signs) == len(scene.signs)


def test_a_block_of_many_groups_is_cut_in_drive_order_with_the_same_result(scene, candidates, index):
    one = R.refine_signs(candidates, index, block_m=float("inf"))
    groups = R.merge_candidates(candidates, 1.0)
    params = dataclasses.replace(R.RefineParams(), block_max_groups=2)
    with R.CloudBlocks(candidates, groups, index, 1.0, 40.0, R.RefineParams()) as whole, \
            R.CloudBlocks(candidates, groups, index, 1.0, 40.0, params) as cut:
        assert max(len(b) for b in whole.blocks) > 2 and max(len(b) for b in cut.blocks) <= 2
        assert len(cut.blocks) > len(whole.blocks)
        # every group once, each cut block inside one block of 40 m, in drive order
        np.testing.assert_array_equal(np.sort(np.concatenate(cut.blocks)), np.arange(len(groups)))
        s_m = whole._axis.locate(whole.centres)[0]
        parent = {int(g): k for k, b in enumerate(whole.blocks) for g in b}
        assert all(len({parent[int(g)] for g in b}) == 1 for b in cut.blocks)
        ends = [(parent[int(b[0])], s_m[b].min(), s_m[b].max()) for b in cut.blocks]
        for (k0, _, hi), (k1, lo, _) in zip(ends, ends[1:]):
            assert k1 > k0 or (k1 == k0 and lo >= hi)
    _same_result(R.refine_signs(candidates, index, params=params, block_m=40.0), one)
    # one block (block_m inf) stays one block, however many groups
    with R.CloudBlocks(candidates, groups, index, 1.0, float("inf"), params) as single:
        assert len(single.blocks) == 1


def test_blocks_refined_in_threads_give_the_same_signs_and_log_in_order(candidates, index):
    runs = {}
    for threads in (1, 2):
        log = []
        params = dataclasses.replace(R.RefineParams(), block_threads=threads)
        result = R.refine_signs(candidates, index, params=params, block_m=7.0,
                                progress=Progress(on_info=log.append, on_warning=log.append))
        runs[threads] = (result, [str(m) for m in log])
    _same_result(runs[2][0], runs[1][0])
    assert runs[1][1] and runs[2][1] == runs[1][1]        # the blocks' messages in block order


def test_refining_a_las_file_block_by_block_gives_the_one_block_result(scene, candidates, tmp_path):
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    one = R.refine_signs(candidates, las, block_m=float("inf"))
    _same_result(R.refine_signs(candidates, las, block_m=20.0), one)
    # and the single index read the old way (all of the cloud near the candidates at once)
    old = R.cloud_around_candidates(candidates, las, R.DEFAULT_MERGE_RADIUS_M)
    with R.CloudBlocks(candidates, R.merge_candidates(candidates, 1.0), las, 1.0, 20.0, R.RefineParams()) as blocks:
        assert blocks.bright == pytest.approx(R.bright_level(old))
    _same_result(R.refine_signs(candidates, old, block_m=float("inf")), one)


def test_a_spooled_block_of_many_points_is_halved_with_the_same_result(scene, candidates, tmp_path):
    """A block over ``block_max_points`` points (and of more than one group) is halved, its
    groups in drive order, each half in a spool file of its own with the block's points
    within its reach; again while a half is over. The signs do not change."""
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    one = R.refine_signs(candidates, las, block_m=float("inf"))
    groups = R.merge_candidates(candidates, 1.0)
    params = dataclasses.replace(R.RefineParams(), block_max_points=3000)
    with R.CloudBlocks(candidates, groups, las, 1.0, 40.0, R.RefineParams()) as whole, \
            R.CloudBlocks(candidates, groups, las, 1.0, 40.0, params) as halved:
        counts = [halved._spool.count("block", sid) for sid in halved._spool_ids]
        assert max(whole._spool.count("block", sid) for sid in whole._spool_ids) > 3000
        assert len(halved.blocks) > len(whole.blocks)
        assert all(n <= 3000 or len(gs) == 1 for n, gs in zip(counts, halved.blocks))
        np.testing.assert_array_equal(np.sort(np.concatenate(halved.blocks)), np.arange(len(groups)))
        files = sorted(os.listdir(halved._spool.folder))
        assert len(files) == len([n for n in counts if n])      # the halved blocks' files are gone
        assert halved.bright == pytest.approx(whole.bright)
        # a half holds exactly the block's points within its own reach
        parent = {int(g): k for k, b in enumerate(whole.blocks) for g in b}
        for b, gs in enumerate(halved.blocks):
            k = parent[int(gs[0])]
            assert all(parent[int(g)] == k for g in gs)
            xy, radius = halved._groups_read(gs)
            rows = whole._spool.read("block", whole._spool_ids[k])
            mine = R.CropRegion.corridor(radius, points_xy=xy).mask(rows["xyz"][:, 0], rows["xyz"][:, 1])
            assert np.array_equal(np.sort(halved._block(b).point_index), np.sort(rows["point_index"][mine]))
    _same_result(R.refine_signs(candidates, las, params=params, block_m=40.0), one)


def test_cancel_while_halving_blocks_stops_and_leaves_no_spool(scene, candidates, tmp_path, monkeypatch):
    """Cancel asked for once the spool pass is over stops the halving of dense blocks, and
    the spool folder goes with it."""
    from roadsigns.core.errors import Cancelled

    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    spooled, folders = [False], []
    spool_blocks = R.CloudBlocks._spool_blocks

    def then_cancel(self, progress):
        spool_blocks(self, progress)
        folders.append(self._spool.folder)
        spooled[0] = True

    read_after, read = [], R.Spool.read

    def reading(self, kind, index):
        if spooled[0]:
            read_after.append(index)
        return read(self, kind, index)

    monkeypatch.setattr(R.CloudBlocks, "_spool_blocks", then_cancel)
    monkeypatch.setattr(R.Spool, "read", reading)
    params = dataclasses.replace(R.RefineParams(), block_max_points=3000)
    with pytest.raises(Cancelled):
        R.CloudBlocks(candidates, R.merge_candidates(candidates, 1.0), las, 1.0, 40.0, params,
                      Progress(is_cancelled=lambda: spooled[0]))
    assert folders and not os.path.exists(folders[0])
    assert read_after == []           # no block was read back to be halved


def test_blocks_hold_no_shape_of_the_whole_drive(scene, candidates, tmp_path, monkeypatch):
    """The corridor is built only around the points tested, with the same shape there as the
    drive-wide one; a block's read region only while spooling meets it, a few at a time, and
    the hull that picks the chunks to read holds it: 10 MB of shapes on 9 km otherwise."""
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    one = R.refine_signs(candidates, las, block_m=float("inf"))
    monkeypatch.setattr(R, "REGIONS_HELD", 2)
    held = []
    region = R.CloudBlocks._region

    def counted(self, b):
        out = region(self, b)
        held.append(len(self._regions))
        return out

    monkeypatch.setattr(R.CloudBlocks, "_region", counted)
    with R.CloudBlocks(candidates, R.merge_candidates(candidates, 1.0), las, 1.0, 7.0, R.RefineParams()) as blocks:
        assert len(blocks.blocks) >= 6 and held and max(held) <= 2
        assert not hasattr(blocks, "corridor")
        whole = R.CropRegion.corridor(blocks.corridor_m, points_xy=blocks.ok_xy)
        rng = np.random.default_rng(3)
        lo, hi = blocks.ok_xy.min(axis=0) - 5.0, blocks.ok_xy.max(axis=0) + 5.0
        for _ in range(20):    # windows of points anywhere along the drive
            c = rng.uniform(lo, hi)
            xy = c + rng.uniform(-8.0, 8.0, (4000, 2))
            np.testing.assert_array_equal(blocks._corridor_mask(xy[:, 0], xy[:, 1]), whole.mask(xy[:, 0], xy[:, 1]))
        for b in range(len(blocks.blocks)):
            xy, radius = blocks._block_read(b)
            hull = R.shapely.convex_hull(R.shapely.multipoints(xy)).buffer(radius * R.HULL_MARGIN + 0.01, 4)
            assert hull.covers(blocks._region(b).geometry)
    _same_result(R.refine_signs(candidates, las, block_m=7.0), one)


@pytest.mark.parametrize("cloud", ["index", "las"])
def test_image_only_ground_is_read_block_by_block_with_the_one_read_result(scene, candidates, index,
                                                                          tmp_path, monkeypatch, cloud):
    """CloudBlocks.ground_of gathers the points around image-only signs one block at a time
    (on a long drive one read of them all held 0.4 GB), each sign's ground as from one read."""
    if cloud == "las":
        index = str(tmp_path / "cloud.las")
        signscene.write_las(scene, index)
    params, groups = R.RefineParams(), R.merge_candidates(candidates, 1.0)
    ids = sorted({p.sign_id for p in scene.panels if len(views_of(scene, candidates, p.sign_id))})

    def drafts():
        return [R.SignDraft(views_of(scene, candidates, i), x_image=truth(scene, i).centre_world)
                for i in ids]
    one, by_block = drafts(), drafts()
    with R.CloudBlocks(candidates, groups, index, 1.0, float("inf"), params) as blocks:
        blocks.ground_of(one, params)
    reads = []
    real = R.CloudBlocks._around

    def counted(self, centres_xy, radius_m):
        reads.append(len(centres_xy))
        return real(self, centres_xy, radius_m)
    monkeypatch.setattr(R.CloudBlocks, "_around", counted)
    with R.CloudBlocks(candidates, groups, index, 1.0, 20.0, params) as blocks:
        blocks.ground_of(by_block, params)
    assert len(ids) >= 8 and len(reads) >= 4 and max(reads) < len(ids) and sum(reads) == len(ids)
    assert [d.ground[1] for d in by_block] == [d.ground[1] for d in one]
    assert [d.ground[0] for d in by_block] == pytest.approx([d.ground[0] for d in one])
    assert sum(d.ground[1] == R.GROUND_POINTS for d in one) >= len(ids) - 1


def test_a_las_file_is_read_once_for_all_blocks_and_the_spool_removed(scene, candidates, tmp_path,
                                                                      monkeypatch):
    """Several blocks are spooled in one pass over the file (CloudBlocks._spool), not read
    once per block and pass, nor again for the ground of image-only signs (from the spool,
    each sign's as from one read of the cloud); the spool folder goes when refinement ends."""
    import tempfile

    from roadsigns.core.cloudsource import CloudSource
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    reads = []
    real = CloudSource.iter_indexed_chunks

    def counted(self, *args, **kwargs):
        reads.append(kwargs.get("area") is not None)
        return real(self, *args, **kwargs)

    monkeypatch.setattr(CloudSource, "iter_indexed_chunks", counted)
    with R.CloudBlocks(candidates, R.merge_candidates(candidates, 1.0), las, 1.0, 20.0, R.RefineParams()) as blocks:
        assert len(blocks.blocks) >= 4
        assert blocks._spool is not None and os.listdir(blocks._spool.folder)
        drafts = blocks.extract_signs(R.RefineParams())
        assert drafts and reads == [True]  # the bright level and the signs: one read
        ids = sorted({p.sign_id for p in scene.panels if len(views_of(scene, candidates, p.sign_id))})
        image_only = [R.SignDraft(views_of(scene, candidates, i), x_image=truth(scene, i).centre_world)
                      for i in ids]
        blocks.ground_of(image_only, R.RefineParams())
        assert reads == [True]             # their ground: no read of the file
    read_once = R.cloud_around_candidates(candidates, las, R.DEFAULT_MERGE_RADIUS_M)
    assert len(ids) >= 8
    for draft in image_only:
        z, source = R.ground_from_cloud(read_once, R.placement(candidates, draft).centre,
                                        R.placement(candidates, draft).bottom_z, R.RefineParams())
        assert draft.ground[1] == source == R.GROUND_POINTS and draft.ground[0] == pytest.approx(z)
    assert os.listdir(tmp_path / "tmp") == []


def test_drafts_let_their_panels_points_go_once_placed(candidates, index):
    """After a block, a draft keeps its placement (the cloud positions of its panel's points
    among it), not the points themselves: a drive's drafts would otherwise hold 35 bytes a
    panel point (6.5 MB on 4,800 candidates)."""
    params, groups = R.RefineParams(), R.merge_candidates(candidates, 1.0)
    with R.CloudBlocks(candidates, groups, index, 1.0, 20.0, params) as blocks:
        drafts = blocks.extract_signs(params)
        fresh = R.extract_signs(candidates, groups, blocks.index, blocks.bright, params)
    panels = [(d, f) for d, f in zip(drafts, fresh) if f.panel is not None]
    assert len(drafts) == len(fresh) and len(panels) >= 8
    for draft, full in panels:
        assert draft.panel is not None and draft.panel.points is None and full.panel.points is not None
        kept, found = R.placement(candidates, draft), R.placement(candidates, full)
        np.testing.assert_array_equal(kept.point_index, found.point_index)
        np.testing.assert_allclose(kept.centre, found.centre)
        assert kept.mean_intensity == pytest.approx(found.mean_intensity)
        assert kept.width_m == pytest.approx(found.width_m) and kept.source == found.source == "lidar"


def test_a_group_across_a_block_seam_is_refined_once_with_all_its_points(candidates, index,
                                                                        monkeypatch):
    from roadsigns.core.drivewindows import Window
    groups = R.merge_candidates(candidates, 1.0)
    axis = R.drive_axis_of(candidates)
    s = axis.locate(np.array([np.median(candidates.xyz_world[g], axis=0) for g in groups]))[0]
    one = R.refine_signs(candidates, index, block_m=float("inf"))
    order = np.argsort(s)
    for g in (order[1], order[len(groups) // 2], order[-2]):
        for eps in (-0.05, 0.05):   # the seam runs through the group's panel, either side
            edge = float(s[g] + eps)
            monkeypatch.setattr(R, "make_windows", lambda length_m, block_m, edge=edge: [
                Window(0, -np.inf, edge), Window(1, edge, np.inf)])
            with R.CloudBlocks(candidates, groups, index, 1.0, 10.0, R.RefineParams()) as blocks:
                assert len(blocks.blocks) == 2
                mine = next(b for b in blocks.blocks if g in b)
            assert np.all((s[mine] < edge) == (eps > 0))
            _same_result(R.refine_signs(candidates, index, block_m=10.0), one)


def test_median_of_counts_is_numpys_median():
    rng = np.random.default_rng(3)
    for n in (1, 2, 7, 100):
        v = rng.integers(0, 20, n)
        hist = np.bincount(v, minlength=20)
        assert R.median_of_counts(np.arange(20.0), hist) == np.median(v)
        med = np.median(v)
        assert R.median_of_counts(np.abs(np.arange(20.0) - med), hist) == np.median(np.abs(v - med))
    assert np.isnan(R.median_of_counts(np.arange(3.0), np.zeros(3, np.int64)))


@pytest.mark.parametrize("seen_in,limit,kept,missed", [
    ("pano_00015.jpg", 2, False, 4),   # 25.8 m away; stations 16-19 (21-8 m) saw sign 6, not this
    ("pano_00015.jpg", 5, True, 4),    # fewer misses than the limit
    ("pano_00015.jpg", 0, True, 4),    # the rule off
    ("pano_00019.jpg", 2, True, 0),    # seen from the nearest station in front: none nearer
])
def test_a_sign_seen_once_from_afar_and_missed_nearer_is_dropped(scene, index, seen_in, limit, kept, missed):
    """Sign 7 (x = 100 m, on the left, facing the oncoming stations 15-19) keeps one of its
    five views. From station 15 the four stations nearer to its face, which gave detections
    of sign 6, did not see it: a look-alike, dropped unless the rule allows four misses or
    is off. From station 19 no station in front stands nearer, so the lone view is kept."""
    rows = [d for d in scene.detections if d["truth_id"] != 7 or d["image"] == seen_in]
    messages = []
    cand = P.project_detections(P.Detections.from_records(rows), index)
    out = R.refine_signs(cand, index, params=R.RefineParams(single_view_max_nearer_misses=limit),
                         progress=Progress(on_info=messages.append))
    p = truth(scene, 7)
    found = match(out.signs, [p])
    assert (p.sign_id in found) == kept
    if kept:
        assert found[p.sign_id].n_views == 1 and found[p.sign_id].source_images == seen_in
    said = [m for m in messages if "not in the" in m]
    assert said == ([] if kept else [said[0]])
    if not kept:
        assert f"seen in one panorama only ({seen_in}, 25.8 m away)" in said[0]
        assert f"not in the {missed} panoramas nearer to its face" in said[0]
    place = R.Placement(p.centre_world, p.normal, 0.6, 0.6, p.centre_world[2] - 0.3,
                        np.zeros(0, np.int64), np.nan, np.nan, "lidar", None)
    assert R.nearer_stations_that_missed(place, [seen_in], R.DetectedStations.of(cand), R.RefineParams())[0] == missed


def test_only_panoramas_that_gave_detections_count_as_having_missed(scene, index):
    """Sign 1 (x = 20 m) seen only from station 0, 21 m away: of the three stations nearer to
    its face only station 3 gave any detection (of signs 2 and 3); stations 1 and 2 saw
    nothing at all and are not known to the stage, so one miss is counted and the sign kept."""
    rows = [d for d in scene.detections if d["truth_id"] != 1 or d["image"] == "pano_00000.jpg"]
    cand = P.project_detections(P.Detections.from_records(rows), index)
    stations = R.DetectedStations.of(cand)
    assert "pano_00001.jpg" not in stations.images and "pano_00003.jpg" in stations.images
    p = truth(scene, 1)
    place = R.Placement(p.centre_world, p.normal, 0.6, 0.6, p.centre_world[2] - 0.3,
                        np.zeros(0, np.int64), np.nan, np.nan, "lidar", None)
    assert R.nearer_stations_that_missed(place, ["pano_00000.jpg"], stations, R.RefineParams())[0] == 1
    assert p.sign_id in match(R.refine_signs(cand, index).signs, [p])


def _stations_along_x(xs, z=2.4):
    return R.DetectedStations([f"pano_{k:05d}.jpg" for k in range(len(xs))],
                      np.column_stack([xs, np.zeros(len(xs)), np.full(len(xs), z)]))


@pytest.mark.parametrize("centre,normal,seen_from,expected", [
    # a sign 6 m right of the road at x = 40 m facing the stations coming from x < 40: seen
    # from x = 0 (40.4 m), missed from x = 5 ... 35
    ((40.0, -6.0, 2.6), (-1.0, 0.0, 0.0), 0, 7),
    # the same sign facing +x, seen from x = 55 (16.2 m): missed from x = 45 and 50 in front
    # of it; the stations before it see its back
    ((40.0, -6.0, 2.6), (1.0, 0.0, 0.0), 11, 2),
    # a gantry panel 6 m over the road, seen from x = 0: from x = 35 (5 m) it stands 36 deg
    # above the horizon, out of the horizon views, so only x = 5 ... 30 missed it
    ((40.0, 0.0, 6.0), (-1.0, 0.0, 0.0), 0, 6),
])
def test_nearer_stations_that_missed_are_in_front_nearer_and_below_the_elevation_limit(centre, normal, seen_from,
                                                                                      expected):
    stations = _stations_along_x(np.arange(0.0, 60.0, 5.0))
    place = R.Placement(np.array(centre), np.array(normal), 0.6, 0.6, centre[2] - 0.3,
                        np.zeros(0, np.int64), np.nan, np.nan, "lidar", None)
    image = stations.images[seen_from]
    missed, seen_range_m = R.nearer_stations_that_missed(place, [image], stations, R.RefineParams())
    assert seen_range_m == pytest.approx(math.hypot(centre[0] - 5.0 * seen_from, centre[1]))
    assert missed == expected


def test_the_refinement_says_how_many_groups_it_has_refined(scene, candidates, tmp_path):
    las = str(tmp_path / "cloud.las")
    signscene.write_las(scene, las)
    steps = []
    R.refine_signs(candidates, las, block_m=20.0, progress=Progress(on_step=steps.append))
    refining = [s for s in steps if s.template.startswith("Refining the signs")]
    assert any(s.template.startswith("Reading") for s in steps)
    assert len(refining) >= 2 and refining[-1].fields["n"] == refining[-1].fields["count"]
    assert [s.fields["n"] for s in refining] == sorted(s.fields["n"] for s in refining)
