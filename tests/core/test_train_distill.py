"""Distillation in the detector's training (``devtools.train --teacher``): a student learns what
a teacher network computes. Needs torch (devtools/train/requirements.txt), which the plugin's
own setup does not install: skipped where it is missing."""
import numpy as np
import pytest

torch = pytest.importorskip("torch")

from devtools.train import train as T  # noqa: E402
from devtools.train.data import CLASSES  # noqa: E402
from devtools.train.model import SignNet, export_onnx  # noqa: E402

SMALL = {"widths": (8, 8, 16, 16), "fpn": 8, "head": 8}


def outputs(net, x):
    net.eval()
    with torch.no_grad():
        return net(x)


def test_the_loss_is_zero_where_the_student_computes_what_the_teacher_does():
    torch.manual_seed(0)
    logits, regression = torch.randn(2, 6, 16, 16) * 3, torch.randn(2, 4, 16, 16)
    valid = torch.ones(2, 16, 16)
    assert float(T.distillation_loss(logits, regression, logits, regression, valid)) == pytest.approx(0.0, abs=1e-5)


def test_the_loss_grows_with_the_difference_and_leaves_out_the_ignored_cells():
    torch.manual_seed(1)
    t_logits, t_regression = torch.randn(1, 6, 16, 16) * 3, torch.randn(1, 4, 16, 16)
    valid = torch.ones(1, 16, 16)
    losses = [float(T.distillation_loss(t_logits + d, t_regression + d, t_logits, t_regression, valid))
              for d in (0.5, 1.0, 2.0)]
    assert 0.0 < losses[0] < losses[1] < losses[2]
    # a student wrong only where the truth says "ignore" (valid 0) loses nothing on the heatmap
    ignored = torch.zeros(1, 16, 16)
    ignored[:, :8] = 1.0
    student = t_logits.clone()
    student[:, :, 8:] += 5.0
    assert float(T.distillation_loss(student, t_regression, t_logits, t_regression, ignored)) == pytest.approx(
        0.0, abs=1e-5)
    assert float(T.distillation_loss(student, t_regression, t_logits, t_regression, valid)) > 0.1
    # the teacher's outputs take no gradient, the student's do
    s = t_logits.clone().requires_grad_(True)
    t = (t_logits + 1).requires_grad_(True)
    T.distillation_loss(s, t_regression, t, t_regression, valid).backward()
    assert s.grad is not None and float(s.grad.abs().sum()) > 0 and t.grad is None


def test_a_small_student_learns_its_teacher():
    torch.manual_seed(2)
    teacher = SignNet(len(CLASSES), widths=(16, 16, 32, 32), fpn=16, head=16).eval()
    with torch.no_grad():
        teacher.heatmap.bias.fill_(0.0)   # a teacher that boxes something, not a prior of 0.01
    student = SignNet(len(CLASSES), **SMALL)
    x = torch.rand(4, 3, 64, 64)
    valid = torch.ones(4, 16, 16)
    t_logits, t_regression = outputs(teacher, x)
    opt = torch.optim.Adam(student.parameters(), lr=1e-2)
    student.train()
    first = None
    for _ in range(60):
        logits, regression = student(x)
        loss = T.distillation_loss(logits, regression, t_logits, t_regression, valid)
        first = float(loss) if first is None else first
        opt.zero_grad()
        loss.backward()
        opt.step()
    s_logits, s_regression = outputs(student, x)
    final = float(T.distillation_loss(s_logits, s_regression, t_logits, t_regression, valid))
    assert final < 0.3 * first


@pytest.mark.parametrize("suffix", [".onnx", ".pt"])
def test_the_teacher_is_the_network_of_the_exported_file_or_checkpoint(tmp_path, suffix):
    torch.manual_seed(3)
    net = SignNet(len(CLASSES), **SMALL)
    net.train()
    with torch.no_grad():   # batch statistics that are not the initial ones
        for _ in range(5):
            net(torch.rand(4, 3, 64, 64) * 2)
    x = torch.rand(2, 3, 64, 64)
    want_logits, want_regression = outputs(net, x)
    path = str(tmp_path / ("teacher" + suffix))
    if suffix == ".onnx":
        export_onnx(net, path, CLASSES)
    else:
        torch.save({"model": net.state_dict(), "arch": net.arch}, path)
    calibration = [torch.rand(4, 3, 64, 64) for _ in range(3)]
    teacher = T.load_teacher(path, lambda: calibration, torch.device("cpu"))
    assert not teacher.training and not any(p.requires_grad for p in teacher.parameters())
    assert teacher.arch == net.arch
    got_logits, got_regression = outputs(teacher, x)
    np.testing.assert_allclose(got_logits.numpy(), want_logits.numpy(), atol=1e-3)
    np.testing.assert_allclose(got_regression.numpy(), want_regression.numpy(), atol=1e-3)
