"""The grammars, shipped as package data."""
