"""The `btplan run` command."""

from __future__ import annotations
