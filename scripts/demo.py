"""The main job on the sample, through qgis_process, as an analyst's batch script would.

The sample is the generator's ``tiny`` scene (devtools/scenegen: 36 m of street with
panoramas, trajectory, LiDAR and reference signs), made on the fly into ``demo_out/sample``.
The chain is the shipped model ``roadsigns:signinventory`` (import trajectory -> detect
signs with the bundled model -> ground filter -> project detections -> refine signs with
review chips), then ``roadsigns:evaluate`` against the scene's reference signs.
"""
import json
import os
import sys

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools.qgisrun import QgisProcess  # noqa: E402
from devtools.scenegen import generate_scene  # noqa: E402


def main():
    out_dir = os.path.join(REPO_ROOT, "demo_out")
    sample = os.path.join(out_dir, "sample")
    if not os.path.exists(os.path.join(sample, "scene.json")):
        print("Generating the sample scene into {} ...".format(sample))
        generate_scene("tiny", seed=1, out_dir=sample, masks=False)
    with open(os.path.join(sample, "scene.json")) as f:
        scene = json.load(f)
    qgis = QgisProcess()
    out = lambda name: os.path.join(out_dir, name)  # noqa: E731

    def run(stage, **parameters):
        result = qgis.run("roadsigns:" + stage, **parameters)
        if result.returncode != 0:
            print(result.text)
            sys.exit("roadsigns:{} failed".format(stage))
        print("{:<18} {:6.1f} s  {}".format(stage, result.wall_s, (result.json["log"].get("info") or [""])[-1]))
        return result.json["results"]

    lever, bore = scene["lever_arm_m"], scene["boresight_deg"]
    # the shipped model: the whole chain in one qgis_process run, as in the README
    run("signinventory", TRAJECTORY=os.path.join(sample, "trajectory.csv"),
        IMAGE_TIMES=os.path.join(sample, "image_times.csv"),
        IMAGES=os.path.join(sample, "images"), TRAJECTORY_CRS=scene["trajectory_crs"],
        TARGET_CRS=scene["target_crs"], POINT_CLOUD=os.path.join(sample, "cloud.laz"),
        LEVER_ARM_X=lever[0], LEVER_ARM_Y=lever[1], LEVER_ARM_Z=lever[2],
        BORESIGHT_ROLL=bore["roll"], BORESIGHT_PITCH=bore["pitch"], BORESIGHT_YAW=bore["yaw"],
        CONFIDENCE=0.4, **{"stations:Panorama stations": out("stations.gpkg"),
                           "detections:Detections": out("detections.gpkg"),
                           "ground:Ground-classified cloud": out("ground.laz"),
                           "candidates:Sign candidates": out("candidates.gpkg"),
                           "signs:Signs": out("signs.gpkg"),
                           "signs:Panel outlines": out("panel_outlines.gpkg"),
                           "signs:Review report": out("review.html"),
                           "fused:Signs (fused)": out("inventory.gpkg"), "cloudsigns:Poles": out("poles.gpkg")})
    signs = out("inventory.gpkg")
    scores = run("evaluate", SIGNS=signs, REFERENCE=os.path.join(sample, "reference_signs.csv"),
                 MATCH_RADIUS=1.0, OUTPUT_REPORT=out("evaluation.html"))
    print("\nSign inventory: {} (images and cloud fused; style inventory.qml, review chips in signs_chips/)"
          .format(signs))
    print("Poles: {}".format(out("poles.gpkg")))
    print("Review report: {}".format(out("review.html")))
    print("Evaluation report: {}".format(scores["OUTPUT_REPORT"]))
    print("precision {PRECISION:.3f}  recall {RECALL:.3f}  class accuracy {CLASS_ACCURACY:.3f}  "
          "median error {MEDIAN_ERROR:.3f} m  p95 {P95_ERROR:.3f} m  height error {MEDIAN_HEIGHT_ERROR:.3f} m  "
          "azimuth error {MEDIAN_AZIMUTH_ERROR:.1f} deg".format(**scores))


if __name__ == "__main__":
    main()
