"""The QTI export: an IMS content package whose items validate against the IMS QTI 2.1 XSD
(tests/reference/qti, lxml, no network), with the key as each response's correct value, the
relative tolerance in QTI's percent, and the figure packaged beside its item."""

from __future__ import annotations

import io
import zipfile
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from lxml import etree

from solver.exercises import TYPES
from solver.exercises.export import significant_digits

ROOT = Path(__file__).resolve().parents[2]
QTI = "{http://www.imsglobal.org/xsd/imsqti_v2p1}"
CP = "{http://www.imsglobal.org/xsd/imscp_v1p1}"


@pytest.fixture(scope="module")
def schema() -> Any:
    return etree.XMLSchema(etree.parse(str(ROOT / "tests/reference/qti/qtiv2p1/imsqti_v2p1.xsd")))


def _package(client: TestClient, kind: str, **body: Any) -> zipfile.ZipFile:
    r = client.post(
        "/api/v1/exercises/export", json={"type": kind, "seed": 3, "format": "qti", **body}
    )
    assert r.status_code == 200, r.text
    assert r.headers["content-type"] == "application/zip"
    assert r.headers["content-disposition"].endswith('.zip"')
    return zipfile.ZipFile(io.BytesIO(r.content))


@pytest.mark.parametrize("kind", list(TYPES))
def test_every_item_validates_and_carries_the_key(
    client: TestClient, schema: Any, kind: str
) -> None:
    package = _package(client, kind, count=2)
    exercises = client.post("/api/v1/exercises", json={"type": kind, "seed": 3, "count": 2}).json()[
        "exercises"
    ]
    manifest = etree.fromstring(package.read("imsmanifest.xml"))
    resources = manifest.findall(f"{CP}resources/{CP}resource")
    assert len(resources) == len(exercises)
    for resource, e in zip(resources, exercises, strict=True):
        assert resource.get("type") == "imsqti_item_xmlv2p1"
        item = etree.fromstring(package.read(resource.get("href")))
        assert schema.validate(item), schema.error_log
        assert item.get("title") == e["title"]
        image = item.find(f".//{QTI}img")
        assert image is not None and e["id"] not in (image.get("alt") or "")
        figure = package.read(f"items/{image.get('src')}")
        assert etree.fromstring(figure).tag == "{http://www.w3.org/2000/svg}svg"
        declared = item.findall(f"{QTI}responseDeclaration")
        assert len(declared) == len(e["asked"])
        for d, asked in zip(declared, e["asked"], strict=True):
            value = d.findtext(f"{QTI}correctResponse/{QTI}value") or "nan"
            expected = e["answers"][asked["key"]]
            assert abs(float(value) - expected) <= 0.1 * asked["tolerance"] * abs(expected)
            digits = value.lstrip("-").replace(".", "").lstrip("0")
            assert len(digits) <= significant_digits(asked["tolerance"])
        tolerances = {q.get("tolerance") for q in item.iter(f"{QTI}equal")}
        assert tolerances == {"1"}  # percent, relative
        interactions = item.findall(f".//{QTI}textEntryInteraction")
        assert len(interactions) == len(e["asked"])


def test_the_schema_refuses_a_broken_item(client: TestClient, schema: Any) -> None:
    package = _package(client, "slider_crank", count=1)
    name = next(n for n in package.namelist() if n.endswith(".xml") and n.startswith("items/"))
    item = etree.fromstring(package.read(name))
    assert schema.validate(item)
    item.find(f"{QTI}responseDeclaration").set("baseType", "number")  # not a QTI base type
    assert not schema.validate(item)


def test_the_chosen_tolerance_reaches_the_items(client: TestClient) -> None:
    package = _package(client, "four_bar_velocity", count=1, tolerance=0.02)
    item = next(package.read(n) for n in package.namelist() if n.endswith(".xml") and "items/" in n)
    assert b'tolerance="2"' in item


@pytest.mark.parametrize(
    "kind", ["four_bar_acceleration", "inverted_slider_crank", "flywheel", "synthesis_function"]
)
def test_each_typical_mistake_has_a_zero_answer_whose_feedback_names_it(
    client: TestClient, schema: Any, kind: str
) -> None:
    """Like the Moodle export's 0 % answers: after the right answer's branch, a branch per
    typical mistake ``equal`` (relative, the tolerance) to its value scores nothing and shows a
    feedbackBlock naming it; the checker, given that value, names the same mistake."""
    package = _package(client, kind, count=2, difficulty="challenging")
    branches = 0
    for name in package.namelist():
        if not (name.startswith("items/") and name.endswith(".xml")):
            continue
        item = etree.fromstring(package.read(name))
        assert schema.validate(item), schema.error_log
        blocks = {b.get("identifier"): b for b in item.iter(f"{QTI}feedbackBlock")}
        practice_id = item.get("identifier").replace("-", ":")
        for condition in item.iter(f"{QTI}responseCondition"):
            first, *others = list(condition)
            assert first.tag == f"{QTI}responseIf"
            assert first.find(f".//{QTI}correct") is not None
            for branch in others:
                assert branch.tag == f"{QTI}responseElseIf"
                equal = branch.find(f"{QTI}equal")
                assert equal.get("toleranceMode") == "relative" and equal.get("tolerance") == "1"
                response = equal.find(f"{QTI}variable").get("identifier")
                value = float(equal.find(f"{QTI}baseValue").text or "nan")
                assert branch.find(f".//{QTI}setOutcomeValue").get("identifier") == "FEEDBACK"
                shown = branch.find(f".//{QTI}multiple/{QTI}baseValue").text
                text = "".join(blocks[shown].itertext())
                key = response.removeprefix("RESPONSE_")
                checked = client.post(
                    "/api/v1/exercises/check", json={"id": practice_id, "answers": {key: value}}
                ).json()["results"]
                row = next(r for r in checked if r["key"] == key)
                assert row["verdict"] == "incorrect" and row["mistake"] is not None
                assert text.startswith("Not right: ") and row["diagnosis"] in text
                branches += 1
    assert branches > 0
