"""devtools.train.codes: the faces of generated panoramas that train the sign-code classifier.
The front faces are cut with their codes, the back faces as the backs of signs (``back``), in
one reading of the panoramas; the cache holds codes, not a classifier's label indices, so
classifiers of other names share it. A tiny scene is written here: one panorama, a front
face, a back face, a small one and a hidden one."""
import json

import cv2
import numpy as np

from devtools.train import codes
from roadsigns.core import signcodes


def _scene(tmp_path):
    scene_dir = tmp_path / "scene"
    (scene_dir / "images").mkdir(parents=True)
    pano = np.full((256, 512, 3), 120, np.uint8)
    cv2.rectangle(pano, (100, 100), (129, 129), (30, 30, 220), -1)    # the front face: red
    cv2.rectangle(pano, (300, 100), (329, 129), (150, 150, 150), -1)  # the back face: grey
    cv2.imwrite(str(scene_dir / "images" / "pano_00000.jpg"), pano)
    signs = [{"sign_id": 1, "class": "stop", "variant": "stop"}, {"sign_id": 2, "class": "stop", "variant": "stop"}]
    seen = [{"sign_id": 1, "facing": "front", "occlusion": 0.0, "visible_box": [100, 100, 129, 129]},
            {"sign_id": 2, "facing": "back", "occlusion": 0.0, "visible_box": [300, 100, 329, 129]},
            {"sign_id": 2, "facing": "back", "occlusion": 0.0, "visible_box": [400, 100, 405, 105]},   # small
            {"sign_id": 1, "facing": "front", "occlusion": 0.8, "visible_box": [200, 100, 229, 129]}]  # hidden
    (scene_dir / "scene.json").write_text(json.dumps({"signs": signs, "images": [
        {"image": "pano_00000.jpg", "signs": seen}]}))
    return str(scene_dir)


def test_the_classifier_names_end_with_the_back_of_a_sign_and_other():
    names = codes.classifier_names()
    assert names[-2:] == [signcodes.BACK_CODE, "other"]
    assert names.count(signcodes.BACK_CODE) == 1


def test_front_faces_keep_their_codes_and_back_faces_are_backs(tmp_path):
    scene = _scene(tmp_path)
    cache = str(tmp_path / "pano.npz")
    names = ["DE:206", "other"]
    fronts = codes.pano_crops([scene], names, cache)
    assert [(label, side) for _, label, side in fronts] == [(0, 30.0)]
    crop = fronts[0][0]
    centre = crop[crop.shape[0] // 2, crop.shape[1] // 2].astype(int)
    assert np.abs(centre - [30, 30, 220]).max() < 20                  # BGR, as read (JPEG)
    # another classifier's names, the same cache: the label follows the code
    again = codes.pano_crops([scene], ["other", "back", "DE:206"], cache)
    assert [label for _, label, _ in again] == [2]
    backs = codes.back_crops([scene], cache)                          # the same reading's backs
    assert len(backs) == 1
    centre = backs[0][backs[0].shape[0] // 2, backs[0].shape[1] // 2].astype(int)
    assert np.abs(centre - 150).max() < 20                            # the grey back, not the red face
    assert len(codes.back_crops([], cache)) == 1                      # read from the cache
