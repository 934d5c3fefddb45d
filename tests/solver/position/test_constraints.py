"""The constraint equations (solver.position.constraints): the condition number of the velocity
equations is dimensionless (scale invariant), and the rates the solver reports satisfy the
differentiated loop equations J qdot = b_v, J qddot = b_a.
"""

import copy

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solver.analysis.instant import analyze
from solver.errors import KinematicsError
from solver.model.scene import parse_linkage
from solver.position.constraints import (
    ConstraintSystem,
    KnownPoses,
    States,
    velocity_condition_number,
    velocity_jacobian,
)
from solver.solutions import solve
from solver.teaching.presets import build_preset
from tests.linkage_strategies import linkages
from tests.solver.position.test_newton import TRIAD, with_angle

FAMILIES = (
    "four_bar", "slider_crank", "inverted_slider_crank", "quick_return",
    "slider_guide_extension", "block_in_lever", "six_bar",
)  # fmt: skip


def test_velocity_condition_number_is_scale_invariant() -> None:
    base = build_preset("four_bar", {"crank_angle_deg": 40.0})
    scaled = {**base, "points": {k: [1e3 * c for c in v] for k, v in base["points"].items()}}
    c1 = analyze(parse_linkage(base)).diagnostics.condition_number
    c2 = analyze(parse_linkage(scaled)).diagnostics.condition_number
    assert c1 is not None and c2 is not None
    assert c2 == pytest.approx(c1, rel=1e-9)


@pytest.mark.slow
@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(st.sampled_from(FAMILIES).flatmap(linkages), st.floats(-180.0, 180.0))
def test_velocity_jacobian_is_the_constraint_systems(doc: dict[str, object], turn: float) -> None:
    """The velocity system's J built at one pose (``velocity_jacobian``, the condition number's)
    equals ``ConstraintSystem(scene, moving links, drivers=True)``'s, entry by entry to 1e-15
    of its largest entry (its ``LinearForm``'s products round otherwise), and bit for bit
    joint by joint (the same row functions), and so do the rows that are lengths: every preset
    family, the block in a slotted lever (prismatic) and six-bars, the driver turned away from
    the drawn pose. The condition number is numpy's cond of that J scaled (rel 1e-12 cond:
    entries that differ by rounding move the smallest singular value by about 1e-15 cond of
    itself)."""
    drivers = doc["drivers"]
    assert isinstance(drivers, list)
    drivers[0]["angle_deg"] = turn
    scene = parse_linkage(doc)
    try:
        motion = analyze(scene, ["position"]).motion
    except KinematicsError:  # the turned linkage does not close
        return
    J, lengths = velocity_jacobian(scene, motion.links, 0)
    system = ConstraintSystem(scene, scene.moving_links, drivers=True)
    _, expected, _ = system.equations(KnownPoses(motion.links, scene).at(0), 0)
    np.testing.assert_allclose(J, expected, rtol=0.0, atol=1e-15 * np.max(np.abs(expected)))
    assert np.array_equal(lengths, system.length_rows)
    general = copy.copy(system)
    general.linear = None  # joint by joint
    assert np.array_equal(J, general.equations(KnownPoses(motion.links, scene).at(0), 0)[1])
    # cond of that J, rotation columns over the size and angle rows times it: numpy's 2-norm cond
    expected[:, 2::3] /= scene.size
    expected[~system.length_rows] *= scene.size
    condition = velocity_condition_number(scene, motion.links, 0)
    assert condition == pytest.approx(np.linalg.cond(expected), rel=1e-12 * max(condition, 1.0))


def test_triad_rates_satisfy_the_differentiated_loop_equations() -> None:
    """J qdot = b_v and J qddot = b_a hold for the rates the solver reports (residual relative
    to |b| below 1e-12), and the worked solution writes that system out with those numbers."""
    scene = parse_linkage(with_angle(TRIAD, 70.0))
    result = analyze(scene)
    group = ("T", "L1", "L2", "L3")
    system = ConstraintSystem(scene, group)
    poses = KnownPoses(result.motion.links, scene).at(0)
    for order in (1, 2):
        _, J, b = system.equations(poses, order)
        q = np.concatenate([
            np.append(poses[link].v if order == 1 else poses[link].a,
                      poses[link].omega if order == 1 else poses[link].alpha)
            for link in group
        ])  # fmt: skip
        assert np.linalg.norm(J @ q - b) <= 1e-12 * max(1.0, np.linalg.norm(b))
    solution = solve(scene, "vector", 4)
    newton_steps = [
        s for s in solution.steps if s.kind in ("velocity.newton", "acceleration.newton")
    ]
    assert len(newton_steps) == 2  # velocities and accelerations
    for step in newton_steps:
        assert r"\begin{bmatrix}" in step.latex and "matrix system" in step.text
    omega_T = f"{result.links['T'].omega:.4g}"
    assert omega_T in newton_steps[0].latex


def _random_states(rng: np.random.Generator, samples: int) -> States:
    return States(
        rng.normal(size=(samples, 2)), rng.normal(size=samples), rng.normal(size=(samples, 2)),
        rng.normal(size=samples), rng.normal(size=(samples, 2)), rng.normal(size=samples),
    )  # fmt: skip


@pytest.mark.parametrize("case", ["group", "held angles", "velocity system"])
def test_linear_form_equals_the_joint_by_joint_equations(case: str) -> None:
    """Phi, J and b by the matrix products of LinearForm equal those written joint by joint
    (the general evaluation, also used for sliders and 40 digits) at random poses and rates of
    every link, to 1e-13 of their size."""
    scene = parse_linkage(TRIAD)
    system = {
        "group": ConstraintSystem(scene, ("T", "L1", "L2", "L3")),
        "held angles": ConstraintSystem(scene, scene.moving_links, angles=("crank",)),
        "velocity system": ConstraintSystem(scene, scene.moving_links, drivers=True),
    }[case]
    assert system.linear is not None
    general = copy.copy(system)
    general.linear = None
    rng = np.random.default_rng(7)
    samples = 5
    known = {name: _random_states(rng, samples) for name in system.known}
    q, qd = rng.normal(size=(2, samples, system.n))
    turns = rng.normal(size=(samples, len(system.angles)))
    for order in (0, 1, 2):
        fast = system.evaluate(known, q, qd, order, turns)
        slow = general.evaluate(known, q, qd, order, turns)
        for name, a, b in zip(("Phi", "J", "b"), fast, slow, strict=True):
            assert np.any(b != 0.0) or (name == "b" and order == 0), name
            np.testing.assert_allclose(a, b, rtol=0.0, atol=1e-13 * max(np.max(np.abs(b)), 1.0))


def test_sliders_and_40_digits_keep_the_joint_by_joint_equations() -> None:
    """A slider's row is not linear in (q, cos, sin): no LinearForm; nor in exact arithmetic."""
    slider = parse_linkage(build_preset("slider_crank", {}))
    assert ConstraintSystem(slider, slider.moving_links).linear is None
    triad = parse_linkage(TRIAD)
    exact = ConstraintSystem(triad, triad.moving_links, exact=lambda x: np.asarray(x, dtype=object))
    assert exact.linear is None


def test_solve_with_the_translations_eliminated_equals_lu() -> None:
    """J x = b solved as an (M, U, U) system in the rotations, then the translations by A^+,
    equals numpy's LU on the whole (M, n, n) J at random poses (to 1e-12 of |x| where
    cond(J) < 1e4); a system with one more unknown than rows (the path's, the crank's angle
    free) has the reduction but is not square, and is solved by least squares."""
    scene = parse_linkage(TRIAD)
    system = ConstraintSystem(scene, ("T", "L1", "L2", "L3"))
    assert system.linear is not None and system.linear.rotations is not None
    rng = np.random.default_rng(3)
    samples = 40
    known = {name: _random_states(rng, samples) for name in system.known}
    q, b = rng.normal(size=(2, samples, system.n))
    _, J, _ = system.evaluate(known, q)
    x = system.solve(J, b)
    lu = np.linalg.solve(J, b[..., None])[..., 0]
    well = np.linalg.cond(J) < 1e4
    assert np.sum(well) >= 10
    for k in np.flatnonzero(well):
        np.testing.assert_allclose(x[k], lu[k], rtol=0.0, atol=1e-12 * np.linalg.norm(lu[k]))
    path = ConstraintSystem(scene, scene.moving_links)  # the crank's angle free: 14 x 15
    assert path.linear is not None and path.linear.rotations is not None
    assert not path.linear.rotations.square and path.rotations(1) is None


@pytest.mark.parametrize("case", ["group", "held angles"])
def test_the_rotations_alone_equal_the_projected_loop_equations(case: str) -> None:
    """constraints.Rotations at random poses: G(theta) = Q^T Phi(c, theta) for any c (Q^T A = 0
    to rounding), dG/dtheta = Q^T J_theta (and a central difference of G, to 1e-7), the
    translations c = -A^+ (...) leave |Phi| = |G| (least squares), and x = rates(J, b) solves
    the whole J x = b (LU, 1e-12 of |x| where cond(J) < 1e4; square systems only). With held
    angles (the path of a two-driver linkage) the angle rows enter G through K_theta."""
    scene = parse_linkage(TRIAD)
    unknown = ("T", "L1", "L2", "L3") if case == "group" else scene.moving_links
    system = ConstraintSystem(scene, unknown, angles=("crank",) if case != "group" else ())
    form = system.linear
    assert form is not None and form.rotations is not None
    rotations = form.rotations
    assert rotations.held == (case != "group") and rotations.square
    rng = np.random.default_rng(11)
    samples = 30
    known = {name: _random_states(rng, samples) for name in system.known}
    q = rng.normal(size=(samples, system.n))
    turns = rng.normal(size=(samples, len(system.angles)))
    k = form.known_terms(known, samples, 0, turns)[0]
    phi, J, _ = system.evaluate(known, q, turns=turns)
    theta = q[:, 2::3]
    G, dG = rotations.pose(theta, rotations.fixed(k))
    np.testing.assert_allclose(G, phi @ rotations.Q, rtol=0.0, atol=1e-13)
    np.testing.assert_allclose(dG, rotations.jacobian(theta), rtol=0.0, atol=1e-15)
    np.testing.assert_allclose(dG, rotations.Q.T @ J[..., 2::3], rtol=0.0, atol=1e-13)
    h = 1e-6
    for u in range(theta.shape[1]):
        step = np.zeros_like(theta)
        step[:, u] = h
        fd = (
            rotations.pose(theta + step, rotations.fixed(k))[0]
            - rotations.pose(theta - step, rotations.fixed(k))[0]
        ) / (2 * h)
        np.testing.assert_allclose(fd, dG[..., u], rtol=0.0, atol=1e-7)
    c = rotations.translations(theta, k)
    closed = rotations.assemble(theta, c)
    np.testing.assert_allclose(closed[:, 2::3], theta, rtol=0.0, atol=0.0)
    least = form.residual(closed, k)
    np.testing.assert_allclose(np.linalg.norm(least, axis=1), np.linalg.norm(G, axis=1), rtol=1e-9)
    b = rng.normal(size=phi.shape)
    x = rotations.rates(theta, dG, b)
    lu = np.linalg.solve(J, b[..., None])[..., 0]
    well = np.linalg.cond(J) < 1e4
    assert np.sum(well) >= 10
    for m in np.flatnonzero(well):
        np.testing.assert_allclose(x[m], lu[m], rtol=0.0, atol=1e-12 * np.linalg.norm(lu[m]))
