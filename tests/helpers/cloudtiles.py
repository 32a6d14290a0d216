"""Point clouds as users receive them, for the tests: a LAS/LAZ file split into square
tiles (laspy), and a virtual point cloud (.vpc) listing tiles as pdal_wrench writes it."""
import json
import os

import laspy
import numpy as np
import pyproj


def split_into_tiles(src, folder, size_m=20.0, scales=None, offsets_shift=None, point_format=None,
                     crs_epsg=None, suffix=".laz"):
    """Write the points of ``src`` as square tiles of ``size_m`` into ``folder`` (file names
    sorted as the tiles' x, then y); returns the tile paths. ``scales`` / ``offsets_shift``
    give every other tile other scales and offsets; ``crs_epsg`` gives the last one another CRS."""
    las = laspy.read(src)
    xyz = np.column_stack([las.x, las.y, las.z])
    i = np.floor((xyz[:, 0] - xyz[:, 0].min()) / size_m).astype(int)
    j = np.floor((xyz[:, 1] - xyz[:, 1].min()) / size_m).astype(int)
    os.makedirs(folder, exist_ok=True)
    paths = []
    keys = sorted(set(zip(i.tolist(), j.tolist())))
    for n, (a, b) in enumerate(keys):
        rows = np.flatnonzero((i == a) & (j == b))
        header = laspy.LasHeader(point_format=point_format or las.header.point_format.id,
                                 version=las.header.version)
        header.scales = las.header.scales if (scales is None or n % 2 == 0) else np.asarray(scales)
        header.offsets = las.header.offsets + (0 if (offsets_shift is None or n % 2 == 0) else offsets_shift)
        epsg = crs_epsg if (crs_epsg is not None and n == len(keys) - 1) else None
        crs = pyproj.CRS.from_epsg(epsg) if epsg else las.header.parse_crs()
        if crs is not None:
            header.add_crs(crs)
        out = laspy.LasData(header)
        out.x, out.y, out.z = xyz[rows, 0], xyz[rows, 1], xyz[rows, 2]
        for name in ("intensity", "classification", "return_number", "number_of_returns", "gps_time"):
            if name in out.point_format.dimension_names and name in las.point_format.dimension_names:
                out[name] = las[name][rows]
        path = os.path.join(folder, f"tile_{a:02d}_{b:02d}{suffix}")
        out.write(path)
        paths.append(path)
    return paths


def write_vpc(path, tiles, relative=True, **feature_extra):
    """A .vpc listing ``tiles`` the way pdal_wrench writes it (hrefs ./relative)."""
    features = []
    for t in tiles:
        h = laspy.read_header(t) if hasattr(laspy, "read_header") else laspy.open(t).header
        href = "./" + os.path.relpath(t, os.path.dirname(path)) if relative else t
        props = {"datetime": "2024-03-14T00:00:00Z", "pc:count": int(h.point_count), "pc:type": "lidar",
                 "pc:encoding": "?", "pc:schemas": [],
                 "proj:bbox": [*map(float, h.mins), *map(float, h.maxs)],
                 "proj:wkt2": pyproj.CRS.from_epsg(25833).to_wkt()}
        features.append({"type": "Feature", "stac_version": "1.0.0", "id": os.path.basename(t),
                         "geometry": None, "properties": props, "links": [],
                         "assets": {"data": {"href": href, "roles": ["data"]}}, **feature_extra})
    with open(path, "w") as f:
        json.dump({"type": "FeatureCollection", "features": features}, f)
    return path


def hilly_street(folder):
    """A 120 m street on a 3 % slope (60 points a m²): one LAZ in ``folder``, and the same split
    into 25 m tiles (whose edges do not fall on CSF's 32 m squares) in ``folder/tiles``:
    ``dict(single, folder, tiles, scene)``."""
    from helpers import cloudgen

    scene = cloudgen.road_scene(length_m=120.0, slope=0.03, density_per_m2=60.0, seed=4)
    single = os.path.join(str(folder), "street.laz")
    cloudgen.write_scene(single, scene)
    tiles = split_into_tiles(single, os.path.join(str(folder), "tiles"), size_m=25.0)
    return dict(single=single, folder=os.path.join(str(folder), "tiles"), tiles=tiles, scene=scene)


def classes_by_point(paths):
    """The points of the LAS/LAZ files ``paths`` in the order of their coordinates:
    ``(keys, classes)``, keys the coordinates in mm (int64, ``(n, 3)``)."""
    keys, classes = [], []
    for p in paths:
        las = laspy.read(p)
        keys.append(np.round(np.column_stack([las.x, las.y, las.z]) * 1000).astype(np.int64))
        classes.append(np.asarray(las.classification))
    k, c = np.concatenate(keys), np.concatenate(classes)
    order = np.lexsort(k.T[::-1])
    return k[order], c[order]


def same_classes_cases():
    """``(method, params, crop)`` cases for the tests that compare a cut run (tiles, blocks)
    with one run over the file: CSF and SMRF at their defaults, and a cropped CSF with a cloth
    step that is no binary fraction."""
    from roadsigns.core import ground

    return [("csf", None, False), ("smrf", None, False),
            ("csf", ground.CsfParams(resolution=0.3, threshold=0.2), True)]


def street_crop(single):
    """The crop polygons of those cases: a corridor along the street of :func:`hilly_street`
    that leaves two of its tiles out and cuts through the others."""
    import shapely

    from roadsigns.core import cloudsource

    x0, y0 = cloudsource.open_cloud(single).bounds[:2]
    return [shapely.box(x0 + 3, y0 + 6, x0 + 80, y0 + 24)]
