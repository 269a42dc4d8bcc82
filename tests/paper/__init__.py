"""Tests of tefcore.paper."""
