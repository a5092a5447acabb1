"""Property: whatever shape the output paths take, no input is lost and nothing is half done.

Paths are drawn from the shapes users and scripts give: plain names, long legal names,
links to the input or to another output, a link loop, aliases of standard output,
/dev/null, a missing folder, a folder, a name ending in a slash. Whatever the draw, the
CLI ends in exit 0 or 2 with clean messages, the input is byte for byte as it was, and
no temporary file is left beside anything.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from hostile import PICK_PLACE, assert_clean, budget, invoke
from hypothesis import given
from hypothesis import strategies as st

SHAPES = ("plain", "long", "link_to_input", "input", "link_to_other", "loop", "stdout",
          "dev_null", "missing_folder", "folder", "slash")


def path_of(shape: str, folder: Path, index: int) -> str:
    """One output path of the given shape, made (links, folders) inside `folder`."""
    named = folder / f"out{index}.txt"
    if shape == "plain":
        return str(named)
    if shape == "long":
        return str(folder / ("x" * (250 - len(str(index))) + f"{index}.txt"))
    if shape == "input":
        return str(folder / "domain.bt")
    if shape == "link_to_input":
        link = folder / f"in_link{index}"
        if not link.is_symlink():
            link.symlink_to(folder / "domain.bt")
        return str(link)
    if shape == "link_to_other":
        link = folder / f"other_link{index}"
        if not link.is_symlink():
            link.symlink_to(folder / "out0.txt")
        return str(link)
    if shape == "loop":
        a, b = folder / f"loop_a{index}", folder / f"loop_b{index}"
        if not a.is_symlink():
            a.symlink_to(b)
            b.symlink_to(a)
        return str(a)
    if shape == "stdout":
        return ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"][index % 4]
    if shape == "dev_null":
        return "/dev/null"
    if shape == "missing_folder":
        return str(folder / "nowhere" / f"out{index}.txt")
    if shape == "folder":
        (folder / f"dir{index}").mkdir(exist_ok=True)
        return str(folder / f"dir{index}")
    return str(folder / f"out{index}.txt") + "/"


@budget(0.5)
@given(tree=st.sampled_from(SHAPES), plan=st.sampled_from(SHAPES),
       command=st.sampled_from(["plan", "run"]))
def test_any_output_paths_leave_the_input_whole_and_no_temporary_file(
        tree: str, plan: str, command: str) -> None:
    folder = Path(tempfile.mkdtemp())
    try:
        domain = folder / "domain.bt"
        shutil.copyfile(PICK_PLACE, domain)
        before = domain.read_bytes()
        first, second = path_of(tree, folder, 0), path_of(plan, folder, 1)
        flags = (["-q", "-o", first, "--plan-out", second] if command == "plan"
                 else ["-q", "--trace", first, "--plan-out", second])
        result = invoke([command, str(domain), *flags])
        assert_clean(result)
        assert result.exit_code in (0, 2), result.output
        assert domain.read_bytes() == before
        assert not [p for p in folder.rglob("*.tmp")], sorted(folder.rglob("*"))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
