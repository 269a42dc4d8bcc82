"""Tests of tefcore.trimming."""
