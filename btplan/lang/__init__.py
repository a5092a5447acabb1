"""Read domains and problems (the .bt language and PDDL) into checked models."""

from btplan.lang.loader import BtFile, Collection, collect, load, load_domain, parse_bt
from btplan.lang.report import InputErrors

__all__ = [
    "BtFile",
    "Collection",
    "InputErrors",
    "collect",
    "load",
    "load_domain",
    "parse_bt",
]
