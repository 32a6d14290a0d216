"""The bundled sign-code classifier (models/signcodes.onnx) behind the bundled detector, through
qgis_process with the default parameters: on the generated panoramas of scenes never
trained on (preset tiny; the classifier trains on seeds from 100 up), the speed limit 50 of
seed 23 comes out as DE:274[50] and the stop sign of seed 8 as DE:206. (Seed 23's stop sign
is 6-14 px wide in every panorama, too narrow for a sure reading of its code: seed 8's is
seen at 22 and 27 px.)

Each sign's detections (its own class, IoU >= 0.5 with its visible or whole box in a
panorama that sees its front) are put to the vote refine makes (core.signcodes.vote,
weight = detection score x the crop's side across the box's narrower side), which the code
must win, read in at least half of the views. Without the bundled classifier the test is
skipped, and fails under CI=true.
"""
import os

import pytest
from helpers.scenes import render_scene, scene_inputs, seam_iou
from osgeo import ogr

from devtools import REPO_ROOT

BUNDLED_DETECTOR = os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx")
BUNDLED_CLASSIFIER = os.path.join(REPO_ROOT, "models", "signcodes.onnx")
#: (class, variant): (the tiny scene's seed, the code expected)
EXPECTED = {("prohibitory", "50"): (23, "DE:274[50]"), ("stop", "stop"): (8, "DE:206")}


def require_bundled():
    for path in (BUNDLED_DETECTOR, BUNDLED_CLASSIFIER):
        if not os.path.isfile(path):
            reason = "no bundled model {}".format(path)
            if os.environ.get("CI", "").lower() == "true":
                pytest.fail("CI=true but {}: CI must test the bundled sign-code classifier".format(reason),
                            pytrace=False)
            pytest.skip(reason)


@pytest.fixture(scope="module")
def run(qgis_process, tmp_path_factory):
    """``run(seed)``: scene tiny/seed (panoramas, no cloud), its stations, and detectsigns with
    every default; each seed run once."""
    import json

    require_bundled()
    done = {}

    def run_seed(seed):
        if seed not in done:
            work = tmp_path_factory.mktemp("codes_bundled_{}".format(seed))
            scene_dir = str(work / "scene")
            render_scene(scene_dir, "tiny", seed, "--no-lidar", "--no-masks")
            with open(os.path.join(scene_dir, "scene.json")) as f:
                scene = json.load(f)
            stations = str(work / "stations.gpkg")
            imported = qgis_process.run("roadsigns:importtrajectory", OUTPUT=stations,
                                        **scene_inputs(scene_dir, scene))
            assert imported.returncode == 0, imported.text
            out = str(work / "detections.gpkg")
            detected = qgis_process.run("roadsigns:detectsigns", STATIONS=stations, OUTPUT=out)  # bundled models
            assert detected.returncode == 0, detected.text
            dataset = ogr.Open(out)
            rows = [{k: f[k] for k in f.keys()} for f in dataset.GetLayer(0)]
            dataset = None
            done[seed] = (scene, rows, detected.text)
        return done[seed]

    return run_seed


@pytest.mark.parametrize("variant", sorted(EXPECTED), ids=lambda v: v[0])
def test_bundled_classifier_reads_the_generated_signs(run, variant):
    from roadsigns.core.signcodes import legible_side_px, vote

    seed, expected = EXPECTED[variant]
    scene, rows, text = run(seed)
    assert "signcodes.onnx" in text
    width = scene["image_width"]
    signs = [s for s in scene["signs"] if (s["class"], s["variant"]) == variant]
    assert signs, "the scene has no {} sign".format(variant)
    views = []
    for meta in scene["images"]:
        for seen in meta["signs"]:
            if seen["sign_id"] not in {s["sign_id"] for s in signs} or seen["facing"] != "front" \
                    or not seen.get("visible_box"):
                continue
            for d in rows:
                box = [d["u0"], d["v0"], d["u1"], d["v1"]]
                if d["image"] == meta["image"] and d["class"] == variant[0] and max(
                        seam_iou(box, seen["visible_box"], width), seam_iou(box, seen["box"], width)) >= 0.5:
                    side = legible_side_px(box, d["width"], d["height"])
                    views.append((d["code"], d["code_score"], d["score"] * side, meta["image"]))
    assert views, "the bundled detector found no {} sign".format(variant)
    code, share, n = vote([v[0] for v in views], [v[1] for v in views], [v[2] for v in views])
    assert code == expected, views
    assert n >= len(views) / 2, views  # most views read it
    print("\n{}: {} of {} views read {} (share {:.2f})".format(variant, n, len(views), code, share))
