"""Upsample by a fixed scale, not by sizes computed in the graph: the same detector, faster.

    .venv/bin/python -m devtools.train.upsample --model models/roadsigns-int8.onnx \
        --out models/roadsigns-int8.onnx

The pyramid's ``F.interpolate(p, size=f.shape[-2:])`` exports as a ``Resize`` whose
``sizes`` are computed from ``Shape`` operators on the lateral feature map. In an int8 file
those maps are uint8 in the channels-last layout onnxruntime runs its convolutions in, so
each ``Shape`` costs a ``Transpose`` back and a ``DequantizeLinear`` of a whole feature map,
only to read four integers (six of each on the bundled detector, about 7 % of its time on
two cores; ``models/README.md``, "Upsampling by scale"). Every level of the pyramid doubles
the one below it at any input whose sides are multiples of the deepest stride, so each such
``Resize`` is given its constant ``scales`` instead, and the operators that computed its
``sizes`` are dropped. The file is checked by running both graphs on the same input: the
outputs must be identical, else nothing is written.
"""
from __future__ import annotations

import argparse
import json
import os
import sys

import numpy as np

from .. import REPO_ROOT
from .onnxfile import cpu_session, save_model, set_metadata

#: The metadata entry that records the rewrite.
UPSAMPLE_METADATA_KEY = "upsample"


def _example_input(model) -> np.ndarray:
    """A random batch of two at the model's input size: float in 0..1, or uint8 pixels."""
    from onnx import TensorProto

    tensor = model.graph.input[0].type.tensor_type
    shape = tuple(d.dim_value for d in tensor.shape.dim)
    if len(shape) != 4 or not all(shape[1:]):
        raise SystemExit(f"expected a 4-d image input with a fixed size but its batch, got "
                         f"{[d.dim_value or d.dim_param for d in tensor.shape.dim]}")
    rng = np.random.default_rng(0)
    if tensor.elem_type == TensorProto.UINT8:
        return rng.integers(0, 256, (2,) + shape[1:], dtype=np.uint8)
    return rng.random((2,) + shape[1:], dtype=np.float32)


def computed_size_resizes(model) -> list:
    """The ``Resize`` nodes whose ``sizes`` input is computed in the graph (not an initializer)."""
    constants = {i.name for i in model.graph.initializer}
    constants.update(o for n in model.graph.node if n.op_type == "Constant" for o in n.output)
    return [n for n in model.graph.node
            if n.op_type == "Resize" and len(n.input) == 4 and n.input[3] and n.input[3] not in constants]


def _run(model, feed: dict, extra_outputs=()) -> list:
    import onnx

    probe = onnx.ModelProto()
    probe.CopyFrom(model)
    for name in extra_outputs:
        probe.graph.output.add(name=name)
    return cpu_session(probe).run(None, feed)


def _drop_unused(graph) -> int:
    """Remove the nodes whose outputs nothing reads, then the initializers nothing reads."""
    dropped = 0
    wanted = {o.name for o in graph.output}
    while True:
        read = set(wanted)
        for node in graph.node:
            read.update(node.input)
        unused = [n for n in graph.node if not any(o in read for o in n.output)]
        if not unused:
            break
        for node in unused:
            graph.node.remove(node)
        dropped += len(unused)
    read = {name for node in graph.node for name in node.input}
    for init in [i for i in graph.initializer if i.name not in read]:
        graph.initializer.remove(init)
    return dropped


def upsample_by_scale(model_path: str, out_path: str) -> dict:
    """Write ``model_path`` with every computed-size ``Resize`` given its constant integer
    scales to ``out_path`` (may be the same file; written under a temporary name first).
    Returns ``{"resizes": n, "dropped_nodes": m}``; the metadata entry
    :data:`UPSAMPLE_METADATA_KEY` records it. A file without such a ``Resize`` is left as it
    is, and nothing is written (``{"resizes": 0, "dropped_nodes": 0}``). SystemExit, writing
    nothing, when a ``Resize`` does not scale by whole numbers at the model's input size or
    the outputs differ."""
    import onnx
    from onnx import numpy_helper

    model = onnx.load(model_path)
    resizes = computed_size_resizes(model)
    if not resizes:
        return {"resizes": 0, "dropped_nodes": 0}
    feed = {model.graph.input[0].name: _example_input(model)}
    probes = [name for node in resizes for name in (node.input[0], node.output[0])]
    values = _run(model, feed, probes)
    before = values[:len(model.graph.output)]
    seen = dict(zip(probes, values[len(model.graph.output):]))
    for node in resizes:
        x_shape, y_shape = seen[node.input[0]].shape, seen[node.output[0]].shape
        if len(x_shape) != len(y_shape) or any(y % x for x, y in zip(x_shape, y_shape)):
            raise SystemExit(f"{model_path}: {node.name or node.output[0]} resizes {x_shape} to {y_shape}, "
                             f"not by whole numbers")
        scales = np.array([y // x for x, y in zip(x_shape, y_shape)], np.float32)
        name = f"{node.output[0]}_scales"
        model.graph.initializer.append(numpy_helper.from_array(scales, name))
        node.input[2] = name
        del node.input[3]
    dropped = _drop_unused(model.graph)
    del model.graph.value_info[:]
    set_metadata(model, UPSAMPLE_METADATA_KEY,
                 json.dumps({"resizes_by_scale": len(resizes), "by": "devtools.train.upsample"}))
    onnx.checker.check_model(model)
    after = _run(model, feed)
    if not all(np.array_equal(a, b) for a, b in zip(before, after)):
        raise SystemExit(f"{model_path}: the graph upsampled by scale gives other outputs; nothing written")
    save_model(model, out_path)
    return {"resizes": len(resizes), "dropped_nodes": dropped}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m devtools.train.upsample", description=__doc__.splitlines()[0])
    ap.add_argument("--model", default=os.path.join(REPO_ROOT, "models", "roadsigns-int8.onnx"))
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    done = upsample_by_scale(a.model, a.out)
    if not done["resizes"]:
        print(f"{a.model} has no Resize with sizes computed in the graph: nothing written")
    else:
        print(f"wrote {a.out}: {done['resizes']} Resize by scale, {done['dropped_nodes']} nodes dropped")
    return 0


if __name__ == "__main__":
    sys.exit(main())
