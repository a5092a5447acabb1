"""Read domains and problems (the .bt language and PDDL) into checked models."""

from btplan.lang.loader import BtFile, Collection, collect, load, load_domain, parse_bt

__all__ = ["BtFile", "Collection", "collect", "load", "load_domain", "parse_bt"]
