"""Tests of tefcore.paper.figures."""
