"""The main job on the bundled sample, through qgis_process, as an analyst's batch script would.

For now the chain is its first stage: a small generated drive (trajectory CSV at 100 Hz,
image times, panoramas) is imported into panorama stations. Later stages join as they land.
Outputs go to ``demo_out/``.
"""
import os
import sys

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from devtools import trajsample  # noqa: E402
from devtools.qgisrun import QgisProcess  # noqa: E402


def main():
    out_dir = os.path.join(REPO_ROOT, "demo_out")
    sample_dir = os.path.join(out_dir, "sample")
    os.makedirs(sample_dir, exist_ok=True)
    sample = trajsample.make_sample(sample_dir, width_px=512, crs="geographic")
    print("Sample drive: {} panoramas, trajectory {}".format(len(sample["names"]),
                                                              sample["trajectory_csv"]))
    qgis = QgisProcess()
    stations = os.path.join(out_dir, "stations.gpkg")
    run = qgis.run("roadsigns:importtrajectory", TRAJECTORY=sample["trajectory_csv"],
                   IMAGE_TIMES=sample["image_times"], IMAGES=sample["images"],
                   TRAJECTORY_CRS="EPSG:4326", TARGET_CRS="EPSG:32633",
                   LEVER_ARM_X=0.4, LEVER_ARM_Z=-1.8, OUTPUT=stations)
    if run.returncode != 0:
        print(run.text)
        sys.exit("roadsigns:importtrajectory failed")
    for line in run.json["log"].get("info", []):
        print("  " + line)
    print("Stations: {} ({:.1f} s)".format(stations, run.wall_s))
    from osgeo import ogr
    dataset = ogr.Open(stations)  # keep a reference: the layer dies with its dataset
    layer = dataset.GetLayer(0)
    print("{:>4} {:<14} {:>12} {:>13} {:>8} {:>8}".format("id", "image", "x", "y", "z", "heading"))
    for feature in layer:
        print("{:>4} {:<14} {:>12.3f} {:>13.3f} {:>8.3f} {:>8.3f}".format(
            feature["station_id"], feature["image"], feature["x"], feature["y"], feature["z"],
            feature["heading"]))
    print("Stages still to come: detectsigns, groundfilter, projectdetections, refinesigns, evaluate")


if __name__ == "__main__":
    main()
