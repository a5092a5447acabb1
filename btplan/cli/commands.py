"""Imports each command module so that it registers itself on the app."""

from btplan.cli import check, export, generate, plan, run, sweep, view  # noqa: F401
