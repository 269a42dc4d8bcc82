"""Tests of tefcore.sweeps."""
