"""Newton groups along a sweep: the branch followed from the drawn pose, then every sample at once.

**The branch rule.** The pose of a linkage with a Newton group at a driver turn t (the rotation of
the first driver from its drawn pose) is the end of the path that starts at the drawn pose and
turns the driver from 0 to t, the linkage's configuration moving continuously. Where a limit
position stops that path before t, the driver is turned the other way round instead, to
t - 2 pi sign(t). Other drivers are first turned, one after the other, from 0 to their given
turns with the first held at 0. A sweep and a single instant apply the same rule, so /analyze at
a swept angle returns the swept pose.

**Following the path** (``Branch``): pseudo-arclength continuation on the whole linkage's loop
equations F(y) = 0 (the first driver's angle free), in the moving links' rotations alone where
the equations are linear in them (``constraints.Rotations``: the translations are eliminated and
follow from the rotations; 4 equations in 5 angles for a Stephenson III triad), else in every
link's (x, y, theta) with lengths scaled by the scene size: from a node y_k with unit tangent
tau_k (the null vector of dF/dy), the predictor y_k + h tau_k + h^2/2 kappa_k + h^3/6 kappa'_k
(``predict``) is corrected by Newton-Raphson on [F(y); tau_k . (y - y_pred)] = 0. A step is
accepted when the corrector contracts and converges, the tangent turns by less than
MAX_TANGENT_TURN, the path's orientation sign det [dF/dy; tau] is kept (``_orientation``: it
changes only across a bifurcation, so a step that lands on a neighbouring strand of F = 0 has
crossed one) and the quintic between the two nodes stays on the path with its driver turn
monotone (``_monotone``: a step across two limit positions, an S, is not); otherwise h is halved
(down to MIN_STEP; a step under BIFURCATION_STEP may change the orientation: it crosses a
bifurcation); an easy step doubles h (up to MAX_STEP). A limit position (a fold: the
driver's turn reaches an extremum along the path) shows as a change of sign of the tangent's
driver component; it is located by safeguarded Newton on that component, to rounding, so the
limits do not depend on the number of samples.
Where the path was followed with long steps (a middle further than HALVING_RESIDUAL from it),
every segment of the leg is then halved at once (``Branch.halved``).

**Every sample at once** (``solve_group``): each sample's starting value is the quintic Hermite
interpolant of the path between its two nodes (positions, tangents and curvatures, in
arclength; solved for the sample's turn); the group's coordinates are then polished by
Newton-Raphson on all samples together, each sample only until it meets the tolerance
(``newton.newton_rotations``: (N, U, U) solves in the rotations, the Jacobian never formed), and
the velocities and accelerations solved the same way.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg.lapack import dgesv

from solver.errors import NotAssemblable
from solver.kinematics.rigid import Array, LinkMotion
from solver.model.scene import LinkageScene
from solver.position import constraints, newton
from solver.position.constraints import ConstraintSystem, States
from solver.position.newton import NewtonReport

NODE_TOLERANCE = 1e-9  # a path node's residual, relative to the scene size (samples are polished)
LIMIT_TOLERANCE = 1e-15  # a limit position's residual: rounding, ~4 eps (the limits are answers)
MAX_STEP = 1.0  # arclength of one step, in scene sizes and radians
MIN_STEP = 1e-9
MAX_TANGENT_TURN = math.radians(60.0)
BIFURCATION_STEP = 1e-6  # a step this short crosses a bifurcation (or strands as close as that)
MONOTONE_AT = np.linspace(0.0, 1.0, 9)  # where a step's quintic is checked to turn monotonely
MAX_CORRECTION = 0.3  # the corrector may move the predictor by this fraction of the step
CONTRACTION = 0.3  # each corrector step at most this fraction of the one before
CORRECTOR_ITERATIONS = 8
# Residual (scaled) allowed at the middle of the cubic between two nodes: the samples' starting
# values are that close to the path, well inside Newton-Raphson's quadratic convergence.
INTERPOLATION_RESIDUAL = 1e-3
# Where a leg's middles lie further than this from the path, its samples would start where
# Newton-Raphson needs a second iteration: every segment is halved first (``Branch.halved``).
HALVING_RESIDUAL = 1e-5
# A path closes after a whole turn where the two poses agree this closely (path coordinates:
# radians, lengths over the size): far above their correction (NODE_TOLERANCE times their
# condition number), far below the distance between two assembly modes at one driver angle
# away from a bifurcation.
CLOSURE = 1e-6
FOLD_TANGENT = 1e-8  # the tangent's driver component at a located limit (turn error ~ 1e-16)
FOLD_XTOL = 1e-12  # or the bracket on the arclength this short
FOLD_ITERATIONS = 60
# A sample's start must lie within this (relative to the size) of the root it converges to, and
# the root within two first Newton steps of it; otherwise the path is refined around the sample
# (its segment halved, at most MAX_REFINEMENTS times) and the sample solved again.
BRANCH_GAP = 1e-2
MAX_REFINEMENTS = 12
POLISH_ITERATIONS = 12


def bordered_solve(J: Array, row: Array, top: Array | None, last: float) -> Array:
    """[J; row] z = [top; last] (top None: zeros): LU (LAPACK's dgesv, called directly:
    numpy.linalg.solve's checks cost three times the solve of a small system) where square and
    regular, least squares otherwise."""
    rows = J.shape[0]
    A = np.empty((rows + 1, J.shape[1]))
    A[:rows], A[rows] = J, row
    b = np.zeros(rows + 1)
    if top is not None:
        b[:rows] = top
    b[rows] = last
    if A.shape[0] == A.shape[1]:
        x, info = dgesv(A, b)[2:]
        if info == 0:
            return np.asarray(x)
    return np.linalg.lstsq(A, b, rcond=None)[0]


def _bordered_solves(J: Array, rows: Array, top: Array, last: Array) -> Array:
    """[J_k; row_k] z_k = [top_k; last_k] for K stacked systems (LU; numpy.linalg.LinAlgError
    where one is singular or they are not square)."""
    A = np.concatenate([J, rows[:, None, :]], axis=1)
    b = np.concatenate([top, last[:, None]], axis=1)
    return np.asarray(np.linalg.solve(A, b[..., None])[..., 0])


def _arc(chord: Array | float, bend: Array | float) -> Array | float:
    """The length of a circular arc on ``chord`` with squared curvature ``bend``:
    c (1 + c^2 kappa^2 / 24) (the arc's series to second order)."""
    return chord * (1.0 + chord * chord * bend / 24.0)


def _norm(v: Array) -> float:
    """|v| for a vector (numpy.linalg.norm's generality costs more than the product)."""
    return math.sqrt(float(v @ v))


@dataclass
class Leg:
    """Nodes of the path from the drawn pose in one sense of the driver: arclength s, scaled
    coordinates x, unit tangents tau; ``limit`` is the turn of the limit position that ends it."""

    s: list[float]
    x: list[Array]
    tau: list[Array]
    kappa: list[Array | None]  # the path's curvature dtau/ds at each node, where known
    h: float = 0.1
    limit: float | None = None
    halved: tuple[Array, Array, Array, Array] | None = None  # ``Branch.halved``, while valid
    gap: float = 0.0  # the largest residual at a segment's middle found by ``Branch.extend``

    def insert(self, k: int, x: Array, tau: Array, kappa: Array | None) -> None:
        """A node at index k (k = len: appended), its arclength from node k - 1 that of a
        circular arc with their chord c and mean squared curvature: c (1 + c^2 |kappa|^2 / 24)."""
        chord = _norm(x - self.x[k - 1])
        before = self.kappa[k - 1]
        bend = 0.0 if kappa is None or before is None else 0.5 * (kappa @ kappa + before @ before)
        self.s.insert(k, self.s[k - 1] + float(_arc(chord, bend)))
        self.x.insert(k, x)
        self.tau.insert(k, tau)
        self.kappa.insert(k, kappa)
        self.halved = None

    def remove(self) -> None:
        """Take the last node off."""
        for nodes in (self.s, self.x, self.tau, self.kappa):
            nodes.pop()
        self.halved = None

    def middle(self) -> Array:
        """The quintic interpolant of the last segment (``quintic_hermite``) at its middle:
        (x0 + x1)/2 + 5h/32 (tau0 - tau1) + h^2/64 (kappa0 + kappa1), h the segment's arclength
        (a curvature not known: (tau1 - tau0)/h, which gives the cubic's middle)."""
        h = self.s[-1] - self.s[-2]
        (x0, x1), (tau0, tau1) = self.x[-2:], self.tau[-2:]
        kappa0, kappa1 = self.kappa[-2:]
        if kappa0 is None or kappa1 is None:
            kappa0 = kappa1 = (tau1 - tau0) / h
        return np.asarray(
            0.5 * (x0 + x1) + (5.0 * h / 32.0) * (tau0 - tau1) + (h * h / 64.0) * (kappa0 + kappa1)
        )

    def arrays(self, first: int = 0) -> tuple[Array, Array, Array, Array]:
        """Nodes ``first`` onwards as arrays: s, x, tau, and kappa (a curvature not known is
        estimated from the tangents by centred differences)."""
        s, X, T = np.array(self.s[first:]), np.array(self.x[first:]), np.array(self.tau[first:])
        if all(kappa is not None for kappa in self.kappa[first:]):
            return s, X, T, np.array(self.kappa[first:])
        return s, X, T, np.gradient(T, s, axis=0) if len(s) > 1 else np.zeros_like(T)


def _orientation(J: Array, tau: Array) -> float:
    """sign det [J; tau]: the orientation of the path at a node with Jacobian J = dF/dx and unit
    tangent tau (Allgower and Georg). It keeps its sign along a strand of F(x) = 0, through limit
    positions too, and changes it only across a bifurcation, so a step to a node of the other
    sign has crossed to a neighbouring strand (or through a bifurcation)."""
    return float(np.linalg.slogdet(np.vstack([J, tau]))[0])


def _monotone(leg: Leg, free: int, sense: int) -> bool:
    """Whether the driver's turn x[free] moves in ``sense`` all along the quintic of the leg's
    last segment (its derivative checked at MONOTONE_AT): ``Branch._segments`` solves t(u) = turn
    on the quintic by Newton's method, and a path that went back and forth across two limit
    positions within one step (an S) does not turn monotonely."""
    s, X, T, K = leg.arrays(len(leg.s) - 2)
    h = s[1] - s[0]
    # ``quintic_hermite``'s data for the turn alone (``quintic_hermite`` itself costs 5 times more).
    data = np.array([X[0], h * T[0], h * h * K[0], h * h * K[1], h * T[1], X[1]])[:, free]
    return bool(np.all(sense * (_MONOTONE_RATES @ data) > 0.0))


def predict(leg: Leg, h: float) -> Array:
    """x + h tau + h^2/2 kappa + h^3/6 kappa': the Taylor step from the leg's last node, with
    its curvature kappa = dtau/ds (``Branch.curvature``) and kappa' from the last two nodes'
    curvatures; where the curvatures are not known (no linear form), kappa from the last two
    nodes' tangents (first order from the drawn pose)."""
    x, tau, kappa = leg.x[-1], leg.tau[-1], leg.kappa[-1]
    if len(leg.s) < 2:
        return x + h * tau if kappa is None else x + h * tau + (0.5 * h * h) * kappa
    step = leg.s[-1] - leg.s[-2]
    before = leg.kappa[-2]
    if kappa is None or before is None:
        return x + h * tau + (0.5 * h * h / step) * (tau - leg.tau[-2])
    return x + h * tau + (0.5 * h * h) * kappa + (h * h * h / (6.0 * step)) * (kappa - before)


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
        self.system = constraints.constraint_system(scene, scene.moving_links, others)
        self.held = np.array([held]).reshape(1, len(others))
        self.free_driver = free
        self.scale = self.system.scaled[0]
        ground = scene.ground
        anchor = self.system.anchor0[ground][None]
        zero2, zero = np.zeros((1, 2)), np.zeros(1)
        self.known = {ground: States(anchor, zero, zero2, zero, zero2, zero)}
        x0 = (self.system.drawn() if start is None else start) / self.scale
        self._path(x0, self.system.column[drivers[free]])
        self.legs: dict[int, Leg] = {}
        for sense in (1, -1):
            tau = np.zeros(self.y0.size)
            tau[self.free] = sense
            J = self._f(self.y0)[1]
            tau = self.tangent(J, tau)
            self.legs[sense] = Leg([0.0], [self.y0], [tau], [self.curvature(self.y0, tau, J)])

    def _path(self, x0: Array, column: int) -> None:
        """The coordinates y the path is followed in, from the scaled drawn coordinates x0: the
        rotations alone where the equations are linear in them (``constraints.Rotations``: the
        translations follow from them), else x; ``free`` the first driver's index in y."""
        _, row_scale, scaled = self.system.scaled
        rotations = None if scaled is None else scaled.rotations
        self.bending: Callable[[Array, Array], Array] | None = None
        if scaled is None or rotations is None:
            self.equations = self.system.residual(self.known, 1, self.held, (self.scale, row_scale))
            self.bending = None if scaled is None else scaled.bending
            self.lift: Callable[[Array], Array] = lambda y: y
            self.y0, self.free = x0, column + 2
            self.angles = np.arange(x0.size) % 3 == 2
            return
        known = scaled.known_terms(self.known, 1, 0, self.held)[0][0]
        fixed = rotations.fixed(known)
        self.equations = lambda y: rotations.pose(y, fixed)
        self.bending = rotations.bending
        self.lift = lambda y: rotations.assemble(y, rotations.translations(y, known))
        self.y0, self.free = x0[2::3], column // 3
        self.angles = np.ones(self.y0.size, dtype=bool)

    def _f(self, x: Array) -> tuple[Array, Array]:
        """Scaled residual F(y) and Jacobian dF/dy at path coordinates y."""
        return self.equations(x)

    def tangent(self, J: Array, previous: Array) -> Array:
        """The unit null vector of the Jacobian J = dF/dx, on the side of ``previous``."""
        z = bordered_solve(J, previous, None, 1.0)
        return z / _norm(z)

    def curvature(self, x: Array, tau: Array, J: Array) -> Array | None:
        """kappa = x'' at a node x with tangent tau: [J; tau] kappa = [bending; 0] (the second
        derivative of F(x(s)) = 0, and tau . kappa = 0 for a unit tangent); None without the
        linear form (a slider: the predictor estimates it from two tangents)."""
        if self.bending is None:
            return None
        return bordered_solve(J, tau, self.bending(x, tau), 0.0)

    def correct(
        self, predicted: Array, tau: Array, tolerance: float = NODE_TOLERANCE
    ) -> tuple[Array, Array, bool, int]:
        """Newton-Raphson on [F(x); tau . (x - predicted)] = 0 from the predictor: the point,
        dF/dx there, whether it converged and in how many iterations."""
        x = predicted
        last = math.inf  # squared lengths, as the residual's: no square roots
        for iteration in range(CORRECTOR_ITERATIONS + 1):
            F, J = self._f(x)
            if float(F @ F) <= tolerance * tolerance:
                return x, J, True, iteration
            if iteration == CORRECTOR_ITERATIONS:
                break
            dx = bordered_solve(J, tau, F, float(tau @ (x - predicted)))
            step = float(dx @ dx)
            if not math.isfinite(step) or step > CONTRACTION * CONTRACTION * last:
                break  # not contracting: too long a step
            x, last = x - dx, step
        return x, J, False, iteration

    def _turn(self, x: Array) -> float:
        return float(x[self.free])

    def extend(self, sense: int, target: float) -> Leg:
        """Follow the path in ``sense`` until the driver's turn passes ``target`` or a limit."""
        leg = self.legs[sense]
        orientation = _orientation(self._f(leg.x[-1])[1], leg.tau[-1])
        while leg.limit is None and sense * (self._turn(leg.x[-1]) - target) < 0.0:
            x, tau, h = leg.x[-1], leg.tau[-1], leg.h
            predicted = predict(leg, h)
            new, J, ok, _ = self.correct(predicted, tau)
            tau_new, grow = tau, 0.5
            if ok:  # near the predictor (not on a neighbouring strand of the path), gently turning
                tau_new = self.tangent(J, tau)
                turn = math.acos(min(1.0, float(tau_new @ tau)))
                moved = _norm(new - predicted) / h
                # The turn grows like h, the predictor's error like h^2 (second order): aim at
                # 0.6 of their bounds with the next step (either may be 0: a straight path).
                grow = 0.6 * min(
                    MAX_TANGENT_TURN / max(turn, 1e-12),
                    math.sqrt(MAX_CORRECTION / max(moved, 1e-12)),
                )
                # On the strand of the last node (unless too short a step to avoid a bifurcation).
                oriented = _orientation(J, tau_new)
                crossed = oriented != orientation and h > BIFURCATION_STEP
                ok = turn <= MAX_TANGENT_TURN and moved <= MAX_CORRECTION and not crossed
            if ok:  # the quintic between the two nodes must stay on the path (the samples' start)
                kappa = self.curvature(new, tau_new, J)
                leg.insert(len(leg.s), new, tau_new, kappa)
                gap = _norm(self._f(leg.middle())[0])
                ahead = sense * tau_new[self.free] > 0.0  # no limit position at the new node
                ok = gap <= INTERPOLATION_RESIDUAL and (
                    not ahead or _monotone(leg, self.free, sense)
                )
                grow = grow if ok else 0.5
                if not ok or not ahead:
                    leg.remove()
                else:
                    leg.gap = max(leg.gap, gap)
            if not ok:
                leg.h = h * min(max(grow, 0.25), 0.5)
                if leg.h < MIN_STEP:  # the path cannot be continued (a bifurcation): stop here
                    leg.limit = self._turn(x)
                continue
            orientation = oriented
            if not ahead:
                self._limit(leg, sense, h, sense * float(tau_new[self.free]))
                break
            leg.h = min(h * min(grow, 2.0), MAX_STEP)
        return leg

    def _limit(self, leg: Leg, sense: int, h: float, beyond: float) -> None:
        """The limit position between the last node and the step h past it (where the tangent's
        driver component g, ``beyond`` there, changed sign): the zero of g along the step,
        appended as a node. Trial points s are corrected from the node's second-order
        prediction x + s tau + s^2/2 kappa (on the plane normal to tau at s, as
        tau . kappa = 0); the next trial is Newton's, s - g / g' with g' = kappa's driver
        component over tau . tangent (the arclength per unit s), where it falls inside the
        bracket (the first from the node's kappa), else regula falsi's (Illinois) on it. The
        turn is stationary at the limit, so a component c left over moves it by only ~ c^2."""
        x, tau, kappa0 = leg.x[-1], leg.tau[-1], leg.kappa[-1]
        a, b = 0.0, h
        g_a, g_b = sense * float(tau[self.free]), beyond
        s = math.nan if kappa0 is None else -g_a / (sense * float(kappa0[self.free]))
        point, tangent, kept = x, tau, 0
        for _ in range(FOLD_ITERATIONS):
            if not a < s < b:
                s = (a * g_b - b * g_a) / (g_b - g_a)
            predicted = x + s * tau if kappa0 is None else x + s * tau + (0.5 * s * s) * kappa0
            point, J, _, _ = self.correct(predicted, tau, LIMIT_TOLERANCE)
            tangent = self.tangent(J, tau)
            kappa = self.curvature(point, tangent, J)
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
            slope = math.nan if kappa is None else sense * float(kappa[self.free])
            s = s - g * float(tau @ tangent) / slope if slope != 0.0 else math.nan
        leg.insert(len(leg.s), point, tangent, kappa)
        leg.limit = self._turn(point)

    def reaches(self, turn: float) -> bool:
        """Whether the path from the drawn pose reaches ``turn`` before a limit position."""
        sense = 1 if turn >= 0.0 else -1
        leg = self.extend(sense, turn)
        return leg.limit is None or sense * (turn - leg.limit) <= 0.0

    def limits(self, low: float, high: float) -> tuple[float, float] | None:
        """None if the driver turns from ``low`` to ``high`` (and through a whole turn) with no
        limit position and the path closes after that turn (``closes``); else the turns of the
        two limit positions around the drawn pose (a rocker whose limits lie more than a turn
        apart: its range is wider than a turn, whichever way the driver turns)."""
        high = max(high, low + 2.0 * math.pi, 0.0)
        # Reached: a limit that the last step's overshoot met past them does not count.
        start = min(low, 0.0)
        if self.reaches(high) and self.reaches(start) and self.closes(start):
            return None
        # Not a whole turn (or one that does not close): both legs stop at a limit.
        ahead = self.extend(1, 4.0 * math.pi)
        behind = self.extend(-1, -4.0 * math.pi)
        if ahead.limit is None or behind.limit is None:
            return None
        return behind.limit, ahead.limit

    def closes(self, turn: float) -> bool:
        """Whether the pose after a whole turn of the driver from ``turn`` is the pose at
        ``turn``: both taken from the path and corrected with the driver's turn held (``correct``
        bordered by the driver's axis), their coordinates within CLOSURE (rotations modulo
        2 pi). Then the path is a circuit of one turn, as a full revolution's sweep needs; a
        rocker whose limits lie more than a turn apart passes ``turn`` + 2 pi on another part of
        its path; a turn the path does not reach does not close."""
        axis = np.zeros(self.y0.size)
        axis[self.free] = 1.0
        ends = []
        for t in (turn, turn + 2.0 * math.pi):
            if t == 0.0:  # the drawn pose
                ends.append(self.y0)
                continue
            sense = 1 if t > 0.0 else -1
            if not self.reaches(t):
                return False
            start = self._segments(self.legs[sense], sense, np.array([t]))[0]
            y, _, converged, _ = self.correct(start, axis)
            if not converged:
                return False
            ends.append(y)
        d = ends[1] - ends[0]
        d[self.angles] = np.remainder(d[self.angles] + math.pi, 2.0 * math.pi) - math.pi
        return bool(np.max(np.abs(d)) <= CLOSURE)

    def guesses(self, turns: Array) -> tuple[Array, Array, Array]:
        """Interpolated coordinates (unscaled, (K, n)) at ``turns`` by the branch rule, which
        turns the path reaches, and the turns as reached (the other way round: t -+ 2 pi)."""
        turns = np.array(turns, dtype=float)
        x = np.zeros((turns.size, self.y0.size))
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
                x[mine] = self._segments(self.legs[sense], sense, turns[mine])
        return self.lift(x) * self.scale, reached, turns

    def pose(self, turn: float, tolerance: float) -> Array | None:
        """The linkage's coordinates at the free driver's ``turn`` (None if not reached),
        polished to ``tolerance`` (relative to the size) with every driver's angle held."""
        x, reached, _ = self.guesses(np.array([turn]))
        if not reached[0]:
            return None
        drivers = [d.link for d in self.scene.drivers]
        system = constraints.constraint_system(self.scene, self.scene.moving_links, drivers)
        angles = list(self.held[0])
        angles.insert(self.free_driver, turn)
        q, _, _, _ = newton.newton_raphson(
            system,
            self.known,
            x,
            newton.residual_tolerance(tolerance, system),
            turns=np.array([angles]),
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
                    new, J, ok, _ = self.correct(x + fraction * chord * tau, tau)
                    if ok:
                        break
                if not ok:
                    continue
                tangent = self.tangent(J, tau)
                leg.insert(k + 1, new, tangent, self.curvature(new, tangent, J))

    def halved(self, leg: Leg) -> tuple[Array, Array, Array, Array]:
        """The leg's nodes (``Leg.arrays``) with a node added at the middle of every segment,
        all segments at once, where a middle checked by ``extend`` lay further than
        HALVING_RESIDUAL from the path (the samples' quintic starting values then come 2^6 times
        closer, its error going as h^6, and most settle in one Newton-Raphson iteration; a leg
        followed closely, as between limit positions, is returned as it is, halving costing
        more there than it saves). Each middle is corrected from the quintic's by
        Newton-Raphson on [F(x); tau . (x - middle)] = 0, tau the quintic's unit tangent there
        (stacked bordered solves), and gets its tangent and curvature as a node does; a middle
        whose corrector does not converge within the step rules (``extend``) is left out, and
        without the curvature (``bending``) the nodes are returned as they are."""
        if leg.halved is not None:
            return leg.halved
        nodes = leg.arrays()
        leg.halved = nodes
        if self.bending is None or len(leg.s) < 2 or leg.gap <= HALVING_RESIDUAL:
            return nodes
        s, X, T, K = nodes
        segments = np.arange(s.size - 1)
        quintic = quintic_hermite(nodes, segments)
        middle = horner(quintic, 0.5)
        tau = horner(quintic[1:] * np.arange(1.0, 6.0)[:, None, None], 0.5)  # dx/du
        tau /= np.sqrt(np.einsum("ki,ki->k", tau, tau))[:, None]
        x, zero = middle, np.zeros(segments.size)
        try:
            F, J = self._f(x)
            for _ in range(CORRECTOR_ITERATIONS):
                if np.max(np.einsum("kr,kr->k", F, F)) <= NODE_TOLERANCE**2:
                    break
                x = x - _bordered_solves(J, tau, F, np.einsum("ki,ki->k", tau, x - middle))
                F, J = self._f(x)
            tangent = _bordered_solves(J, tau, np.zeros_like(F), np.ones(segments.size))
            tangent /= np.sqrt(np.einsum("ki,ki->k", tangent, tangent))[:, None]
            kappa = _bordered_solves(J, tangent, self.bending(x, tangent), zero)
        except np.linalg.LinAlgError:
            return nodes
        moved = np.sqrt(np.einsum("ki,ki->k", x - middle, x - middle))
        good = (np.einsum("kr,kr->k", F, F) <= NODE_TOLERANCE**2) & (
            moved <= MAX_CORRECTION * 0.5 * np.diff(s)
        )
        order = np.argsort(np.concatenate([2 * np.arange(s.size), 2 * segments[good] + 1]))
        X2, T2, K2 = (
            np.concatenate([a, b[good]])[order] for a, b in ((X, x), (T, tangent), (K, kappa))
        )
        chords = np.diff(X2, axis=0)
        chord = np.sqrt(np.einsum("ki,ki->k", chords, chords))
        squared = np.einsum("ki,ki->k", K2, K2)
        bend = 0.5 * (squared[1:] + squared[:-1])
        s2 = np.concatenate([[0.0], np.cumsum(_arc(chord, bend))])
        leg.halved = (s2, X2, T2, K2)
        return leg.halved

    def _segments(self, leg: Leg, sense: int, turns: Array) -> Array:
        """The coordinates at ``turns`` on the leg: in the segment between the nodes bracketing
        each, the u in [0, 1] where the quintic's driver turn is the turn (Newton-Raphson on the
        monotone t(u)), then the quintic there."""
        nodes = self.halved(leg)
        f = self.free
        t_nodes = sense * nodes[1][:, f]
        k = np.clip(np.searchsorted(t_nodes, sense * turns) - 1, 0, t_nodes.size - 2)
        quintic = quintic_hermite(nodes, k)
        turn = quintic[..., f]
        t0, t1 = nodes[1][k, f], nodes[1][k + 1, f]
        u = np.clip((turns - t0) / np.where(t1 != t0, t1 - t0, 1.0), 0.0, 1.0)
        slope = turn[1:] * np.arange(1.0, 6.0)[:, None]
        for _ in range(8):
            rate = horner(slope, u)
            step = (horner(turn, u) - turns) / np.where(rate != 0.0, rate, 1.0)
            u = np.clip(u - step, 0.0, 1.0)
            if np.max(np.abs(step)) <= 1e-12:  # the samples are polished from here
                break
        return horner(quintic, u[:, None])


# The quintic Hermite basis (value, first and second derivative at u = 0 and 1) as monomials:
# x(u) = sum_j u^j sum_i QUINTIC[j, i] data_i, data (x0, x0', x0'', x1'', x1', x1).
_QUINTIC = np.array([
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, 0.5, 0.0, 0.0, 0.0],
    [-10.0, -6.0, -1.5, 0.5, -4.0, 10.0],
    [15.0, 8.0, 1.5, -1.0, 7.0, -15.0],
    [-6.0, -3.0, -0.5, 0.5, -3.0, 6.0],
])  # fmt: skip
# The rate dx/du of the quintic at MONOTONE_AT as a matrix on its data (``_monotone``).
_MONOTONE_RATES = np.vander(MONOTONE_AT, 5, increasing=True) @ (
    _QUINTIC[1:] * np.arange(1.0, 6.0)[:, None]
)


def quintic_hermite(nodes: tuple[Array, Array, Array, Array], k: Array) -> Array:
    """The monomial coefficients (6, K, n) of the quintic Hermite interpolant in u in [0, 1] of
    segments k (node k to k + 1: positions, and tangents and curvatures in arclength, times the
    segment's arclength h and h^2); ``nodes`` from ``Leg.arrays``."""
    s, X, T, K = nodes
    h = (s[k + 1] - s[k])[:, None]
    data = np.stack([X[k], T[k] * h, K[k] * h * h, K[k + 1] * h * h, T[k + 1] * h, X[k + 1]])
    return np.tensordot(_QUINTIC, data, axes=1)


def horner(coefficients: Array, u: Array | float) -> Array:
    """sum_j coefficients[j] u^j by Horner's rule."""
    value = coefficients[-1]
    for c in coefficients[-2::-1]:
        value = value * u + c
    return value


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
    system = constraints.constraint_system(scene, group)
    samples = turns[0].size if turns else 1
    states = constraints.states({name: known[name] for name in system.known}, scene)
    polish = Polish(system, states, samples, continuation)
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
    tolerance = polish.tolerance
    message = f"Newton-Raphson closed the loop of {', '.join(group)}"
    if not np.all(converged):
        at = turns[0] if turns else np.zeros(samples)
        message = _failure(scene, group, at, polish.reached, worst, tolerance, polish.iterations)
    report = NewtonReport(
        tuple(group), converged, polish.iterations, worst, tolerance, message,
        continuation.tolerance,
    )  # fmt: skip
    return motions, report


class Polish:
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
        self.tolerance = newton.residual_tolerance(continuation.tolerance, system)
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
            self.q[todo], self.residual[todo], its, first, moved = self.newton_raphson(todo, q0)
            self.iterations = max(self.iterations, its)
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

    def newton_raphson(self, todo: Array, q0: Array) -> tuple[Array, Array, int, Array, Array]:
        """Newton-Raphson on the samples ``todo`` from ``q0`` (``newton.newton_rotations`` where
        the group's equations are linear in (q, cos, sin)): q, residuals, iterations, and the
        lengths of each sample's first step and of its whole move (rotations times the size)."""
        part = self.states
        if todo.size < self.q.shape[0]:
            part = {name: _take(s, todo) for name, s in self.states.items()}
        rotations, linear = self.system.rotations(todo.size), self.system.linear
        if rotations is None or linear is None:
            q, residual, its, first = newton.newton_raphson(
                self.system, part, q0, self.tolerance, polish=self.polish,
                max_iterations=POLISH_ITERATIONS,
            )  # fmt: skip
        else:
            q, residual, its, first = newton.newton_rotations(
                linear, rotations, linear.known_terms(part, todo.size, 0, None)[0], q0,
                self.size, self.tolerance, polish=self.polish, max_iterations=POLISH_ITERATIONS,
            )  # fmt: skip
        step = (q - q0) * self.weights
        return q, residual, its, first, np.sqrt(np.einsum("mi,mi->m", step, step))


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
