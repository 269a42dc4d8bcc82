"""Tests of tefcore.structure."""
