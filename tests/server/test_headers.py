"""Security headers (issue 15): a CSP without inline script or unsafe-eval, nosniff, no framing,
and no CORS unless origins are configured. The pages the server sends (the app, the printable
solution, the OpenAPI page) carry no inline script, so they work under that CSP."""

from __future__ import annotations

from html.parser import HTMLParser

import pytest
from fastapi.testclient import TestClient

from server.app import app, create_app
from server.settings import Settings
from tests.server.test_errors import FOUR_BAR

client = TestClient(app, raise_server_exceptions=False)
RESPONSES = [
    ("GET", "/", None),
    ("GET", "/api/v1/docs", None),
    ("GET", "/api/v1/openapi.json", None),
    ("GET", "/api/v1/solution.html?preset=four_bar", None),
    ("POST", "/api/v1/solution.html", {"scene": FOUR_BAR}),
    ("POST", "/api/v1/analyze", {"scene": FOUR_BAR}),
    ("POST", "/api/v1/analyze", {"scene": {}}),  # a problem
    ("GET", "/api/v1/nowhere", None),  # a 404
    ("GET", "/health", None),
    ("GET", "/js/main.js", None),
]
PAGES = ["/", "/api/v1/docs", "/api/v1/solution.html?preset=four_bar"]


def directives(policy: str) -> dict[str, list[str]]:
    parts = (d.split() for d in policy.split(";") if d.strip())
    return {p[0]: p[1:] for p in parts}


@pytest.mark.parametrize(("method", "path", "body"), RESPONSES)
def test_every_response_carries_the_security_headers(method: str, path: str, body: object) -> None:
    response = client.request(method, path, json=body)
    csp = directives(response.headers["content-security-policy"])
    assert csp["script-src"] == ["'self'"]  # no 'unsafe-inline', no 'unsafe-eval'
    assert "'unsafe-eval'" not in response.headers["content-security-policy"]
    assert csp["frame-ancestors"] == ["'none'"] and csp["object-src"] == ["'none'"]
    assert response.headers["x-content-type-options"] == "nosniff"
    assert response.headers["x-frame-options"] == "DENY"


class _Scripts(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.inline: list[str] = []
        self.sources: list[str] = []
        self.handlers: list[str] = []
        self._in_inline = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        named = dict(attrs)
        self.handlers += [name for name, _ in attrs if name.startswith("on")]
        if tag == "script":
            if named.get("src"):
                self.sources.append(str(named["src"]))
            else:
                self._in_inline = True

    def handle_data(self, data: str) -> None:
        if self._in_inline and data.strip():
            self.inline.append(data.strip()[:60])

    def handle_endtag(self, tag: str) -> None:
        if tag == "script":
            self._in_inline = False


@pytest.mark.parametrize("path", PAGES)
def test_pages_have_no_inline_script_and_their_scripts_are_served(path: str) -> None:
    page = _Scripts()
    page.feed(client.get(path).text)
    assert page.inline == [] and page.handlers == []
    assert page.sources
    for source in page.sources:
        assert not source.startswith(("http:", "https:", "//")), source
        url = source if source.startswith("/") else f"/{source}"
        assert client.get(url).status_code == 200, source


def test_no_cors_by_default() -> None:
    response = client.post(
        "/api/v1/analyze", json={"scene": FOUR_BAR}, headers={"origin": "https://elsewhere.example"}
    )
    assert response.status_code == 200
    assert "access-control-allow-origin" not in response.headers
    preflight = client.options(
        "/api/v1/analyze",
        headers={
            "origin": "https://elsewhere.example",
            "access-control-request-method": "POST",
        },
    )
    assert "access-control-allow-origin" not in preflight.headers


def test_cors_for_the_configured_origins_only() -> None:
    allowed = TestClient(create_app(Settings(workers=0, cors_origins=("https://a.example",))))
    ok = allowed.post(
        "/api/v1/analyze", json={"scene": FOUR_BAR}, headers={"origin": "https://a.example"}
    )
    assert ok.headers["access-control-allow-origin"] == "https://a.example"
    other = allowed.post(
        "/api/v1/analyze", json={"scene": FOUR_BAR}, headers={"origin": "https://b.example"}
    )
    assert "access-control-allow-origin" not in other.headers
