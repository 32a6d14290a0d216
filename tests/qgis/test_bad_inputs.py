"""The bad-input table (issue 19): every algorithm, every parser, deliberately bad inputs and
cancels at several points, run through ``qgis_process``.

Each row gives the algorithm, its parameters with the bad input (``@name``: a file of
``helpers/badinputs.build``; ``{out}``: the row's own empty output folder), the fragments the
message must hold and, for a cancel, the progress in percent at which the user cancels. For
every bad row: the algorithm fails (qgis_process would exit non-zero), the message holds the
fragments, nothing the user sees holds a Python traceback, and nothing is left in the
output folder. The ``OK`` rows must succeed, and their files have the permissions of the
user's umask (not 0600).

All rows run in ONE ``qgis_process`` start (helpers/processing_runner.py runs them with
``processing.run`` in the qgis_process that loaded the plugin); a few rows also run as
separate ``qgis_process run`` calls to check the exit code and the printed output.
``ISSUE`` maps the nine failures of the issue to their rows.
"""
import json
import os

import pytest
from helpers import badinputs

RUNNER = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "helpers",
                      "processing_runner.py")

IMPORT = dict(TRAJECTORY="@trajectory", IMAGE_TIMES="@image_times", IMAGES="@images",
              TRAJECTORY_CRS="EPSG:32633", TARGET_CRS="EPSG:32633", OUTPUT="{out}/stations.gpkg")
DETECT = dict(STATIONS="@stations", MODEL="@model", OUTPUT="{out}/detections.gpkg")
GROUND = dict(INPUT="@road", ENGINE=2, OUTPUT="{out}/ground.laz")
PROJECT = dict(DETECTIONS="@detections", POINT_CLOUD="@cloud", MAX_RANGE=30, OUTPUT="{out}/candidates.gpkg")
REFINE = dict(CANDIDATES="@candidates", POINT_CLOUD="@cloud", IMAGES="@panoramas", OUTPUT="{out}/signs.gpkg",
              OUTLINES="{out}/outlines.gpkg", SIGN_POINTS="{out}/sign_points.laz",
              REVIEW_REPORT="{out}/review.html")
EVALUATE = dict(SIGNS="@signs", REFERENCE="@reference", MATCH_RADIUS=1.0,
                OUTPUT_REPORT="{out}/evaluation.html")
PROBE = dict(OUTPUT="{out}/layer.gpkg", REPORT="{out}/report.html")
BASE = {"importtrajectory": IMPORT, "detectsigns": DETECT, "groundfilter": GROUND,
        "projectdetections": PROJECT, "refinesigns": REFINE, "evaluate": EVALUATE, "boundaryprobe": PROBE}
#: outputs of an earlier run in the output folder: a failed run must leave them as they were
EARLIER = {"layer.gpkg": "an earlier layer", "report.html": "an earlier report"}
CANCELLED = ["Cancelled", "nothing was written"]
OK = None


def row(row_id, algorithm, expect, cancel_at=None, existing=None, warn=None, **overrides):
    """A table row: parameters = the algorithm's good ones with ``overrides`` (None drops one);
    ``existing``: files already in the output folder ({name: text}); ``warn``: for a good
    run, a fragment of the warning it must give (empty inputs: a warning, nothing processed)."""
    parameters = dict(BASE[algorithm])
    parameters.update(overrides)
    return dict(id=row_id, algorithm=algorithm if algorithm == "boundaryprobe" else "roadsigns:" + algorithm,
                expect=expect, cancel_at=cancel_at, existing=existing or {}, warn=warn,
                parameters={k: v for k, v in parameters.items() if v is not None})


TABLE = [
    # --- importtrajectory: trajectory CSV, SBET, image times, poses, panoramas, CRSs
    row("import-empty-csv", "importtrajectory", ["traj_empty.csv", "is empty"], TRAJECTORY="@traj_empty"),
    row("import-header-only", "importtrajectory", ["traj_header_only.csv", "no data rows"],
        TRAJECTORY="@traj_header_only"),
    row("import-missing-columns", "importtrajectory", ["missing column(s) roll, pitch, heading"],
        TRAJECTORY="@traj_columns"),
    row("import-nan", "importtrajectory", ["traj_nan.csv, line 4, field 'y'", "finite number"],
        TRAJECTORY="@traj_nan"),
    row("import-duplicate-time", "importtrajectory", ["traj_dup.csv, line 5", "duplicated"],
        TRAJECTORY="@traj_dup"),
    row("import-extra-fields", "importtrajectory",
        ["traj_decimal_commas.csv, line 2", "9 fields", "header has 8", "decimal comma"],
        TRAJECTORY="@traj_decimal_commas"),
    row("import-semicolon-decimal-comma", "importtrajectory",
        ["traj_semicolon_decimal.csv, line 2, field 'time'", "1000,", "decimal comma"],
        TRAJECTORY="@traj_semicolon_decimal"),
    row("import-binary-csv", "importtrajectory", ["traj_binary.csv", "UTF-8"], TRAJECTORY="@traj_binary"),
    row("import-utf16-csv", "importtrajectory", ["traj_utf16.csv", "UTF-8"], TRAJECTORY="@traj_utf16"),
    row("import-trajectory-missing", "importtrajectory", ["Trajectory file not found", "does_not_exist.csv"],
        TRAJECTORY="@missing"),
    row("import-time-outside", "importtrajectory", ["times_late.csv, line 2", "outside the trajectory's span"],
        IMAGE_TIMES="@times_late"),
    row("import-image-missing", "importtrajectory", ["gone.jpg"], IMAGE_TIMES="@times_gone",
        FAIL_ON_MISSING_IMAGE=True),
    row("import-image-listed-twice", "importtrajectory", ["times_dup.csv, line 3", "already listed on line 2"],
        IMAGE_TIMES="@times_dup"),
    row("import-times-extra-fields", "importtrajectory",
        ["times_extra.csv, line 3", "3 fields", "header has 2", "decimal comma"], IMAGE_TIMES="@times_extra"),
    row("import-poses-extra-fields", "importtrajectory", ["poses_extra.csv, line 3", "10 fields", "header has 8"],
        TRAJECTORY=None, IMAGE_TIMES=None, POSES="@poses_extra"),
    row("import-not-equirectangular", "importtrajectory", ["w.jpg is 90 x 30 pixels", "twice as wide"],
        IMAGE_TIMES="@times_wide", IMAGES="@wide_images"),
    row("import-panorama-too-large", "importtrajectory", ["pano_0001.png", "more pixels than", "32768 x 16384"],
        IMAGE_TIMES="@times_big_bad", IMAGES="@big_images", FAIL_ON_MISSING_IMAGE=True),
    row("import-sbet-truncated", "importtrajectory", ["sbet_cut.out", "not a multiple of 136 bytes"],
        TRAJECTORY="@sbet_cut"),
    row("import-sbet-garbage", "importtrajectory", ["sbet_garbage.out", "out of range"],
        TRAJECTORY="@sbet_garbage"),
    row("import-target-geographic", "importtrajectory", ["is not projected"], TARGET_CRS="EPSG:4326"),
    row("import-lonlat-as-projected", "importtrajectory",
        ["drive_geo", "trajectory.csv, line 2", "WGS 84 / UTM zone 33N", "area of use", "longitude/latitude"],
        TRAJECTORY="@trajectory_lonlat"),
    row("import-metres-as-lonlat", "importtrajectory",
        ["trajectory.csv, line 2", "not a longitude/latitude", "WGS 84"], TRAJECTORY_CRS="EPSG:4326"),
    row("import-poses-lonlat-as-projected", "importtrajectory", ["poses.csv, line 2", "area of use"],
        TRAJECTORY=None, IMAGE_TIMES=None, POSES="@poses_lonlat"),
    row("import-folder-missing", "importtrajectory", ["Panorama folder not found"], IMAGES="@not_a_folder"),
    row("import-poses-and-trajectory", "importtrajectory", ["not both"], POSES="@poses"),
    row("import-no-trajectory", "importtrajectory", ["A trajectory file and an image times file are needed"],
        TRAJECTORY=None),
    row("import-cancel-reading", "importtrajectory", CANCELLED, cancel_at=5),
    row("import-cancel-writing", "importtrajectory", CANCELLED, cancel_at=90),

    # --- detectsigns: stations layer, model, labels
    row("detect-null-width", "detectsigns", ["station 1 has no value in the field width"],
        STATIONS="@stations_null_width"),
    row("detect-all-null", "detectsigns", ["has no value in the field"], STATIONS="@stations_all_null"),
    row("detect-empty-layer", "detectsigns", ["Panorama stations", "no feature"], STATIONS="@stations_empty"),
    row("detect-missing-fields", "detectsigns", ["missing field(s)", "qw"], STATIONS="@stations_no_pose"),
    row("detect-geographic-stations", "detectsigns", ["EPSG:4326", "projected CRS"], STATIONS="@stations_4326"),
    row("detect-model-missing", "detectsigns", ["ONNX model not found"], MODEL="@missing"),
    row("detect-model-not-onnx", "detectsigns", ["not_a_model.onnx"], MODEL="@model_text"),
    row("detect-labels-empty", "detectsigns", ["labels_empty.txt", "no class names"], LABELS="@labels_empty"),
    row("detect-cancel-detecting", "detectsigns", CANCELLED, cancel_at=40),
    row("detect-cancel-writing", "detectsigns", CANCELLED, cancel_at=95),

    # --- groundfilter: LAS/LAZ, crop layers, CRS
    row("ground-empty-crop", "groundfilter", ["crop layer", "no feature"], CROP="@crop_empty"),
    row("ground-crop-no-geometry", "groundfilter", ["crop layer", "no geometry"], CROP="@crop_null_geometry"),
    row("ground-crop-elsewhere", "groundfilter", ["crop", "does not overlap"], CROP="@crop_far"),
    row("ground-crop-points-no-buffer", "groundfilter", ["give a crop buffer"], CROP="@crop_points"),
    row("ground-not-las", "groundfilter", ["cloud_text.laz", "expected a LAS or LAZ file"], INPUT="@cloud_text"),
    row("ground-truncated-laz", "groundfilter", ["cloud_truncated.laz", "truncated or corrupt"],
        INPUT="@cloud_truncated"),
    row("ground-bit-flipped-laz", "groundfilter", ["cloud_flipped.laz", "corrupt"], INPUT="@cloud_flipped"),
    row("ground-cloud-without-crs", "groundfilter", ["road_nocrs.laz", "no coordinate reference system"],
        INPUT="@road_nocrs"),
    row("ground-local-coordinates", "groundfilter", ["road_local.laz", "area of use"], INPUT="@road_local"),
    row("ground-geographic-cloud-crs", "groundfilter", ["EPSG:4326", "projected CRS"], CLOUD_CRS="EPSG:4326"),
    row("ground-cloud-missing", "groundfilter", ["does_not_exist.csv", "does not exist"], INPUT="@missing"),
    row("ground-cancel-reading", "groundfilter", CANCELLED, cancel_at=20),
    row("ground-cancel-writing", "groundfilter", CANCELLED, cancel_at=80),

    # --- projectdetections: detections layer, cloud, CRSs
    row("project-cloud-without-crs", "projectdetections", ["cloud_nocrs.laz", "no coordinate reference system",
                                                           "Cloud CRS"], POINT_CLOUD="@cloud_nocrs"),
    row("project-4326-vs-crsless-cloud", "projectdetections", ["no coordinate reference system"],
        DETECTIONS="@detections_4326", POINT_CLOUD="@cloud_nocrs"),
    row("project-4326-vs-metric-cloud", "projectdetections", ["EPSG:4326", "EPSG:25833"],
        DETECTIONS="@detections_4326"),
    row("project-4326-vs-given-cloud-crs", "projectdetections", ["EPSG:4326", "projected CRS"],
        DETECTIONS="@detections_4326", POINT_CLOUD="@cloud_nocrs", CLOUD_CRS="EPSG:4326"),
    row("project-other-crs", "projectdetections", ["EPSG:32633", "EPSG:25833"], DETECTIONS="@detections_other_crs"),
    row("project-all-null", "projectdetections", ["Detection", "empty"], DETECTIONS="@detections_all_null"),
    row("project-truncated-laz", "projectdetections", ["cloud_truncated.laz", "truncated or corrupt"],
        POINT_CLOUD="@cloud_truncated"),
    row("project-bit-flipped-laz", "projectdetections", ["cloud_flipped.laz", "corrupt"],
        POINT_CLOUD="@cloud_flipped"),
    row("project-cancel", "projectdetections", CANCELLED, cancel_at=30),

    # --- refinesigns: candidates layer, cloud, panoramas, several outputs
    row("refine-cloud-without-crs", "refinesigns", ["cloud_nocrs.laz", "no coordinate reference system"],
        POINT_CLOUD="@cloud_nocrs"),
    row("refine-4326-vs-crsless-cloud", "refinesigns", ["no coordinate reference system"],
        CANDIDATES="@candidates_4326", POINT_CLOUD="@cloud_nocrs"),
    row("refine-4326-vs-metric-cloud", "refinesigns", ["EPSG:4326", "EPSG:25833"], CANDIDATES="@candidates_4326"),
    row("refine-all-null", "refinesigns", ["Detection", "empty"], CANDIDATES="@candidates_all_null"),
    row("refine-null-status", "refinesigns", ["field status is empty"], CANDIDATES="@candidates_null_status"),
    row("refine-text-in-number-field", "refinesigns", ["Sign candidates, feature 1", "field cand_x holds 'abc'"],
        CANDIDATES="@candidates_text"),
    row("refine-folder-missing", "refinesigns", ["Panorama folder not found", "no_such_folder"],
        IMAGES="@not_a_folder"),
    row("refine-report-unwritable", "refinesigns", ["Cannot write", "review.html"],
        REVIEW_REPORT="/proc/roadsigns/review.html"),
    row("refine-truncated-laz", "refinesigns", ["cloud_truncated.laz", "truncated or corrupt"],
        POINT_CLOUD="@cloud_truncated"),
    row("refine-cancel-refining", "refinesigns", CANCELLED, cancel_at=20),
    row("refine-cancel-after-chips", "refinesigns", CANCELLED, cancel_at=90),
    row("refine-cancel-sign-points", "refinesigns", CANCELLED, cancel_at=92),
    row("refine-cancel-writing-layers", "refinesigns", CANCELLED, cancel_at=96),

    # --- evaluate: sign layer, reference CSV or layer, report
    row("evaluate-geographic-signs", "evaluate", ["EPSG:4326", "projected CRS"], SIGNS="@signs_4326"),
    row("evaluate-reference-extra-fields", "evaluate",
        ["reference_extra.csv, line 3", "10 fields", "header has 9", "decimal comma"],
        REFERENCE="@reference_extra"),
    row("evaluate-reference-missing", "evaluate", ["Reference file not found"], REFERENCE="@missing"),
    row("evaluate-reference-duplicate-id", "evaluate", ["reference_dup.csv, line 3", "already used on line 2"],
        REFERENCE="@reference_dup"),
    row("evaluate-reference-lonlat", "evaluate", ["reference_lonlat.csv", "area of use"],
        REFERENCE="@reference_lonlat"),
    row("evaluate-reference-elsewhere", "evaluate", ["reference_far.csv", "do not overlap"],
        REFERENCE="@reference_far"),
    row("evaluate-reference-all-null", "evaluate", ["reference_all_null.gpkg", "no valid x, y, z"],
        REFERENCE="@reference_all_null"),
    row("evaluate-signs-no-class", "evaluate", ["no field 'class'"], SIGNS="@signs_no_class"),
    row("evaluate-signs-empty", "evaluate", ["The sign layer is empty"], SIGNS="@signs_empty"),
    row("evaluate-signs-all-null", "evaluate", ["Sign layer", "no valid x, y, z"], SIGNS="@signs_all_null"),
    row("evaluate-report-unwritable", "evaluate", ["Cannot write", "evaluation.html"],
        OUTPUT_REPORT="/proc/roadsigns/evaluation.html"),

    # --- the boundary itself: an algorithm that writes a layer and a report, then fails
    row("boundary-unexpected-error", "boundaryprobe", ["Unexpected error (TypeError: a bug over two lines)",
                                                       "QGIS message log"], MODE=1),
    row("boundary-rust-panic", "boundaryprobe", ["Unexpected error (PanicException"], MODE=2),
    row("boundary-disk-full", "boundaryprobe", ["No space left on device", "Nothing was written"], MODE=3),
    row("boundary-out-of-memory", "boundaryprobe", ["Out of memory"], MODE=4),
    row("boundary-cancel-at-the-end", "boundaryprobe", CANCELLED, MODE=5),
    row("boundary-earlier-outputs-kept", "boundaryprobe", ["Unexpected error"], existing=EARLIER, MODE=1),

    # --- the good runs: they succeed and their files get the umask's permissions
    row("ok-import-450-mpx-panorama", "importtrajectory", OK, IMAGE_TIMES="@times_big_ok", IMAGES="@big_images"),
    row("ok-detect", "detectsigns", OK),
    row("ok-ground", "groundfilter", OK, CROP="@crop"),
    row("ok-project-with-cloud-crs", "projectdetections", OK, POINT_CLOUD="@cloud_nocrs", CLOUD_CRS="EPSG:25833"),
    row("ok-refine", "refinesigns", OK),
    row("ok-evaluate", "evaluate", OK),
    row("ok-project-empty-layer", "projectdetections", OK, warn="No detections to project",
        DETECTIONS="@detections_empty"),
    row("ok-refine-empty-layer", "refinesigns", OK, warn="No candidates to refine", CANDIDATES="@candidates_empty"),
    row("ok-report-in-a-new-folder", "evaluate", OK, OUTPUT_REPORT="{out}/new/folder/evaluation.html"),
    row("ok-boundary-replaces-earlier-outputs", "boundaryprobe", OK, existing=EARLIER, MODE=0),
]
BAD = [r for r in TABLE if r["expect"] is not OK]
GOOD = [r for r in TABLE if r["expect"] is OK]

#: the nine failures of issue 19 and the rows that show each
ISSUE = {
    1: ["detect-empty-layer", "detect-geographic-stations", "ok-detect", "refine-report-unwritable"],
    2: ["import-cancel-writing", "detect-cancel-writing", "refine-cancel-after-chips"],
    3: ["ground-empty-crop"],
    4: ["import-lonlat-as-projected"],
    5: ["project-4326-vs-crsless-cloud", "refine-4326-vs-crsless-cloud"],
    6: ["evaluate-geographic-signs"],
    7: ["import-extra-fields", "evaluate-reference-extra-fields"],
    8: ["import-panorama-too-large", "ok-import-450-mpx-panorama", "detect-empty-layer",
        "evaluate-report-unwritable"],
    9: ["ok-ground", "ok-refine", "ok-evaluate"],
}

#: rows also run as their own ``qgis_process run`` (exit code and printed output)
CLI_ROWS = ["detect-empty-layer", "ground-empty-crop", "evaluate-geographic-signs"]


def resolve(value, data):
    if isinstance(value, str) and value.startswith("@"):
        return data[value[1:]]
    return value


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    return badinputs.build(str(tmp_path_factory.mktemp("bad-inputs-data")))


@pytest.fixture(scope="module")
def table(qgis_process, data, tmp_path_factory):
    """Every row run in one qgis_process; {row id: result}, and the umask."""
    work = tmp_path_factory.mktemp("bad-inputs-out")
    rows = [dict(r, parameters={k: resolve(v, data) for k, v in r["parameters"].items()}) for r in TABLE]
    table_path, results_path = str(work / "table.json"), str(work / "results.json")
    with open(table_path, "w") as f:
        json.dump({"work": str(work / "rows"), "rows": rows}, f)
    run = qgis_process("run", RUNNER, "--", "TABLE=" + table_path, "RESULTS=" + results_path, timeout=600)
    assert run.returncode == 0 and os.path.exists(results_path), run.text
    with open(results_path) as f:
        return json.load(f)


def user_text(result):
    return "\n".join([result["error"] or ""] + [text for _, text in result["seen"]])


def test_table_size():
    algorithms = {r["algorithm"] for r in BAD} - {"boundaryprobe"}
    assert len(BAD) >= 40 and len(algorithms) == 6
    assert all(sum(r["algorithm"] == a for r in BAD) >= 6 for a in algorithms)
    assert len({r["id"] for r in TABLE}) == len(TABLE)
    assert {r for rows in ISSUE.values() for r in rows} <= {r["id"] for r in TABLE}


@pytest.mark.parametrize("case", BAD, ids=[r["id"] for r in BAD])
def test_bad_input(table, case):
    result = table["rows"][case["id"]]
    shown = user_text(result)
    assert not result["ok"], "{} succeeded:\n{}".format(case["id"], shown)
    assert result["error_type"] == "QgsProcessingException", shown
    for fragment in case["expect"]:
        assert fragment in result["error"], "{!r} not in the message:\n{}".format(fragment, shown)
    assert "\n" not in result["error"].strip(), "not one line:\n" + result["error"]
    assert "Traceback" not in shown and 'File "' not in shown, shown
    assert [name for name, _ in result["files"]] == sorted(case["existing"]), "left behind: {}".format(
        result["files"])
    assert result["existing"] == case["existing"], "earlier outputs changed"
    if case["cancel_at"] is not None:
        assert result["cancelled_at"] is not None, "the run ended before it could be cancelled"


@pytest.mark.parametrize("case", GOOD, ids=[r["id"] for r in GOOD])
def test_good_run(table, case):
    result = table["rows"][case["id"]]
    shown = user_text(result)
    assert result["ok"], shown
    assert "Traceback" not in shown, shown
    if case["warn"]:
        assert any(kind == "warning" and case["warn"] in text for kind, text in result["seen"]), shown
    assert result["files"], "nothing written"
    assert all(result["existing"][name] != text for name, text in case["existing"].items()), "not replaced"
    want = {False: 0o666 & ~table["umask"], True: 0o777 & ~table["umask"]}
    for name, mode in result["files"]:
        assert not os.path.basename(name.rstrip("/")).startswith("."), "temporary file left: " + name
        assert mode == want[name.endswith("/")], "{}: mode {:o}, want {:o}".format(
            name, mode, want[name.endswith("/")])


def test_refine_writes_every_output(table):
    names = {name for name, _ in table["rows"]["ok-refine"]["files"]}
    assert {"signs.gpkg", "outlines.gpkg", "sign_points.laz", "review.html", "signs.qml",
            "signs_chips/"} <= names, names


def test_unexpected_errors_are_logged_not_shown(table):
    """An exception other than a user error reaches the message log with its traceback, and
    only there."""
    for row_id in ("boundary-unexpected-error", "boundary-rust-panic"):
        logged = [message for tag, _, message in table["rows"][row_id]["log"] if tag == "Road sign inventory"]
        assert any("Traceback" in m and "processAlgorithm" in m for m in logged), logged
    for result in table["rows"].values():
        for tag, _, message in result["log"]:
            if "Traceback" in message:
                assert tag == "Road sign inventory"


@pytest.mark.parametrize("row_id", CLI_ROWS)
def test_through_qgis_process(qgis_process, data, tmp_path, row_id):
    case = next(r for r in TABLE if r["id"] == row_id)
    parameters = {k: str(resolve(v, data)).replace("{out}", str(tmp_path)) for k, v in case["parameters"].items()}
    run = qgis_process.run(case["algorithm"], **parameters)
    assert run.returncode != 0
    for fragment in case["expect"]:
        assert fragment in run.text, run.text
    assert "Traceback" not in run.text, run.text
    assert os.listdir(tmp_path) == []
