"""Modal truncation: the imbalanced flap's hover flutter versus the blade modes retained."""

import numpy as np
import pytest

from tefcore.config.io import load_config
from tefcore.paper.attribution.modal_truncation import (
    mode_additions,
    select_modes,
    truncation_table,
)
from tefcore.structure.blade import blade_modes


def test_select_modes_keeps_the_chosen_rows_and_columns():
    every = blade_modes(load_config("mdart"), n_modes=12)
    sub = select_modes(every, ["torsion 2", "flap 1"])          # any order in, frequency order out
    assert sub.labels == ["flap 1", "torsion 2"]
    i, j = every.labels.index("flap 1"), every.labels.index("torsion 2")
    assert sub.modal_stiffness[0, 1] == every.modal_stiffness[i, j]
    np.testing.assert_array_equal(sub.vectors, every.vectors[:, [i, j]])
    with pytest.raises(ValueError, match="flap 9"):
        select_modes(every, ["flap 9"])


def test_six_modes_hide_the_coupling_that_nine_show():
    # Measured on the MDART data: six modes +0.32 /rev, nine +3.04; flap 4
    # alone on top of the six +2.40.  0.05 /rev: the Floquet exponents' error and the
    # trim's tolerance are below 1e-3 /rev; the margin allows small changes of the
    # identity rules, not of the physics (a wrong coupling moves these by > 0.5).
    cfg = load_config("mdart")
    t = truncation_table(cfg, counts=(6, 9)).set_index("modes")["real part /rev"]
    assert t[6] == pytest.approx(0.32, abs=0.05) and t[9] == pytest.approx(3.04, abs=0.05)
    add = mode_additions(cfg, added=("flap 4",))["real part /rev"].tolist()
    assert add == pytest.approx([0.32, 2.40], abs=0.05)
