"""Exercises in the browser: the printable sheet rendered in Chromium, the instructor page and
the student mode (static/exercises.html), against the real server."""

from __future__ import annotations

import json
import re
import urllib.request
from typing import Any

import pytest

from tests.browser.conftest import AppPage

pytestmark = pytest.mark.browser


def export(app: AppPage, **body: Any) -> str:
    request = urllib.request.Request(
        f"{app.url}/api/v1/exercises/export",
        data=json.dumps(body).encode(),
        headers={"Content-Type": "application/json"},
        method="POST",
    )
    with urllib.request.urlopen(request, timeout=60) as response:
        text: str = response.read().decode()
        return text


@pytest.mark.parametrize("with_solutions", [False, True])
def test_the_printable_sheet_renders_with_its_figures(app: AppPage, with_solutions: bool) -> None:
    html = export(
        app, type="quick_return", seed=12, count=3, format="html", with_solutions=with_solutions
    )
    app.log.allow(r"favicon\.ico")  # asked for by the JSON page of /health, which has none
    app.page.goto(f"{app.url}/health")  # the app's origin, so /vendor/katex/ resolves
    app.page.set_content(html, wait_until="load")
    page = app.page
    assert page.locator("section.sheet").count() == 3
    figures = page.locator("section.sheet figure svg")
    assert figures.count() == 3
    for k in range(3):
        box = figures.nth(k).bounding_box()
        assert box is not None and box["width"] > 300 and box["height"] > 200
        assert figures.nth(k).locator("line, polygon").count() >= 3
    page.wait_for_function("document.querySelectorAll('.tex .katex').length > 0")
    assert page.locator(".tex .katex-error").count() == 0
    pdf = page.pdf(format="A4")
    pages = len(re.findall(rb"/Type\s*/Page[^s]", pdf))
    if with_solutions:
        assert pages >= 3
        assert page.locator(".step").count() > 30
    else:
        assert pages == 3  # one page per student
    app.screenshot(f"exercise-sheet-{'key' if with_solutions else 'student'}")
