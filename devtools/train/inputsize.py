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
"""
from __future__ import annotations

import argparse
import json
import os
import sys

from .. import REPO_ROOT
from .onnxfile import cpu_session, save_model, set_metadata


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
    if len(dims) != 4 or not dims[w_axis].dim_value:
        raise SystemExit(f"{model_path}: expected a float [batch, 3, height, width] or uint8 [batch, height, "
                         f"width, 3] input with a fixed width")
    old_height = dims[h_axis].dim_value or dims[h_axis].dim_param
    dims[h_axis].ClearField("dim_param")
    dims[h_axis].dim_value = int(height_px)
    del model.graph.value_info[:]            # shapes inferred for the old height
    width = dims[w_axis].dim_value
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


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m devtools.train.inputsize", description=__doc__.splitlines()[0])
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns.onnx"))
    ap.add_argument("--height", type=int, required=True, help="input height in pixels (multiple of 32)")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    set_input_height(a.model, a.out, a.height)
    print(f"wrote {a.out}: input height {a.height}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
