"""bench/bench_drive_repeat.py: a drive repeated by moving headers and layers, not points."""
import os
import sys

import laspy
import numpy as np
import pytest
from helpers import cloudgen

from devtools import REPO_ROOT

sys.path.insert(0, os.path.join(REPO_ROOT, "bench"))
import bench_drive_repeat as rep  # noqa: E402


@pytest.mark.parametrize("suffix", [".las", ".laz"])
def test_a_shifted_copy_has_every_point_moved_east_and_nothing_else(tmp_path, suffix):
    src, dst = str(tmp_path / ("a" + suffix)), str(tmp_path / ("b" + suffix))
    cloudgen.write_scene(src, cloudgen.road_scene(length_m=20.0, density_per_m2=20.0))
    rep.shifted_las(src, dst, 2000.0)
    a, b = laspy.read(src), laspy.read(dst)
    np.testing.assert_allclose(np.asarray(b.x), np.asarray(a.x) + 2000.0, atol=1e-6)
    np.testing.assert_array_equal(np.asarray(b.y), np.asarray(a.y))
    np.testing.assert_array_equal(np.asarray(b.z), np.asarray(a.z))
    np.testing.assert_array_equal(np.asarray(b.intensity), np.asarray(a.intensity))
    assert b.header.maxs[0] == pytest.approx(a.header.maxs[0] + 2000.0)
    assert b.header.mins[0] == pytest.approx(a.header.mins[0] + 2000.0)
    assert b.header.mins[1] == a.header.mins[1]


def test_a_repeated_layer_moves_each_copy_and_renumbers_its_ids(tmp_path):
    from osgeo import ogr, osr

    src, dst = str(tmp_path / "stations.gpkg"), str(tmp_path / "stations3.gpkg")
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(src)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32633)
    layer = ds.CreateLayer("stations", srs, ogr.wkbPoint25D)
    fields = (("station_id", ogr.OFTInteger), ("x", ogr.OFTReal), ("y", ogr.OFTReal), ("image", ogr.OFTString))
    for name, kind in fields:
        layer.CreateField(ogr.FieldDefn(name, kind))
    for k in range(1, 5):
        f = ogr.Feature(layer.GetLayerDefn())
        f.SetField("station_id", k), f.SetField("x", 100.0 + k), f.SetField("y", 5.0), f.SetField("image", f"p{k}.jpg")
        f.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT Z ({100.0 + k} 5 1)"))
        layer.CreateFeature(f)
    del layer, ds
    assert rep.repeated_layer(src, dst, 3, 1000.0) == 12
    out_source = ogr.Open(dst)   # kept: a layer outlives no data source
    out = out_source.GetLayer(0)
    rows = [(f.GetField("station_id"), f.GetField("x"), f.GetGeometryRef().GetX(), f.GetField("image")) for f in out]
    assert [r[0] for r in rows] == list(range(1, 13))
    for i, (sid, x, gx, image) in enumerate(rows):
        copy, k = divmod(i, 4)
        assert x == gx == 100.0 + k + 1 + 1000.0 * copy and image == f"p{k + 1}.jpg"
