"""Moodle's import rules for the XML the exports write, as Moodle documents them, checked without a
Moodle: the Moodle XML format (docs.moodle.org/en/Moodle_XML_format, read by
question/format/xml/format.php), the Embedded Answers (Cloze) syntax
(docs.moodle.org/en/Embedded_Answers_(Cloze)_question_type) and MathJax 3's delimiters (Moodle's
MathJax filter: ``\\( \\)`` and ``\\[ \\]``, where a ``\\\\`` outside an environment is ignored).

``problems(xml)`` lists every rule a file breaks (empty: it imports as intended).
``python -m tests.moodle_rules record DIR`` writes the reference file of every exercise type
(tests/reference/moodle: one standard exercise of seed 1, with its worked solution).
"""

from __future__ import annotations

import base64
import re
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

QUESTION_TYPES = {"category", "numerical", "cloze"}  # the ones the exports write
CLOZE_PART = re.compile(r"\{(\d*):(?:NUMERICAL|NM):((?:\\.|[^\\}])*)\}")
ALTERNATIVE = re.compile(r"(=|%(-?[0-9.]+)%)?((?:\\.|[^\\:#])*):((?:\\.|[^\\#])*)(?:#(.*))?", re.S)
INLINE = re.compile(r"\\\((.*?)\\\)", re.S)
DISPLAY = re.compile(r"\\\[(.*?)\\\]", re.S)
MAX_INLINE = 80  # characters of LaTeX in one \( \): about a phone's width (390 px) typeset


@dataclass(frozen=True)
class Alternative:
    """One answer of a cloze NUMERICAL part: its fraction (%), value, tolerance and feedback (its
    escapes undone, as Moodle shows it)."""

    fraction: float
    value: float
    tolerance: float
    feedback: str


def cloze_parts(text: str) -> list[list[Alternative]]:
    """The NUMERICAL parts of a cloze question text, each as its answers; a ValueError for one
    the syntax does not allow."""
    parts = []
    for _, body in CLOZE_PART.findall(text):
        alternatives = []
        for alt in re.split(r"(?<!\\)~", body):
            m = ALTERNATIVE.fullmatch(alt)
            if m is None:
                raise ValueError(f"not a NUMERICAL answer: {alt[:80]!r}")
            mark, fraction, value, tolerance, feedback = m.groups()
            percent = 100.0 if mark == "=" else float(fraction) if fraction else 0.0
            shown = re.sub(r"\\(.)", r"\1", feedback or "")  # as Moodle shows it, unescaped
            alternatives.append(Alternative(percent, float(value), float(tolerance), shown))
        parts.append(alternatives)
    return parts


def _top_level_breaks(latex: str) -> bool:
    r"""Whether ``\\`` occurs outside an environment (MathJax 3 ignores it there)."""
    depth = 0
    for k in range(len(latex)):
        if latex.startswith(r"\begin", k):
            depth += 1
        elif latex.startswith(r"\end", k):
            depth -= 1
        elif depth == 0 and latex.startswith("\\\\", k):
            return True
    return False


def math_problems(html: str, where: str) -> list[str]:
    out = []
    if html.count(r"\(") != html.count(r"\)") or html.count(r"\[") != html.count(r"\]"):
        out.append(f"{where}: unbalanced math delimiters")
    for formula in INLINE.findall(html):
        if _top_level_breaks(formula):
            out.append(f"{where}: a line break \\\\ in inline math: {formula[:60]!r}")
        if len(formula) > MAX_INLINE:
            out.append(f"{where}: an inline formula wider than a phone: {formula[:60]!r}")
    for formula in DISPLAY.findall(html):
        if _top_level_breaks(formula):
            out.append(f"{where}: a line break \\\\ outside an environment: {formula[:60]!r}")
    return out


def _files(question: ET.Element, path: str, where: str) -> list[str]:
    out = []
    node = question.find(path)
    text = "" if node is None else node.findtext("text") or ""
    names = set()
    for f in [] if node is None else node.findall("file"):
        name = f.get("name") or ""
        names.add(name)
        if f.get("encoding") != "base64" or not f.get("path", "").startswith("/"):
            out.append(f"{where}: file {name} without encoding base64 and a path")
        try:
            base64.b64decode(f.text or "", validate=True)
        except ValueError:
            out.append(f"{where}: file {name} is not base64")
    for name in re.findall(r"@@PLUGINFILE@@/([^\"'?#]+)", text):
        if name not in names:
            out.append(f"{where}: @@PLUGINFILE@@/{name} has no <file>")
    return out


def _numerical(q: ET.Element, where: str) -> list[str]:
    out = []
    answers = q.findall("answer")
    if not answers:
        out.append(f"{where}: a numerical question without an answer")
    for a in answers:
        try:
            fraction = float(a.get("fraction", "nan"))
            value = a.findtext("text") or ""
            if value != "*":
                float(value)
            if float(a.findtext("tolerance") or "nan") < 0:
                out.append(f"{where}: a negative tolerance")
        except ValueError as error:
            out.append(f"{where}: {error}")
            continue
        if not 0 <= fraction <= 100:
            out.append(f"{where}: fraction {fraction} outside 0..100")
        if a.find("feedback/text") is None:
            out.append(f"{where}: an answer without <feedback><text>")
    if not any(a.get("fraction") == "100" for a in answers):
        out.append(f"{where}: no answer graded 100 %")
    return out


def _cloze(text: str, where: str) -> list[str]:
    try:
        parts = cloze_parts(text)
    except ValueError as error:
        return [f"{where}: {error}"]
    if not parts:
        return [f"{where}: a cloze question without a sub-question"]
    out = []
    rest = CLOZE_PART.sub("", text)
    if rest.count("{") != rest.count("}") or "~%" in rest:  # an unescaped } ended a part early
        out.append(f"{where}: a sub-question broken by an unescaped special character")
    for k, part in enumerate(parts):
        if not any(a.fraction == 100.0 for a in part):
            out.append(f"{where}: part {k + 1} has no answer graded 100 %")
        if any(a.tolerance < 0 or not 0 <= a.fraction <= 100 for a in part):
            out.append(f"{where}: part {k + 1}: a negative tolerance or a fraction out of range")
    return out


def problems(xml: str) -> list[str]:
    """Every rule the Moodle XML file breaks (see the module docstring)."""
    try:
        quiz = ET.fromstring(xml)
    except ET.ParseError as error:
        return [f"not well-formed XML: {error}"]
    if quiz.tag != "quiz":
        return [f"the root is <{quiz.tag}>, not <quiz>"]
    out = []
    for k, q in enumerate(quiz.findall("question")):
        kind = q.get("type") or ""
        where = f"question {k} ({kind})"
        if kind not in QUESTION_TYPES:
            out.append(f"{where}: unknown type")
            continue
        if kind == "category":
            if not (q.findtext("category/text") or "").startswith("$course$/"):
                out.append(f"{where}: a category outside $course$/")
            continue
        if not (q.findtext("name/text") or "").strip():
            out.append(f"{where}: no name")
        text = q.findtext("questiontext/text") or ""
        if q.find("questiontext").get("format") != "html" or not text:  # type: ignore[union-attr]
            out.append(f"{where}: no HTML question text")
        if q.find("generalfeedback/text") is None:
            out.append(f"{where}: no <generalfeedback><text>")
        for tag, low, high in (("defaultgrade", 0, 1e9), ("penalty", 0, 1), ("hidden", 0, 1)):
            try:
                if not low <= float(q.findtext(tag) or "nan") <= high:
                    out.append(f"{where}: <{tag}> out of range")
            except ValueError:
                out.append(f"{where}: <{tag}> is not a number")
        out += _files(q, "questiontext", where)
        out += math_problems(text, where)
        out += math_problems(q.findtext("generalfeedback/text") or "", f"{where} feedback")
        for img in re.findall(r"<img [^>]*>", text):
            if "max-width: 100%" not in img or 'alt="' not in img:
                out.append(f"{where}: an image without alt text or max-width 100 %")
        out += _numerical(q, where) if kind == "numerical" else _cloze(text, where)
    return out


def record(directory: Path) -> None:
    """Write ``<type>.xml`` for every exercise type: one standard exercise (seed 1) with its
    worked solution in the general feedback."""
    from solver.exercises import TYPES, ExerciseId, build
    from solver.exercises.export import moodle_xml

    directory.mkdir(parents=True, exist_ok=True)
    for kind in TYPES:
        xml = moodle_xml([build(ExerciseId(kind, "standard", 1, 0))], with_solutions=True)
        (directory / f"{kind}.xml").write_text(xml)


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] != "record":
        sys.exit("usage: python -m tests.moodle_rules record DIR")
    record(Path(sys.argv[2]))
