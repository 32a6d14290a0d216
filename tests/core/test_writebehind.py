"""core.writebehind and the writers that use it (Spool, CloudWriter): the same files as
writing in line, in order, and no error lost."""
import os
import threading
import time

import laspy
import numpy as np
import pytest

from roadsigns.core.drivewindows import Spool
from roadsigns.core.pointcloud import CloudWriter
from roadsigns.core.writebehind import WriteBehind


def test_writes_run_in_order_on_one_other_thread_one_at_a_time():
    done, threads, running = [], set(), []

    def write(k):
        running.append(k)
        assert len(running) == 1  # never two at once
        threads.add(threading.get_ident())
        time.sleep(0.01 * (k % 3))
        done.append(k)
        running.remove(k)

    with WriteBehind() as behind:
        for k in range(12):
            behind.submit(write, k)
    assert done == list(range(12))
    assert threads and threading.get_ident() not in threads


def test_a_writes_error_is_raised_by_the_next_submit_wait_or_close():
    def fail():
        raise OSError("disk full")

    for finish in ("submit", "wait", "close"):
        behind = WriteBehind()
        behind.submit(fail)
        with pytest.raises(OSError, match="disk full"):
            if finish == "submit":
                behind.submit(lambda: None)
            elif finish == "wait":
                behind.wait()
            else:
                behind.close()
        behind.abandon()


def test_abandon_waits_for_the_write_and_drops_its_error():
    finished = []

    def slow_fail():
        time.sleep(0.05)
        finished.append(True)
        raise OSError("late")

    behind = WriteBehind()
    behind.submit(slow_fail)
    behind.abandon()
    assert finished == [True]
    with pytest.raises(RuntimeError):
        behind.submit(lambda: None)


@pytest.mark.parametrize("background", [False, True])
def test_spool_reads_back_every_row_in_order(tmp_path, background):
    rng = np.random.default_rng(1)
    dtype = np.dtype([("x", "f8"), ("k", "i4")])
    parts = {k: [] for k in range(3)}
    with Spool({"p": dtype}, folder=str(tmp_path), flush_bytes=50 * dtype.itemsize, background=background) as spool:
        for step in range(40):
            k = int(rng.integers(3))
            rows = np.zeros(int(rng.integers(1, 30)), dtype)
            rows["x"], rows["k"] = rng.random(len(rows)), step
            spool.append("p", k, rows)
            parts[k].append(rows)
        for k in range(3):
            got = spool.read("p", k)
            np.testing.assert_array_equal(got, np.concatenate(parts[k]))
            in_parts = list(spool.read_parts("p", k, part_rows=7))
            assert all(len(p) == 7 for p in in_parts[:-1]) and 1 <= len(in_parts[-1]) <= 7
            np.testing.assert_array_equal(np.concatenate(in_parts), got)
            spool.discard("p", k)
            assert list(spool.read_parts("p", k)) == []
            assert spool.read("p", k).size == 0
        folder = spool.folder
    assert not os.path.exists(folder)


def test_rows_discarded_before_a_flush_no_longer_count_towards_it(tmp_path):
    dtype = np.dtype([("x", "f8")])
    with Spool({"p": dtype}, folder=str(tmp_path), flush_bytes=100 * dtype.itemsize) as spool:
        spool.append("p", 0, np.zeros(60, dtype))
        spool.append("p", 1, np.zeros(30, dtype))
        spool.discard("p", 0)
        assert spool._pending_bytes == 30 * dtype.itemsize
        spool.append("p", 1, np.zeros(60, dtype))     # 90 rows wait: under the 100, not written yet
        assert not os.path.exists(spool._path("p", 1))
        assert spool.count("p", 1) == 90 and spool.count("p", 0) == 0


def test_spool_raises_a_background_writes_error(tmp_path):
    dtype = np.dtype([("x", "f8")])
    spool = Spool({"p": dtype}, folder=str(tmp_path), flush_bytes=1, background=True)
    os.rmdir(spool.folder)  # the next append cannot be written
    spool.append("p", 0, np.zeros(3, dtype))
    with pytest.raises(FileNotFoundError):
        spool.read("p", 0)
    spool.close()


def _points(header, n, seed):
    rng = np.random.default_rng(seed)
    pts = laspy.ScaleAwarePointRecord.zeros(n, header=header)
    pts.x, pts.y, pts.z = rng.random(n) * 100, rng.random(n) * 100, rng.random(n) * 10
    pts.classification = rng.integers(0, 10, n)
    return pts


@pytest.mark.parametrize("suffix", [".las", ".laz"])
def test_cloud_writer_in_the_background_writes_the_same_file(tmp_path, suffix):
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales, header.offsets = [0.001] * 3, [0.0] * 3
    chunks = [_points(header, n, k) for k, n in enumerate((1000, 1, 5000, 0, 2500))]
    read = {}
    for background in (False, True):
        path = str(tmp_path / f"out-{background}{suffix}")
        with CloudWriter(path, header, background=background) as writer:
            for c in chunks:
                writer.write(c)
            assert writer.point_count == 8501
        read[background] = laspy.read(path)
    assert len(read[True].points) == 8501
    for name in ("X", "Y", "Z", "classification"):
        np.testing.assert_array_equal(np.asarray(read[True][name]), np.asarray(read[False][name]))


def test_cloud_writer_raises_a_background_writes_error_and_leaves_no_file(tmp_path):
    header = laspy.LasHeader(point_format=6, version="1.4")
    other = laspy.LasHeader(point_format=1, version="1.2")
    path = tmp_path / "out.laz"
    with pytest.raises(Exception):
        with CloudWriter(str(path), header) as writer:
            writer.write(_points(header, 100, 0))
            writer.write(_points(other, 100, 1))  # another point format: lazrs fails on its thread
            writer.write(_points(header, 100, 2))
    assert not path.exists()
    assert os.listdir(tmp_path) == []
