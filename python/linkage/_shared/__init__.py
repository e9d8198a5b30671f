"""Helpers shared by every layer of the package: arrays, files, caches, choices, sizes, progress."""
