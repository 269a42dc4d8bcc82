"""Tests of tefcore.model."""
