"""The `btplan generate` command."""

from __future__ import annotations
