"""The scene generator's truth for poles and faded signs (``reference_poles.csv``, the
``faded`` column of ``reference_signs.csv``) against its own cloud."""
import csv
import json
import os

import laspy
import numpy as np
import pytest

from devtools.scenegen.textures import VARIANT_CODES
from roadsigns.core.evaluate import read_reference_csv

KINDS = {"sign_pole", "light_pole", "gantry", "other"}


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    from devtools.scenegen import generate_scene

    folder = str(tmp_path_factory.mktemp("truth"))
    paths = generate_scene("tiny", seed=6, out_dir=folder, panoramas=False, masks=False)
    las = laspy.read(paths["cloud"])
    cloud = {"xyz": np.column_stack([las.x, las.y, las.z]), "cls": np.asarray(las.classification),
             "intensity": np.asarray(las.intensity, float)}
    with open(paths["scene_json"]) as f:
        meta = json.load(f)
    return folder, paths, cloud, meta


def test_every_sign_is_carried_by_its_pole_or_gantry(scene):
    folder, paths, _, meta = scene
    poles = _rows(paths["reference_poles"])
    assert list(poles[0]) == ["pole_id", "kind", "x", "y", "z_foot", "height", "diameter", "structure_id",
                              "sign_ids"]
    assert {p["kind"] for p in poles} <= KINDS and {"sign_pole", "light_pole", "gantry"} <= {p["kind"] for p in poles}
    carriers = {}
    for p in poles:
        for sid in p["sign_ids"].split():
            carriers.setdefault(int(sid), []).append(p)
    mounts = {s["sign_id"]: s["mount"] for s in meta["signs"]}
    assert set(carriers) == set(mounts)
    for sid, held_by in carriers.items():
        if mounts[sid] == "gantry":
            assert len(held_by) == 2 and {p["kind"] for p in held_by} == {"gantry"}
            assert held_by[0]["structure_id"] == held_by[1]["structure_id"]
        else:
            assert len(held_by) == 1
            assert held_by[0]["kind"] == ("light_pole" if mounts[sid] == "lamp_post" else "sign_pole")


def test_pole_feet_and_radii_match_the_cloud(scene):
    _, paths, cloud, _ = scene
    xyz, cls = cloud["xyz"], cloud["cls"]
    ground = xyz[cls == 2]
    supports = xyz[np.isin(cls, (65, 66))]
    checked = 0
    for p in _rows(paths["reference_poles"]):
        foot = np.array([float(p["x"]), float(p["y"]), float(p["z_foot"])])
        r = float(p["diameter"]) / 2
        g = ground[np.hypot(*(ground[:, :2] - foot[:2]).T) < 0.4]
        if len(g) >= 5:
            assert abs(np.median(g[:, 2]) - foot[2]) < 0.05, p
        band = supports[(np.abs(supports[:, 2] - foot[2] - 1.0) < 0.5)
                        & (np.hypot(*(supports[:, :2] - foot[:2]).T) < r + 0.1)]
        if len(band) >= 10:
            d = np.hypot(*(band[:, :2] - foot[:2]).T)
            assert abs(np.median(d) - r) < 0.02, (p, np.median(d))
            if p["kind"] != "gantry":          # a gantry's beam sits on its posts, higher
                top = supports[np.hypot(*(supports[:, :2] - foot[:2]).T) < r + 0.02][:, 2].max()
                assert top <= foot[2] + float(p["height"]) + 0.05
            checked += 1
    assert checked >= 5


def test_faded_and_code_columns_last_and_faded_faces_are_dull(scene):
    _, paths, cloud, meta = scene
    rows = _rows(paths["reference"])
    assert list(rows[0])[-2:] == ["faded", "code"] and {r["faded"] for r in rows} <= {"0", "1"}
    variant = {s["sign_id"]: (s["class"], s["variant"]) for s in meta["signs"]}
    assert [r["code"] for r in rows] == [VARIANT_CODES[variant[int(r["sign_id"])]] for r in rows]
    assert len(read_reference_csv(paths["reference"]).ids) == len(rows)     # old readers still work
    faded = {int(r["sign_id"]) for r in rows if r["faded"] == "1"}
    assert faded == {s["sign_id"] for s in meta["signs"] if s["faded"]} and faded
    xyz, cls, inten = cloud["xyz"], cloud["cls"], cloud["intensity"]
    panel = cls == 64
    for s in meta["signs"]:
        if s["facing"] != "oncoming" or s["mount"] == "gantry":
            continue
        on = panel & (np.linalg.norm(xyz - np.array(s["centre"]), axis=1) < 0.25)
        if on.sum() < 20:
            continue
        level = np.median(inten[on]) / 65535
        assert (level < 0.3) if s["sign_id"] in faded else (level > 0.7), (s["sign_id"], level)


def test_reference_poles_are_deterministic(scene, tmp_path):
    from devtools.scenegen import generate_scene

    _, paths, _, _ = scene
    again = generate_scene("tiny", seed=6, out_dir=str(tmp_path), panoramas=False, lidar=False)
    for key in ("reference_poles", "reference"):
        with open(paths[key], "rb") as a, open(again[key], "rb") as b:
            assert a.read() == b.read(), key
    assert os.path.getsize(again["reference_poles"]) > 200
