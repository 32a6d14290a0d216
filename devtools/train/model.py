"""A small CenterNet-style sign detector (PyTorch) and its ONNX export.

Backbone: plain residual stages to stride 32; top-down pyramid back to stride 4; one shared
head predicting a per-class centre heatmap (``nc`` channels) and, per cell, the centre
offset and log box size in stride units (4 channels). The exported graph decodes itself:
sigmoid, best class per cell, 3 x 3 max-pool peaks, top-k, giving ``[batch, K, 6]`` rows
x1, y1, x2, y2, score, class in input pixels (the plugin's "nms" layout).
"""
from __future__ import annotations

import json
import math
import os

import torch
import torch.nn as nn
import torch.nn.functional as F

STRIDE = 4
TOP_K = 100


class ConvBN(nn.Sequential):
    def __init__(self, cin, cout, k=3, stride=1, groups=1, act=True):
        super().__init__(nn.Conv2d(cin, cout, k, stride, k // 2, groups=groups, bias=False),
                         nn.BatchNorm2d(cout), nn.ReLU(inplace=True) if act else nn.Identity())


class ResBlock(nn.Module):
    def __init__(self, c):
        super().__init__()
        self.body = nn.Sequential(ConvBN(c, c), ConvBN(c, c, act=False))

    def forward(self, x):
        return F.relu(x + self.body(x))


class SepConv(nn.Sequential):
    """Depthwise 3 x 3 then pointwise: the cheap convolutions at high resolution."""

    def __init__(self, cin, cout):
        super().__init__(ConvBN(cin, cin, 3, groups=cin), ConvBN(cin, cout, 1))


#: The default widths (the 1.10 M detector bundled until 27 November; the bundled file is
#: wider, see its metadata): backbone stages at strides 4/8/16/32, pyramid, head.
ARCH_DEFAULT = {"widths": (32, 48, 96, 160), "fpn": 64, "head": 32}
#: The exported file's metadata key holding its network's widths (JSON of ``SignNet.arch``),
#: which ``--init`` from the file reads; files exported before 27 November lack it.
ARCH_METADATA_KEY = "architecture"


class SignNet(nn.Module):
    def __init__(self, num_classes: int = 6, widths=ARCH_DEFAULT["widths"], fpn: int = ARCH_DEFAULT["fpn"],
                 head: int = ARCH_DEFAULT["head"]):
        super().__init__()
        c4, c8, c16, c32 = widths
        self.num_classes = num_classes
        self.arch = {"widths": tuple(int(c) for c in widths), "fpn": int(fpn), "head": int(head)}
        self.stem = nn.Sequential(ConvBN(3, 16, 3, 2), ConvBN(16, c4, 3, 2))
        self.s8 = nn.Sequential(ConvBN(c4, c8, 3, 2), ResBlock(c8))
        self.s16 = nn.Sequential(ConvBN(c8, c16, 3, 2), ResBlock(c16), ResBlock(c16))
        self.s32 = nn.Sequential(ConvBN(c16, c32, 3, 2), ResBlock(c32))
        self.lat32 = ConvBN(c32, fpn, 1)
        self.lat16 = ConvBN(c16, fpn, 1)
        self.lat8 = ConvBN(c8, fpn, 1)
        self.smooth16 = ConvBN(fpn, fpn)
        self.smooth8 = SepConv(fpn, fpn)
        self.reduce8 = ConvBN(fpn, head, 1)
        self.lat4 = ConvBN(c4, head, 1)
        self.smooth4 = SepConv(head, head)
        self.head = SepConv(head, head)
        self.heatmap = nn.Conv2d(head, num_classes, 1)
        self.regression = nn.Conv2d(head, 4, 1)
        nn.init.constant_(self.heatmap.bias, -4.6)  # prior 0.01

    def forward(self, x):
        """x: [B, 3, H, W] RGB 0..1 -> heatmap logits [B, nc, H/4, W/4], regression [B, 4, H/4, W/4]."""
        f4 = self.stem(x)
        f8 = self.s8(f4)
        f16 = self.s16(f8)
        f32 = self.s32(f16)
        p = self.lat32(f32)
        p = self.smooth16(self.lat16(f16) + F.interpolate(p, size=f16.shape[-2:], mode="nearest"))
        p = self.smooth8(self.lat8(f8) + F.interpolate(p, size=f8.shape[-2:], mode="nearest"))
        p = self.reduce8(p)
        p = self.smooth4(self.lat4(f4) + F.interpolate(p, size=f4.shape[-2:], mode="nearest"))
        h = self.head(p)
        return self.heatmap(h), self.regression(h)


def widened(net: SignNet, widths, fpn: int, head: int) -> SignNet:
    """A wider SignNet that computes exactly what ``net`` computes (eval mode), to train on
    from there: each convolution's old outputs keep their weights and read nothing from the
    new input channels (zero weights); the new output channels start as a fresh network's
    and are read by no old channel until training moves those zeros. Batch norms of old
    channels keep their statistics. Every width at least ``net``'s."""
    big = SignNet(net.num_classes, widths, fpn, head)
    small_state = net.state_dict()
    convs = {name: m for name, m in big.named_modules() if isinstance(m, nn.Conv2d)}
    state = big.state_dict()
    with torch.no_grad():
        for name, value in state.items():
            old = small_state[name]
            if any(b < a for a, b in zip(old.shape, value.shape)):
                raise ValueError(f"{name}: {tuple(value.shape)} is narrower than {tuple(old.shape)}")
            module = convs.get(name.rsplit(".", 1)[0])
            if module is not None and name.endswith("weight") and module.groups == 1 and value.ndim == 4:
                value[:old.shape[0], old.shape[1]:] = 0.0     # old outputs ignore the new inputs
            value[tuple(slice(0, n) for n in old.shape)] = old
    big.load_state_dict(state)
    return big


def decode(heat_logits, regression, k: int = TOP_K):
    """Peaks of the heatmap -> ``[B, k, 6]`` x1, y1, x2, y2, score, class in input pixels."""
    heat = torch.sigmoid(heat_logits)
    score, cls = heat.max(dim=1, keepdim=True)  # one class per cell
    peak = F.max_pool2d(score, 3, stride=1, padding=1)
    score = score * (peak == score).to(score.dtype)
    b, _, h, w = score.shape
    scores, idx = score.reshape(b, h * w).topk(k, dim=1)
    ys = torch.div(idx, w, rounding_mode="floor")
    xs = idx - ys * w
    reg = regression.reshape(b, 4, h * w)
    gather = idx.unsqueeze(1).expand(b, 4, k)
    r = reg.gather(2, gather)
    classes = cls.reshape(b, h * w).gather(1, idx)
    cx = (xs.to(r.dtype) + r[:, 0]) * STRIDE
    cy = (ys.to(r.dtype) + r[:, 1]) * STRIDE
    bw = torch.exp(r[:, 2].clamp(max=8.0)) * STRIDE
    bh = torch.exp(r[:, 3].clamp(max=8.0)) * STRIDE
    return torch.stack([cx - bw / 2, cy - bh / 2, cx + bw / 2, cy + bh / 2, scores, classes.to(r.dtype)], dim=2)


class Exported(nn.Module):
    """The network with its decoder, as the ONNX file holds it."""

    def __init__(self, net: SignNet, k: int = TOP_K, score_power: float = 1.0):
        super().__init__()
        self.net, self.k, self.score_power = net, k, float(score_power)

    def forward(self, images):
        out = decode(*self.net(images), k=self.k)
        if self.score_power == 1.0:
            return out
        # a monotone remap of the scores (ranking unchanged): see calibration_power()
        return torch.cat([out[..., :4], out[..., 4:5].pow(self.score_power), out[..., 5:]], dim=-1)


#: Where an export puts the detector's own best-F1 threshold (its scores are calibrated to
#: it). The plugin's default CONFIDENCE (core.detector.DEFAULT_CONFIDENCE, 0.5) sits above
#: it since the second look keeps confirmed boxes under the threshold (models/README.md).
PLUGIN_DEFAULT_CONFIDENCE = 0.4


def calibration_power(best_threshold: float, target: float = PLUGIN_DEFAULT_CONFIDENCE) -> float:
    """The power p with best_threshold ** p = target: exported scores raised to p put the
    validation's best-F1 operating point at the plugin's default confidence."""
    return math.log(target) / math.log(best_threshold)


def export_onnx(net: SignNet, path: str, class_names, size_px: int = 640, extra_metadata=None,
                score_power: float = 1.0):
    """Write the decoded model to ``path`` (opset 17, dynamic batch) with Ultralytics-style
    metadata ``names``, ``task`` and ``imgsz`` the plugin reads, its upsampling by constant
    scales (:func:`devtools.train.upsample.upsample_by_scale`)."""
    import onnx

    from .upsample import upsample_by_scale

    net = net.eval().to(memory_format=torch.contiguous_format)
    model = Exported(net, score_power=score_power)
    dummy = torch.zeros(1, 3, size_px, size_px)
    tmp = path + ".tmp"
    torch.onnx.export(model, dummy, tmp, opset_version=17, input_names=["images"], output_names=["output0"],
                      dynamic_axes={"images": {0: "batch"}, "output0": {0: "batch"}}, dynamo=False)
    proto = onnx.load(tmp)
    meta = {"names": "{" + ", ".join(f"{k}: '{n}'" for k, n in enumerate(class_names)) + "}",
            "task": "detect", "imgsz": f"[{size_px}, {size_px}]", "stride": str(STRIDE),
            "author": "Road Sign Inventory (devtools/train)", "license": "see models/README.md",
            ARCH_METADATA_KEY: json.dumps(dict(net.arch, widths=list(net.arch["widths"])))}
    meta.update(extra_metadata or {})
    for key, value in meta.items():
        entry = proto.metadata_props.add()
        entry.key, entry.value = key, str(value)
    onnx.save(proto, path)
    os.remove(tmp)
    upsample_by_scale(path, path)     # the pyramid's Resize by constant scales (devtools.train.upsample)
    return path


def onnx_arch(onnx_path: str) -> dict:
    """The widths an exported file records (:data:`ARCH_METADATA_KEY`, written by
    :func:`export_onnx`), else :data:`ARCH_DEFAULT` (files exported before 27 November: a
    wider one's widths are then given with ``--widths``)."""
    import onnx

    meta = {p.key: p.value for p in onnx.load(onnx_path, load_external_data=False).metadata_props}
    recorded = json.loads(meta[ARCH_METADATA_KEY]) if ARCH_METADATA_KEY in meta else {}
    return dict(ARCH_DEFAULT, **{k: tuple(v) if k == "widths" else int(v) for k, v in recorded.items()})
