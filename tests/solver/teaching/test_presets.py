"""Tests of solver.teaching.presets: every preset's document against its defining geometry
(defaults and hypothesis draws), the two assembly branches, the reference example scenes S000-T1..T4
and S001 rebuilt from their dimensions, the error messages, and (once the analysis exists) a round
trip through the scene parser and the position solver."""

from __future__ import annotations

import cmath
import json
import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings

from solver.errors import InvalidScene, NotAssemblable
from solver.teaching.presets import COINCIDENT, PRESETS, build_preset
from tests.strategies import assemblable_presets

EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"
EXPECTED_NAMES = [
    "four_bar",
    "slider_crank",
    "inverted_slider_crank",
    "quick_return",
    "slider_guide_extension",
    "seed004",
]


def _points(doc: Mapping[str, Any]) -> dict[str, complex]:
    return {name: complex(x, y) for name, (x, y) in doc["points"].items()}


def _defaults(name: str) -> dict[str, float]:
    return {p.name: p.default for p in PRESETS[name].parameters}


def _example(name: str) -> dict[str, Any]:
    doc: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return doc


def check_geometry(name: str, v: Mapping[str, float], doc: Mapping[str, Any], tol: float) -> None:
    """Assert the document realises the parameters: every length, the crank angle, the points on
    their guide or slot lines, the branch and the coupler point. Distances are compared to within
    ``tol`` times the largest length parameter (property: the definition of each preset)."""
    p = _points(doc)
    size = max(abs(x) for k, x in v.items() if k not in ("omega", "alpha", "crank_angle_deg"))

    def close(a: complex | float, b: complex | float) -> None:
        assert abs(a - b) <= tol * size, (a, b)

    pivot, pin = (
        p[k]
        for k in {"inverted_slider_crank": "OA", "quick_return": ["O2", "A"], "seed004": "OA"}.get(
            name, "AB"
        )
    )
    assert pivot == 0
    close(abs(pin - pivot), v["crank"])
    close(pin, cmath.rect(v["crank"], math.radians(v["crank_angle_deg"])))
    joints = {j["point"]: j for j in doc["joints"]}

    if name == "seed004":
        a, b, gamma = p["A"], p["B"], p["Gamma"]
        assert gamma == v["ground"]
        close(abs(b - a), v["coupler"])
        close(abs(b - gamma), v["rocker"])
        assert ((b - a) / (gamma - a)).imag > 0  # B to the left of A->Gamma
        close(p["D"], gamma + (b - gamma) / abs(b - gamma) * (v["rocker"] + v["extension"]))
    elif name == "four_bar":
        b, c, d = p["B"], p["C"], p["D"]
        assert d == v["ground"]
        close(abs(c - b), v["coupler"])
        close(abs(c - d), v["rocker"])
        assert (((c - b) / (d - b)).imag > 0) == (v["assembly"] == 0)  # open: C left of B->D
    elif name in ("slider_crank", "slider_guide_extension"):
        b, c = p["B"], p["C"]
        close(abs(c - b), v["rod" if name == "slider_crank" else "coupler"])
        close(c.imag, v["offset" if name == "slider_crank" else "guide_height"])
        assert (c.real >= b.real) == (v.get("assembly", 0) == 0)
        assert joints["C"]["axis"] == [1.0, 0.0]
        if name == "slider_guide_extension":
            close(p["D"], c + v["extension"] * (c - b) / abs(c - b))
    else:
        lever_pivot, end = (
            (p["C"], p["D"]) if name == "inverted_slider_crank" else (p["O4"], p["B"])
        )
        ground = v["ground"]
        assert lever_pivot == (ground if name == "inverted_slider_crank" else -1j * ground)
        u = complex(*joints["A"]["axis"])
        close(abs(u), 1.0)
        close(abs(end - lever_pivot), v["lever"])
        for on_slot in (p["A"], end):  # slot line: pivot + offset iu + s u, s >= 0
            close(((on_slot - lever_pivot) / u).imag, v["slot_offset"])
            assert ((on_slot - lever_pivot) / u).real >= -tol * size
        if name == "quick_return":
            close(abs(p["C"] - end), v["rod"])
            close(p["C"].imag, v["ram_height"])
            assert p["C"].real >= end.real

    coupler_point = complex(v.get("coupler_point_u", 0.0), v.get("coupler_point_v", 0.0))
    if "P" in p:
        b, c = p["B"], p["C"]
        close((p["P"] - b) / ((c - b) / abs(c - b)), coupler_point)
    elif name in ("four_bar", "slider_crank"):  # left out only where it falls on B or C
        xs, ys = [z.real for z in p.values()], [z.imag for z in p.values()]
        drawing = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
        offset = min(abs(coupler_point), abs(coupler_point - abs(p["C"] - p["B"])))
        assert offset <= COINCIDENT * drawing + tol * size


def check_structure(doc: Mapping[str, Any]) -> None:
    """Assert the document keeps the scene-v1 rules the presets rely on (spec/scene-v1.md)."""
    json.dumps(doc, allow_nan=False)
    assert doc["kind"] == "linkage" and doc["title"]
    links = doc["links"]
    assert [name for name, link in links.items() if link.get("ground")] == ["ground"]
    listed = {p for link in links.values() for p in link["points"]}
    assert listed == set(doc["points"])
    for joint in doc["joints"]:
        first, second = (links[name]["points"] for name in joint["links"])
        if joint["type"] == "revolute":
            assert joint["point"] in first and joint["point"] in second
        else:  # slider: the point is attached to the follower, not to the guide
            assert joint["type"] == "slider"
            assert joint["point"] in second and joint["point"] not in first
            assert math.isclose(math.hypot(*joint["axis"]), 1.0)
    freedom = 3 * (len(links) - 1) - sum(2 if j["type"] == "revolute" else 1 for j in doc["joints"])
    assert freedom == 1
    assert doc["drivers"] == [
        {"link": "crank", "omega": doc["drivers"][0]["omega"], "alpha": doc["drivers"][0]["alpha"]}
    ]


# --- metadata and defaults -----------------------------------------------------------------------


def test_presets_are_listed_in_order_with_documented_parameters() -> None:
    assert list(PRESETS) == EXPECTED_NAMES
    for name, preset in PRESETS.items():
        assert preset.name == name and preset.title and len(preset.description) > 100
        names = [p.name for p in preset.parameters]
        assert len(set(names)) == len(names)
        assert {"crank", "crank_angle_deg", "omega", "alpha"} <= set(names)
        for parameter in preset.parameters:
            assert parameter.description
            assert parameter.check(parameter.default) == parameter.default
            units = ("m", "deg", "rad/s", "rad/s^2", "", "kg", "kg/m", "m/s^2", "N", "N m")
            assert parameter.unit in units


@pytest.mark.parametrize("name", EXPECTED_NAMES)
def test_defaults_realise_the_parameters(name: str) -> None:
    values = _defaults(name)
    doc = build_preset(name, {})
    assert doc == build_preset(name, values)
    check_structure(doc)
    check_geometry(name, values, doc, tol=1e-12)
    assert doc["drivers"][0]["omega"] == values["omega"]
    assert doc["drivers"][0]["alpha"] == values["alpha"]


def test_four_bar_default_is_the_seed_004_crank_rocker() -> None:
    v = _defaults("four_bar")
    assert (v["ground"], v["crank"], v["coupler"], v["rocker"]) == (1.0, 0.15, 1.0, 0.55)
    assert v["omega"] == 8 * math.pi  # 240 rpm
    assert "P" in build_preset("four_bar", {})["points"]


@pytest.mark.parametrize("name", ["four_bar", "slider_crank"])
def test_coupler_point_on_a_joint_is_left_out(name: str) -> None:
    for u, v in [(0.0, 0.0), (0.35 if name == "slider_crank" else 1.0, 0.0)]:
        doc = build_preset(name, {"coupler_point_u": u, "coupler_point_v": v})
        assert "P" not in doc["points"]
        assert doc["links"]["coupler"]["points"] == ["B", "C"]
        check_structure(doc)


@pytest.mark.parametrize(
    ("name", "values"),
    [
        ("inverted_slider_crank", {"slot_offset": 0.05}),
        ("inverted_slider_crank", {"slot_offset": -0.05, "crank": 0.45, "lever": 1.0}),
        ("quick_return", {"slot_offset": 0.1}),
        ("quick_return", {"slot_offset": -0.1, "crank_angle_deg": 200.0}),
    ],
)
def test_offset_slot_passes_through_the_pin(name: str, values: dict[str, float]) -> None:
    doc = build_preset(name, values)
    check_structure(doc)
    check_geometry(name, _defaults(name) | values, doc, tol=1e-12)


# --- assembly branches ---------------------------------------------------------------------------


def test_four_bar_branches_are_mirror_images_across_bd() -> None:
    open_, crossed = (_points(build_preset("four_bar", {"assembly": a})) for a in (0.0, 1.0))
    b, d = open_["B"], open_["D"]
    assert abs(open_["C"] - crossed["C"]) > 0.1
    # reflection across the line B->D: z -> b + conj((z - b)/e) e with e the unit of B->D
    e = (d - b) / abs(d - b)
    assert abs(b + ((open_["C"] - b) / e).conjugate() * e - crossed["C"]) < 1e-12
    check_geometry(
        "four_bar",
        _defaults("four_bar") | {"assembly": 1.0},
        build_preset("four_bar", {"assembly": 1.0}),
        tol=1e-12,
    )


def test_slider_crank_branches_are_mirror_images_across_the_normal_through_b() -> None:
    right, left = (_points(build_preset("slider_crank", {"assembly": a})) for a in (0.0, 1.0))
    assert right["C"].real > right["B"].real > left["C"].real
    assert right["C"].imag == left["C"].imag == 0.05
    assert abs(right["C"].real + left["C"].real - 2 * right["B"].real) < 1e-12
    check_geometry(
        "slider_crank",
        _defaults("slider_crank") | {"assembly": 1.0},
        build_preset("slider_crank", {"assembly": 1.0}),
        tol=1e-12,
    )


# --- the reference example scenes rebuilt ---------------------------------------------------------


def _same_points(
    doc: Mapping[str, Any],
    example: Mapping[str, Any],
    names: Mapping[str, str] | None = None,
    turn: complex = 1,
) -> None:
    """Each example point (renamed by ``names``, turned by ``turn`` about the origin) equals the
    document's; the examples are rounded to 12 decimals."""
    ours, theirs = _points(doc), _points(example)
    for name, z in theirs.items():
        assert abs(ours[(names or {}).get(name, name)] - turn * z) < 1e-9, name


def test_s000_t1_four_bar() -> None:
    example = _example("S000-T1")
    doc = build_preset(
        "four_bar",
        {
            "ground": 2.5,
            "crank": 1.0,
            "coupler": 2.0,
            "rocker": math.sqrt(1.25),
            "crank_angle_deg": 90.0,
            "coupler_point_u": 0.0,
            "coupler_point_v": 0.0,
            "omega": -1.0,
            "alpha": -1.0,
        },
    )
    _same_points(doc, example)
    for key in ("links", "joints", "drivers"):
        assert doc[key] == example[key]


def test_s000_t3_slider_with_coupler_extension() -> None:
    example = _example("S000-T3")
    doc = build_preset(
        "slider_guide_extension",
        {
            "crank": 0.3,
            "coupler": 0.5,
            "extension": 0.4,
            "guide_height": 0.24,
            "crank_angle_deg": math.degrees(math.atan2(0.24, -0.18)),
            "omega": -4.0,
        },
    )
    _same_points(doc, example)
    for key in ("links", "joints", "drivers"):
        assert doc[key] == example[key]


def test_s000_t4_centred_slider_crank() -> None:
    example = _example("S000-T4")
    bx, by = example["points"]["B"]
    cx, _ = example["points"]["C"]
    doc = build_preset(
        "slider_crank",
        {
            "crank": math.hypot(bx, by),
            "rod": math.hypot(cx - bx, by),
            "offset": 0.0,
            "crank_angle_deg": math.degrees(math.atan2(by, bx)),
            "coupler_point_u": 0.0,
            "coupler_point_v": 0.0,
            "omega": -2.0,
            "alpha": -3.0,
        },
    )
    _same_points(doc, example)
    for key in ("links", "joints", "drivers"):
        assert doc[key] == example[key]


def test_s001_offset_slider_crank() -> None:
    example = _points(_example("S001-offset-slider-crank"))
    a, b = example["A"], example["B"]
    doc = build_preset(
        "slider_crank",
        {
            "crank": abs(a),
            "rod": abs(b - a),
            "offset": 0.05,
            "crank_angle_deg": 60.0,
        },
    )
    ours = _points(doc)
    assert abs(ours["B"] - a) < 1e-9 and abs(ours["C"] - b) < 1e-9


def test_s000_t2_inverted_slider_crank_turned_half_a_turn() -> None:
    # S000-T2 has the lever pivot (A) left of the crank pivot (C); turned by 180 deg about C it is
    # the preset's layout with the crank at -30 deg: crank C->B = 0.4 m, pivots sqrt(0.12) m apart
    example = _example("S000-T2")
    shift = complex(*example["points"]["C"])
    example["points"] = {
        k: [x - shift.real, y - shift.imag] for k, (x, y) in example["points"].items()
    }
    doc = build_preset(
        "inverted_slider_crank",
        {
            "crank": 0.4,
            "ground": math.sqrt(0.12),
            "lever": 0.4,
            "crank_angle_deg": -30.0,
            "omega": -2.0,
            "alpha": 3.0,
        },
    )
    _same_points(doc, example, names={"C": "O", "B": "A", "A": "C", "D": "D"}, turn=-1)
    assert doc["joints"][2]["axis"] == pytest.approx([0.0, -1.0], abs=1e-12)


# --- errors --------------------------------------------------------------------------------------


def test_unknown_preset_lists_the_available_names() -> None:
    with pytest.raises(
        InvalidScene,
        match="unknown preset 'watt'; available: four_bar, "
        "slider_crank, inverted_slider_crank, quick_return, slider_guide_extension",
    ):
        build_preset("watt", {})


def test_unknown_parameter_is_named_with_the_allowed_ones() -> None:
    with pytest.raises(InvalidScene) as info:
        build_preset("four_bar", {"crank": 0.1, "lenght": 1.0, "beta": 2.0})
    assert info.value.message == (
        "unknown parameter(s) beta, lenght for preset 'four_bar'; allowed: ground, crank, "
        "coupler, rocker, crank_angle_deg, assembly, coupler_point_u, coupler_point_v, omega, "
        "alpha, mass_per_length, gravity, load"
    )


@pytest.mark.parametrize(
    ("name", "values", "message"),
    [
        ("four_bar", {"crank": 0.0}, "crank = 0 m is outside the range [0.0001, 10000] m"),
        ("slider_crank", {"rod": 2e4}, "rod = 20000 m is outside the range [0.0001, 10000] m"),
        ("four_bar", {"omega": -2e4}, "omega = -20000 rad/s is outside the range"),
        ("quick_return", {"crank_angle_deg": 400.0}, "crank_angle_deg = 400 deg is outside"),
        ("four_bar", {"assembly": 0.5}, "assembly = 0.5 is not one of 0, 1"),
        ("slider_crank", {"assembly": 2.0}, "assembly = 2 is not one of 0, 1"),
        ("four_bar", {"ground": math.nan}, "ground must be a finite number"),
        ("four_bar", {"alpha": math.inf}, "alpha must be a finite number"),
        ("four_bar", {"crank": "long"}, "crank: expected a number, got 'long'"),
        (
            "inverted_slider_crank",
            {"slot_offset": 0.6},
            "lever = 0.5 m must be longer than |slot_offset| = 0.6 m",
        ),
    ],
)
def test_invalid_values_are_refused(name: str, values: dict[str, Any], message: str) -> None:
    with pytest.raises(InvalidScene, match=re.escape(message)):
        build_preset(name, values)


@pytest.mark.parametrize(
    ("name", "values", "message"),
    [
        (  # B = (-0.15, 0): |BD| = 1.15 m, out of the reach of coupler + rocker
            "four_bar",
            {"coupler": 0.6, "rocker": 0.5, "crank_angle_deg": 180.0},
            "|BD| = 1.15 m > coupler + rocker = 1.1 m at crank angle 180 deg",
        ),
        (  # B = (0.15, 0): |BD| = 0.85 m, closer than coupler - rocker
            "four_bar",
            {"coupler": 1.0, "rocker": 0.1, "crank_angle_deg": 0.0},
            "|BD| = 0.85 m < |coupler - rocker| = 0.9 m at crank angle 0 deg",
        ),
        (  # crank = ground at angle 0 puts B on D: no triangle BCD
            "four_bar",
            {"crank": 1.0, "crank_angle_deg": 0.0},
            "|BD| = 0 m < |coupler - rocker| = 0.45 m at crank angle 0 deg",
        ),
        (  # B = (0, 0.1): 0.9 m below the guide
            "slider_crank",
            {"offset": 1.0, "crank_angle_deg": 90.0},
            "the distance from B to the guide line y = 1 m is 0.9 m > rod = 0.35 m "
            "at crank angle 90 deg",
        ),
        (  # B = (0.3, 0): 0.64 m below the guide
            "slider_guide_extension",
            {"crank_angle_deg": 0.0, "guide_height": 0.64},
            "the distance from B to the guide line y = 0.64 m is 0.64 m > coupler = 0.5 m "
            "at crank angle 0 deg",
        ),
        (  # A = (0.15, 0): 0.15 m from C, the slot is 0.2 m from C
            "inverted_slider_crank",
            {"crank_angle_deg": 0.0, "slot_offset": 0.2},
            "|CA| = 0.15 m < |slot_offset| = 0.2 m at crank angle 0 deg: "
            "the pin cannot reach the slot line",
        ),
        (  # lever vertical at crank angle 90 deg: B = (0, 0.3), 0.3 m below the ram's guide
            "quick_return",
            {"crank_angle_deg": 90.0, "ram_height": 0.6},
            "the distance from B to the ram's guide y = 0.6 m is 0.3 m > rod = 0.2 m "
            "at crank angle 90 deg",
        ),
    ],
)
def test_geometry_that_cannot_close_is_not_assemblable(
    name: str, values: dict[str, float], message: str
) -> None:
    with pytest.raises(NotAssemblable) as info:
        build_preset(name, values)
    assert info.value.message == message


def test_build_does_not_mutate_its_input() -> None:
    values = {"crank": 0.2}
    build_preset("four_bar", values)
    assert values == {"crank": 0.2}


# --- properties ----------------------------------------------------------------------------------


@pytest.mark.slow
@settings(max_examples=300, deadline=None)
@given(assemblable_presets())
def test_assemblable_draws_realise_their_parameters(case: tuple[str, dict[str, float]]) -> None:
    name, values = case
    doc = build_preset(name, values)
    check_structure(doc)
    check_geometry(name, values, doc, tol=1e-9)


# --- round trip through the scene parser and the position solver ----------------------------------


@pytest.mark.parametrize("name", EXPECTED_NAMES)
def test_default_documents_parse_and_analyze_to_their_drawn_pose(name: str) -> None:
    analysis = pytest.importorskip("solver.analysis.instant")
    scene_module = pytest.importorskip("solver.model.scene")
    parse = getattr(scene_module, "parse_scene", None) or scene_module.parse_linkage
    doc = build_preset(name, {})
    result = analysis.analyze(parse(doc))
    for point, (x, y) in doc["points"].items():
        position = result.points[point].position
        assert abs(complex(position[0], position[1]) - complex(x, y)) < 1e-9, point
