"""The monitor tests run BT.CPP beside btplan through the oracle of tests/bt."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bt"))
