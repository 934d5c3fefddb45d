"""GET /api/v1/presets and POST /api/v1/presets/{name}: textbook mechanisms as scenes, by family:
the linkages (the default), ``?family=cams`` (docs/CAMS.md) and ``?family=gear_trains``
(docs/GEARS.md). Preset names are unique across the families, so one POST route serves each.

Each preset gets its own POST route with a request model built from its parameters, so the
OpenAPI page documents every parameter with its unit, default and bounds.
"""

from collections.abc import Callable, Mapping
from functools import cache
from typing import Any, Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field, create_model

from server.edge import FiniteJSONResponse, StrictJSONRoute
from server.responses import ResultResponse
from server.scene_schema import SceneObject
from server.schemas import FRONT_PROBLEMS, PresetList
from solver.errors import InvalidScene
from solver.teaching.cam_presets import CAM_PRESETS
from solver.teaching.gear_presets import GEAR_PRESETS
from solver.teaching.presets import PRESETS, Preset, PresetParameter

Family = Literal["linkages", "cams", "gear_trains"]
FAMILIES: dict[str, Mapping[str, Preset]] = {
    "linkages": PRESETS,
    "cams": CAM_PRESETS,
    "gear_trains": GEAR_PRESETS,
}
ALL_PRESETS: dict[str, Preset] = {
    name: preset for family in FAMILIES.values() for name, preset in family.items()
}
assert len(ALL_PRESETS) == sum(len(family) for family in FAMILIES.values()), "a name twice"

router = APIRouter(
    prefix="/presets",
    tags=["presets"],
    route_class=StrictJSONRoute,
    default_response_class=ResultResponse,
    responses=FRONT_PROBLEMS,
)


@router.get("", summary="The textbook mechanisms and their parameters", response_model=PresetList)
def list_presets(family: Family = "linkages") -> FiniteJSONResponse:
    """``family``: the linkages (default), the cams (docs/CAMS.md) or the gear trains
    (docs/GEARS.md); each preset with its parameters and its ``scene`` at their defaults (what
    ``POST /presets/{name}`` with ``{}`` answers)."""
    return FiniteJSONResponse(
        {
            "presets": [
                {
                    "name": p.name,
                    "title": p.title,
                    "description": p.description,
                    "parameters": [
                        {
                            "name": q.name,
                            "default": q.default,
                            "unit": q.unit,
                            "description": q.description,
                            "minimum": q.minimum,
                            "maximum": q.maximum,
                            "choices": None if q.choices is None else list(q.choices),
                            "labels": None if q.labels is None else list(q.labels),
                        }
                        for q in p.parameters
                    ],
                    "scene": default_scene(p.name),
                }
                for p in FAMILIES[family].values()
            ]
        }
    )


@cache
def default_scene(name: str) -> dict[str, Any]:
    """The scene of preset ``name`` at its defaults (the body of ``POST /presets/{name}`` with
    ``{}``), built once per process: the listing carries it, so that the app opens a preset at
    its defaults without another request."""
    return ALL_PRESETS[name].build({})


def _published(q: PresetParameter) -> Callable[[dict[str, Any]], None] | None:
    """What the schema says of a parameter's number beyond its bounds (published, not
    enforced: the preset's own check answers 422 with its reason): whole teeth. Its choices
    are not published: openapi-python-client generates no endpoint for a number enum."""
    if q.unit != "teeth":
        return None
    extra = {"multipleOf": 1}

    def publish(schema: dict[str, Any]) -> None:
        for branch in schema.get("anyOf", []):  # the number, not the null
            if branch.get("type") == "number":
                branch.update(extra)

    return publish


def _parameters_model(preset: Preset) -> type[BaseModel]:
    fields: dict[str, Any] = {
        q.name: (
            float | None,
            Field(
                None,
                description=f"{q.description} [{q.unit or '-'}]; default {q.default:g}",
                ge=q.minimum,
                le=q.maximum,
                json_schema_extra=_published(q),
            ),
        )
        for q in preset.parameters
    }
    config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True)
    return create_model(f"{preset.name}_parameters", __config__=config, **fields)


def _route(preset: Preset) -> None:
    model = _parameters_model(preset)

    def build(parameters: model | None = None) -> FiniteJSONResponse:  # type: ignore[valid-type]
        given: dict[str, float] = (
            {} if parameters is None else parameters.model_dump(exclude_none=True)
        )
        return FiniteJSONResponse(preset.build(given))

    router.add_api_route(
        f"/{preset.name}",
        build,
        methods=["POST"],
        summary=preset.title,
        description=preset.description,
        name=f"preset_{preset.name}",
        response_model=SceneObject,
        response_description="A scene-v1 document",
    )


for _preset in ALL_PRESETS.values():
    _route(_preset)


def no_such_preset(name: str) -> InvalidScene:
    """The refusal of an unknown preset name, listing every family's names."""
    return InvalidScene(
        f"unknown preset '{name[:64]}'; available: "
        + "; ".join(f"{family}: {', '.join(presets)}" for family, presets in FAMILIES.items())
    )


def build_any_preset(name: str, values: Mapping[str, float]) -> dict[str, Any]:
    """The scene document of the preset ``name`` of any family (a linkage, a cam, a gear train)
    with the given parameter values."""
    preset = ALL_PRESETS.get(name)
    if preset is None:
        raise no_such_preset(name)
    return preset.build(values)


@router.post("/{name}", summary="Unknown preset names", include_in_schema=False)
def unknown_preset(name: str) -> FiniteJSONResponse:
    raise no_such_preset(name)
