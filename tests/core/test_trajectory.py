"""core.trajectory: stations from CSV / SBET / poses against an independent computation,
and every bad input giving a clear InputError."""

import numpy as np
import pytest
from helpers.contract import angle_between_deg, expected_stations, quat_to_matrix
from pyproj import Proj, Transformer

from devtools import trajsample
from roadsigns.core import crs as rcrs
from roadsigns.core.errors import InputError
from roadsigns.core.trajectory import CameraMount, import_stations

MOUNT = CameraMount(lever_arm_m=(0.4, -0.1, -1.8), boresight_roll_deg=0.3,
                    boresight_pitch_deg=-0.5, boresight_yaw_deg=1.2)


LEVER = MOUNT.lever_arm_m
BORESIGHT = (MOUNT.boresight_roll_deg, MOUNT.boresight_pitch_deg, MOUNT.boresight_yaw_deg)


def check_against_truth(result, sample, position_tol_m=1e-3, angle_tol_deg=1e-3):
    st = result.stations
    assert st.image == sample["names"]
    centres, rotations = expected_stations(sample["drive"], sample["times"], LEVER, BORESIGHT)
    assert np.abs(st.xyz_world - centres).max() < position_tol_m
    R = np.array([quat_to_matrix(q) for q in st.q_world_from_pano_wxyz])
    assert angle_between_deg(R, rotations).max() < angle_tol_deg
    forward = rotations[:, :, 0]
    heading = np.mod(np.degrees(np.arctan2(forward[:, 0], forward[:, 1])), 360)
    assert np.abs((st.heading_deg - heading + 180) % 360 - 180).max() < angle_tol_deg
    assert (st.width_px == 64).all() and (st.height_px == 32).all()


def test_projected_csv(drive_projected):
    result = import_stations(drive_projected["images"], "EPSG:32633", "EPSG:32633",
                             trajectory_path=drive_projected["trajectory_csv"],
                             image_times_path=drive_projected["image_times"], mount=MOUNT)
    check_against_truth(result, drive_projected)
    assert np.allclose(result.stations.time_s, drive_projected["times"])
    assert any("unchanged" in m for m in result.messages)


def test_geographic_csv(drive_geographic):
    result = import_stations(drive_geographic["images"], "EPSG:32633", "EPSG:4326",
                             trajectory_path=drive_geographic["trajectory_csv"],
                             image_times_path=drive_geographic["image_times"], mount=MOUNT)
    check_against_truth(result, drive_geographic)


def test_sbet(drive_projected):
    result = import_stations(drive_projected["images"], "EPSG:32633", trajectory_path=drive_projected["sbet"],
                             image_times_path=drive_projected["image_times"], mount=MOUNT)
    check_against_truth(result, drive_projected)


def test_poses(drive_projected, drive_geographic):
    result = import_stations(drive_projected["images"], "EPSG:32633", "EPSG:32633",
                             poses_path=drive_projected["poses"], mount=MOUNT)
    check_against_truth(result, drive_projected)
    result = import_stations(drive_geographic["images"], "EPSG:32633", "EPSG:4326",
                             poses_path=drive_geographic["poses"], mount=MOUNT)
    check_against_truth(result, drive_geographic)


def test_default_target_is_utm_zone_of_a_geographic_trajectory(drive_geographic):
    result = import_stations(drive_geographic["images"], None, "EPSG:4326",
                             trajectory_path=drive_geographic["trajectory_csv"],
                             image_times_path=drive_geographic["image_times"], mount=MOUNT)
    assert "UTM zone 33N" in result.target_crs_wkt
    check_against_truth(result, drive_geographic)


def test_true_heading_becomes_grid_heading_east_of_central_meridian(tmp_path):
    """At 2.5 deg east of the UTM 33 central meridian (15 E) at 48 N, gamma = +1.858 deg:
    a vehicle heading 90 deg true heads 88.142 deg grid."""
    gamma = Proj("EPSG:32633").get_factors(17.5, 48.0).meridian_convergence
    assert gamma == pytest.approx(1.858, abs=5e-4)
    trajsample.write_images(str(tmp_path), ["a.png"], fmt="PNG")
    (tmp_path / "poses.csv").write_text("image,x,y,z,roll,pitch,heading\na.png,17.5,48.0,200,0,0,90\n")
    result = import_stations(str(tmp_path), "EPSG:32633", "EPSG:4326",
                             poses_path=str(tmp_path / "poses.csv"))
    assert result.stations.heading_deg[0] == pytest.approx(90.0 - 1.858, abs=5e-4)
    assert np.isnan(result.stations.time_s[0])
    e, n = Transformer.from_crs("EPSG:4326", "EPSG:32633", always_xy=True).transform(17.5, 48.0)
    assert result.stations.xyz_world[0] == pytest.approx([e, n, 200.0], abs=1e-6)


def test_delimiters_and_extra_columns(tmp_path, drive_projected):
    for delimiter in (";", "\t", " "):
        path = trajsample.write_trajectory_csv(str(tmp_path / "t.txt"), drive_projected["drive"],
                                               delimiter=delimiter)
        result = import_stations(drive_projected["images"], "EPSG:32633", "EPSG:32633", trajectory_path=path,
                                 image_times_path=drive_projected["image_times"], mount=MOUNT)
        check_against_truth(result, drive_projected)


def test_compound_target_says_what_happens_to_heights(drive_projected):
    result = import_stations(drive_projected["images"], "EPSG:32633+3855", "EPSG:32633",
                             poses_path=drive_projected["poses"])
    assert any(m.startswith("Heights:") and "EGM2008" in m for m in result.messages)


# --- bad input ------------------------------------------------------------------------

def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def run_csv(sample, trajectory_path, times_path=None, **kw):
    return import_stations(sample["images"], "EPSG:32633", "EPSG:32633",
                           trajectory_path=trajectory_path,
                           image_times_path=times_path or sample["image_times"], **kw)


def first_lines(path, n):
    with open(path) as f:
        return "".join(f.readline() for _ in range(n))


@pytest.mark.parametrize("text,expected", [
    ("", "is empty"),
    ("time,x,y,z,roll,pitch\n1,2,3,4,5,6\n", "missing column(s) heading; found time, x, y, z, roll, pitch"),
    ("time,x,y,z,roll,pitch,heading\n", "no data rows"),
])
def test_bad_trajectory_files(tmp_path, drive_projected, text, expected):
    with pytest.raises(InputError) as e:
        run_csv(drive_projected, write(tmp_path, "t.csv", text))
    assert expected in str(e.value) and "t.csv" in str(e.value)


@pytest.mark.parametrize("bad,expected", [
    ("abc", "line 4, field 'heading': expected a number, found 'abc'"),
    ("nan", "line 4, field 'heading': expected a finite number, found 'nan'"),
    ("inf", "line 4, field 'heading': expected a finite number, found 'inf'"),
])
def test_non_numeric_values_name_line_and_field(tmp_path, drive_projected, bad, expected):
    lines = first_lines(drive_projected["trajectory_csv"], 5).splitlines()
    fields = lines[3].split(",")
    fields[6] = bad
    lines[3] = ",".join(fields)
    with pytest.raises(InputError) as e:
        run_csv(drive_projected, write(tmp_path, "t.csv", "\n".join(lines) + "\n"))
    assert expected in str(e.value)


@pytest.mark.parametrize("swap,expected", [("dup", "line 3: time"), ("back", "line 3: time")])
def test_times_must_increase(tmp_path, drive_projected, swap, expected):
    lines = first_lines(drive_projected["trajectory_csv"], 5).splitlines()
    row2 = lines[1].split(",")
    row3 = lines[2].split(",")
    row3[0] = row2[0] if swap == "dup" else str(float(row2[0]) - 1)
    lines[2] = ",".join(row3)
    with pytest.raises(InputError) as e:
        run_csv(drive_projected, write(tmp_path, "t.csv", "\n".join(lines) + "\n"))
    message = str(e.value)
    assert expected in message
    assert ("duplicated" if swap == "dup" else "goes back in time") in message


def test_image_time_outside_span_is_error_or_skipped(tmp_path, drive_projected):
    times = write(tmp_path, "times.csv", "image,time\npano_0000.jpg,5.0\npano_0001.jpg,{}\n".format(
        drive_projected["times"][1]))
    with pytest.raises(InputError) as e:
        run_csv(drive_projected, drive_projected["trajectory_csv"], times)
    assert "line 2" in str(e.value) and "pano_0000.jpg" in str(e.value) and "outside" in str(e.value)
    result = run_csv(drive_projected, drive_projected["trajectory_csv"], times, skip_outside=True)
    assert result.stations.image == ["pano_0001.jpg"]
    assert any("Skipped 1 image" in w for w in result.warnings)


def test_gap_around_an_image_warns_with_its_length(tmp_path, drive_projected):
    t, *_ = drive_projected["drive"].samples()
    keep = np.abs(t - drive_projected["times"][2]) > 0.4  # a 0.8 s hole around image 2
    lines = open(drive_projected["trajectory_csv"]).read().splitlines()
    text = "\n".join([lines[0]] + [line for line, k in zip(lines[1:], keep) if k]) + "\n"
    result = run_csv(drive_projected, write(tmp_path, "t.csv", text), max_gap_s=0.5)
    assert any("gap" in w and "0.8" in w and "pano_0002.jpg" in w for w in result.warnings)


def test_missing_and_unreadable_images(tmp_path, drive_projected):
    times = write(tmp_path, "times.csv", "image,time\nnot_there.jpg,{}\npano_0001.jpg,{}\n".format(
        drive_projected["times"][0], drive_projected["times"][1]))
    result = run_csv(drive_projected, drive_projected["trajectory_csv"], times)
    assert result.stations.image == ["pano_0001.jpg"]
    assert any("Skipped 1 panorama" in w and "not_there.jpg" in w for w in result.warnings)
    with pytest.raises(InputError) as e:
        run_csv(drive_projected, drive_projected["trajectory_csv"], times, fail_on_missing_image=True)
    assert "not_there.jpg" in str(e.value)


def test_corrupt_image_is_skipped(tmp_path, drive_projected):
    folder = tmp_path / "imgs"
    folder.mkdir()
    (folder / "bad.jpg").write_bytes(b"\xff\xd8 this is not a jpeg")
    trajsample.write_images(str(folder), ["ok.jpg"])
    times = write(tmp_path, "times.csv", "image,time\nbad.jpg,{}\nok.jpg,{}\n".format(
        drive_projected["times"][0], drive_projected["times"][1]))
    result = import_stations(str(folder), "EPSG:32633", "EPSG:32633",
                             trajectory_path=drive_projected["trajectory_csv"], image_times_path=times)
    assert result.stations.image == ["ok.jpg"]
    assert any("bad.jpg" in w for w in result.warnings)


def test_panorama_not_twice_as_wide(tmp_path, drive_projected):
    from PIL import Image
    Image.new("RGB", (100, 40)).save(tmp_path / "wide.png")
    times = write(tmp_path, "times.csv", "image,time\nwide.png,{}\n".format(drive_projected["times"][0]))
    with pytest.raises(InputError) as e:
        import_stations(str(tmp_path), "EPSG:32633", "EPSG:32633",
                        trajectory_path=drive_projected["trajectory_csv"], image_times_path=times)
    assert "wide.png is 100 x 40 pixels" in str(e.value)


def test_sbet_size_must_be_a_multiple_of_136(tmp_path, drive_projected):
    data = open(drive_projected["sbet"], "rb").read()
    path = tmp_path / "cut.out"
    path.write_bytes(data[:-10])
    with pytest.raises(InputError) as e:
        import_stations(drive_projected["images"], "EPSG:32633", trajectory_path=str(path),
                        image_times_path=drive_projected["image_times"])
    assert "not a multiple of 136 bytes" in str(e.value) and "cut.out" in str(e.value)


@pytest.mark.parametrize("target,source,expected", [
    ("EPSG:999999", "EPSG:32633", "Unknown target CRS"),
    ("EPSG:32633", "nonsense", "Unknown trajectory CRS"),
    ("EPSG:4326", "EPSG:32633", "is not projected"),
])
def test_crs_errors(drive_projected, target, source, expected):
    with pytest.raises(InputError) as e:
        import_stations(drive_projected["images"], target, source, poses_path=drive_projected["poses"])
    assert expected in str(e.value)


def test_duplicate_image_names(tmp_path, drive_projected):
    times = write(tmp_path, "times.csv", "image,time\na.jpg,{0}\na.jpg,{0}\n".format(drive_projected["times"][0]))
    with pytest.raises(InputError) as e:
        run_csv(drive_projected, drive_projected["trajectory_csv"], times)
    assert "line 3: image 'a.jpg' already listed on line 2" in str(e.value)


def test_utm_zone_choice():
    assert rcrs.utm_crs_for(17.5, 48.0).to_epsg() == 32633
    assert rcrs.utm_crs_for(-70.6, -33.4).to_epsg() == 32719
