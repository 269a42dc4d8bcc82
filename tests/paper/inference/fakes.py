"""Cheap stand-ins for the claims' checks, for the study's tests (importable by workers).

Each evaluator has the signature of the study's: ``(cfg, claims, readings, protocol,
cache_folder) -> {reading: table, "broken": {}}``; every fitted claim's margin is a
smooth function of the sample's flap mass (peak at 0.40 lb/ft), so a study has
something to find, at no cost.
"""

import os
import time

import pandas as pd

__all__ = ["PEAK", "margin_of", "quick", "slow"]

#: The flap mass (kg/m) where the stand-in's margins peak: 0.40 lb/ft.
PEAK = 0.40 * 1.48816


def margin_of(cfg) -> float:
    return 1.0 - 4.0 * abs(cfg.flap.mass - PEAK)


def _table(cfg, claims):
    m = margin_of(cfg)
    return pd.DataFrame({"id": [c.id for c in claims], "figure": [c.figure for c in claims],
                         "tag": [c.tag for c in claims],
                         "status": ["pass" if m > 0 else "fail"] * len(claims),
                         "margin": [m] * len(claims)})


def quick(cfg, claims, readings, protocol, cache_folder):
    return {"broken": {}, **{r: _table(cfg, claims) for r in readings}}


def slow(cfg, claims, readings, protocol, cache_folder):
    """As :func:`quick`, taking ``TEFCORE_FAKE_SECONDS`` (default 2) of wall time."""
    time.sleep(float(os.environ.get("TEFCORE_FAKE_SECONDS", "2")))
    return quick(cfg, claims, readings, protocol, cache_folder)
