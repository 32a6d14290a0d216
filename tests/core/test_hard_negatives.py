"""The look-alikes training pastes unlabelled (devtools/train/data.py, ``hard_negative``)."""
import numpy as np
import pytest

from devtools.train import data


@pytest.mark.parametrize("kind", sorted(data.NEGATIVE_MAKERS))
def test_every_look_alike_is_an_opaque_bgra_patch(kind):
    rng = np.random.default_rng(3)
    maker = data.NEGATIVE_MAKERS[kind]
    for _ in range(5):
        patch = maker(rng, None) if kind == "convex_mirror" else maker(rng)
        assert patch.dtype == np.uint8 and patch.ndim == 3 and patch.shape[2] == 4
        assert min(patch.shape[:2]) >= 8
        assert (patch[..., 3] > 0).mean() > 0.1   # something is drawn


def test_bunting_pennants_point_down():
    rng = np.random.default_rng(5)
    for _ in range(10):
        alpha = data._bunting(rng)[..., 3] > 0
        h = alpha.shape[0]
        top, bottom = alpha[: h // 3].sum(), alpha[2 * h // 3:].sum()
        assert top > 2 * bottom


def test_lattice_is_thin_bars_not_a_filled_panel():
    rng = np.random.default_rng(6)
    for _ in range(10):
        alpha = data._lattice(rng)[..., 3] > 0
        h = alpha.shape[0]
        assert alpha[:2].any(axis=0).mean() > 0.9 and alpha[-2:].any(axis=0).mean() > 0.9   # its chords
        assert 1 - alpha[h // 3:2 * h // 3].mean() > 0.3   # seen through between the bars


def test_hard_negative_draws_every_kind():
    rng = np.random.default_rng(0)
    kinds = {data.hard_negative(rng)[1] for _ in range(300)}
    assert kinds == set(data.NEGATIVE_MAKERS)


def test_hard_negative_draws_only_the_kinds_asked_for():
    rng = np.random.default_rng(1)
    assert {data.hard_negative(rng, kinds=("sign_back",))[1] for _ in range(20)} == {"sign_back"}
    others = tuple(k for k in data.NEGATIVE_MAKERS if k != "sign_back")
    assert {data.hard_negative(rng, kinds=others)[1] for _ in range(300)} == set(others)


def test_a_signs_back_is_a_plain_grey_plate_mostly_with_its_pole_in_front():
    """No sheeting colour anywhere: a plate of one grey, its rails of a darker one and, in
    most draws, the pole across it in a third grey."""
    rng = np.random.default_rng(8)
    with_pole = 0
    for _ in range(40):
        patch = data._sign_back(rng)
        drawn = patch[..., :3][patch[..., 3] > 0].astype(int)
        assert (drawn.max(axis=1) - drawn.min(axis=1)).max() <= 12   # grey: channels within a few levels
        greys = len(np.unique(drawn, axis=0))
        assert greys <= 3
        with_pole += greys == 3
    assert 0.5 * 40 <= with_pole <= 0.9 * 40
