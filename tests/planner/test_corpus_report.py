"""The corpus benchmark's summary, for any choice of planners."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

BENCH = Path(__file__).resolve().parents[2] / "bench" / "corpus.py"


def _corpus() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_corpus", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench_corpus"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_report_without_btplan_counts_each_planner() -> None:
    corpus = _corpus()
    cases = [corpus.Case("d", "p01", {"fd": corpus.Run(True, 1.0, 10.0, 3),
                                      "pyperplan": corpus.Run(False, 2.0, 20.0)})]
    lines = corpus.report(cases, ["fd", "pyperplan"], 30.0)
    assert any(line.split()[:3] == ["d", "1/1", "0/1"] for line in lines)
    assert not any("btplan /" in line for line in lines)


def test_report_with_btplan_gives_ratios() -> None:
    corpus = _corpus()
    cases = [corpus.Case("d", "p01", {"btplan": corpus.Run(True, 2.0, 10.0, 4),
                                      "fd": corpus.Run(True, 1.0, 10.0, 4)})]
    lines = corpus.report(cases, ["btplan", "fd"], 30.0)
    assert any("btplan / fd on the 1 problems" in line and "2.00" in line for line in lines)


def test_the_targets_judge_coverage_per_domain_and_time_on_small_and_large() -> None:
    corpus = _corpus()
    run = corpus.Run

    def case(domain: str, name: str, mine: tuple[bool, float], fd: bool,
             pyperplan: tuple[bool, float]) -> object:
        return corpus.Case(domain, name, {"btplan": run(mine[0], mine[1], 10.0, 3),
                                          "fd": run(fd, 1.0, 10.0, 3),
                                          "pyperplan": run(pyperplan[0], pyperplan[1], 10.0, 3)})

    cases = [case("a", "p01", (True, 1.0), True, (True, 2.0)),
             case("a", "p02", (True, 3.0), True, (True, 2.0)),
             case("b", "p01", (False, 1.0), True, (True, 2.0)),
             case("b", "p02", (True, 1.0), True, (True, 2.0))]
    lines = corpus.report(cases, ["btplan", "fd", "pyperplan"], 30.0)
    coverage = next(line for line in lines if "coverage on every domain" in line)
    assert coverage.endswith("missed (b 1/2)")
    timing = next(line for line in lines if "small and large" in line)
    assert "small 0.50 on 1, large 1.00 on 2" in timing and timing.endswith(": met")
    lines = corpus.report(cases[:2], ["btplan", "fd", "pyperplan"], 30.0)
    assert next(line for line in lines if "coverage on" in line).endswith(": met")
    assert next(line for line in lines if "small and large" in line).endswith(": missed")
