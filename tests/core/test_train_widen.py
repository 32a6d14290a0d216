"""devtools.train.model.widened: a wider detector that starts from the narrow one's function.

Training needs torch (devtools/train/requirements.txt), which the plugin's own setup does not
install: these tests run where it is installed and are skipped elsewhere.
"""
import pytest
from helpers.trainedlooking import trained_looking

torch = pytest.importorskip("torch")

from devtools.train.model import ARCH_DEFAULT, SignNet, widened  # noqa: E402


def test_widened_network_computes_the_same_heatmaps_and_boxes():
    torch.manual_seed(0)
    small = trained_looking(SignNet(6))
    big = widened(small, widths=(48, 64, 160, 256), fpn=96, head=48).eval()
    assert big.arch == {"widths": (48, 64, 160, 256), "fpn": 96, "head": 48}
    assert sum(p.numel() for p in big.parameters()) > 2 * sum(p.numel() for p in small.parameters())
    x = torch.rand(2, 3, 96, 128)
    with torch.no_grad():
        (h0, r0), (h1, r1) = small(x), big(x)
    assert torch.allclose(h0, h1, atol=1e-4) and torch.allclose(r0, r1, atol=1e-4)
    # and the new channels are not dead: the zeros that hide them get a gradient
    h1, r1 = big(x)
    (h1.sum() + r1.sum()).backward()
    hidden = big.s16[0][0].weight.grad[:96, 48:]   # stride-16 stage: old outputs, new inputs (48 -> 64)
    assert hidden.abs().sum() > 0

def test_widening_only_part_of_the_network_and_refusing_to_narrow():
    small = trained_looking(SignNet(6))
    deep = widened(small, widths=(32, 48, 128, 224), fpn=ARCH_DEFAULT["fpn"], head=ARCH_DEFAULT["head"]).eval()
    x = torch.rand(1, 3, 64, 64)
    with torch.no_grad():
        assert torch.allclose(small(x)[0], deep(x)[0], atol=1e-4)
    with pytest.raises(ValueError, match="narrower"):
        widened(small, widths=(16, 48, 96, 160), fpn=64, head=32)


def test_an_exported_file_records_its_widths_for_init(tmp_path):
    """``--init`` from an exported file builds the network of the file's recorded widths
    (``onnx_arch``), so a wider file needs no --widths; an older file without the record
    gives the defaults."""
    import onnx

    from devtools.train.model import ARCH_METADATA_KEY, export_onnx, onnx_arch

    wide = widened(SignNet(6), widths=(32, 64, 128, 256), fpn=96, head=32)
    path = export_onnx(wide, str(tmp_path / "wide.onnx"), [str(k) for k in range(6)], size_px=64)
    assert onnx_arch(path) == wide.arch
    proto = onnx.load(path)
    kept = [p for p in proto.metadata_props if p.key != ARCH_METADATA_KEY]
    del proto.metadata_props[:]
    proto.metadata_props.extend(kept)
    onnx.save(proto, str(tmp_path / "old.onnx"))
    assert onnx_arch(str(tmp_path / "old.onnx")) == ARCH_DEFAULT
