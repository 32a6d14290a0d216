"""The bundled model (models/roadsigns-int8.onnx) through qgis_process finds a generated scene's signs.

The scene (tests/conftest.py ``scene_tiny``: preset tiny, seed 3, 2048 x 1024 panoramas) was
never used in training (training scenes have seeds from 100 up). Clearly visible signs:
front faces at least 20 px tall and at most 20 % hidden. Each must be found with its class
(IoU >= 0.5 with its visible or whole box), and the detections must lie on signs.
"""
import os

import numpy as np
import pytest
from helpers.scenes import seam_iou
from osgeo import ogr

from devtools import REPO_ROOT
from roadsigns.core.detector import DEFAULT_CONFIDENCE
from roadsigns.core.rescue import class_of_code
from roadsigns.core.signcodes import read_codes_table, unlisted_code_class

BUNDLED = os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx")
MIN_HEIGHT_PX = 20
MAX_OCCLUSION = 0.2
MIN_RECALL = 0.8          # of clearly visible signs found with the right class
MIN_ON_SIGN_SHARE = 0.9   # of detections lying on a true sign (front face)
CODES_TABLE = read_codes_table(os.path.join(REPO_ROOT, "models", "sign-codes-de.csv"))

pytestmark = pytest.mark.skipif(not os.path.isfile(BUNDLED), reason="no bundled model")


def read_as_its_class(detection):
    """Whether the code read in a detection the second look kept is one of its class: a code
    of the bundled table whose class is the detection's, or ``unlisted:`` and the class. The
    second look keeps a box when the codes of one class add up to >= 0.9 and gives it that
    class, so the best code, the one the layer holds, is of that class (its own probability
    may be under 0.9: a speed limit whose digits are unsure)."""
    code, klass = detection["code"], detection["class"]
    return klass == (unlisted_code_class(code) or class_of_code(code, CODES_TABLE, [klass]))


def front_faces(scene):
    """Per image, the signs it shows front on (with a visible box)."""
    return {m["image"]: [s for s in m["signs"] if s["facing"] == "front" and s.get("visible_box")]
            for m in scene["images"]}


def on_a_sign(detection, faces, width, min_iou=0.3):
    """Whether a detection's box overlaps one of ``faces`` (visible or whole box) by ``min_iou``."""
    box = [detection["u0"], detection["v0"], detection["u1"], detection["v1"]]
    return any(max(seam_iou(box, s["visible_box"], width), seam_iou(box, s["box"], width)) >= min_iou
               for s in faces)


def read_detections(path):
    dataset = ogr.Open(path)
    rows = [{k: f[k] for k in ("image", "class", "score", "code", "code_score", "u0", "v0", "u1", "v1")}
            for f in dataset.GetLayer(0)]
    dataset = None
    return rows


@pytest.fixture(scope="module")
def detections(qgis_process, scene_tiny_stations, tmp_path_factory):
    work = tmp_path_factory.mktemp("bundled")
    stations = scene_tiny_stations
    out = str(work / "detections.gpkg")
    # no MODEL: the bundled one; every view (the upward ring too), as the test counts the signs
    # clearly visible anywhere in each panorama
    run = qgis_process.run("roadsigns:detectsigns", STATIONS=stations, UPWARD_VIEWS=True, OUTPUT=out)
    assert run.returncode == 0, run.text
    assert "roadsigns-int8.onnx" in run.text
    assert "Edge-on look" in run.text and "Zoomed look" in run.text   # both on by default
    return read_detections(out)


def test_bundled_model_finds_the_clearly_visible_signs(detections, scene_tiny):
    _, scene = scene_tiny
    width = scene["image_width"]
    sign_class = {s["sign_id"]: s["class"] for s in scene["signs"]}
    by_image = {}
    for d in detections:
        by_image.setdefault(d["image"], []).append(d)
    wanted, found, missed = 0, 0, []
    for meta in scene["images"]:
        for s in meta["signs"]:
            vb = s.get("visible_box")
            if (s["facing"] != "front" or vb is None or vb[3] - vb[1] < MIN_HEIGHT_PX
                    or s["occlusion"] > MAX_OCCLUSION):
                continue
            wanted += 1
            hit = any(d["class"] == sign_class[s["sign_id"]]
                      and max(seam_iou([d["u0"], d["v0"], d["u1"], d["v1"]], box, width)
                              for box in (vb, s["box"])) >= 0.5
                      for d in by_image.get(meta["image"], []))
            found += hit
            if not hit:
                missed.append((meta["image"], s["sign_id"], sign_class[s["sign_id"]], [round(v) for v in vb]))
    assert wanted >= 10  # the scene shows enough signs for the test to mean something
    assert found >= MIN_RECALL * wanted, f"found {found} of {wanted}; missed {missed}"


def test_bundled_model_detections_lie_on_signs(detections, scene_tiny):
    _, scene = scene_tiny
    width = scene["image_width"]
    fronts = front_faces(scene)
    assert detections
    off = [(d["image"], d["class"], round(d["score"], 2), [round(d[k]) for k in ("u0", "v0", "u1", "v1")])
           for d in detections if not on_a_sign(d, fronts[d["image"]], width)]
    assert len(off) <= (1 - MIN_ON_SIGN_SHARE) * len(detections), \
        f"{len(off)} of {len(detections)} detections on no sign: {off}"
    # the default CONFIDENCE, or kept by the second look (a code of its class read)
    assert all(d["score"] >= DEFAULT_CONFIDENCE or read_as_its_class(d) for d in detections)


def test_second_look_adds_only_boxes_the_classifier_reads(qgis_process, scene_tiny_stations, scene_tiny, tmp_path):
    """With CONFIDENCE 0.9 the boxes scored from RESCUE_CONFIDENCE (default 0.05) to 0.9 get the
    second look: the detections from 0.9 up are those of a run without it, and each box it adds
    has a sign code of its class read (:func:`read_as_its_class`) and lies on a sign."""
    _, scene = scene_tiny
    runs = {}
    for name, rescue in (("off", 0.9), ("on", None)):
        out = str(tmp_path / f"{name}.gpkg")
        extra = {} if rescue is None else {"RESCUE_CONFIDENCE": rescue}
        run = qgis_process.run("roadsigns:detectsigns", STATIONS=scene_tiny_stations, CONFIDENCE=0.9, OUTPUT=out,
                               **extra)
        assert run.returncode == 0, run.text
        assert ("Second look" in run.text) == (rescue is None)
        runs[name] = read_detections(out)

    def sure(rows):
        return sorted((r["image"], r["class"], round(r["u0"], 2), round(r["v0"], 2), round(r["u1"], 2),
                       round(r["v1"], 2), r["code"]) for r in rows if r["score"] >= 0.9)
    assert sure(runs["on"]) == sure(runs["off"])
    assert all(r["score"] >= 0.9 for r in runs["off"])
    added = [r for r in runs["on"] if r["score"] < 0.9]
    assert len(added) >= 3, "the second look kept nothing: the test shows nothing"
    assert all(read_as_its_class(r) for r in added), [(r["class"], r["code"], r["code_score"]) for r in added]
    width = scene["image_width"]
    fronts = front_faces(scene)
    on_sign = [on_a_sign(r, fronts[r["image"]], width) for r in added]
    assert np.mean(on_sign) >= MIN_ON_SIGN_SHARE, f"{on_sign.count(False)} of {len(added)} added boxes on no sign"


def test_zoomed_look_adds_sure_boxes_on_signs(qgis_process, scene_tiny_stations, scene_tiny, tmp_path):
    """ZOOMED_LOOK (core/zoomlook.py), the second look and the edge-on look off (RESCUE_CONFIDENCE
    at the confidence, EDGE_ON_LOOK false) to see it alone: the detections of a run without it
    are all there, and each box it adds scores the confidence or more and lies on a sign."""
    _, scene = scene_tiny
    runs = {}
    for name, zoom in (("off", False), ("on", True)):
        out = str(tmp_path / f"{name}.gpkg")
        run = qgis_process.run("roadsigns:detectsigns", STATIONS=scene_tiny_stations, ZOOMED_LOOK=zoom,
                               EDGE_ON_LOOK=False, RESCUE_CONFIDENCE=DEFAULT_CONFIDENCE, OUTPUT=out)
        assert run.returncode == 0, run.text
        assert ("Zoomed look" in run.text) == zoom and "Edge-on look" not in run.text
        runs[name] = read_detections(out)

    def key(r):
        return r["image"], r["class"], round(r["u0"], 2), round(r["v0"], 2), round(r["u1"], 2), round(r["v1"], 2)
    on = {key(r): r for r in runs["on"]}
    assert all(key(r) in on for r in runs["off"])
    before = {key(r) for r in runs["off"]}
    added = [r for k, r in on.items() if k not in before]
    assert added, "the zoomed look added nothing: the test shows nothing"
    assert all(r["score"] >= DEFAULT_CONFIDENCE for r in added)
    width = scene["image_width"]
    fronts = front_faces(scene)
    off_sign = [(r["image"], r["class"], [round(r[k]) for k in ("u0", "v0", "u1", "v1")]) for r in added
                if not on_a_sign(r, fronts[r["image"]], width)]
    assert len(off_sign) <= (1 - MIN_ON_SIGN_SHARE) * len(added), f"added boxes on no sign: {off_sign}"
