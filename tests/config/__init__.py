"""Tests of tefcore.config."""
