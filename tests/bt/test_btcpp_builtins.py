"""Each built-in node of BT.CPP 4, in small trees with scripted leaves, ticked in
BehaviorTree.CPP and in btplan side by side: statuses, leaf calls and blackboard agree."""

from __future__ import annotations

import pytest
from bt_stubs import ScriptWorld

from btplan.bt import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.blackboard import as_text
from btplan.bt.formats.btcpp import dump_xml, load_xml

pytest.importorskip("behaviortreepy")
from btcpp_oracle import UNREADABLE, BtcppDocRun

MODEL = ('<TreeNodesModel><Action ID="A"/><Action ID="B"/><Action ID="C"/>'
         '<Condition ID="P"/><Condition ID="Q"/></TreeNodesModel>')
R, S, F = RUNNING, SUCCESS, FAILURE
P, Q = ("P", ()), ("Q", ())

# (name, tree body, ticks, action scripts, {tick: (facts added, facts removed)})
CASES: list[tuple[str, str, int, dict[str, list[Status]], dict[int, tuple[set, set]]]] = [
    ("sequence_with_memory", "<SequenceWithMemory><A/><B/><C/></SequenceWithMemory>", 8,
     {"A": [S], "B": [R, F, S], "C": [R, S]}, {}),
    ("async_sequence", "<AsyncSequence><A/><B/><P/></AsyncSequence>", 7,
     {"A": [S], "B": [R, S]}, {3: ({P}, set())}),
    ("async_fallback", "<AsyncFallback><P/><A/><B/></AsyncFallback>", 7,
     {"A": [F], "B": [R, S]}, {5: ({P}, set())}),
    ("parallel_all", '<ParallelAll max_failures="-1"><A/><B/><C/></ParallelAll>', 8,
     {"A": [R, F], "B": [S], "C": [R, R, F, R, S]}, {}),
    ("parallel", '<Parallel success_count="2" failure_count="2"><A/><B/><C/></Parallel>', 8,
     {"A": [R, F], "B": [R, R, S], "C": [R, R, R, S]}, {}),
    ("if_then_else", "<IfThenElse><P/><A/><B/></IfThenElse>", 8,
     {"A": [R, R, S], "B": [R, S]}, {0: ({P}, set()), 1: (set(), {P})}),
    ("if_then", "<IfThenElse><P/><A/></IfThenElse>", 5, {"A": [R, S]},
     {2: ({P}, set())}),
    ("while_do_else", "<WhileDoElse><P/><A/><B/></WhileDoElse>", 9,
     {"A": [R], "B": [R, R, S]}, {0: ({P}, set()), 2: (set(), {P}), 5: ({P}, set())}),
    ("switch", '<Sequence><Script code="v := \'1\'"/><ReactiveFallback><Switch3 variable="{v}" '
     'case_1="1" case_2="two" case_3="3.0"><A/><B/><C/><AlwaysFailure/></Switch3>'
     '<Script code="v := v == \'1\' ? \'two\' : \'3\'" _failureIf="v == \'3\'"/></ReactiveFallback>'
     '</Sequence>', 10, {"A": [R, R, F], "B": [R, F], "C": [R, R, S]}, {}),
    ("repeat", '<Repeat num_cycles="3"><Sequence><A/><B/></Sequence></Repeat>', 10,
     {"A": [S], "B": [R, S, S, R, S]}, {}),
    ("repeat_fails", '<Repeat num_cycles="-1"><A/></Repeat>', 6, {"A": [S, R, S, F]}, {}),
    ("retry_for_ever", '<RetryUntilSuccessful num_attempts="-1"><A/></RetryUntilSuccessful>',
     6, {"A": [F, R, F, F, S]}, {}),
    ("retry_from_the_blackboard", '<Sequence><Script code="num_locs := 3"/>'
     '<RetryUntilSuccessful num_attempts="{num_locs}"><A/></RetryUntilSuccessful></Sequence>',
     6, {"A": [F, R, F, F, R, S]}, {}),
    ("keep_running", "<KeepRunningUntilFailure><A/></KeepRunningUntilFailure>", 6,
     {"A": [S, R, S, F]}, {}),
    ("run_once", '<Sequence><RunOnce then_skip="false"><A/></RunOnce><B/></Sequence>', 6,
     {"A": [R, F], "B": [S]}, {}),
    ("precondition", '<Sequence><Script code="go := 1"/><Precondition if="go == 1" '
     'else="SKIPPED"><A/></Precondition><Script code="go := 0"/></Sequence>', 6,
     {"A": [R, R, S]}, {}),
    ("loop_string", '<Sequence><Script code="q := \'a;b;c\'; seen := \'\'"/>'
     '<LoopString queue="{q}" '
     'value="{item}" if_empty="SUCCESS"><A _onSuccess="seen := seen .. item" /></LoopString>'
     '</Sequence>', 8, {"A": [R, S]}, {}),
    ("loop_bool", '<LoopBool queue="true;false;true" value="{flag}"><Inverter>'
     '<ScriptCondition code="flag"/></Inverter></LoopBool>', 5, {}, {}),
    ("skip_unless_updated", '<Sequence><Script code="n := 0"/><Repeat num_cycles="4">'
     '<Sequence><SkipUnlessUpdated entry="n"><A/></SkipUnlessUpdated>'
     '<Script code="n += 1" _skipIf="n &gt; 1"/></Sequence></Repeat></Sequence>', 8,
     {"A": [R, S]}, {}),
    ("wait_value_update", '<Sequence><Script code="k := 1"/>'
     '<Parallel success_count="1"><WaitValueUpdate entry="k"><B/></WaitValueUpdate>'
     '<Sequence><A/><Script code="k := 2"/></Sequence></Parallel></Sequence>', 6,
     {"A": [R, R, S], "B": [R, S]}, {}),
    ("was_entry_updated", '<Sequence><Script code="e := 1"/><WasEntryUpdated entry="e"/>'
     '<Inverter><WasEntryUpdated entry="e"/></Inverter><UnsetBlackboard key="e"/>'
     '<A/></Sequence>', 4, {"A": [S]}, {}),
    ("while_halts", '<Sequence><Script code="t := 0"/><Parallel success_count="1">'
     '<A _while="t &lt; 2" _onHalted="halted := 1"/><Sequence><B/>'
     '<Script code="t += 1"/></Sequence></Parallel></Sequence>', 8,
     {"A": [R], "B": [R, S, R, S, R, S]}, {}),
    ("pre_conditions", '<Sequence><Script code="x := 5"/><ReactiveSequence _skipIf="x &lt; 0">'
     '<A _failureIf="x &gt; 6" _onFailure="y := 1"/><B _successIf="x == 5" '
     '_onSuccess="x += 1" _post="z := x"/></ReactiveSequence></Sequence>', 6,
     {"A": [R, S], "B": [S]}, {}),
    ("subtree_ports", '<Sequence><Script code="goal := \'dock\'; speed := 1"/>'
     '<SubTree ID="U" goal="{=}" fast="{speed}" mode="eco" _onSuccess="after := 1"/>'
     '</Sequence></BehaviorTree><BehaviorTree ID="U"><Sequence><A _skipIf="mode != \'eco\'"/>'
     '<Script code="fast += 1; goal = goal .. \'!\'; mine := mode"/></Sequence>', 4,
     {"A": [R, S]}, {}),
    ("skipped_later", '<Sequence><Script code="n := 0"/><Fallback><Sequence>'
     '<A _skipIf="n &gt; 0" _onSuccess="n += 1"/></Sequence><B/></Fallback></Sequence>', 4,
     {"A": [S], "B": [R, S]}, {}),
    ("all_skipped", '<Sequence><Fallback><A _skipIf="true"/><B _skipIf="true"/></Fallback>'
     '<C/></Sequence>', 3, {"C": [S]}, {}),
]


@pytest.mark.parametrize(("body", "ticks", "scripts", "changes"),
                         [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_btcpp_and_btplan_agree(body: str, ticks: int, scripts: dict[str, list[Status]],
                                changes: dict[int, tuple[set, set]]) -> None:  # type: ignore[type-arg]
    text = f'<root BTCPP_format="4"><BehaviorTree ID="T">{body}</BehaviorTree>{MODEL}</root>'
    tree = load_xml(text)
    ours, theirs = ScriptWorld((), scripts), ScriptWorld((), scripts)
    run = BtcppDocRun(dump_xml(tree), theirs)
    for tick in range(ticks):
        add, remove = changes.get(tick, (set(), set()))
        for world in (ours, theirs):
            world.facts |= add
            world.facts -= remove
        mine, other = tree.tick(ours), run.tick()
        assert (tick, mine, ours.take_log()) == (tick, other, theirs.take_log())
    assert tree.imported is not None
    board = {k: as_text(float(v) if isinstance(v, bool) else v)
             for k, v in tree.imported.board.snapshot().items()}
    theirs_board = run.board()
    for key in set(board) | set(theirs_board):
        if theirs_board.get(key) == UNREADABLE:
            continue
        a, b = board.get(key), theirs_board.get(key)
        try:
            assert a is not None and b is not None and float(a) == pytest.approx(float(b))
        except ValueError:
            assert a == b, key


def test_a_recorded_tick_of_an_imported_tree_keeps_its_conditions() -> None:
    from btplan.bt import TickRecorder

    text = (f'<root BTCPP_format="4"><BehaviorTree ID="T"><Sequence>'
            '<Script code="n := 0"/><A _skipIf="n == 0" _post="n := 9"/><B _onSuccess="n += 1"/>'
            f'</Sequence></BehaviorTree>{MODEL}</root>')
    tree = load_xml(text)
    recorder = TickRecorder()
    recorder.attach(tree)
    assert tree.tick(ScriptWorld((), {"B": [S]})) is SUCCESS
    assert recorder.last is not None
    assert [n.status for n in recorder.last.nodes][-1] is SUCCESS
    assert tree.imported is not None and tree.imported.board.get("n") == 1.0
    assert type(tree.root.children[1]).__name__ == "Action"
