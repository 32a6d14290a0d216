"""Tiny real sign-code classifiers built with onnx.helper: the output depends on the crop's
mean colour only (GlobalAveragePool -> MatMul with a fixed weight -> Add a bias -> Softmax),
so a test knows what each crop must come out as.

With the default weights and names ``("DE:206", "DE:215", "other")`` the logits of an RGB
crop of mean colour (r, g, b) in 0..1 are ``(10 r, 10 b, 5)``: a red crop is ``DE:206``
(stop), a blue one ``DE:215`` (roundabout), a grey one ``other``. A pipeline that swapped
R and B would read red as blue.
"""
import json

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

NAMES = ("DE:206", "DE:215", "other")
#: (3, C): rows R, G, B of the mean colour; columns the names
WEIGHTS = np.array([[10.0, 0.0, 0.0],
                    [0.0, 0.0, 0.0],
                    [0.0, 10.0, 0.0]], np.float32)
BIAS = np.array([0.0, 0.0, 5.0], np.float32)


def logits_of(rgb_mean01, weights=WEIGHTS, bias=BIAS):
    """The model's logits for a crop of mean colour ``rgb_mean01`` (3 values in 0..1)."""
    return np.asarray(rgb_mean01, np.float64) @ np.asarray(weights, np.float64) + bias


def make_classifier(path, names=NAMES, side=32, batch="batch", logits=False, meta="default",
                    input_shape=None, input_type=TensorProto.FLOAT, output_rank=2, extra_outputs=0,
                    weights=WEIGHTS, bias=BIAS):
    """Write a classifier to ``path``; returns the path as a str.

    ``batch``: "batch" (dynamic) or an int (fixed). ``logits``: leave out the Softmax and say
    ``output = logits``. ``meta``: "default" (``names`` as JSON, ``task`` classify, the output
    kind), a dict (used as is) or None (no metadata). ``input_shape``: override the declared
    input (the weight's rows follow its channels). ``input_type``: the input's element type
    (cast to float inside). ``output_rank``: 3 adds an axis to the output.
    ``extra_outputs``: zero columns added to the output (C != number of names).
    """
    shape = list(input_shape) if input_shape is not None else [batch, 3, side, side]
    channels = shape[1] if len(shape) > 1 and isinstance(shape[1], int) else 3
    w = np.zeros((channels, np.shape(weights)[1] + extra_outputs), np.float32)
    rows = min(channels, 3)
    w[:rows, :np.shape(weights)[1]] = np.asarray(weights, np.float32)[:rows]
    b = np.concatenate([np.asarray(bias, np.float32), np.zeros(extra_outputs, np.float32)])
    nodes = [helper.make_node("Cast", ["images"], ["x"], to=TensorProto.FLOAT),
             helper.make_node("GlobalAveragePool", ["x"], ["pooled"]),
             helper.make_node("Flatten", ["pooled"], ["mean"], axis=1),
             helper.make_node("MatMul", ["mean", "w"], ["scaled"]),
             helper.make_node("Add", ["scaled", "b"], ["logits"])]
    last = "logits"
    if not logits:
        nodes.append(helper.make_node("Softmax", ["logits"], ["probs"], axis=1))
        last = "probs"
    out_shape = [shape[0], w.shape[1]]
    initializers = [numpy_helper.from_array(w, "w"), numpy_helper.from_array(b, "b")]
    if output_rank == 3:
        nodes.append(helper.make_node("Unsqueeze", [last, "axes"], ["out3"]))
        initializers.append(numpy_helper.from_array(np.array([1], np.int64), "axes"))
        last, out_shape = "out3", [shape[0], 1, w.shape[1]]
    nodes.append(helper.make_node("Identity", [last], ["output0"]))
    graph = helper.make_graph(
        nodes, "tinyclassifier",
        [helper.make_tensor_value_info("images", input_type, shape)],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, out_shape)],
        initializers)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    if meta == "default":
        meta = {"names": json.dumps(list(names)), "task": "classify"}
        if logits:
            meta["output"] = "logits"
    if meta:
        helper.set_model_props(model, meta)
    onnx.checker.check_model(model)
    onnx.save(model, str(path))
    return str(path)
