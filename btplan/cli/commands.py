"""Imports each command module so that it registers itself on the app.

Command modules are listed here as they are added; each owns one subcommand.
"""
