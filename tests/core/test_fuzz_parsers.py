"""Property-based fuzzing of every reader of user files (issue 19): whatever the bytes, a
reader either parses them or raises :class:`InputError`; never any other exception.

Readers: the trajectory CSV, the SBET, the image times, the per-image poses, the labels
file, the reference signs CSV, the layer readers (stations, detections, candidates: the
plain records the adapters hand to core, NULLs in every field among them) and LAS/LAZ
clouds truncated or with flipped bits. Hypothesis runs derandomized (a fixed seed), so CI
sees the same examples every time; the whole module takes well under a minute.
"""
import os
import struct

import numpy as np
import pytest
from helpers import cloudgen
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from devtools import temp_folder
from roadsigns.core import pointcloud
from roadsigns.core.detections import DETECTION_FIELDS, Detections
from roadsigns.core.detector import read_labels_file
from roadsigns.core.errors import InputError
from roadsigns.core.evaluate import read_reference_csv
from roadsigns.core.projection import CANDIDATE_FIELDS, ProjectionResult
from roadsigns.core.schema import Columns
from roadsigns.core.trajectory import (
    POSE_COLUMNS,
    STATION_FIELDS,
    TRAJECTORY_COLUMNS,
    Stations,
    import_stations,
    read_image_times,
    read_poses,
    read_sbet,
    read_trajectory,
)

FUZZ = settings(derandomize=True, deadline=None, max_examples=200, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
FEW = settings(FUZZ, max_examples=60)
FOLDER = temp_folder("roadsigns-fuzz-")  # removed when the test process exits


def write(name, data):
    path = os.path.join(FOLDER, name)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode("utf-8", "surrogatepass"))
    return path


def parses_or_input_error(reader, path):
    """Call ``reader(path)``; an InputError is a fine answer, anything else fails the test."""
    try:
        return reader(path)
    except InputError as error:
        assert str(error)  # the message formats
        return None


# --- delimited text: realistic tables with every kind of damage --------------------------

NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.floats(-1e7, 1e7).map(lambda v: "{:.6f}".format(v)),
    st.floats(-1e4, 1e4).map(lambda v: "{:.3f}".format(v).replace(".", ",")),  # decimal comma
    st.integers(-10**30, 10**30).map(str),
    st.sampled_from(["", " ", "nan", "NaN", "inf", "-inf", "1e999", "1_000", "0x10", "1.2.3", "--1",
                     "\x00", "\"1.5\"", "'2'", "1,5", "null", "NULL", "\u00a0", "\u2212" + "1", "١٢"]),
)
TEXT_FIELDS = st.one_of(
    st.text(max_size=12),
    st.sampled_from(["pano_0000.jpg", "pano_0000.jpg", "", "a\"b", "\"quoted, comma\"", "x\ty", "../etc/passwd",
                     "\x00", "é.jpg", "\ufeff", "\r"]),
)
DELIMITERS = st.sampled_from([",", ";", "\t", " ", "  ", "|", ", "])
NEWLINES = st.sampled_from(["\n", "\r\n", "\r", "\n\n"])


@st.composite
def tables(draw, columns, text_columns=()):
    """A delimited table with (mostly) the right header: columns shuffled, renamed, dropped
    or added; rows of numbers or text, too few or too many fields; BOM, blank lines."""
    header = list(columns)
    if draw(st.booleans()):
        header = draw(st.permutations(header))
    if draw(st.integers(0, 4)) == 0:
        header = [h.upper() if draw(st.booleans()) else " {} ".format(h) for h in header]
    if draw(st.integers(0, 5)) == 0 and header:
        del header[draw(st.integers(0, len(header) - 1))]
    if draw(st.integers(0, 5)) == 0:
        header.append(draw(st.sampled_from(["quality", "time", "", "x", draw(st.text(max_size=6))])))
    delimiter = draw(DELIMITERS)
    newline = draw(NEWLINES)
    lines = [delimiter.join(header)]
    for _ in range(draw(st.integers(0, 6))):
        n = len(header) + draw(st.sampled_from([0, 0, 0, 0, -1, 1, 2]))
        fields = []
        for k in range(max(n, 0)):
            name = header[k].strip().lower() if k < len(header) else ""
            fields.append(draw(TEXT_FIELDS if name in text_columns else NUMBERS))
        if draw(st.integers(0, 6)) == 0:
            fields.append("")  # a trailing delimiter
        lines.append(delimiter.join(fields))
        if draw(st.integers(0, 8)) == 0:
            lines.append("")
    text = newline.join(lines) + draw(st.sampled_from(["", newline]))
    if draw(st.integers(0, 8)) == 0:
        text = "\ufeff" + text
    return text


ANY_TEXT = st.one_of(st.text(max_size=300), st.binary(max_size=300).map(lambda b: b.decode("latin-1")))


@given(st.one_of(tables(TRAJECTORY_COLUMNS + ("quality",)), ANY_TEXT, st.binary(max_size=200)))
@FUZZ
def test_trajectory_csv(data):
    trajectory = parses_or_input_error(read_trajectory, write("trajectory.csv", data))
    if trajectory is not None:
        assert np.isfinite(trajectory.time_s).all() and (np.diff(trajectory.time_s) > 0).all()
        assert len(trajectory.locations) == len(trajectory)


@given(st.one_of(tables(("image", "time"), text_columns=("image",)), ANY_TEXT, st.binary(max_size=200)))
@FUZZ
def test_image_times(data):
    parsed = parses_or_input_error(read_image_times, write("image_times.csv", data))
    if parsed is not None:
        names, times, _ = parsed
        assert len(set(names)) == len(names) and all(names) and np.isfinite(times).all()


@given(st.one_of(tables(POSE_COLUMNS + ("time",), text_columns=("image",)), ANY_TEXT, st.binary(max_size=200)))
@FUZZ
def test_poses(data):
    poses = parses_or_input_error(read_poses, write("poses.csv", data))
    if poses is not None:
        assert len(poses.locations) == len(poses.image)


REFERENCE = ("sign_id", "class", "x", "y", "z", "height", "width", "panel_height", "azimuth")


@given(st.one_of(tables(REFERENCE, text_columns=("sign_id", "class")), ANY_TEXT, st.binary(max_size=200)))
@FUZZ
def test_reference_csv(data):
    signs = parses_or_input_error(read_reference_csv, write("reference.csv", data))
    if signs is not None:
        assert len(set(signs.ids)) == len(signs.ids) and np.isfinite(signs.xyz).all()


@given(st.one_of(ANY_TEXT, st.binary(max_size=300), st.lists(st.text(max_size=20), max_size=8).map("\n".join)))
@FUZZ
def test_labels_file(data):
    names = parses_or_input_error(read_labels_file, write("labels.txt", data))
    if names is not None:
        assert names and all(n and n == n.strip() for n in names)


def test_unreadable_paths():
    for reader in (read_trajectory, read_image_times, read_poses, read_reference_csv, read_labels_file,
                   read_sbet):
        for path in (os.path.join(FOLDER, "missing.csv"), FOLDER):
            with pytest.raises(InputError):
                reader(path)


# --- SBET: records of 17 little-endian float64 ------------------------------------------------

RADIANS = st.floats(-3.2, 3.2)


@st.composite
def sbets(draw):
    """Plausible SBETs (time increasing, lat/lon in radians) with damage: NaN, huge values,
    time going back, a cut record, big-endian bytes."""
    n = draw(st.integers(0, 12))
    time = np.cumsum([draw(st.floats(-0.1, 1.0)) for _ in range(n)]) + 1000.0
    records = np.zeros((n, 17))
    records[:, 0] = time
    for k in range(n):
        records[k, 1:4] = [draw(st.floats(-1.6, 1.6)), draw(RADIANS), draw(st.floats(-500, 5000))]
        records[k, 7:11] = [draw(RADIANS) for _ in range(4)]
        if draw(st.integers(0, 10)) == 0:
            records[k, draw(st.integers(0, 16))] = draw(st.floats(allow_nan=True, allow_infinity=True))
    data = records.astype(draw(st.sampled_from(["<f8", "<f8", ">f8"]))).tobytes()
    if draw(st.integers(0, 6)) == 0:
        data = data[:draw(st.integers(0, len(data)))]
    return data


@given(st.one_of(sbets(), st.binary(max_size=17 * 8 * 3)))
@FUZZ
def test_sbet(data):
    trajectory = parses_or_input_error(read_sbet, write("trajectory.out", data))
    if trajectory is not None:
        assert np.isfinite(trajectory.x).all() and (np.abs(trajectory.y) <= 90).all()
        assert (np.diff(trajectory.time_s) > 0).all()


# --- the whole import: parsed files with implausible positions, CRSs, times ------------------

@pytest.fixture(scope="module")
def images():
    from PIL import Image

    folder = os.path.join(FOLDER, "images")
    os.makedirs(folder, exist_ok=True)
    for k in range(3):
        Image.new("RGB", (64, 32)).save(os.path.join(folder, "pano_{}.jpg".format(k)))
    return folder


COORDINATES = st.one_of(st.floats(-1e8, 1e8), st.floats(-200, 200), st.sampled_from([0.0, 500000.0, 17.5, 48.0]))


@given(x=st.lists(COORDINATES, min_size=3, max_size=3), y=st.lists(COORDINATES, min_size=3, max_size=3),
       z=st.floats(-1e5, 1e5), angles=st.lists(st.floats(-720, 720), min_size=3, max_size=3),
       crs=st.sampled_from(["EPSG:4326", "EPSG:32633", "EPSG:25833", "EPSG:3857", "EPSG:2056", "EPSG:4979"]),
       target=st.sampled_from([None, "EPSG:32633", "EPSG:32617", "EPSG:4326", "EPSG:2056"]))
@settings(FUZZ, max_examples=80, suppress_health_check=list(HealthCheck))
def test_import_from_poses(images, x, y, z, angles, crs, target):
    lines = ["image,x,y,z,roll,pitch,heading"] + [
        "pano_{},{!r},{!r},{!r},{!r},{!r},{!r}".format(k, x[k], y[k], z, *angles) for k in range(3)]
    path = write("poses_import.csv", "\n".join(lines))
    try:
        result = import_stations(images, target, crs, poses_path=path)
    except InputError:
        return
    assert np.isfinite(result.stations.xyz_world).all()
    assert np.isfinite(result.stations.q_world_from_pano_wxyz).all()


# --- the layer readers: records as the adapters read them from a layer ----------------------

FIELD_VALUES = st.one_of(st.none(), st.floats(allow_nan=True, allow_infinity=True), st.integers(-2**63, 2**63),
                         st.text(max_size=8), st.sampled_from(["", "abc", "1.5", "nan", "ok", "no_points"]))


def records_for(schema, good):
    """Records of ``schema``: good values with some replaced by anything, or all NULL."""
    def damage(record, values):
        return {k: (values[k] if k in values else v) for k, v in record.items()}

    damaged = st.lists(st.fixed_dictionaries({}, optional={f.name: FIELD_VALUES for f in schema}),
                       min_size=1, max_size=3).map(lambda many: [damage(good, v) for v in many])
    all_null = st.integers(1, 3).map(lambda n: [{f.name: None for f in schema} for _ in range(n)])
    return st.one_of(damaged, all_null, st.just([]))


GOOD_STATION = {"station_id": 1, "image": "a.jpg", "path": "/x/a.jpg", "time": 1.0, "x": 500000.0,
                "y": 5400000.0, "z": 100.0, "qw": 1.0, "qx": 0.0, "qy": 0.0, "qz": 0.0, "heading": 90.0,
                "width": 64, "height": 32}
GOOD_DETECTION = dict(GOOD_STATION, det_id=1, **{"class": "stop"}, score=0.9, u0=10.0, v0=5.0, u1=20.0,
                      v1=15.0, n_views=1, code="DE:206", code_score=0.95)
GOOD_CANDIDATE = dict(GOOD_DETECTION, cand_x=500001.0, cand_y=5400001.0, cand_z=101.0, range_m=3.0,
                      n_points=40, normal_e=0.0, normal_n=-1.0, normal_u=0.0, quality=0.8, status="ok")


@given(records_for(STATION_FIELDS, GOOD_STATION))
@FUZZ
def test_stations_records(rows):
    stations = parses_or_input_error(Stations.from_records, rows)
    if stations is not None:
        assert np.isfinite(stations.xyz_world).all()


@given(records_for(DETECTION_FIELDS, {k: GOOD_DETECTION[k] for k in (f.name for f in DETECTION_FIELDS)}))
@FUZZ
def test_detections_records(rows):
    detections = parses_or_input_error(Detections.from_records, rows)
    if detections is not None and len(detections):
        assert np.isfinite(detections.ray_ends_world(10.0)).all()


@given(records_for(CANDIDATE_FIELDS, {k: GOOD_CANDIDATE[k] for k in (f.name for f in CANDIDATE_FIELDS)}))
@FUZZ
def test_candidates_records(rows):
    parses_or_input_error(ProjectionResult.from_records, rows)


def layer_values(field):
    """Values a layer read gives a field of this kind (numbers or NULL, text or NULL); a NaN
    is NULL there (``Field.value``), so it is left out."""
    if field.kind is int:
        return st.one_of(st.none(), st.integers(-2**53, 2**53))
    if field.kind is float:
        return st.one_of(st.none(), st.floats(allow_nan=False), st.integers(-2**53, 2**53))
    return st.one_of(st.none(), st.text(max_size=8), st.sampled_from(["", "ok", "no_points", "DE:206"]))


def layer_records(schema, good):
    """Records of ``schema`` as a layer read gives them: good values, some replaced."""
    def damage(record, values):
        return {k: (values[k] if k in values else v) for k, v in record.items()}

    return st.lists(st.fixed_dictionaries({}, optional={f.name: layer_values(f) for f in schema}),
                    min_size=0, max_size=3).map(lambda many: [damage(good, v) for v in many])


def outcome(reader, rows):
    """What ``reader`` makes of ``rows``: its result's fields, or the InputError's message."""
    try:
        result = reader(rows)
    except InputError as error:
        return str(error)
    fields = vars(result)
    if isinstance(result, ProjectionResult):
        fields = dict(fields, detections=vars(result.detections))
    return repr({k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in fields.items()})


READERS = [(Stations.from_records, STATION_FIELDS, GOOD_STATION),
           (Detections.from_records, DETECTION_FIELDS, GOOD_DETECTION),
           (ProjectionResult.from_records, CANDIDATE_FIELDS, GOOD_CANDIDATE)]


@pytest.mark.parametrize("reader, schema, good", READERS, ids=["stations", "detections", "candidates"])
def test_columns_read_as_the_records_they_hold(reader, schema, good):
    """A layer read into Columns (arrays, not a dict a feature) gives every reader the same
    result, or the same error, as the records themselves."""
    good = {f.name: good[f.name] for f in schema}

    @given(layer_records(schema, good))
    @FEW
    def check(rows):
        columns = Columns(schema)
        for row in rows:
            columns.append(row)
        assert len(columns) == len(rows)
        assert [dict(r) for r in columns] == [{f.name: f.value(r.get(f.name)) for f in schema} for r in rows]
        assert outcome(reader, columns) == outcome(reader, rows)

    check()


def test_columns_store_numbers_not_text():
    columns = Columns(STATION_FIELDS)
    with pytest.raises(ValueError):
        columns.append(dict(GOOD_STATION, x="east"))
    assert len(columns) == 0 and len(columns.column("x")) == 0   # nothing of the row was stored
    columns.append(dict(GOOD_STATION, time=None))
    assert columns[0]["time"] is None and np.isnan(columns.column("time")[0])
    assert columns[-1]["station_id"] == 1 and isinstance(columns[0]["station_id"], int)
    with pytest.raises(IndexError):
        columns[1]
    with pytest.raises(KeyError):
        columns[0]["no such field"]


# --- LAS/LAZ: truncated and bit-flipped -------------------------------------------------------

@pytest.fixture(scope="module")
def laz_bytes():
    scene = cloudgen.road_scene(length_m=10.0, density_per_m2=30.0, seed=1)
    path = os.path.join(FOLDER, "small.laz")
    cloudgen.write_scene(path, scene)
    with open(path, "rb") as f:
        return f.read()


def read_cloud(path):
    """Everything a stage reads of a cloud: header, CRS, every chunk."""
    header = pointcloud.read_header(path)
    pointcloud.crs_wkt_of_header(header)
    n = 0
    for chunk in pointcloud.iter_chunks(path, chunk_points=1000):
        n += len(pointcloud.xyz_of(chunk))
    return n


@pytest.mark.parametrize("fraction", [0.0, 0.01, 0.1, 0.2, 0.5, 0.9, 0.999])
def test_truncated_laz_is_an_input_error(laz_bytes, fraction):
    path = write("truncated.laz", laz_bytes[:int(len(laz_bytes) * fraction)])
    with pytest.raises(InputError):
        read_cloud(path)


@pytest.mark.parametrize("where", ["points start", "chunk table", "middle"])
def test_flipped_bytes_are_an_input_error(laz_bytes, where):
    """Damage where LAZ notices it: the chunk table's offset, the chunk table (whose count
    would make lazrs allocate gigabytes and abort the process) and the compressed points of
    a chunk: each an InputError naming the file, never a crash. (A flip elsewhere in the
    compressed points may decode to other values without any error: LAZ has no checksum.)"""
    data = bytearray(laz_bytes)
    offset_to_points = struct.unpack_from("<I", data, 96)[0]
    start = {"points start": offset_to_points, "chunk table": len(data) - 64,
             "middle": len(data) // 4}[where]
    data[start:start + 64] = bytes(b ^ 0xFF for b in data[start:start + 64])
    with pytest.raises(InputError, match="flipped.laz: the file is truncated or corrupt"):
        read_cloud(write("flipped.laz", bytes(data)))


@given(st.lists(st.tuples(st.integers(0, 10**9), st.integers(0, 7)), min_size=1, max_size=8))
@settings(FUZZ, max_examples=150, suppress_health_check=list(HealthCheck))
def test_bit_flips(laz_bytes, flips):
    """Any flipped bits: the cloud reads (a flip in an unused byte) or is an InputError."""
    data = bytearray(laz_bytes)
    for position, bit in flips:
        data[position % len(data)] ^= 1 << bit
    path = write("bitflip.laz", bytes(data))
    try:
        read_cloud(path)
    except InputError:
        pass


@given(st.binary(min_size=0, max_size=400))
@FEW
def test_random_bytes_with_las_signature(data):
    try:
        read_cloud(write("random.laz", b"LASF" + data))
    except InputError:
        pass


def test_structured_header_damage(laz_bytes):
    """The header fields that steer reading: point count, offset to points, format, sizes."""
    header = bytearray(laz_bytes)
    for offset, fmt in ((94, "<H"), (96, "<I"), (104, "B"), (105, "<H"), (107, "<I"), (100, "<I"),
                        (247, "<Q")):
        for value in (0, 1, 2**(8 * struct.calcsize(fmt)) - 1):
            damaged = bytearray(header)
            struct.pack_into(fmt, damaged, offset, value)
            try:
                read_cloud(write("header.laz", bytes(damaged)))
            except InputError:
                pass
