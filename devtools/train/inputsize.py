"""Set the input height of an exported detector (float or int8) without retraining.

    .venv/bin/python -m devtools.train.inputsize --model models/roadsigns.onnx --height 384 \
        --out models/roadsigns.onnx

The detector is fully convolutional and its decoder reads the feature map's size from the
graph (``Shape`` operators), so the same weights run on views of another height at the same
pixel density. The plugin cuts its views at the model's input size (``imgsz``, height then
width): 640 x 384 horizon views of 80 degrees span +-26.7 degrees of elevation instead of
+-40 degrees, leaving out sky and road, and cost about 0.6 of the square views' time
(``models/README.md``, "Views that skip sky and road"). The file's ``imgsz`` metadata is
updated and ``input_height`` records the change; a quantised file keeps its calibration.

``--any-size`` (:func:`take_any_size`) declares the input's height and width symbolic
(``height``, ``width``) instead: the same graph, which then also runs on an image of its own
size, any multiple of 32 (the horizon seen as one band, ``core.panorama.BandView``). ``imgsz``
stays the size the views are cut at. The outputs at that size are checked identical, and
nothing is written otherwise.
"""
from __future__ import annotations

import argparse
import json
import os
import sys

from .. import REPO_ROOT
from .onnxfile import cpu_session, save_model, set_metadata


def metadata_imgsz(model) -> list:
    """The ``imgsz`` metadata entry of ``model`` (``[height, width]``), or ``[]``."""
    return json.loads({e.key: e.value for e in model.metadata_props}.get("imgsz", "[]"))


def set_input_height(model_path: str, out_path: str, height_px: int) -> None:
    """Write ``model_path`` with input height ``height_px`` (a multiple of the stride 32 of the
    deepest level) to ``out_path`` (may be the same file; written under a temporary name
    first), checked by running it once."""
    import numpy as np
    import onnx

    if height_px <= 0 or height_px % 32:
        raise SystemExit(f"the height must be a positive multiple of 32, got {height_px}")
    model = onnx.load(model_path)
    tensor = model.graph.input[0].type.tensor_type
    dims = tensor.shape.dim
    pixels = tensor.elem_type == onnx.TensorProto.UINT8       # uint8 [batch, h, w, 3] (devtools.train.rawinput)
    h_axis, w_axis = (1, 2) if pixels else (2, 3)
    imgsz = metadata_imgsz(model)
    width = 0
    if len(dims) == 4:          # the declared width, else (a file of any size) its imgsz's
        width = dims[w_axis].dim_value or (int(imgsz[1]) if len(imgsz) == 2 else 0)
    if not width:
        raise SystemExit(f"{model_path}: expected a float [batch, 3, height, width] or uint8 [batch, height, "
                         f"width, 3] input with a fixed width, or one in its imgsz metadata")
    old_height = dims[h_axis].dim_value or dims[h_axis].dim_param
    for axis, side in ((h_axis, int(height_px)), (w_axis, width)):   # a file of any size gets a fixed one
        dims[axis].ClearField("dim_param")
        dims[axis].dim_value = side
    del model.graph.value_info[:]            # shapes inferred for the old height
    set_metadata(model, "imgsz", f"[{height_px}, {width}]")
    set_metadata(model, "input_height", json.dumps({"from": old_height, "to": int(height_px)}))
    onnx.checker.check_model(model)
    session = cpu_session(model)
    blank = (np.zeros((1, height_px, width, 3), np.uint8) if pixels
             else np.zeros((1, 3, height_px, width), np.float32))
    out = session.run(None, {session.get_inputs()[0].name: blank})
    if out[0].ndim != 3 or out[0].shape[-1] != 6:
        raise SystemExit(f"{model_path} at height {height_px} gives outputs of shape {out[0].shape}")
    save_model(model, out_path)


#: The names of the symbolic input sides :func:`take_any_size` declares.
ANY_SIZE_DIMS = ("height", "width")


def take_any_size(model_path: str, out_path: str) -> None:
    """Write ``model_path`` with its input's height and width symbolic to ``out_path`` (may be
    the same file; written under a temporary name first). SystemExit, writing nothing, when
    the outputs at the file's ``imgsz`` differ or a 2 x 1.5 times larger image fails."""
    import numpy as np
    import onnx

    model = onnx.load(model_path)
    reference = onnx.ModelProto()
    reference.CopyFrom(model)
    tensor = model.graph.input[0].type.tensor_type
    dims = tensor.shape.dim
    pixels = tensor.elem_type == onnx.TensorProto.UINT8
    h_axis, w_axis = (1, 2) if pixels else (2, 3)
    if len(dims) != 4:
        raise SystemExit(f"{model_path}: expected a float [batch, 3, height, width] or uint8 [batch, height, "
                         f"width, 3] input")
    height, width = (dims[h_axis].dim_value, dims[w_axis].dim_value)
    if not (height and width):
        height, width = metadata_imgsz(model) or (0, 0)
    if not (height and width):
        raise SystemExit(f"{model_path}: neither its input nor its imgsz metadata gives a size to check")
    for axis, name in zip((h_axis, w_axis), ANY_SIZE_DIMS):
        dims[axis].ClearField("dim_value")
        dims[axis].dim_param = name
    del model.graph.value_info[:]
    onnx.checker.check_model(model)

    def image(h, w, seed):
        x = np.random.default_rng(seed).integers(0, 256, (1, h, w, 3), dtype=np.uint8)
        return x if pixels else np.ascontiguousarray(x.transpose(0, 3, 1, 2)).astype(np.float32) / 255.0

    old, new = cpu_session(reference), cpu_session(model)
    name = new.get_inputs()[0].name
    for seed in range(2):
        x = image(height, width, seed)
        if not all(np.array_equal(a, b) for a, b in zip(old.run(None, {name: x}), new.run(None, {name: x}))):
            raise SystemExit(f"{model_path}: other outputs with a symbolic input size; nothing written")
    big = new.run(None, {name: image(-(-3 * height // 64) * 32, 2 * width, 2)})[0]
    if big.ndim != 3 or big.shape[-1] != 6:
        raise SystemExit(f"{model_path}: a larger image gives outputs of shape {big.shape}; nothing written")
    save_model(model, out_path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m devtools.train.inputsize", description=__doc__.splitlines()[0])
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns.onnx"))
    ap.add_argument("--height", type=int, help="input height in pixels (multiple of 32)")
    ap.add_argument("--any-size", action="store_true", help="declare the input's height and width symbolic")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    if (a.height is None) == (not a.any_size):
        ap.error("give --height or --any-size")
    if a.any_size:
        take_any_size(a.model, a.out)
        print(f"wrote {a.out}: input height and width symbolic")
    else:
        set_input_height(a.model, a.out, a.height)
        print(f"wrote {a.out}: input height {a.height}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
