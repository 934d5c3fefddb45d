"""Exercises (exercises-v1): types, generation, checking with diagnosis, and exports.

Exercises are generated, never stored: ``type:difficulty:seed:index`` determines one completely,
so checking needs nothing but the id. Extensions beyond the spec: ``with_solutions`` on
POST /exercises adds each exercise's worked solution (``solution``: the steps), and
GET /exercises/{id} answers one exercise with its worked solution (the student mode's share link).
``exam: true`` makes an exam set (docs/EXERCISES.md, "Exam sets"): opaque ids under the deployment
secret KINEMATICS_EXAM_SECRET, whose GET is the statement only and whose check is refused.
"""

from __future__ import annotations

import os
from typing import Annotated, Any, Literal

from fastapi import APIRouter, Depends, HTTPException
from fastapi.responses import Response
from pydantic import Field

import solver
from server import budget
from server.mathml import mathml
from server.pdf import html_to_pdf, require_browser
from server.responses import ResultResponse
from server.schemas import (
    PROBLEMS,
    CheckResponse,
    ExamStatementModel,
    ExerciseList,
    ExerciseModel,
    ExerciseTypeList,
    Problem,
    Strict,
)
from server.workers import WorkerRoute, front_check
from solver.errors import InvalidScene
from solver.exercises import (
    DIFFICULTIES,
    MAX_COUNT,
    TYPES,
    Exercise,
    ExerciseId,
    build,
    generate,
    parse_id,
)
from solver.exercises.checking import check
from solver.exercises.exam import UnknownExamId, is_exam_id, open_exam_id
from solver.exercises.export import (
    MAX_TOLERANCE,
    MIN_TOLERANCE,
    answer_csv,
    exercises_json,
    html_sheets,
    moodle_xml,
    set_name,
    student_names,
    with_tolerance,
)
from solver.exercises.generation import build_exam, check_generation
from solver.exercises.model import DEFAULT_DIFFICULTY, DEFAULT_TOLERANCE, MAX_SEED
from solver.exercises.qti import qti_package
from solver.exercises.solutions import worked_solution

MAX_ANSWER = 1e15  # a given answer beyond this is no number a student means
SECRET_VARIABLE = "KINEMATICS_EXAM_SECRET"
MIN_SECRET_LENGTH = 16
MIN_EXAM_SEED = 2**32  # below: a student number, a date, a small count: guessable

router = APIRouter(
    prefix="/exercises",
    tags=["exercises"],
    route_class=WorkerRoute,
    default_response_class=ResultResponse,
    responses=PROBLEMS,
)


class ExercisesRequest(Strict):
    type: str = Field(
        description="An exercise type from GET /exercises/types.",
        max_length=64,
        json_schema_extra={"enum": list(TYPES)},  # published; an unknown one is 422 with the list
    )
    count: int = Field(
        1,
        strict=True,
        description=f"How many exercises (1 to {MAX_COUNT}; outside them 413 limit_exceeded).",
        json_schema_extra={"minimum": 1, "maximum": MAX_COUNT},
    )
    seed: int = Field(0, strict=True, ge=0, le=MAX_SEED, description="Seed (e.g. a student id).")
    difficulty: str = Field(
        DEFAULT_DIFFICULTY, max_length=32, description=f"One of {', '.join(DIFFICULTIES)}."
    )
    with_solutions: bool = Field(
        False, description="Extension: add each exercise's worked solution (its steps)."
    )
    exam: bool = Field(
        False,
        description="Extension: an exam set. Its ids are opaque (an HMAC-SHA-256 token under the "
        f"deployment secret {SECRET_VARIABLE}), GET /exercises/{{id}} serves only their "
        "statements and /exercises/check refuses them. The seed is the set's password: at least "
        f"{MIN_EXAM_SEED} (draw it at random) and kept private, as this answer's keys.",
    )


def configured_secret() -> bytes | None:
    """The deployment secret of exam ids, read in the server's process (a dependency: the
    workers, forked from a server started earlier, get it with the request), or None."""
    secret = os.environ.get(SECRET_VARIABLE, "")
    return secret.encode() if len(secret) >= MIN_SECRET_LENGTH else None


ExamSecret = Annotated[bytes | None, Depends(configured_secret)]


def exam_secret(secret: bytes | None) -> bytes:
    """The deployment secret of exam ids, or a 503 problem saying how to set it."""
    if secret is None:
        raise HTTPException(
            503,
            f"exam sets need the deployment secret {SECRET_VARIABLE} (at least "
            f"{MIN_SECRET_LENGTH} characters), which this server does not have: set it in the "
            "server's environment, e.g. export "
            f"{SECRET_VARIABLE}=$(python3 -c 'import secrets; print(secrets.token_urlsafe(32))'), "
            "and restart it; keep it private and unchanged (a new secret makes every exam id "
            "unknown)",
        )
    return secret


def set_secret(request: ExercisesRequest, secret: bytes | None) -> bytes | None:
    """The exam secret for an exam set (refusing a guessable seed), None for a practice set."""
    if not request.exam:
        return None
    if request.seed < MIN_EXAM_SEED:
        raise InvalidScene(
            f"seed: an exam set's seed is its password (anyone who has it and the type gets the "
            f"key from this server): expected a random integer from {MIN_EXAM_SEED} to "
            f"{MAX_SEED}, got {request.seed}"
        )
    return exam_secret(secret)


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


def exercises_cost(
    request: ExercisesRequest,
    secret: bytes | None,
    path: str = "/api/v1/exercises",
    count: int | None = None,
) -> float:
    """In the server's process: the request's bounds (an exam set: its seed and the secret),
    then count (the request's unless given) x the type's cost."""
    count = request.count if count is None else count
    check_generation(request.type, request.difficulty, count)
    set_secret(request, secret)
    return budget.exercises(request.type, count, request.with_solutions, path)


@router.post(
    "",
    summary="Generate exercises: statement, figure, scene, asked quantities, key",
    response_model=ExerciseList,
)
@front_check(exercises_cost)
def exercises_route(request: ExercisesRequest, secret: ExamSecret) -> ResultResponse:
    exercises = generate(
        request.type, request.difficulty, request.seed, request.count, set_secret(request, secret)
    )
    return ResultResponse(
        {"exercises": [exercise_body(e, request.with_solutions) for e in exercises]}
    )


def open_exam(exercise_id: str, secret: bytes | None) -> ExerciseId:
    """The parameters of an exam id, or a 404 problem (an id this server did not make)."""
    try:
        return open_exam_id(exercise_id, exam_secret(secret))
    except UnknownExamId as unknown:
        raise HTTPException(404, unknown.message) from None


def one_exercise_cost(exercise_id: str, secret: bytes | None) -> float:
    """The id's form (an exam id: that it opens), then one exercise of its type with its worked
    solution."""
    if is_exam_id(exercise_id):
        kind = open_exam(exercise_id, secret).type
    else:
        kind = parse_id(exercise_id).type
    return solver.exercise_work(kind, 1, True).seconds


@router.get(
    "/{exercise_id}",
    summary="One exercise by its id: a practice one with its key and worked solution, an exam "
    "one with its statement only",
    response_model=ExerciseModel | ExamStatementModel,
    responses={
        404: {
            "model": Problem,
            "description": "An exam id that this server did not make, or made under another "
            "secret (not_found); a practice id that is not of the form "
            "type:difficulty:seed:index is 422 invalid_scene",
        }
    },
)
@front_check(one_exercise_cost)
def exercise_route(exercise_id: str, secret: ExamSecret) -> ResultResponse:
    if is_exam_id(exercise_id):
        exam = build_exam(open_exam(exercise_id, secret), exam_secret(secret))
        return ResultResponse(exam.statement_json())
    return ResultResponse(exercise_body(build(parse_id(exercise_id)), True))


Answer = Annotated[float, Field(ge=-MAX_ANSWER, le=MAX_ANSWER)]


class CheckRequest(Strict):
    id: str = Field(description="The exercise id, type:difficulty:seed:index.", max_length=200)
    answers: dict[str, Answer | None] = Field(
        description="The given answers by key (SI units, |x| <= 1e15); a key left out (or null) "
        "is 'missing'."
    )


def check_cost(request: CheckRequest) -> float:
    """The id's form (an exam id is refused: a check within 1 % would let a student bisect the
    key), then one exercise of its type (its key)."""
    if is_exam_id(request.id):
        raise HTTPException(
            403,
            "this is an exam exercise: the server does not check its answers (a check within "
            "1 % would let anyone bisect the key); your instructor grades it",
        )
    return solver.exercise_work(parse_id(request.id).type, 1, False).seconds


@router.post(
    "/check",
    summary="Grade answers within tolerance and diagnose typical mistakes",
    response_model=CheckResponse,
    responses={
        403: {
            "model": Problem,
            "description": "An exam exercise (forbidden): its answers are graded by the "
            "instructor, never checked by the server",
        }
    },
)
@front_check(check_cost)
def check_route(request: CheckRequest) -> ResultResponse:
    return ResultResponse(check(request.id, request.answers))


ExportFormat = Literal["moodle_xml", "html", "pdf", "csv", "json", "qti"]
EXPORT_PATH = "/api/v1/exercises/export"
# Chromium's print of the sheets (server.pdf): its start, then each page; a key with worked
# solutions prints about six pages an exercise. Measured on the 2-core test machine at a load
# average of 17: 5.6 s for a one-page sheet, 7.1 s for 30 pages, 12.5 s for the key of two
# slider-cranks (12 pages); unloaded, the start is well under a second.
PDF_START_SECONDS = 1.5
PDF_PAGE_SECONDS = 0.05
PDF_KEY_PAGES = 6
PDF_TIMEOUT_SHARE = 0.9  # of the export's time limit: the browser is stopped before the worker
_MEDIA = {
    "moodle_xml": ("application/xml", "xml"),
    "html": ("text/html; charset=utf-8", "html"),
    "pdf": ("application/pdf", "pdf"),
    "csv": ("text/csv; charset=utf-8", "csv"),
    "json": ("application/json", "json"),
    "qti": ("application/zip", "zip"),
}


# The JSON export is the POST /exercises body; the others are text.
EXPORT_SCHEMAS = {"application/json": {"$ref": "#/components/schemas/ExerciseList"}}


class ExportRequest(ExercisesRequest):
    format: ExportFormat = Field(
        description="moodle_xml (question bank), html (printable sheet), pdf (the html sheet "
        "printed by the server's Chromium; with_solutions: the key; 503 pdf_unavailable where "
        "the server has no Chromium), csv (answer key), json, qti (an IMS QTI 2.1 content "
        "package, a zip)."
    )
    moodle_question: Literal["auto", "numerical", "cloze"] = Field(
        "auto",
        description="Extension: 'auto' makes a numerical question of an exercise asking one "
        "quantity and a cloze question of one asking several; 'numerical' one numerical "
        "question per asked quantity; 'cloze' one cloze question per exercise.",
    )
    tolerance: float = Field(
        DEFAULT_TOLERANCE,
        ge=MIN_TOLERANCE,
        le=MAX_TOLERANCE,
        description="Relative tolerance of every answer in this export (the Moodle answers, the "
        f"key's tolerance column): 0.01 is 1 %; from {MIN_TOLERANCE} to {MAX_TOLERANCE}.",
    )
    students_csv: str | None = Field(
        None,
        max_length=20_000,
        description="Extension: the class list as CSV text, one student a row, the name in the "
        "first column (a first row reading name or student is a header). One exercise per "
        "student: count is the number of students, and each sheet of the html export carries "
        "its student's name.",
    )

    def students(self) -> list[str] | None:
        """The class list's names, or None without one."""
        return None if self.students_csv is None else student_names(self.students_csv)


def export_cost(request: ExportRequest, secret: bytes | None) -> float:
    """The export's cost: one exercise per student when a class list is given; a PDF adds
    Chromium's print (its start and a page per exercise) and is refused at once (503
    ``pdf_unavailable``) where the server has no Chromium."""
    students = request.students()
    count = request.count if students is None else len(students)
    if request.format != "pdf":
        return exercises_cost(request, secret, EXPORT_PATH, count)
    require_browser()
    pages = count * (PDF_KEY_PAGES if request.with_solutions else 1)
    printing = PDF_START_SECONDS + pages * PDF_PAGE_SECONDS
    return budget.seconds(
        exercises_cost(request, secret, EXPORT_PATH, count) + printing,
        f"{count} exercises and printing them ({printing:g} s in Chromium)",
        EXPORT_PATH,
    )


@router.post(
    "/export",
    summary="The exercises as a file: Moodle XML, printable HTML or PDF, CSV answer key, JSON or "
    "QTI",
    response_class=Response,
    responses={
        200: {
            "description": "The file, as an attachment",
            "content": {
                media: {"schema": EXPORT_SCHEMAS.get(media, {"type": "string"})}
                for media, _ in _MEDIA.values()
            },
        }
    },
)
@front_check(export_cost)
def export_route(request: ExportRequest, secret: ExamSecret) -> Response:
    students = request.students()
    count = request.count if students is None else len(students)
    exercises = generate(
        request.type, request.difficulty, request.seed, count, set_secret(request, secret)
    )
    exercises = with_tolerance(exercises, request.tolerance)
    content: str | bytes
    if request.format == "moodle_xml":
        content = moodle_xml(exercises, request.moodle_question, request.with_solutions)
    elif request.format == "html":
        content = html_sheets(exercises, request.with_solutions, mathml, students)
    elif request.format == "pdf":
        content = html_to_pdf(
            html_sheets(exercises, request.with_solutions, mathml, students),
            PDF_TIMEOUT_SHARE * budget.time_limit(EXPORT_PATH),
        )
    elif request.format == "csv":
        content = answer_csv(exercises)
    elif request.format == "qti":
        content = qti_package(exercises)
    else:
        content = exercises_json(exercises, request.with_solutions)
    media, extension = _MEDIA[request.format]
    key = "-key" if request.with_solutions and request.format in ("html", "pdf") else ""
    name = f"exercises-{set_name(exercises, '-')}{key}.{extension}"
    return Response(
        content,
        media_type=media,
        headers={"Content-Disposition": f'attachment; filename="{name}"'},
    )
