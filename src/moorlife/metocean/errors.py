"""The error of an unusable hindcast."""

from __future__ import annotations

__all__ = ["HindcastError"]


class HindcastError(ValueError):
    """A hindcast is unusable; the message names the file, column, first bad row and value."""
