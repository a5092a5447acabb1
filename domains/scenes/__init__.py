"""The PyBullet scenes of the example domains, shipped as package data."""
