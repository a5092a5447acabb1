"""The `btplan plan` command."""

from __future__ import annotations
