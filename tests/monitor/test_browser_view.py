"""The browser view in a real headless browser: Debian's Chromium driven through its own
chromedriver by Selenium (`.ci/run` installs both; nothing is downloaded).

The page is served by btplan (a saved trace, or a live `btplan run --view`) and used as a
user would: it loads, shows the tree with the statuses of the tick the timeline is at,
scrubs, follows a live run, and stays usable with a tree of 3,000 nodes."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.cli import app
from btplan.cli.view import read_trace
from btplan.monitor.browser import BrowserView, TraceLines
from big_trees import big_trace
from peers import free_port

ROOT = Path(__file__).resolve().parents[2]
OBSTACLE = str(ROOT / "domains" / "pick_place_obstacle.bt")
EXAMPLE2 = str(ROOT / "examples" / "example2.dist")
CHROMIUM, DRIVER = shutil.which("chromium"), shutil.which("chromedriver")

if not (CHROMIUM and DRIVER) and os.environ.get("CI") != "true":
    pytest.skip("Debian's chromium and chromium-driver are not installed (.ci/run installs "
                "them)", allow_module_level=True)


@pytest.fixture(scope="module")
def browser() -> Iterator[object]:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    assert CHROMIUM and DRIVER, "CI must have chromium and chromedriver (.ci/run)"
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu",
                     "--disable-dev-shm-usage", "--window-size=1400,900"):
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service(DRIVER), options=options)
    yield driver
    driver.quit()


def wait_for(predicate: object, seconds: float = 30.0) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if predicate():  # type: ignore[operator]
            return
        time.sleep(0.05)
    raise AssertionError("the page did not get there in time")


def ready(driver: object) -> None:
    wait_for(lambda: driver.execute_script("return document.body.dataset.ready") == "1")  # type: ignore[attr-defined]


def drawn(driver: object) -> dict[int, str | None]:
    """uid -> data-status of every node the page draws."""
    return {int(uid): status for uid, status in driver.execute_script(  # type: ignore[attr-defined]
        "return [...document.querySelectorAll('#tree g.node')]"
        ".map(g => [g.dataset.uid, g.getAttribute('data-status')])")}


@pytest.fixture(scope="module")
def example2(tmp_path_factory: pytest.TempPathFactory) -> list[dict[str, object]]:
    trace = tmp_path_factory.mktemp("view") / "example2.jsonl"
    result = CliRunner().invoke(app, ["run", OBSTACLE, "--scenario", EXAMPLE2, "--trace",
                                      str(trace), "-q"])
    assert result.exit_code == 0, result.output
    return [json.loads(line) for line in read_trace(str(trace))]


def serve(lines: list[dict[str, object]]) -> BrowserView:
    return BrowserView(TraceLines([json.dumps(line) for line in lines]), "example 2", 0,
                       live=False)


def tree_at(lines: list[dict[str, object]], index: int) -> list[list[object]]:
    return next(line["tree"] for line in reversed(lines[:index + 1]) if "tree" in line)  # type: ignore[return-value]


def test_a_saved_run_shows_the_tree_and_the_statuses_of_the_tick_chosen(
        browser: object, example2: list[dict[str, object]]) -> None:
    from selenium.webdriver.common.by import By

    server = serve(example2)
    try:
        browser.get(server.url)  # type: ignore[attr-defined]
        ready(browser)
        grew = next(i for i, line in enumerate(example2) if i and line.get("tree"))
        for _ in range(grew):
            browser.find_element(By.ID, "next").click()  # type: ignore[attr-defined]
        tick = example2[grew]["tick"]
        assert browser.find_element(By.ID, "tick-label").text.startswith(f"tick {tick} of")  # type: ignore[attr-defined]
        shown = drawn(browser)
        rows = tree_at(example2, grew)
        assert len(shown) == len(rows)  # every node of the tree at that tick
        statuses = dict(example2[grew]["statuses"])  # type: ignore[arg-type]
        assert shown == {uid: statuses.get(uid) for uid, *_ in rows}
        before = {uid for uid, *_ in tree_at(example2, grew - 1)}
        new = {int(uid) for uid in browser.execute_script(  # type: ignore[attr-defined]
            "return [...document.querySelectorAll('#tree g.node.new')].map(g => g.dataset.uid)")}
        assert new == {uid for uid, *_ in rows} - before and new
        facts = [li.text for li in browser.find_elements(By.CSS_SELECTOR, "#facts li:not(.removed)")]  # type: ignore[attr-defined]
        expected = set(example2[0]["facts_at_start"])  # type: ignore[arg-type]
        for line in example2[:grew + 1]:
            expected -= set(line["facts"]["removed"])  # type: ignore[index]
            expected |= set(line["facts"]["added"])  # type: ignore[index]
        assert facts == sorted(expected)
        events = browser.find_element(By.ID, "tick-events").text  # type: ignore[attr-defined]
        assert "set blocks(sphere, tau_goal)" in events and "grew" in events
        labels = browser.execute_script(  # type: ignore[attr-defined]
            "return [...document.querySelectorAll('#tree g.node text')].map(t => t.textContent)")
        assert "MoveTo(sphere, tau_sphere)" in labels  # text in the page, not pixels
    finally:
        server.close()


def test_scrubbing_moves_tick_by_tick(browser: object,
                                      example2: list[dict[str, object]]) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    server = serve(example2)
    try:
        browser.get(server.url)  # type: ignore[attr-defined]
        ready(browser)
        scrub = browser.find_element(By.ID, "scrub")  # type: ignore[attr-defined]
        scrub.send_keys(Keys.END)
        last = example2[-1]["tick"]
        wait_for(lambda: browser.execute_script("return document.body.dataset.tick") == str(last))  # type: ignore[attr-defined]
        for step in range(1, 4):
            scrub.send_keys(Keys.ARROW_LEFT)
            index = len(example2) - 1 - step
            wait_for(lambda i=index: browser.execute_script(  # type: ignore[attr-defined]
                "return document.body.dataset.tick") == str(example2[i]["tick"]))
            statuses = dict(example2[index]["statuses"])  # type: ignore[arg-type]
            shown = drawn(browser)
            assert {u: s for u, s in shown.items() if s} == statuses
        scrub.send_keys(Keys.HOME)
        wait_for(lambda: browser.execute_script("return document.body.dataset.tick") == "1")  # type: ignore[attr-defined]
    finally:
        server.close()


def test_a_live_run_updates_the_page_as_it_goes(browser: object) -> None:
    port = free_port()
    run = subprocess.Popen([sys.executable, "-m", "btplan", "run", OBSTACLE, "--scenario",
                            EXAMPLE2, "--view", str(port), "--hz", "4", "-q"], cwd=ROOT,
                           text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        url = f"http://127.0.0.1:{port}/"
        deadline = time.monotonic() + 60
        while True:
            try:
                browser.get(url)  # type: ignore[attr-defined]
                ready(browser)
                break
            except Exception:  # noqa: BLE001 (the run is not serving yet)
                if time.monotonic() > deadline or run.poll() is not None:
                    raise
                time.sleep(0.2)
        first = int(browser.execute_script("return document.body.dataset.tick"))  # type: ignore[attr-defined]
        sizes = [len(drawn(browser))]
        wait_for(lambda: int(browser.execute_script(  # type: ignore[attr-defined]
            "return document.body.dataset.tick")) > first + 3, 60)
        _, err = run.communicate(timeout=60)
        assert run.returncode == 0, err
        wait_for(lambda: browser.execute_script(  # type: ignore[attr-defined]
            "return document.getElementById('live').hidden"), 10)
        sizes.append(len(drawn(browser)))
        assert sizes[-1] > sizes[0]  # the tree grew in front of the user
        assert int(browser.execute_script("return document.body.dataset.tick")) >= 19  # type: ignore[attr-defined]
    finally:
        if run.poll() is None:
            run.kill()


def test_a_3000_node_tree_renders_and_its_search_finds_a_node(browser: object) -> None:
    from selenium.webdriver.common.by import By

    lines = big_trace(3000)
    rows = json.loads(lines[0])["tree"]
    uid, _, _, name = next(row for row in rows[1500:] if row[2] == "Condition")
    server = BrowserView(TraceLines(lines), "3,000 nodes", 0, live=False)
    try:
        browser.get(server.url)  # type: ignore[attr-defined]
        ready(browser)
        assert len(drawn(browser)) == 3000
        query = browser.find_element(By.ID, "query")  # type: ignore[attr-defined]
        query.send_keys(name.split(",")[0])
        wait_for(lambda: browser.find_element(By.ID, "matches").text == "1 of 1")  # type: ignore[attr-defined]
        found = browser.find_element(By.CSS_SELECTOR, "#tree g.node.match")  # type: ignore[attr-defined]
        assert found.get_attribute("data-uid") == str(uid)
        assert browser.execute_script(  # type: ignore[attr-defined]
            "const r = arguments[0].getBoundingClientRect();"
            "return r.top >= 0 && r.bottom <= innerHeight", found)  # scrolled into view
        browser.find_element(By.ID, "collapse-quiet").click()  # type: ignore[attr-defined]
        assert len(drawn(browser)) < 100  # only the branch to the running node is left open
        browser.find_element(By.ID, "expand-all").click()  # type: ignore[attr-defined]
        assert len(drawn(browser)) == 3000
    finally:
        server.close()


@pytest.mark.slow
def test_a_simulated_run_shows_the_camera_beside_the_tree(browser: object) -> None:
    port = free_port()
    run = subprocess.Popen([sys.executable, "-m", "btplan", "run", "domains/youbot.bt", "--sim",
                            "pybullet", "--view", str(port), "--hz", "50", "-q"], cwd=ROOT,
                           text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                browser.get(f"http://127.0.0.1:{port}/")  # type: ignore[attr-defined]
                ready(browser)
                break
            except Exception:  # noqa: BLE001 (not serving yet)
                if time.monotonic() > deadline or run.poll() is not None:
                    raise
                time.sleep(0.2)
        wait_for(lambda: browser.execute_script(  # type: ignore[attr-defined]
            "const i = document.getElementById('frame');"
            "return !i.hidden && i.complete && i.naturalWidth === 320"), 30)
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/frame?tick=100000") as reply:
            assert reply.read(8) == b"\x89PNG\r\n\x1a\n"
        _, err = run.communicate(timeout=120)
        assert run.returncode == 0, err
    finally:
        if run.poll() is None:
            run.kill()
