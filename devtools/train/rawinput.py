"""Let an int8 detector take the views as OpenCV cuts them: uint8 BGR, channels last.

    .venv/bin/python -m devtools.train.rawinput --model models/roadsigns-int8.onnx \
        --out models/roadsigns-int8.onnx

A statically quantised detector (``devtools.train.quantize``) begins by quantising its float
input ``[batch, 3, height, width]`` (RGB in 0..1) to uint8 with scale 1/255 and zero point 0:
the pixels it was given, back again. The plugin makes that float input from OpenCV's uint8
BGR images (``cv2.dnn.blobFromImages``: the channels swapped, planes split, divided by 255),
and onnxruntime then transposes it back to channels last for its int8 convolutions. Here the
model's input becomes those images as they are, ``uint8 [batch, height, width, 3]`` in BGR
order: the ``QuantizeLinear`` is replaced by a ``Transpose`` that onnxruntime's layout
optimiser cancels against its own, and the first convolution's weights take the channels in
BGR order (the same int8 numbers, their input channels reversed). The metadata entry
``channel_order`` says ``BGR``; ``core.detector.Detector`` reads it.

The pixels reach the first convolution as the same uint8 numbers, so the outputs are
identical to the float-input file's on the same images; the file is checked so, and nothing
is written otherwise.
"""
from __future__ import annotations

import argparse
import os
import sys

import numpy as np

from .. import REPO_ROOT, import_roadsigns
from .onnxfile import cpu_session, save_model, set_metadata

#: The metadata entry with the input's channel order, as ``core.detector`` reads it.
CHANNEL_ORDER_KEY = import_roadsigns("roadsigns.core.detector").CHANNEL_ORDER_KEY


def _only(items, what: str, model_path: str):
    if len(items) != 1:
        raise SystemExit(f"{model_path}: expected one {what}, found {len(items)}")
    return items[0]


def take_uint8_bgr(model_path: str, out_path: str) -> None:
    """Write ``model_path`` (float input quantised at once with scale 1/255, zero point 0) with
    a ``uint8 [batch, height, width, 3]`` BGR input to ``out_path`` (may be the same file;
    written under a temporary name first). SystemExit, writing nothing, when the file does not
    begin so or the outputs differ."""
    import cv2
    import onnx
    from onnx import TensorProto, numpy_helper

    model = onnx.load(model_path)
    graph = model.graph
    inp = graph.input[0]
    dims = inp.type.tensor_type.shape.dim
    if inp.type.tensor_type.elem_type != TensorProto.FLOAT or len(dims) != 4 or dims[1].dim_value != 3 \
            or not dims[2].dim_value or not dims[3].dim_value:
        raise SystemExit(f"{model_path}: expected a float [batch, 3, height, width] input with fixed sides")
    height, width = dims[2].dim_value, dims[3].dim_value
    input_name = inp.name
    inits = {i.name: i for i in graph.initializer}
    readers = lambda name: [n for n in graph.node if name in n.input]   # noqa: E731
    quantize = _only(readers(input_name), f"node reading {input_name}", model_path)
    if quantize.op_type != "QuantizeLinear" or len(quantize.input) < 3:
        raise SystemExit(f"{model_path}: its input is read by a {quantize.op_type}, not quantised at once")
    scale = numpy_helper.to_array(inits[quantize.input[1]])
    zero = numpy_helper.to_array(inits[quantize.input[2]])
    if scale.size != 1 or abs(float(scale) * 255.0 - 1.0) > 1e-6 or zero.dtype != np.uint8 or int(zero) != 0:
        raise SystemExit(f"{model_path}: its input is quantised with scale {float(scale)} and zero point "
                         f"{zero}, not 1/255 and uint8 0")
    pixels = quantize.output[0]
    dequantize = _only(readers(pixels), f"node reading {pixels}", model_path)
    conv = _only(readers(dequantize.output[0]), f"node reading {dequantize.output[0]}", model_path)
    if dequantize.op_type != "DequantizeLinear" or conv.op_type != "Conv":
        raise SystemExit(f"{model_path}: the quantised input goes to a {dequantize.op_type} and a "
                         f"{conv.op_type}, not to the first convolution")
    weight_dq = next((n for n in graph.node if conv.input[1] in n.output), None)
    weight_name = weight_dq.input[0] if weight_dq is not None and weight_dq.op_type == "DequantizeLinear" \
        else conv.input[1]
    weight = numpy_helper.to_array(inits[weight_name])
    if weight.ndim != 4 or weight.shape[1] != 3:
        raise SystemExit(f"{model_path}: the first convolution's weights are {weight.shape}, not [out, 3, kh, kw]")

    reference = onnx.ModelProto()
    reference.CopyFrom(model)
    inits[weight_name].CopyFrom(numpy_helper.from_array(np.ascontiguousarray(weight[:, ::-1]), weight_name))
    position = list(graph.node).index(quantize)
    graph.node.remove(quantize)
    graph.node.insert(position, onnx.helper.make_node("Transpose", [input_name], [pixels], perm=[0, 3, 1, 2],
                                                      name="channels_first"))
    for name in quantize.input[1:]:
        if not readers(name):
            graph.initializer.remove(inits[name])
    batch = dims[0].dim_param or dims[0].dim_value
    new_input = onnx.helper.make_tensor_value_info(input_name, TensorProto.UINT8, [batch, height, width, 3])
    graph.input.remove(inp)
    graph.input.insert(0, new_input)
    del graph.value_info[:]
    set_metadata(model, CHANNEL_ORDER_KEY, "BGR")
    onnx.checker.check_model(model)

    images = [np.random.default_rng(k).integers(0, 256, (height, width, 3), dtype=np.uint8) for k in range(2)]
    images[1][:] = np.array([0, 128, 255], np.uint8)          # the ends of the range, per channel
    old, new = cpu_session(reference), cpu_session(model)
    for image in images:
        before = old.run(None, {input_name: cv2.dnn.blobFromImages([image], 1.0 / 255.0, swapRB=True)})
        after = new.run(None, {input_name: image[None]})
        if not all(np.array_equal(a, b) for a, b in zip(before, after)):
            raise SystemExit(f"{model_path}: the uint8 BGR input gives other outputs; nothing written")
    save_model(model, out_path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m devtools.train.rawinput", description=__doc__.splitlines()[0])
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx"))
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    take_uint8_bgr(a.model, a.out)
    print(f"wrote {a.out}: input uint8 [batch, height, width, 3], BGR")
    return 0


if __name__ == "__main__":
    sys.exit(main())
