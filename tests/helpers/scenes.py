"""Parameters of generated scenes (devtools/scenegen) for qgis_process runs."""
import os


def scene_mount(scene):
    """A generated scene's camera mount as importtrajectory parameters."""
    lever, bore = scene["lever_arm_m"], scene["boresight_deg"]
    return dict(LEVER_ARM_X=lever[0], LEVER_ARM_Y=lever[1], LEVER_ARM_Z=lever[2],
                BORESIGHT_ROLL=bore["roll"], BORESIGHT_PITCH=bore["pitch"], BORESIGHT_YAW=bore["yaw"])


def scene_inputs(scene_dir, scene):
    """Trajectory, image times, panoramas, CRSs and mount of a generated scene."""
    return dict(TRAJECTORY=os.path.join(scene_dir, "trajectory.csv"),
                IMAGE_TIMES=os.path.join(scene_dir, "image_times.csv"),
                IMAGES=os.path.join(scene_dir, "images"), TRAJECTORY_CRS=scene["trajectory_crs"],
                TARGET_CRS=scene["target_crs"], **scene_mount(scene))


def ground_and_oracle(qgis_process, scene_dir, stations, work):
    """The scene's cloud ground-filtered around the stations (classes reset) and detections
    made from its true boxes (devtools/oracle.py): ``(ground.laz, detections.gpkg)`` in ``work``."""
    from devtools.oracle import oracle_detections

    ground = str(work / "ground.laz")
    run = qgis_process.run("roadsigns:groundfilter", INPUT=os.path.join(scene_dir, "cloud.laz"),
                           CROP=stations, CROP_BUFFER=25, RESET_CLASSES=True, OUTPUT=ground)
    assert run.returncode == 0, run.text
    detections = str(work / "detections.gpkg")
    assert oracle_detections(scene_dir, stations, detections) > 10
    return ground, detections


def render_scene(out_dir, preset="tiny", seed=1, *options, jobs=2):
    """``devtools.scenegen`` run as its own command (options as on its command line:
    ``"--no-lidar"``, ``"--pano-width", "1024"``, ...), its panoramas rendered by ``jobs``
    processes forked from that command, not from the tests' process (which holds detector
    sessions and their threads): the same files as :func:`devtools.scenegen.generate_scene`
    writes, in about half the time."""
    import subprocess
    import sys

    from devtools import REPO_ROOT

    run = subprocess.run([sys.executable, "-m", "devtools.scenegen", "--preset", preset, "--seed", str(seed),
                          "--jobs", str(jobs), "--out", str(out_dir), *map(str, options)],
                         cwd=REPO_ROOT, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return str(out_dir)


def seam_iou(a, b, width):
    """IoU of two panorama boxes ``u0, v0, u1, v1`` (px), columns compared modulo the
    panorama's ``width`` (a box may run past the seam): the best of ``a`` shifted by a
    width either way (devtools.train.metrics.iou_matrix)."""
    from devtools.train.metrics import iou_matrix

    return max(float(iou_matrix([a[0] + shift, a[1], a[2] + shift, a[3]], b)[0, 0])
               for shift in (-width, 0.0, width))
