"""Exports of a set of exercises: Moodle XML, a printable HTML sheet, a CSV answer key, JSON.

- Moodle XML: a question bank with a category per set. An exercise asking one quantity is a
  ``numerical`` question; one asking several is a ``cloze`` question with a NUMERICAL part per
  quantity (``style="numerical"`` makes one numerical question per quantity instead). The
  statement and its figure (the SVG as a file of the question, ``@@PLUGINFILE@@``) are in every
  question; the tolerance is absolute, as Moodle wants it: the relative tolerance times the answer.
- HTML: one page per exercise (one per student when the seed is the student's number), with the
  statement, the figure and a table to fill in; ``with_solutions`` adds the answer key and the
  worked solution. LaTeX is typeset by KaTeX from the app's /vendor/katex/ when the sheet is
  opened from the app; every formula also has its plain-text form.
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
from collections.abc import Sequence
from html import escape
from typing import Any
from xml.sax.saxutils import escape as xml_escape

from solver.exercises.exam import PREFIX as EXAM_PREFIX
from solver.exercises.model import Exercise
from solver.exercises.solutions import worked_solution

MOODLE_STYLES = ("auto", "numerical", "cloze")


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


def _cdata(html: str) -> str:
    return "<![CDATA[" + html.replace("]]>", "]]]]><![CDATA[>") + "]]>"


def _statement_html(e: Exercise, figure_src: str) -> str:
    return (
        f"<p>{escape(e.statement.text)}</p>"
        f"<p>\\({escape(e.statement.latex)}\\)</p>"
        f'<p><img src="{figure_src}" alt="{escape(figure_alt(e))}" width="420" '
        'height="300"/></p>'
    )


def figure_alt(e: Exercise) -> str:
    """The figure's alt text: what it shows, never the exercise's id (a practice id is the key)."""
    return f"Figure: {e.title}, drawn to scale with its points labelled"


def _figure_file(e: Exercise) -> str:
    data = base64.b64encode(e.statement.figure_svg.encode()).decode()
    return f'<file name="figure.svg" path="/" encoding="base64">{data}</file>'


def _question(kind: str, name: str, text_html: str, e: Exercise, body: str) -> str:
    return (
        f'<question type="{kind}"><name><text>{xml_escape(name)}</text></name>'
        f'<questiontext format="html"><text>{_cdata(text_html)}</text>{_figure_file(e)}'
        "</questiontext>"
        '<generalfeedback format="html"><text></text></generalfeedback>'
        f"<defaultgrade>{len(e.asked) if kind == 'cloze' else 1}</defaultgrade>"
        f"<penalty>0.3333333</penalty><hidden>0</hidden><idnumber>{xml_escape(name)}</idnumber>"
        f"{body}</question>"
    )


def _numerical(e: Exercise, index: int) -> str:
    asked = e.asked[index]
    answer = e.answers[asked.key]
    text = (
        _statement_html(e, "@@PLUGINFILE@@/figure.svg")
        + f"<p>{escape(asked.label[:1].upper() + asked.label[1:])} in {escape(asked.unit)}:</p>"
    )
    body = (
        f'<answer fraction="100" format="moodle_auto_format"><text>{_number(answer)}</text>'
        f"<tolerance>{_number(absolute_tolerance(answer, asked.tolerance))}</tolerance>"
        '<feedback format="html"><text></text></feedback></answer>'
        f"<units><unit><multiplier>1</multiplier><unit_name>{xml_escape(asked.unit)}</unit_name>"
        "</unit></units><unitgradingtype>0</unitgradingtype><unitpenalty>0.1</unitpenalty>"
        "<showunits>3</showunits><unitsleft>0</unitsleft>"
    )
    return _question("numerical", f"{e.name} {asked.key}", text, e, body)


def _cloze(e: Exercise) -> str:
    rows = "".join(
        f"<li>{escape(a.label)} [{escape(a.unit)}]: "
        f"{{1:NUMERICAL:={_number(e.answers[a.key])}:"
        f"{_number(absolute_tolerance(e.answers[a.key], a.tolerance))}}}</li>"
        for a in e.asked
    )
    text = _statement_html(e, "@@PLUGINFILE@@/figure.svg") + f"<ul>{rows}</ul>"
    return _question("cloze", e.name, text, e, "")


def moodle_xml(exercises: Sequence[Exercise], style: str = "auto") -> str:
    """A Moodle XML question bank (see the module docstring)."""
    category = f"$course$/Kinematics exercises/{set_name(exercises, '/')}"
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>\n<quiz>',
        f'<question type="category"><category><text>{xml_escape(category)}</text></category>'
        "</question>",
    ]
    for e in exercises:
        if style == "cloze" or (style == "auto" and len(e.asked) > 1):
            parts.append(_cloze(e))
        else:
            parts += [_numerical(e, k) for k in range(len(e.asked))]
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
.name { margin: 0.6rem 0 1rem; } figure { margin: 0.8rem 0; } .tex { margin: 0.5rem 0; }
table { border-collapse: collapse; margin: 0.8rem 0; width: 100%; }
td, th { border: 1px solid #9ca3af; padding: 0.35rem 0.5rem; text-align: left; }
td.blank { width: 35%; } .step { margin: 0.6rem 0; break-inside: avoid; }
.step h3 { font-size: 0.95rem; margin: 0.2rem 0; } .plain { color: #374151; font-size: 0.85rem; }
@media print { .sheet { padding: 0; } @page { margin: 15mm; } }
"""

_KATEX_CSS = '<link rel="stylesheet" href="/vendor/katex/katex.min.css">'
# At the end of the body: the formulas are there when the (blocking) script has loaded.
_KATEX_JS = """
<script src="/vendor/katex/katex.min.js"></script>
<script src="/js/sheet.js"></script>
"""


def _tex(latex: str) -> str:
    return f'<div class="tex" data-tex="{escape(latex)}">{escape(latex)}</div>'


def _sheet(e: Exercise, with_solutions: bool) -> str:
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
    out = [
        f'<section class="sheet" data-id="{escape(e.name)}">',
        f"<h1>{escape(e.title)}</h1><div class='id'>Exercise {escape(e.name)}</div>",
        "<div class='name'>Name: ____________________________</div>",
        f"<p>{escape(e.statement.text)}</p>",
        _tex(e.statement.latex),
        f"<figure>{e.statement.figure_svg}</figure>",
        f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>",
    ]
    if with_solutions:
        out.append("<h2>Worked solution</h2>")
        for step in worked_solution(e):
            out.append(
                f"<div class='step'><h3>{escape(step['title'])}</h3>{_tex(step['latex'])}"
                f"<div class='plain'>{escape(step['text'])}</div></div>"
            )
    out.append("</section>")
    return "".join(out)


def html_sheets(exercises: Sequence[Exercise], with_solutions: bool) -> str:
    """A printable HTML document, one page per exercise."""
    kind = "answer key" if with_solutions else "exercise sheet"
    title = f"{exercises[0].title}: {kind}"
    return (
        f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><link rel="icon" '
        f'href="/favicon.svg"><title>{escape(title)}'
        f"</title><style>{_STYLE}</style>{_KATEX_CSS}</head><body>"
        + "".join(_sheet(e, with_solutions) for e in exercises)
        + f"{_KATEX_JS}</body></html>\n"
    )
