"""Exports of a set of exercises: Moodle XML, a printable HTML sheet, a CSV answer key, JSON.

- Moodle XML: a question bank with a category per set (its info says how to give each student
  one of its questions through a random question). An exercise asking one quantity is a
  ``numerical`` question; one asking several is a ``cloze`` question with a NUMERICAL part per
  quantity (``style="numerical"`` makes one numerical question per quantity instead). The
  statement, its data one formula a line (``\\( \\)`` without ``\\\\``: MathJax 3 reads them)
  and its figure (the SVG as a file of the question, ``@@PLUGINFILE@@``, at most the screen's
  width) are in every question. Each answer is written in the digits that fix it within the
  tolerance, the tolerance absolute, as Moodle wants it (the relative tolerance times the
  answer); after the right answer, one 0 % answer per typical mistake at the value the mistake
  gives, its feedback naming the mistake; the general feedback gives the answers and, with
  ``with_solutions``, the worked solution.
- HTML: one page per exercise (per student with ``students``), with the statement, the figure
  and a table to fill in; ``with_solutions`` adds the answer key and the worked solution.
  Self-contained: no script and no external file, every formula typeset by the function given
  (the server's MathML, ``server.mathml``), so a sheet saved to disk opens and prints anywhere.
- CSV: the answer key, one row per exercise and asked quantity, numbers in full precision.

An exam set (``solver.exercises.exam``) is named by its exam ids everywhere, and by
``set_name`` (no seed) in file names and the Moodle category; the figure's alt text describes the
figure and names no id.
"""

from __future__ import annotations

import base64
import csv
import io
import json
import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from html import escape
from typing import Any
from xml.sax.saxutils import escape as xml_escape

from solver.errors import InvalidScene
from solver.exercises.checking import mistakes_of
from solver.exercises.exam import PREFIX as EXAM_PREFIX
from solver.exercises.generation import MAX_COUNT
from solver.exercises.model import Asked, Exercise, within
from solver.exercises.solutions import worked_solution
from solver.teaching.mistakes import typical_mistake

MOODLE_STYLES = ("auto", "numerical", "cloze")
MAX_TOLERANCE = 0.2  # relative: an export may grade within 0.01 % to 20 %
MIN_TOLERANCE = 1e-4
CATEGORY_NOTE = (
    "<p>One exercise per student: add to the quiz one <em>random question</em> from this "
    "category (Add, a random question, this category, 1 question) and Moodle gives each "
    "student one of its questions, drawn at the attempt's start; every question of the "
    "category is a different exercise of the same type and difficulty, graded alike.</p>"
)


def absolute_tolerance(answer: float, relative: float) -> float:
    return abs(answer) * relative


def set_name(exercises: Sequence[Exercise], sep: str) -> str:
    """A set's name in a file name or a Moodle category: ``type-difficulty-seed`` for practice;
    for an exam set, whose seed is a secret of the instructor's, ``type-difficulty-exam-<tag>``
    with a piece of the first exam id (which tells nothing of the key)."""
    first = exercises[0]
    parts = [first.id.type, first.id.difficulty]
    if first.exam_id is None:
        parts.append(str(first.id.seed) if sep == "-" else f"seed {first.id.seed}")
    else:
        parts.append(f"exam-{first.exam_id.removeprefix(EXAM_PREFIX)[:10]}")
    return sep.join(parts)


def _number(x: float) -> str:
    return repr(float(x))


def significant_digits(tolerance: float) -> int:
    """The significant digits that fix a number within ``tolerance`` (relative) with a tenth of it
    to spare: rounding to n digits errs by at most 5 10^-n relative, so
    n = ceil(log10(50 / tolerance)); 4 for 1 %."""
    return max(3, math.ceil(math.log10(50.0 / tolerance) - 1e-9))


def answer_text(value: float, tolerance: float) -> str:
    """An answer as written in the key: ``significant_digits(tolerance)`` digits, never "-0"."""
    text = f"{value:.{significant_digits(tolerance)}g}"
    return "0" if float(text) == 0.0 else text


def _tolerance_text(value: float, tolerance: float) -> str:
    """The absolute tolerance of ``value`` (relative ``tolerance``), to three digits."""
    return f"{absolute_tolerance(value, tolerance):.3g}"


def _cdata(html: str) -> str:
    return "<![CDATA[" + html.replace("]]>", "]]]]><![CDATA[>") + "]]>"


def _split_top(latex: str, separators: tuple[str, ...]) -> list[str]:
    """``latex`` cut at each top-level separator (never inside braces or an environment), the
    pieces trimmed of spaces and commas, empty ones dropped."""
    pieces: list[str] = []
    depth, start, k = 0, 0, 0
    while k < len(latex):
        if latex.startswith(r"\begin", k):
            depth += 1
        elif latex.startswith(r"\end", k):
            depth -= 1
        sep = next((x for x in separators if latex.startswith(x, k)), None) if depth == 0 else None
        if sep is not None:
            pieces.append(latex[start:k])
            k = start = k + len(sep)
            continue
        char = latex[k]
        depth += {"{": 1, "}": -1}.get(char, 0)
        k += 2 if char == "\\" else 1  # an escaped character: \{, \}, \, ...
    pieces.append(latex[start:])
    trimmed = (p.strip().strip(",").strip() for p in pieces)
    return [p for p in trimmed if p]


def latex_lines(latex: str) -> list[str]:
    r"""The LaTeX's lines, cut at each top-level ``\\``: each is typeset on its own (MathJax 3
    ignores ``\\`` in inline math, KaTeX and MathML want one line each)."""
    return _split_top(latex, ("\\\\",))


def latex_items(latex: str) -> list[str]:
    r"""A statement's givens one by one: its lines cut at each top-level ``,\;`` too, without
    the "Find ..." line (the answer fields say what is asked); one datum a piece fits a phone."""
    return [
        item
        for line in latex_lines(latex)
        if not line.startswith(r"\text{Find")
        for item in _split_top(line, (r",\;",))
    ]


def _givens_html(latex: str) -> str:
    r"""The statement's data, one formula a list item, in ``\( \)`` (Moodle's MathJax and its
    TeX filter both read them)."""
    return (
        "<ul>" + "".join(f"<li>\\({escape(item)}\\)</li>" for item in latex_items(latex)) + "</ul>"
    )


def _statement_html(e: Exercise, figure_src: str) -> str:
    return (
        f"<p>{escape(e.statement.text)}</p>"
        + _givens_html(e.statement.latex)
        + f'<p><img src="{figure_src}" alt="{escape(figure_alt(e))}" width="420" height="300" '
        'style="max-width: 100%; height: auto;"/></p>'
    )


def figure_alt(e: Exercise) -> str:
    """The figure's alt text: what it shows, never the exercise's id (a practice id is the key)."""
    return f"Figure: {e.title}, drawn to scale with its points labelled"


def _figure_file(e: Exercise) -> str:
    data = base64.b64encode(e.statement.figure_svg.encode()).decode()
    return f'<file name="figure.svg" path="/" encoding="base64">{data}</file>'


@dataclass(frozen=True)
class Distractor:
    """A wrong answer a typical mistake gives: its value and the feedback that names the
    mistake."""

    value: float
    feedback: str


def distractors(e: Exercise) -> dict[str, list[Distractor]]:
    """Per asked key, the wrong answers of the exercise's typical mistakes
    (``checking.mistakes_of``) that lie outside the tolerance of the key and of each other: the
    answers a Moodle question grades 0 % with feedback naming the mistake."""
    made = mistakes_of(e)
    found: dict[str, list[Distractor]] = {}
    for a in e.asked:
        tol = a.tolerance
        right = e.answers[a.key]
        kept: list[Distractor] = []
        for mistake in made:
            wrong = mistake.values.get(a.key)
            if wrong is None or not math.isfinite(wrong) or within(wrong, right, 2 * tol):
                continue
            if any(within(wrong, d.value, 2 * tol) for d in kept):
                continue
            title = typical_mistake(mistake.kind).title
            kept.append(Distractor(wrong, f"Not right: {title.rstrip('.')}. {mistake.sentence}"))
        found[a.key] = kept
    return found


def _feedback_html(e: Exercise, with_solutions: bool) -> str:
    """The general feedback: the answers as the key writes them, and (``with_solutions``) the
    worked solution, each step's formulas one display line each."""
    rows = "".join(
        f"<li>\\({a.symbol} = {answer_text(e.answers[a.key], a.tolerance)}\\,"
        f"\\mathrm{{{escape(a.unit)}}}\\)</li>"
        for a in e.asked
    )
    out = [f"<p>The answers:</p><ul>{rows}</ul>"]
    if with_solutions:
        out.append("<h4>Worked solution</h4>")
        for step in worked_solution(e):
            lines = "".join(f"<p>\\[{escape(line)}\\]</p>" for line in latex_lines(step["latex"]))
            out.append(f"<h5>{escape(step['title'])}</h5>{lines}<p>{escape(step['text'])}</p>")
    return "".join(out)


def _question(kind: str, name: str, text_html: str, e: Exercise, body: str, feedback: str) -> str:
    return (
        f'<question type="{kind}"><name><text>{xml_escape(name)}</text></name>'
        f'<questiontext format="html"><text>{_cdata(text_html)}</text>{_figure_file(e)}'
        "</questiontext>"
        f'<generalfeedback format="html"><text>{_cdata(feedback)}</text></generalfeedback>'
        f"<defaultgrade>{len(e.asked) if kind == 'cloze' else 1}</defaultgrade>"
        f"<penalty>0.3333333</penalty><hidden>0</hidden><idnumber>{xml_escape(name)}</idnumber>"
        f"{body}</question>"
    )


def _moodle_answer(fraction: int, value: str, tolerance: str, feedback: str) -> str:
    return (
        f'<answer fraction="{fraction}" format="moodle_auto_format"><text>{value}</text>'
        f"<tolerance>{tolerance}</tolerance>"
        f'<feedback format="html"><text>{_cdata(escape(feedback))}</text></feedback></answer>'
    )


def _numerical(e: Exercise, index: int, with_solutions: bool) -> str:
    asked = e.asked[index]
    tolerance = asked.tolerance
    answer = e.answers[asked.key]
    label = asked.label[:1].upper() + asked.label[1:]
    text = _statement_html(e, "@@PLUGINFILE@@/figure.svg") + (
        f"<p>This question asks only for the {escape(asked.label)} "
        f"\\({escape(asked.symbol)}\\), in {escape(asked.unit)}.</p>"
        if len(e.asked) > 1
        else f"<p>{escape(label)} \\({escape(asked.symbol)}\\) in {escape(asked.unit)}:</p>"
    )
    answers = [
        _moodle_answer(100, answer_text(answer, tolerance), _tolerance_text(answer, tolerance),
                       "Right.")
    ]  # fmt: skip
    answers += [
        _moodle_answer(0, answer_text(d.value, tolerance), _tolerance_text(d.value, tolerance),
                       d.feedback)
        for d in distractors(e)[asked.key]
    ]  # fmt: skip
    body = (
        "".join(answers)
        + f"<units><unit><multiplier>1</multiplier><unit_name>{xml_escape(asked.unit)}</unit_name>"
        "</unit></units><unitgradingtype>0</unitgradingtype><unitpenalty>0.1</unitpenalty>"
        "<showunits>3</showunits><unitsleft>0</unitsleft>"
    )
    return _question(
        "numerical", f"{e.name} {asked.key}", text, e, body, _feedback_html(e, with_solutions)
    )


def cloze_escape(text: str) -> str:
    r"""Text inside a cloze sub-question (its feedback): Moodle's special characters ``\ } # ~ /
    "`` escaped with a backslash, as the Embedded Answers (Cloze) documentation asks."""
    return re.sub(r'([\\}#~/"])', r"\\\1", text)


def _cloze_part(e: Exercise, asked: Asked) -> str:
    tolerance = asked.tolerance
    answer = e.answers[asked.key]
    parts = [
        f"={answer_text(answer, tolerance)}:{_tolerance_text(answer, tolerance)}#"
        + cloze_escape("Right.")
    ]
    parts += [
        f"%0%{answer_text(d.value, tolerance)}:{_tolerance_text(d.value, tolerance)}#"
        + cloze_escape(escape(d.feedback, quote=False))
        for d in distractors(e)[asked.key]
    ]
    return "{1:NUMERICAL:" + "~".join(parts) + "}"


def _cloze(e: Exercise, with_solutions: bool) -> str:
    rows = "".join(
        f"<li>{escape(a.label)} \\({escape(a.symbol)}\\) [{escape(a.unit)}]: "
        f"{_cloze_part(e, a)}</li>"
        for a in e.asked
    )
    text = _statement_html(e, "@@PLUGINFILE@@/figure.svg") + f"<ul>{rows}</ul>"
    return _question("cloze", e.name, text, e, "", _feedback_html(e, with_solutions))


def student_names(text: str) -> list[str]:
    """The names of a class list in CSV: the first cell of each row that has one, a first row
    reading "name" or "student" (any case) taken as a header; ``InvalidScene`` for an empty
    list or more than ``MAX_COUNT`` names."""
    try:
        rows = [r[0].strip() for r in csv.reader(io.StringIO(text)) if r and r[0].strip()]
    except csv.Error as error:
        raise InvalidScene(f"students_csv: not CSV text ({error})") from None
    if rows and rows[0].lower() in ("name", "names", "student", "students"):
        rows = rows[1:]
    if not 1 <= len(rows) <= MAX_COUNT:
        raise InvalidScene(
            f"students_csv: expected 1 to {MAX_COUNT} names (one a row), got {len(rows)}"
        )
    return [name[:100] for name in rows]


def with_tolerance(exercises: Sequence[Exercise], tolerance: float) -> list[Exercise]:
    """The exercises with every asked quantity graded within ``tolerance`` (relative): an
    export's choice, for the key, the Moodle answers and the diagnosis alike."""
    return [
        replace(e, asked=tuple(replace(a, tolerance=tolerance) for a in e.asked)) for e in exercises
    ]


def moodle_xml(
    exercises: Sequence[Exercise], style: str = "auto", with_solutions: bool = False
) -> str:
    """A Moodle XML question bank (see the module docstring): the set's category, then a
    question per exercise (or per asked quantity), each graded within its tolerance."""
    category = f"$course$/Kinematics exercises/{set_name(exercises, '/')}"
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>\n<quiz>',
        f'<question type="category"><category><text>{xml_escape(category)}</text></category>'
        f'<info format="html"><text>{_cdata(CATEGORY_NOTE)}</text></info></question>',
    ]
    for e in exercises:
        if style == "cloze" or (style == "auto" and len(e.asked) > 1):
            parts.append(_cloze(e, with_solutions))
        else:
            parts += [_numerical(e, k, with_solutions) for k in range(len(e.asked))]
    parts.append("</quiz>\n")
    return "\n".join(parts)


def answer_csv(exercises: Sequence[Exercise]) -> str:
    """The answer key, one row per exercise and asked quantity."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(
        ["id", "type", "difficulty", "seed", "index", "key", "label", "unit", "path", "answer",
         "tolerance", "absolute_tolerance"]
    )  # fmt: skip
    for e in exercises:
        for a in e.asked:
            answer = e.answers[a.key]
            writer.writerow(
                [e.name, e.id.type, e.id.difficulty, e.id.seed, e.id.index, a.key, a.label,
                 a.unit, a.path, _number(answer), a.tolerance,
                 _number(absolute_tolerance(answer, a.tolerance))]
            )  # fmt: skip
    return out.getvalue()


def exercises_json(exercises: Sequence[Exercise], with_solutions: bool) -> str:
    """The POST /exercises response body."""
    bodies: list[dict[str, Any]] = []
    for e in exercises:
        body = e.as_json()
        if with_solutions:
            body["solution"] = {"steps": worked_solution(e)}
        bodies.append(body)
    return json.dumps({"exercises": bodies}, ensure_ascii=False)


_STYLE = """
body { font-family: system-ui, sans-serif; margin: 0; color: #111827; }
.sheet { padding: 18mm 16mm; page-break-after: always; break-after: page; }
.sheet:last-child { page-break-after: auto; break-after: auto; }
h1 { font-size: 1.25rem; margin: 0 0 0.3rem; } .id { color: #6b7280; font-size: 0.85rem; }
.name { margin: 0.6rem 0 1rem; } figure { margin: 0.8rem 0; break-inside: avoid; }
figure svg { max-width: 100%; height: auto; }
.tex { margin: 0.35rem 0; overflow-x: auto; } .tex math { font-size: 1.1em; }
code.tex { display: block; font-size: 0.9rem; white-space: pre-wrap; }
table { border-collapse: collapse; margin: 0.8rem 0; width: 100%; break-inside: avoid; }
td, th { border: 1px solid #9ca3af; padding: 0.35rem 0.5rem; text-align: left; }
td.blank { width: 35%; } .step { margin: 0.6rem 0; break-inside: avoid; }
.step h3 { font-size: 0.95rem; margin: 0.2rem 0; } .plain { color: #374151; font-size: 0.85rem; }
@media print { .sheet { padding: 0; } @page { size: A4; margin: 15mm; } .tex { overflow: visible; }
  body { font-size: 10.5pt; } figure svg { width: 100mm; } }
"""


def latex_source(latex: str) -> str:
    """A formula as its LaTeX source (the library's own typesetting, with no dependency): the
    server typesets with MathML instead (``server.mathml``)."""
    return f"<code class='tex'>{escape(latex)}</code>"


def _tex(latex: str, typeset: Callable[[str], str]) -> str:
    r"""A formula one line at a time (``latex_lines``), at most three ``,\;``-separated items a
    line (an A4 page's width), each line typeset by ``typeset``."""
    lines = [
        r",\; ".join(items[k : k + 3])
        for line in latex_lines(latex)
        for items in [_split_top(line, (r",\;",))]
        for k in range(0, len(items), 3)
    ]
    return "".join(f"<div class='tex'>{typeset(line)}</div>" for line in lines)


def _sheet(
    e: Exercise, with_solutions: bool, typeset: Callable[[str], str], student: str | None
) -> str:
    rows = "".join(
        f"<tr><td>{escape(a.label)}</td><td>{escape(a.unit)}</td>"
        + (
            f'<td class="answer" data-key="{escape(a.key)}">{e.answers[a.key]:.6g}</td>'
            f"<td>± {a.tolerance * 100:g} %</td>"
            if with_solutions
            else '<td class="blank"></td>'
        )
        + "</tr>"
        for a in e.asked
    )
    head = "<th>quantity</th><th>unit</th>" + (
        "<th>answer</th><th>tolerance</th>" if with_solutions else "<th>your answer</th>"
    )
    name = "____________________________" if student is None else escape(student)
    out = [
        f'<section class="sheet" data-id="{escape(e.name)}">',
        f"<h1>{escape(e.title)}</h1><div class='id'>Exercise {escape(e.name)}</div>",
        f"<div class='name'>Name: {name}</div>",
        f"<p>{escape(e.statement.text)}</p>",
        _tex(e.statement.latex, typeset),
        f"<figure>{e.statement.figure_svg}</figure>",
        f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>",
    ]
    if with_solutions:
        out.append("<h2>Worked solution</h2>")
        for step in worked_solution(e):
            out.append(
                f"<div class='step'><h3>{escape(step['title'])}</h3>"
                f"{_tex(step['latex'], typeset)}"
                f"<div class='plain'>{escape(step['text'])}</div></div>"
            )
    out.append("</section>")
    return "".join(out)


def html_sheets(
    exercises: Sequence[Exercise],
    with_solutions: bool,
    typeset: Callable[[str], str] = latex_source,
    students: Sequence[str] | None = None,
) -> str:
    """A printable HTML document, one page per exercise: self-contained (no script, no external
    file), every formula typeset by ``typeset`` (LaTeX to HTML: the server's MathML); with
    ``students``, the i-th page carries the i-th student's name."""
    kind = "answer key" if with_solutions else "exercise sheet"
    title = f"{exercises[0].title}: {kind}"
    names: Sequence[str | None] = [None] * len(exercises) if students is None else students
    return (
        f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{escape(title)}'
        f"</title><style>{_STYLE}</style></head><body>"
        + "".join(
            _sheet(e, with_solutions, typeset, student)
            for e, student in zip(exercises, names, strict=True)
        )
        + "</body></html>\n"
    )
