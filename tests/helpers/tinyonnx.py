"""Tiny ONNX "detectors" built with onnx.helper: the output is a constant tensor written by
the test (plus 0 x the input's mean, so the input is used and the batch follows it)."""
import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper


def make_model(path, output, input_shape=(1, 3, 64, 64), meta=None):
    """A model whose output is ``output`` (shape [1, a, b]) repeated over the batch."""
    raw = np.asarray(output, np.float32)
    graph = helper.make_graph(
        [helper.make_node("ReduceMean", ["images"], ["mean"], axes=[1, 2, 3], keepdims=0),
         helper.make_node("Reshape", ["mean", "shape"], ["mean3"]),
         helper.make_node("Mul", ["mean3", "zero"], ["nothing"]),
         helper.make_node("Add", ["raw", "nothing"], ["output0"])],
        "tiny",
        [helper.make_tensor_value_info("images", TensorProto.FLOAT, list(input_shape))],
        [helper.make_tensor_value_info("output0", TensorProto.FLOAT, ["batch", raw.shape[1], raw.shape[2]])],
        [numpy_helper.from_array(raw, "raw"), numpy_helper.from_array(np.zeros(1, np.float32), "zero"),
         numpy_helper.from_array(np.array([-1, 1, 1], np.int64), "shape")])
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    if meta:
        helper.set_model_props(model, meta)
    onnx.checker.check_model(model)
    onnx.save(model, str(path))
    return str(path)
