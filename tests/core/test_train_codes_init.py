"""devtools.train.codes.init_from_onnx: a sign-code classifier with more names starts from an
exported one, computing the same probabilities over the names they share.

Training needs torch (devtools/train/requirements.txt), which the plugin's own setup does not
install: these tests run where it is installed and are skipped elsewhere.
"""
import json

import numpy as np
import onnx
import pytest
from helpers.trainedlooking import trained_looking

torch = pytest.importorskip("torch")

from devtools.train import codes  # noqa: E402

OLD_NAMES = ["DE:206", "DE:274[30]", "DE:274[50]", "other"]
NEW_NAMES = ["DE:206", "DE:274[30]", "DE:274[50]", "unlisted:prohibitory", "unlisted:stop", "other"]


def test_a_classifier_with_more_names_starts_from_the_exported_one(tmp_path):
    torch.manual_seed(0)
    old = trained_looking(codes.build_net(len(OLD_NAMES)), seed=3)
    path = str(tmp_path / "old.onnx")
    codes.export_onnx(old, OLD_NAMES, path, {})
    old.eval()   # the export leaves its wrapper's training mode on the network
    crops = np.random.default_rng(1).integers(0, 256, (16, codes.CROP_PX, codes.CROP_PX, 3), dtype=np.uint8)
    x = codes.to_tensor(crops, "cpu")
    new = codes.build_net(len(NEW_NAMES))
    copied = codes.init_from_onnx(new, NEW_NAMES, path, [x])
    assert copied.tolist() == [n in OLD_NAMES for n in NEW_NAMES]
    new.eval()
    with torch.no_grad():
        p_old = torch.softmax(old(x), 1).numpy()
        logits = new(x)
    shared = [NEW_NAMES.index(n) for n in OLD_NAMES]
    p_new_shared = torch.softmax(logits[:, shared], 1).numpy()
    np.testing.assert_allclose(p_new_shared, p_old, atol=1e-4)
    # a new name starts from its class's codes (the prohibitory ones: the two limits), not from zero
    rows = new.head[-1].weight.detach().numpy()
    np.testing.assert_allclose(rows[NEW_NAMES.index("unlisted:prohibitory")], rows[[1, 2]].mean(0), atol=1e-6)
    np.testing.assert_allclose(rows[NEW_NAMES.index("unlisted:stop")], rows[0], atol=1e-6)
    assert json.loads(onnx.load(path).metadata_props[0].value) == OLD_NAMES


def test_only_the_new_rows_learn():
    """train_new_rows_only: after some steps the features and the file's rows are as they
    were, the new names' rows moved."""
    torch.manual_seed(0)
    net = trained_looking(codes.build_net(len(NEW_NAMES)), seed=3)
    before = {k: v.clone() for k, v in net.state_dict().items()}
    copied = np.array([n in OLD_NAMES for n in NEW_NAMES])
    opt = codes.train_new_rows_only(net, copied, lr=1e-2)
    x = torch.rand(8, 3, codes.CROP_PX, codes.CROP_PX)
    y = torch.tensor([3, 4] * 4)
    for _ in range(5):
        net.train()
        net.features.eval()
        loss = torch.nn.functional.cross_entropy(net(x), y)
        opt.zero_grad()
        loss.backward()
        opt.step()
    after = net.state_dict()
    for key, value in before.items():
        if not key.startswith("head."):
            assert torch.equal(after[key], value), key
    weight, bias = after["head.1.weight"], after["head.1.bias"]
    assert torch.equal(weight[copied], before["head.1.weight"][copied])
    assert torch.equal(bias[copied], before["head.1.bias"][copied])
    assert not torch.allclose(weight[~copied], before["head.1.weight"][~copied])
