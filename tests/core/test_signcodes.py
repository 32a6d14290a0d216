"""Sign codes: the codes table, the ONNX classifier (tiny real models from
``helpers.tinyclassifier`` whose answer follows the crop's mean colour), crops cut from
synthetic equirectangular panoramas (``helpers.synthpano``) and the vote across views."""
import json
import os

import cv2
import numpy as np
import pytest
from helpers.synthpano import disc_pano_box, paint_discs
from helpers.tinyclassifier import NAMES, logits_of, make_classifier
from onnx import TensorProto

from roadsigns.core import schema
from roadsigns.core import signcodes as sc
from roadsigns.core.errors import InputError
from roadsigns.core.panorama import PerspectiveView

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUNDLED_TABLE = os.path.join(REPO_ROOT, "models", "sign-codes-de.csv")
RED_BGR, BLUE_BGR = (0, 0, 255), (255, 0, 0)


def write(tmp_path, text, name="codes.csv", encoding="utf-8"):
    path = tmp_path / name
    path.write_bytes(text.encode(encoding))
    return str(path)


def softmax(x):
    e = np.exp(np.asarray(x, float) - np.max(x))
    return e / e.sum()


# --- the codes table ----------------------------------------------------------------------

def test_bundled_table_reads():
    table = sc.read_codes_table(BUNDLED_TABLE)
    with open(BUNDLED_TABLE, encoding="utf-8") as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")][1:]
    assert len(table) == len(rows) > 40
    assert table.codes[0] == "DE:101" and table.codes[-1] == rows[-1].split(";")[0]
    assert table.entry("DE:274[50]") == sc.SignCode("DE:274[50]", "speed limit 50", "prohibitory")
    assert table.entry("DE:206").class_name == "stop"
    assert "DE:215" in table and sc.OTHER_CODE not in table
    assert {e.class_name for e in table} == set(sc.SIGN_CLASSES)
    assert table.path == BUNDLED_TABLE
    with pytest.raises(KeyError):
        table.entry("DE:999")


def test_table_with_bom_crlf_comments_and_blanks(tmp_path):
    text = ("# comment\r\n\r\n  # indented comment\r\nCode ; Name ; Class\r\n"
            "DE:206;stop;stop\r\n# between\r\nDE:274[50]; speed limit 50 ;Prohibitory;\r\n")
    table = sc.read_codes_table(write(tmp_path, "\ufeff" + text))
    assert table.codes == ("DE:206", "DE:274[50]")
    assert table.entry("DE:274[50]") == sc.SignCode("DE:274[50]", "speed limit 50", "prohibitory")


HEADER = "code;name;class\n"


@pytest.mark.parametrize("text, where, expected", [
    ("# only comments\nDE:206;stop;stop\n", "line 2", "expected the header code;name;class, found DE:206;stop;stop"),
    ("code,name,class\nDE:206,stop,stop\n", "line 1", "expected the header code;name;class"),
    ("# c\n" + HEADER + "DE:206;stop\n", "line 3", "expected 3 fields separated by semicolons"),
    (HEADER + "DE:206;stop;stop;extra\n", "line 2", "found 4"),
    (HEADER + "DE:206;stop;stop\n;speed limit;prohibitory\n", "line 3", "the code is empty"),
    (HEADER + "DE:206;;stop\n", "line 2", "the name of DE:206 is empty"),
    (HEADER + "DE:206;stop;stop\n# c\nDE:206;stop again;stop\n", "lines 2 and 4", "DE:206 is there twice"),
    (HEADER + "DE:206;stop;octagon\n", "line 2",
     "unknown class octagon for DE:206; expected one of warning, prohibitory, mandatory, information, stop, yield"),
    (HEADER + "other;no code;warning\n", "line 2", "the code other is reserved"),
    (HEADER + "unlisted:warning;a warning;warning\n", "line 2", "the code unlisted:warning is reserved"),
    (HEADER + "DE:206;stop;stop\nback;a sign's back;stop\n", "line 3", "the code back is reserved"),
    ("# c\n" + HEADER + "# no rows\n", "", "holds no codes"),
    ("# c\n\n", "", "is empty: expected the header code;name;class"),
])
def test_bad_tables_name_the_line(tmp_path, text, where, expected):
    path = write(tmp_path, text)
    with pytest.raises(InputError) as e:
        sc.read_codes_table(path)
    message = str(e.value)
    assert path in message and expected in message
    message = message.replace(path, "PATH")
    assert (where + ":" in message) if where else ("line" not in message)


def test_table_not_found_and_not_utf8(tmp_path):
    with pytest.raises(InputError, match="not found"):
        sc.read_codes_table(str(tmp_path / "missing.csv"))
    path = write(tmp_path, HEADER + "DE:206;Straße;stop\n", encoding="latin-1")
    with pytest.raises(InputError, match="not UTF-8 text"):
        sc.read_codes_table(path)


# --- the classifier -----------------------------------------------------------------------

@pytest.fixture(scope="module")
def table():
    return sc.read_codes_table(BUNDLED_TABLE)


def solid(rgb, h=32, w=32):
    return np.full((h, w, 3), rgb, np.uint8)


def test_classifier_reads_its_metadata(tmp_path, table):
    clf = sc.CodeClassifier(make_classifier(tmp_path / "tiny.onnx"), table)
    assert clf.names == NAMES
    assert (clf.input_px, clf.max_batch, clf.crop_margin, clf.output_kind) == (32, 64, 0.15, "probabilities")
    line = clf.describe()
    assert line.startswith("tiny.onnx: 2 codes and 'other', input 32 x 32 px") and "\n" not in line
    meta = {"names": json.dumps(NAMES[:2]), "task": "classify", "crop_margin": "0.3"}
    clf = sc.CodeClassifier(make_classifier(tmp_path / "m.onnx", side=24, meta=meta,
                                            weights=np.eye(3, 2), bias=np.zeros(2)), table)
    assert (clf.names, clf.input_px, clf.crop_margin) == (("DE:206", "DE:215"), 24, 0.3)
    assert clf.describe().startswith("m.onnx: 2 codes, input 24 x 24 px")


def test_red_is_not_blue(tmp_path, table):
    """RGB crops of any size go through in RGB order: red reads DE:206, blue DE:215."""
    clf = sc.CodeClassifier(make_classifier(tmp_path / "tiny.onnx"), table)
    crops = [solid((255, 0, 0)), solid((0, 0, 255), 100, 60), solid((255, 0, 0), 8, 8),
             solid((90, 90, 90), 300, 200), solid((0, 0, 255), 20, 90)]
    codes, probs = clf.classify(crops)
    assert codes == ["DE:206", "DE:215", "DE:206", "other", "DE:215"]
    want = [softmax(logits_of(c[0, 0] / 255.0)).max() for c in crops]
    assert probs == pytest.approx(want, abs=1e-5)
    assert probs[0] == pytest.approx(np.exp(10) / (np.exp(10) + 1 + np.exp(5)), abs=1e-5)


def test_resizing_averages_the_colours(tmp_path, table):
    """A crop half red, half blue (left/right) keeps its mean when shrunk or enlarged."""
    clf = sc.CodeClassifier(make_classifier(tmp_path / "tiny.onnx"), table)
    for h, w in ((200, 120), (10, 6), (32, 32)):
        crop = solid((255, 0, 0), h, w)
        crop[:, w // 2:] = (0, 0, 255)
        mean = crop.reshape(-1, 3).mean(axis=0) / 255.0
        probs = clf.probabilities([crop])[0]
        assert probs == pytest.approx(softmax(logits_of(mean)), abs=0.01)


def test_logits_are_softmaxed(tmp_path, table):
    plain = sc.CodeClassifier(make_classifier(tmp_path / "p.onnx"), table)
    raw = sc.CodeClassifier(make_classifier(tmp_path / "l.onnx", logits=True), table)
    assert raw.output_kind == "logits"
    crops = [solid((200, 10, 30)), solid((40, 90, 220)), solid((90, 90, 90))]
    p_raw = raw.probabilities(crops)
    assert p_raw.sum(axis=1) == pytest.approx([1, 1, 1])
    assert p_raw == pytest.approx(plain.probabilities(crops), abs=1e-6)
    assert raw.classify(crops)[0] == ["DE:206", "DE:215", "other"]


def test_batches_keep_the_order(tmp_path, table):
    pattern = [(255, 0, 0), (0, 0, 255), (100, 100, 100)]
    want_of = dict(zip(pattern, ["DE:206", "DE:215", "other"]))
    crops = [solid(pattern[(k * k) % 3], 16 + k % 40, 16 + k % 23) for k in range(150)]
    want = [want_of[tuple(int(x) for x in c[0, 0])] for c in crops]
    dynamic = sc.CodeClassifier(make_classifier(tmp_path / "d.onnx"), table)
    assert dynamic.max_batch == 64
    codes, probs = dynamic.classify(crops)
    assert codes == want and probs.shape == (150,)
    fixed = sc.CodeClassifier(make_classifier(tmp_path / "f.onnx", batch=4), table)
    assert fixed.max_batch == 4
    assert fixed.classify(crops[:10])[0] == want[:10]  # 4 + 4 + 2 padded to 4
    one = sc.CodeClassifier(make_classifier(tmp_path / "one.onnx", batch=1), table)
    assert one.classify(crops[:5])[0] == want[:5]


def test_empty_input(tmp_path, table):
    clf = sc.CodeClassifier(make_classifier(tmp_path / "tiny.onnx"), table)
    codes, probs = clf.classify([])
    assert codes == [] and probs.shape == (0,)


@pytest.mark.parametrize("kwargs, expected", [
    (dict(meta=None), "its metadata needs 'names', a JSON list of the sign codes in output order"),
    (dict(meta={"task": "classify"}), "its metadata needs 'names'"),
    (dict(meta={"names": json.dumps(["DE:206", "DE:206", "other"])}), "names DE:206 more than once"),
    (dict(meta={"names": json.dumps(NAMES), "task": "detect"}), "is a detect model"),
    (dict(meta={"names": json.dumps(NAMES), "output": "scores"}), "output = scores; expected probabilities or logits"),
    (dict(meta={"names": json.dumps(NAMES), "crop_margin": "wide"}), "crop_margin = wide; expected a number"),
    (dict(input_shape=["batch", 1, 32, 32]), "of shape ['batch', 1, 32, 32]"),
    (dict(input_shape=["batch", 3, 32, 48]), "of shape ['batch', 3, 32, 48]"),
    (dict(input_shape=["batch", 3, 32]), "of shape ['batch', 3, 32]"),
    (dict(input_shape=["batch", 3, "h", "w"]), "of shape ['batch', 3, 'h', 'w']"),
    (dict(input_type=TensorProto.UINT8), "type tensor(uint8); supported: float [batch, 3, S, S]"),
    (dict(output_rank=3), "output of shape [1, 1, 3] for a batch of 1; supported: [batch, C] with C = 3"),
    (dict(extra_outputs=2), "output of shape [1, 5] for a batch of 1; supported: [batch, C] with C = 3"),
])
def test_unsupported_models(tmp_path, table, kwargs, expected):
    path = make_classifier(tmp_path / "bad.onnx", **kwargs)
    with pytest.raises(InputError) as e:
        sc.CodeClassifier(path, table)
    assert path in str(e.value) and expected in str(e.value)


def test_unknown_names_are_listed_with_the_table(tmp_path, table):
    names = ["DE:206", "XX:1", "other"] + ["XX:{}".format(k) for k in range(2, 9)]
    path = make_classifier(tmp_path / "u.onnx", meta={"names": json.dumps(names)},
                           weights=np.zeros((3, len(names))), bias=np.zeros(len(names)))
    with pytest.raises(InputError) as e:
        sc.CodeClassifier(path, table)
    message = str(e.value)
    assert path in message and BUNDLED_TABLE in message
    assert message.endswith(": XX:1, XX:2, XX:3, XX:4, XX:5 and 3 more")
    with pytest.raises(InputError, match="not found"):
        sc.CodeClassifier(str(tmp_path / "missing.onnx"), table)


def test_a_classifier_may_answer_signs_whose_code_the_table_lacks(tmp_path, table):
    """``unlisted:<class>`` names one of the six classes; another word after the prefix is
    an unknown name like any code the table lacks."""
    names = ["DE:206", sc.unlisted_code("prohibitory"), sc.unlisted_code("stop"), "other"]
    path = make_classifier(tmp_path / "k.onnx", meta={"names": json.dumps(names)},
                           weights=np.zeros((3, len(names))), bias=np.zeros(len(names)))
    clf = sc.CodeClassifier(path, table)
    assert clf.names == tuple(names)
    assert clf.describe().startswith("k.onnx: 1 codes, 2 classes of signs without a code and 'other'")
    names.insert(3, sc.BACK_CODE)   # the back of a sign, since 3 December
    path = make_classifier(tmp_path / "b.onnx", meta={"names": json.dumps(names)},
                           weights=np.zeros((3, len(names))), bias=np.zeros(len(names)))
    assert sc.CodeClassifier(path, table).describe().startswith(
        "b.onnx: 1 codes, 2 classes of signs without a code and 'other' and 'back'")
    names[1] = "unlisted:octagon"
    path = make_classifier(tmp_path / "bad.onnx", meta={"names": json.dumps(names)},
                           weights=np.zeros((3, len(names))), bias=np.zeros(len(names)))
    with pytest.raises(InputError, match="not in the sign codes table .*: unlisted:octagon$"):
        sc.CodeClassifier(path, table)


def test_only_codes_of_the_table_are_codes():
    assert [sc.is_code(n) for n in ("DE:206", "other", "", "unlisted:stop", "back")] == [True, False, False, False,
                                                                                         False]
    assert [sc.unlisted_code_class(n) for n in ("unlisted:stop", "unlisted:octagon", "DE:206", "stop")] == [
        "stop", None, None, None]
    assert sc.unlisted_code_class(sc.unlisted_code("yield")) == "yield"


# --- crops --------------------------------------------------------------------------------

W = 2048


def red_mask(crop_rgb):
    return (crop_rgb[..., 0] > 160) & (crop_rgb[..., 2] < 100)


def centroid(mask):
    """Centre of the mask in continuous pixels (within about half a pixel of the disc's
    centre: the painted disc's edge is quantised to whole panorama pixels)."""
    ys, xs = np.nonzero(mask)
    return xs.mean() + 0.5, ys.mean() + 0.5


def expected_side(box, width=W, margin=sc.DEFAULT_CROP_MARGIN):
    """The native side: the box's larger angular side x (1 + 2 margin), in panorama pixels."""
    u0, v0, u1, v1 = box
    el = np.radians(90.0 - (v0 + v1) / 2 / (width / 2) * 180.0)
    fov = max((u1 - u0) / width * 360.0 * np.cos(el), (v1 - v0) / (width / 2) * 180.0) * (1 + 2 * margin)
    return fov, int(round(fov / 360.0 * width))


def disc_area_px(radius_deg, fov_deg, side):
    """Area of a disc of angular radius r seen straight on by a pinhole view: pi (f tan r)^2."""
    f = side / 2 / np.tan(np.radians(fov_deg / 2))
    return np.pi * (f * np.tan(np.radians(radius_deg))) ** 2


def test_crop_is_centred_rectified_and_native(tmp_path):
    az, el, r = 40.0, 25.0, 4.0
    pano = paint_discs([(az, el, r, RED_BGR), (az + 20, el, r, BLUE_BGR)], W)
    box = disc_pano_box(az, el, r, W)
    crop = sc.cut_crop(pano, box)
    fov, side = expected_side(box)
    assert side == 59 and crop.shape == (side, side, 3) and crop.dtype == np.uint8
    mask = red_mask(crop)
    assert centroid(mask) == pytest.approx((side / 2, side / 2), abs=0.6)
    assert mask.sum() == pytest.approx(disc_area_px(r, fov, side), rel=0.04)
    # rectified: the disc is round (the panorama stretches it 1 / cos 25 deg = 1.10 wide)
    ys, xs = np.nonzero(mask)
    assert (xs.max() - xs.min()) == pytest.approx(ys.max() - ys.min(), abs=1)
    assert tuple(crop[side // 2, side // 2]) == (255, 0, 0)  # RGB: the BGR red came out red
    assert not (crop[..., 2] > 160).any()  # the blue disc 20 deg away is outside
    # the same pixels as the plugin's perspective views give (PerspectiveView.cut, BGR)
    view = PerspectiveView(az, el, fov, side, side)
    assert np.abs(view.cut(pano)[:, :, ::-1].astype(int) - crop).max() <= 2


def test_crop_of_a_disc_on_the_horizon_is_symmetric():
    pano = paint_discs([(0.0, 0.0, 5.0, RED_BGR)], W)
    crop = sc.cut_crop(pano, disc_pano_box(0.0, 0.0, 5.0, W))
    side = crop.shape[0]
    assert centroid(red_mask(crop)) == pytest.approx((side / 2, side / 2), abs=0.01)
    assert np.array_equal(crop, crop[::-1]) and np.array_equal(crop, crop[:, ::-1])


def test_crop_across_the_seam_is_whole():
    """A disc on the seam, on a random texture, comes out as the same disc turned to the
    front (the panorama rolled by half its width): columns wrap, pixel for pixel."""
    r = 5.0
    az = 180.0 - 0.5 * 360.0 / W  # half a pixel off: a crop column samples across the seam
    texture = np.random.default_rng(7).integers(0, 256, (W // 2, W, 3), dtype=np.uint8)
    texture[..., 2] //= 2  # no red in it (BGR)
    behind = np.where(red_mask(paint_discs([(az, 5.0, r, (0, 0, 255))], W)[..., ::-1])[..., None],
                      np.uint8(RED_BGR), texture)
    box = disc_pano_box(az, 5.0, r, W)
    assert box[0] < W < box[2]  # the detections layer's form
    seam_crop = sc.cut_crop(behind, box)
    front_crop = sc.cut_crop(np.roll(behind, W // 2, axis=1), box - [W / 2, 0, W / 2, 0])
    assert seam_crop.shape == front_crop.shape == (74, 74, 3)
    mask = red_mask(seam_crop)
    side = seam_crop.shape[0]
    assert centroid(mask) == pytest.approx((side / 2, side / 2), abs=0.6)
    assert mask.sum() == pytest.approx(disc_area_px(r, expected_side(box)[0], side), rel=0.04)
    assert np.abs(seam_crop.astype(int) - front_crop.astype(int)).max() <= 10  # fixed-point maps
    # the same box with both ends past W gives the same crop
    assert np.array_equal(sc.cut_crop(behind, box + [W, 0, W, 0]), seam_crop)


def test_crop_side_is_clamped():
    r = 30.0
    pano = paint_discs([(-60.0, 0.0, r, RED_BGR)], W)
    box = disc_pano_box(-60.0, 0.0, r, W)
    fov, native = expected_side(box)
    assert native == 444
    small = sc.cut_crop(pano, box)
    assert small.shape == (256, 256, 3)
    large = sc.cut_crop(pano, box, max_side_px=512)
    assert large.shape == (native, native, 3)
    # the same view, only sampled coarser: the disc covers the same share of it
    assert red_mask(small).mean() == pytest.approx(red_mask(large).mean(), rel=0.02)
    assert red_mask(large).sum() == pytest.approx(disc_area_px(r, fov, native), rel=0.02)
    tiny = sc.cut_crop(pano, (1000.0, 500.0, 1001.0, 501.0))
    assert tiny.shape == (8, 8, 3)


def test_crop_shrunk_below_native_does_not_alias():
    """Fine print (1-px stripes) in a crop cut at a quarter of its native side comes out an
    even grey, not a moire pattern."""
    pano = np.zeros((W // 2, W, 3), np.uint8)
    pano[:, ::2] = 255
    crop = sc.cut_crop(pano, (900.0, 400.0, 1100.0, 600.0), max_side_px=64)  # native 260 px
    assert crop.shape == (64, 64, 3)
    assert crop.mean() == pytest.approx(127.5, abs=3) and crop.std() < 12


def test_margin_widens_the_crop():
    az, el, r = -100.0, -10.0, 6.0
    pano = paint_discs([(az, el, r, RED_BGR)], W)
    box = disc_pano_box(az, el, r, W)
    narrow = sc.cut_crop(pano, box, margin=0.15)
    wide = sc.cut_crop(pano, box, margin=0.5)
    fov_n, side_n = expected_side(box, margin=0.15)
    fov_w, side_w = expected_side(box, margin=0.5)
    assert (narrow.shape[0], wide.shape[0]) == (side_n, side_w) == (89, 137)
    # native density both times: the disc has (about) the same size in pixels
    assert red_mask(wide).sum() == pytest.approx(red_mask(narrow).sum(), rel=0.04)
    assert red_mask(wide).mean() < 0.5 * red_mask(narrow).mean()
    assert centroid(red_mask(wide)) == pytest.approx((side_w / 2, side_w / 2), abs=0.6)


def test_crop_feeds_the_classifier(tmp_path, table):
    """Panorama (BGR) -> crop (RGB) -> classifier: a red disc reads DE:206, a blue one DE:215."""
    pano = paint_discs([(30.0, 5.0, 5.0, RED_BGR), (-150.0, 5.0, 5.0, BLUE_BGR)], W)
    crops = [sc.cut_crop(pano, disc_pano_box(a, 5.0, 5.0, W), margin=0.0) for a in (30.0, -150.0)]
    clf = sc.CodeClassifier(make_classifier(tmp_path / "tiny.onnx"), table)
    assert clf.classify(crops)[0] == ["DE:206", "DE:215"]


def test_the_classifier_cuts_big_signs_at_twice_its_input_side(tmp_path, table):
    """What the chain reads: a big sign is sampled at twice the classifier's input side (not
    its native 130 px), a small one at its native side, and after the shrink to the input
    side the picture is the native crop's; fine print still does not alias."""
    clf = sc.CodeClassifier(make_classifier(tmp_path / "tiny.onnx"), table)
    s = clf.input_px
    rng = np.random.default_rng(4)
    texture = cv2.GaussianBlur(rng.integers(0, 255, (W // 2, W, 3), np.uint8), (0, 0), 1.5)
    pano = paint_discs([(20.0, 0.0, 8.0, RED_BGR), (-60.0, 2.0, 1.2, BLUE_BGR)], W)
    grey = (pano == 90).all(axis=2)
    pano[grey] = texture[grey]                      # a textured street around the signs
    big, small = disc_pano_box(20.0, 0.0, 8.0, W), disc_pano_box(-60.0, 2.0, 1.2, W)
    native_big = sc.cut_crop(pano, big, clf.crop_margin)
    assert native_big.shape[0] > 2 * s
    read_big = clf.cut_crop(pano, big)
    assert read_big.shape == (2 * s, 2 * s, 3)
    a, b = (cv2.resize(c, (s, s), interpolation=cv2.INTER_AREA).astype(int) for c in (native_big, read_big))
    assert np.abs(a - b).mean() < 2.0 and np.abs(a - b).max() < 40
    assert np.array_equal(clf.cut_crop(pano, small), sc.cut_crop(pano, small, clf.crop_margin))
    # a big sign across the seam reads as the same sign turned to the front
    seam = paint_discs([(180.0, 0.0, 8.0, RED_BGR)], W)
    seam[(seam == 90).all(axis=2)] = texture[(seam == 90).all(axis=2)]
    front = np.roll(seam, W // 2, axis=1)
    at_seam, at_front = (clf.cut_crop(p, disc_pano_box(a, 0.0, 8.0, W)).astype(int)
                         for p, a in ((seam, 180.0), (front, 0.0)))
    assert at_seam.shape == at_front.shape == (2 * s, 2 * s, 3)
    assert np.abs(at_seam - at_front).mean() < 1.0
    stripes = np.zeros((W // 2, W, 3), np.uint8)
    stripes[:, ::2] = 255
    crop = clf.cut_crop(stripes, (900.0, 400.0, 1100.0, 600.0))
    assert crop.mean() == pytest.approx(127.5, abs=3) and crop.std() < 12


def test_a_box_found_in_a_view_crops_as_its_panorama_box():
    """fusesigns reads codes of boxes found in perspective views (viewclass): the crop
    around such a box is the one cut_crop cuts around the same sign's panorama box."""
    az, el, r = -30.0, 8.0, 3.0
    pano = paint_discs([(az, el, r, RED_BGR), (az + 15, el, r, BLUE_BGR)], W)
    pano_crop = sc.cut_crop(pano, disc_pano_box(az, el, r, W))
    view = PerspectiveView(az + 2.0, el - 1.0, 30.0, 320, 320)  # the sign a little off the view's centre
    mask = red_mask(view.cut(pano)[:, :, ::-1])
    ys, xs = np.nonzero(mask)
    box = (xs.min(), ys.min(), xs.max() + 1.0, ys.max() + 1.0)
    crop_view, native = sc.view_box_crop_view(view, box, W)
    crop = sc.cut_square_view(pano, crop_view, native)
    # the box's edges in the view are whole view pixels around a disc painted in whole
    # panorama pixels: the sign's angular size agrees to a few per cent
    assert crop.shape[0] == pytest.approx(pano_crop.shape[0], rel=0.06) and crop.shape[0] == native
    half_pixel_deg = 0.5 * 360.0 / W  # the painted disc's centre is good to half a panorama pixel
    assert crop_view.yaw_deg == pytest.approx(az, abs=half_pixel_deg)
    assert crop_view.pitch_deg == pytest.approx(el, abs=half_pixel_deg)
    assert red_mask(crop).mean() == pytest.approx(red_mask(pano_crop).mean(), rel=0.1)
    assert centroid(red_mask(crop)) == pytest.approx((native / 2, native / 2), abs=0.6)
    assert not (crop[..., 2] > 160).any()  # the blue disc 15 deg away is outside


def test_code_support_and_decision():
    # A: weights 10 x 0.9 + 10 x 0.7 = 16 of 16 + 1 x 0.8 (B): share 16 / 16.8, mean p 0.8
    code, support, views = sc.code_support(["A", "A", "B"], [0.9, 0.7, 0.8], [10.0, 10.0, 1.0])
    assert (code, views) == ("A", 2) and support == pytest.approx(16 / 16.8 * 0.8)
    assert sc.code_support([], [], []) == ("", pytest.approx(float("nan"), nan_ok=True), 0)
    table = sc.read_codes_table(BUNDLED_TABLE)
    never = pytest.fail  # the class's support is asked only when code and class disagree
    keep = sc.decide_code("DE:206", 0.8, 2, "stop", never, table)
    assert (keep.code, keep.name, keep.check, keep.klass) == ("DE:206", "stop", "", "stop")
    low = sc.decide_code("DE:206", 0.3, 2, "stop", never, table)
    assert (low.code, low.score, low.views) == ("", 0.3, 2)
    assert sc.decide_code("other", 0.9, 3, "stop", never, table).code == ""
    unknown = sc.decide_code(sc.unlisted_code("stop"), 0.9, 3, "stop", never, table)
    assert (unknown.code, unknown.name, unknown.check, unknown.klass, unknown.views) == ("", "", "", "stop", 3)
    won = sc.decide_code("DE:206", 0.8, 2, "mandatory", lambda: 0.5, table)
    assert (won.code, won.check, won.klass) == ("DE:206", sc.CLASS_FROM_CODE, "stop")
    lost = sc.decide_code("DE:206", 0.8, 2, "mandatory", lambda: 0.9, table)
    assert (lost.code, lost.check, lost.klass) == ("", sc.CODE_DROPPED, "mandatory")
    assert sc.class_support(["stop", "stop", "yield"], [0.8, 0.6, 0.6], "stop") == pytest.approx(1.4 / 2.0 * 0.7)
    assert sc.class_support(["yield"], [0.6], "stop") == 0.0


def test_bad_box():
    with pytest.raises(InputError, match="not four finite pixel coordinates"):
        sc.cut_crop(np.zeros((64, 128, 3), np.uint8), (1.0, float("nan"), 3.0, 4.0))


# --- the vote -----------------------------------------------------------------------------

def test_vote_weights_the_views():
    assert sc.vote(["A", "B", "A"], [0.9, 0.8, 0.5], [1.0, 3.0, 1.0]) == pytest.approx(("B", 2.4 / 3.8, 1))
    assert sc.vote(["A", "B", "A"], [0.9, 0.8, 0.5], [1.0, 1.0, 1.0]) == pytest.approx(("A", 1.4 / 2.2, 2))
    assert sc.vote(["A"], [0.3], [5.0]) == ("A", 1.0, 1)


def test_vote_ties_go_to_the_largest_single_weight():
    # A: 4 x 0.5 = 2; B: 1 x 1 + 1 x 1 = 2
    assert sc.vote(["A", "B", "B"], [0.5, 1.0, 1.0], [4.0, 1.0, 1.0]) == pytest.approx(("A", 0.5, 1))
    assert sc.vote(["B", "B", "A"], [1.0, 1.0, 0.5], [1.0, 1.0, 4.0]) == pytest.approx(("A", 0.5, 1))
    # a tie up to rounding (0.1 + 0.2 vs 0.3): still a tie
    assert sc.vote(["A", "A", "B"], [0.1, 0.2, 0.3], [1.0, 1.0, 1.5])[0] == "B"
    assert sc.vote(["A", "A", "B"], [0.1, 0.2, 0.3], [1.0, 1.0, 0.5])[0] == "A"


def test_vote_other_can_win_and_empty():
    assert sc.vote(["other", "DE:206", "other"], [0.9, 0.95, 0.8], [1.0, 1.0, 1.0]) == \
        pytest.approx(("other", 1.7 / 2.65, 2))
    assert sc.vote([], [], []) == ("", 0.0, 0)
    assert sc.vote(["A", "B"], [0.0, 0.0], [1.0, 2.0]) == ("B", 0.0, 1)  # no votes: the weightier view
    with pytest.raises(ValueError):
        sc.vote(["A"], [0.5, 0.5], [1.0])


def test_fields():
    assert schema.names(sc.CODE_FIELDS) == ("code", "code_score")
    assert [f.kind for f in sc.CODE_FIELDS] == [str, float]
    assert schema.names(sc.SIGN_CODE_FIELDS) == ("code", "code_name", "code_score", "code_views", "code_check")
    assert [f.kind for f in sc.SIGN_CODE_FIELDS] == [str, str, float, int, str]
