"""Sign panels and poles from the cloud alone (core.cloudsigns and its modules).

Two kinds of scenes: a hand-built cloud (a straight drive, flat ground, a sign on a pole,
a faded sign on a pole, a bare pole; exact truth, fast) and a generated ``tiny`` scene
(devtools/scenegen: gantry, shared poles, signs seen from behind, a faded sign, trees,
billboards, mirrors, lamp posts) whose reference files give the truth.
"""
import csv
import math
import os

import laspy
import numpy as np
import pytest
import shapely

from roadsigns.core import cloudpanels as CP
from roadsigns.core import cloudsigns as CS
from roadsigns.core import retroreflectivity as RR
from roadsigns.core.drivewindows import DriveAxis, Track, Window, WindowSpool, make_windows, split_window
from roadsigns.core.errors import Cancelled, InputError, Progress
from roadsigns.core.poles import POLE_FIELDS
from roadsigns.core.projection import cell_keys
from roadsigns.core.schema import names, typed_record

FULL = 65535
SPEED_MPS = 10.0
SENSOR_Z = 2.5


# --------------------------------------------------------------------------------------
# A hand-built drive
# --------------------------------------------------------------------------------------

class Built:
    """Truth of the hand-built scene."""
    signs = [  # centre, width, height, intensity share of full scale, faded
        {"centre": np.array([30.0, 6.0, 2.7]), "w": 0.6, "h": 0.6, "level": 0.92, "faded": False},
        {"centre": np.array([45.0, -6.0, 2.5]), "w": 0.9, "h": 0.6, "level": 0.18, "faded": True},
    ]
    poles = [np.array([30.06, 6.0]), np.array([45.06, -6.0]), np.array([20.0, 6.5])]
    pole_tops = [3.05, 2.85, 3.0]


def _half_cylinder(axis_xy, radius, z0, z1, view_xy, rng, step=0.02):
    """Points on the half of a vertical cylinder facing ``view_xy``."""
    ang = np.arange(0, 2 * np.pi, step / radius)
    z = np.arange(z0, z1, step)
    A, Z = np.meshgrid(ang, z)
    nrm = np.column_stack([np.cos(A.ravel()), np.sin(A.ravel())])
    view = np.asarray(view_xy, float) - axis_xy
    keep = nrm @ (view / np.linalg.norm(view)) > 0.05
    xy = axis_xy + radius * nrm[keep]
    return np.column_stack([xy, Z.ravel()[keep]]) + rng.normal(0, 0.003, (int(keep.sum()), 3))


def build_cloud(path, intensity_scale=1.0, ground_class=2, zero_intensity=False, saturate=False, seed=0):
    """Write the hand-built scene; the sensor drives along +x at y = 0 and sees each point
    from 45 degrees ahead (its gps_time is when the sensor was |y| m before it)."""
    rng = np.random.default_rng(seed)
    parts, inten, cls = [], [], []
    gx, gy = np.meshgrid(np.arange(0.0, 60.0, 0.12), np.arange(-11.0, 11.0, 0.12))
    ground = np.column_stack([gx.ravel(), gy.ravel(), rng.normal(0, 0.005, gx.size)])
    parts.append(ground)
    inten.append(np.full(len(ground), 0.08))
    cls.append(np.full(len(ground), ground_class))
    for sign in Built.signs:
        c = sign["centre"]
        u, v = np.meshgrid(np.arange(-sign["w"] / 2 + 0.0125, sign["w"] / 2, 0.025),
                           np.arange(-sign["h"] / 2 + 0.0125, sign["h"] / 2, 0.025))
        # the face looks at -x (oncoming traffic); in-plane axes: y (right seen from the front: -y... any) and z
        pts = np.column_stack([np.full(u.size, c[0]) + rng.normal(0, 0.004, u.size), c[1] + u.ravel(),
                               c[2] + v.ravel()])
        parts.append(pts)
        inten.append(np.full(len(pts), sign["level"]))
        cls.append(np.full(len(pts), 1))
    for axis_xy, top in zip(Built.poles, Built.pole_tops):
        view = (axis_xy[0] - abs(axis_xy[1]), 0.0)
        pts = _half_cylinder(axis_xy, 0.035, 0.0, top, view, rng)
        if axis_xy[0] < 40:  # the pole behind the sign at x = 30 is hidden where the panel is
            hidden = (pts[:, 2] > 2.4) & (axis_xy[0] > 25)
            pts = pts[~hidden]
        else:
            hidden = pts[:, 2] > 2.2
            pts = pts[~hidden]
        parts.append(pts)
        inten.append(np.full(len(pts), 0.3))
        cls.append(np.full(len(pts), 1))
    xyz = np.concatenate(parts)
    level = np.concatenate(inten) * intensity_scale * (1 + 0.03 * rng.standard_normal(len(xyz)))
    if zero_intensity:
        level[:] = 0.0
    if saturate:
        level[np.concatenate(cls) != 2] = 1.5
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales = np.array([0.001, 0.001, 0.001])
    header.offsets = np.array([0.0, 0.0, 0.0])
    rec = laspy.ScaleAwarePointRecord.zeros(len(xyz), header=header)
    rec.x, rec.y, rec.z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    rec.intensity = np.clip(np.round(level * FULL), 0, FULL).astype(np.uint16)
    rec.classification = np.concatenate(cls).astype(np.uint8)
    rec.gps_time = (xyz[:, 0] - np.abs(xyz[:, 1])) / SPEED_MPS
    with laspy.open(str(path), mode="w", header=header) as w:
        w.write_points(rec)
    return str(path)


def built_track(shift_x=0.0):
    x = np.arange(-5.0, 65.0, 0.5)
    return Track(np.column_stack([x + shift_x, np.zeros_like(x), np.full_like(x, SENSOR_Z)]), x / SPEED_MPS)


@pytest.fixture(scope="module")
def built_path(tmp_path_factory):
    return build_cloud(tmp_path_factory.mktemp("built") / "cloud.las")


@pytest.fixture(scope="module")
def built_result(built_path):
    return CS.find_signs_in_cloud(built_path, built_track())


def _nearest(found_xyz, xyz):
    d = np.linalg.norm(np.asarray(found_xyz) - xyz, axis=1)
    k = int(np.argmin(d))
    return k, float(d[k])


def test_built_signs_found_at_their_place_with_size_and_facing(built_result):
    res = built_result
    assert len(res.signs) == len(Built.signs)
    centres = np.array([s.centre_world for s in res.signs])
    for truth in Built.signs:
        k, d = _nearest(centres, truth["centre"])
        sign = res.signs[k]
        assert d < 0.02, (truth, sign.centre_world)
        assert abs(sign.width - truth["w"]) < 0.04 and abs(sign.panel_height - truth["h"]) < 0.04
        assert abs(((sign.azimuth_deg - 270.0) + 180) % 360 - 180) < 2.0   # the face looks west (-x)
        assert abs(sign.height - truth["centre"][2]) < 0.03
        assert sign.support == CS.SUPPORT_POLE and sign.face_seen


def test_built_poles_feet_kinds_and_carried_signs(built_result):
    res = built_result
    assert len(res.poles) == len(Built.poles)
    feet = np.array([[p.x, p.y, 0.0] for p in res.poles])
    centres = np.array([s.centre_world for s in res.signs])
    for axis_xy, top, carries in zip(Built.poles, Built.pole_tops, (0, 1, None)):
        k, d = _nearest(feet, np.array([*axis_xy, 0.0]))
        pole = res.poles[k]
        assert d <= 0.03, (axis_xy, pole)
        assert abs(pole.z_foot) < 0.02 and pole.lean_deg < 3.0
        if carries is None:
            assert pole.kind == "other" and pole.sign_ids == []
        else:
            j, _ = _nearest(centres, Built.signs[carries]["centre"])
            assert pole.kind == "sign_pole" and pole.sign_ids == [res.signs[j].sign_id]
            assert res.signs[j].pole_id == pole.pole_id
            top_truth = Built.signs[carries]["centre"][2] + Built.signs[carries]["h"] / 2
            assert abs(pole.height - top_truth) < 0.1


def test_poles_keep_no_head_points_once_their_window_is_searched(built_result):
    """A pole's head points serve its window (support, a gantry over the road); a long drive
    finds thousands of poles, so the result keeps them only for gantries (their beams find
    the far posts, over the whole drive), not for the other poles."""
    assert built_result.poles
    params = CS.CloudSignParams().poles
    assert not any(p.is_gantry(params) for p in built_result.poles)
    assert all(p.head_xyz.shape == (0, 3) and _held_bytes(p.head_xyz) == 0 for p in built_result.poles)
    assert any(p.reach_m > 0 for p in built_result.poles)  # heads were there and measured


def test_found_panels_keep_no_window_rows_once_their_window_is_searched(built_path, monkeypatch):
    """A found panel's rows index its window's points; the drive's signs keep the panel's
    measures and its point count, not the rows (a long drive finds thousands of panels)."""
    kept = []
    real_finish = CS._finish
    monkeypatch.setattr(CS, "_finish", lambda found, *a, **k: kept.extend(found) or real_finish(found, *a, **k))
    res = CS.find_signs_in_cloud(built_path, built_track())
    assert kept and len(res.signs) and all(f.n_points > 0 for f in kept)
    assert all(len(f.panel.rows) == 0 and _held_bytes(f.panel.rows) == 0 for f in kept)
    assert {s.n_points for s in res.signs} <= {f.n_points for f in kept}   # counted before they went


def _held_bytes(array: np.ndarray) -> int:
    """The memory an array keeps alive: its own, or that of the array it is a view of."""
    while isinstance(array.base, np.ndarray):
        array = array.base
    return array.nbytes


def test_built_faded_sign_flagged_healthy_not(built_result):
    centres = np.array([s.centre_world for s in built_result.signs])
    for truth in Built.signs:
        k, _ = _nearest(centres, truth["centre"])
        condition = built_result.signs[k].condition
        assert (condition in ("check", "poor")) == truth["faded"], (truth, condition)
        assert built_result.signs[k].bright_share > 0.5 or truth["faded"]


def test_built_log_states_threshold(built_result):
    text = " ".join(built_result.messages)
    assert "bright threshold" in text and "{:.3f}".format(built_result.threshold.value) in text


def test_small_chunks_and_windows_give_the_same_answer(built_path, built_result):
    params = CS.CloudSignParams(window_m=8.0, margin_m=5.0)
    small = CS.find_signs_in_cloud(built_path, built_track(), params=params, chunk_points=7_000)
    assert small.n_windows > built_result.n_windows
    assert small.max_window_points < 0.6 * built_result.max_window_points
    a = np.array(sorted(tuple(np.round(s.centre_world, 2)) for s in built_result.signs))
    b = np.array(sorted(tuple(np.round(s.centre_world, 2)) for s in small.signs))
    assert a.shape == b.shape and np.abs(a - b).max() <= 0.011
    pa = np.array(sorted((round(p.x, 2), round(p.y, 2)) for p in built_result.poles))
    pb = np.array(sorted((round(p.x, 2), round(p.y, 2)) for p in small.poles))
    assert pa.shape == pb.shape and np.abs(pa - pb).max() <= 0.011


def test_dense_windows_searched_in_parts_give_the_same_answer(built_path, built_result):
    """A window of more than window_max_points is searched in parts: the most points a part
    holds drops, the signs and poles stay (at the same places, each once). Margins of 10 m in
    both runs: the built street's objects stand within a few metres of each other, so with
    narrower margins the part holding them holds every point of its window."""
    whole = CS.find_signs_in_cloud(built_path, built_track(), params=CS.CloudSignParams(margin_m=10.0))
    params = CS.CloudSignParams(margin_m=10.0, window_max_points=800)
    parts = CS.find_signs_in_cloud(built_path, built_track(), params=params)
    assert whole.n_parts == whole.n_windows == parts.n_windows
    assert parts.n_parts >= 2 * parts.n_windows
    assert parts.max_window_points < whole.max_window_points
    a = np.array(sorted(tuple(np.round(s.centre_world, 2)) for s in whole.signs))
    b = np.array(sorted(tuple(np.round(s.centre_world, 2)) for s in parts.signs))
    assert len(a) and a.shape == b.shape and np.abs(a - b).max() <= 0.011
    assert len(whole.signs) == len(built_result.signs)
    assert sorted(s.support for s in whole.signs) == sorted(s.support for s in parts.signs)
    pa = np.array(sorted((round(p.x, 2), round(p.y, 2)) for p in whole.poles))
    pb = np.array(sorted((round(p.x, 2), round(p.y, 2)) for p in parts.poles))
    assert len(pa) and pa.shape == pb.shape and np.abs(pa - pb).max() <= 0.011


def test_a_dense_window_is_not_held_while_its_parts_are_searched(built_path, monkeypatch):
    """A window searched in parts is read whole once, to cut it; each part's rows are then read
    from the spool's file, so no whole window is held while a part of it is searched (fails
    where the parts are cut from the whole window, kept meanwhile)."""
    import gc
    import weakref

    from roadsigns.core import drivewindows

    whole_reads = []
    read = drivewindows.Spool.read

    def tracked_read(self, kind, index, rows=None):
        out = read(self, kind, index, rows)
        if kind == "points" and rows is None:
            whole_reads.append(weakref.ref(out))
        return out

    held = []
    process_window = CS._process_window

    def tracked_process_window(window, rows, *args, **kwargs):
        gc.collect()
        held.append(sum(1 for ref in whole_reads if ref() is not None and ref() is not rows))
        return process_window(window, rows, *args, **kwargs)

    monkeypatch.setattr(drivewindows.Spool, "read", tracked_read)
    monkeypatch.setattr(CS, "_process_window", tracked_process_window)
    result = CS.find_signs_in_cloud(built_path, built_track(),
                                    params=CS.CloudSignParams(window_max_points=800, window_threads=1))
    assert result.n_parts >= 2 * result.n_windows and len(held) == result.n_parts
    assert len(whole_reads) == result.n_windows and max(held) == 0


def test_a_spool_reads_a_files_rows_by_position(tmp_path):
    dtype = np.dtype([("s", "f4"), ("k", "i8")])
    with WindowSpool(make_windows(10.0, 10.0), 0.0, {"p": dtype}, folder=str(tmp_path)) as spool:
        rows = np.zeros(50, dtype)
        rows["s"], rows["k"] = np.linspace(0.0, 9.9, 50), np.arange(50)
        spool.add("p", rows["s"], rows)
        whole = spool.read("p", 0)
        pick = np.array([3, 0, 49, 17, 17])
        got = spool.read("p", 0, pick)
        assert got.dtype == dtype and np.array_equal(got, whole[pick])
        assert len(spool.read("p", 0, np.zeros(0, np.int64))) == 0
        assert len(spool.read("p", 5, np.zeros(0, np.int64))) == 0     # no file: nothing appended
        with pytest.raises(IndexError):
            spool.read("p", 0, np.array([50]))
        with pytest.raises(IndexError):
            spool.read("p", 5, np.array([0]))


@pytest.mark.parametrize("window", [Window(3, 100.0, 150.0), Window(0, -np.inf, 50.0), Window(9, 450.0, np.inf)])
def test_split_window_parts_tile_the_core_and_keep_their_margins(window):
    rng = np.random.default_rng(1)
    margin = 10.0
    lo = window.s0_m if np.isfinite(window.s0_m) else 30.0   # the drive's first and last windows:
    hi = window.s1_m if np.isfinite(window.s1_m) else 470.0  # their points end where the drive does
    s = np.sort(np.r_[rng.uniform(lo - margin, hi + margin, 3000), rng.normal(0.5 * (lo + hi), 2.0, 4000)])
    s = s[(s >= window.s0_m - margin) & (s < window.s1_m + margin)]
    parts = split_window(window, s, margin, max_points=1500, min_core_m=margin)
    assert len(parts) > 2 and all(p.index == window.index for p, _ in parts)
    assert parts[0][0].s0_m == window.s0_m and parts[-1][0].s1_m == window.s1_m
    for (a, _), (b, _) in zip(parts, parts[1:]):
        assert a.s1_m == b.s0_m                         # the cores tile the window's core, in order
    for part, rows in parts:
        want = np.flatnonzero((s >= part.s0_m - margin) & (s < part.s1_m + margin))
        assert np.array_equal(rows, want)               # exactly the points within the margin
        core = s[part.owns(s)]
        assert len(rows) <= 1500 or np.ptp(core) <= margin + 1e-9   # small, or too short to cut
    owned = np.concatenate([rows[part.owns(s[rows])] for part, rows in parts])
    assert np.array_equal(np.sort(owned), np.flatnonzero(window.owns(s)))   # each point owned once
    whole = split_window(window, s, margin, max_points=len(s), min_core_m=margin)
    assert len(whole) == 1 and whole[0][0] == window and np.array_equal(whole[0][1], np.arange(len(s)))


def test_windows_searched_in_threads_give_the_same_answer(tiny):
    folder, res, axis, _ = tiny
    track = Track(axis.track.xyz_world, axis.track.time_s)
    kw = dict(window_m=12.0, margin_m=8.0)
    one = CS.find_signs_in_cloud(os.path.join(folder, "cloud.laz"), track,
                                 params=CS.CloudSignParams(window_threads=1, **kw))
    two = CS.find_signs_in_cloud(os.path.join(folder, "cloud.laz"), track,
                                 params=CS.CloudSignParams(window_threads=2, **kw))
    assert one.n_windows >= 4 and len(one.signs) > 0
    same = lambda a, b: repr([x.as_dict() for x in a]) == repr([x.as_dict() for x in b])  # noqa: E731 (NaN)
    assert same(one.signs, two.signs) and same(one.poles, two.poles)
    assert one.rejected == two.rejected and one.max_window_points == two.max_window_points


def test_the_reading_pass_in_threads_spools_the_same_rows_in_the_same_order(tiny, tmp_path):
    """Pass 1 works on the cloud's chunks in a pool of threads and spools what they give
    in reading order: each window's points and ground, and the intensity histogram, are
    the same row for row with one thread and with two (many small chunks)."""
    from roadsigns.core.cloudsource import open_cloud

    folder, _, axis, _ = tiny
    spooled = {}
    for threads in (1, 2):
        params = CS.CloudSignParams(window_threads=threads)
        windows = make_windows(axis.length_m, params.window_m)
        hist = RR.IntensityHistogram()
        with WindowSpool(windows, params.margin_m, {"points": CS.POINT_DTYPE, "ground": CS.GROUND_DTYPE},
                         folder=str(tmp_path)) as spool:
            counts = CS._spool_cloud(open_cloud(os.path.join(folder, "cloud.laz")), axis, spool, hist, True,
                                     params, 7_000, Progress())
            rows = [(spool.read("points", w.index), spool.read("ground", w.index)) for w in windows]
        spooled[threads] = counts, rows, hist
    (counts1, rows1, hist1), (counts2, rows2, hist2) = spooled[1], spooled[2]
    assert counts1[0] > 20 * 7_000 and counts1[1] > 0 and counts1[2] > 0
    assert counts1 == counts2
    for (p1, g1), (p2, g2) in zip(rows1, rows2):
        assert p1.tobytes() == p2.tobytes() and g1.tobytes() == g2.tobytes()
    assert sum(len(p) for p, _ in rows1) >= counts1[1]
    assert np.array_equal(hist1.counts, hist2.counts) and hist1.n_total == hist2.n_total > 0


def test_cancel_while_windows_are_searched_in_threads(built_path):
    seen = {"windows": 0}

    def cancelled():
        return seen["windows"] >= 2

    def on_report(percent):
        if percent > 50.0:                    # pass 2: the windows
            seen["windows"] += 1

    params = CS.CloudSignParams(window_m=10.0, margin_m=5.0, window_threads=2)
    with pytest.raises(Cancelled):
        CS.find_signs_in_cloud(built_path, built_track(), params=params,
                               progress=Progress(on_report, cancelled))
    assert 2 <= seen["windows"] < 6


def test_map_in_order_keeps_order_bounds_the_work_in_flight_and_cancels():
    import threading
    import time

    from roadsigns.core.drivewindows import map_in_order

    lock, state = threading.Lock(), {"now": 0, "most": 0, "started": []}

    def work(i):
        with lock:
            state["now"] += 1
            state["most"] = max(state["most"], state["now"])
            state["started"].append(i)
        time.sleep(0.05 if i % 2 else 0.01)              # uneven: later items finish first
        with lock:
            state["now"] -= 1
        return i * i

    assert list(map_in_order(work, range(9), 2, lambda: None)) == [i * i for i in range(9)]
    assert state["most"] == 2
    assert list(map_in_order(work, iter(range(4)), 1, lambda: None)) == [0, 1, 4, 9]
    state["started"].clear()
    seen = []

    def check():
        if len(seen) >= 3:
            raise Cancelled("cancelled")

    with pytest.raises(Cancelled):
        for r in map_in_order(work, range(50), 2, check):
            seen.append(r)
    assert seen == [0, 1, 4] and len(state["started"]) <= 5


def test_window_spool_bounds_memory_and_duplicates_margins(tmp_path):
    windows = make_windows(100.0, 20.0)
    dtype = np.dtype([("s", "f8")])
    with WindowSpool(windows, 5.0, {"p": dtype}, folder=str(tmp_path), flush_bytes=100 * dtype.itemsize) as spool:
        s_all = np.arange(0.0, 100.0, 0.1)
        for k in range(0, len(s_all), 50):
            s = s_all[k:k + 50]
            rows = np.zeros(len(s), dtype)
            rows["s"] = s
            spool.add("p", s, rows)
            assert spool._pending_bytes < (100 + 2 * 50) * dtype.itemsize     # flushed once past the limit
        spool.flush()
        for w in windows:
            got = spool.read("p", w.index)["s"]
            lo, hi = max(w.s0_m, -1e9) - 5.0, min(w.s1_m, 1e9) + 5.0
            want = s_all[(s_all >= lo) & (s_all < hi)]
            assert np.array_equal(np.sort(got), want)
    assert not os.path.exists(spool.folder)


def test_ground_thinned_to_the_first_point_in_the_corridor_of_each_cell():
    """The ground kept is the first point inside the corridor of every cell, as thinning
    the inside points would give, while the corridor test sees far fewer points."""
    rng = np.random.default_rng(5)
    n = 60000
    xyz = np.column_stack([rng.uniform(0, 20, n), rng.uniform(-8, 8, n), rng.normal(0, 0.05, n)])
    out_by = np.abs(xyz[:, 1] + 0.3 * np.sin(xyz[:, 0])) - 5.0   # a wavy corridor edge
    asked = []

    def inside(rows):
        asked.append(len(rows))
        return out_by[rows] <= 0, out_by[rows] <= CS.cell_reach_m(0.25), xyz[rows, 0]  # "arc length": x

    got, got_s = CS._thin_ground(xyz, 0.25, inside)
    assert np.array_equal(got_s, xyz[got, 0])           # each kept point's own arc length
    # brute force: thin the inside points, first of each cell in reading order
    rows_in = np.flatnonzero(out_by <= 0)
    keys = cell_keys(xyz[:, 0], xyz[:, 1], 0.25)[rows_in]
    _, first = np.unique(keys, return_index=True)
    want = np.sort(rows_in[first])
    assert np.array_equal(got, want)
    assert len(got) > 1000 and sum(asked) < 0.25 * n


def test_records_follow_the_schemas(built_result):
    records = built_result.sign_records()
    assert records and all(tuple(r) == names(CS.CLOUD_SIGN_FIELDS) for r in records)
    for r in records:
        assert typed_record(CS.CLOUD_SIGN_FIELDS, r)["sign_id"] == r["sign_id"]
        outline = shapely.from_wkt(r["outline_wkt"])
        corners = np.array(outline.exterior.coords)[:4]
        assert np.allclose(corners.mean(axis=0), [r["x"], r["y"], r["z"]], atol=1e-3)
        assert abs(np.linalg.norm(corners[1] - corners[0]) - r["width"]) < 1e-3
        assert abs(np.linalg.norm(corners[3] - corners[0]) - r["panel_height"]) < 1e-3
        assert r["condition"] in RR.CONDITIONS
    poles = built_result.pole_records()
    assert poles and all(tuple(p) == names(POLE_FIELDS) for p in poles)


# --------------------------------------------------------------------------------------
# Bad input
# --------------------------------------------------------------------------------------

def test_all_zero_intensity_is_an_error_naming_the_file(tmp_path):
    path = build_cloud(tmp_path / "dark.las", zero_intensity=True)
    with pytest.raises(InputError) as e:
        CS.find_signs_in_cloud(path, built_track())
    assert path in str(e.value) and "intensity" in str(e.value)


def test_saturated_intensity_warns_with_the_threshold(tmp_path):
    path = build_cloud(tmp_path / "hot.las", saturate=True)
    warnings = []
    res = CS.find_signs_in_cloud(path, built_track(), progress=Progress(on_warning=warnings.append))
    saturated = [w for w in res.warnings if "saturated" in w]
    assert saturated and saturated[0] in warnings
    assert "{:.3f}".format(res.threshold.value) in saturated[0]
    assert saturated[0].fields["thr"] == res.threshold.value


def test_stations_away_from_the_cloud_say_by_how_much(built_path):
    with pytest.raises(InputError) as e:
        CS.find_signs_in_cloud(built_path, built_track(shift_x=1000.0))
    # cloud x in [0, 60); the shifted track starts at x = 995
    assert e.value.fields["path"] == built_path
    assert abs(e.value.fields["gap"] - (995.0 - 59.96)) < 0.1
    assert "do not overlap" in str(e.value)


def test_cloud_without_ground_is_an_error(tmp_path):
    path = build_cloud(tmp_path / "noground.las", ground_class=1)
    with pytest.raises(InputError) as e:
        CS.find_signs_in_cloud(path, built_track())
    assert path in str(e.value) and "ground" in str(e.value)


def test_cancel_stops_the_stage(built_path):
    calls = {"n": 0}

    def cancelled():
        calls["n"] += 1
        return calls["n"] > 3

    with pytest.raises(Cancelled):
        CS.find_signs_in_cloud(built_path, built_track(), progress=Progress(is_cancelled=cancelled),
                               chunk_points=20_000)


# --------------------------------------------------------------------------------------
# Intensity model, threshold, condition; the drive axis
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("alpha", [0.0, 1.0, 2.0])
def test_threshold_separates_retroreflective_returns_and_finds_the_range_exponent(alpha):
    rng = np.random.default_rng(1)
    hist = RR.IntensityHistogram()
    r = rng.uniform(3.0, 30.0, 200_000)
    dull = 0.15 * 2 ** (0.5 * rng.standard_normal(len(r))) * (10.0 / r) ** alpha
    hist.add(np.clip(dull * FULL, 1, FULL), r)
    r_b = rng.uniform(3.0, 30.0, 6_000)
    bright = 0.9 * (10.0 / r_b) ** alpha * (1 + 0.05 * rng.standard_normal(len(r_b)))
    hist.add(np.clip(bright * FULL, 1, FULL), r_b)
    thr = hist.threshold()
    assert abs(thr.range_exponent - alpha) < 0.1 and thr.method == RR.METHOD_VALLEY
    model = RR.IntensityModel(range_exponent=thr.range_exponent)
    assert np.mean(model.range_normalised(bright * FULL, r_b) >= thr.value) > 0.97
    assert np.mean(model.range_normalised(dull * FULL, r) >= thr.value) < 0.001
    fixed = hist.threshold(range_exponent=0.0)
    assert fixed.range_exponent == 0.0 and fixed.range_bins_used == 0


def test_threshold_without_sheeting_is_the_background_level():
    rng = np.random.default_rng(2)
    hist = RR.IntensityHistogram()
    hist.add(0.15 * 2 ** (0.5 * rng.standard_normal(100_000)) * FULL, np.full(100_000, 10.0))
    thr = hist.threshold()
    assert thr.method == RR.METHOD_BACKGROUND and thr.value == pytest.approx(thr.background)
    assert thr.value > 0.15 * 2 ** 1.5


def test_incidence_normalisation_is_capped():
    model = RR.IntensityModel()
    head_on = model.normalised(FULL * 0.5, 10.0, 1.0)
    assert head_on == pytest.approx(0.5)
    assert model.normalised(FULL * 0.25, 10.0, 0.5) == pytest.approx(0.5)
    assert model.normalised(FULL * 0.25, 10.0, 0.01) == pytest.approx(0.5)   # capped at 60 degrees


def test_condition_thresholds_and_reference():
    assert RR.condition_of(1.0, 1.0, True) == RR.GOOD
    assert RR.condition_of(0.5, 1.0, True) == RR.CHECK
    assert RR.condition_of(0.2, 1.0, True) == RR.POOR
    assert RR.condition_of(1.0, 1.0, False) == RR.UNKNOWN
    assert RR.drive_reference(np.array([1.0, 1.2, 1.4]), 0.5) == (1.2, "drive")
    assert RR.drive_reference(np.array([1.0]), 0.5) == (0.75, "threshold")
    assert RR.drive_reference(np.array([1.0, 1.2, 1.4]), 0.5, retro_reference=2.0) == (2.0, "given")
    values = np.r_[np.full(50, 1.0), np.full(10, 0.1)]
    interior = np.r_[np.ones(50, bool), np.zeros(10, bool)]
    assert RR.retro_index(values, interior) == 1.0


def test_closed_form_eigen_agrees_with_lapack():
    rng = np.random.default_rng(3)
    # shapes of neighbourhoods: a plane with rows, a line, a blob, and a point far from the origin
    pts = [rng.normal(size=(16, 3)) * s for s in ([1.0, 0.5, 0.01], [1.0, 0.02, 0.01], [1.0, 1.0, 1.0])]
    pts += [rng.normal(size=(16, 3)) for _ in range(200)]
    mats = np.array([np.cov(p.T, bias=True) for p in pts])
    w_ref, V_ref = np.linalg.eigh(mats)
    entries = (mats[:, 0, 0], mats[:, 1, 1], mats[:, 2, 2], mats[:, 0, 1], mats[:, 0, 2], mats[:, 1, 2])
    w, v = CP.sym3_eigen(*entries)
    assert np.allclose(w, w_ref, rtol=0, atol=1e-12 * w_ref[:, 2:].max())
    assert np.allclose(np.linalg.norm(v, axis=1), 1.0)
    assert np.all(np.abs(np.einsum("mi,mi->m", v, V_ref[:, :, 0])) > 1 - 1e-9)   # sign is free
    w, v = CP.sym3_eigen(*(np.full(1, x) for x in (2.0, 2.0, 2.0, 0.0, 0.0, 0.0)))   # isotropic
    assert np.allclose(w, 2.0) and np.allclose(v, [[0.0, 0.0, 1.0]])


def test_local_features_match_eigh_far_from_the_origin():
    rng = np.random.default_rng(4)
    plane = np.column_stack([rng.uniform(0, 2, 400), np.zeros(400), rng.uniform(0, 2, 400)])
    plane[:, 1] += rng.normal(0, 0.003, 400)
    xyz = plane + [641_180.0, 5_340_273.0, 230.0]          # UTM-sized coordinates
    normal, lin, flat, sca = CP.local_features(xyz, k=16)
    from scipy.spatial import cKDTree
    _, idx = cKDTree(xyz).query(xyz, k=16)
    nb = xyz[idx] - xyz[idx].mean(axis=1, keepdims=True)
    w, V = np.linalg.eigh(np.einsum("mki,mkj->mij", nb, nb) / 16)
    assert np.allclose(flat, w[:, 0] / w[:, 1], atol=1e-6)
    assert np.allclose(lin, (w[:, 2] - w[:, 1]) / w[:, 2], atol=1e-6)
    assert np.all(np.abs(normal[:, 1]) > 0.99)              # the wall faces y
    assert np.all(np.abs(np.einsum("mi,mi->m", normal, V[:, :, 0])) > 1 - 1e-6)


def test_ground_model_median_of_near_points_else_the_nearest():
    g = np.array([[0.0, 0.0, 1.0], [0.5, 0.0, 2.0], [0.0, 0.5, 4.0], [0.5, 0.5, 10.0], [20.0, 0.0, 7.0]])
    ground = CS.GroundModel(g)
    z = ground(np.array([[0.25, 0.25], [40.0, 0.0], [1.0, 0.0]]))
    assert z[0] == pytest.approx(3.0)                     # median of 1, 2, 4, 10 (the far one is out)
    assert z[1] == pytest.approx(7.0)                     # nothing within reach: the nearest point's
    assert z[2] == pytest.approx(np.median([1.0, 2.0, 4.0, 10.0]))
    assert np.isnan(CS.GroundModel(np.zeros((0, 3)))(np.zeros((2, 2)))).all()


def test_drive_axis_locates_points_and_sensor_positions():
    axis = DriveAxis(built_track())
    s, off, _ = axis.locate(np.array([[10.0, 3.0], [20.0, -2.0]]))
    assert np.allclose(s, [15.0, 25.0], atol=0.26) and np.allclose(off, [-3.0, 2.0])  # right is -y here
    sensor = axis.sensor_positions(np.array([[10.0, 3.0, 1.0]]), np.array([0.7]))
    assert np.allclose(sensor, [[7.0, 0.0, SENSOR_Z]])
    near = axis.sensor_positions(np.array([[10.0, 3.0, 1.0]]), None)
    assert np.allclose(near[0, :2], [10.0, 0.0], atol=0.26)
    assert Window(0, 0.0, 10.0).owns(np.array([0.0, 9.99, 10.0])).tolist() == [True, True, False]


# --------------------------------------------------------------------------------------
# A generated scene
# --------------------------------------------------------------------------------------

def _read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    from devtools.scenegen import generate_scene

    folder = str(tmp_path_factory.mktemp("cloudsigns_tiny"))
    generate_scene("tiny", seed=4, out_dir=folder, panoramas=False, masks=False)
    traj = np.genfromtxt(os.path.join(folder, "trajectory.csv"), delimiter=",", names=True)
    track = Track(np.column_stack([traj["x"], traj["y"], traj["z"] + 2.0]), traj["time"])
    res = CS.find_signs_in_cloud(os.path.join(folder, "cloud.laz"), track)
    las = laspy.read(os.path.join(folder, "cloud.laz"))
    cloud = {"xyz": np.column_stack([las.x, las.y, las.z]), "cls": np.asarray(las.classification)}
    return folder, res, DriveAxis(track), cloud


def _seen(folder, axis, cloud, xyz, classes, radius, planar=False):
    """Reference objects the drive saw: along the drive, in the corridor, scanned."""
    s, off, _ = axis.locate(np.atleast_2d(xyz))
    pts = cloud["xyz"][np.isin(cloud["cls"], classes)]
    dims = 2 if planar else 3
    d = np.linalg.norm(pts[None, :, :dims] - np.atleast_2d(xyz)[:, None, :dims], axis=2)
    return (s >= 0) & (s <= axis.length_m) & (np.abs(off) <= 11.0) & ((d <= radius).sum(axis=1) >= 20)


def test_scene_signs_found_to_the_centimetre(tiny):
    folder, res, axis, cloud = tiny
    ref = _read_csv(os.path.join(folder, "reference_signs.csv"))
    xyz = np.array([[float(r["x"]), float(r["y"]), float(r["z"])] for r in ref])
    seen = _seen(folder, axis, cloud, xyz, [64], 0.5)
    assert seen.sum() >= 6
    found = np.array([s.centre_world for s in res.signs])
    d = np.linalg.norm(found[:, None, :] - xyz[None, :, :], axis=2)
    for j in np.flatnonzero(seen):
        assert d[:, j].min() <= 0.10, ("missed", ref[j])
    s_found, off_found, _ = axis.locate(found)
    in_area = (s_found >= 0) & (s_found <= axis.length_m) & (np.abs(off_found) <= 11.0)
    assert np.all(d[in_area].min(axis=1) <= 0.10), "a sign where the reference has none"
    assert np.median(d.min(axis=0)[seen]) <= 0.03


def test_scene_poles_feet_kinds_and_signs(tiny):
    folder, res, axis, cloud = tiny
    ref = _read_csv(os.path.join(folder, "reference_poles.csv"))
    feet = np.array([[float(r["x"]), float(r["y"]), float(r["z_foot"])] for r in ref])
    seen = _seen(folder, axis, cloud, feet, [65, 66], 0.3, planar=True)
    assert seen.sum() >= 6
    found = np.array([[p.x, p.y, p.z_foot] for p in res.poles])
    d = np.linalg.norm(found[:, None, :2] - feet[None, :, :2], axis=2)
    signs = _read_csv(os.path.join(folder, "reference_signs.csv"))
    sign_xyz = {r["sign_id"]: np.array([float(r["x"]), float(r["y"]), float(r["z"])]) for r in signs}
    by_id = {s.sign_id: s for s in res.signs}
    for j in np.flatnonzero(seen):
        k = int(np.argmin(d[:, j]))
        assert d[k, j] <= 0.10, ("foot", ref[j], res.poles[k])
        pole = res.poles[k]
        assert abs(pole.z_foot - feet[j, 2]) <= 0.05
        assert pole.kind == ref[j]["kind"], (ref[j], pole)
        carried = [sign_xyz[i] for i in ref[j]["sign_ids"].split()]
        got = [by_id[i].centre_world for i in pole.sign_ids]
        assert len(got) == len(carried), (ref[j], pole)
        for c in carried:
            assert min(np.linalg.norm(g - c) for g in got) <= 0.10
    assert np.all(d.min(axis=1) <= 0.5), "a pole where the reference has none"


def test_scene_faded_signs_flagged(tiny):
    folder, res, _, _ = tiny
    ref = _read_csv(os.path.join(folder, "reference_signs.csv"))
    assert "faded" in ref[0]
    found = np.array([s.centre_world for s in res.signs])
    n_faded = 0
    for r in ref:
        xyz = np.array([float(r["x"]), float(r["y"]), float(r["z"])])
        d = np.linalg.norm(found - xyz, axis=1)
        if d.min() > 0.1:
            continue
        sign = res.signs[int(np.argmin(d))]
        if r["faded"] == "1":
            n_faded += 1
            assert sign.condition in ("check", "poor"), (r, sign.retro_index)
        elif sign.face_seen:
            assert sign.condition == "good", (r, sign.retro_index, res.reference)
        else:
            assert sign.condition == "unknown"
    assert n_faded >= 1


def test_scene_panels_seen_from_behind_face_the_right_way(tiny):
    folder, res, _, _ = tiny
    ref = _read_csv(os.path.join(folder, "reference_signs.csv"))
    found = np.array([s.centre_world for s in res.signs])
    checked = 0
    for r in ref:
        d = np.linalg.norm(found - np.array([float(r["x"]), float(r["y"]), float(r["z"])]), axis=1)
        if d.min() <= 0.1:
            sign = res.signs[int(np.argmin(d))]
            diff = abs((sign.azimuth_deg - float(r["azimuth"]) + 180.0) % 360.0 - 180.0)
            assert diff < 5.0, (r, sign.azimuth_deg, sign.face_seen)
            checked += 1
    assert checked >= 6
    assert any(not s.face_seen for s in res.signs)     # the scene has signs seen from behind
    assert math.isfinite(res.reference) and res.reference_source == "drive"


def test_stations_or_a_line_serve_as_the_track(built_path, built_result):
    from types import SimpleNamespace

    t = built_track()
    stations = SimpleNamespace(xyz_world=t.xyz_world[::10], time_s=t.time_s[::10])
    line = t.xyz_world                                   # no times: nearest track positions
    want = np.array(sorted(tuple(s.centre_world) for s in built_result.signs))
    for track in (stations, line):
        res = CS.find_signs_in_cloud(built_path, track)
        got = np.array(sorted(tuple(s.centre_world) for s in res.signs))
        assert got.shape == want.shape and np.abs(got - want).max() < 0.02


def _window_points(xyz):
    """WindowPoints of ``xyz`` with their local features; the other fields are not used."""
    n = len(xyz)
    normal, lin, flat, sca = CP.local_features(xyz)
    zeros = np.zeros(n)
    return CP.WindowPoints(xyz=xyz, h=xyz[:, 2], sensor=np.zeros((n, 3)), intensity=zeros,
                           intensity_rn=zeros, bright=np.zeros(n, bool), s_m=zeros, offset_m=zeros,
                           tangent_xy=np.tile([0.0, 1.0], (n, 1)), normal=normal, linearity=lin,
                           flatness=flat, scattering=sca)


def _triangle_behind_its_pole(rng):
    """The back of a yield sign (0.9 m, tip down at z 2.0) in the plane y = 0, its points 5 cm
    apart in rows 2.5 cm apart (the tip: one or two points a row), and its pole 9 cm in front
    of it (towards the scanner at y < 0), scanned all round and more densely, as a drive
    scans a pole it passes."""
    u, v = np.meshgrid(np.arange(-0.45, 0.451, 0.05), np.arange(0.0, 0.78, 0.025))
    inside = np.abs(u) <= 0.45 * v / 0.78
    face = np.column_stack([u[inside], np.zeros(inside.sum()), 2.0 + v[inside]])
    axis_xy, radius = np.array([0.0, -0.09]), 0.035
    z = np.arange(0.5, 3.2, 0.01)
    angles = np.linspace(0.0, 2.0 * math.pi, 16, endpoint=False)
    pole = np.array([[axis_xy[0] + radius * math.cos(a), axis_xy[1] + radius * math.sin(a), zz]
                     for zz in z for a in angles])
    xyz = np.concatenate([face, pole]) + rng.normal(0, 0.002, (len(face) + len(pole), 3))
    return xyz, len(face), (axis_xy, radius)


def test_a_triangles_tip_beside_its_pole_is_flat_once_the_pole_is_out_of_its_neighbourhood():
    # the cloud's yield and warning signs seen from behind lost their tips: the tip's
    # neighbours were mostly the pole's, so they were neither flat nor facing the road
    xyz, n_face, pole = _triangle_behind_its_pole(np.random.default_rng(5))
    pts = _window_points(xyz)
    params = CP.PanelParams()
    tip = np.flatnonzero((np.arange(len(xyz)) < n_face) & (xyz[:, 2] < 2.15))
    assert len(tip) >= 10

    def dark_panel_like(normal, linearity, flatness):   # find_panels' tests of a dark point
        facing = np.abs(normal[:, 1]) >= math.cos(math.radians(params.max_normal_to_track_deg
                                                                + params.dark_normal_slack_deg))
        return (flatness <= params.dark_max_flatness) & (linearity <= params.dark_max_linearity) & facing

    before = dark_panel_like(pts.normal[tip], pts.linearity[tip], pts.flatness[tip])
    normal, linearity, flatness = CP.features_off_poles(pts, [pole], params)
    after = dark_panel_like(normal[tip], linearity[tip], flatness[tip])
    assert before.mean() < 0.2 and after.mean() > 0.8, (before.mean(), after.mean())
    # the pole's own points, and those just past its estimated surface, keep their features
    d = np.linalg.norm(xyz[:, :2] - pole[0], axis=1)
    kept = d <= pole[1] + params.pole_surface_m + params.pole_clearance_m
    assert kept[n_face:].all()
    assert np.array_equal(normal[kept], pts.normal[kept]) and np.array_equal(flatness[kept], pts.flatness[kept])
    assert pts.flatness is not flatness                  # the window's own arrays are not changed
    off = CP.PanelParams(pole_feature_reach_m=0.0)
    assert CP.features_off_poles(pts, [pole], off)[2] is pts.flatness


def test_the_halves_of_a_triangle_split_at_its_pole_are_one_panel():
    # a warning sign seen from behind, cut by its pole's shadow: one half holds the apex
    u, v = np.meshgrid(np.arange(-0.45, 0.451, 0.02), np.arange(0.0, 0.78, 0.02))
    inside = np.abs(u) <= 0.45 * (0.78 - v) / 0.78
    xyz = np.column_stack([u[inside], np.zeros(inside.sum()), 2.0 + v[inside]])
    pts = _window_points(xyz)
    a = np.flatnonzero(xyz[:, 0] < -0.10)                 # no apex: its top is 0.6 m lower
    b = np.flatnonzero(xyz[:, 0] > -0.02)                 # the apex
    params = CP.PanelParams()
    in_the_gap = (np.array([-0.06, -0.07]), 0.035)
    far_away = (np.array([1.5, -0.07]), 0.035)
    assert not CP._side_by_side(pts, a, b, params)                 # the tops differ
    assert not CP._side_by_side(pts, a, b, params, [far_away])
    assert CP._side_by_side(pts, a, b, params, [in_the_gap])
    assert CP._merge_parts(pts, [a, b], params, [in_the_gap]) == [[0, 1]]
    # two panels stacked on one pole share no edge: apart, pole or not
    lower = np.flatnonzero(xyz[:, 2] < 2.25)
    upper = np.flatnonzero(xyz[:, 2] > 2.35)
    assert not CP._side_by_side(pts, lower, upper, params, [in_the_gap])


def _slice_of_pole(rng, centre_xy, radius=0.05, n=12):
    """The near half of a pole's section (an arc facing a sensor at -y), at h 1.0 m."""
    a = rng.uniform(math.pi * 1.1, math.pi * 1.9, n)
    return np.column_stack([centre_xy[0] + radius * np.cos(a), centre_xy[1] + radius * np.sin(a)])


def _stripe(x0, x1, y, n=12):
    return np.column_stack([np.linspace(x0, x1, n), np.full(n, y)])


def test_a_section_flanked_on_two_sides_is_a_piece_of_a_row_not_a_pole():
    """A pole's section with pieces of a row (a wall in stripes) within ``flank_m`` on both
    sides is not a section; with them on one side only, or farther than ``flank_m``, it is
    (the flank test takes the slice's points near the section from the slice's tree: fails
    where it misses points within the radius, or counts points beyond it)."""
    from roadsigns.core import poles as P

    params = P.PoleParams()
    rng = np.random.default_rng(3)
    pole = _slice_of_pole(rng, (0.0, 0.0))

    def sections(*others):
        xy = np.vstack([pole, *others])
        xyz = np.column_stack([xy, np.full(len(xy), 1.0)])
        sensor = np.tile([0.0, -8.0, 2.0], (len(xy), 1))
        found = P._sections(xyz, xyz[:, 2].copy(), sensor, params)
        return [s for s in found if np.hypot(*s.centre) < 0.2]

    reach = 0.05 + params.flank_m                # about half the section's extent plus flank_m
    left, right = _stripe(-reach + 0.25, -reach + 0.05, 0.0), _stripe(reach - 0.05, reach - 0.25, 0.0)
    far_left, far_right = _stripe(-reach - 0.45, -reach - 0.25, 0.0), _stripe(reach + 0.25, reach + 0.45, 0.0)
    assert len(sections()) == 1
    assert len(sections(left)) == 1 and len(sections(right)) == 1
    assert sections(left, right) == []
    assert len(sections(far_left, far_right)) == 1


def test_the_search_says_which_window_it_is_on(tmp_path):
    path = build_cloud(tmp_path / "steps.las")
    steps = []
    CS.find_signs_in_cloud(path, built_track(), progress=Progress(on_step=steps.append))
    windows = [s for s in steps if s.template.startswith("Searching the drive")]
    reading = [s for s in steps if s.template.startswith("Reading")]
    assert reading and {s.fields["name"] for s in reading} == {"steps.las"}
    assert steps.index(reading[-1]) < steps.index(windows[0])
    assert windows[-1].fields["n"] == windows[-1].fields["count"] == windows[0].fields["count"]
