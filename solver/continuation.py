"""Newton groups along a sweep: the branch followed from the drawn pose, then every sample at once.

**The branch rule.** The pose of a linkage with a Newton group at a driver turn t (the rotation of
the first driver from its drawn pose) is the end of the path that starts at the drawn pose and
turns the driver from 0 to t, the linkage's configuration moving continuously. Where a limit
position stops that path before t, the driver is turned the other way round instead, to
t - 2 pi sign(t). Other drivers are first turned, one after the other, from 0 to their given
turns with the first held at 0. A sweep and a single instant apply the same rule, so /analyze at
a swept angle returns the swept pose.

**Following the path** (``Branch``): pseudo-arclength continuation on the whole linkage's loop
equations F(x) = 0 (every moving link unknown, the first driver's angle free, lengths scaled by
the scene size): from a node x_k with unit tangent tau_k (the null vector of dF/dx), the
predictor x_k + h tau_k is corrected by Newton-Raphson on [F(x); tau_k . (x - x_pred)] = 0. A step
is accepted when the corrector contracts and converges and the tangent turns by less than
MAX_TANGENT_TURN; otherwise h is halved (down to MIN_STEP); an easy step doubles h (up to
MAX_STEP). A limit position (a fold: the driver's turn reaches an extremum along the path) shows
as a change of sign of the tangent's driver component; it is located by regula falsi on that
component, to rounding, so the limits do not depend on the number of samples.

**Every sample at once** (``solve_group``): each sample's starting value is the cubic Hermite
interpolant of the path between its two nodes (in arclength, solved for the sample's turn); the
group's coordinates are then polished by Newton-Raphson on all samples together (stacked
Jacobians, ``numpy.linalg.solve`` on (N, n, n)), and the velocities and accelerations solved the
same way.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg.lapack import dgesv

from solver import constraints, newton
from solver.constraints import ConstraintSystem, States
from solver.errors import NotAssemblable
from solver.newton import NewtonReport
from solver.rigid import Array, LinkMotion
from solver.scene import LinkageScene

NODE_TOLERANCE = 1e-9  # a path node's residual, relative to the scene size (samples are polished)
LIMIT_TOLERANCE = 1e-13  # the residual of a limit position's node (the limits are answers)
MAX_STEP = 1.0  # arclength of one step, in scene sizes and radians
MIN_STEP = 1e-9
MAX_TANGENT_TURN = math.radians(30.0)
MAX_CORRECTION = 0.1  # the corrector may move the predictor by this fraction of the step
CONTRACTION = 0.3  # each corrector step at most this fraction of the one before
CORRECTOR_ITERATIONS = 8
# Residual (scaled) allowed at the middle of the cubic between two nodes: the samples' starting
# values are that close to the path, well inside Newton-Raphson's quadratic convergence.
INTERPOLATION_RESIDUAL = 1e-3
FOLD_TANGENT = 1e-8  # the tangent's driver component at a located limit (turn error ~ 1e-16)
FOLD_XTOL = 1e-12  # or the bracket on the arclength this short
FOLD_ITERATIONS = 60
# A sample's start must lie within this (relative to the size) of the root it converges to, and
# the root within two first Newton steps of it; otherwise the path is refined around the sample
# (its segment halved, at most MAX_REFINEMENTS times) and the sample solved again.
BRANCH_GAP = 1e-2
MAX_REFINEMENTS = 12
POLISH_ITERATIONS = 12


def _solve(A: Array, rhs: Array) -> Array:
    """A x = rhs: LU (LAPACK's dgesv, called directly: numpy.linalg.solve's checks cost three
    times the solve of a small system) for a square regular A, least squares otherwise."""
    if A.shape[0] == A.shape[1]:
        x, info = dgesv(A, rhs)[2:]
        if info == 0:
            return np.asarray(x)
    return np.linalg.lstsq(A, rhs, rcond=None)[0]


def _norm(v: Array) -> float:
    """|v| for a vector (numpy.linalg.norm's generality costs more than the product)."""
    return math.sqrt(float(v @ v))


def _bordered(J: Array, row: Array) -> Array:
    """[J; row]: the Jacobian with one more row."""
    A = np.empty((J.shape[0] + 1, J.shape[1]))
    A[:-1], A[-1] = J, row
    return A


@dataclass
class _Leg:
    """Nodes of the path from the drawn pose in one sense of the driver: arclength s, scaled
    coordinates x, unit tangents tau; ``limit`` is the turn of the limit position that ends it."""

    s: list[float]
    x: list[Array]
    tau: list[Array]
    h: float = 0.1
    limit: float | None = None
    kappa: Array | None = None  # the path's curvature dtau/ds at the last node, where known


def _predict(leg: _Leg, h: float) -> Array:
    """x + h tau + h^2/2 kappa: the second-order Taylor step from the leg's last node, with its
    curvature kappa = dtau/ds (``Branch._curvature``), else estimated from the last two nodes'
    tangents (first order from the drawn pose)."""
    x, tau, kappa = leg.x[-1], leg.tau[-1], leg.kappa
    if kappa is None and len(leg.s) >= 2:
        kappa = (tau - leg.tau[-2]) / (leg.s[-1] - leg.s[-2])
    return x + h * tau if kappa is None else x + h * tau + (0.5 * h * h) * kappa


class Branch:
    """The configuration path of the whole linkage as driver ``free`` turns, the others held at
    the turns ``held`` (in the order of the scene's drivers), from the pose ``start`` (drawn).

    Coordinates are those of ``ConstraintSystem`` (each moving link's first point and rotation
    from the drawn pose), scaled: lengths by the scene size.
    """

    def __init__(
        self,
        scene: LinkageScene,
        free: int = 0,
        held: tuple[float, ...] = (),
        start: Array | None = None,
    ) -> None:
        drivers = [d.link for d in scene.drivers]
        others = drivers[:free] + drivers[free + 1 :]
        self.scene = scene
        self.system = ConstraintSystem(scene, scene.moving_links, angles=others)
        self.held = np.array([held]).reshape(1, len(others))
        self.free_driver = free
        self.free = self.system.column[drivers[free]] + 2
        size = scene.size
        self.scale = np.tile([size, size, 1.0], len(self.system.unknown))
        self.row_scale = np.where(self.system.length_rows, size, 1.0)
        ground = scene.ground
        anchor = self.system.anchor0[ground][None]
        zero2, zero = np.zeros((1, 2)), np.zeros(1)
        self.known = {ground: States(anchor, zero, zero2, zero, zero2, zero)}
        form = self.system.linear
        self.form = None if form is None else form.scaled(self.scale, self.row_scale)
        self.equations = self.system.residual(
            self.known, 1, self.held, (self.scale, self.row_scale)
        )
        x0 = (self.system.drawn() if start is None else start) / self.scale
        self.legs: dict[int, _Leg] = {}
        for sense in (1, -1):
            tau = np.zeros(x0.size)
            tau[self.free] = sense
            J = self._f(x0)[1]
            tau = self._tangent(J, tau)
            self.legs[sense] = _Leg([0.0], [x0], [tau], kappa=self._curvature(x0, tau, J))

    def _f(self, x: Array) -> tuple[Array, Array]:
        """Scaled residual F(x) and Jacobian dF/dx at scaled coordinates x."""
        return self.equations(x)

    def _tangent(self, J: Array, previous: Array) -> Array:
        """The unit null vector of the Jacobian J = dF/dx, on the side of ``previous``."""
        A = _bordered(J, previous)
        rhs = np.zeros(A.shape[0])
        rhs[-1] = 1.0
        z = _solve(A, rhs)
        return z / _norm(z)

    def _curvature(self, x: Array, tau: Array, J: Array) -> Array | None:
        """kappa = x'' at a node x with tangent tau: [J; tau] kappa = [bending; 0] (the second
        derivative of F(x(s)) = 0, and tau . kappa = 0 for a unit tangent); None without the
        linear form (a slider: the predictor estimates it from two tangents)."""
        if self.form is None:
            return None
        return _solve(_bordered(J, tau), np.append(self.form.bending(x, tau), 0.0))

    def _correct(
        self, predicted: Array, tau: Array, tolerance: float = NODE_TOLERANCE
    ) -> tuple[Array, Array, bool, int]:
        """Newton-Raphson on [F(x); tau . (x - predicted)] = 0 from the predictor: the point,
        dF/dx there, whether it converged and in how many iterations."""
        x = predicted
        last = np.inf
        for iteration in range(CORRECTOR_ITERATIONS + 1):
            F, J = self._f(x)
            if _norm(F) <= tolerance:
                return x, J, True, iteration
            if iteration == CORRECTOR_ITERATIONS:
                break
            dx = _solve(_bordered(J, tau), np.append(F, tau @ (x - predicted)))
            step = _norm(dx)
            if not np.isfinite(step) or step > CONTRACTION * last:
                break  # not contracting: too long a step
            x, last = x - dx, step
        return x, J, False, iteration

    def _turn(self, x: Array) -> float:
        return float(x[self.free])

    def extend(self, sense: int, target: float) -> _Leg:
        """Follow the path in ``sense`` until the driver's turn passes ``target`` or a limit."""
        leg = self.legs[sense]
        while leg.limit is None and sense * (self._turn(leg.x[-1]) - target) < 0.0:
            x, tau, h = leg.x[-1], leg.tau[-1], leg.h
            predicted = _predict(leg, h)
            new, J, ok, _ = self._correct(predicted, tau)
            tau_new, grow = tau, 0.5
            if ok:  # near the predictor (not on a neighbouring strand of the path), gently turning
                tau_new = self._tangent(J, tau)
                turn = math.acos(min(1.0, float(tau_new @ tau)))
                moved = _norm(new - predicted) / h
                # The turn grows like h, the predictor's error like h^2 (second order): aim at
                # 0.6 of their bounds with the next step.
                grow = 0.6 * min(
                    MAX_TANGENT_TURN / max(turn, 1e-12), math.sqrt(MAX_CORRECTION / moved)
                )
                ok = turn <= MAX_TANGENT_TURN and moved <= MAX_CORRECTION
            if ok:  # the cubic between the two nodes must stay on the path (the samples' start)
                chord = _norm(new - x)
                middle = 0.5 * (x + new) + 0.125 * chord * (tau - tau_new)
                ok = _norm(self._f(middle)[0]) <= INTERPOLATION_RESIDUAL
                grow = grow if ok else 0.5
            if not ok:
                leg.h = h * min(max(grow, 0.25), 0.5)
                if leg.h < MIN_STEP:  # the path cannot be continued (a bifurcation): stop here
                    leg.limit = self._turn(x)
                continue
            if sense * tau_new[self.free] <= 0.0:
                self._limit(leg, sense, h, sense * float(tau_new[self.free]))
                break
            leg.s.append(leg.s[-1] + chord)
            leg.x.append(new)
            leg.tau.append(tau_new)
            leg.kappa = self._curvature(new, tau_new, J)
            leg.h = min(h * min(grow, 2.0), MAX_STEP)
        return leg

    def _limit(self, leg: _Leg, sense: int, h: float, beyond: float) -> None:
        """The limit position between the last node and the step h past it (where the tangent's
        driver component, ``beyond`` there, changed sign): the zero of that component along the
        step by regula falsi (Illinois), appended as a node. The turn is stationary at the
        limit, so a component c left over moves it by only ~ c^2."""
        x, tau = leg.x[-1], leg.tau[-1]
        a, b = 0.0, h
        g_a, g_b = sense * float(tau[self.free]), beyond
        point, tangent, kept = x, tau, 0
        for _ in range(FOLD_ITERATIONS):
            s = (a * g_b - b * g_a) / (g_b - g_a)
            point, J, _, _ = self._correct(x + s * tau, tau, LIMIT_TOLERANCE)
            tangent = self._tangent(J, tau)
            g = sense * float(tangent[self.free])
            if abs(g) <= FOLD_TANGENT or b - a <= FOLD_XTOL:
                break
            if g > 0.0:
                a, g_a = s, g
                g_b = g_b / 2.0 if kept == 1 else g_b
                kept = 1
            else:
                b, g_b = s, g
                g_a = g_a / 2.0 if kept == -1 else g_a
                kept = -1
        leg.s.append(leg.s[-1] + _norm(point - x))
        leg.x.append(point)
        leg.tau.append(tangent)
        leg.limit = self._turn(point)

    def reaches(self, turn: float) -> bool:
        """Whether the path from the drawn pose reaches ``turn`` before a limit position."""
        sense = 1 if turn >= 0.0 else -1
        leg = self.extend(sense, turn)
        return leg.limit is None or sense * (turn - leg.limit) <= 0.0

    def limits(self, low: float, high: float) -> tuple[float, float] | None:
        """None if the driver turns from ``low`` to ``high`` (and through a whole turn) with no
        limit position; else the turns of the two limit positions around the drawn pose."""
        high = max(high, low + 2.0 * math.pi, 0.0)
        ahead, behind = self.extend(1, high), self.extend(-1, min(low, 0.0))
        if ahead.limit is None and behind.limit is None:
            return None
        # One leg stopped at a limit: the path is not a whole turn, so the other leg stops too.
        ahead = self.extend(1, 4.0 * math.pi)
        behind = self.extend(-1, -4.0 * math.pi)
        if ahead.limit is None or behind.limit is None:
            return None
        return behind.limit, ahead.limit

    def guesses(self, turns: Array) -> tuple[Array, Array, Array]:
        """Interpolated coordinates (unscaled, (K, n)) at ``turns`` by the branch rule, which
        turns the path reaches, and the turns as reached (the other way round: t -+ 2 pi)."""
        turns = np.array(turns, dtype=float)
        x = np.zeros((turns.size, self.scale.size))
        reached = np.zeros(turns.size, dtype=bool)
        for sense in (1, -1):
            mine = (turns >= 0.0) if sense > 0 else (turns < 0.0)
            if np.any(mine):
                leg = self.extend(sense, float(np.max(sense * turns[mine])) * sense)
                stop = np.inf if leg.limit is None else sense * leg.limit
                reached |= mine & (sense * turns <= stop)
        for k in np.flatnonzero(~reached):  # the other way round
            other = turns[k] - 2.0 * math.pi * math.copysign(1.0, turns[k])
            if self.reaches(other):
                reached[k] = True
                turns[k] = other
        for sense in (1, -1):
            mine = reached & ((turns >= 0.0) if sense > 0 else (turns < 0.0))
            if np.any(mine):
                x[mine] = self._interpolate(self.legs[sense], sense, turns[mine])
        return x * self.scale, reached, turns

    def pose(self, turn: float, tolerance: float) -> Array | None:
        """The linkage's coordinates at the free driver's ``turn`` (None if not reached),
        polished to ``tolerance`` (relative to the size) with every driver's angle held."""
        x, reached, _ = self.guesses(np.array([turn]))
        if not reached[0]:
            return None
        drivers = [d.link for d in self.scene.drivers]
        system = ConstraintSystem(self.scene, self.scene.moving_links, angles=drivers)
        angles = list(self.held[0])
        angles.insert(self.free_driver, turn)
        q, _, _, _ = newton.newton_raphson(
            system, self.known, x, tolerance * self.scene.size, turns=np.array([angles])
        )
        return q[0]

    def refine(self, turns: Array) -> None:
        """Split the path's segments that hold ``turns`` (a node added at the middle, or nearer
        the segment's start where the corrector does not converge from the middle)."""
        for sense in (1, -1):
            leg = self.legs[sense]
            mine = turns[(turns >= 0.0) if sense > 0 else (turns < 0.0)]
            if mine.size == 0 or len(leg.s) < 2:
                continue
            t_nodes = sense * np.array(leg.x)[:, self.free]
            segments = np.clip(np.searchsorted(t_nodes, sense * mine) - 1, 0, len(leg.s) - 2)
            for k in sorted(set(segments.tolist()), reverse=True):
                x, tau = leg.x[k], leg.tau[k]
                chord = _norm(leg.x[k + 1] - x)
                for fraction in (0.5, 0.25, 0.125, 0.0625):  # the middle, or nearer node k
                    new, J, ok, _ = self._correct(x + fraction * chord * tau, tau)
                    if ok:
                        break
                if not ok:
                    continue
                leg.s.insert(k + 1, leg.s[k] + _norm(new - x))
                leg.x.insert(k + 1, new)
                leg.tau.insert(k + 1, self._tangent(J, tau))

    def _interpolate(self, leg: _Leg, sense: int, turns: Array) -> Array:
        """Cubic Hermite interpolation in arclength between the nodes bracketing each turn."""
        X = np.array(leg.x)
        T = np.array(leg.tau)
        s = np.array(leg.s)
        t_nodes = sense * X[:, self.free]
        k = np.clip(np.searchsorted(t_nodes, sense * turns) - 1, 0, len(leg.s) - 2)
        h = (s[k + 1] - s[k])[:, None]
        x0, x1, d0, d1 = X[k], X[k + 1], T[k] * h, T[k + 1] * h
        t0, t1 = x0[:, self.free], x1[:, self.free]
        u = np.clip((turns - t0) / np.where(t1 != t0, t1 - t0, 1.0), 0.0, 1.0)
        f = self.free
        for _ in range(6):  # Newton on the monotone cubic t(u) = turn
            h00, h10, h01, h11 = _hermite(u)
            g00, g10 = 6 * u**2 - 6 * u, 3 * u**2 - 4 * u + 1
            g01, g11 = 6 * u - 6 * u**2, 3 * u**2 - 2 * u
            t = h00 * t0 + h10 * d0[:, f] + h01 * t1 + h11 * d1[:, f]
            dt = g00 * t0 + g10 * d0[:, f] + g01 * t1 + g11 * d1[:, f]
            u = np.clip(u - (t - turns) / np.where(dt != 0.0, dt, 1.0), 0.0, 1.0)
        h00, h10, h01, h11 = _hermite(u)
        return h00[:, None] * x0 + h10[:, None] * d0 + h01[:, None] * x1 + h11[:, None] * d1


def _hermite(u: Array) -> tuple[Array, Array, Array, Array]:
    """The cubic Hermite basis h00, h10, h01, h11 at u in [0, 1]."""
    u2, u3 = u * u, u * u * u
    return 2 * u3 - 3 * u2 + 1, u3 - 2 * u2 + u, 3 * u2 - 2 * u3, u3 - u2


@dataclass
class Continuation:
    """Newton groups' settings for one request, and the branches followed so far (reused by
    every assembly of the same request: the feasibility probe, the sweep, its limits)."""

    scene: LinkageScene
    tolerance: float = newton.NEWTON_TOLERANCE
    branches: dict[tuple[float, ...], Branch] = field(default_factory=dict)

    def branch(self, held: tuple[float, ...]) -> Branch:
        """The first driver's branch with the other drivers at ``held``, reached from the drawn
        pose by turning them one after the other (the first driver held at 0)."""
        if held not in self.branches:
            start: Array | None = None
            for index in range(1, len(held) + 1):
                others = (0.0, *held[: index - 1], *(0.0,) * (len(held) - index))
                stage = Branch(self.scene, index, others, start)
                start = stage.pose(held[index - 1], self.tolerance)
                if start is None:
                    raise NotAssemblable(
                        f"the linkage cannot be closed: turning driver {index + 1} "
                        f"({self.scene.drivers[index].link}) from its drawn pose either way "
                        "meets a limit position first"
                    )
            self.branches[held] = Branch(self.scene, 0, held, start)
        return self.branches[held]


def solve_group(
    scene: LinkageScene,
    group: Sequence[str],
    known: Mapping[str, LinkMotion],
    turns: Sequence[Array],
    order: int,
    continuation: Continuation,
) -> tuple[dict[str, LinkMotion], NewtonReport]:
    """The links of ``group`` at every sample by the branch rule, then their rates.

    ``turns`` are the drivers' turns per sample; the group's known neighbours come from
    ``known`` (the closed-form groups solved before it).
    """
    system = ConstraintSystem(scene, group)
    samples = turns[0].size if turns else 1
    states = constraints.states({name: known[name] for name in system.known}, scene)
    polish = _Polish(system, states, samples, continuation)
    if not turns:
        polish.run(np.arange(samples), None, None)
    else:  # one branch per set of the other drivers' turns
        held = np.stack(turns[1:], axis=1) if len(turns) > 1 else np.zeros((samples, 0))
        for key in np.unique(held, axis=0) if held.shape[1] else held[:1]:
            todo = np.flatnonzero(np.all(held == key, axis=1))
            polish.run(todo, continuation.branch(tuple(key.tolist())), turns[0])
    qd, qdd = constraints.rates(system, states, polish.q, order)
    motions = system.motions(polish.q, qd, qdd)
    converged = polish.reached & polish.settled
    worst = float(np.max(polish.residual, initial=0.0))
    tolerance = continuation.tolerance * scene.size
    message = f"Newton-Raphson closed the loop of {', '.join(group)}"
    if not np.all(converged):
        at = turns[0] if turns else np.zeros(samples)
        message = _failure(scene, group, at, polish.reached, worst, tolerance, polish.iterations)
    report = NewtonReport(
        tuple(group), converged, polish.iterations, worst, tolerance, message,
        continuation.tolerance,
    )  # fmt: skip
    return motions, report


class _Polish:
    """Every sample of a Newton group polished by batched Newton-Raphson from the branch's
    interpolated path (``q``, ``residual``; ``reached`` by the branch rule; ``settled`` on the
    root its start points at), the path refined around samples that did not settle."""

    def __init__(
        self,
        system: ConstraintSystem,
        states: Mapping[str, States],
        samples: int,
        continuation: Continuation,
    ) -> None:
        self.system, self.states = system, states
        scene = system.scene
        self.size = scene.size
        self.tolerance = continuation.tolerance * scene.size
        self.polish = continuation.tolerance <= newton.NEWTON_TOLERANCE
        self.q = np.tile(system.drawn(), (samples, 1))
        self.residual = np.zeros(samples)
        self.reached = np.ones(samples, dtype=bool)
        self.settled = np.zeros(samples, dtype=bool)
        self.iterations = 0
        column = {link: 3 * k for k, link in enumerate(scene.moving_links)}
        self.columns = np.concatenate([column[g] + np.arange(3) for g in system.unknown])
        self.weights = np.tile([1.0, 1.0, scene.size], len(system.unknown))

    def run(self, todo: Array, branch: Branch | None, turns: Array | None) -> None:
        """Polish the samples ``todo`` (at the first driver's ``turns``, on ``branch``)."""
        for attempt in range(MAX_REFINEMENTS + 1):
            q0 = self.q[todo]
            way = np.zeros(todo.size)
            if branch is not None and turns is not None:
                x, self.reached[todo], way = branch.guesses(turns[todo])
                q0 = x[:, self.columns]
            part = {name: _take(s, todo) for name, s in self.states.items()}
            self.q[todo], self.residual[todo], its, first = newton.newton_raphson(
                self.system, part, q0, self.tolerance, polish=self.polish,
                max_iterations=POLISH_ITERATIONS,
            )  # fmt: skip
            self.iterations = max(self.iterations, its)
            step = (self.q[todo] - q0) * self.weights
            moved = np.sqrt(np.einsum("mi,mi->m", step, step))
            # Converged to the root its start points at: about one first step away, and close.
            good = (self.residual[todo] <= self.tolerance) & (
                moved <= 2.0 * first + 1e-9 * self.size
            )
            self.settled[todo] = good & (first <= BRANCH_GAP * self.size)
            bad = self.reached[todo] & ~self.settled[todo]
            if branch is None or not np.any(bad) or attempt == MAX_REFINEMENTS:
                break
            branch.refine(way[bad])
            todo = todo[bad]


def _take(states: States, index: Array) -> States:
    return States(*(np.asarray(getattr(states, f))[index] for f in States.__dataclass_fields__))


def _failure(
    scene: LinkageScene,
    group: Sequence[str],
    turns: Array,
    reached: Array,
    residual: float,
    tolerance: float,
    iterations: int,
) -> str:
    """Why the group could not be closed at some sample, with the numbers."""
    names = ", ".join(group)
    link = scene.drivers[0].link
    points = scene.links[link].points
    drawn = 0.0
    if len(points) >= 2:
        d = scene.drawn(points[1]) - scene.drawn(points[0])
        drawn = math.atan2(d[1], d[0])
    if not np.all(reached):
        k = int(np.argmin(reached))
        return (
            f"the loop of {names} cannot be closed at {link} angle "
            f"{math.degrees(drawn + float(turns[k])):.6g} deg: turning {link} from its drawn pose "
            "either way meets a limit position first"
        )
    if residual <= tolerance:
        return f"Newton-Raphson could not follow the branch of {names} to every sample"
    return (
        f"Newton-Raphson did not close the loop of {names}: residual {residual:.3g} m > "
        f"tolerance {tolerance:.3g} m after {iterations} iterations"
    )
