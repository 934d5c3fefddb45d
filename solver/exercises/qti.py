"""The exercises as an IMS QTI 2.1 content package, for the LMSs that import QTI (Canvas,
Blackboard, OpenOLAT, ...): a zip with ``imsmanifest.xml`` (IMS Content Packaging 1.1) and, per
exercise, an ``assessmentItem`` with its figure beside it.

An item states the exercise in words (the statement, which states every datum and the sign
convention), shows the figure (``<img>``, its alt text naming no id) and asks each quantity in a
``textEntryInteraction`` with a float ``responseDeclaration`` whose ``correctResponse`` is the
key; response processing adds 1 to SCORE for each answer ``equal`` to it with ``toleranceMode``
relative (QTI's tolerance is in percent). Else, for each typical mistake of the exercise whose
wrong value lies apart from the key (``export.distractors``, the Moodle export's 0 % answers),
an answer ``equal`` to that value scores nothing and adds the mistake's identifier to FEEDBACK,
which shows the ``feedbackBlock`` naming it under the answer's field. Validated against the IMS
QTI 2.1 XSD in the tests.
"""

from __future__ import annotations

import io
import re
import zipfile
from collections.abc import Sequence
from xml.sax.saxutils import escape, quoteattr

from solver.exercises.export import Distractor, answer_text, distractors, figure_alt, set_name
from solver.exercises.model import Exercise

NAMESPACE = "http://www.imsglobal.org/xsd/imsqti_v2p1"
SCHEMA = "http://www.imsglobal.org/xsd/qti/qtiv2p1/imsqti_v2p1.xsd"


def item_identifier(e: Exercise) -> str:
    """The exercise's name as an XML NCName (QTI identifiers): ``:`` becomes ``-``."""
    return re.sub(r"[^A-Za-z0-9_.-]", "-", e.name)


def _response(e: Exercise, key: str) -> str:
    return f"RESPONSE_{key}"


def mistake_identifier(key: str, k: int) -> str:
    """The FEEDBACK identifier of the k-th typical mistake's answer to the quantity ``key``."""
    return f"MISTAKE_{key}_{k}"


def _equal(response: str, tolerance: float, value: str) -> str:
    return (
        f'<equal toleranceMode="relative" tolerance="{tolerance * 100:g}">'
        f'<variable identifier="{response}"/>{value}</equal>'
    )


def _mistake_branch(response: str, tolerance: float, identifier: str, d: Distractor) -> str:
    """``responseElseIf`` the answer equals the mistake's value: FEEDBACK gets its identifier."""
    value = f'<baseValue baseType="float">{answer_text(d.value, tolerance)}</baseValue>'
    return (
        f"<responseElseIf>{_equal(response, tolerance, value)}"
        '<setOutcomeValue identifier="FEEDBACK"><multiple><variable identifier="FEEDBACK"/>'
        f'<baseValue baseType="identifier">{identifier}</baseValue></multiple>'
        "</setOutcomeValue></responseElseIf>"
    )


def assessment_item(e: Exercise, figure: str) -> str:
    """The QTI 2.1 ``assessmentItem`` of one exercise, its figure at the relative URL
    ``figure``."""
    wrong = distractors(e)
    declarations = "".join(
        f'<responseDeclaration identifier="{_response(e, a.key)}" cardinality="single" '
        f'baseType="float"><correctResponse><value>'
        f"{answer_text(e.answers[a.key], a.tolerance)}</value></correctResponse>"
        "</responseDeclaration>"
        for a in e.asked
    )
    fields = "".join(
        f"<p>{escape(a.label[:1].upper() + a.label[1:])} ({escape(a.unit)}): "
        f'<textEntryInteraction responseIdentifier="{_response(e, a.key)}" '
        'expectedLength="12"/></p>'
        + "".join(
            f'<feedbackBlock outcomeIdentifier="FEEDBACK" '
            f'identifier="{mistake_identifier(a.key, k)}" showHide="show">'
            f"<p>{escape(d.feedback)}</p></feedbackBlock>"
            for k, d in enumerate(wrong[a.key])
        )
        for a in e.asked
    )
    rules = "".join(
        "<responseCondition><responseIf>"
        + _equal(_response(e, a.key), a.tolerance, f'<correct identifier="{_response(e, a.key)}"/>')
        + '<setOutcomeValue identifier="SCORE"><sum><variable identifier="SCORE"/>'
        '<baseValue baseType="float">1</baseValue></sum></setOutcomeValue></responseIf>'
        + "".join(
            _mistake_branch(_response(e, a.key), a.tolerance, mistake_identifier(a.key, k), d)
            for k, d in enumerate(wrong[a.key])
        )
        + "</responseCondition>"
        for a in e.asked
    )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<assessmentItem xmlns="{NAMESPACE}" '
        'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
        f'xsi:schemaLocation="{NAMESPACE} {SCHEMA}" identifier="{item_identifier(e)}" '
        f'title={quoteattr(e.title)} adaptive="false" timeDependent="false">'
        f"{declarations}"
        '<outcomeDeclaration identifier="SCORE" cardinality="single" baseType="float">'
        "<defaultValue><value>0</value></defaultValue></outcomeDeclaration>"
        '<outcomeDeclaration identifier="FEEDBACK" cardinality="multiple" baseType="identifier"/>'
        '<outcomeDeclaration identifier="MAXSCORE" cardinality="single" baseType="float">'
        f"<defaultValue><value>{len(e.asked)}</value></defaultValue></outcomeDeclaration>"
        f"<itemBody><p>{escape(e.statement.text)}</p>"
        f'<p><img src={quoteattr(figure)} alt={quoteattr(figure_alt(e))} width="420" '
        f'height="300"/></p>{fields}</itemBody>'
        f"<responseProcessing>{rules}</responseProcessing></assessmentItem>\n"
    )


def _manifest(exercises: Sequence[Exercise]) -> str:
    resources = "".join(
        f'<resource identifier="R-{item_identifier(e)}" type="imsqti_item_xmlv2p1" '
        f'href="items/{item_identifier(e)}.xml"><file href="items/{item_identifier(e)}.xml"/>'
        f'<file href="items/{item_identifier(e)}/figure.svg"/></resource>'
        for e in exercises
    )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<manifest xmlns="http://www.imsglobal.org/xsd/imscp_v1p1" '
        f'identifier="M-{re.sub(r"[^A-Za-z0-9_.-]", "-", set_name(exercises, "-"))}">'
        f"<organizations/><resources>{resources}</resources></manifest>\n"
    )


def qti_package(exercises: Sequence[Exercise]) -> bytes:
    """The zip: ``imsmanifest.xml``, ``items/<id>.xml`` and ``items/<id>/figure.svg``."""
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as package:
        package.writestr("imsmanifest.xml", _manifest(exercises))
        for e in exercises:
            name = item_identifier(e)
            package.writestr(f"items/{name}.xml", assessment_item(e, f"{name}/figure.svg"))
            package.writestr(f"items/{name}/figure.svg", e.statement.figure_svg)
    return out.getvalue()
