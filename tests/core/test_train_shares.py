"""The training command lines' mix shares (``--source-weights``, ``--mix``)."""
import pytest

from devtools.train import codes
from devtools.train.data import parse_shares


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
