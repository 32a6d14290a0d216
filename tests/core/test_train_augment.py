"""The training crops' colour jitter and the decoded store of a scene's views
(devtools/train/data.py): the same pixels as the steps one after another, and as the JPEGs."""
import os

import cv2
import numpy as np
import pytest

from devtools.train.data import VIEW_STORE_NAME, colour_jitter, jitter_matrix, view_store


def test_the_jitter_matrix_is_saturation_contrast_brightness_and_gain_in_turn():
    rng = np.random.default_rng(5)
    pixels = rng.uniform(0, 255, (40, 30, 3)).astype(np.float32)
    for saturation, contrast, brightness, gain in [(0.5, 0.65, -40.0, (0.88, 1.0, 1.12)),
                                                   (1.4, 1.35, 40.0, (1.12, 0.9, 0.95)),
                                                   (1.0, 1.0, 0.0, (1.0, 1.0, 1.0))]:
        grey = pixels.mean(2, keepdims=True)
        expected = grey + (pixels - grey) * saturation
        expected = (expected - 128) * contrast + 128 + brightness
        expected = expected * np.asarray(gain, np.float32)
        got = cv2.transform(pixels, jitter_matrix(saturation, contrast, brightness, gain))
        assert np.abs(got - expected).max() < 1e-3


class _Draws:
    """A stand-in for numpy's Generator giving ``colour_jitter`` the draws a test wants."""

    def __init__(self, randoms, uniform):
        self.randoms, self.uniform_value = list(randoms), uniform

    def random(self):
        return self.randoms.pop(0)

    def uniform(self, lo, hi, size=None):
        return self.uniform_value if size is None else np.full(size, self.uniform_value)

    def integers(self, hi):
        return 12345


def test_the_noise_has_the_drawn_sigma_in_every_channel():
    flat = np.full((200, 160, 3), 128, np.uint8)
    # no colour matrix (0.9 >= 0.8), no blur (0.9 >= 0.25), noise (0.1 < 0.3) of sigma 6
    out = colour_jitter(flat, _Draws([0.9, 0.9, 0.1], 6.0)).astype(np.float64)
    for c in range(3):
        assert abs(out[..., c].std() - 6.0) < 0.3
        assert abs(out[..., c].mean() - 127.5) < 0.3      # the bytes are truncated: half a level down


def test_a_seed_gives_the_same_crop_and_another_seed_another():
    image = np.random.default_rng(0).integers(0, 256, (96, 128, 3), dtype=np.uint8)
    outs = [colour_jitter(image, np.random.default_rng(seed)) for seed in (1, 1, 2)]
    assert outs[0].dtype == np.uint8 and outs[0].shape == image.shape
    assert np.array_equal(outs[0], outs[1])
    assert not np.array_equal(outs[0], outs[2])
    unchanged = colour_jitter(image, _Draws([0.9, 0.9, 0.9], 1.0))             # no step drawn
    assert np.array_equal(unchanged, image) and unchanged is not image


def _write_views(folder, sizes):
    rng = np.random.default_rng(1)
    paths = []
    for k, (h, w) in enumerate(sizes):
        path = os.path.join(folder, f"v{k}.jpg")
        cv2.imwrite(path, rng.integers(0, 256, (h, w, 3), dtype=np.uint8), [cv2.IMWRITE_JPEG_QUALITY, 93])
        paths.append(path)
    return paths


def test_the_view_store_holds_the_decoded_jpegs(tmp_path):
    paths = _write_views(str(tmp_path), [(48, 64)] * 4)
    assert view_store(str(tmp_path), paths, build=False) is None          # a worker does not make it
    store = view_store(str(tmp_path), paths)
    assert store.shape == (4, 48, 64, 3) and store.dtype == np.uint8
    for k, path in enumerate(paths):
        assert np.array_equal(store[k], cv2.imread(path, cv2.IMREAD_COLOR))
    assert sorted(os.listdir(tmp_path)) == sorted([os.path.basename(p) for p in paths] + [VIEW_STORE_NAME])
    again = view_store(str(tmp_path), paths, build=False)                   # found whole by another process
    assert np.array_equal(np.asarray(again), np.asarray(store))
    assert view_store(str(tmp_path), paths[:3]) is None                      # not these rows' store


def test_views_of_two_sizes_or_a_failed_write_get_no_store_and_leave_nothing(tmp_path, monkeypatch):
    paths = _write_views(str(tmp_path), [(48, 64), (48, 64), (40, 64)])
    assert view_store(str(tmp_path), paths) is None
    assert sorted(os.listdir(tmp_path)) == ["v0.jpg", "v1.jpg", "v2.jpg"]

    def unreadable(path, flags=None):
        raise OSError("disk gone")

    good = paths[:2]
    first = cv2.imread(good[0])
    monkeypatch.setattr(cv2, "imread", lambda path, flags=None: first if path == good[0] else unreadable(path))
    with pytest.raises(OSError, match="disk gone"):
        view_store(str(tmp_path), good)
    assert sorted(os.listdir(tmp_path)) == ["v0.jpg", "v1.jpg", "v2.jpg"]


def test_a_scene_cut_in_two_processes_gives_the_views_one_gives(tmp_path):
    from devtools.scenegen import generate_scene
    from devtools.train.data import scene_view_samples

    scene = str(tmp_path / "scene")
    generate_scene("tiny", 6, scene, lidar=False, pano_width=1024)
    cut = {}
    for jobs in (1, 2):
        folder = str(tmp_path / f"views-{jobs}")
        rows = scene_view_samples(scene, folder, rng=np.random.default_rng(4), jobs=jobs)
        cut[jobs] = (folder, rows)
    (one, rows_one), (two, rows_two) = cut[1], cut[2]
    assert len(rows_one) >= 8 and sum(len(r[1]) for r in rows_one) > 0
    assert [os.path.basename(r[0]) for r in rows_one] == [os.path.basename(r[0]) for r in rows_two]
    for a, b in zip(rows_one, rows_two):
        assert all(np.array_equal(x, y) for x, y in zip(a[1:], b[1:]))
        with open(a[0], "rb") as fa, open(b[0], "rb") as fb:
            assert fa.read() == fb.read()
    assert np.array_equal(np.load(os.path.join(one, VIEW_STORE_NAME)), np.load(os.path.join(two, VIEW_STORE_NAME)))
    unstored = scene_view_samples(scene, str(tmp_path / "views-val"), rng=np.random.default_rng(4), store=False)
    assert len(unstored) == len(rows_one) and not os.path.exists(str(tmp_path / "views-val" / VIEW_STORE_NAME))
    # the index is the cache: a second call reads it and cuts nothing
    again = scene_view_samples(scene, one, rng=np.random.default_rng(99), jobs=2)
    assert [r[0] for r in again] == [r[0] for r in rows_one]
