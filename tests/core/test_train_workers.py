"""devtools.train: the batches drawn in worker processes (``--workers``, what keeps a GPU fed)
and the data mix without the GTSDB frames a device machine did not get.

Training needs torch (devtools/train/requirements.txt), which the plugin's own setup does not
install: these tests run where it is installed and are skipped elsewhere.
"""
import numpy as np
import pytest

torch = pytest.importorskip("torch")

from devtools.train import train as T  # noqa: E402,N812
from devtools.train.data import CLASSES, Sample  # noqa: E402

CROP_PX = 64


class DrawnMix:
    """The part of ``DataMix`` a worker uses: crops drawn from its ``rng``, one box each, and
    the scenes it is told of (loaded only once the main process has cut them)."""
    crop_px = CROP_PX

    def __init__(self):
        self.rng = np.random.default_rng(0)
        self.scans = []

    def add_scenes(self, folders, cut=True):
        assert cut is False          # a worker never cuts views: the main process does
        self.scans.append(list(folders))

    def sample(self):
        image = self.rng.integers(0, 256, (CROP_PX, CROP_PX, 3), dtype=np.uint8)
        x0, y0 = self.rng.integers(0, CROP_PX // 2, 2)
        box = np.array([[x0, y0, x0 + 16, y0 + 16]], np.float32)
        return Sample(image, box, np.array([int(self.rng.integers(len(CLASSES)))]))


def test_image_bytes_make_the_same_batch_as_floats():
    mix = DrawnMix()
    samples = [mix.sample() for _ in range(3)]
    x_float, targets_float = T.batch_tensors(samples, CROP_PX, len(CLASSES))
    x_bytes, targets_bytes = T.batch_tensors(samples, CROP_PX, len(CLASSES), as_uint8=True)
    assert x_bytes.dtype == torch.uint8 and x_float.dtype == torch.float32
    torch.testing.assert_close(T.to_unit(x_bytes), x_float)
    assert T.to_unit(x_float) is x_float
    for a, b in zip(targets_float, targets_bytes):
        torch.testing.assert_close(a, b)
    # RGB: the first channel is the BGR image's last
    np.testing.assert_array_equal(x_bytes[0, 0].numpy(), samples[0].image[..., 2])


def test_each_worker_draws_its_own_stream_and_a_resumed_run_another():
    mix = DrawnMix()
    loader = T.batch_loader(mix, ["scene-a"], 4, seed=5, first_step=0, workers=2, pin=False)
    first = [next(loader)[0] for _ in range(4)]        # the workers take turns
    assert first[0].shape == (4, 3, CROP_PX, CROP_PX) and first[0].dtype == torch.uint8
    assert not torch.equal(first[0], first[1])          # worker 0's first batch and worker 1's
    again = T.batch_loader(DrawnMix(), ["scene-a"], 4, seed=5, first_step=0, workers=2, pin=False)
    assert all(torch.equal(a, next(again)[0]) for a in first)   # the same seed, the same batches
    resumed = T.batch_loader(DrawnMix(), ["scene-a"], 4, seed=5, first_step=100, workers=2, pin=False)
    assert not torch.equal(first[0], next(resumed)[0])
    # in this process, without workers, the stream is seeded the same way as worker 0's
    stream = iter(T.BatchStream(DrawnMix(), ["scene-a"], 4, seed=5, first_step=0))
    assert torch.equal(next(stream)[0], first[0])


def test_the_mix_leaves_out_missing_frames_and_their_mined_false_alarms(tmp_path, capsys):
    present = [tmp_path / f"{k:05d}.jpg" for k in (0, 2)]
    for path in present:
        path.write_bytes(b"x")
    mix = object.__new__(T.DataMix)
    mix.gtsdb = [(str(tmp_path / f"{k:05d}.jpg"), np.zeros((0, 4)), np.zeros(0)) for k in range(3)]
    mix.hard = [(0, "box a"), (1, "box b"), (2, "box c")]
    mix._drop_missing_frames()
    assert [row[0] for row in mix.gtsdb] == [str(p) for p in present]
    assert mix.hard == [(0, "box a"), (1, "box c")]     # frame 2 is now the second
    assert "1 GTSDB training frames are missing" in capsys.readouterr().out
    nothing = object.__new__(T.DataMix)
    nothing.gtsdb, nothing.hard = [(str(tmp_path / "99999.jpg"), None, None)], []
    with pytest.raises(SystemExit, match="no GTSDB training frame"):
        nothing._drop_missing_frames()


def test_a_worker_reads_the_views_from_their_store_once_the_main_process_has_made_it(tmp_path):
    import cv2

    from devtools.train.data import view_store

    rng = np.random.default_rng(2)
    rows = []
    for k in range(3):
        path = str(tmp_path / f"v{k}.jpg")
        cv2.imwrite(path, rng.integers(0, 256, (32, 48, 3), dtype=np.uint8))
        rows.append((path, np.zeros((0, 4), np.float32), np.zeros(0, np.int64)))
    worker = object.__new__(T.DataMix)
    worker.view_pixels, worker._views_mapped = {}, set()
    worker._scene_views = {"scene": (str(tmp_path), rows)}
    worker._map_views("scene", build=False)              # not made yet: the JPEGs meanwhile
    assert worker.view_pixels == {} and "scene" not in worker._views_mapped
    assert np.array_equal(worker._load(rows[1]).image, cv2.imread(rows[1][0]))
    view_store(str(tmp_path), [row[0] for row in rows])  # the main process makes it
    worker._map_views("scene", build=False)
    assert set(worker.view_pixels) == {row[0] for row in rows}
    for row in rows:
        image = worker._load(row).image
        assert np.array_equal(image, cv2.imread(row[0])) and image.flags.writeable
