"""POST /api/v1/synthesis: the four-bar for two or three coupler positions, a function or a
quick-return time ratio (docs/SYNTHESIS.md).

The request models publish the three task shapes in OpenAPI and check the JSON types; the
solver (``solver.synthesize``) checks the meaning (how many positions, ranges, a time ratio no
crank-rocker gives) and says why in an ``invalid_scene``. The work is bounded (a fixed number of
analyses and one sweep of 720 samples), so no budget is computed before it; the route runs in a
worker under its time limit, as every solver route does.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from fastapi import APIRouter, Body
from pydantic import Field

import solver
from server import budget
from server.responses import ResultResponse, respond
from server.scene_schema import LinkageSceneObject
from server.schemas import PROBLEMS, WARNINGS, Open, Strict
from server.workers import WorkerRoute, front_check
from solver.analysis.work_estimate import SYNTHESIS_COST

Point = Annotated[list[float], Field(min_length=2, max_length=2, description="[x, y] (m)")]


class PositionSpec(Strict):
    point: Point = Field(description="Where the coupler point P is in this position (m).")
    angle_deg: float = Field(
        description="The coupler's angle (deg); the coupler turns by this minus the first "
        "position's angle."
    )


class MotionTask(Strict):
    """Motion generation: the coupler point P through 2 or 3 positions with the coupler turned."""

    task: Literal["motion"]
    positions: list[PositionSpec] = Field(description="2 or 3 precision positions, in order.")
    moving_pivots: list[Point] | None = Field(
        None,
        description="[B, C]: the coupler's pivots at the first position, in the fixed frame "
        "(the fixed pivots A, D are then the centre points). Give this or fixed_pivots.",
    )
    fixed_pivots: list[Point] | None = Field(
        None,
        description="[A, D]: the fixed pivots (the inverse problem: the moving pivots B, C are "
        "then the circle points).",
    )
    bisector_offsets: list[float] | None = Field(
        None,
        min_length=2,
        max_length=2,
        description="[dA, dD] (m), two positions with moving_pivots only: A on the "
        "perpendicular bisector of B1B2 at the signed distance dA from the chord's midpoint "
        "(positive to the left of B1 -> B2), D on that of C1C2 at dD. Absent: each one chord "
        "length from the midpoint, on the side of B1C1 away from P1.",
    )


class FunctionTask(Strict):
    """Function generation by Freudenstein's equation."""

    task: Literal["function"]
    function: str = Field(
        description="y = f(x) as an expression in x (the time-law language with x for t)."
    )
    x_range: list[float] = Field(description="[x0, xf].")
    input_range_deg: list[float] = Field(
        description="The crank's absolute angles (deg, from the ground line A -> D) for x0, xf."
    )
    output_range_deg: list[float] = Field(
        description="The rocker's absolute angles (deg) for f(x0), f(xf)."
    )
    precision_points: int | list[float] = Field(
        3, description="3 (Chebyshev spacing over x_range) or a list of three x values."
    )
    ground_length: float = Field(1.0, description="|AD| (m); the linkage scales with it.")


class QuickReturnTask(Strict):
    """A quick-return crank-rocker."""

    task: Literal["quick_return"]
    time_ratio: float = Field(description="Slow stroke's time over the fast one's, >= 1.")
    rocker_length: float = Field(description="|DC| (m).")
    swing_deg: float = Field(description="The rocker's swing between its limit positions (deg).")


SynthesisTask = Annotated[MotionTask | FunctionTask | QuickReturnTask, Field(discriminator="task")]


class SynthesisCheck(Open):
    driver_angle_deg: float = Field(description="The crank's absolute angle at this position.")
    error: float = Field(
        description="How far off the analysed scene is there (motion, quick return: m; "
        "function: in units of y)."
    )
    reached: bool


class SynthesisDefects(Open):
    branch: bool = Field(description="A position is met only on the other assembly.")
    order: bool = Field(description="The positions are not met in the given order.")
    grashof: bool = Field(description="The crank cannot turn fully (/sweep's feasible false).")
    grashof_class: str


class SynthesisResponse(Open):
    """POST /synthesis (docs/SYNTHESIS.md)."""

    task: str
    scene: LinkageSceneObject = Field(
        description="The scene-v1 linkage, ready for /analyze, /sweep."
    )
    dimensions: dict[str, Any]
    checks: list[SynthesisCheck]
    defects: SynthesisDefects
    warnings: list[str] = WARNINGS
    steps: list[dict[str, Any]] = Field(
        description="The worked solution: the construction step by step (title, latex, text, "
        "values, checks), the first with an SVG figure."
    )


EXAMPLES: dict[str, Any] = {
    "motion": {
        "summary": "Three coupler positions, the moving pivots given",
        "value": {
            "task": "motion",
            "positions": [
                {"point": [0, 0], "angle_deg": 0},
                {"point": [1, 0.5], "angle_deg": 30},
                {"point": [2, 0.3], "angle_deg": 60},
            ],
            "moving_pivots": [[-0.5, -0.2], [0.5, -0.3]],
        },
    },
    "function": {
        "summary": "y = x^2 over 1..2 by Freudenstein's equation at Chebyshev spacing",
        "value": {
            "task": "function",
            "function": "x^2",
            "x_range": [1, 2],
            "input_range_deg": [30, 120],
            "output_range_deg": [60, 150],
            "precision_points": 3,
        },
    },
    "quick_return": {
        "summary": "A crank-rocker with time ratio 1.25 and a 60 deg swing",
        "value": {
            "task": "quick_return",
            "time_ratio": 1.25,
            "rocker_length": 0.1,
            "swing_deg": 60,
        },
    },
}

router = APIRouter(
    tags=["synthesis"],
    route_class=WorkerRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)


def synthesis_cost(request: SynthesisTask) -> float:
    """A task's cost: the design and its checks (its sizes are fixed: at most three positions
    or precision points), ``SYNTHESIS_COST``."""
    reckoning = f"a synthesis task, {SYNTHESIS_COST:g} s"
    return budget.seconds(SYNTHESIS_COST, reckoning, "/api/v1/synthesis")


@router.post(
    "/synthesis",
    summary="Design a four-bar: two or three coupler positions, a function, or a quick-return "
    "time ratio; checked by the solver's own analysis",
    response_model=SynthesisResponse,
)
@front_check(synthesis_cost)
def synthesis_route(
    request: Annotated[SynthesisTask, Body(openapi_examples=EXAMPLES)],
) -> ResultResponse:
    return respond(solver.synthesize(request.model_dump(exclude_unset=True)))
