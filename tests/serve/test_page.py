"""The live page in headless Chromium against a real server: type a mission and read it said back, set
the start on the map, plan and see the path, drive the simulated robot to the end, at desktop and phone
width, by mouse and by keyboard; no console error, no failed request. Screenshots of every step go to
``$SGPLAN_SCREENSHOTS`` when set (they were looked at; docs/serve.md describes them)."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import sgplan
from sgplan.starts import start_cell
from tests.browser import browser, launch, watch
from tests.serve.conftest import KITCHEN_TEXT, ServerProcess

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ServerProcess]:
    process = ServerProcess(tmp_path_factory.mktemp("state")).start()
    yield process
    process.kill()


@pytest.fixture
def page(server: ServerProcess) -> Iterator[tuple[Any, list[str]]]:
    sync_playwright, executable = browser()
    with sync_playwright() as p:  # type: ignore[operator]
        chromium = launch(p, executable)
        tab = chromium.new_page(viewport={"width": 1280, "height": 900})
        problems = watch(tab, quiet_failures=("/events",))  # a stream the page closes itself
        tab.on(
            "response", lambda r: problems.append(f"HTTP {r.status}: {r.url}") if r.status >= 400 else None
        )
        tab.goto(server.url + "/")
        tab.wait_for_selector(
            '#layers .floor[data-floor="1"][data-ready="true"]', state="attached", timeout=30_000
        )
        yield tab, problems
        chromium.close()


def shot(tab: Any, name: str) -> None:
    folder = os.environ.get("SGPLAN_SCREENSHOTS")
    if folder:
        Path(folder).mkdir(parents=True, exist_ok=True)
        tab.screenshot(path=str(Path(folder) / f"{name}.png"), full_page=True)


def on_screen(tab: Any, cell: tuple[int, int, int], shape: tuple[int, int]) -> tuple[float, float]:
    """Where ``cell`` is on the page: the map is drawn in the map frame (rows to the right, columns up)."""
    stage = tab.locator(f'#layers .floor[data-floor="{cell[2]}"] .stage')
    stage.scroll_into_view_if_needed()
    box = stage.bounding_box()
    rows, cols = shape
    return (
        box["x"] + (cell[0] + 0.5) / rows * box["width"],
        box["y"] + (cols - 1 - cell[1] + 0.5) / cols * box["height"],
    )


def _cost(tab: Any) -> float:
    return float(tab.locator("#status").inner_text().split("cost ")[1].split(" m")[0])


def test_type_plan_close_a_door_and_drive_the_robot(page: tuple[Any, list[str]]) -> None:
    tab, problems = page
    building = sgplan.load_scene("demo")
    session = sgplan.Session(building)
    dining, _ = start_cell(building, session.grid(), "dining_room")

    tab.fill("#mission", KITCHEN_TEXT)
    tab.wait_for_function("document.getElementById('explanation').textContent.includes('room_4, floor 0')")
    said = tab.locator("#explanation").inner_text()
    assert "Go to the kitchen (room_4, floor 0), then go to the bedroom (room_11, floor 1)" in said
    assert "Never enter the bathroom (room_5, floor 0)" in said
    shot(tab, "1-said-back")

    tab.fill("#mission", "Go to the kitchen.")
    tab.wait_for_function("document.getElementById('explanation').textContent.includes('Formula: F')")
    tab.mouse.click(*on_screen(tab, dining, building.floors[0].shape))
    assert tab.locator("#start-shown").inner_text() == f"cell row {dining[0]}, column {dining[1]}, floor 0"
    assert tab.locator('#layers .floor[data-floor="0"] svg.marks circle.chosen-start').count() == 1
    tab.locator("#plan").click()
    tab.wait_for_function("document.getElementById('status').textContent.startsWith('Run ')")
    assert "(in-progress): optimal" in tab.locator("#status").inner_text()
    overlay = tab.locator('#layers .floor[data-floor="0"] svg.overlay')
    assert overlay.locator("polyline.path").count() > 0 and overlay.locator("circle.start").count() == 1
    assert "Left: go to the kitchen (room_4, floor 0)" in tab.locator("#left").inner_text()
    first_path, first_cost = overlay.inner_html(), _cost(tab)
    shot(tab, "2-planned")

    # Hovering the map names the room (the report's hover, on the served floors).
    tab.mouse.move(*on_screen(tab, dining, building.floors[0].shape))
    assert "room: dining_room (room_7" in tab.locator("#tooltip").inner_text()

    # Close the corridor's door into the kitchen: the path goes round through the bathroom.
    door = tab.locator(
        'svg.marks rect.door[aria-label="close the door between the corridor and the kitchen"]'
    )
    door.click()
    tab.wait_for_function(
        f"document.getElementById('status').textContent.startsWith('Run ') && "
        f"!document.getElementById('status').textContent.includes('cost {first_cost:.2f} m')"
    )
    assert _cost(tab) > first_cost
    assert tab.locator('#layers .floor[data-floor="0"] svg.overlay').inner_html() != first_path
    assert tab.locator("svg.marks rect.door.closed").count() == 1
    tab.wait_for_function(
        "document.getElementById('log').textContent.includes('closed the door between the corridor')"
    )
    shot(tab, "3-door-closed")

    tab.locator("#play").click()
    tab.wait_for_function("document.getElementById('verdict').textContent.includes('done')", timeout=60_000)
    assert tab.locator("#left").inner_text() == "Nothing is left: the mission is done."
    assert tab.locator('#layers .floor[data-floor="0"] svg.marks circle.robot').count() == 1
    tab.wait_for_function("document.getElementById('log').textContent.includes('done: ')")
    shot(tab, "4-driven")
    assert problems == []


def test_keyboard_and_phone_width(page: tuple[Any, list[str]]) -> None:
    tab, problems = page
    tab.set_viewport_size({"width": 390, "height": 844})
    tab.focus("#start-room")
    tab.keyboard.type("kitchen")
    tab.keyboard.press("Tab")  # to the mission
    tab.keyboard.type("Go to the dining room.")
    tab.wait_for_function("document.getElementById('explanation').textContent.includes('dining room')")
    tab.wait_for_function("!document.getElementById('plan').disabled")
    tab.focus("#plan")
    tab.keyboard.press("Enter")
    tab.wait_for_function("document.getElementById('status').textContent.startsWith('Run ')")
    # Nothing wider than the phone's screen but the map, which scales with it.
    width = tab.evaluate("document.documentElement.scrollWidth")
    assert width <= 390
    shot(tab, "5-phone")
    tab.locator("#cancel-run").click()
    tab.wait_for_function("document.getElementById('status').textContent.includes('(cancelled)')")
    assert problems == []
