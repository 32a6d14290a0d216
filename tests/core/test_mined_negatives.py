"""devtools.train.codes.mined_negatives: the boxes the bundled detector finds on no sign of a
generated scene become ``other`` crops for the sign-code classifier; a box on a listed sign
never does."""
import json
import os

import cv2
import numpy as np

from devtools.train import codes, data


def test_a_box_counts_as_off_the_signs_unless_it_lies_mostly_on_one():
    signs = np.array([[100, 100, 140, 140]], float)
    boxes = np.array([[300, 300, 330, 330],     # far away
                      [102, 101, 139, 141],     # the sign itself
                      [136, 100, 176, 140],     # 4 of its 40 px inside the sign: a tenth
                      [130, 100, 170, 140]])    # a quarter inside
    assert codes.off_every_sign(boxes, signs, 2048).tolist() == [True, False, True, False]
    assert codes.off_every_sign(boxes, np.zeros((0, 4)), 2048).all()
    # a box across the seam (u1 past W) lies on a sign at the panorama's left edge
    assert not codes.off_every_sign(np.array([[2040, 100, 2060, 140]]), np.array([[0, 100, 12, 140]]), 2048)[0]


def _scene_with_two_signs(scene_dir, listed):
    """A grey panorama with a 30 km/h sign and a 50 km/h sign on the horizon; ``scene.json``
    lists the ones in ``listed`` (0, 1)."""
    tx = data.import_textures()
    pano = np.full((1024, 2048, 3), 120, np.uint8)
    pano += np.random.default_rng(0).integers(0, 12, pano.shape, dtype=np.uint8)
    signs = []
    for k, (variant, u) in enumerate((("30", 560), ("50", 1500))):
        tex = cv2.cvtColor(tx.sign_texture("prohibitory", variant, 48), cv2.COLOR_RGBA2BGRA)
        v = 500
        alpha = tex[..., 3:4].astype(np.float32) / 255.0
        roi = pano[v:v + 48, u:u + 48].astype(np.float32)
        pano[v:v + 48, u:u + 48] = (alpha * tex[..., :3] + (1 - alpha) * roi).astype(np.uint8)
        if k in listed:
            signs.append({"sign_id": k + 1, "box": [u, v, u + 47, v + 47], "visible_box": [u, v, u + 47, v + 47],
                          "facing": "front", "occlusion": 0.0})
    os.makedirs(os.path.join(scene_dir, "images"), exist_ok=True)
    cv2.imwrite(os.path.join(scene_dir, "images", "pano_00000.jpg"), pano, [cv2.IMWRITE_JPEG_QUALITY, 95])
    with open(os.path.join(scene_dir, "scene.json"), "w") as f:
        json.dump({"images": [{"image": "pano_00000.jpg", "signs": signs}], "signs": []}, f)


def test_the_detectors_boxes_on_no_listed_sign_are_mined_and_cached(tmp_path):
    one = str(tmp_path / "one-listed")
    both = str(tmp_path / "both-listed")
    _scene_with_two_signs(one, listed=(0,))
    _scene_with_two_signs(both, listed=(0, 1))
    cache = str(tmp_path / "mined-one.npz")
    mined = codes.mined_negatives([one], cache)
    assert len(mined) >= 1   # the unlisted 50 sign: on no sign the truth knows
    assert all(c.dtype == np.uint8 and c.ndim == 3 and c.shape[2] == 3 for c in mined)
    # the crop is the unlisted sign's, at u 1500: its red ring is in it (BGR: red in channel 2)
    red = [((c[..., 2] > 150) & (c[..., 1] < 90)).mean() for c in mined]
    assert max(red) > 0.05
    again = codes.mined_negatives([one], cache)
    assert len(again) == len(mined) and all(np.array_equal(a, b) for a, b in zip(again, mined))
    assert codes.mined_negatives([both], str(tmp_path / "mined-both.npz")) == []
