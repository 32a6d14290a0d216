"""projectdetections, refinesigns and evaluate through qgis_process on a generated scene,
with detections made from the scene's true boxes (devtools/oracle.py) so that the cloud
stages are measured apart from the detector."""
import os

import laspy
import numpy as np
import pytest
from helpers.scenes import ground_and_oracle
from osgeo import ogr

# the goals of the issue (Zhang 2023: P 0.978 / R 0.947; Balado 2020: 97.5 % within 0.5 m)
# the panel's size: round signs come in sizes 150-180 mm apart (420, 600 and 750 mm across in
# Germany), so a size within half a step tells the size apart, and few miss it by a step
GOALS = dict(PRECISION=0.97, RECALL=0.95, MEDIAN_ERROR=0.05, P95_ERROR=0.20,
             MEDIAN_HEIGHT_ERROR=0.05, MEDIAN_AZIMUTH_ERROR=5.0, CLASS_ACCURACY=0.97,
             MEDIAN_SIZE_ERROR=0.075, P95_SIZE_ERROR=0.15)


def rows(path):
    dataset = ogr.Open(path)
    layer = dataset.GetLayer(0)
    out = []
    for feature in layer:
        row = {k: feature[k] for k in feature.keys()}
        g = feature.GetGeometryRef()
        row["_geometry"] = None if g is None else ogr.GeometryTypeToName(g.GetGeometryType())
        out.append(row)
    return out


@pytest.fixture(scope="module")
def chain(qgis_process, scene_tiny, scene_tiny_stations, tmp_path_factory):
    scene_dir, scene = scene_tiny
    work = tmp_path_factory.mktemp("chain")
    stations = scene_tiny_stations
    ground, detections = ground_and_oracle(qgis_process, scene_dir, stations, work)
    return dict(work=work, stations=stations, ground=ground, detections=detections, scene=scene,
                scene_dir=scene_dir)


def project(qgis_process, chain, cloud, name):
    out = str(chain["work"] / name)
    run = qgis_process.run("roadsigns:projectdetections", DETECTIONS=chain["detections"],
                           POINT_CLOUD=cloud, MAX_RANGE=30, OUTPUT=out)
    assert run.returncode == 0, run.text
    return out


def refine(qgis_process, chain, candidates, cloud, name, **extra):
    out = str(chain["work"] / name)
    run = qgis_process.run("roadsigns:refinesigns", CANDIDATES=candidates, POINT_CLOUD=cloud,
                           MERGE_RADIUS=1.0, OUTPUT=out, **extra)
    assert run.returncode == 0, run.text
    return out, run


def evaluate(qgis_process, chain, signs, reference=None):
    run = qgis_process.run("roadsigns:evaluate", SIGNS=signs,
                           REFERENCE=reference or os.path.join(chain["scene_dir"], "reference_signs.csv"),
                           MATCH_RADIUS=1.0, OUTPUT_REPORT=str(chain["work"] / "evaluation.html"))
    assert run.returncode == 0, run.text
    return run.json["results"]


def test_candidates_lie_on_their_panels(qgis_process, chain):
    candidates = rows(project(qgis_process, chain, chain["ground"], "candidates.gpkg"))
    assert len(candidates) == len(rows(chain["detections"]))
    ok = [c for c in candidates if c["status"] == "ok"]
    assert len(ok) >= 0.9 * len(candidates)
    assert all(c["_geometry"] == "3D Point" for c in ok)
    panels = chain["scene"]["signs"]
    for c in ok:
        p = np.array([c["cand_x"], c["cand_y"], c["cand_z"]])
        # the nearest true panel of the detection's class: on its plane, inside its outline
        best = min((s for s in panels if s["class"] == c["class"]),
                   key=lambda s: np.linalg.norm(p - np.array(s["centre"])))
        normal = np.array(best["normal"])
        assert abs(np.dot(p - np.array(best["centre"]), normal)) < 0.05
        offset = p - np.array(best["centre"])
        in_plane = offset - np.dot(offset, normal) * normal
        assert np.linalg.norm(in_plane) < max(best["width"], best["panel_height"]) / 2 + 0.1


def test_sign_layer_meets_the_goals(qgis_process, chain):
    candidates = project(qgis_process, chain, chain["ground"], "candidates.gpkg")
    points = str(chain["work"] / "sign_points.laz")
    review = str(chain["work"] / "review" / "review.html")
    signs, run = refine(qgis_process, chain, candidates, chain["ground"], "signs.gpkg",
                        OUTLINES=str(chain["work"] / "outlines.gpkg"), SIGN_POINTS=points,
                        IMAGES=os.path.join(chain["scene_dir"], "images"), REVIEW_REPORT=review)
    layer = rows(signs)
    fields = ["sign_id", "class", "score", "code", "code_name", "code_score", "code_views", "code_check",
              "height", "bottom_height", "width", "panel_height", "azimuth",
              "n_views", "n_points", "source_images", "best_image", "mean_intensity", "planarity",
              "position_source", "x", "y", "z", "chip"]
    assert list(k for k in layer[0] if not k.startswith("_")) == fields
    check_review(chain, signs, layer, review)
    assert all(s["_geometry"] == "3D Point" and s["position_source"] == "lidar" for s in layer)
    assert all(s["best_image"] in s["source_images"].split(";") for s in layer)
    shared = [s for s in chain["scene"]["signs"] if s["mount"] == "shared_pole"]
    assert len(shared) == 2  # two panels on one pole, both must be found apart
    results = evaluate(qgis_process, chain, signs)
    for name, goal in GOALS.items():
        better = results[name] >= goal if name in ("PRECISION", "RECALL", "CLASS_ACCURACY") else results[name] <= goal
        assert better, (name, results[name], goal)
    outlines = rows(str(chain["work"] / "outlines.gpkg"))
    assert len(outlines) == len(layer) and all(o["_geometry"] == "3D Polygon" for o in outlines)
    sign_points = laspy.read(points)
    assert len(sign_points) == sum(s["n_points"] for s in layer) > 0
    assert set(np.unique(sign_points.classification)) <= {1}  # the panels, not the ground


def check_review(chain, signs_path, layer, review_path):
    """Each sign's chip, linked by a relative path, shows its panel; the report shows them all;
    the style file sits beside the layer."""
    import cv2
    folder = os.path.dirname(signs_path)
    html = open(review_path, encoding="utf-8").read()
    for sign in layer:
        assert sign["chip"] and not os.path.isabs(sign["chip"])
        chip = cv2.imread(os.path.join(folder, sign["chip"]))
        assert chip is not None and chip.shape[:2] == (256, 256)
        link = os.path.relpath(os.path.join(folder, sign["chip"]), os.path.dirname(review_path))
        assert 'src="{}"'.format(link) in html
    assert html.count('class="sign"') == len(layer)
    qml = os.path.splitext(signs_path)[0] + ".qml"
    style = open(qml).read()
    assert "categorizedSymbol" in style and all(c in style for c in ("warning", "stop", "yield"))
    assert "height" in style


def test_signs_out_of_the_scanners_reach_are_triangulated(qgis_process, chain):
    """A scanner that reaches 4 m from the vehicle: the roadside signs have no points and
    must be placed from their rays (position_source = image), the gantry signs from the cloud."""
    near = str(chain["work"] / "near.laz")
    run = qgis_process.run("roadsigns:groundfilter", INPUT=os.path.join(chain["scene_dir"], "cloud.laz"),
                           CROP=chain["stations"], CROP_BUFFER=4, RESET_CLASSES=True, OUTPUT=near)
    assert run.returncode == 0, run.text
    signs, run = refine(qgis_process, chain, project(qgis_process, chain, near, "cand_near.gpkg"), near,
                        "signs_near.gpkg")
    assert "stations' height" in run.text  # no ground below those signs: the fallback is named
    layer = rows(signs)
    truth = chain["scene"]["signs"]
    placed = [s for s in layer if s["position_source"] == "image"]
    assert len(placed) >= 3
    for s in placed:
        p = np.array([s["x"], s["y"], s["z"]])
        nearest = min(truth, key=lambda t: np.linalg.norm(p - np.array(t["centre"])))
        assert np.linalg.norm(p - np.array(nearest["centre"])) < 0.3
        assert s["class"] == nearest["class"] and s["n_views"] >= 2
    gantry = [s for s in layer if s["position_source"] == "lidar"]
    assert len(gantry) == sum(t["mount"] == "gantry" for t in truth)


def test_cloud_without_ground_class_is_refused(qgis_process, chain):
    out = chain["work"] / "never.gpkg"
    run = qgis_process.run("roadsigns:projectdetections", DETECTIONS=chain["detections"],
                           POINT_CLOUD=_no_ground(chain), MAX_RANGE=30, OUTPUT=str(out))
    assert run.returncode != 0 and "roadsigns:groundfilter" in run.text
    assert not out.exists()


def _no_ground(chain):
    las = laspy.read(chain["ground"])
    las.classification = np.ones(len(las.points), np.uint8)
    path = str(chain["work"] / "no_ground.laz")
    las.write(path)
    return path


def edited_copy(path, copy, sql):
    """A copy of a GeoPackage with one SQL statement applied to it."""
    ogr.GetDriverByName("GPKG").CopyDataSource(ogr.Open(path), copy)
    dataset = ogr.Open(copy, 1)
    dataset.ExecuteSQL(sql)
    dataset = None
    return copy


def test_crs_mismatch_is_refused(qgis_process, chain, tmp_path):
    other = edited_copy(chain["detections"], str(tmp_path / "det_4326.gpkg"),
                        "UPDATE gpkg_geometry_columns SET srs_id = 4326")
    run = qgis_process.run("roadsigns:projectdetections", DETECTIONS=other, POINT_CLOUD=chain["ground"],
                           OUTPUT=str(tmp_path / "c.gpkg"))
    assert run.returncode != 0 and "EPSG:4326" in run.text and "EPSG:32633" in run.text


def test_empty_detections_give_empty_layers(qgis_process, chain, tmp_path):
    empty = edited_copy(chain["detections"], str(tmp_path / "empty.gpkg"), "DELETE FROM detections")
    candidates = str(tmp_path / "c.gpkg")
    run = qgis_process.run("roadsigns:projectdetections", DETECTIONS=empty, POINT_CLOUD=chain["ground"],
                           OUTPUT=candidates)
    assert run.returncode == 0, run.text
    assert "No detections" in run.text and rows(candidates) == []
    signs = str(tmp_path / "s.gpkg")
    run = qgis_process.run("roadsigns:refinesigns", CANDIDATES=candidates, POINT_CLOUD=chain["ground"],
                           OUTPUT=signs)
    assert run.returncode == 0, run.text
    assert "No candidates" in run.text and rows(signs) == []


def test_a_sign_left_with_its_farthest_view_is_dropped_unless_the_view_check_is_off(qgis_process, chain, tmp_path):
    """The sign with the most views keeps only its farthest one: the nearer panoramas that saw
    it saw other signs too, so by default (SINGLE_VIEW_MAX_NEARER_MISSES 2) the lone view is
    a look-alike and dropped, and the log says so; with 0 it is kept, where the sign stands."""
    from roadsigns.core.refine import RefineParams

    info = qgis_process("--json", "help", "roadsigns:refinesigns")
    assert info.returncode == 0, info.text
    parameter = info.json["parameters"]["SINGLE_VIEW_MAX_NEARER_MISSES"]
    assert parameter["default_value"] == RefineParams().single_view_max_nearer_misses == 2

    candidates = rows(project(qgis_process, chain, chain["ground"], "candidates.gpkg"))
    ok = [c for c in candidates if c["status"] == "ok"]
    panels = chain["scene"]["signs"]

    def panel_of(c):
        p = np.array([c["cand_x"], c["cand_y"], c["cand_z"]])
        return min(range(len(panels)), key=lambda k: np.linalg.norm(p - np.array(panels[k]["centre"])))

    views = {}
    for c in ok:
        views.setdefault(panel_of(c), []).append(c)
    sign, its = max(views.items(), key=lambda kv: (len({c["image"] for c in kv[1]}), -kv[0]))
    farthest = max(its, key=lambda c: c["range_m"])
    others = [c["det_id"] for c in its if c["det_id"] != farthest["det_id"]]
    seen_elsewhere = {c["image"] for c in ok if panel_of(c) != sign}
    assert len(others) >= 3 and {c["image"] for c in its} - {farthest["image"]} <= seen_elsewhere
    lone = edited_copy(str(chain["work"] / "candidates.gpkg"), str(tmp_path / "lone.gpkg"),
                       "DELETE FROM candidates WHERE det_id IN ({})".format(",".join(map(str, others))))
    centre = np.array(panels[sign]["centre"])

    def found(layer):
        return [s for s in layer if np.linalg.norm(np.array([s["x"], s["y"], s["z"]]) - centre) < 0.5]

    signs, run = refine(qgis_process, chain, lone, chain["ground"], "lone.gpkg")
    assert found(rows(signs)) == []
    assert "Candidates [{}] dropped: seen in one panorama only ({}".format(farthest["det_id"], farthest["image"]) \
        in run.text and "panoramas nearer to its face" in run.text
    kept, run = refine(qgis_process, chain, lone, chain["ground"], "lone-kept.gpkg", SINGLE_VIEW_MAX_NEARER_MISSES=0)
    assert [s["source_images"] for s in found(rows(kept))] == [farthest["image"]]
    assert len(rows(kept)) == len(rows(signs)) + 1 and "nearer to its face" not in run.text
