"""The scene generator's panoramas rendered by several processes (``--jobs``) are the files
one process writes: each panorama draws from its own random stream."""
import json
import os

from devtools.scenegen import generate_scene


def _files(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, files in os.walk(folder) for f in files)


def test_two_jobs_write_the_same_scene_as_one(tmp_path):
    one, two = str(tmp_path / "one"), str(tmp_path / "two")
    for out, jobs in ((one, 1), (two, 2)):
        generate_scene("tiny", 5, out, lidar=False, pano_width=512, jobs=jobs)
    assert _files(one) == _files(two)
    images = [f for f in _files(one) if f.startswith("images" + os.sep)]
    assert len(images) >= 8
    for name in _files(one):
        if name != "scene.json":
            with open(os.path.join(one, name), "rb") as a, open(os.path.join(two, name), "rb") as b:
                assert a.read() == b.read(), name
    with open(os.path.join(one, "scene.json")) as a, open(os.path.join(two, "scene.json")) as b:
        meta_one, meta_two = json.load(a), json.load(b)
    meta_one.pop("timings_s", None), meta_two.pop("timings_s", None)
    assert meta_one == meta_two
    assert [m["image"] for m in meta_one["images"]] == sorted(m["image"] for m in meta_one["images"])
    assert sum(len(m["signs"]) for m in meta_one["images"]) > 0
