"""int8 static quantisation of the sign detector (onnxruntime.quantization).

    .venv/bin/python -m devtools.train.quantize --model models/roadsigns.onnx \
        --out bench/out/roadsigns-int8.onnx [--format qdq|qoperator] [--calibration 96]

Calibration images are fed exactly as ``core.detector.Detector`` feeds the model
(letterboxed 640 x 640, RGB 0..1): perspective views cut with ``ViewSet.default`` from the
panoramas of the *training* scenes (``bench/out/train/scenes``, seeds from 100 up; the
bench's seeds are never used) and 640-px tiles of GTSDB training images 0-499 (500-599
stay held out). The backbone and pyramid are quantised (convolutions with per-channel int8
weights, additions, resizes, ReLUs; activations uint8); the two 1 x 1 output
convolutions (heatmap, box regression) and the decoder after them (sigmoid, peaks, top-k,
box arithmetic) stay float, so scores and coordinates keep their resolution.
Weights use 7 bits (``reduce_range``): on
CPUs without VNNI (AVX2 only, as the development machine) onnxruntime's u8 x s8 kernels
add pairs of products in int16 and saturate with full 8-bit weights (scores off by up to
0.07 on a test model; 0.003 with 7 bits).
The metadata is copied and ``quantization`` added; the plugin runs the file as it runs
the float one. A QDQ file then takes the views' uint8 BGR pixels, channels last, instead of
the float input it quantises at once (``devtools.train.rawinput``; ``--float-input`` keeps
the float input).
"""
from __future__ import annotations

import argparse
import glob
import os
import sys
import tempfile

import numpy as np

from .. import REPO_ROOT, import_roadsigns
from . import data
from .rawinput import take_uint8_bgr

DEFAULT_SCENES = os.path.join(REPO_ROOT, "bench", "out", "train", "scenes")


def calibration_images(n: int, scene_root: str = DEFAULT_SCENES, seed: int = 0, gtsdb_share: float = 0.5):
    """``n`` BGR images: half panorama views of the training scenes, half GTSDB 0-499 tiles."""
    import cv2

    panorama = import_roadsigns("roadsigns.core.panorama")
    rng = np.random.default_rng(seed)
    n_gtsdb = int(round(n * gtsdb_share)) if glob.glob(os.path.join(scene_root, "*", "scene.json")) else n
    out = []
    rows = data.read_gtsdb(data.GTSDB_TRAIN_IDS)
    for k in rng.choice(len(rows), n_gtsdb, replace=False):
        image = cv2.imread(rows[int(k)][0])
        h, w = image.shape[:2]
        x, y = int(rng.integers(0, max(1, w - 640))), int(rng.integers(0, max(1, h - 640)))
        out.append(image[y:y + 640, x:x + 640])
    panos = sorted(glob.glob(os.path.join(scene_root, "*", "images", "*.jpg")))
    if panos and n > n_gtsdb:
        views = panorama.ViewSet.training(size_px=640)
        per_pano = 4
        for path in rng.choice(panos, -(-(n - n_gtsdb) // per_pano), replace=False):
            pano = panorama.read_panorama(str(path))
            cut = list(views.cut_all(pano))
            for j in rng.choice(len(cut), per_pano, replace=False):
                out.append(cut[int(j)])
    return out[:n]


class _Reader:
    """onnxruntime CalibrationDataReader over preprocessed images."""

    def __init__(self, input_name: str, images, size_px: int = 640):
        det = import_roadsigns("roadsigns.core.detector")
        import cv2

        self._items = iter([
            {input_name: cv2.dnn.blobFromImages([det.letterbox(im, size_px, size_px)[0]], 1.0 / 255.0, swapRB=True)}
            for im in images])

    def get_next(self):
        return next(self._items, None)


def output_conv_nodes(model) -> list:
    """Names of the convolutions whose outputs leave the network for the decoder (the
    heatmap and box-regression layers): no ReLU, addition, resize or convolution reads them."""
    consumers: dict = {}
    for n in model.graph.node:
        for i in n.input:
            consumers.setdefault(i, []).append(n.op_type)
    inner = {"Relu", "Add", "Conv", "Resize"}
    return [n.name for n in model.graph.node
            if n.op_type == "Conv" and not inner.intersection(consumers.get(n.output[0], []))]


def head_and_decoder_nodes(model) -> list:
    """The output convolutions and every node downstream of them (sigmoid, peaks, top-k,
    box arithmetic): kept float so scores and coordinates keep their resolution."""
    heads = set(output_conv_nodes(model))
    tainted, names = set(), []
    for n in model.graph.node:  # ONNX graphs are topologically sorted
        if n.name in heads or tainted.intersection(n.input):
            tainted.update(n.output)
            names.append(n.name)
    return names


def quantize(model_path: str, out_path: str, images, fmt: str = "qdq", per_channel: bool = True,
             reduce_range: bool = True, method: str = "minmax", keep_head_float: bool = True,
             op_types=None, uint8_input: bool = True) -> str:
    import onnx
    from onnxruntime.quantization import CalibrationMethod, QuantFormat, QuantType, quantize_static
    from onnxruntime.quantization.shape_inference import quant_pre_process

    model = onnx.load(model_path)
    input_name = model.graph.input[0].name
    dims = [d.dim_value for d in model.graph.input[0].type.tensor_type.shape.dim]
    size_px = dims[3] if len(dims) == 4 and dims[3] > 0 else 640
    exclude: list = []
    meta = {p.key: p.value for p in model.metadata_props}
    with tempfile.TemporaryDirectory() as tmp:
        pre = os.path.join(tmp, "pre.onnx")
        quant_pre_process(model_path, pre, skip_symbolic_shape=True)
        # node names survive pre-processing; re-read them there
        pre_model = onnx.load(pre)
        if keep_head_float:
            exclude = head_and_decoder_nodes(pre_model)
        quantize_static(
            pre, out_path, _Reader(input_name, images, size_px),
            quant_format=QuantFormat.QDQ if fmt == "qdq" else QuantFormat.QOperator,
            op_types_to_quantize=list(op_types) if op_types else None, per_channel=per_channel,
            reduce_range=reduce_range,
            activation_type=QuantType.QUInt8, weight_type=QuantType.QInt8, nodes_to_exclude=exclude,
            calibrate_method={"minmax": CalibrationMethod.MinMax, "percentile": CalibrationMethod.Percentile,
                              "entropy": CalibrationMethod.Entropy}[method],
            # the input is pixels / 255: quantised over 0..1 whatever the calibration images
            # hold, its uint8 values are the pixels (what devtools.train.rawinput relies on)
            extra_options={"ActivationSymmetric": False, "WeightSymmetric": True,
                           "TensorQuantOverrides": {input_name: [{"rmin": np.float32(0.0), "rmax": np.float32(1.0)}]}})
    q = onnx.load(out_path)
    del q.metadata_props[:]
    meta["quantization"] = (f"int8 static ({fmt}, {'per-channel' if per_channel else 'per-tensor'} "
                            f"{'7-bit' if reduce_range else '8-bit'} weights, "
                            f"{method} calibration on {len(images)} images; "
                            f"operators: {', '.join(op_types) if op_types else 'all'}; "
                            f"float head and decoder: {len(exclude)} nodes from "
                            f"{', '.join(output_conv_nodes(onnx.load(model_path)))})")
    for key, value in meta.items():
        entry = q.metadata_props.add()
        entry.key, entry.value = key, value
    onnx.save(q, out_path)
    if uint8_input and fmt == "qdq":
        take_uint8_bgr(out_path, out_path)
    return out_path


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m devtools.train.quantize", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns.onnx"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--format", choices=("qdq", "qoperator"), default="qdq")
    ap.add_argument("--calibration", type=int, default=96, help="calibration images")
    ap.add_argument("--method", choices=("minmax", "percentile", "entropy"), default="minmax")
    ap.add_argument("--per-tensor", action="store_true", help="per-tensor weight scales")
    ap.add_argument("--full-range", action="store_true",
                    help="8-bit weights; the default 7-bit weights avoid the int16 overflow of u8 x s8 "
                         "products on CPUs without VNNI (AVX2), which costs several %% of score there")
    ap.add_argument("--quantize-head", action="store_true", help="also quantise the two output convolutions")
    ap.add_argument("--ops", default="all", help="operator types to quantise, comma-separated, or 'all' "
                    "(onnxruntime's default set: Conv, Add, Resize, MaxPool, ...)")
    ap.add_argument("--scenes", default=DEFAULT_SCENES, help="training scenes for panorama views")
    ap.add_argument("--float-input", action="store_true",
                    help="keep the float [batch, 3, h, w] input (default for qdq: the views' uint8 BGR pixels)")
    a = ap.parse_args(argv)
    images = calibration_images(a.calibration, a.scenes)
    quantize(a.model, a.out, images, a.format, not a.per_tensor, not a.full_range, a.method, not a.quantize_head,
             None if a.ops == "all" else tuple(a.ops.split(",")), not a.float_input)
    print(f"wrote {a.out} ({os.path.getsize(a.out) / 1e6:.2f} MB) from {len(images)} calibration images")
    return 0


if __name__ == "__main__":
    sys.exit(main())
