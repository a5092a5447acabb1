"""btplan: planning domains to reactive Behavior Trees."""

__version__ = "0.1.0"
