"""Tests of tefcore.paper.attribution."""
