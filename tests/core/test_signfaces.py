"""Sign faces of many countries drawn in code (devtools/train/signfaces.py) and their bench
set (bench/bench_detector.py drawn_face_frames): each family has its class's outline and
sheeting, faces are repeatable, and the bench counts each pasted face once by family."""
import math
import os
import sys

import numpy as np
import pytest

from devtools import REPO_ROOT
from devtools.train import data as train_data
from devtools.train import signfaces

sys.path.insert(0, os.path.join(REPO_ROOT, "bench"))
import bench_detector as bd  # noqa: E402

#: Share of its bounding box an outline fills: a disc, a triangle, an octagon, a panel.
OUTLINE_SHARE = {"prohibitory": math.pi / 4, "mandatory": math.pi / 4, "warning": 0.5, "yield": 0.5,
                 "stop": 2 / (1 + math.sqrt(2))}   # 0.828


def _opaque_share(face):
    ys, xs = np.nonzero(face[..., 3])
    box = face[ys.min():ys.max() + 1, xs.min():xs.max() + 1, 3]
    return float((box > 0).mean())


def _colour(rgb, name):
    r, g, b = (rgb[..., k].astype(int) for k in range(3))
    return {"red": (r > g + 60) & (r > b + 40), "blue": (b > r + 40) & (b > g + 10)}[name]


@pytest.mark.parametrize("family", sorted(signfaces.FAMILIES))
def test_each_family_has_its_class_outline(family):
    rng = np.random.default_rng(7)
    cls = signfaces.family_class(family)
    for _ in range(6):
        face, drawn_cls, drawn_family = signfaces.random_face(rng, 120, families=[family])
        assert (drawn_cls, drawn_family) == (cls, family)
        assert face.dtype == np.uint8 and face.shape[2] == 4 and max(face.shape[:2]) == 120
        assert set(np.unique(face[..., 3])) <= {0, 255}
        share = _opaque_share(face)
        if cls == "information":   # rectangles, corners rounded at most a little
            assert share > 0.93, share
        else:
            assert abs(share - OUTLINE_SHARE[cls]) < 0.06, (family, share)


@pytest.mark.parametrize("family, colour", [("ring_legend", "red"), ("no_parking", "red"), ("no_stopping", "red"),
                                            ("no_entry", "red"), ("blue_disc", "blue"), ("octagon", "red")])
def test_round_faces_carry_their_sheeting_on_the_rim(family, colour):
    """A red ring (or disc, or octagon) or a blue disc: sampled just inside the outline."""
    rng = np.random.default_rng(3)
    for _ in range(6):
        face, _, _ = signfaces.random_face(rng, 160, families=[family])
        rgb = face[..., :3]
        c, r = 79.5, 80.0
        a = np.linspace(0, 2 * np.pi, 72, endpoint=False)
        inner = 0.82 if family in ("no_entry", "blue_disc", "octagon") else 0.88
        ring = [rgb[int(round(c + inner * r * math.sin(t))), int(round(c + inner * r * math.cos(t)))] for t in a]
        # a white rim outside, faded sheeting or dirt may take some of the ring
        assert _colour(np.array(ring), colour).mean() > 0.6 or _faded(face), family


def _faded(face):
    rgb = face[..., :3][face[..., 3] > 0].astype(float)
    return rgb.std(axis=1).mean() < 40      # washed out towards grey


def test_no_parking_fields_are_blue_and_no_entry_bars_white():
    rng = np.random.default_rng(11)
    for family, centre_colour in (("no_parking", "blue"), ("no_stopping", "blue")):
        for _ in range(6):
            face, _, _ = signfaces.random_face(rng, 160, families=[family])
            # the field between the bars, left, right, above and below the centre: blue where
            # no letter (a P or an E on a fifth of them) lies on it
            spots = [_colour(face[y - 2:y + 3, x - 2:x + 3, :3], "blue").mean() > 0.8
                     for x, y in ((55, 80), (105, 80), (80, 55), (80, 105))]
            assert sum(spots) >= 2 or _faded(face), family
    for _ in range(6):
        face, _, _ = signfaces.random_face(rng, 160, families=["no_entry"])
        bar = face[78:82, 50:110, :3].astype(int)
        assert (bar.min(axis=2) > 150).mean() > 0.8 or _faded(face)


def test_faces_are_repeatable_and_vary():
    a = signfaces.random_faces(12, seed=5, size_px=96)
    b = signfaces.random_faces(12, seed=5, size_px=96)
    c = signfaces.random_faces(12, seed=6, size_px=96)
    for (fa, ca, na), (fb, cb, nb) in zip(a, b):
        np.testing.assert_array_equal(fa, fb)
        assert (ca, na) == (cb, nb)
    assert any(fa.shape != fc.shape or not np.array_equal(fa, fc) for (fa, _, _), (fc, _, _) in zip(a, c))
    # every class comes up, each about as often as the others
    classes = [cls for _, cls, _ in signfaces.random_faces(600, seed=1, size_px=48)]
    counts = np.array([classes.count(c) for c in signfaces.CLASSES])
    assert counts.min() > 0.6 * 100 and counts.max() < 1.4 * 100


def test_training_faces_are_bgra_with_class_ids():
    patches, classes = train_data.drawn_faces(30, seed=2, size_px=64)
    again, _ = train_data.drawn_faces(30, seed=2, size_px=64)
    faces = signfaces.random_faces(30, seed=2, size_px=64)
    assert len(patches) == len(classes) == 30
    for patch, cls, (face, name, _), same in zip(patches, classes, faces, again):
        assert train_data.CLASSES[cls] == name
        np.testing.assert_array_equal(patch[..., [2, 1, 0, 3]], face)   # RGBA -> BGRA
        np.testing.assert_array_equal(patch, same)


def test_a_word_is_drawn_inside_its_box():
    img = np.zeros((60, 200, 4), np.uint8)
    signfaces.draw_text(img, "ARRÊT", (255, 255, 255), (20, 10, 180, 50), np.random.default_rng(0))
    ys, xs = np.nonzero(img[..., 0] > 128)
    assert len(xs) > 100
    assert xs.min() >= 19 and xs.max() <= 181 and ys.min() >= 9 and ys.max() <= 51
    assert xs.max() - xs.min() > 100 or ys.max() - ys.min() > 30   # fitted to the box, not tiny


@pytest.mark.skipif(not os.path.isdir(os.path.join(train_data.DATA_DIR, "gtsdb-train")),
                    reason="needs the shared data folder beside the checkout")
def test_the_face_set_pastes_every_family_in_every_band_once_and_is_repeatable():
    ids = range(500, 524)
    frames = list(bd.drawn_face_frames(ids=ids, per_family=2))
    again = list(bd.drawn_face_frames(ids=ids, per_family=2))
    truth = train_data.read_gtsdb(ids)
    families = [f for frame in frames for f in frame.families]
    n_bands = len(bd.FACE_SIZES_PX)
    # a face that found no free spot is not pasted; nearly all are
    assert len(families) >= 0.9 * len(signfaces.FAMILIES) * n_bands * 2
    assert set(families) == set(signfaces.FAMILIES)
    for frame, (_, own, _), same in zip(frames, truth, again):
        assert len(frame.families) == len(frame.boxes) == len(frame.classes)
        np.testing.assert_array_equal(frame.ignored, own)
        np.testing.assert_array_equal(frame.boxes, same.boxes)
        assert frame.families == same.families
        for family, cls in zip(frame.families, frame.classes):
            assert train_data.CLASSES[cls] == signfaces.family_class(family)
        heights = frame.boxes[:, 3] - frame.boxes[:, 1]
        assert np.all((heights >= 0.5 * bd.FACE_SIZES_PX[0][0]) & (heights <= 1.5 * bd.FACE_SIZES_PX[-1][1]))


def test_a_red_ring_tells_the_limit_it_states_and_the_same_draws_make_the_same_faces():
    rng_a, rng_b = np.random.default_rng(11), np.random.default_rng(11)
    limits = {}
    for _ in range(120):
        face, cls, family = signfaces.random_face(rng_a, 96)
        face_b, cls_b, family_b, limit = signfaces.random_face_with_limit(rng_b, 96)
        assert np.array_equal(face, face_b) and (cls, family) == (cls_b, family_b)
        if limit is not None:
            assert family == "ring_legend"
        limits.setdefault(family, set()).add(limit)
    assert limits["ring_legend"] - {None}   # some rings state a limit, ...
    assert None in limits["ring_legend"]    # ... others a letter, a pictogram, or are crossed out


def test_a_face_takes_a_code_where_the_table_has_one_else_its_unlisted_class():
    from devtools.train import codes

    names = codes.classifier_names()
    unlisted = names.index("unlisted:prohibitory")
    assert codes.face_label(names, "ring_legend", "50", unlisted) == names.index("DE:274[50]")
    assert codes.face_label(names, "ring_legend", "90", unlisted) == unlisted     # no 90 in the table
    assert codes.face_label(names, "ring_legend", "3.5m", unlisted) == unlisted
    assert codes.face_label(names, "ring_legend", None, unlisted) == unlisted
    assert codes.face_label(names, "octagon", None, unlisted) == names.index("DE:206")


def test_a_polygon_shrunk_keeps_its_centroid_and_its_nearest_edge_moves_in_by_the_pixels_asked():
    # a 3-4-5 right triangle; its centroid (4/3, 1) is 0.8 px from the hypotenuse, its nearest
    # edge (2-D points: numpy 2 has no 2-D np.cross, the helper must not need it)
    pts = np.array([[0.0, 0.0], [4.0, 0.0], [0.0, 3.0]])
    centroid = pts.mean(0)
    shrunk = signfaces._shrunk(pts, 0.5)
    assert np.allclose(shrunk.mean(0), centroid)
    assert np.allclose(shrunk - centroid, (pts - centroid) * (1.0 - 0.5 / 0.8))
    a, b = shrunk[1], shrunk[2]
    u, v = b - a, centroid - a
    assert abs(u[0] * v[1] - u[1] * v[0]) / np.linalg.norm(u) == pytest.approx(0.8 - 0.5)
