"""The main job on the bundled sample, through qgis_process, as an analyst's batch script would.

The sample is the generator's ``tiny`` scene (devtools/scenegen: 36 m of street, panoramas,
trajectory, LiDAR, reference signs), made on the fly into ``demo_out/sample``. The chain
runs the stages the plugin has today; the others are listed as still to come.
"""
import json
import os
import sys

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools.qgisrun import QgisProcess  # noqa: E402
from devtools.scenegen import generate_scene  # noqa: E402

CHAIN = ("importtrajectory", "detectsigns", "groundfilter", "projectdetections", "refinesigns",
         "evaluate")


def main():
    out_dir = os.path.join(REPO_ROOT, "demo_out")
    sample = os.path.join(out_dir, "sample")
    if not os.path.exists(os.path.join(sample, "scene.json")):
        print("Generating the sample scene into {} ...".format(sample))
        generate_scene("tiny", seed=1, out_dir=sample, masks=False)
    with open(os.path.join(sample, "scene.json")) as f:
        scene = json.load(f)
    qgis = QgisProcess()
    available = set(qgis("--json", "list").json["providers"]["roadsigns"]["algorithms"])

    def run(stage, **parameters):
        result = qgis.run("roadsigns:" + stage, **parameters)
        if result.returncode != 0:
            print(result.text)
            sys.exit("roadsigns:{} failed".format(stage))
        print("{:<18} {:6.1f} s  {}".format(stage, result.wall_s, "; ".join(
            result.json["log"].get("info", [])[-2:])))
        return result.json["results"]

    lever, bore = scene["lever_arm_m"], scene["boresight_deg"]
    stations = run("importtrajectory", TRAJECTORY=os.path.join(sample, "trajectory.csv"),
                   IMAGE_TIMES=os.path.join(sample, "image_times.csv"),
                   IMAGES=os.path.join(sample, "images"), TRAJECTORY_CRS=scene["trajectory_crs"],
                   TARGET_CRS=scene["target_crs"], LEVER_ARM_X=lever[0], LEVER_ARM_Y=lever[1],
                   LEVER_ARM_Z=lever[2], BORESIGHT_ROLL=bore["roll"], BORESIGHT_PITCH=bore["pitch"],
                   BORESIGHT_YAW=bore["yaw"], OUTPUT=os.path.join(out_dir, "stations.gpkg"))["OUTPUT"]
    ground = run("groundfilter", INPUT=os.path.join(sample, "cloud.laz"), CROP=stations,
                 CROP_BUFFER=20, RESET_CLASSES=True, OUTPUT=os.path.join(out_dir, "ground.laz"))
    print("\nOutputs in {}:".format(out_dir))
    print("  panorama stations  {}".format(stations))
    print("  ground-classified  {} ({} of {} points kept, {} ground, engine {})".format(
        ground["OUTPUT"], ground["POINTS_OUT"], ground["POINTS_IN"], ground["GROUND_POINTS"],
        ground["ENGINE_USED"]))
    missing = [s for s in CHAIN if "roadsigns:" + s not in available]
    detect_note = " (detectsigns needs a model: none is bundled yet)" if "roadsigns:detectsigns" in available else ""
    print("Stages still to come in the demo: {}{}".format(
        ", ".join(missing + ["detectsigns"] if detect_note else missing), detect_note))


if __name__ == "__main__":
    main()
