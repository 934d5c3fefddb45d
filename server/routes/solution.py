"""POST /api/v1/solution (worked solution as data) and /api/v1/solution.html (printable page).

The solution comes from ``solver.steps.solve``; ``results`` is exactly the /analyze body of the
same scene (the same analysis, converted by the same functions). The HTML page is standalone and
print-friendly: KaTeX from /vendor/katex/ typesets the steps in the browser, every step also has
its plain text, and nothing is loaded from another host.
"""

from __future__ import annotations

import html
import json
from collections.abc import Iterable, Mapping, Sequence
from typing import Annotated, Any, Literal

from fastapi import APIRouter, Query
from fastapi.responses import HTMLResponse
from pydantic import Field

from server import budget
from server.edge import FiniteJSONResponse
from server.responses import JSON, analysis_response, spatial_response
from server.routes.scenes import parse_scene
from server.schemas import EXAMPLES, Strict
from server.workers import WorkerRoute
from solver.analysis import QUANTITIES, LinkageAnalysis
from solver.presets import build_preset
from solver.scene import LinkageScene
from solver.spatial import SpatialChain
from solver.steps import Solution, solve

router = APIRouter(
    tags=["solutions"], route_class=WorkerRoute, default_response_class=FiniteJSONResponse
)

Method = Literal["vector", "loop"]


def _example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


class SolutionRequest(Strict):
    scene: dict[str, Any] = Field(
        description="A scene-v1 document: kind 'linkage' or 'spatial_chain'.",
        examples=[_example("S000-T2"), _example("S002-spatial-arm")],
    )
    method: Method = Field(
        "vector",
        description="'vector' (relative velocities, seed 000 form) or 'loop' (loop "
        "closure in complex form with Cramer's rule, seed 001 form; for linkages that are not "
        "chains of four-bar, slider-crank or slotted-lever loops the solution falls back to "
        "'vector' and says so).",
    )
    digits: int = Field(
        4,
        ge=1,
        le=15,
        strict=True,
        description="Significant digits of the numbers shown (1 to 15).",
    )


def solution_body(solution: Solution) -> JSON:
    """The /solution response: steps, mistakes, methods, and the /analyze body as results."""
    if isinstance(solution.analysis, LinkageAnalysis):
        results = analysis_response(solution.analysis)
    else:
        results = spatial_response(solution.analysis, frozenset(QUANTITIES))
    return {
        "method": solution.method,
        "requested_method": solution.requested_method,
        "digits": solution.digits,
        "steps": [step.as_json() for step in solution.steps],
        "mistakes": [mistake.as_json() for mistake in solution.mistakes],
        "results": results,
    }


def parse_and_budget(doc: Mapping[str, Any]) -> LinkageScene | SpatialChain:
    """The scene of a /solution request, refused before any work if it costs too much."""
    scene = parse_scene(doc)
    if isinstance(scene, LinkageScene):
        budget.instant(scene)
    return scene


@router.post("/solution", summary="Worked solution, step by step, in the textbook's form")
def solution_route(request: SolutionRequest) -> FiniteJSONResponse:
    scene = parse_and_budget(request.scene)
    return FiniteJSONResponse(solution_body(solve(scene, request.method, request.digits)))


# --- the printable page -------------------------------------------------------------------------

_CSS = """
:root { color-scheme: light; }
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 2rem auto;
       max-width: 60rem; padding: 0 1rem; color: #111; line-height: 1.45; }
h1 { font-size: 1.6rem; margin-bottom: 0.2rem; }
h2 { font-size: 1.25rem; border-bottom: 1px solid #999; padding-bottom: 0.2rem; margin-top: 2rem; }
h3 { font-size: 1rem; margin: 0 0 0.4rem; }
.meta { color: #444; margin-top: 0; }
table { border-collapse: collapse; margin: 0.5rem 0 1rem; font-size: 0.92rem; }
th, td { border: 1px solid #bbb; padding: 0.2rem 0.55rem; text-align: left; vertical-align: top; }
th { background: #eee; }
ol.steps { padding-left: 1.6rem; }
li.step { margin: 0 0 1.2rem; }
.math { overflow-x: auto; overflow-y: hidden; padding: 0.2rem 0; }
.math.error, .math.pending { font-family: ui-monospace, monospace; font-size: 0.8rem;
       white-space: pre-wrap; color: #555; }
.math.error { border-left: 3px solid #b00; padding-left: 0.5rem; }
p.text { margin: 0.3rem 0 0; color: #333; font-size: 0.92rem; }
ul.mistakes li { margin-bottom: 0.6rem; }
.note { border: 1px solid #c90; background: #fff8e6; padding: 0.5rem 0.8rem; }
button.print { float: right; font-size: 0.95rem; padding: 0.3rem 0.8rem; }
@media print {
  body { margin: 0; max-width: none; font-size: 10.5pt; }
  button.print { display: none; }
  h2 { break-after: avoid; }
  li.step, ul.mistakes li, table { break-inside: avoid; }
  .math { overflow: visible; }
  a { color: inherit; text-decoration: none; }
}
"""


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _vector(value: Any) -> str:
    if isinstance(value, list | tuple):
        return "(" + ", ".join(f"{float(x):.6g}" for x in value) + ")"
    return _e(value)


def _table(caption: str, header: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    """An HTML table: caption, a header row, and rows of cells already escaped."""
    head = "".join(f"<th>{h}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><caption>{caption}</caption><tr>{head}</tr>{body}</table>"


def _driver_motion(d: Mapping[str, Any]) -> str:
    if "angle_law" in d:
        return f"angle law {_e(d['angle_law'])} rad"
    return f"omega = {_e(d.get('omega', 0))} rad/s, alpha = {_e(d.get('alpha', 0))} rad/s^2" + (
        f", angle {_e(d['angle_deg'])} deg" if "angle_deg" in d else ""
    )


def _scene_tables(doc: Mapping[str, Any]) -> str:
    """The scene's data as tables (from the validated document)."""
    if doc.get("kind") == "spatial_chain":
        return _table(
            "Joints (origin m, rate rad/s or m/s)",
            ["joint", "type", "origin", "axis", "rate", "rate of rate"],
            (
                [
                    _e(j.get("name")),
                    _e(j.get("type")),
                    _vector(j.get("origin")),
                    _vector(j.get("axis")),
                    _e(j.get("rate")),
                    _e(j.get("rate_dot", 0)),
                ]
                for j in doc.get("joints", [])
            ),
        ) + _table(
            "Points (m)",
            ["point", "body", "position"],
            (
                [_e(n), _e(p.get("body")), _vector(p.get("position"))]
                for n, p in doc.get("points", {}).items()
            ),
        )
    parts = [
        _table(
            "Points as drawn (m)",
            ["point", "position"],
            ([_e(n), _vector(xy)] for n, xy in doc.get("points", {}).items()),
        ),
        _table(
            "Links",
            ["link", "points", ""],
            (
                [
                    _e(n),
                    _e(", ".join(map(str, link.get("points", [])))),
                    "ground" if link.get("ground") else "",
                ]
                for n, link in doc.get("links", {}).items()
            ),
        ),
        _table(
            "Joints (slider and prismatic: links = guide, follower)",
            ["type", "point", "links", "slot axis"],
            (
                [
                    _e(j.get("type")),
                    _e(j.get("point")),
                    _e(", ".join(map(str, j.get("links", [])))),
                    _vector(j["axis"]) if "axis" in j else "",
                ]
                for j in doc.get("joints", [])
            ),
        ),
        _table(
            "Drivers",
            ["link", "motion"],
            ([_e(d.get("link")), _driver_motion(d)] for d in doc.get("drivers", [])),
        ),
    ]
    moving = doc.get("moving_points", [])
    if moving:
        parts.append(
            _table(
                "Moving points (s in m, t in s)",
                ["point", "carrier", "path", "s(t)"],
                (
                    [
                        _e(m.get("name")),
                        _e(m.get("link")),
                        _e(json.dumps(m.get("path"))),
                        _e(m.get("s_law")),
                    ]
                    for m in moving
                ),
            )
        )
    if "time" in doc:
        parts.append(f"<p>Analysed instant: t = {_e(doc['time'])} s.</p>")
    return "".join(parts)


def solution_page(doc: Mapping[str, Any], solution: Solution) -> str:
    """The standalone, print-friendly HTML page of a worked solution."""
    title = doc.get("title") or (
        "spatial chain" if doc.get("kind") == "spatial_chain" else "linkage"
    )
    method = {
        "vector": "relative velocities (vector method)",
        "loop": "loop closure in complex form",
    }[solution.method]
    steps = "".join(
        f'<li class="step"><h3>{_e(s.title)}</h3>'
        + (
            f'<div class="math pending" data-latex="{_e(s.latex)}">{_e(s.latex)}</div>'
            if s.latex
            else ""
        )
        + f'<p class="text">{_e(s.text)}</p></li>'
        for s in solution.steps
    )
    mistakes = "".join(
        f"<li><strong>{_e(m.title)}</strong><br>{_e(m.text)}</li>" for m in solution.mistakes
    )
    note = ""
    if solution.fell_back:
        note = (
            f'<p class="note">The {_e(solution.requested_method)} method does not apply to '
            "this scene; the first step says why.</p>"
        )
    return f"""<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Worked solution: {_e(title)}</title>
<link rel="icon" href="/favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="/vendor/katex/katex.min.css">
<style>{_CSS}</style>
</head>
<body>
<header>
<button class="print" type="button">Print</button>
<h1>Worked solution: {_e(title)}</h1>
<p class="meta">Method: {_e(method)}. Numbers to {solution.digits} significant digits, SI units;
z out of the page, angular velocities counter-clockwise positive.</p>
{note}
</header>
<main>
<section aria-labelledby="data-title"><h2 id="data-title">Scene</h2>{_scene_tables(doc)}</section>
<section aria-labelledby="steps-title"><h2 id="steps-title">Solution</h2>
<ol class="steps">{steps}</ol></section>
<section aria-labelledby="mistakes-title"><h2 id="mistakes-title">Typical mistakes</h2>
<ul class="mistakes">{mistakes or "<li>None listed for this scene.</li>"}</ul></section>
</main>
<script src="/vendor/katex/katex.min.js"></script>
<script src="/js/solution-page.js"></script>
</body>
</html>
"""


def _page(doc: Mapping[str, Any], method: str, digits: int) -> HTMLResponse:
    solution = solve(parse_and_budget(doc), method, digits)
    return HTMLResponse(solution_page(doc, solution))


@router.get(
    "/solution.html",
    summary="Printable worked solution of a textbook preset",
    response_class=HTMLResponse,
)
def solution_page_preset(
    preset: Annotated[str, Query(max_length=64, description="A preset name (GET /presets).")],
    method: Annotated[Method, Query()] = "vector",
    digits: Annotated[int, Query(ge=1, le=15)] = 4,
) -> HTMLResponse:
    return _page(build_preset(preset, {}), method, digits)


@router.post(
    "/solution.html", summary="Printable worked solution of a scene", response_class=HTMLResponse
)
def solution_page_scene(request: SolutionRequest) -> HTMLResponse:
    return _page(request.scene, request.method, request.digits)
