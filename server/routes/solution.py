"""POST /api/v1/solution (worked solution as data) and /api/v1/solution.html (printable page).

The solution comes from ``solver.solve``; ``results`` is exactly the /analyze body of the same
scene. The HTML page (``server.solution_page``) is standalone and print-friendly.
"""

from __future__ import annotations

import json
import math
from typing import Annotated, Any

from fastapi import APIRouter, Depends, Query, Request
from fastapi.responses import HTMLResponse
from pydantic import Field

import solver
from server import budget
from server.responses import ResultResponse, respond
from server.routes.presets import ALL_PRESETS, build_any_preset
from server.scene_schema import SceneObject
from server.schemas import EXAMPLES, PROBLEMS, STRICT, SolutionResponse, Strict
from server.solution_page import solution_page
from server.workers import WorkerRoute, front_check
from solver.analysis.work_estimate import SOLUTION_COST
from solver.errors import InvalidScene

router = APIRouter(
    tags=["solutions"],
    route_class=WorkerRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)

Method = solver.Method  # declared once, in solver.solutions.solve


def _example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


class SolutionRequest(Strict):
    scene: SceneObject = Field(
        description="A scene-v1 document: kind 'linkage', 'spatial_chain', 'cam' (at 'angle_deg'; "
        "docs/CAMS.md) or 'gear_train' (written out by the tabular and formula methods whatever "
        "'method' asks; docs/GEARS.md).",
        examples=[_example("S000-T2"), _example("S002-spatial-arm")],
    )
    method: Method = Field(
        "vector",
        description="'vector' (relative velocities, seed 000 form) or 'loop' (loop "
        "closure in complex form with Cramer's rule, seed 001 form; for linkages that are not "
        "chains of four-bar, slider-crank or slotted-lever loops the solution falls back to "
        "'vector' and says so); 'newton_euler' (the dynamics of the instant) or 'statics' (the "
        "static force analysis; docs/DYNAMICS.md).",
    )
    digits: int = Field(
        4,
        ge=1,
        le=15,
        strict=True,
        description="Significant digits of the numbers shown (1 to 15).",
    )
    angle_deg: float | None = Field(
        None,
        allow_inf_nan=False,
        description="A cam's cam angle in degrees (default 0; docs/CAMS.md); not for a linkage.",
    )
    strict: bool = STRICT


def solution_cost(request: SolutionRequest, path: str = "/api/v1/solution") -> float:
    """In the server's process: the scene's instant and the solution's writing."""
    return budget.read_instant(request.scene, request.strict, path, SOLUTION_COST)


@router.post(
    "/solution",
    summary="Worked solution, step by step, in the textbook's form",
    response_model=SolutionResponse,
)
@front_check(solution_cost)
def solution_route(request: SolutionRequest) -> ResultResponse:
    read = solver.read_scene(request.scene, strict=request.strict)
    return respond(solver.solve(read, request.method, request.digits, angle_deg=request.angle_deg))


def _page(
    doc: dict[str, Any],
    method: str,
    digits: int,
    strict: bool = False,
    angle_deg: float | None = None,
) -> HTMLResponse:
    read = solver.read_scene(doc, strict=strict)
    solution = solver.solve(read, method, digits, angle_deg=angle_deg)
    return HTMLResponse(solution_page(doc, solution))


def preset_values(request: Request) -> dict[str, float]:
    """Every query parameter but preset, method, digits and angle_deg, as a parameter of the preset
    (``crank=0.2``): a number, or ``invalid_scene`` (not a number, given twice, not finite);
    the preset refuses unknown names. Read on the server's side, so only numbers go to a
    worker."""
    values: dict[str, float] = {}
    for key, raw in request.query_params.multi_items():
        if key in ("preset", "method", "digits", "angle_deg"):
            continue
        try:
            number = float(raw)
        except ValueError:
            raise InvalidScene(f"{key}: expected a number, got {raw!r}") from None
        if key in values or not math.isfinite(number):
            raise InvalidScene(f"{key}: given twice or not finite ({raw!r})")
        values[key] = number
    return values


@router.get(
    "/solution.html",
    summary="Printable worked solution of a textbook preset",
    response_class=HTMLResponse,
)
@front_check(
    lambda preset, values, **_: budget.read_instant(
        build_any_preset(preset, values), False, "/api/v1/solution.html", SOLUTION_COST
    )
)
def solution_page_preset(
    preset: Annotated[
        str,
        Query(
            max_length=64,
            description="A preset name of any family (GET /presets).",
            json_schema_extra={"enum": list(ALL_PRESETS)},
        ),
    ],
    values: Annotated[dict[str, float], Depends(preset_values)],
    method: Annotated[Method, Query()] = "vector",
    digits: Annotated[int, Query(ge=1, le=15)] = 4,
    angle_deg: Annotated[
        float | None,
        Query(allow_inf_nan=False, description="A cam's cam angle in degrees (default 0)."),
    ] = None,
) -> HTMLResponse:
    """A linkage, cam or gear-train preset; every other query parameter is a parameter of the
    preset (``crank=0.2``), never silently ignored."""
    return _page(build_any_preset(preset, values), method, digits, angle_deg=angle_deg)


@router.post(
    "/solution.html", summary="Printable worked solution of a scene", response_class=HTMLResponse
)
@front_check(lambda request: solution_cost(request, "/api/v1/solution.html"))
def solution_page_scene(request: SolutionRequest) -> HTMLResponse:
    return _page(request.scene, request.method, request.digits, request.strict, request.angle_deg)
