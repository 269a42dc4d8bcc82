"""What ``tefcore simulate`` prints and writes: the summary lines and the JSON document.

Examples
--------
>>> json_document({"growth_time_domain_per_rev": float("nan"), "mode": "TEF"})["mode"]
'TEF'
>>> json_document({"x": float("nan")})["x"] is None
True
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["json_document", "summary_lines", "top_terms"]


def _clean(value):
    """JSON-ready: NaN and infinities as None, numpy scalars as Python ones."""
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def json_document(summary: dict, work=None, floquet_work=None) -> dict:
    """The ``--json`` document: the summary, the work per revolution, the Floquet split.

    Parameters
    ----------
    summary : dict
        :attr:`tefcore.timedomain.simulate.SimulationResult.summary`.
    work : pandas.DataFrame, optional
        The work of the named terms per revolution.
    floquet_work : dict, optional
        The Floquet decomposition of the root (term -> contribution).

    Returns
    -------
    dict
        JSON-ready (NaN as null).
    """
    doc = dict(summary)
    if work is not None:
        doc["work_per_revolution"] = work.to_dict(orient="records")
    if floquet_work:
        doc["floquet_work"] = floquet_work
    return _clean(doc)


def top_terms(values: dict, n: int = 4) -> list[tuple[str, float]]:
    """The ``n`` terms of largest magnitude, largest first.

    Parameters
    ----------
    values : dict of str to float
        Term -> contribution.
    n : int, optional
        How many.

    Returns
    -------
    list of (str, float)
    """
    return sorted(values.items(), key=lambda kv: -abs(kv[1]))[:n]


def _rate(value) -> str:
    return "n/a" if value is None or not math.isfinite(value) else f"{value:+.4f} /rev"


def summary_lines(result) -> list[str]:
    """What ``tefcore simulate`` prints: start, fitted growth, Floquet, agreement, work.

    Parameters
    ----------
    result : tefcore.timedomain.simulate.SimulationResult
        The simulation.

    Returns
    -------
    list of str
        Lines of at most about 100 columns (the caller wraps).
    """
    s = result.summary
    if s["start"] == "flap impulse":
        start = f"started from a flap impulse ({s['amplitude_chord']:g} chord per rad)"
    elif s["start"] == "least stable flap-induced root":
        # the words of `tefcore stability`: a flutter root is an unstable one
        state = "stable" if s["growth_floquet_per_rev"] <= 0 else "neutral"
        start = (f"started from the least stable flap-induced root, {s['mode']}, at "
                 f"{s['amplitude_chord']:g} chord (no flutter root: it is {state})")
    else:
        start = f"started from the {s['start']} ({s['mode']}) at {s['amplitude_chord']:g} chord"
    lines = [f"{start}; {s['revolutions']:g} revolutions"]
    if s["fit_revolutions"] and math.isfinite(s["growth_time_domain_per_rev"]):
        a, b = s["fit_revolutions"]
        lines.append(f"growth of the {s['component'].replace('_', ' ')} over revolutions "
                     f"{a}-{b}: {_rate(s['growth_time_domain_per_rev'])} "
                     f"(x{s['growth_factor_per_revolution']:.3g} per revolution)")
    else:
        lines.append(s["note"])
    verdict = {True: "agrees", False: "DISAGREES", None: "not compared"}[s["agrees"]]
    lines.append(f"Floquet real part of {s['compared_with']}: {_rate(s['growth_floquet_per_rev'])}"
                 f" at {s['frequency_floquet_per_rev']:.3f} /rev; difference "
                 f"{_rate(s['difference'])} (tolerance {s['tolerance']:.4f}): {verdict}")
    if result.work is not None and len(result.work):
        last = result.work.iloc[-1]
        terms = [c for c in result.work.columns
                 if c not in ("revolution", "sum", "energy_growth")]
        parts = ", ".join(f"{t} {v:+.3f}" for t, v in top_terms(last[terms].to_dict(), 3))
        lines.append(f"work per revolution (last, /rev): {parts}; sum {last['sum']:+.4f} = "
                     f"energy growth {last['energy_growth']:+.4f}")
    nl = s.get("nonlinear")
    if nl:
        dep = nl["departures"].get("0.01")
        where = ("never departs by 1 %" if dep is None else
                 f"departs by 1 % at {dep['psi_rev']:.3f} rev (flap "
                 f"{dep['flap_deflection_deg']:.3g} deg, twist {dep['twist_flap_midspan_deg']:.3g} "
                 "deg)")
        lines.append(f"nonlinear march: growth {_rate(nl['growth_nonlinear_per_rev'])} against "
                     f"{_rate(nl['growth_linear_same_window'])} linear (windows of "
                     f"{nl['fit_window_rev']:g} rev, to {nl['reached_rev']:.3f} rev); {where}"
                     + (f"; stopped: {nl['stopped']}" if nl["stopped"] else ""))
    return lines
