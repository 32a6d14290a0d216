"""The training command lines' mix shares (``--source-weights``, ``--mix``), view scales
(``--view-scales``) and scenes (``--train-scenes``)."""
import pytest

from devtools.train import codes
from devtools.train.data import parse_scale_range, parse_scene_specs, parse_shares


def test_shares_parse_and_a_malformed_item_is_refused():
    assert parse_shares("views=0.5, gtsdb=0.2") == {"views": 0.5, "gtsdb": 0.2}
    for bad in ("mined", "=0.1", "mined=x"):
        with pytest.raises(ValueError):
            parse_shares(bad)


def test_the_classifier_command_line_takes_the_mix_and_refuses_an_unknown_source():
    with pytest.raises(SystemExit):
        codes.main(["--mix", "mined", "--evaluate", "unused.onnx"])
    with pytest.raises(ValueError, match="no source"):
        codes.Sampler.__init__(object.__new__(codes.Sampler), [], mix={"billboards": 0.1})


def test_view_scales_parse_and_a_range_that_is_not_one_is_refused():
    assert parse_scale_range("0.45,1.6") == (0.45, 1.6)
    for bad in ("0.5", "0.5,1,2", "1.6,0.45", "0,1", "-1,1", "a,1"):
        with pytest.raises(ValueError):
            parse_scale_range(bad)


def test_training_scenes_parse_and_a_malformed_item_is_refused():
    assert parse_scene_specs("default:100, tiny:101,default:103:3072") == (
        ("default", 100, None), ("tiny", 101, None), ("default", 103, 3072))
    for bad in ("default", ":100", "default:x", "default:100:1:2", "default:7"):
        with pytest.raises(ValueError):
            parse_scene_specs(bad)
