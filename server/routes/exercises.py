"""Exercises (exercises-v1): types, generation, checking with diagnosis, and exports.

Exercises are generated, never stored: ``type:difficulty:seed:index`` determines one completely,
so checking needs nothing but the id. Extensions beyond the spec: ``with_solutions`` on
POST /exercises adds each exercise's worked solution (``solution``: the steps), and
GET /exercises/{id} answers one exercise with its worked solution (the student mode's share link).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from fastapi import APIRouter
from fastapi.responses import Response
from pydantic import Field

import solver
from server import budget
from server.responses import ResultResponse
from server.schemas import (
    PROBLEMS,
    CheckResponse,
    ExerciseList,
    ExerciseModel,
    ExerciseTypeList,
    Strict,
)
from server.workers import WorkerRoute, front_check
from solver.exercises import DIFFICULTIES, MAX_COUNT, TYPES, Exercise, build, generate, parse_id
from solver.exercises.checking import check
from solver.exercises.export import answer_csv, exercises_json, html_sheets, moodle_xml
from solver.exercises.generation import check_generation
from solver.exercises.model import DEFAULT_DIFFICULTY, MAX_SEED
from solver.exercises.solutions import worked_solution

MAX_ANSWER = 1e15  # a given answer beyond this is no number a student means

router = APIRouter(
    prefix="/exercises",
    tags=["exercises"],
    route_class=WorkerRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)


class ExercisesRequest(Strict):
    type: str = Field(description="An exercise type from GET /exercises/types.", max_length=64)
    count: int = Field(1, strict=True, description=f"How many exercises (1 to {MAX_COUNT}).")
    seed: int = Field(0, strict=True, ge=0, le=MAX_SEED, description="Seed (e.g. a student id).")
    difficulty: str = Field(
        DEFAULT_DIFFICULTY, max_length=32, description=f"One of {', '.join(DIFFICULTIES)}."
    )
    with_solutions: bool = Field(
        False, description="Extension: add each exercise's worked solution (its steps)."
    )


def exercise_body(exercise: Exercise, with_solution: bool) -> dict[str, Any]:
    body = exercise.as_json()
    if with_solution:
        body["solution"] = {"steps": worked_solution(exercise)}
    return body


@router.get(
    "/types",
    summary="Every exercise type, its difficulties and what it can ask",
    response_model=ExerciseTypeList,
)
@front_check(lambda: 0.0)
def types_route() -> ResultResponse:
    return ResultResponse(
        {
            "types": [
                {
                    "name": t.name,
                    "title": t.title,
                    "description": t.description,
                    "difficulties": list(DIFFICULTIES),
                    "asks": list(t.asks),
                }
                for t in TYPES.values()
            ]
        }
    )


def exercises_cost(request: ExercisesRequest, path: str = "/api/v1/exercises") -> float:
    """In the server's process: the request's bounds, then count x the type's cost."""
    check_generation(request.type, request.difficulty, request.count)
    return budget.exercises(request.type, request.count, request.with_solutions, path)


@router.post(
    "",
    summary="Generate exercises: statement, figure, scene, asked quantities, key",
    response_model=ExerciseList,
)
@front_check(exercises_cost)
def exercises_route(request: ExercisesRequest) -> ResultResponse:
    exercises = generate(request.type, request.difficulty, request.seed, request.count)
    return ResultResponse(
        {"exercises": [exercise_body(e, request.with_solutions) for e in exercises]}
    )


def one_exercise_cost(exercise_id: str) -> float:
    """The id's form, then one exercise of its type with its worked solution."""
    return solver.exercise_work(parse_id(exercise_id).type, 1, True).seconds


@router.get(
    "/{exercise_id}",
    summary="One exercise by its id, with its worked solution",
    response_model=ExerciseModel,
)
@front_check(one_exercise_cost)
def exercise_route(exercise_id: str) -> ResultResponse:
    return ResultResponse(exercise_body(build(parse_id(exercise_id)), True))


Answer = Annotated[float, Field(ge=-MAX_ANSWER, le=MAX_ANSWER)]


class CheckRequest(Strict):
    id: str = Field(description="The exercise id, type:difficulty:seed:index.", max_length=200)
    answers: dict[str, Answer | None] = Field(
        description="The given answers by key (SI units, |x| <= 1e15); a key left out (or null) "
        "is 'missing'."
    )


def check_cost(request: CheckRequest) -> float:
    """The id's form, then one exercise of its type (its key)."""
    return solver.exercise_work(parse_id(request.id).type, 1, False).seconds


@router.post(
    "/check",
    summary="Grade answers within tolerance and diagnose typical mistakes",
    response_model=CheckResponse,
)
@front_check(check_cost)
def check_route(request: CheckRequest) -> ResultResponse:
    return ResultResponse(check(request.id, request.answers))


ExportFormat = Literal["moodle_xml", "html", "csv", "json"]
_MEDIA = {
    "moodle_xml": ("application/xml", "xml"),
    "html": ("text/html; charset=utf-8", "html"),
    "csv": ("text/csv; charset=utf-8", "csv"),
    "json": ("application/json", "json"),
}


class ExportRequest(ExercisesRequest):
    format: ExportFormat = Field(
        description="moodle_xml (question bank), html (printable sheet), csv (answer key), json."
    )
    moodle_question: Literal["auto", "numerical", "cloze"] = Field(
        "auto",
        description="Extension: 'auto' makes a numerical question of an exercise asking one "
        "quantity and a cloze question of one asking several; 'numerical' one numerical "
        "question per asked quantity; 'cloze' one cloze question per exercise.",
    )


@router.post(
    "/export",
    summary="The exercises as a file: Moodle XML, printable HTML, CSV answer key or JSON",
    response_class=Response,
    responses={
        200: {
            "description": "The file, as an attachment",
            "content": {media: {"schema": {"type": "string"}} for media, _ in _MEDIA.values()},
        }
    },
)
@front_check(lambda request: exercises_cost(request, "/api/v1/exercises/export"))
def export_route(request: ExportRequest) -> Response:
    exercises = generate(request.type, request.difficulty, request.seed, request.count)
    if request.format == "moodle_xml":
        content = moodle_xml(exercises, request.moodle_question)
    elif request.format == "html":
        content = html_sheets(exercises, request.with_solutions)
    elif request.format == "csv":
        content = answer_csv(exercises)
    else:
        content = exercises_json(exercises, request.with_solutions)
    media, extension = _MEDIA[request.format]
    key = "-key" if request.with_solutions and request.format == "html" else ""
    name = f"exercises-{request.type}-{request.difficulty}-{request.seed}{key}.{extension}"
    return Response(
        content,
        media_type=media,
        headers={"Content-Disposition": f'attachment; filename="{name}"'},
    )
