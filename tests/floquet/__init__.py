"""Tests of tefcore.floquet."""
