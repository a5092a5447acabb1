"""The browser view in headless Chromium: how long a 3,000-node tree takes to show, and
the screenshots of Example 2 growing that docs/monitor.md shows.

Time to show: from asking for the page to the page drawn (the tree laid out and every
node on screen), measured by the page itself (`performance.now()`, from navigation
start) and by the script (wall clock around `driver.get` and the wait), best and median
of `--repeat` loads, for trees of 1,000, 3,000 and 10,000 nodes.

    python bench/browser_view.py               # about half a minute
    python bench/browser_view.py --shots docs/images
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from typer.testing import CliRunner

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "monitor"))

from btplan.cli import app  # noqa: E402
from btplan.cli.view import read_trace  # noqa: E402
from btplan.monitor.browser import BrowserView, TraceLines  # noqa: E402
from big_trees import big_trace  # noqa: E402


def driver() -> object:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "chromium"
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu",
                     "--disable-dev-shm-usage", "--window-size=1400,900"):
        options.add_argument(argument)
    return webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)


def load(browser: object, url: str) -> tuple[float, float, int]:
    """Page-side ms to ready, wall-clock ms to ready, nodes drawn."""
    started = time.perf_counter()
    browser.get(url)  # type: ignore[attr-defined]
    while browser.execute_script("return document.body.dataset.ready") != "1":  # type: ignore[attr-defined]
        time.sleep(0.005)
    wall = (time.perf_counter() - started) * 1000
    page = float(browser.execute_script("return document.body.dataset.readyMs"))  # type: ignore[attr-defined]
    nodes = browser.execute_script("return document.querySelectorAll('#tree g.node').length")  # type: ignore[attr-defined]
    return page, wall, int(nodes)


def time_to_show(browser: object, repeat: int) -> None:
    print(f"{'nodes':>7}{'page ms (best/median)':>26}{'wall ms (best/median)':>26}")
    for size in (1000, 3000, 10000):
        server = BrowserView(TraceLines(big_trace(size)), f"{size} nodes", 0, live=False)
        try:
            runs = [load(browser, server.url) for _ in range(repeat)]
        finally:
            server.close()
        assert all(n == size for *_, n in runs)
        page = [p for p, _, _ in runs]
        wall = [w for _, w, _ in runs]
        print(f"{size:>7}{min(page):>14.0f} / {statistics.median(page):<9.0f}"
              f"{min(wall):>14.0f} / {statistics.median(wall):<9.0f}")


def screenshots(browser: object, folder: Path) -> None:
    from selenium.webdriver.common.by import By

    trace = Path(tempfile.mkdtemp()) / "example2.jsonl"
    result = CliRunner().invoke(app, ["run", str(ROOT / "domains/pick_place_obstacle.bt"),
                                      "--scenario", str(ROOT / "examples/example2.dist"),
                                      "--trace", str(trace), "-q"])
    assert result.exit_code == 0, result.output
    lines = read_trace(str(trace))
    ticks = [json.loads(line)["tick"] for line in lines]
    server = BrowserView(TraceLines(lines), "Example 2 (examples/example2.dist)", 0, live=False)
    folder.mkdir(parents=True, exist_ok=True)
    try:
        browser.set_window_size(1700, 1300)  # type: ignore[attr-defined]
        load(browser, server.url)
        browser.find_element(By.ID, "follow").click()  # type: ignore[attr-defined]
        for tick in (1, 5, 15, ticks[-1]):
            browser.execute_script(  # type: ignore[attr-defined]
                "const s = document.getElementById('scrub'); s.value = arguments[0];"
                "s.dispatchEvent(new Event('input'));", ticks.index(tick))
            browser.execute_script("document.getElementById('tree-pane').scrollTo(0, 0)")  # type: ignore[attr-defined]
            browser.save_screenshot(str(folder / f"view-example2-tick{tick:02d}.png"))  # type: ignore[attr-defined]
            print("wrote", folder / f"view-example2-tick{tick:02d}.png")
    finally:
        server.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--shots", type=Path, help="write the Example 2 screenshots here")
    args = parser.parse_args()
    browser = driver()
    try:
        time_to_show(browser, args.repeat)
        if args.shots is not None:
            screenshots(browser, args.shots)
    finally:
        browser.quit()  # type: ignore[attr-defined]


if __name__ == "__main__":
    main()
