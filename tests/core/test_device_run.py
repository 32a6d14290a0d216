"""The packing of a GPU training run into two device calls (devtools/train/device_run.py),
on a small made-up data folder: every frame lands once, each part within a call's bytes."""
import csv
import os
import re
import subprocess

import cv2
import numpy as np
import pytest

from devtools.train import device_run
from devtools.train.data import GTSDB_TRAIN_IDS


def _jpeg(path, value):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    cv2.imwrite(path, np.full((8, 8, 3), value, np.uint8))


@pytest.fixture
def made_up(tmp_path):
    data = tmp_path / "data"
    for name in ("README.md", "sign-codes-de.csv"):
        (data / name).parent.mkdir(parents=True, exist_ok=True)
        (data / name).write_text("x\n")
    (data / "gtsdb-train").mkdir()
    (data / "gtsdb-train" / "gt.txt").write_text("00001.jpg;1;2;30;40;14\n")
    for k in list(GTSDB_TRAIN_IDS) + list(device_run.VAL_FRAMES):
        _jpeg(str(data / "gtsdb-train" / "images" / f"{k:05d}.jpg"), k % 250)
    rows = []
    for track in ("00000", "00001"):
        for n in range(10):
            name = f"stop/{track}_{3 * n:05d}.png"
            img = np.full((30 + n, 30 + n, 3), 40 + n, np.uint8)
            (data / "gtsrb-train" / "train" / "stop").mkdir(parents=True, exist_ok=True)
            cv2.imwrite(str(data / "gtsrb-train" / "train" / name), img)
            rows.append({"File": name, "Width": 30 + n, "Height": 30 + n, "Roi.X1": 1, "Roi.Y1": 1,
                         "Roi.X2": 28, "Roi.Y2": 28, "ClassId": 14, "Track": track, "Frame": f"{3 * n:05d}"})
    rows.reverse()  # not in frame order: the packer orders each track itself
    with open(data / "gtsrb-train" / "GT-train.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]), delimiter=";")
        writer.writeheader()
        writer.writerows(rows)
    scenes = tmp_path / "scenes"
    for name in device_run.TINY_SCENES:
        (scenes / name / "images").mkdir(parents=True)
        (scenes / name / "scene.json").write_text("{}")
    wheels = tmp_path / "whl"
    wheels.mkdir()
    for name in device_run.WHEEL_NAMES:
        (wheels / f"{name}-1.0-py3-none-any.whl").write_bytes(b"PK")
    return data, scenes, wheels


def _files(folder):
    return {os.path.relpath(os.path.join(d, f), folder) for d, _, files in os.walk(folder) for f in files}


def test_every_frame_lands_once_every_third_in_part_b_and_the_scripts_are_whole(made_up, tmp_path):
    data, scenes, wheels = made_up
    out = tmp_path / "out"
    packed = device_run.pack(str(out), str(data), str(scenes), str(wheels))
    assert packed["left_out"] == []
    a, b = _files(out / "a"), _files(out / "b")
    in_a = {int(f[-9:-4]) for f in a if f.startswith("images/")}
    in_b = {int(f[-9:-4]) for f in b if f.startswith("shared/data/gtsdb-train/images/")}
    assert in_a | in_b == set(GTSDB_TRAIN_IDS) | set(device_run.VAL_FRAMES)
    assert not in_a & in_b
    assert {k for k in GTSDB_TRAIN_IDS if k % 3 == 0} | set(device_run.VAL_FRAMES) == in_b
    for part, size in (("a", packed["a"]), ("b", packed["b"])):
        assert size == device_run.tree_bytes(str(out / part)) <= packed["budget"]
    assert {f"whl/{n}-1.0-py3-none-any.whl" for n in device_run.WHEEL_NAMES} <= a
    run_sh = (out / "b" / "run.sh").read_text()
    # every @PLACEHOLDER@ filled (`date -d @SECONDS` is the script's own)
    assert not re.search(r"@[A-Z_]+@", run_sh) and os.access(out / "b" / "run.sh", os.X_OK)
    for seed in device_run.DEFAULT_SEEDS:
        assert f"default:{seed}" in run_sh
    for seed in device_run.MORE_SEEDS:          # the bundled file's own streets by default
        assert f"default:{seed}" not in run_sh
    assert '--tall-share 0" > $W/train.args' in run_sh
    assert "--check-cuda" in (out / "a" / "stash.sh").read_text()
    # the training keeps to its own deadline, so a run at its budget still exports; its flags are
    # written down for a third call, which goes on from the last checkpoint with them
    assert re.search(r"--minutes 600 [^#]*> \$W/train\.args\nT0=\$T0 W=\$W bash devtools/train/device_train\.sh",
                     run_sh)
    train_sh = open(os.path.join(device_run.REPO_ROOT, "devtools", "train", "device_train.sh")).read()
    assert re.search(r"python3 -m devtools\.train \$\(cat \"\$W/train\.args\"\) \$RESUME_ARGS [^#]*"
                     r"--until \$\(date", train_sh)
    assert 'RESUME_ARGS="--resume $W/last.pt"' in train_sh
    for script in (out / "a" / "stash.sh", out / "b" / "run.sh",
                   os.path.join(device_run.REPO_ROOT, "devtools", "train", "device_train.sh")):
        assert subprocess.run(["bash", "-n", str(script)], capture_output=True).returncode == 0, script
    assert {f"scenes/{name}/scene.json" for name in device_run.TINY_SCENES} <= b
    for name in device_run.HELD_OUT_SCENES:   # the second held-out set is never trained on
        preset, seed = name.split("-")
        assert f"{preset}:{seed}" not in run_sh and not any(f.startswith(f"scenes/{name}/") for f in b)


def test_gtsrb_crops_are_six_of_each_tracks_ten_in_frame_order_as_jpeg_under_their_names(made_up, tmp_path):
    data, scenes, wheels = made_up
    out = tmp_path / "out"
    device_run.pack(str(out), str(data), str(scenes), str(wheels))
    crops = sorted(f for f in _files(out / "b") if f.startswith("shared/data/gtsrb-train/train/"))
    kept = sorted(f"shared/data/gtsrb-train/train/stop/{t}_{3 * n:05d}.png"
                  for t in ("00000", "00001") for n in device_run.GTSRB_TRACK_FRAMES)
    assert crops == kept
    for name in crops:
        path = out / "b" / name
        assert path.read_bytes()[:2] == b"\xff\xd8"   # JPEG bytes
        n = int(name[-9:-4]) // 3
        image = cv2.imread(str(path))                  # read by content, whatever the name says
        assert image.shape[:2] == (30 + n, 30 + n)
        assert abs(float(image.mean()) - (40 + n)) < 2


def test_what_does_not_fit_is_left_out_and_said(made_up, tmp_path, monkeypatch):
    data, scenes, wheels = made_up
    out = tmp_path / "out"
    whole = device_run.pack(str(out), str(data), str(scenes), str(wheels))
    frame = os.path.getsize(data / "gtsdb-train" / "images" / "00001.jpg")
    # calls that hold 80 frames fewer together than the two parts did (a frame goes to the other
    # part when one is full, so only a shortfall of both leaves frames out)
    short = whole["budget"] - (whole["a"] + whole["b"]) // 2 + 40 * frame
    monkeypatch.setattr(device_run, "CALL_BYTES", device_run.CALL_BYTES - short)
    packed = device_run.pack(str(out), str(data), str(scenes), str(wheels))
    assert packed["a"] <= packed["budget"] and packed["b"] <= packed["budget"]
    assert len(packed["left_out"]) >= 20
    assert set(packed["left_out"]) <= set(GTSDB_TRAIN_IDS)   # the validation frames always go
    held = {int(f[-9:-4]) for f in _files(out) if f.endswith(".jpg")}
    assert not held & set(packed["left_out"])
    assert held | set(packed["left_out"]) == set(GTSDB_TRAIN_IDS) | set(device_run.VAL_FRAMES)


def test_missing_wheels_are_named_with_the_command_that_fetches_them(made_up, tmp_path):
    data, scenes, _ = made_up
    with pytest.raises(SystemExit, match="pip download"):
        device_run.pack(str(tmp_path / "out"), str(data), str(scenes), str(tmp_path / "no-wheels"))


def test_the_second_gpu_runs_streets_and_mix_can_be_packed_and_held_out_streets_cannot(made_up, tmp_path):
    data, scenes, wheels = made_up
    out = tmp_path / "out"
    six = device_run.DEFAULT_SEEDS + device_run.MORE_SEEDS
    device_run.pack(str(out), str(data), str(scenes), str(wheels), seeds=six, tall_share=0.25)
    run_sh = (out / "b" / "run.sh").read_text()
    assert "for s in " + " ".join(map(str, six)) + "; do" in run_sh
    assert all(f"default:{seed}" in run_sh for seed in six)
    assert '--tall-share 0.25" > $W/train.args' in run_sh
    with pytest.raises(SystemExit, match="103: held out"):
        device_run.pack(str(out), str(data), str(scenes), str(wheels), seeds=(100, 103))
