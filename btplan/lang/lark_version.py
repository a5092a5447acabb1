"""btplan's readers need lark 1.x; ROS 2's wheels bring lark-parser 0.12 (for their
message generators), which installs a module of the same name. Whichever was installed
last is the one imported: say so plainly instead of failing somewhere in a grammar."""

from __future__ import annotations

import lark

if int(lark.__version__.split(".")[0]) < 1:
    raise ImportError(
        f"btplan needs lark 1.1.9 or later, but the module 'lark' is version "
        f"{lark.__version__} (lark-parser, which ROS 2's wheels install, puts a module of "
        "the same name there); put lark back with: "
        "pip install --force-reinstall --no-deps 'lark>=1.1.9'")
