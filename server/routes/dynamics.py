"""POST /api/v1/balance (dynamics-v1): full force balancing of a four-bar.

The ``forces`` and ``energy`` quantities of /analyze and /sweep are the solver's
(``solver.dynamics.body``), like every other quantity.
"""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter
from pydantic import Field

import solver
from server.responses import ResultResponse
from server.scene_schema import LinkageSceneObject
from server.schemas import PROBLEMS, BalanceResponse, Strict
from server.workers import WorkerRoute, front_check
from solver.analysis.work_estimate import BALANCE_COST
from solver.dynamics.balance import balance_four_bar
from solver.dynamics.body import balance_body
from solver.errors import InvalidScene
from solver.model.scene import LinkageScene


class CounterweightSpec(Strict):
    link: str = Field(description="A link that turns about the ground (the crank or the rocker).")
    mass: float = Field(gt=0, le=1e9, description="The counterweight's mass (kg).")


class BalanceRequest(Strict):
    scene: LinkageSceneObject = Field(description="A four-bar 'linkage' with masses (dynamics-v1).")
    counterweights: list[CounterweightSpec] = Field(
        max_length=2, description="One counterweight on each link that turns about the ground."
    )


router = APIRouter(
    tags=["dynamics"],
    route_class=WorkerRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)


def balance_cost(request: BalanceRequest) -> float:
    """In the server's process: the scene parsed, a balancing's cost."""
    _linkage(request.scene)
    return BALANCE_COST


def _linkage(doc: dict[str, Any]) -> LinkageScene:
    scene = solver.parse_scene(doc)
    if not isinstance(scene, LinkageScene):
        raise InvalidScene("kind: /balance takes a 'linkage' scene")
    return scene


@router.post(
    "/balance",
    summary="Full force balancing of a four-bar: counterweights that keep the centre of mass still",
    response_model=BalanceResponse,
)
@front_check(balance_cost)
def balance_route(request: BalanceRequest) -> ResultResponse:
    scene = _linkage(request.scene)
    result = balance_four_bar(
        scene, request.scene, [(c.link, c.mass) for c in request.counterweights]
    )
    return ResultResponse(balance_body(result))
