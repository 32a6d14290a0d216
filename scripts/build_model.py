"""Build the shipped Processing model ``models/sign_inventory.model3``: the whole chain,
stations -> detections -> ground filter -> candidates -> signs (with review chips) -> signs
and poles found in the cloud alone -> the fused inventory, with
sensible defaults. Run with QGIS's Python (the plugin's provider must resolve its ids):

    QT_HASH_SEED=1 QT_QPA_PLATFORM=offscreen /usr/bin/python3 scripts/build_model.py

(``QT_HASH_SEED=1``: Qt writes each element's attributes in the order of its hash; with this
seed, the order of the committed file, so that a rebuild's diff shows only what changed.)

The README's single ``qgis_process`` command for the chain is this model.
"""
import os
import sys

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

from qgis.core import (  # noqa: E402
    Qgis,
    QgsApplication,
    QgsProcessingModelAlgorithm,
    QgsProcessingModelChildAlgorithm,
    QgsProcessingModelChildParameterSource,
    QgsProcessingModelOutput,
    QgsProcessingModelParameter,
    QgsProcessingOutputLayerDefinition,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QPointF  # noqa: E402

OUT = os.path.join(REPO_ROOT, "models", "sign_inventory.model3")
DOUBLE = Qgis.ProcessingNumberParameterType.Double


def add_input(model, parameter, help_text, x, y):
    parameter.setHelp(help_text)
    component = QgsProcessingModelParameter(parameter.name())
    component.setPosition(QPointF(x, y))
    model.addModelParameter(parameter, component)


def child(model, child_id, algorithm, sources, x, y, outputs=()):
    c = QgsProcessingModelChildAlgorithm(algorithm)
    c.setChildId(child_id)
    c.setDescription(child_id)
    c.setPosition(QPointF(x, y))
    for name, source in sources.items():
        c.addParameterSources(name, [source])
    model_outputs = {}
    for name, label, *temporary in outputs:
        output = QgsProcessingModelOutput(label)
        output.setChildId(child_id)
        output.setChildOutputName(name)
        if temporary:  # optional: a temporary layer unless the user names a file
            output.setMandatory(False)
            output.setDefaultValue(QgsProcessingOutputLayerDefinition("TEMPORARY_OUTPUT"))
        output.setPosition(QPointF(x + 200, y + 40))
        model_outputs[label] = output
    c.setModelOutputs(model_outputs)
    model.addChildAlgorithm(c)
    return child_id


def param(name):
    return QgsProcessingModelChildParameterSource.fromModelParameter(name)


def output_of(child_id, name="OUTPUT"):
    return QgsProcessingModelChildParameterSource.fromChildOutput(child_id, name)


def static(value):
    return QgsProcessingModelChildParameterSource.fromStaticValue(value)


def build():
    from roadsigns.core.detector import DEFAULT_CONFIDENCE, DEFAULT_STATION_SPACING_M  # after import_roadsigns()
    from roadsigns.core.signcodes import DEFAULT_CODE_CONFIDENCE
    horizon_views = QgsApplication.processingRegistry().algorithmById(
        "roadsigns:detectsigns").parameterDefinition("HORIZON_VIEWS")
    model = QgsProcessingModelAlgorithm("Sign inventory (whole chain)", "Road sign inventory", "roadsigns")
    model.setName("signinventory")
    model.setHelpContent({"ALG_DESC": (
        "The whole road-sign inventory: panorama stations from the trajectory, sign detection "
        "in the panoramas, ground filter and crop of the point cloud around the drive, "
        "projection of each detection into the cloud, and refinement and merging into the "
        "sign layer, with a review chip of every sign and the review report; then the sign "
        "panels and poles found in the cloud alone, fused with the image signs into the final "
        "inventory (Signs (fused): which sources found each sign, its condition, the signs "
        "the cameras missed)."),
        "ALG_CREATOR": "Road Sign Inventory"})
    file_ = Qgis.ProcessingFileParameterBehavior.File
    y = 60
    inputs = [
        (QgsProcessingParameterFile("TRAJECTORY", "Trajectory (CSV or SBET)", behavior=file_),
         "time,x,y,z,roll,pitch,heading CSV, or an Applanix SBET."),
        (QgsProcessingParameterFile("IMAGE_TIMES", "Image times (CSV)", behavior=file_),
         "image,time CSV of the panoramas."),
        (QgsProcessingParameterFile("IMAGES", "Panorama folder",
                                    behavior=Qgis.ProcessingFileParameterBehavior.Folder),
         "Folder of the equirectangular panoramas."),
        (QgsProcessingParameterCrs("TRAJECTORY_CRS", "Trajectory CRS", "EPSG:4326"),
         "CRS of the trajectory positions (ignored for an SBET)."),
        (QgsProcessingParameterCrs("TARGET_CRS", "Target CRS (projected, the point cloud's)"),
         "Projected CRS of the outputs: the point cloud's CRS."),
        (QgsProcessingParameterFile("POINT_CLOUD", "Point cloud (LAS/LAZ)", behavior=file_),
         "The drive's LiDAR cloud."),
        (QgsProcessingParameterFile("MODEL", "ONNX detector (empty: bundled)", behavior=file_,
                                    optional=True), "Your own ONNX detector, or empty for the bundled one."),
        (QgsProcessingParameterNumber("CONFIDENCE", "Minimum detection confidence", DOUBLE, DEFAULT_CONFIDENCE,
                                      False, 0, 1),
         "Detections scoring below this are dropped."),
        (QgsProcessingParameterNumber("STATION_SPACING_M", "Detect in a panorama at least every (m)", DOUBLE,
                                      DEFAULT_STATION_SPACING_M, False, 0),
         "Detects in as few panoramas as leave no more than this distance between one detected in and the "
         "next (the ones between are skipped); 0 detects in every panorama. On held-out test streets a "
         "panorama every 5 m found every sign, every 10 m lost 2 in 45."),
        (QgsProcessingParameterEnum(  # detectsigns' own choices, labels and default
            "HORIZON_VIEWS", horizon_views.description(), options=horizon_views.options(),
            defaultValue=horizon_views.defaultValue()),
         "The views of the horizon ring each panorama is cut into. 6 views, turned so that their seams ahead and "
         "behind fall inside the closer views ahead and behind, take about 0.8 times the detection time; on "
         "held-out test streets with a panorama every 5 m the chain found the same signs with either, and on a "
         "test drive one false sign more with 6 (flagged for review). 8 by default; 6 trades a little accuracy "
         "for speed."),
        (QgsProcessingParameterBoolean("READ_CODES", "Read the sign codes", True),
         "Reads what each sign says (its code, such as DE:274[50] for speed limit 50) with the sign-code "
         "classifier; unchecked, the code fields stay empty."),
        (QgsProcessingParameterFile("CLASSIFIER", "Sign-code classifier (empty: bundled)", behavior=file_,
                                    optional=True),
         "Your own ONNX sign-code classifier (format in models/README.md), or empty for the bundled one."),
        (QgsProcessingParameterFile("CODES_TABLE", "Sign codes table (empty: bundled)", behavior=file_,
                                    optional=True),
         "The codes table of your classifier (code;name;class, format in models/README.md), or empty for the "
         "bundled German table."),
        (QgsProcessingParameterNumber("CODE_CONFIDENCE", "Minimum code confidence", DOUBLE, DEFAULT_CODE_CONFIDENCE,
                                      False, 0, 1),
         "A sign's voted code whose support (code_score) is below this is left empty."),
    ]
    for name, default, help_text in (("LEVER_ARM_X", 0.0, "Lever arm x, forward (m)."),
                                     ("LEVER_ARM_Y", 0.0, "Lever arm y, right (m)."),
                                     ("LEVER_ARM_Z", 0.0, "Lever arm z, down (m)."),
                                     ("BORESIGHT_ROLL", 0.0, "Boresight roll (°)."),
                                     ("BORESIGHT_PITCH", 0.0, "Boresight pitch (°)."),
                                     ("BORESIGHT_YAW", 0.0, "Boresight yaw (°).")):
        inputs.append((QgsProcessingParameterNumber(name, help_text.rstrip("."), DOUBLE, default), help_text))
    help_content = dict(model.helpContent())
    for parameter, help_text in inputs:
        add_input(model, parameter, help_text, 120, y)
        help_content[parameter.name()] = help_text  # the model's help keeps parameter help
        y += 60
    model.setHelpContent(help_content)

    mount = {n: param(n) for n in ("LEVER_ARM_X", "LEVER_ARM_Y", "LEVER_ARM_Z", "BORESIGHT_ROLL",
                                   "BORESIGHT_PITCH", "BORESIGHT_YAW")}
    stations = child(model, "stations", "roadsigns:importtrajectory", dict(
        TRAJECTORY=param("TRAJECTORY"), IMAGE_TIMES=param("IMAGE_TIMES"), IMAGES=param("IMAGES"),
        TRAJECTORY_CRS=param("TRAJECTORY_CRS"), TARGET_CRS=param("TARGET_CRS"), **mount), 450, 80,
        [("OUTPUT", "Panorama stations")])
    codes = {n: param(n) for n in ("READ_CODES", "CLASSIFIER", "CODES_TABLE")}
    detections = child(model, "detections", "roadsigns:detectsigns", dict(
        STATIONS=output_of(stations), MODEL=param("MODEL"), CONFIDENCE=param("CONFIDENCE"),
        STATION_SPACING_M=param("STATION_SPACING_M"), HORIZON_VIEWS=param("HORIZON_VIEWS"), **codes),
        450, 220,
        [("OUTPUT", "Detections")])
    ground = child(model, "ground", "roadsigns:groundfilter", dict(
        INPUT=param("POINT_CLOUD"), CROP=output_of(stations), CROP_BUFFER=static(25.0),
        METHOD=static(0), ENGINE=static(0)), 450, 360, [("OUTPUT", "Ground-classified cloud")])
    candidates = child(model, "candidates", "roadsigns:projectdetections", dict(
        DETECTIONS=output_of(detections), POINT_CLOUD=output_of(ground), MAX_RANGE=static(30.0)),
        450, 500, [("OUTPUT", "Sign candidates")])
    signs = child(model, "signs", "roadsigns:refinesigns", dict(
        CANDIDATES=output_of(candidates), POINT_CLOUD=output_of(ground), MERGE_RADIUS=static(1.0),
        CODE_CONFIDENCE=param("CODE_CONFIDENCE"), CODES_TABLE=param("CODES_TABLE"), IMAGES=param("IMAGES")),
        450, 640,
        [("OUTPUT", "Signs"), ("OUTLINES", "Panel outlines"), ("REVIEW_REPORT", "Review report")])
    cloud = child(model, "cloudsigns", "roadsigns:findsignsincloud", dict(
        POINT_CLOUD=output_of(ground), STATIONS=output_of(stations)), 750, 500,
        [("POLES", "Poles", True)])  # its sign panels are an intermediate result: temporary
    child(model, "fused", "roadsigns:fusesigns", dict(
        SIGNS=output_of(signs), CLOUD_SIGNS=output_of(cloud), STATIONS=output_of(stations),
        IMAGES=param("IMAGES"), MODEL=param("MODEL"), CONFIDENCE=param("CONFIDENCE"),
        CODE_CONFIDENCE=param("CODE_CONFIDENCE"), **codes), 750, 640,
        [("OUTPUT", "Signs (fused)")])
    model.updateDestinationParameters()  # the children's model outputs become the model's
    return model


def main():
    app = QgsApplication([], False)
    app.initQgis()
    from devtools import import_roadsigns
    import_roadsigns()
    from roadsigns.provider.provider import RoadSignsProvider
    provider = RoadSignsProvider()
    QgsApplication.processingRegistry().addProvider(provider)
    model = build()
    ok, errors = model.validate()
    if not ok:
        sys.exit("The model does not validate: {}".format(errors))
    if not model.toFile(OUT):
        sys.exit("Cannot write {}".format(OUT))
    print("wrote", OUT)


if __name__ == "__main__":
    main()
