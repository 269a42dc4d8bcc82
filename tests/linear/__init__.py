"""Tests of tefcore.linear."""
