"""POST /api/v1/solution (worked solution as data) and /api/v1/solution.html (printable page).

The solution comes from ``solver.steps.solve``; ``results`` is exactly the /analyze body of the
same scene (the same analysis, converted by the same functions). The HTML page is standalone and
print-friendly: KaTeX from /vendor/katex/ typesets the steps in the browser, every step also has
its plain text, and nothing is loaded from another host.
"""

from __future__ import annotations

import html
import json
from collections.abc import Mapping
from typing import Annotated, Any, Literal

from fastapi import APIRouter, Query
from fastapi.responses import HTMLResponse
from pydantic import Field

from server.edge import FiniteJSONResponse, StrictJSONRoute
from server.responses import JSON, analysis_response, spatial_response
from server.routes.scenes import parse_scene
from server.schemas import EXAMPLES, Strict
from solver.analysis import QUANTITIES, LinkageAnalysis
from solver.presets import build_preset
from solver.steps import Solution, solve

router = APIRouter(
    tags=["solutions"], route_class=StrictJSONRoute, default_response_class=FiniteJSONResponse
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


@router.post("/solution", summary="Worked solution, step by step, in the textbook's form")
def solution_route(request: SolutionRequest) -> FiniteJSONResponse:
    scene = parse_scene(request.scene)
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

_SCRIPT = """
document.querySelectorAll('.math[data-latex]').forEach(function (el) {
  if (!window.katex) { el.classList.remove('pending'); el.classList.add('error'); return; }
  try {
    katex.render(el.getAttribute('data-latex'), el,
                 {displayMode: true, throwOnError: true, strict: 'ignore', trust: false});
    el.classList.remove('pending');
  } catch (err) {
    el.classList.remove('pending');
    el.classList.add('error');
    el.title = 'KaTeX could not read this step: ' + err.message;
  }
});
document.querySelectorAll('button.print').forEach(function (b) {
  b.addEventListener('click', function () { window.print(); });
});
"""


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _vector(value: Any) -> str:
    if isinstance(value, list | tuple):
        return "(" + ", ".join(f"{float(x):.6g}" for x in value) + ")"
    return _e(value)


def _scene_tables(doc: Mapping[str, Any]) -> str:
    """The scene's data as tables (from the validated document)."""
    parts = []
    if doc.get("kind") == "spatial_chain":
        rows = "".join(
            f"<tr><td>{_e(j.get('name'))}</td><td>{_e(j.get('type'))}</td>"
            f"<td>{_vector(j.get('origin'))}</td><td>{_vector(j.get('axis'))}</td>"
            f"<td>{_e(j.get('rate'))}</td><td>{_e(j.get('rate_dot', 0))}</td></tr>"
            for j in doc.get("joints", [])
        )
        parts.append(
            "<table><caption>Joints (origin m, rate rad/s or m/s)</caption><tr>"
            "<th>joint</th><th>type</th><th>origin</th><th>axis</th><th>rate</th>"
            f"<th>rate of rate</th></tr>{rows}</table>"
        )
        rows = "".join(
            f"<tr><td>{_e(n)}</td><td>{_e(p.get('body'))}</td>"
            f"<td>{_vector(p.get('position'))}</td></tr>"
            for n, p in doc.get("points", {}).items()
        )
        parts.append(
            "<table><caption>Points (m)</caption><tr><th>point</th><th>body</th>"
            f"<th>position</th></tr>{rows}</table>"
        )
        return "".join(parts)
    rows = "".join(
        f"<tr><td>{_e(n)}</td><td>{_vector(xy)}</td></tr>"
        for n, xy in doc.get("points", {}).items()
    )
    parts.append(
        "<table><caption>Points as drawn (m)</caption><tr><th>point</th>"
        f"<th>position</th></tr>{rows}</table>"
    )
    rows = "".join(
        f"<tr><td>{_e(n)}</td><td>{_e(', '.join(map(str, link.get('points', []))))}"
        f"</td><td>{'ground' if link.get('ground') else ''}</td></tr>"
        for n, link in doc.get("links", {}).items()
    )
    parts.append(
        "<table><caption>Links</caption><tr><th>link</th><th>points</th><th></th></tr>"
        f"{rows}</table>"
    )
    rows = "".join(
        f"<tr><td>{_e(j.get('type'))}</td><td>{_e(j.get('point'))}</td>"
        f"<td>{_e(', '.join(map(str, j.get('links', []))))}</td>"
        f"<td>{_vector(j['axis']) if 'axis' in j else ''}</td></tr>"
        for j in doc.get("joints", [])
    )
    parts.append(
        "<table><caption>Joints (slider and prismatic: links = guide, follower)"
        "</caption><tr><th>type</th><th>point</th><th>links</th><th>slot axis</th></tr>"
        f"{rows}</table>"
    )
    rows = "".join(
        f"<tr><td>{_e(d.get('link'))}</td><td>"
        + (
            f"angle law {_e(d['angle_law'])} rad"
            if "angle_law" in d
            else f"omega = {_e(d.get('omega', 0))} rad/s, alpha = {_e(d.get('alpha', 0))} rad/s^2"
            + (f", angle {_e(d['angle_deg'])} deg" if "angle_deg" in d else "")
        )
        + "</td></tr>"
        for d in doc.get("drivers", [])
    )
    parts.append(
        f"<table><caption>Drivers</caption><tr><th>link</th><th>motion</th></tr>{rows}</table>"
    )
    moving = doc.get("moving_points", [])
    if moving:
        rows = "".join(
            f"<tr><td>{_e(m.get('name'))}</td><td>{_e(m.get('link'))}</td>"
            f"<td>{_e(json.dumps(m.get('path')))}</td><td>{_e(m.get('s_law'))}</td>"
            "</tr>"
            for m in moving
        )
        parts.append(
            "<table><caption>Moving points (s in m, t in s)</caption><tr><th>point</th>"
            f"<th>carrier</th><th>path</th><th>s(t)</th></tr>{rows}</table>"
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
<script>{_SCRIPT}</script>
</body>
</html>
"""


def _page(doc: Mapping[str, Any], method: str, digits: int) -> HTMLResponse:
    solution = solve(parse_scene(doc), method, digits)
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
