"""The `btplan check` command."""

from __future__ import annotations
