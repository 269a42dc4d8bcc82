"""tefcore's tests, one folder per layer of the package (tests/<layer>/)."""
