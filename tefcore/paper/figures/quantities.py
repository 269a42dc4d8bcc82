"""The quantities the paper's figures plot, and their units.

Each quantity a claim or a digitised curve can be about has a canonical unit
(what tefcore computes: eigenvalues over Omega in 1/rev, SI otherwise) and
the units the paper's axes use (:data:`QUANTITIES`); the swept field of a
figure has its dimension (:func:`swept_dimension`).  :func:`x_to_si` and
:func:`y_to_canonical` convert a figure's axis values.

Examples
--------
>>> round(float(y_to_canonical("hinge_moment", [1.0], "ft-lb")[0]), 6)   # N m
1.355818
"""

from __future__ import annotations

import math

import numpy as np

from ...config.configuration import SECTIONS, resolve_field
from ...units import to_si
from .catalogue import FIGURES

__all__ = ["QUANTITIES", "QUANTITY_NAMES", "quantity_unit", "swept_dimension", "x_to_si",
           "y_to_canonical"]


_FT_LBF = 1.3558179483314004  # N m per ft-lbf

_PER_REV = {"1/rev": 1.0, "/rev": 1.0, "": 1.0, "1/s": "1/s"}   # eigenvalue / Omega

_FREQ = {"/rev": 1.0, "1/rev": 1.0, "": 1.0, "Hz": "Hz"}

_POWER = {"W": 1.0, "hp": 745.6998715822702, "ft-lb/s": _FT_LBF}

#: quantity -> (figures, canonical unit, {accepted unit: factor}); "1/s" and "Hz"
#: are converted with the figure's rotor speed
QUANTITIES = {
    "real_part": ("stability", "1/rev", _PER_REV),
    "damping": ("stability", "1/rev", _PER_REV),
    "damping_ratio": ("stability", "1", {"1": 1.0, "": 1.0, "%": 0.01, "percent": 0.01}),
    "frequency_per_rev": ("stability", "/rev", _FREQ),
    "natural_frequency_per_rev": ("stability", "/rev", _FREQ),
    "hinge_moment": (("fig5",), "N m", {"N m": 1.0, "N-m": 1.0, "Nm": 1.0, "ft-lb": _FT_LBF,
                                        "in-lb": _FT_LBF / 12}),
    "half_peak_to_peak_deg": (("fig6", "fig7"), "deg", {"deg": 1.0, "": 1.0}),
    "peak_power": (("fig6", "fig7"), "W", _POWER),
    "mean_power": (("fig6", "fig7"), "W", _POWER),
}

#: quantity -> its name in printed claims (``"damping ratio -0.0123"``), as the panels
#: label their axes
QUANTITY_NAMES = {
    "real_part": "real part", "damping": "damping −Re(s)/Ω",
    "damping_ratio": "damping ratio", "frequency_per_rev": "frequency",
    "natural_frequency_per_rev": "natural frequency", "hinge_moment": "hinge moment",
    "half_peak_to_peak_deg": "flap response (half peak-to-peak)", "peak_power": "peak power",
    "mean_power": "mean power",
}


def quantity_unit(quantity: str) -> str:
    """The unit printed after a value of `quantity`: its canonical unit, none when dimensionless.

    Parameters
    ----------
    quantity : str
        A key of :data:`QUANTITIES`, or ``""`` (none).

    Returns
    -------
    str
        ``"1/rev"``, ``"N m"``, ...; ``""`` for a dimensionless quantity
        (the damping ratio: its name says what it is, a unit "1" says nothing).

    Examples
    --------
    >>> quantity_unit("real_part"), quantity_unit("damping_ratio")
    ('1/rev', '')
    """
    unit = QUANTITIES[quantity][1] if quantity else ""
    return "" if unit == "1" else unit


#: x of the response figures (fig6 has none): {unit: factor to the table's unit}
_RESPONSE_X = {"fig5": {"": 1.0, "deg": 1.0, "rad": 180 / math.pi},
               "fig7": {"": 1.0, "%": 0.01, "percent": 0.01}}

def swept_dimension(figure: str) -> str:
    """Physical dimension of a stability figure's swept field (e.g. ``"angle"``).

    Parameters
    ----------
    figure : str
        Stability figure, a key of :data:`tefcore.paper.figures.catalogue.FIGURES`.

    Returns
    -------
    str
        The dimension of the configuration field it sweeps, as declared in
        :mod:`tefcore.config.sections` (used to convert ``"150 lb/in"`` to SI).

    Examples
    --------
    >>> swept_dimension("fig3"), swept_dimension("fig10")
    ('angle', 'force_per_length')
    """
    section, name = resolve_field(FIGURES[figure].parameter)
    return next(p.dimension for p in SECTIONS[section].PARAMS if p.name == name)

def x_to_si(figure: str, values, unit: str = ""):
    """Convert x values of `figure` from `unit` to the unit of its result table.

    Parameters
    ----------
    figure : str
        A stability figure, ``"fig5"`` or ``"fig7"`` (Fig. 6 has no x).
    values : float or array_like
        The x values as the claim writes them.
    unit : str
        Their unit: stability figures accept any unit of the swept field's
        dimension (``"lb/in"``, ``"deg"``, ``"percent"``; ``""``: already SI);
        Fig. 5 ``""``, ``"deg"`` or ``"rad"`` of azimuth; Fig. 7 ``""``,
        ``"%"`` or ``"percent"`` of the flap chord.

    Returns
    -------
    float or numpy.ndarray
        ``values`` in the unit of the figure's result table: SI of the swept
        field, Fig. 5's azimuth in deg, Fig. 7's overhang as a fraction.

    Raises
    ------
    ValueError
        A unit the figure does not accept.

    Examples
    --------
    >>> float(x_to_si("fig7", 29, "percent"))
    0.29
    """
    if figure in FIGURES:
        return to_si(values, unit, swept_dimension(figure)) if unit else values
    table = _RESPONSE_X.get(figure, {})
    if unit not in table:
        raise ValueError(f"x unit {unit!r} not accepted for {figure}; use one of {list(table)}")
    return np.multiply(values, table[unit])

def y_to_canonical(quantity: str, values, unit: str, rotor_speed: float | None = None):
    """Convert `values` of `quantity` from `unit` to its canonical unit (:data:`QUANTITIES`).

    Parameters
    ----------
    quantity : str
        A key of :data:`QUANTITIES` (``"real_part"``, ``"hinge_moment"``, ...).
    values : float or array_like
        Values as digitised or stated.
    unit : str
        Their unit, one of those :data:`QUANTITIES` accepts for the quantity
        (``"1/s"``, ``"Hz"``, ``"%"``, ``"ft-lb"``, ``"hp"``, ...).
    rotor_speed : float, optional
        Rotor speed Omega [rad/s] of the figure, needed to turn a rate per
        second (``"1/s"``) or ``"Hz"`` into per rev.

    Returns
    -------
    numpy.ndarray
        The values in the canonical unit (1/rev, /rev, N m, W, deg or 1).

    Raises
    ------
    ValueError
        A unit not accepted for the quantity, or a per-second unit without
        ``rotor_speed``.

    Examples
    --------
    >>> y_to_canonical("damping_ratio", [2.0], "%")
    array([0.02])
    """
    table = QUANTITIES[quantity][2]
    if unit not in table:
        raise ValueError(f"unit {unit!r} not accepted for {quantity}; use one of {list(table)}")
    factor = table[unit]
    if isinstance(factor, str):  # per second / Hz -> per rev (rad of azimuth or cycles)
        if rotor_speed is None:
            raise ValueError(f"converting {quantity} from {unit!r} needs the rotor speed")
        factor = (1.0 if factor == "1/s" else 2 * math.pi) / rotor_speed
    return np.asarray(values, float) * factor
