"""Newton-Raphson groups.

Sources: the closed-form dyads (a four-bar solved by Newton must equal its RRR solution to
rounding) and central finite differences (a triad, which no dyad can solve).
"""

import math

import numpy as np

from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep
from solver.kinematics.rigid import cross
from solver.model.scene import parse_linkage
from solver.position import continuation
from solver.position.assembly import DriverInput, assemble
from solver.position.topology import (
    NewtonStep,
    build_plan,
)
from solver.teaching.presets import build_preset

TRIAD = {
    "kind": "linkage",
    "points": {"O": [0, 0], "A": [0.3, 0.2], "P1": [1.0, 1.0], "P2": [1.6, 1.2],
               "P3": [1.3, 0.5], "G2": [2.2, 1.9], "G3": [1.8, -0.3]},
    "links": {"ground": {"points": ["O", "G2", "G3"], "ground": True},
              "crank": {"points": ["O", "A"]}, "T": {"points": ["P1", "P2", "P3"]},
              "L1": {"points": ["A", "P1"]}, "L2": {"points": ["G2", "P2"]},
              "L3": {"points": ["G3", "P3"]}},
    "joints": [{"type": "revolute", "point": "O", "links": ["ground", "crank"]},
               {"type": "revolute", "point": "A", "links": ["crank", "L1"]},
               {"type": "revolute", "point": "P1", "links": ["L1", "T"]},
               {"type": "revolute", "point": "P2", "links": ["T", "L2"]},
               {"type": "revolute", "point": "P3", "links": ["T", "L3"]},
               {"type": "revolute", "point": "G2", "links": ["L2", "ground"]},
               {"type": "revolute", "point": "G3", "links": ["L3", "ground"]}],
    "drivers": [{"link": "crank", "omega": 2.0, "alpha": 0.5}],
}  # fmt: skip


def with_angle(doc: dict, degrees: float) -> dict:
    driver = {**doc["drivers"][0], "angle_deg": degrees}
    return {**doc, "drivers": [driver]}


def test_triad_needs_newton_and_reports_it() -> None:
    scene = parse_linkage(TRIAD)
    plan = build_plan(scene)
    assert isinstance(plan.steps[-1], NewtonStep) and not plan.closed_form
    result = analyze(parse_linkage(with_angle(TRIAD, 70.0)))
    (report,) = result.diagnostics.newton
    assert np.all(report.converged)
    assert report.iterations <= 10
    assert report.residual_norm <= 1e-14 * scene.size  # polished to rounding


def test_triad_velocities_and_accelerations_equal_finite_differences() -> None:
    """Central differences in the crank angle (h = 1e-4 deg): truncation ~ h^2 ~ 3e-12, and
    the positions are exact to ~1e-15, so the derivatives agree to ~1e-7 relative."""
    angle = 70.0
    h = 1e-4
    omega, alpha = 2.0, 0.0
    doc = {**TRIAD, "drivers": [{"link": "crank", "omega": omega, "alpha": alpha}]}
    at = {d: analyze(parse_linkage(with_angle(doc, angle + d * h))) for d in (-1, 0, 1)}
    dtheta = math.radians(h)
    for name in ("P1", "P2", "P3"):
        x = [at[d].points[name].position for d in (-1, 0, 1)]
        v = [at[d].points[name].velocity for d in (-1, 0, 1)]
        fd_v = (x[2] - x[0]) / (2 * dtheta) * omega
        fd_a = (v[2] - v[0]) / (2 * dtheta) * omega
        np.testing.assert_allclose(at[0].points[name].velocity, fd_v, rtol=1e-6, atol=1e-8)
        np.testing.assert_allclose(at[0].points[name].acceleration, fd_a, rtol=1e-6, atol=1e-7)


def test_newton_on_a_four_bar_equals_the_closed_form_dyad() -> None:
    """The same coupler and rocker solved by Newton-Raphson and by the RRR dyad."""
    scene = parse_linkage(build_preset("four_bar", {"crank_angle_deg": 50.0, "alpha": 3.0}))
    turns = np.radians(np.linspace(0.0, 90.0, 7))
    inputs = [DriverInput(turns, np.full(7, 8 * math.pi), np.full(7, 3.0))]
    closed = assemble(scene, build_plan(scene), inputs, 2, continuation=True)
    known = {name: closed.links[name] for name in (scene.ground, "crank")}
    solved, report = continuation.solve_group(
        scene, ("coupler", "rocker"), known, [turns], 2, continuation.Continuation(scene)
    )
    assert np.all(report.converged)
    for link in ("coupler", "rocker"):
        np.testing.assert_allclose(solved[link].theta, closed.links[link].theta, atol=1e-12)
        np.testing.assert_allclose(solved[link].omega, closed.links[link].omega, rtol=1e-10)
        np.testing.assert_allclose(solved[link].alpha, closed.links[link].alpha, rtol=1e-9)


def test_triad_sweep_keeps_its_branch() -> None:
    result = sweep(parse_linkage(TRIAD), 40, ["position"])
    P1, P2, P3 = (result.motion.points[n].p for n in ("P1", "P2", "P3"))
    drawn = {n: np.array(TRIAD["points"][n], float) for n in ("P1", "P2", "P3")}
    orientation = np.sign(cross(drawn["P2"] - drawn["P1"], drawn["P3"] - drawn["P1"]))
    assert np.all(np.sign(cross(P2 - P1, P3 - P1)) == orientation)
    np.testing.assert_allclose(
        np.hypot(*(P2 - P1).T), np.hypot(*(drawn["P2"] - drawn["P1"])), rtol=1e-12
    )


def test_newton_without_the_jacobian_takes_the_same_steps() -> None:
    """newton.newton_rotations (Phi by matrix products, the step by (M, U, U) solves in the
    rotations, J never formed) and newton_raphson on the whole group, from the same starts
    (a swept triad's poses, perturbed by up to 2e-2 rad and 2e-2 m): the same iterations, first
    steps (1e-12), residuals and poses (1e-13 m); a polished sample's residual at rounding."""
    from solver.position import constraints, newton

    scene = parse_linkage(TRIAD)
    swept = sweep(scene, 24, ["position"])
    group = ("T", "L1", "L2", "L3")
    system = constraints.ConstraintSystem(scene, group)
    known = constraints.states({name: swept.motion.links[name] for name in system.known}, scene)
    solved = np.concatenate(
        [
            np.stack([*swept.motion.links[g].anchor.p.T, swept.motion.links[g].theta], 1)
            for g in group
        ],
        axis=1,
    )
    rng = np.random.default_rng(5)
    start = solved + rng.uniform(-2e-2, 2e-2, solved.shape)
    tolerance = 1e-13 * scene.size
    whole = newton.newton_raphson(system, known, start, tolerance)
    form, rotations = system.linear, system.rotations(start.shape[0])
    assert form is not None and rotations is not None
    k = form.known_terms(known, start.shape[0], 0, None)[0]
    fast = newton.newton_rotations(form, rotations, k, start, scene.size, tolerance)
    assert fast[2] == whole[2] >= 3
    np.testing.assert_allclose(fast[3], whole[3], rtol=1e-12)
    np.testing.assert_allclose(fast[0], whole[0], rtol=0.0, atol=1e-13)
    np.testing.assert_allclose(fast[0], solved, rtol=0.0, atol=1e-12)
    assert np.all(fast[1] <= 4 * newton.ROUNDING * scene.size)
