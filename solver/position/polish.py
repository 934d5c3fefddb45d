"""A single instant's position polished in 40-digit arithmetic (issue 14).

Newton-Raphson on the full constraint set, q <- q - J(q)^-1 Phi(q): every joint of every loop,
with every moving link but the drivers unknown and each driver's link held at its given turn.
Phi is evaluated with mpmath at 40 digits from the drawn coordinates and the drivers' angles
taken as exact (``angle_deg`` converted to radians and the drawn angle subtracted at 40 digits
too); the step is solved in double, so each step gains about -log10(cond eps) digits near the
root (far from it, next to a change point, it halves the error), until the residual stops
falling. The velocity and acceleration equations J qdot = b_v, J qddot = b_a are then evaluated
at the 40-digit position and solved in double. Where the closed form snapped a dyad to
tangency (its start on the line of centres, where Newton-Raphson stalls), it restarts on either
side and keeps the root on the drawn branches.

Why 40 digits and not the 80-bit long double: next to a change point the position error is
cond x the residual, which the rate equations amplify by cond again; with a residual of
eps_ld = 1e-19 the rates are off by cond^2 x 1e-19 (1e-5 at cond 1e6); and the accelerations
solved at a position rounded to double are off by cond^2 x eps (the rounded pose is that of a
linkage whose lengths differ by eps). Evaluating J and b at the 40-digit pose and rounding them
(not the pose) leaves the rates good to cond x eps, the rounding of one solve (see
docs/CONTINUATION.md, "A single instant at a posed angle").
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any

import mpmath as mp
import numpy as np

from solver.kinematics.rigid import Array, LinkMotion
from solver.model.scene import Driver, LinkageScene
from solver.position.assembly import DriverInput, Motion
from solver.position.constraints import ConstraintSystem, States, solve_linear, states
from solver.position.groups import group_of
from solver.position.groups.base import Where
from solver.position.topology import DyadStep, LeverStep, Plan

DIGITS = 40  # the arithmetic of Phi: a residual of 1e-40 L leaves cond 1e-40 L of position error
CONVERGED = 1e-36  # residual / size: a few roundings at 40 digits, nothing left to gain
STALLED = 1e-30  # residual / size above this: Newton-Raphson did not reach the root
SPREAD = 1e-7  # / size: a restart's offset, above the closed form's sqrt(16 eps) near tangency
MAX_STEPS = 30  # far from the root (a change point) each step halves the error; then 3 suffice


def _exact(x: Array) -> Array:
    """The doubles of ``x`` as 40-digit numbers (exactly: every double is one), an object array."""
    x = np.asarray(x, dtype=float)
    out = np.empty(x.shape, dtype=object)
    out.reshape(-1)[:] = [mp.mpf(v) for v in x.flat]
    return out


def exact_turn(scene: LinkageScene, driver: Driver, time: float, near: float) -> Any:
    """theta_d = radians(angle_deg) - atan2(drawn) + omega t + alpha t^2 / 2 in 40 digits (the
    law's own value for an ``angle_law``), the whole turns chosen nearest the double turn
    ``near`` the closed form used."""
    with mp.workdps(DIGITS):
        if driver.angle_law is not None:
            return mp.mpf(near)
        turn = mp.mpf(0)
        if driver.angle_deg is not None:
            first, second = (scene.drawn(p) for p in scene.links[driver.link].points[:2])
            d = [mp.mpf(second[k]) - mp.mpf(first[k]) for k in (0, 1)]
            turn = mp.radians(mp.mpf(driver.angle_deg)) - mp.atan2(d[1], d[0])
        t = mp.mpf(time)
        turn += mp.mpf(driver.omega) * t + mp.mpf(driver.alpha) * t * t / 2
        return turn + 2 * mp.pi * round(float((near - turn) / (2 * mp.pi)))


def _held(
    scene: LinkageScene, driver: Driver | None, turn: Any, rates: DriverInput | None
) -> States:
    """A driver's link (or the ground: None) at ``turn`` with its given rates, its first point
    in 40 digits: pivot + R(turn) (first - pivot)."""
    link = scene.ground if driver is None else driver.link
    pivot = scene.links[link].points[0] if driver is None else driver.pivot
    pivot0 = _exact(scene.drawn(pivot))
    d = _exact(scene.drawn(scene.links[link].points[0])) - pivot0
    cos, sin = mp.cos(turn), mp.sin(turn)
    c = pivot0 + np.array([cos * d[0] - sin * d[1], sin * d[0] + cos * d[1]], dtype=object)
    r = np.array([-d[1], d[0]], dtype=object)  # k x d, turned below
    r = np.array([cos * r[0] - sin * r[1], sin * r[0] + cos * r[1]], dtype=object)
    omega = mp.mpf(0) if rates is None else mp.mpf(float(rates.omega[0]))
    alpha = mp.mpf(0) if rates is None else mp.mpf(float(rates.alpha[0]))
    # the first point's rates about the pivot: v = omega k x r, a = alpha k x r - omega^2 r
    v = r * omega
    a = r * alpha + np.array([-r[1], r[0]], dtype=object) * (omega * omega)
    return States(
        c[None],
        np.array([turn], dtype=object),
        v[None],
        np.array([omega], dtype=object),
        a[None],
        np.array([alpha], dtype=object),
    )


def polish(
    scene: LinkageScene,
    plan: Plan,
    inputs: Sequence[DriverInput],
    turns: Sequence[Any],
    order: int,
    motion: Motion,
) -> tuple[Motion, float]:
    """The single-sample ``motion`` with its position polished at the drivers' 40-digit
    ``turns`` (rates from ``inputs``) and its rates solved there (J and b evaluated in 40
    digits, rounded, solved in double); and the final residual |Phi| in metres (rounded).

    Where Newton-Raphson stalls (a dyad within rounding of tangency in the closed form, placed
    on its line of centres, where the two assemblies cannot be told apart), it starts again on
    either side along J's null vector and keeps the root on the plan's drawn branches."""
    drivers = [d.link for d in scene.drivers]
    unknown = [name for name in scene.moving_links if name not in drivers]
    if not unknown:
        return motion, 0.0
    with mp.workdps(DIGITS):
        system = ConstraintSystem(scene, unknown, exact=_exact)
        known = {scene.ground: _held(scene, None, mp.mpf(0), None)}
        for driver, turn, given in zip(scene.drivers, turns, inputs, strict=True):
            known[driver.link] = _held(scene, driver, turn, given)
        start = states(motion.links, scene)
        q = _exact(np.concatenate([np.append(start[k].c[0], start[k].theta[0]) for k in unknown]))
        q, J, residual = _newton(system, known, q[None], scene.size)
        gradient_sine = motion.gradient_sine
        drawn = [side for side, _ in _sides(plan, lambda link, p: scene.drawn(p), lambda _: 0)]
        if not residual < STALLED * scene.size and drawn:  # a dyad with two branches stalled
            null = np.linalg.svd(J[0].astype(float))[2][-1]
            for side in (1.0, -1.0):
                found, found_J, found_residual = _newton(
                    system, known, q + side * SPREAD * scene.size * null, scene.size
                )
                at = _sides(plan, *_placing(system, known, found[0]))
                if found_residual < STALLED * scene.size and [s for s, _ in at] == drawn:
                    q, J, residual = found, found_J, found_residual
                    # the closed form's tangency within rounding (gradient_sine 0) is resolved
                    gradient_sine = np.array([min(sine for _, sine in at)])
                    break
        qd = qdd = None
        if order >= 1:
            _, J, b = system.evaluate(known, q, order=1)
            qd = solve_linear(J.astype(float), b.astype(float))
        if order >= 2:
            _, J, b = system.evaluate(known, q, qd, order=2)
            qdd = solve_linear(J.astype(float), b.astype(float))
        links = system.motions(
            q.astype(float),
            None if qd is None else qd.astype(float),
            None if qdd is None else qdd.astype(float),
        )
    return _at(scene, motion, links, gradient_sine), float(residual)


def _newton(
    system: ConstraintSystem, known: dict[str, States], q: Array, size: float
) -> tuple[Array, Array, Any]:
    """q <- q - J^-1 Phi(q) (Phi in 40 digits, the step in double) until the residual stops
    falling or is below CONVERGED x size: (q, J, |Phi|)."""
    phi, J, _ = system.evaluate(known, q)
    residual = mp.sqrt(np.sum(phi * phi))
    for _ in range(MAX_STEPS):
        trial = q - solve_linear(J.astype(float), phi.astype(float))
        trial_phi, trial_J, _ = system.evaluate(known, trial)
        trial_residual = mp.sqrt(np.sum(trial_phi * trial_phi))
        if not trial_residual < residual:
            break
        q, phi, J, residual = trial, trial_phi, trial_J, trial_residual
        if residual < CONVERGED * size:
            break
    return q, J, residual


def _placing(
    system: ConstraintSystem, known: dict[str, States], q: Array
) -> tuple[Where, Callable[[str], Any]]:
    """Where a link's point is, and a link's turn, at the coordinates ``q`` (40 digits)."""

    def pose(link: str) -> tuple[Any, Any, Any]:
        if link in system.column:
            k = system.column[link]
            return q[k], q[k + 1], q[k + 2]
        return known[link].c[0, 0], known[link].c[0, 1], known[link].theta[0]

    def where(link: str, point: str) -> Any:
        x, y, theta = pose(link)
        d = _exact(system.scene.drawn(point)) - _exact(system.anchor0[link])
        cos, sin = mp.cos(theta), mp.sin(theta)
        return np.array([x + cos * d[0] - sin * d[1], y + sin * d[0] + cos * d[1]], dtype=object)

    return where, lambda link: pose(link)[2]


def _sides(plan: Plan, where: Where, turn: Callable[[str], Any]) -> list[tuple[bool, float]]:
    """Each two-branch dyad's branch, the sign of g1 x g2 (its two constraint gradients, asked
    of its group: ``Group.gradients``; it changes sign between the two intersections), and
    |g1 x g2| / |g1| |g2| (the sine between the two gradients, 0 at a tangency)."""

    def turning(link: str) -> tuple[Any, Any]:
        theta = turn(link)
        return mp.cos(theta), mp.sin(theta)

    sides = []
    for step in plan.steps:
        if not isinstance(step, DyadStep | LeverStep):
            continue
        g = group_of(step).gradients(step, where, turning)
        if g is None:
            continue
        cross = g[0][0] * g[1][1] - g[0][1] * g[1][0]
        norms = mp.sqrt((g[0][0] ** 2 + g[0][1] ** 2) * (g[1][0] ** 2 + g[1][1] ** 2))
        sides.append((bool(cross > 0), float(abs(cross) / norms)))
    return sides


def _at(
    scene: LinkageScene, motion: Motion, solved: dict[str, LinkMotion], gradient_sine: Array
) -> Motion:
    """``motion`` with the ``solved`` links and ``gradient_sine``, and every point of a moving
    link placed from its link (the first link listing it)."""
    links = {**motion.links, **solved}
    ground = set(scene.links[scene.ground].points)
    points = dict(motion.points)
    placed: set[str] = set()
    for name in scene.moving_links:
        for p in scene.links[name].points:
            if p not in ground and p not in placed:
                points[p] = links[name].point(scene.drawn(p))
                placed.add(p)
    return dataclasses.replace(motion, links=links, points=points, gradient_sine=gradient_sine)
