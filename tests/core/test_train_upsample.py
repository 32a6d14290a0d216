"""devtools.train.upsample: a Resize whose sizes the graph computes gets constant scales; the
outputs stay identical, and the bundled detectors are written that way."""
import numpy as np
import onnx
import onnxruntime as ort
import pytest
from onnx import TensorProto, helper, numpy_helper

from devtools.train.upsample import UPSAMPLE_METADATA_KEY, computed_size_resizes, upsample_by_scale


def pyramid_model(path, side_px: int):
    """``x + upsample(maxpool(x))``, the upsampling's sizes read from ``Shape(x)`` as
    torch.onnx exports ``F.interpolate(p, size=x.shape[-2:])``."""
    nodes = [
        helper.make_node("MaxPool", ["x"], ["pooled"], kernel_shape=[2, 2], strides=[2, 2]),
        helper.make_node("Shape", ["pooled"], ["pooled_shape"]),
        helper.make_node("Slice", ["pooled_shape", "zero", "two"], ["batch_channels"]),
        helper.make_node("Shape", ["x"], ["x_shape"]),
        helper.make_node("Slice", ["x_shape", "two", "four"], ["sides"]),
        helper.make_node("Concat", ["batch_channels", "sides"], ["sizes"], axis=0),
        helper.make_node("Resize", ["pooled", "", "", "sizes"], ["up"], mode="nearest",
                         coordinate_transformation_mode="asymmetric", nearest_mode="floor"),
        helper.make_node("Add", ["x", "up"], ["y"]),
    ]
    ints = [numpy_helper.from_array(np.array([v], np.int64), name)
            for name, v in (("zero", 0), ("two", 2), ("four", 4))]
    graph = helper.make_graph(
        nodes, "pyramid",
        [helper.make_tensor_value_info("x", TensorProto.FLOAT, ["batch", 4, side_px, side_px])],
        [helper.make_tensor_value_info("y", TensorProto.FLOAT, ["batch", 4, side_px, side_px])], ints)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    onnx.checker.check_model(model)
    onnx.save(model, str(path))
    return str(path)


def run(path, x):
    return ort.InferenceSession(str(path), providers=["CPUExecutionProvider"]).run(None, {"x": x})[0]


def test_a_computed_size_resize_gets_constant_scales_and_the_same_outputs(tmp_path):
    source = pyramid_model(tmp_path / "pyramid.onnx", 16)
    assert len(computed_size_resizes(onnx.load(source))) == 1
    out = tmp_path / "scaled.onnx"
    done = upsample_by_scale(source, str(out))
    model = onnx.load(str(out))
    assert done == {"resizes": 1, "dropped_nodes": 5}
    assert computed_size_resizes(model) == []
    assert [n.op_type for n in model.graph.node] == ["MaxPool", "Resize", "Add"]
    (resize,) = [n for n in model.graph.node if n.op_type == "Resize"]
    scales = {i.name: numpy_helper.to_array(i) for i in model.graph.initializer}[resize.input[2]]
    assert scales.tolist() == [1, 1, 2, 2]
    assert len(resize.input) == 3
    assert {p.key: p.value for p in model.metadata_props}[UPSAMPLE_METADATA_KEY] == \
        '{"resizes_by_scale": 1, "by": "devtools.train.upsample"}'
    assert {i.name for i in model.graph.initializer} == {resize.input[2]}     # the sizes' constants gone
    x = np.random.default_rng(3).random((3, 4, 16, 16), dtype=np.float32)   # another batch than the check's
    assert np.array_equal(run(source, x), run(out, x))
    # a file with nothing left to rewrite is left alone
    assert upsample_by_scale(str(out), str(tmp_path / "again.onnx")) == {"resizes": 0, "dropped_nodes": 0}
    assert not (tmp_path / "again.onnx").exists()


def test_a_resize_by_a_fraction_is_refused_and_nothing_is_written(tmp_path):
    source = pyramid_model(tmp_path / "odd.onnx", 9)      # pooled to 4 x 4, sized back to 9 x 9
    out = tmp_path / "scaled.onnx"
    with pytest.raises(SystemExit, match="not by whole numbers"):
        upsample_by_scale(source, str(out))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["odd.onnx"]


@pytest.mark.parametrize("name", ["BUNDLED_MODEL", "BUNDLED_FLOAT_MODEL"])
def test_the_bundled_detectors_upsample_by_scale(name):
    from roadsigns.algorithms import paths
    model = onnx.load(getattr(paths, name))
    assert computed_size_resizes(model) == []
    assert sum(n.op_type == "Resize" for n in model.graph.node) == 3
    assert '"resizes_by_scale": 3' in {p.key: p.value for p in model.metadata_props}[UPSAMPLE_METADATA_KEY]
