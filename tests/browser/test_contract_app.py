"""The browser draws, the server computes (issue 9): one /solution per pause carries the
analysis and the polygons' segments, the acceleration polygon draws the server's segments, and
the server's warnings reach the status line."""

from __future__ import annotations

import base64
import json
from typing import Any

import pytest

from solver.teaching.presets import build_preset
from tests.browser.conftest import AppPage
from tests.browser.test_app import pause_and_wait, wait_analysed, wait_until

pytestmark = pytest.mark.browser


def api_calls(app: AppPage) -> list[str]:
    """The API paths the page asked for so far (a short wait lets Playwright deliver events)."""
    app.page.wait_for_timeout(50)
    return [u.split("/api/v1", 1)[1] for u in app.log.requests if "/api/v1/" in u]


def test_one_request_per_pause_and_the_servers_segments(app: AppPage) -> None:
    app.open()
    page = app.page
    pause_and_wait(page)
    # The paused instant's worked solution is asked for a frame after its polygons are drawn:
    # counted before the requests of the next instant.
    wait_until(lambda: api_calls(app)[-1:] == ["/solution"], what="the paused instant's solution")
    before = len(api_calls(app))
    page.focus("#crank-angle")
    page.keyboard.press("ArrowRight")
    wait_analysed(page)
    wait_until(lambda: len(api_calls(app)) > before, what="the request of the new instant")
    page.wait_for_timeout(1000)  # nothing else follows
    # The instant as drawn (/analyze with the polygons), then its worked solution, once each.
    assert api_calls(app)[before:] == ["/analyze", "/solution"]
    # The normal parts drawn are the server's segments, one arrow each (x: from, to, gap).
    angle = float(page.input_value("#crank-angle"))
    scene = build_preset("four_bar", {})
    scene["drivers"][0]["angle_deg"] = angle
    status, solution = app.post("/solution", {"scene": scene})
    assert status == 200
    segments = solution["polygons"]["segments"]
    normal = json.loads(
        page.evaluate(
            """JSON.stringify(document.getElementById('acceleration-polygon').data
                .find((t) => t.name.startsWith('normal part')).x)"""
        )
    )
    assert len(normal) == 3 * len(segments) > 0


def share_link(app: AppPage, scene: dict[str, Any]) -> str:
    state = {"v": 1, "scene": scene, "source": {"type": "shared"}, "view": {"playing": False}}
    token = base64.urlsafe_b64encode(json.dumps(state).encode()).decode().rstrip("=")
    return f"{app.url}/#s=j.{token}"


def test_a_typo_in_a_scene_is_shown_not_swallowed(app: AppPage) -> None:
    scene = build_preset("four_bar", {})
    scene["drivers"][0]["omegaa"] = 2.0
    app.page.goto(share_link(app, scene))
    app.wait_ready()
    wait_until(
        lambda: (
            "drivers[0].omegaa is not a scene field; did you mean omega?"
            in app.page.inner_text("#status")
        ),
        what="the warning on the status line",
    )
    assert app.page.get_attribute("#status", "data-level") == "warning"
