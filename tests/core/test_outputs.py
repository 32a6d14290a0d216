"""core.outputs: outputs written whole or not at all, with the umask's permissions; and the
core writers cancelled at several points leave nothing behind (issue 19)."""
import os
import stat

import numpy as np
import pytest
from helpers import cloudgen

from roadsigns.core import outputs
from roadsigns.core.errors import Cancelled, InputError, Progress
from roadsigns.core.ground import run_ground_filter
from roadsigns.core.pointcloud import CloudWriter, CropRegion, crop_cloud, read_header
from roadsigns.core.refine import write_sign_points
from roadsigns.core.review import write_chips, write_review_report


def mode(path):
    return stat.S_IMODE(os.stat(path).st_mode)


@pytest.fixture
def umask_027():
    old = os.umask(0o027)
    yield
    os.umask(old)


def cancel_after(n):
    """A Progress whose user cancels once it has been asked ``n`` times."""
    calls = [0]

    def is_cancelled():
        calls[0] += 1
        return calls[0] > n

    return Progress(is_cancelled=is_cancelled)


@pytest.fixture(scope="module")
def cloud(tmp_path_factory):
    path = str(tmp_path_factory.mktemp("cloud") / "road.laz")
    cloudgen.write_scene(path, cloudgen.road_scene(length_m=20.0, density_per_m2=40.0, seed=4))
    return path


def test_default_modes_follow_the_umask(umask_027):
    assert outputs.current_umask() == 0o027
    assert outputs.default_file_mode() == 0o640 and outputs.default_folder_mode() == 0o750


def test_atomic_text_gets_normal_permissions(tmp_path, umask_027):
    path = tmp_path / "report.html"
    outputs.write_text_atomically(str(path), "<p>x</p>")
    assert path.read_text() == "<p>x</p>" and mode(path) == 0o640
    assert os.listdir(tmp_path) == ["report.html"]


def test_atomic_file_failure_keeps_the_old_file(tmp_path):
    path = tmp_path / "out.txt"
    path.write_text("old")
    with pytest.raises(RuntimeError):
        with outputs.atomic_file(str(path)) as temporary:
            open(temporary, "w").write("half")
            raise RuntimeError("disk full")
    assert path.read_text() == "old" and os.listdir(tmp_path) == ["out.txt"]


def test_missing_folder_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        outputs.temp_path_beside(str(tmp_path / "no" / "x.laz"))


def test_staged_outputs_commit_and_rollback(tmp_path, umask_027):
    (tmp_path / "chips").mkdir()
    (tmp_path / "chips" / "old.jpg").write_text("old chip")
    staged = outputs.StagedOutputs()
    file_name = staged.file(str(tmp_path / "a.laz"))
    folder = staged.folder(str(tmp_path / "chips"))
    assert os.path.dirname(file_name) == str(tmp_path) and os.path.basename(file_name).startswith(".roadsigns-")
    open(file_name, "w").write("points")
    open(os.path.join(folder, "sign_1.jpg"), "w").write("chip")
    staged.commit()
    assert sorted(os.listdir(tmp_path)) == ["a.laz", "chips"]
    assert os.listdir(tmp_path / "chips") == ["sign_1.jpg"]  # the folder is replaced as a whole
    assert mode(tmp_path / "a.laz") == 0o640 and mode(tmp_path / "chips") == 0o750
    assert mode(tmp_path / "chips" / "sign_1.jpg") == 0o640

    staged = outputs.StagedOutputs()
    open(staged.file(str(tmp_path / "a.laz")), "w").write("new points")
    staged.folder(str(tmp_path / "chips"))
    assert staged.rollback() == []
    assert sorted(os.listdir(tmp_path)) == ["a.laz", "chips"] and (tmp_path / "a.laz").read_text() == "points"


def test_staged_output_never_written_is_an_error(tmp_path):
    staged = outputs.StagedOutputs()
    staged.file(str(tmp_path / "a.html"))
    with pytest.raises(InputError, match="was not written"):
        staged.commit()
    assert staged.rollback() == [] and os.listdir(tmp_path) == []


def test_cloud_writer_output_is_not_0600(tmp_path, cloud, umask_027):
    out = tmp_path / "copy.laz"
    with CloudWriter(str(out), read_header(cloud)) as writer:
        writer.write(__import__("laspy").read(cloud).points[:10])
    assert mode(out) == 0o640


def test_review_report_is_not_0600(tmp_path):
    path = tmp_path / "review.html"
    write_review_report([{"sign_id": 1, "class": "stop"}], [""], str(path))
    assert mode(path) == 0o666 & ~outputs.current_umask()


# --- cancel at several points: nothing is left ----------------------------------------------

@pytest.mark.parametrize("after", [0, 1, 2, 3, 5, 8])
def test_ground_filter_cancelled(tmp_path, cloud, after):
    with pytest.raises(Cancelled):
        run_ground_filter(cloud, str(tmp_path / "ground.laz"), engine="builtin", chunk_points=2000,
                          progress=cancel_after(after))
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("after", [0, 1, 3])
def test_crop_cancelled(tmp_path, cloud, after):
    x0, y0, _ = cloudgen.ORIGIN
    region = CropRegion.corridor(5.0, points_xy=[[x0 + 5, y0], [x0 + 15, y0]])
    with pytest.raises(Cancelled):
        crop_cloud(cloud, str(tmp_path / "crop.laz"), region, chunk_points=2000, progress=cancel_after(after))
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("after", [0, 1])
def test_sign_points_cancelled(tmp_path, cloud, after):
    with pytest.raises(Cancelled):
        write_sign_points(cloud, str(tmp_path / "points.laz"), [np.arange(0, 5000, 7)],
                          progress=cancel_after(after))
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("after", [0, 1])
def test_chips_cancelled_in_a_staged_folder(tmp_path, after):
    from PIL import Image

    images = tmp_path / "images"
    images.mkdir()
    for k in range(3):
        Image.new("RGB", (512, 256), (90, 90, 90)).save(images / "p{}.jpg".format(k))
    out = tmp_path / "out"
    out.mkdir()
    signs = [{"sign_id": k, "best_image": "p{}.jpg".format(k)} for k in range(3)]
    staged = outputs.StagedOutputs()
    with pytest.raises(Cancelled):
        write_chips(signs, [np.array([100.0, 100.0, 120.0, 120.0])] * 3, str(images),
                    staged.folder(str(out / "signs_chips")), cancel_after(after))
    assert staged.rollback() == [] and os.listdir(out) == []
