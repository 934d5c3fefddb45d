"""The compiled column-form plan (solver.position.compiled_plan) gives the general assembler's
motion bit for bit, and hands back to it wherever the branch search or a failure message is needed.

Bit for bit: every array of the motion (points, links, margins, gradient sine) compared as bytes,
so a last-bit difference or a -0.0 for a 0.0 fails. Independent values of the same quantities
are the general assembler's own tests (tests/solver/position/test_dyads.py, test_assembly.py, the
reference cases); here the claim is only that the compiled plan is the same computation.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from solver.analysis.sweeps import sweep
from solver.model.scene import parse_linkage
from solver.position.assembly import DriverInput, Motion, assemble, coarse, path_steps
from solver.position.compiled_plan import compiled_plan
from solver.position.topology import build_plan
from solver.teaching.presets import build_preset
from tests.dynamics_cases import five_bars
from tests.linkage_strategies import linkages


def arrays(motion: Motion) -> dict[str, Any]:
    """Every array of a motion by a path name (None where not computed)."""
    out: dict[str, Any] = {
        "margin": motion.margin,
        "converged": motion.converged,
        "gradient_sine": motion.gradient_sine,
    }
    for name, p in motion.points.items():
        out |= {f"{name}.p": p.p, f"{name}.v": p.v, f"{name}.a": p.a}
    for name, link in motion.links.items():
        out |= {
            f"{name}.anchor0": link.anchor0,
            f"{name}.anchor.p": link.anchor.p,
            f"{name}.anchor.v": link.anchor.v,
            f"{name}.anchor.a": link.anchor.a,
            f"{name}.theta": link.theta,
            f"{name}.omega": link.omega,
            f"{name}.alpha": link.alpha,
        }
    out |= {f"margin of {k}": m for k, m in motion.group_margins.items()}
    return out


def assert_identical(fast: Motion, general: Motion) -> None:
    mine, theirs = arrays(fast), arrays(general)
    assert list(mine) == list(theirs)  # same points and links, in the same order
    for key, value in theirs.items():
        if value is None:
            assert mine[key] is None, key
            continue
        ours = np.asarray(mine[key])
        assert ours.shape == np.shape(value) and ours.dtype == np.asarray(value).dtype, key
        assert ours.tobytes() == np.ascontiguousarray(value).tobytes(), key
    assert fast.failures == general.failures == [] and fast.approaches == general.approaches
    assert fast.size == general.size


def inputs_for(doc: dict[str, Any], turns: np.ndarray, second: float = 0.0) -> list[DriverInput]:
    """The first driver turned by ``turns``, the others held at ``second``, their rates as
    given."""
    n = turns.size
    out = []
    for k, driver in enumerate(doc["drivers"]):
        theta = turns if k == 0 else np.full(n, second)
        rates = (np.full(n, float(driver.get("omega", 0.0))), np.full(n, driver.get("alpha", 0.0)))
        out.append(DriverInput(theta, *rates))
    return out


def check(doc: dict[str, Any], turns: np.ndarray, keep: int | None = None) -> None:
    scene = parse_linkage(doc)
    plan = build_plan(scene)
    compiled = compiled_plan(scene, plan)
    assert compiled is not None
    inputs = inputs_for(doc, turns)
    for order in (0, 1, 2):
        fast = compiled.run(inputs, order, keep)
        general = assemble(scene, plan, inputs, order, continuation=True)
        if fast is None:  # the general assembler had to decide: a failure, a close approach,
            # or a step too long to follow as it is
            assert general.failures or general.approaches or coarse(path_steps(inputs))
            continue
        if keep is not None:
            general = general.cut(slice(0, keep))
        assert_identical(fast, general)


def turns_with_the_drawn_pose(samples: int, start: float) -> np.ndarray:
    """A revolution from ``start`` with one sample at exactly 0 (the drawn pose)."""
    turns = start + 2.0 * math.pi * np.arange(samples) / samples
    turns[samples // 3] = 0.0
    return turns


@pytest.mark.slow
@settings(max_examples=12, deadline=None)
@given(linkages("four_bar"), st.floats(-math.pi, math.pi), st.sampled_from([7, 36, 361]))
def test_four_bars_bit_for_bit(doc: dict[str, Any], start: float, samples: int) -> None:
    check(doc, turns_with_the_drawn_pose(samples, start), keep=samples - 1)


@settings(max_examples=8, deadline=None)
@given(linkages("six_bar", newton=False), st.floats(-0.3, 0.3))
def test_six_bars_by_dyads_bit_for_bit(doc: dict[str, Any], start: float) -> None:
    """Watt and Stephenson six-bars: dyads on moving centres, ternary links carrying points."""
    scene = parse_linkage(doc)
    if compiled_plan(scene, build_plan(scene)) is None:  # a dyad of two fixed centres
        return
    turns = start + np.linspace(-0.05, 0.05, 41)  # near the drawn pose, which closes
    check(doc, turns)


@settings(max_examples=8, deadline=None)
@given(five_bars(), st.floats(-0.2, 0.2))
def test_two_drivers_bit_for_bit(doc: dict[str, Any], second: float) -> None:
    scene = parse_linkage(doc)
    plan = build_plan(scene)
    compiled = compiled_plan(scene, plan)
    assert compiled is not None
    turns = np.linspace(-0.05, 0.05, 21)
    for order in (0, 1, 2):
        inputs = inputs_for(doc, turns, second)
        fast = compiled.run(inputs, order)
        if fast is not None:  # it closes everywhere
            assert_identical(fast, assemble(scene, plan, inputs, order, continuation=True))


def test_signed_zeros_at_rest_and_on_the_axes() -> None:
    """A crank at rest (every rate a signed zero) drawn along the axes, the ground at -0.0."""
    doc = build_preset("four_bar", {"omega": 0.0, "alpha": 0.0, "crank_angle_deg": 90.0})
    doc["points"]["A"] = [-0.0, -0.0]
    doc["drivers"][0]["omega"] = 0.0
    turns = math.pi / 2.0 * np.arange(4)
    check(doc, turns)
    doc["drivers"][0]["omega"] = -0.0
    check(doc, turns)


def test_hands_back_near_a_change_point_and_where_it_cannot_close() -> None:
    """1e-9 from a change point the branch search must look: None, and the sweep is the general
    assembler's (it keeps the branch; test_assembly.py); a non-Grashof linkage that
    cannot turn fully: None too."""
    near = {"ground": 1.0, "crank": 0.4, "coupler": 0.9, "rocker": 0.5 + 1e-9}
    for values in (near, {"ground": 1.0, "crank": 0.8, "coupler": 0.5, "rocker": 0.6}):
        doc = build_preset("four_bar", {**values, "crank_angle_deg": 30.0})
        scene = parse_linkage(doc)
        compiled = compiled_plan(scene, build_plan(scene))
        assert compiled is not None
        turns = 2.0 * math.pi * np.arange(361) / 360
        assert compiled.run(inputs_for(doc, turns), 2) is None
    assert sweep(parse_linkage(doc), 360).feasible is False


@pytest.mark.parametrize("preset", ["slider_crank", "inverted_slider_crank", "quick_return"])
def test_slots_and_levers_are_not_compiled(preset: str) -> None:
    scene = parse_linkage(build_preset(preset, {}))
    assert compiled_plan(scene, build_plan(scene)) is None


@pytest.mark.slow
def test_compiled_once_per_scene_object_forgotten_with_it() -> None:
    import gc
    import weakref

    scene = parse_linkage(build_preset("four_bar", {}))
    plan = build_plan(scene)
    compiled = compiled_plan(scene, plan)
    assert compiled is not None and compiled_plan(scene, plan) is compiled
    kept = weakref.ref(compiled)
    del scene, plan, compiled
    gc.collect()
    assert kept() is None
