"""The typical mistakes for a scene, each with the wrong number a student would get.

Only mistakes that apply to the scene are listed: a Coriolis factor of 2 where a slot turns, the
Coriolis term on a fixed guide where a slider's link turns, omega^2 with the wrong sign, the
cross product in the wrong order, the unknowns of a dyad mixed up, omega written for alpha, and,
for moving points and spatial chains, the mistakes of seeds 002 and 003 (ERRATA.md). The wrong
value is computed by making exactly that mistake with the solver's numbers, and shown next to
the right one. Each mistake's id and title are its entry in the catalogue
(``solver.teaching.mistakes``), which the exercise checker names its diagnoses by too.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from itertools import pairwise

import numpy as np

from solver.kinematics.relative_motion import MovingPointMotion, coriolis_acceleration
from solver.kinematics.rigid import omega_cross, perp, solve_2x2
from solver.kinematics.spatial import SpatialAnalysis, SpatialChain
from solver.model.scene import MovingPoint
from solver.position.topology import CircleSpec, DriverStep, DyadStep, LeverStep, LineSpec
from solver.solutions.format import Formatter
from solver.solutions.groups import solution_group
from solver.solutions.linkage import LinkageContext, SlotMotion
from solver.solutions.model import Mistake, Step, Value
from solver.teaching.mistakes import (
    alpha_squared,
    coriolis_with_omega_of,
    coriolis_without_factor_2,
    cross_order,
    normal_term_sign,
    omega_for_alpha,
    typical_mistake,
)


def _value(fmt: Formatter, value: float | np.ndarray, unit: str) -> Value:
    number: float | tuple[float, ...]
    number = tuple(float(x) for x in value) if isinstance(value, np.ndarray) else float(value)
    return Value(number, unit, fmt.display(number, unit))


def _mistake(
    fmt: Formatter,
    kind: str,
    text: str,
    wrong: float | np.ndarray,
    right: float | np.ndarray,
    unit: str,
    *anchors: tuple[str, str],
) -> Mistake:
    """The catalogue's mistake ``kind`` (its title) with this scene's text and its wrong and
    right values."""
    w, r = _value(fmt, wrong, unit), _value(fmt, right, unit)
    return Mistake(
        kind,
        typical_mistake(kind).title,
        f"{text} Wrong: {w.display}; right: {r.display}.",
        {"wrong": w, "right": r},
        anchors,
    )


def place_mistakes(steps: Sequence[Step], mistakes: Sequence[Mistake], loop: bool) -> list[Mistake]:
    """Each mistake with the index of the step it belongs to (its first anchor found among the
    steps: kind prefix and part of the title). A mistake whose step is not in this solution is
    left out; in a loop-method solution only the loop's and the moving points' steps count."""
    placed = []
    for mistake in mistakes:
        for kind, part in mistake.anchors:
            found = next(
                (
                    i
                    for i, step in enumerate(steps)
                    if step.kind.startswith(kind) and part in step.title
                ),
                None,
            )
            if found is None:
                continue
            if not loop or steps[found].kind.startswith(("loop.", "relative.")):
                placed.append(replace(mistake, step=found))
            break
    return placed


def _round2(x: float) -> float:
    """x rounded to two significant digits (0.3464 -> 0.35), as a hand solution rounds."""
    return float(f"{x:.1e}") if x else 0.0


def _solve2(columns: tuple[np.ndarray, np.ndarray], rhs: np.ndarray) -> np.ndarray:
    """x with x0 columns[0] + x1 columns[1] = rhs (``rigid.solve_2x2``)."""
    first, second = columns
    solved = solve_2x2((first[0], second[0]), (first[1], second[1]), (rhs[0], rhs[1]))
    return np.array(solved, dtype=float)


def _lever_anchors(step: LeverStep) -> tuple[tuple[str, str], ...]:
    """Where a slip in a lever's Coriolis term shows: its Coriolis, lever or loop step."""
    return (
        ("acceleration.coriolis", step.pin),
        ("acceleration.lever", step.pin),
        ("loop.acceleration", ""),
    )


class LinkageMistakes:
    def __init__(self, ctx: LinkageContext) -> None:
        self.ctx = ctx
        self.fmt = ctx.fmt
        self.out: list[Mistake] = []

    def nonzero(self, value: float | np.ndarray, unit: str) -> bool:
        if isinstance(value, np.ndarray):
            return not all(x == 0.0 for x in self.fmt.clean_vector(tuple(value), unit))
        return not self.fmt.is_zero(value, unit)

    # --- Coriolis -------------------------------------------------------------------------------

    def coriolis(self) -> None:
        ctx = self.ctx
        plan = ctx.analysis.plan
        for step in plan.steps:
            group = solution_group(step)
            if group is not None:
                group.coriolis_mistakes(self, step)

    def lever_coriolis(self, step: LeverStep) -> None:
        """a_Cor = 2 omega x v_rel of a pin in a turning lever's slot: the slips of the factor 2
        and of the absolute velocity."""
        slot = self.ctx.slot(step.link, step.pin)
        assert slot.coriolis_acceleration is not None
        if not (
            self.nonzero(slot.omega_guide, "rad/s") and self.nonzero(slot.relative_velocity, "m/s")
        ):
            return
        self.lever_factor_2(step, slot)
        v_abs = self.ctx.vel(step.pin)
        if self.nonzero(v_abs - slot.relative_velocity, "m/s"):
            self.lever_absolute_velocity(step, slot, v_abs)

    def lever_alpha_without_2(self, step: LeverStep, slot: SlotMotion) -> float:
        """The lever's alpha from a_P = a_O + alpha k x r - omega^2 r + a_rel u + a_Cor with
        a_Cor halved: [k x r, u] (alpha, a_rel) = a_P - a_O + omega^2 r - omega k x v_rel."""
        ctx = self.ctx
        r = ctx.pos(step.pin) - ctx.pos(step.pivot)
        base = ctx.acc(step.pin) - ctx.acc(step.pivot) + ctx.omega(step.link) ** 2 * r
        assert slot.coriolis_acceleration is not None
        half = coriolis_without_factor_2(slot.coriolis_acceleration)
        alpha: float = _solve2((perp(r), slot.direction), base - half)[0]
        return alpha

    def lever_factor_2(self, step: LeverStep, slot: SlotMotion) -> None:
        """omega x v_rel for 2 omega x v_rel, and the lever's alpha that follows from it."""
        fmt = self.fmt
        assert slot.coriolis_acceleration is not None
        alpha_wrong = self.lever_alpha_without_2(step, slot)
        self.out.append(
            _mistake(
                fmt,
                "coriolis_without_factor_2",
                f"The Coriolis acceleration of {step.pin} in the turning slot of {step.link} is "
                f"2 omega({step.link}) x v_rel, twice omega x v_rel: half comes from the relative "
                "velocity turning with the slot, half from the slot carrying the point to places "
                "that move faster. Without the 2, a_Cor is wrong and so is the lever's angular "
                f"acceleration: alpha({step.link}) would come out as "
                f"{fmt.text_value(alpha_wrong, 'rad/s^2')} instead of "
                f"{fmt.text_value(self.ctx.alpha(step.link), 'rad/s^2')}.",
                coriolis_without_factor_2(slot.coriolis_acceleration),
                slot.coriolis_acceleration,
                "m/s^2",
                *_lever_anchors(step),
            )
        )

    def lever_absolute_velocity(self, step: LeverStep, slot: SlotMotion, v_abs: np.ndarray) -> None:
        """2 omega x v_abs for 2 omega x v_rel."""
        fmt = self.fmt
        assert slot.coriolis_acceleration is not None
        self.out.append(
            _mistake(
                fmt,
                "coriolis.absolute_velocity",
                f"a_Cor = 2 omega({step.link}) x v_rel uses the velocity of {step.pin} "
                f"relative to the slot ({fmt.text_vector(tuple(slot.relative_velocity), 'm/s')}), "
                f"not its absolute velocity ({fmt.text_vector(tuple(v_abs), 'm/s')}).",
                coriolis_acceleration(np.asarray(slot.omega_guide), v_abs),
                slot.coriolis_acceleration,
                "m/s^2",
                *_lever_anchors(step),
            )
        )

    def slot_coriolis(self, step: DyadStep, spec: LineSpec) -> None:
        """a_Cor = 2 omega_guide x v_rel of a dyad's point in a slot: none on a fixed guide, the
        factor 2 in a turning one."""
        ctx = self.ctx
        slot = ctx.slot(spec.guide, step.point)
        assert slot.coriolis_acceleration is not None
        if spec.guide == ctx.scene.ground:
            self.fixed_guide_coriolis(step, slot)
            return
        if self.nonzero(slot.omega_guide, "rad/s") and self.nonzero(slot.relative_velocity, "m/s"):
            self.out.append(
                _mistake(
                    self.fmt,
                    "coriolis_without_factor_2",
                    f"The Coriolis acceleration of {step.point} in the turning slot of "
                    f"{spec.guide} is 2 omega({spec.guide}) x v_rel, not omega x v_rel.",
                    coriolis_without_factor_2(slot.coriolis_acceleration),
                    slot.coriolis_acceleration,
                    "m/s^2",
                    ("acceleration.coriolis", step.point),
                    ("loop.acceleration", ""),
                )
            )

    def fixed_guide_coriolis(self, step: DyadStep, slot: SlotMotion) -> None:
        """2 omega_follower x v_rel on a fixed guide, where a_Cor = 0, and what it does to the
        circle's link: [k x r, -u] (alpha, a_rel) = a_Cor - (a_C - omega^2 r)."""
        ctx, fmt, point = self.ctx, self.fmt, step.point
        follower = slot.joint.follower
        omega_f = ctx.omega(follower)
        if not (self.nonzero(omega_f, "rad/s") and self.nonzero(slot.relative_velocity, "m/s")):
            return
        assert slot.coriolis_acceleration is not None
        wrong = coriolis_with_omega_of(omega_f, slot.relative_velocity)
        consequence = ""
        circle = next((s for s in step.loci if isinstance(s, CircleSpec)), None)
        if circle is not None:
            r = ctx.pos(point) - ctx.pos(circle.center)
            base = ctx.acc(circle.center) - ctx.omega(circle.link) ** 2 * r
            alpha_wrong = _solve2((perp(r), -slot.direction), wrong - base)[0]
            consequence = (
                f" Carried into the equations it gives alpha({circle.link}) = "
                f"{fmt.text_value(alpha_wrong, 'rad/s^2')} instead of "
                f"{fmt.text_value(ctx.alpha(circle.link), 'rad/s^2')}."
            )
        self.out.append(
            _mistake(
                fmt,
                "coriolis_on_fixed_guide",
                f"{point} slides in a slot fixed in the ground. The Coriolis term is "
                "2 omega_guide x v_rel with the angular velocity of the guide, which is zero; "
                f"the angular velocity of link {follower} ({fmt.text_value(omega_f, 'rad/s')}) "
                f"does not belong in it." + consequence,
                wrong,
                slot.coriolis_acceleration,
                "m/s^2",
                ("acceleration.coriolis", point),
            )
        )

    # --- signs and orders -----------------------------------------------------------------------

    def first_rotation(self) -> tuple[str, str, str] | None:
        """(link, pivot, point) of the first driven link with a turning rate and a second point."""
        ctx = self.ctx
        for step in ctx.analysis.plan.steps:
            if isinstance(step, DriverStep) and self.nonzero(ctx.omega(step.link), "rad/s"):
                others = [p for p in ctx.scene.links[step.link].points if p != step.pivot]
                if others:
                    return step.link, step.pivot, others[0]
        return None

    def signs(self) -> None:
        """The slips with a driven link's rotation about its pivot O and a point P of it:
        a_P = a_O + alpha x r - omega^2 r and v_P = v_O + omega x r, r = r(O, P)."""
        found = self.first_rotation()
        if found is None:
            return
        link, pivot, point = found
        self.normal_sign(link, pivot, point)
        self.cross_order(link, pivot, point)
        if self.nonzero(self.ctx.alpha(link) - self.ctx.omega(link), "rad/s^2"):
            self.omega_for_alpha(link, pivot, point)

    def normal_sign(self, link: str, pivot: str, point: str) -> None:
        """+omega^2 r for the normal term -omega^2 r."""
        ctx, fmt = self.ctx, self.fmt
        r = ctx.pos(point) - ctx.pos(pivot)
        omega, alpha = ctx.omega(link), ctx.alpha(link)
        self.out.append(
            _mistake(
                fmt,
                "normal.sign",
                f"The normal (centripetal) acceleration of {point} about {pivot} is -omega^2 "
                f"r({pivot},{point}): it points from {point} back towards {pivot}, whatever the "
                f"sign of omega (omega^2 = ({fmt.text(omega, 'rad/s')})^2 = "
                f"{fmt.text(omega**2, '1/s^2')} is "
                "positive). Writing +omega^2 r turns it outwards.",
                normal_term_sign(ctx.acc(pivot), omega, alpha, r),
                ctx.acc(point),
                "m/s^2",
                ("acceleration.rigid", f"of {point} ("),
            )
        )

    def cross_order(self, link: str, pivot: str, point: str) -> None:
        """r x omega for omega x r: v_O - omega x r."""
        ctx = self.ctx
        r = ctx.pos(point) - ctx.pos(pivot)
        self.out.append(
            _mistake(
                self.fmt,
                "cross.order",
                f"v({point}) = v({pivot}) + omega x r({pivot},{point}); r x omega = -(omega x r) "
                "reverses the relative velocity. In the determinant, the row of omega comes before "
                "the row of r.",
                cross_order(ctx.vel(pivot), ctx.omega(link), r),
                ctx.vel(point),
                "m/s",
                ("velocity.rigid", f"of {point} ("),
            )
        )

    def omega_for_alpha(self, link: str, pivot: str, point: str) -> None:
        """omega x r for the tangential term alpha x r."""
        ctx, fmt = self.ctx, self.fmt
        r = ctx.pos(point) - ctx.pos(pivot)
        omega, alpha = ctx.omega(link), ctx.alpha(link)
        self.out.append(
            _mistake(
                fmt,
                "labels.omega_alpha",
                f"The tangential acceleration is alpha x r, with the angular acceleration "
                f"alpha({link}) = {fmt.text_value(alpha, 'rad/s^2')}; writing omega x r there "
                f"(omega({link}) = {fmt.text_value(omega, 'rad/s')}) mixes up the two labels.",
                omega_for_alpha(ctx.acc(pivot), omega, r),
                ctx.acc(point),
                "m/s^2",
                ("acceleration.rigid", f"of {point} ("),
            )
        )

    def unknowns(self) -> None:
        """An RRR dyad: two different links, two different unknowns. The slip takes the driven
        link's omega for the unknown one in v_P = v_C + omega x r(C, P), at the first dyad whose
        circle is centred on a driven link."""
        ctx = self.ctx
        drivers = {s.link for s in ctx.analysis.plan.steps if isinstance(s, DriverStep)}
        for step in ctx.analysis.plan.steps:
            group = solution_group(step)
            circles = group.circles(step) if group is not None else []
            if not circles:
                continue
            known = next(
                (d for d in drivers if circles[0].center in ctx.scene.links[d].points), None
            )
            if known is not None and known != circles[0].link:
                assert isinstance(step, DyadStep)  # a point on circles: a dyad's
                self.which_link(step, circles, known)
                return

    def which_link(self, step: DyadStep, circles: list[CircleSpec], known: str) -> None:
        """v_C + omega(known) x r(C, P) for v_C + omega(first) x r(C, P)."""
        ctx, fmt, first = self.ctx, self.fmt, circles[0]
        r = ctx.pos(step.point) - ctx.pos(first.center)
        text = (
            f"In v({step.point}) = v({first.center}) + omega x r({first.center},"
            f"{step.point}), omega is the unknown angular velocity of link "
            f"{first.link}, not the known omega({known}) of the driven link."
        )
        if len(circles) == 2:
            second = circles[1].link
            text += (
                f" The two unknowns belong to different links: omega({first.link}) ="
                f" {fmt.text_value(ctx.omega(first.link), 'rad/s')} and "
                f"omega({second}) = {fmt.text_value(ctx.omega(second), 'rad/s')} "
                f"(likewise alpha({first.link}) = "
                f"{fmt.text_value(ctx.alpha(first.link), 'rad/s^2')} and "
                f"alpha({second}) = {fmt.text_value(ctx.alpha(second), 'rad/s^2')});"
                " giving them one symbol mixes them up."
            )
        self.out.append(
            _mistake(
                fmt,
                "unknowns.which_link",
                text,
                ctx.vel(first.center) + omega_cross(ctx.omega(known), r),
                ctx.vel(step.point),
                "m/s",
                ("velocity.dyad.side", f"through link {first.link}"),
                ("velocity.dyad", step.point),
            )
        )

    # --- moving points --------------------------------------------------------------------------

    def moving_points(self) -> None:
        """The slips with a point moving on a link (seed 003): the carrier's rate in v_rel, the
        factor 2 of a_Cor = 2 omega x v_rel, a_Cor on a translating carrier, the sense of
        a_rel^tau and the transport velocity taken at the path's centre."""
        moving: dict[str, MovingPointMotion] = getattr(self.ctx.analysis, "moving_points", {}) or {}
        for mp in self.ctx.scene.moving_points:
            m = moving.get(mp.name)
            if m is None:
                continue
            centre = self.turning_arc_centre(mp, m)
            if centre is not None:
                self.carrier_rate(mp, m, centre)
                self.coriolis_factor(mp, m)
            self.translating_carrier(mp, m)
            self.tangential_sense(mp, m)
            if centre is not None:
                self.transport_point(mp, m, centre)

    def turning_arc_centre(self, mp: MovingPoint, m: MovingPointMotion) -> str | None:
        """The centre of an arc path on a carrier that turns (omega != 0), else None."""
        if mp.path.type == "arc" and self.nonzero(float(m.omega_carrier), "rad/s"):
            return mp.path.center
        return None

    def carrier_rate(self, mp: MovingPoint, m: MovingPointMotion, centre: str) -> None:
        """v_rel = s_dot tau; the slip adds the carrier's rotation, v_rel + omega R tau."""
        v_rel = np.asarray(m.relative_velocity)
        speed = float(np.hypot(*v_rel))
        if speed == 0:
            return
        radius = float(np.hypot(*(np.asarray(m.position) - self.ctx.pos(centre))))
        tau = v_rel / speed * np.sign(float(m.s_dot) or 1.0)
        self.out.append(
            _mistake(
                self.fmt,
                "relative.carrier_rate",
                f"The relative velocity of {mp.name} is what an observer on {mp.link} "
                "sees: s-dot along the path's tangent. Adding the carrier's rotation "
                "(R (theta-dot + phi-dot)) counts the transport motion twice.",
                v_rel + float(m.omega_carrier) * radius * tau,
                v_rel,
                "m/s",
                ("relative.relative_velocity", mp.name),
            )
        )

    def coriolis_factor(self, mp: MovingPoint, m: MovingPointMotion) -> None:
        """a_Cor = 2 omega x v_rel; the slip drops the 2."""
        self.out.append(
            _mistake(
                self.fmt,
                "coriolis_without_factor_2",
                f"a_Cor({mp.name}) = 2 omega({mp.link}) x v_rel, not omega x v_rel.",
                coriolis_without_factor_2(np.asarray(m.coriolis_acceleration)),
                np.asarray(m.coriolis_acceleration),
                "m/s^2",
                ("relative.coriolis", mp.name),
            )
        )

    def turning_neighbour(self, link: str) -> str | None:
        """A link that turns (omega != 0) and is pinned to ``link`` by a revolute joint."""
        ctx = self.ctx
        for joint in ctx.scene.joints:
            if joint.type != "revolute" or link not in joint.links:
                continue
            other = joint.links[0] if joint.links[1] == link else joint.links[1]
            if self.nonzero(ctx.omega(other), "rad/s"):
                return other
        return None

    def translating_carrier(self, mp: MovingPoint, m: MovingPointMotion) -> None:
        """a_Cor = 2 omega_carrier x v_rel = 0 on a translating carrier; the slip takes the
        omega of the turning link that drives it."""
        v_rel = np.asarray(m.relative_velocity)
        if self.nonzero(float(m.omega_carrier), "rad/s") or not self.nonzero(v_rel, "m/s"):
            return
        other = self.turning_neighbour(mp.link)
        if other is None:
            return
        self.out.append(
            _mistake(
                self.fmt,
                "coriolis.translating_carrier",
                f"The carrier {mp.link} translates (omega = 0), so a_Cor = 0 even though link "
                f"{other} that drives it turns (omega({other}) = "
                f"{self.fmt.text_value(self.ctx.omega(other), 'rad/s')}); the Coriolis term "
                "uses the carrier's angular velocity only.",
                coriolis_with_omega_of(self.ctx.omega(other), v_rel),
                np.asarray(m.coriolis_acceleration),
                "m/s^2",
                ("relative.coriolis", mp.name),
            )
        )

    def tangential_sense(self, mp: MovingPoint, m: MovingPointMotion) -> None:
        """a_rel = a_rel^n + s_ddot tau; the slip reverses the tangential part:
        a_rel - 2 a_rel^tau."""
        tangential = np.asarray(m.relative_tangential)
        if mp.path.type != "arc" or not self.nonzero(tangential, "m/s^2"):
            return
        self.out.append(
            _mistake(
                self.fmt,
                "relative.tangential_sense",
                f"a_rel^tau = s-double-dot tau points along the direction of increasing s "
                f"({mp.path.direction} on the arc). Writing it as eps_rel x r with "
                "eps_rel counter-clockwise when M runs clockwise (seed 003, task 1) "
                "reverses it.",
                np.asarray(m.relative_acceleration) - 2.0 * tangential,
                np.asarray(m.relative_acceleration),
                "m/s^2",
                ("relative.relative_acceleration", mp.name),
            )
        )

    def transport_point(self, mp: MovingPoint, m: MovingPointMotion, centre: str) -> None:
        """v_transport = v of the carrier's point at M; the slip takes the path centre's v."""
        self.out.append(
            _mistake(
                self.fmt,
                "relative.transport_point",
                "The transport velocity is the velocity of the carrier's point that "
                f"coincides with {mp.name} (omega x r to {mp.name}), not that of the "
                f"path's centre {centre} or of another reference point.",
                self.ctx.vel(centre),
                np.asarray(m.transport_velocity),
                "m/s",
                ("relative.transport_velocity", mp.name),
            )
        )

    # --- the other slips of the seeds (ERRATA.md) ------------------------------------------------

    def alpha_squared(self) -> None:
        """E000-T2-4: -(-3)^2 r, the angular acceleration squared in the normal term."""
        ctx, fmt = self.ctx, self.fmt
        found = self.first_rotation()
        if found is None:
            return
        link, pivot, point = found
        omega, alpha = ctx.omega(link), ctx.alpha(link)
        if not self.nonzero(alpha**2 - omega**2, "1/s^2"):
            return
        r = ctx.pos(point) - ctx.pos(pivot)
        self.out.append(
            _mistake(
                fmt,
                "normal.alpha_squared",
                f"The normal term of {point} is -omega({link})^2 r = -("
                f"{fmt.text(omega, 'rad/s')})^2 r; seed 000 type 2 wrote -(-3)^2 with the angular "
                f"acceleration. With alpha({link})^2 = {fmt.text(alpha**2)} the acceleration "
                "comes out wrong.",
                alpha_squared(ctx.acc(pivot), omega, alpha, r),
                ctx.acc(point),
                "m/s^2",
                ("acceleration.rigid", f"of {point} ("),
                ("loop.acceleration", ""),
            )
        )

    def trigonometry(self) -> None:
        """E000-T3-1: cos phi = 0.3/0.4 (the wrong sides) where sin phi = 0.3/0.5."""
        ctx, fmt = self.ctx, self.fmt
        drivers = {s.link for s in ctx.analysis.plan.steps if isinstance(s, DriverStep)}
        for link in ctx.scene.moving_links:
            points = ctx.scene.links[link].points
            if link in drivers or len(points) < 2:
                continue
            d = np.array(fmt.clean_vector(tuple(ctx.pos(points[1]) - ctx.pos(points[0])), "m"))
            length = float(np.hypot(*d))
            right = math.degrees(math.atan2(d[1], d[0]))
            wrong = math.degrees(math.acos(abs(d[1]) / length))
            if abs(abs(right) - wrong) < 1e-3:
                continue
            self.out.append(
                _mistake(
                    fmt,
                    "position.trigonometry",
                    f"The angle of link {link} ({points[0]} to {points[1]}) has cos = dx/L = "
                    f"{fmt.text(d[0])}/{fmt.text(length)} and sin = dy/L = {fmt.text(d[1])}/"
                    f"{fmt.text(length)}, both; its quadrant follows from the signs (atan2). "
                    "Taking the cosine of the height over the length (seed 000 type 3 wrote "
                    "cos phi = 0.3/0.4 for sin phi = 0.3/0.5) gives another angle, and every "
                    "vector after it is wrong.",
                    wrong,
                    right,
                    "deg",
                    ("loop.position", ""),
                    ("positions", ""),
                )
            )
            return

    def pole_velocity(self) -> None:
        """E000-T1-5: the velocity pole from C computed with a velocity that is not v_C."""
        ctx, fmt = self.ctx, self.fmt
        for link in ctx.scene.moving_links:
            result = ctx.analysis.links[link]
            points = ctx.scene.links[link].points
            if result.velocity_pole is None or ctx.ground_pivot(link) is not None:
                continue
            if len(points) < 2:
                continue
            x, y = points[1], points[0]
            omega = ctx.omega(link)
            if not self.nonzero(ctx.vel(x) - ctx.vel(y), "m/s"):
                continue
            r_wrong = -perp(ctx.vel(y)) / omega  # v_Y = omega x r  =>  r = -perp(v) / omega
            self.out.append(
                _mistake(
                    fmt,
                    "poles.wrong_velocity",
                    f"v({x}) = omega({link}) x r(P,{x}) must use the velocity of {x} itself "
                    f"({fmt.text_vector(tuple(ctx.vel(x)), 'm/s')}); with the velocity of {y} "
                    f"({fmt.text_vector(tuple(ctx.vel(y)), 'm/s')}) the pole lands elsewhere "
                    "(seed 000 type 1 used (0.5, 0, 0) for v_C = (1, 0.5, 0)).",
                    ctx.pos(x) - r_wrong,
                    np.asarray(result.velocity_pole),
                    "m",
                    ("poles.velocity", f"link {link}"),
                )
            )
            return

    def rounding(self) -> None:
        """E000-T2-6: x = sqrt(0.12) = 0.346 rounded to 0.35 changes the crank's length. Only
        where it can happen: the inputs are the drawn coordinates (the data), not the pose at the
        instant analysed (seed 003 Task 2's plate has turned by then, its data are exact)."""
        ctx, fmt = self.ctx, self.fmt
        drawn = ctx.scene.drawn
        rounded = {p: np.array([_round2(c) for c in drawn(p)]) for p in ctx.scene.points}
        worst = None
        for link in ctx.scene.links:
            points = ctx.scene.links[link].points
            for a, b in pairwise(points):
                exact = float(np.hypot(*(drawn(b) - drawn(a))))
                approx = float(np.hypot(*(rounded[b] - rounded[a])))
                change = abs(approx - exact) / exact if exact > 0 else 0.0
                if change > 1e-3 and (worst is None or change > worst[0]):
                    worst = (change, link, a, b, approx, exact)
        if worst is None:
            return
        _, link, a, b, approx, exact = worst
        self.out.append(
            _mistake(
                fmt,
                "inputs.rounding",
                f"Rounded to two significant digits, the coordinates of {a} and {b} no longer "
                f"give the length of link {link}: |{a}{b}| becomes {fmt.text(approx)} m instead of "
                f"{fmt.text(exact)} m. Seed 000 type 2 rounded the pivot's x = 0.346 m to 0.35 m: "
                "its ground became 0.35 m instead of 0.3464 m, and the crank pin drawn from it "
                "0.4031 m from the pivot instead of 0.4 m, another mechanism. Keep the inputs "
                "exact (or round all of them from "
                "the same geometry) and round only the results.",
                approx,
                exact,
                "m",
                ("loop.position", ""),
                ("positions", ""),
            )
        )

    def all(self) -> list[Mistake]:
        self.coriolis()
        self.unknowns()
        self.signs()
        self.alpha_squared()
        self.trigonometry()
        self.pole_velocity()
        self.rounding()
        self.moving_points()
        seen: set[tuple[str, str]] = set()
        unique = []
        for m in self.out:
            key = (m.kind, m.text)
            if key not in seen:
                seen.add(key)
                unique.append(m)
        return unique


def linkage_mistakes(ctx: LinkageContext) -> list[Mistake]:
    """The typical mistakes for a planar linkage (with or without moving points)."""
    return LinkageMistakes(ctx).all()


# What every spatial solution warns about, with no number to compute.
SPATIAL_NOTES = (
    Mistake(
        "spatial.unit_vectors",
        typical_mistake("spatial.unit_vectors").title,
        "Unit vectors cross in cyclic order: E1 x E2 = E3, E2 x E3 = E1, E3 x E1 = "
        "E2 (and reversed order gives the minus sign). E3 x E1 is E2, not E1.",
        anchors=(("spatial.axis_rate", ""),),
    ),
    Mistake(
        "spatial.rigid_points",
        typical_mistake("spatial.rigid_points").title,
        "A point fixed in its body has v_rel = 0 and a_rel = 0: of the five terms "
        "only a_O, alpha x r and omega x (omega x r) remain. They reappear for a "
        "point carried by a prismatic joint.",
        anchors=(("spatial.point.acceleration", ""),),
    ),
)


def spatial_mistakes(
    chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter
) -> list[Mistake]:
    """The typical mistakes for a spatial chain (seed 002)."""
    found = (
        _axis_rate_mistake(chain, analysis, fmt),
        _centripetal_order_mistake(chain, analysis, fmt),
        _spatial_coriolis_mistake(chain, analysis, fmt),
    )
    return [m for m in found if m is not None] + list(SPATIAL_NOTES)


def _axis_rate_mistake(
    chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter
) -> Mistake | None:
    """alpha_k = alpha_{k-1} + rate_dot e + rate (omega x e); the slip leaves out the last term,
    at the first revolute joint where that changes alpha."""
    for joint in chain.joints:
        body = analysis.bodies[joint.name]
        if joint.type != "revolute" or joint.rate == 0 or np.linalg.norm(body.axis_rate) == 0:
            continue
        wrong = body.alpha - joint.rate * body.axis_rate
        scale = max(1.0, float(np.linalg.norm(body.alpha)))
        if float(np.linalg.norm(wrong - body.alpha)) > 1e-12 * scale:
            return _mistake(
                fmt,
                "spatial.axis_rate",
                f"Axis e({joint.name}) is fixed in the body before it, which turns: "
                "d/dt (rate e) = rate-dot e + rate (omega x e). Leaving out omega x e "
                f"gives a wrong alpha({joint.name}).",
                wrong,
                body.alpha,
                "rad/s^2",
                ("spatial.alpha", f"body {joint.name}"),
            )
    return None


def _centripetal_order_mistake(
    chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter
) -> Mistake | None:
    """omega x (omega x r) written (omega x r) x omega: a - 2 a_n, at the first point with one."""
    for point in chain.points:
        motion = analysis.points[point.name]
        if np.linalg.norm(motion.centripetal) > 0:
            return _mistake(
                fmt,
                "spatial.centripetal_order",
                f"The centripetal term of {point.name} is omega x (omega x r), pointing "
                "towards the axis; (omega x r) x omega has the opposite sign.",
                motion.acceleration - 2.0 * motion.centripetal,
                motion.acceleration,
                "m/s^2",
                ("spatial.point.acceleration", f"of {point.name}"),
            )
    return None


def _spatial_coriolis_mistake(
    chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter
) -> Mistake | None:
    """a_Cor = 2 omega x v_rel written without the 2: a - a_Cor / 2, at the first point with one."""
    for point in chain.points:
        motion = analysis.points[point.name]
        if float(np.linalg.norm(motion.coriolis)) > 0:
            return _mistake(
                fmt,
                "coriolis_without_factor_2",
                f"{point.name} is carried by a sliding joint in a turning body: its Coriolis "
                "term is 2 omega x v_rel, not omega x v_rel.",
                motion.acceleration - coriolis_without_factor_2(motion.coriolis),
                motion.acceleration,
                "m/s^2",
                ("spatial.point.acceleration", f"of {point.name}"),
            )
    return None


def loop_mistakes(ctx: LinkageContext) -> list[Mistake]:
    """Mistakes of the loop-closure method: the factor i of a derivative, a spurious i (E001-1)."""
    fmt = ctx.fmt
    out: list[Mistake] = []
    for step in ctx.analysis.plan.steps:
        if isinstance(step, DriverStep):
            others = [p for p in ctx.scene.links[step.link].points if p != step.pivot]
            if others and not fmt.is_zero(ctx.omega(step.link), "rad/s"):
                r = ctx.pos(others[0]) - ctx.pos(step.pivot)
                out.append(
                    _mistake(
                        fmt,
                        "loop.derivative_i",
                        f"Differentiating a e^(i theta) gives i a omega e^(i theta): the factor i "
                        f"turns the term 90 degrees, perpendicular to the link. Without it the "
                        f"velocity of {others[0]} would point along the crank.",
                        ctx.omega(step.link) * r,
                        ctx.vel(others[0]),
                        "m/s",
                        ("loop.velocity", ""),
                    )
                )
                break
    if any(
        "loop.real_slider" in group.loop_mistakes
        for group in map(solution_group, ctx.analysis.plan.steps)
        if group is not None
    ):
        out.append(
            Mistake(
                "loop.real_slider",
                typical_mistake("loop.real_slider").title,
                "s and its derivatives are real numbers: s-double-dot is the real part of the "
                "acceleration loop equation along the guide. An extra i in front of a term of "
                "s-double-dot (as in seed 001, eq. 10) would give it an imaginary part.",
                anchors=(("loop.acceleration", ""),),
            )
        )
    return out
