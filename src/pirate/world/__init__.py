"""Pipe networks as data: the world format, its loader and its geometry (pure)."""
