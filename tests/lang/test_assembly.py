"""Generated assemblies: order constraints that can be met, and the planner's plans on them.

The optimal plan is known without search: a pick and an insert per part, and one
handover for each part lying opening down. btplan must find exactly that, handing
over only those parts, whatever the goal's order.
"""

from __future__ import annotations

import pytest

from btplan.acting.offline import plan
from btplan.lang.assembly import assembly
from btplan.model import Task


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_every_part_needs_parts_mounted_before_it(seed: int) -> None:
    _, problem = assembly(12, seed)
    needs = {f.args[0]: f.args[1:] for f in problem.init if f.predicate == "needs"}
    assert sorted(needs) == sorted(o.name for o in problem.objects if o.type == "part")
    mounted = {"base"}
    while len(mounted) < len(needs) + 1:  # some order mounts every part: no cycle
        ready = {p for p, before in needs.items() if p not in mounted and set(before) <= mounted}
        assert ready
        mounted |= ready


@pytest.mark.parametrize(("parts", "seed"), [(4, 0), (8, 1), (12, 3)])
def test_btplan_finds_the_shortest_assembly_with_handovers_only_where_needed(
    parts: int, seed: int
) -> None:
    domain, problem = assembly(parts, seed)
    result = plan(Task(domain=domain, problem=problem))
    down = sorted(f.args[0] for f in problem.init if f.predicate == "lies" and f.args[2] == "down")
    handed = sorted(a.args[0] for a in result.executed if a.name == "handover")
    assert handed == down
    assert len(result.executed) == 2 * parts + len(down)
    state = Task(domain=domain, problem=problem).initial_state
    for action in result.executed:
        assert action.applicable(state), action
        state = action.apply(state)
    assert all(f"mounted(part{i})" in {str(a) for a in state} for i in range(1, parts + 1))
