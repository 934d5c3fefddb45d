"""The worked solutions in the textbook's form.

The classification step of the slider mechanisms: slider-crank, offset slider-crank,
inverted slider-crank and quick-return, for every seed example and preset of those kinds.
Its stroke, time ratio and slow stroke are checked against the sweep's ram extremes
(``Sweep.strokes``, refined to rounding: tolerance 1e-9 relative), its lever swing and time
ratio against the lever's angle sampled over a turn (tolerance 1e-4 rad: 20000 samples of a
smooth curve near its extremes), and the formulas against their closed forms. The loop method's
Freudenstein equation against its closed-form coefficients."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import sympy

from solver.analysis.sweeps import sweep
from solver.kinematics.dead_centres import (
    crank_turns_fully,
    quick_return_ratio,
    slider_crank_dead_centres,
    slotted_lever_dead_centres,
)
from solver.model.scene import LinkageScene, parse_linkage
from solver.solutions import Step, solve
from solver.solutions import latex as tex
from solver.teaching.presets import build_preset

EXAMPLES = Path(__file__).resolve().parents[3] / "server" / "examples"
SEEDS = ("S000-T2", "S000-T3", "S000-T4", "S001-offset-slider-crank")
PRESETS = ("slider_crank", "quick_return", "inverted_slider_crank", "slider_guide_extension")


def _scene(name: str) -> LinkageScene:
    doc: dict[str, Any] = (
        json.loads((EXAMPLES / f"{name}.json").read_text())
        if name in SEEDS
        else build_preset(name, {})
    )
    return parse_linkage(doc)


def _steps(scene: LinkageScene) -> list[Step]:
    return [
        s
        for s in solve(scene, "vector").steps
        if s.kind == "classification" and "four-bar" not in s.title
    ]


@pytest.mark.parametrize("name", SEEDS + PRESETS)
def test_every_slider_mechanism_is_classified(name: str) -> None:
    assert len(_steps(_scene(name))) == 1


@pytest.mark.parametrize("name", ["S000-T4", "S001-offset-slider-crank", "slider_crank"])
def test_slider_crank_stroke_and_time_ratio_match_the_sweep(name: str) -> None:
    scene = _scene(name)
    (step,) = _steps(scene)
    strokes = sweep(scene, 720).strokes
    (found,) = [s for s in strokes.values() if s is not None]
    stroke = abs(found.displacements[0] - found.displacements[1])
    assert step.values["stroke"].value == pytest.approx(stroke, rel=1e-9)
    assert step.values["time ratio"].value == pytest.approx(found.time_ratio, rel=1e-9)
    assert step.values["slow stroke"].value == pytest.approx(found.slow_stroke, rel=1e-9)


def test_quick_return_stroke_and_time_ratio_match_the_sweep() -> None:
    scene = _scene("quick_return")
    (step,) = _steps(scene)
    found = sweep(scene, 720).strokes["C"]
    assert found is not None
    stroke = abs(found.displacements[0] - found.displacements[1])
    assert step.values["stroke"].value == pytest.approx(stroke, rel=1e-9)
    assert step.values["time ratio"].value == pytest.approx(found.time_ratio, rel=1e-9)
    assert step.values["slow stroke"].value == pytest.approx(found.slow_stroke, rel=1e-9)


def test_inverted_slider_crank_swing_and_time_ratio_by_sampling_the_lever() -> None:
    """The lever's angle psi(theta) = angle of A(theta) - C (slot through C), sampled over a
    turn of the crank: its range is the swing, the crank's turn between its extremes the
    strokes."""
    scene = _scene("inverted_slider_crank")
    (step,) = _steps(scene)
    o, c, a = (np.array(scene.points[p]) for p in ("O", "C", "A"))
    r = float(np.hypot(*(a - o)))
    theta = np.linspace(0.0, 2.0 * math.pi, 20001)
    pins = o + r * np.stack([np.cos(theta), np.sin(theta)], axis=1)
    psi = np.unwrap(np.arctan2(pins[:, 1] - c[1], pins[:, 0] - c[0]))
    assert step.values["swing"].value == pytest.approx(float(np.ptp(psi)), abs=1e-4)
    turn = abs(theta[int(np.argmax(psi))] - theta[int(np.argmin(psi))])
    slow, fast = max(turn, 2 * math.pi - turn), min(turn, 2 * math.pi - turn)
    assert step.values["time ratio"].value == pytest.approx(slow / fast, abs=1e-3)


def test_a_crank_that_cannot_turn_fully_gets_no_stroke() -> None:
    """Seed 000 Task 3: r + |e| = 0.54 m >= l = 0.5 m."""
    (step,) = _steps(_scene("S000-T3"))
    assert "stroke" not in step.values and "does not turn fully" not in step.text
    assert "rocks between two limit positions" in step.text


def test_dead_centre_closed_forms() -> None:
    """Centred slider-crank: stroke 2 r, ratio 1, mu_min = acos(r / l); the offset one's a from
    its two crank angles; slotted lever r/d = 1/2: swing 60 deg, ratio 240/120 = 2."""
    centred = slider_crank_dead_centres(0.1, 0.4, 0.0)
    assert centred.stroke == pytest.approx(0.2, rel=1e-15)
    assert centred.time_ratio == 1.0 and centred.mu_min == pytest.approx(math.acos(0.25))
    offset = slider_crank_dead_centres(0.1, 0.35, 0.05)
    assert offset.theta_near - offset.theta_far == pytest.approx(math.pi + offset.advance)
    assert offset.time_ratio == pytest.approx(quick_return_ratio(offset.advance))
    assert not crank_turns_fully(0.2, 0.5, 0.34) and crank_turns_fully(0.2, 0.5, 0.29)
    lever = slotted_lever_dead_centres(0.15, 0.3)
    assert math.degrees(lever.swing) == pytest.approx(60.0)
    assert lever.time_ratio == pytest.approx(2.0)
    with pytest.raises(ValueError):
        slider_crank_dead_centres(0.2, 0.5, 0.34)


@pytest.mark.parametrize("name", ["S000-T1", "four_bar"])
def test_the_loop_method_writes_freudensteins_equation(name: str) -> None:
    """K1 = a1/a2, K2 = a1/a4, K3 = (a2^2 - a3^2 + a4^2 + a1^2)/(2 a2 a4) from the link lengths,
    and K1 cos phi4 - K2 cos phi2 + K3 = cos(phi2 - phi4) at the solved pose (1e-12): the phase
    form A cos + B sin = C divided by 2 a2 a4."""
    doc = (
        json.loads((EXAMPLES / f"{name}.json").read_text())
        if name.startswith("S")
        else build_preset(name, {})
    )
    (step,) = [
        s
        for s in solve(parse_linkage(doc), "loop").steps
        if s.kind == "position.loop" and "K1" in s.values
    ]
    a1, a2, a3, a4 = (step.values[f"a{n}"].value for n in (1, 2, 3, 4))
    assert step.values["K1"].value == pytest.approx(a1 / a2, rel=1e-14)
    assert step.values["K2"].value == pytest.approx(a1 / a4, rel=1e-14)
    k3 = (a2**2 - a3**2 + a4**2 + a1**2) / (2 * a2 * a4)
    assert step.values["K3"].value == pytest.approx(k3, rel=1e-14)
    left, right = step.values["Freudenstein: left"].value, step.values["Freudenstein: right"].value
    assert left == pytest.approx(right, abs=1e-12)
    assert r"\text{Freudenstein: }" in step.latex and "A\\cos" in step.latex


@pytest.mark.parametrize("name", ["S000-T1", "S000-T2", "S000-T4", "S001-offset-slider-crank"])
def test_the_loop_equations_come_in_symbols_before_the_numbers(name: str) -> None:
    """The loop closure and its real and imaginary parts in general symbols (no number in
    them), before the line with the numbers."""
    doc = json.loads((EXAMPLES / f"{name}.json").read_text())
    loop = next(s for s in solve(parse_linkage(doc), "loop").steps if s.kind == "loop.position")
    lines = loop.latex.split(r" \\ ")
    assert lines[1].startswith(r"&\text{Re: }") and lines[2].startswith(r"&\text{Im: }")
    for line in lines[:3]:  # digits only in subscripts: symbols, no numbers
        assert not re.search(r"\d", re.sub(r"_\{[^}]*\}", "", line)), line
    assert r"\text{both sides}" in lines[-1].removesuffix(r" \end{aligned}")


def _seed_solutions() -> list[tuple[str, Step]]:
    out = []
    for path in sorted(EXAMPLES.glob("S00[0-13]*.json")):
        scene = parse_linkage(json.loads(path.read_text()))
        for method in ("vector", "loop"):
            out += [(f"{path.stem}-{method}", s) for s in solve(scene, method).steps]
    return out


def test_notation_a_lecturer_would_correct() -> None:
    """Issue 29's list, over every planar seed solution in both methods: no 'The carrier
    carrier', no 'same sense' reading of a zero dot product, no 'a/-b', no number of 15 or more
    digits (a law printed as 0.23561944901923448*t)."""
    for name, step in _seed_solutions():
        both = step.text + " " + step.latex
        assert "carrier carrier" not in both, (name, step.title)
        assert not re.search(r"= -?0(\s\S+)?: the same sense", step.text), (name, step.title)
        assert not re.search(r"\d/-\d", step.text), (name, step.title)
        assert not re.search(r"\d{15,}", both), (name, step.title)


def test_laws_print_as_typed_or_as_exact_multiples_of_pi() -> None:
    """Seed 003 Task 2: s(t) = 75 pi (0.1 t + 0.3 t^2) cm typed in metres as
    0.23561944901923448*t + 0.7068583470577035*t^2 is 3 pi t/40 + 9 pi t^2/40; a plain decimal
    stays as typed."""
    law = sympy.sympify("0.23561944901923448*t + 0.7068583470577035*t**2")
    t = sympy.Symbol("t")
    assert tex.exact_pi(law) == 3 * sympy.pi * t / 40 + 9 * sympy.pi * t**2 / 40
    assert tex.law_text("2.0*t + -0.3*t^2", sympy.sympify("2.0*t - 0.3*t**2")) == (
        "2.0*t + -0.3*t^2"
    )
    assert tex.exact_pi(sympy.sympify("1.23456789*t")) == sympy.sympify("1.23456789*t")
    (law_step,) = [
        s
        for n, s in _seed_solutions()
        if n == "S003-T2-rotating-carrier-vector" and s.kind == "relative.law"
    ]
    assert "s(t) = 9*pi*t^2/40 + 3*pi*t/40 (m)" in law_step.text


def test_a_negative_denominator_is_put_in_parentheses() -> None:
    """Seed 000 Task 3's instant centre P13: t = 0.32/(-0.18), not 0.32/-0.18."""
    (step,) = [
        s for n, s in _seed_solutions() if n == "S000-T3-vector" and s.kind == "instant_centres"
    ]
    assert "t = 0.32/(-0.18)" in step.text


def test_a_velocity_written_as_a_complex_number_keeps_both_parts() -> None:
    """Seed 001, loop method: v_B = (-0.9186 + 0 i) m/s, a vector, not '= -0.9186 m/s'."""
    doc = json.loads((EXAMPLES / "S001-offset-slider-crank.json").read_text())
    (step,) = [
        s
        for s in solve(parse_linkage(doc), "loop").steps
        if s.kind == "loop.velocity.point" and "of B " in s.title
    ]
    assert r"\underline{\underline{(-0.9186 + 0\,i)\,\mathrm{m/s}}}" in step.latex


def test_a_point_named_after_a_greek_letter_is_that_letter() -> None:
    """Seed 004's pivot 'Gamma' is \\Gamma in every formula, never the word."""
    assert tex.name("Gamma") == r"\Gamma{}" and tex.name("omega1") == r"\omega{}1"
    assert tex.name("A0") == "A0" and tex.name("crank") == r"\text{crank}"
    for step in solve(parse_linkage(build_preset("seed004", {})), "vector").steps:
        assert r"\text{Gamma}" not in step.latex and "Gamma" not in step.latex.replace(
            r"\Gamma{}", ""
        ), step.title


@pytest.mark.parametrize(
    ("name", "coriolis"),
    [("S000-T1", False), ("S000-T2", True), ("S003-T1-translating-carrier", False),
     ("S003-T2-rotating-carrier", True)],
)  # fmt: skip
def test_the_acceleration_polygon_tabulates_its_parts_at_scale(name: str, coriolis: bool) -> None:
    """Every part drawn (normal omega^2 r, tangential alpha r, transport, Coriolis, relative)
    with its length on paper, |part| / k_a (1e-12 relative); the Coriolis part only where the
    guide turns."""
    doc = json.loads((EXAMPLES / f"{name}.json").read_text())
    (step,) = [
        s for s in solve(parse_linkage(doc), "vector").steps if s.kind == "graphical.acceleration"
    ]
    scale = step.values["k_a"].value
    parts = [k.removeprefix("length ") for k in step.values if k.startswith("length a")]
    parts = [p for p in parts if ":" in p or p.startswith("a_")]  # drawn parts, not images
    assert any(p.startswith("an(") for p in parts) and any(p.startswith("at(") for p in parts)
    assert any(p.startswith("a_cor(") for p in parts) == coriolis
    for part in parts:
        length = step.values[f"length {part}"].value
        assert length == pytest.approx(step.values[f"|{part}|"].value / scale, rel=1e-12)
    assert "in the order drawn" in step.text


@pytest.mark.parametrize(
    ("name", "expected"),
    [("S000-T2", True), ("S003-T2-rotating-carrier", False), ("S000-T1", False)],
)
def test_the_rounding_mistake_only_where_the_data_can_be_rounded(name: str, expected: bool) -> None:
    """The data are the drawn coordinates: seed 000 Task 2's x = sqrt(0.12) m rounds to another
    ground; seed 003 Task 2's plate, exact in its data, has only turned by t = 1 s (the issue's
    |PQ| = 0.3025 m), so no rounding mistake there; the note keeps ground and crank apart."""
    doc = json.loads((EXAMPLES / f"{name}.json").read_text())
    found = [m for m in solve(parse_linkage(doc), "vector").mistakes if m.kind == "inputs.rounding"]
    assert bool(found) == expected
    for m in found:
        assert "link ground: |CA| becomes 0.35 m instead of 0.3464 m" in m.text


@pytest.mark.parametrize("name", SEEDS + PRESETS)
def test_the_classification_angles_are_values_of_the_step_written_once(name: str) -> None:
    """Every angle the slider classification shows in degrees is a value of the step (unit
    'deg', 180/pi times its radians by a ``product`` check), and the LaTeX and the text show that
    value's digits: the number with a degree sign in the LaTeX, its display ('12.34 deg') in
    the text. A crank that turns fully shows a (or the lever's theta and swing) this way."""
    (step,) = _steps(_scene(name))
    degrees = {k: v for k, v in step.values.items() if v.unit == "deg"}
    if "stroke" not in step.values and "swing" not in step.values:
        assert not degrees  # S000-T3: the crank rocks, no angles to show
        return
    assert degrees
    checked = {c.result.ref.key: c for c in step.checks if c.relation == "product"}
    for key, value in degrees.items():
        check = checked[key]
        (radians,) = check.operands
        assert step.values[radians.ref.key].unit == "rad"
        assert value.value == pytest.approx(math.degrees(step.values[radians.ref.key].value))
        assert check.factor == pytest.approx(180 / math.pi)
        assert value.display in step.text, (key, value.display)
        number = value.display.removesuffix(" deg")
        assert number + r"{}^{\circ}" in step.latex, (key, number)


def _group(text: str, at: int) -> tuple[str, int]:
    """The brace group opening at ``text[at]`` ('{'): its inside and the index after it."""
    depth = 0
    for i in range(at, len(text)):
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        if depth == 0:
            return text[at + 1 : i], i + 1
    raise AssertionError("unbalanced braces")


def underbraces(latex: str) -> list[tuple[str, str]]:
    """(inside, label) of every \\underbrace{inside}_{label}."""
    out = []
    for found in re.finditer(r"\\underbrace\{", latex):
        inside, after = _group(latex, found.end() - 1)
        assert latex[after] == "_"
        label, _ = _group(latex, after + 1)
        out.append((inside, label))
    return out


def test_the_lever_pins_acceleration_labels_each_part_it_adds() -> None:
    """Seed 000 Task 2, the pin B in the guide's slot: a_B = a_tr + a_rel + a_Cor, then each
    group of terms under a brace naming its part (the transport part's three terms, s-double-dot
    u the relative part, the Coriolis column the Coriolis part), never a definition of a_tr
    followed by a line that reads as its continuation; omega^2 = (-2)^2 = 4 on a line before
    them, and 4 times r in the transport part."""
    doc = json.loads((EXAMPLES / "S000-T2.json").read_text())
    (step,) = [
        s for s in solve(parse_linkage(doc), "vector").steps if s.kind == "acceleration.lever.side"
    ]
    lines = step.latex.split(r"\\")
    assert not any(r"\quad \vec{a}_{B,\mathrm{tr}} =" in line for line in lines)
    omega2 = r"&\omega_{\text{guide}}^2 = (-2)^2 = 4\,\mathrm{1/s^{2}}"
    assert lines[0].strip() == r"\begin{aligned} " + omega2
    assert lines[1].strip().startswith(r"&\vec{a}_{B} = \vec{a}_{B,\mathrm{tr}} +")
    braces = underbraces(step.latex)
    parts: dict[str, list[str]] = {}
    for inside, label in braces:
        parts.setdefault(label, []).append(inside)
    tr, rel, cor = (rf"\vec{{a}}_{{B,\mathrm{{{p}}}}}" for p in ("tr", "rel", "Cor"))
    assert set(parts) == {tr, rel, cor} and all(len(v) == 2 for v in parts.values())
    assert all(r"\ddot{s}_{B}" in inside for inside in parts[rel])
    assert r"\times \vec{v}_{B,\mathrm{rel}}" in parts[cor][0]
    shown = step.values["a_cor(B)"].display.removesuffix(" m/s^2").strip("()").split(", ")
    assert all(number in parts[cor][1] for number in shown)
    assert r"\omega_{\text{guide}}^2" in parts[tr][0] and r"- 4 \cdot" in parts[tr][1]


def test_the_lever_pins_velocity_labels_each_part_it_adds() -> None:
    """Seed 000 Task 2, the pin B: v_B = v_tr + v_rel, then v_A + omega x r_AB under a brace
    naming the transport part and s-dot u under one naming the relative part, in symbols and
    again with the numbers, so s-dot u never reads as a term of v_tr."""
    doc = json.loads((EXAMPLES / "S000-T2.json").read_text())
    (step,) = [
        s for s in solve(parse_linkage(doc), "vector").steps if s.kind == "velocity.lever.side"
    ]
    lines = step.latex.split(r"\\")
    first = r"\begin{aligned} &\vec{v}_{B} = \vec{v}_{B,\mathrm{tr}} + \vec{v}_{B,\mathrm{rel}},"
    assert lines[0].strip().startswith(first)
    assert not any(r"\mathrm{rel}} = \vec{v}_{A}" in line for line in lines)
    parts: dict[str, list[str]] = {}
    for inside, label in underbraces(step.latex):
        parts.setdefault(label, []).append(inside)
    tr, rel = (rf"\vec{{v}}_{{B,\mathrm{{{p}}}}}" for p in ("tr", "rel"))
    assert set(parts) == {tr, rel} and all(len(v) == 2 for v in parts.values())
    assert parts[tr][0] == r"\vec{v}_{A} + \vec{\omega}_{\text{guide}} \times \vec{r}_{AB}"
    assert r"\omega_{\text{guide}}" in parts[tr][1] and r"\dot{s}_{B}" not in parts[tr][1]
    assert all(inside.startswith(r"\dot{s}_{B}") for inside in parts[rel])
