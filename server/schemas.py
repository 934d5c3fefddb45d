"""Request models at the edge (one per endpoint and direction).

The scene itself is validated by the solver's own parsers (``solver.scene``, ``solver.spatial``),
which know the contract in full and say where a document is wrong; here it is an object with the
spec's examples attached for the OpenAPI page.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

EXAMPLES = Path(__file__).parent / "examples"


def _example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


Quantity = Literal["position", "velocity", "acceleration", "poles", "components"]


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)


class AnalyzeRequest(Strict):
    scene: dict[str, Any] = Field(
        description="A scene-v1 document: kind 'linkage' or 'spatial_chain'.",
        examples=[_example("S000-T1"), _example("S002-spatial-arm")],
    )
    quantities: list[Quantity] | None = Field(
        None, description="What to compute (default: all). The server computes only these."
    )
    tolerance: float | None = Field(
        None,
        description="Newton-Raphson tolerance for linkages the closed-form dyads cannot solve "
        "(triads, some six-bars): the loop-closure residual relative to the scene size, between "
        "1e-15 and 1e-6 (default 1e-13). Looser is faster and less accurate; see "
        "docs/BENCHMARKS.md. Reported in diagnostics.",
    )


class SweepRequest(Strict):
    scene: dict[str, Any] = Field(
        description="A scene-v1 'linkage' document.", examples=[_example("S000-T1")]
    )
    samples: int = Field(360, description="Samples over the revolution (or feasible range).")
    quantities: list[Quantity] | None = Field(
        None,
        description="Default: position only. 'poles': each link's velocity and acceleration "
        "pole per sample (null where none); 'components': the slider joints' (and moving "
        "points') transport, relative and Coriolis parts per sample.",
    )
    time_range: list[float] | None = Field(
        None,
        description="[t0, t1] (s): sweep in time through the scene's time laws instead "
        "of a driver revolution.",
    )
    tolerance: float | None = Field(
        None,
        description="Newton-Raphson tolerance for linkages the closed-form dyads cannot solve "
        "(triads, some six-bars): the loop-closure residual relative to the scene size, between "
        "1e-15 and 1e-6 (default 1e-13). Looser is faster and less accurate; see "
        "docs/BENCHMARKS.md. Reported in diagnostics.",
    )


class EventSpec(Strict):
    moving_point: str = Field(description="The name of a moving point of the scene.")
    reaches: str = Field(description="The name of the point it should coincide with.")
    occurrence: int = Field(1, description="Which meeting after t = 0 (1 = the first).")
    t_max: float = Field(60.0, description="Search 0 < t <= t_max (s).")


class EventsRequest(Strict):
    scene: dict[str, Any] = Field(
        description="A scene-v1 'linkage' with moving_points.",
        examples=[_example("S003-T2-rotating-carrier")],
    )
    event: EventSpec
