"""Shared fixtures of the inference tests: a protocol that keeps the torsion level fixed."""

import pytest

from tefcore.paper.inference.protocol import inference_file


@pytest.fixture
def fixed_protocol(tmp_path):
    """The packaged protocol with ``torsion = "fixed"`` (no 0.7 s re-fit per trial)."""
    text = inference_file("protocol").replace('torsion = "recalibrated"', 'torsion = "fixed"')
    assert 'torsion = "fixed"' in text
    path = tmp_path / "protocol-fixed.toml"
    path.write_text(text)
    return str(path)
