"""Tests of tefcore.paper.run."""
