"""The solving plan (solver.position.topology): each textbook preset decomposes into closed-form
groups (drivers, dyads, levers, two-point and guided links); what remains is a Newton group.
"""

import pytest

from solver.analysis.instant import analyze
from solver.model.scene import parse_linkage
from solver.position.topology import (
    DriverStep,
    DyadStep,
    GuidedStep,
    LeverStep,
    TwoPointStep,
    build_plan,
)
from solver.teaching.presets import build_preset


@pytest.mark.parametrize(("preset", "kinds"), [
    ("four_bar", [DriverStep, DyadStep, TwoPointStep, TwoPointStep]),
    ("slider_crank", [DriverStep, DyadStep, TwoPointStep]),
    ("inverted_slider_crank", [DriverStep, LeverStep]),
    ("quick_return", [DriverStep, LeverStep, DyadStep, TwoPointStep]),
    ("slider_guide_extension", [DriverStep, DyadStep, TwoPointStep]),
])  # fmt: skip
def test_textbook_presets_decompose_into_closed_form_groups(preset: str, kinds: list) -> None:
    plan = build_plan(parse_linkage(build_preset(preset, {})))
    assert [type(step) for step in plan.steps] == kinds
    assert plan.closed_form


def test_block_in_a_guide_is_a_guided_link() -> None:
    """A slider-crank with an explicit block: circle-line dyad, then the block by its guide."""
    doc = build_preset("slider_crank", {"offset": 0.0, "coupler_point_u": 0, "coupler_point_v": 0})
    doc["links"]["block"] = {"points": ["C"]}
    doc["joints"] = [j for j in doc["joints"] if j["type"] == "revolute"] + [
        {"type": "revolute", "point": "C", "links": ["coupler", "block"]},
        {"type": "prismatic", "point": "C", "links": ["ground", "block"], "axis": [1, 0]},
    ]
    scene = parse_linkage(doc)
    plan = build_plan(scene)
    assert any(isinstance(step, GuidedStep) for step in plan.steps)
    result = analyze(scene)
    assert result.links["block"].omega == 0.0
    assert result.points["C"].velocity[1] == pytest.approx(0.0, abs=1e-15)
