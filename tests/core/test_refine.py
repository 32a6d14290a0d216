"""Candidates -> signs (core.refine) on a scene of known sign panels."""
import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

from helpers import signscene
from roadsigns.core import projection as P
from roadsigns.core import refine as R
from roadsigns.core.errors import Progress
from roadsigns.core.pointcloud import TiledIndex, read_header


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
        assert tuple(rec) == R.SIGN_FIELDS
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


@pytest.mark.parametrize("score,kept", [(0.5, False), (0.9, True)])
def test_a_sign_seen_once_needs_a_confident_detection(scene, index, score, kept):
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
