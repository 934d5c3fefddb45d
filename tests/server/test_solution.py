"""HTTP tests of POST /api/v1/solution and the printable /api/v1/solution.html (issue 4).

Sources: the spec ../shared/spec/scene-v1.md (/solution: steps with title, latex, text; results =
the /analyze response; errors as problem+json with a stable code), and the reference scenes of
server/examples. The arithmetic of the steps is re-evaluated with ``verify`` of
tests/solver/solutions/test_solve.py (independent of solver.solutions).
"""

from __future__ import annotations

import copy
import json
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.app import app
from solver.teaching.presets import PRESETS
from tests.solver.solutions.test_solve import unit_floors, verify

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
# A gear train's worked solution: tests/server/test_gear_solution.py; every other example.
SCENES = sorted(
    p.stem for p in EXAMPLES.glob("*.json") if json.loads(p.read_text())["kind"] != "gear_train"
)
PROBLEM = "application/problem+json"
client = TestClient(app)


def example(name: str) -> dict[str, Any]:
    doc: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return doc


def post(body: dict[str, Any]) -> Any:
    return client.post("/api/v1/solution", json=body)


@pytest.mark.parametrize("method", ["vector", "loop"])
@pytest.mark.parametrize("name", SCENES)
def test_solution_results_equal_analyze(name: str, method: str) -> None:
    """Spec: 'results' is the /analyze response for the same scene; every step has title, latex,
    text, values, and its checks re-evaluate."""
    scene = example(name)
    response = post({"scene": scene, "method": method})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["results"] == client.post("/api/v1/analyze", json={"scene": scene}).json()
    assert body["requested_method"] == method and body["method"] in ("vector", "loop")
    assert body["digits"] == 4
    assert body["steps"] and body["steps"][-1]["kind"] == "summary"
    floors = unit_floors(body["steps"])
    for step in body["steps"]:
        assert {"title", "latex", "text", "values", "checks", "kind"} <= set(step)
        assert step["title"] and step["text"]
        assert not verify(step, floors), verify(step, floors)[:2]
    for mistake in body["mistakes"]:
        assert mistake["title"] and mistake["text"]


def test_solution_of_s000_t2_in_the_response() -> None:
    body = post({"scene": example("S000-T2")}).json()
    coriolis = [s for s in body["steps"] if s["kind"] == "acceleration.coriolis"]
    assert len(coriolis) == 1
    value = coriolis[0]["values"]["a_cor(B)"]
    assert value["display"] == "(2.771, 0) m/s^2"
    assert value["source"] == ["joints", 0, "coriolis_acceleration"]
    assert value["value"] == body["results"]["joints"][0]["coriolis_acceleration"]


def test_digits_select_the_displayed_precision() -> None:
    scene = example("S000-T1")
    for digits, shown in ((2, "0.094 rad/s^2"), (8, "0.09375 rad/s^2")):
        body = post({"scene": scene, "digits": digits}).json()
        step = next(s for s in body["steps"] if s["kind"] == "acceleration.dyad.solve")
        assert step["values"]["alpha(coupler)"]["display"] == shown


@pytest.mark.parametrize("extra", [
    {"digits": 0}, {"digits": 16}, {"digits": "4"}, {"digits": 4.5}, {"method": "graphical"},
    {"method": None}, {"unknown": 1},
])  # fmt: skip
def test_bad_options_are_422_problems(extra: dict[str, Any]) -> None:
    response = post({"scene": example("S000-T1"), **extra})
    assert response.status_code == 422
    assert response.headers["content-type"].startswith(PROBLEM)
    assert response.json()["code"] == "invalid_scene"


def test_solver_errors_are_mapped_to_their_codes() -> None:
    scene = copy.deepcopy(example("S000-T1"))
    scene["drivers"][0]["angle_deg"] = 180.0  # |BD| = 3.5 m > 2 + 1.118 m
    response = post({"scene": scene})
    assert response.status_code == 422 and response.json()["code"] == "not_assemblable"
    scene = copy.deepcopy(example("S000-T1"))
    del scene["links"]["rocker"]
    response = post({"scene": scene})
    assert response.status_code == 422 and response.json()["code"] == "invalid_scene"
    response = post({"scene": {"kind": "tetrahedron"}})
    assert response.status_code == 422 and response.json()["code"] == "invalid_scene"


def test_loop_method_on_a_spatial_chain_falls_back_and_says_so() -> None:
    body = post({"scene": example("S002-spatial-arm"), "method": "loop"}).json()
    assert body["method"] == "vector" and body["requested_method"] == "loop"
    assert body["steps"][0]["kind"] == "fallback"


def test_non_finite_numbers_are_rejected() -> None:
    text = json.dumps({"scene": example("S000-T1")}).replace("-1.0", "NaN", 1)
    response = client.post(
        "/api/v1/solution", content=text, headers={"content-type": "application/json"}
    )
    assert response.status_code == 422


# --- the printable page -------------------------------------------------------------------------


class _Page(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.latex: list[str] = []
        self.urls: list[str] = []
        self.scripts: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        found = dict(attrs)
        if found.get("data-latex") is not None:
            self.latex.append(str(found["data-latex"]))
        for key in ("src", "href"):
            if found.get(key):
                self.urls.append(str(found[key]))
        if tag == "script":
            self.scripts.append(str(found.get("src")))


def _page(text: str) -> _Page:
    page = _Page()
    page.feed(text)
    return page


@pytest.mark.parametrize("name", list(PRESETS))
def test_printable_page_of_every_preset(name: str) -> None:
    response = client.get(f"/api/v1/solution.html?preset={name}")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    page = _page(response.text)
    assert "/vendor/katex/katex.min.js" in page.scripts
    assert "/vendor/katex/katex.min.css" in page.urls
    assert all(url.startswith("/") and not url.startswith("//") for url in page.urls), page.urls
    assert "http://" not in response.text and "https://" not in response.text
    assert "@media print" in response.text and "Typical mistakes" in response.text
    scene = client.post(f"/api/v1/presets/{name}").json()
    body = post({"scene": scene}).json()
    assert page.latex == [s["latex"] for s in body["steps"] if s["latex"]]


@pytest.mark.parametrize(
    ("name", "query", "options"),
    [
        ("cam_roller_translating", "&angle_deg=60", {"angle_deg": 60}),
        ("planetary_ring_fixed", "", {}),
    ],
)
def test_printable_page_of_a_cam_or_gear_train_preset(
    name: str, query: str, options: dict[str, Any]
) -> None:
    """GET /solution.html?preset= takes a preset of any family: the page has the steps of
    POST /solution of the preset's scene (a cam's at angle_deg)."""
    response = client.get(f"/api/v1/solution.html?preset={name}{query}")
    assert response.status_code == 200
    scene = client.post(f"/api/v1/presets/{name}").json()
    body = post({"scene": scene, **options}).json()
    assert _page(response.text).latex == [s["latex"] for s in body["steps"] if s["latex"]]
    if options:
        assert (
            _page(response.text).latex
            != _page(client.get(f"/api/v1/solution.html?preset={name}").text).latex
        )


def test_printable_page_by_post_with_options_and_escaping() -> None:
    scene = example("S000-T2")
    scene["title"] = "<script>alert(1)</script> & co"
    response = client.post(
        "/api/v1/solution.html", json={"scene": scene, "method": "loop", "digits": 6}
    )
    assert response.status_code == 200
    assert "<script>alert(1)" not in response.text
    assert "&lt;script&gt;alert(1)&lt;/script&gt; &amp; co" in response.text
    assert "loop closure in complex form" in response.text
    assert "6 significant digits" in response.text
    page = _page(response.text)
    assert "None" not in page.scripts  # no inline script (CSP): KaTeX is started from a file
    assert "/js/solution-page.js" in page.scripts
    assert any(r"\begin{vmatrix}" in latex for latex in page.latex)


def test_printable_page_errors_are_problems() -> None:
    response = client.get("/api/v1/solution.html?preset=nope")
    assert response.status_code == 422 and response.json()["code"] == "invalid_scene"
    assert response.headers["content-type"].startswith(PROBLEM)
    response = client.get("/api/v1/solution.html?preset=four_bar&digits=0")
    assert response.status_code == 422
    response = client.get("/api/v1/solution.html")
    assert response.status_code == 422


def test_vendored_katex_is_served() -> None:
    for path in ("/vendor/katex/katex.min.js", "/vendor/katex/katex.min.css"):
        assert client.get(path).status_code == 200


def test_printable_page_honours_every_preset_parameter() -> None:
    """GET /solution.html?preset=four_bar&crank=0.2: the page is the solution of the preset with
    crank = 0.2 m (the same steps as POST /solution of that scene), never the default silently."""
    response = client.get("/api/v1/solution.html?preset=four_bar&crank=0.2&crank_angle_deg=50")
    assert response.status_code == 200
    scene = client.post("/api/v1/presets/four_bar", json={"crank": 0.2, "crank_angle_deg": 50})
    body = post({"scene": scene.json()}).json()
    assert _page(response.text).latex == [s["latex"] for s in body["steps"] if s["latex"]]
    default = _page(client.get("/api/v1/solution.html?preset=four_bar").text).latex
    assert _page(response.text).latex != default
    for bad in ("cranck=0.2", "crank=abc", "crank=-1", "crank=nan", "crank=0.2&crank=0.3"):
        response = client.get(f"/api/v1/solution.html?preset=four_bar&{bad}")
        assert response.status_code == 422, bad
        assert response.json()["code"] == "invalid_scene", bad


def test_a_law_that_overflows_later_is_solved_as_analyze_answers() -> None:
    """Issue 28: s = exp(100 t) overflows a float past t = 7.1 s; the event step's search for
    s = pi R over 60 s raised OverflowError (500) while /analyze at t = 1 s answers. Both
    answer now, s(0) = 1 m already past pi R (no event step)."""
    scene = example("S003-T1-translating-carrier")
    scene["moving_points"][0]["s_law"] = "exp(100*t)"
    analyzed = client.post("/api/v1/analyze", json={"scene": scene})
    assert analyzed.status_code == 200, analyzed.text[:300]
    solved = post({"scene": scene})
    assert solved.status_code == 200, solved.text[:300]
    assert solved.json()["steps"]
