"""Tests of tefcore.aero."""
