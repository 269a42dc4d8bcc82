"""Tests of tefcore.modes."""
