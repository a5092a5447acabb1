"""The example domains, shipped as package data (btplan.domains)."""
