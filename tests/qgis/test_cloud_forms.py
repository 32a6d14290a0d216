"""The cloud stages through qgis_process on the point cloud as users receive it: one LAZ, a
folder of LAZ tiles, a virtual point cloud (.vpc) of them. Every form gives the result of the
single file; the ground filter writes tiles and a .vpc the next stages read; bad forms are
refused naming the files."""
import os
import shutil

import laspy
import numpy as np
import pytest
from helpers.cloudtiles import classes_by_point, split_into_tiles, write_vpc
from helpers.scenes import ground_and_oracle
from osgeo import ogr


def rows(path):
    dataset = ogr.Open(path)
    layer = dataset.GetLayer(0)
    out = []
    for feature in layer:
        out.append({k: feature[k] for k in feature.keys()})
    return out


@pytest.fixture(scope="module")
def forms(qgis_process, scene_tiny, scene_tiny_stations, tmp_path_factory):
    """The tiny scene's ground-classified cloud as one LAZ, as 12 m tiles in a folder and as a
    .vpc of those tiles; the oracle detections; the raw cloud as tiles too."""
    scene_dir, scene = scene_tiny
    work = tmp_path_factory.mktemp("forms")
    ground, detections = ground_and_oracle(qgis_process, scene_dir, scene_tiny_stations, work)
    tiles = split_into_tiles(ground, str(work / "tiles"), size_m=12.0)
    vpc = write_vpc(str(work / "ground.vpc"), tiles)
    raw_tiles = split_into_tiles(os.path.join(scene_dir, "cloud.laz"), str(work / "raw_tiles"), size_m=15.0)
    return dict(work=work, ground=ground, folder=str(work / "tiles"), tiles=tiles, vpc=vpc,
                detections=detections, stations=scene_tiny_stations, scene_dir=scene_dir,
                raw_folder=str(work / "raw_tiles"), raw_tiles=raw_tiles)


def project(qgis_process, forms, cloud, name):
    out = str(forms["work"] / name)
    run = qgis_process.run("roadsigns:projectdetections", DETECTIONS=forms["detections"], POINT_CLOUD=cloud,
                           MAX_RANGE=30, OUTPUT=out)
    assert run.returncode == 0, run.text
    return rows(out)


@pytest.fixture(scope="module")
def candidates(qgis_process, forms):
    """The candidates projected into the single file: (path, rows)."""
    layer = project(qgis_process, forms, forms["ground"], "cand_file.gpkg")
    return str(forms["work"] / "cand_file.gpkg"), layer


def close_counts(a, b):
    """Point counts of one surface found in the same points read in another order (RANSAC
    draws its samples by position in the list): within a point or two."""
    return abs(a - b) <= max(2, 0.005 * max(a, b))


def same_candidates(a, b):
    """The same candidates, up to the order the points come in (tile by tile, not file order)."""
    assert len(a) == len(b) > 10
    assert [r["status"] for r in a] == [r["status"] for r in b]
    assert sum(r["status"] == "ok" for r in a) >= 0.9 * len(a)
    for ra, rb in zip(a, b):
        assert ra["det_id"] == rb["det_id"] and close_counts(ra["n_points"], rb["n_points"])
        if ra["status"] == "ok":
            pa = np.array([ra["cand_x"], ra["cand_y"], ra["cand_z"]])
            pb = np.array([rb["cand_x"], rb["cand_y"], rb["cand_z"]])
            assert np.linalg.norm(pa - pb) < 2e-3, (ra["det_id"], pa, pb)


def test_projection_on_tiles_and_vpc_equals_the_file(qgis_process, forms, candidates):
    assert len(forms["tiles"]) >= 4
    single = candidates[1]
    same_candidates(single, project(qgis_process, forms, forms["folder"], "cand_folder.gpkg"))
    same_candidates(single, project(qgis_process, forms, forms["vpc"], "cand_vpc.gpkg"))


def test_refinement_and_sign_points_from_a_vpc(qgis_process, forms, candidates):
    out = {}
    for name, cloud in (("file", forms["ground"]), ("vpc", forms["vpc"])):
        signs, points = str(forms["work"] / f"signs_{name}.gpkg"), str(forms["work"] / f"points_{name}.laz")
        run = qgis_process.run("roadsigns:refinesigns", CANDIDATES=candidates[0], POINT_CLOUD=cloud, MERGE_RADIUS=1.0,
                               OUTPUT=signs, SIGN_POINTS=points)
        assert run.returncode == 0, run.text
        las = laspy.read(points)
        out[name] = (rows(signs), np.sort(np.round(np.column_stack([las.x, las.y, las.z]) * 1000).astype(np.int64),
                                          axis=0))
    (signs_a, pts_a), (signs_b, pts_b) = out["file"], out["vpc"]
    assert len(signs_a) == len(signs_b) > 3
    for a, b in zip(signs_a, signs_b):
        assert a["class"] == b["class"] and close_counts(a["n_points"], b["n_points"])
        assert abs(a["x"] - b["x"]) < 2e-3 and abs(a["y"] - b["y"]) < 2e-3 and abs(a["z"] - b["z"]) < 2e-3
    assert len(pts_a) == sum(s["n_points"] for s in signs_a) > 0
    assert len(pts_b) == sum(s["n_points"] for s in signs_b)
    # the points copied out of the tiles are points of the panels found in the file
    set_a, set_b = ({tuple(r) for r in p.tolist()} for p in (pts_a, pts_b))  # (points 1 mm apart are one)
    assert len(set_b & set_a) > 0.99 * len(set_b)


def test_signs_in_the_cloud_from_a_folder_of_tiles(qgis_process, forms):
    found = {}
    for name, cloud in (("file", forms["ground"]), ("folder", forms["folder"])):
        out = str(forms["work"] / f"cloudsigns_{name}.gpkg")
        run = qgis_process.run("roadsigns:findsignsincloud", POINT_CLOUD=cloud, STATIONS=forms["stations"],
                               OUTPUT=out, POLES=str(forms["work"] / f"poles_{name}.gpkg"))
        assert run.returncode == 0, run.text
        found[name] = rows(out)
    a, b = found["file"], found["folder"]
    assert len(a) == len(b) > 3
    for ra, rb in zip(a, b):
        assert ra["condition"] == rb["condition"] and ra["support"] == rb["support"]
        assert np.hypot(ra["x"] - rb["x"], ra["y"] - rb["y"]) < 0.01 and abs(ra["z"] - rb["z"]) < 0.01


def test_ground_filter_writes_tiles_and_a_vpc_the_next_stage_reads(qgis_process, forms):
    work = forms["work"]
    common = dict(CROP=forms["stations"], CROP_BUFFER=25, RESET_CLASSES=True, ENGINE=2)
    one = str(work / "ground_one.laz")
    run = qgis_process.run("roadsigns:groundfilter", INPUT=forms["raw_folder"], OUTPUT=one, **common)
    assert run.returncode == 0, run.text
    run = qgis_process.run("roadsigns:groundfilter", INPUT=forms["raw_folder"], OUTPUT_TILES=True,
                           OUTPUT=str(work / "ground_tiles.laz"), **common)
    assert run.returncode == 0, run.text
    vpc = run.json["results"]["OUTPUT"]
    assert vpc == str(work / "ground_tiles" / "ground_tiles.vpc")
    written = sorted(f for f in os.listdir(work / "ground_tiles") if f.endswith(".laz"))
    assert written and set(written) <= {os.path.basename(t) for t in forms["raw_tiles"]}
    # the classes of the tiles are those of the one file
    ka, ca = classes_by_point([one])
    kb, cb = classes_by_point([str(work / "ground_tiles" / f) for f in written])
    np.testing.assert_array_equal(ka, kb)
    assert (ca == cb).mean() >= 0.999
    # the .vpc output is a cloud the projection takes
    same_candidates(project(qgis_process, forms, one, "cand_one.gpkg"),
                    project(qgis_process, forms, vpc, "cand_tiles_vpc.gpkg"))
    assert not [f for f in os.listdir(work) if f.startswith(".roadsigns")]


def test_bad_cloud_forms_are_named(qgis_process, forms, candidates, tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    run = qgis_process.run("roadsigns:projectdetections", DETECTIONS=forms["detections"], POINT_CLOUD=str(empty),
                           OUTPUT=str(tmp_path / "c.gpkg"))
    assert run.returncode != 0 and "holds no LAS or LAZ file" in run.text and str(empty) in run.text
    mixed = tmp_path / "mixed"
    paths = split_into_tiles(forms["ground"], str(mixed), size_m=12.0, crs_epsg=25832)
    run = qgis_process.run("roadsigns:findsignsincloud", POINT_CLOUD=str(mixed), STATIONS=forms["stations"],
                           OUTPUT=str(tmp_path / "s.gpkg"), POLES=str(tmp_path / "p.gpkg"))
    assert run.returncode != 0 and "different CRSs" in run.text
    assert paths[0] in run.text and paths[-1] in run.text and "EPSG:25832" in run.text
    vpc = tmp_path / "gone.vpc"
    shutil.copy(forms["vpc"], vpc)  # its hrefs are relative: the tiles are not beside the copy
    run = qgis_process.run("roadsigns:refinesigns", CANDIDATES=candidates[0],
                           POINT_CLOUD=str(vpc), OUTPUT=str(tmp_path / "r.gpkg"))
    assert run.returncode != 0 and "which does not exist" in run.text and str(vpc) in run.text
    assert not (tmp_path / "c.gpkg").exists() and not (tmp_path / "s.gpkg").exists()
