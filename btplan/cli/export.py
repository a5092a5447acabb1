"""The `btplan export` command."""

from __future__ import annotations
