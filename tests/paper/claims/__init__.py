"""Tests of tefcore.paper.claims."""
