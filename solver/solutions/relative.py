"""Worked solution of a point M moving along a path fixed in a moving link (seed 003).

For each moving point, at the scene's instant t:

- the time law s(t) and its derivatives (exact, sympy), and M's place on the path;
- transport: the carrier's point coinciding with M, v_tr = v_A + omega x r_AM and
  a_tr = a_A + alpha x r_AM - omega^2 r_AM, with its tangential and normal parts;
- relative: v_rel = s' tau along the path tangent (no carrier rate in it),
  a_rel = s'' tau + (s'^2 / R) n, tangential and normal (towards the centre of the arc);
- Coriolis: a_cor = 2 omega_carrier x v_rel, or why it is zero (the carrier translates);
- v = v_tr + v_rel and a = a_tr + a_rel + a_cor;
- on an arc, the times at which M is opposite its start (s = pi R) and back at it (s = 2 pi R).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import sympy
from scipy.optimize import brentq

from solver.kinematics.relative_motion import MovingPointMotion
from solver.kinematics.rigid import perp
from solver.model.laws import parse_time_law
from solver.model.scene import MovingPoint
from solver.solutions import latex as tex
from solver.solutions.builder import Source, StepBuilder
from solver.solutions.format import latex_unit
from solver.solutions.linkage import (
    ACCELERATION,
    V0,
    VELOCITY,
    LinkageContext,
    det_row_z,
    k_cross,
    put_motion,
    split_part,
)
from solver.solutions.model import Step

EVENT_HORIZON = 60.0  # s: the event search looks this far ahead (the /events default t_max)
EVENT_SAMPLES = 6001


@dataclass(frozen=True)
class Carrier:
    """A turning link that carries a moving point: its rates now and their paths in the
    response (``source('omega')``, ``source('alpha')``)."""

    link: str
    omega: float
    alpha: float
    source: Callable[[str], Source | None]


@dataclass(frozen=True)
class TransportTerms:
    """The keys of v_tr = v_A + omega x r_AM (a_tr = a_A + alpha x r_AM - omega^2 r_AM): A's
    motion (``base``), the carrier's rates, r_AM and the rotation's terms."""

    origin: str  # the carrier's point A
    base: str
    omega: str
    r: str
    rotation: str  # omega x r (velocity) or alpha x r (acceleration)
    alpha: str = ""
    normal: str = ""


def transport_terms(
    b: StepBuilder,
    ctx: LinkageContext,
    carrier: Carrier,
    pair: tuple[str, str],
    r_np: np.ndarray,
    order: int,
    suffix: str = "",
) -> TransportTerms:
    """v_A, omega and omega x r_AM (a_A, omega, alpha, alpha x r_AM and -omega^2 r_AM) with
    r_AM = ``r_np``, A and M the ``pair``: the terms of the transport motion, put in ``b``."""
    a, m = pair
    base = put_motion(b, ctx, a, order)
    w = b.put(f"omega({carrier.link})", carrier.omega, "rad/s", carrier.source("omega"))
    if order == VELOCITY:
        r = b.put(f"r({a},{m})", r_np, "m")
        wxr = b.put(f"omega x r{suffix}", k_cross(carrier.omega, r_np), "m/s")
        return TransportTerms(a, base, w, r, wxr)
    al = b.put(f"alpha({carrier.link})", carrier.alpha, "rad/s^2", carrier.source("alpha"))
    r = b.put(f"r({a},{m})", r_np, "m")
    t = b.put(f"alpha x r{suffix}", k_cross(carrier.alpha, r_np), "m/s^2")
    n = b.put(f"normal{suffix}", -(carrier.omega**2) * r_np, "m/s^2")
    return TransportTerms(a, base, w, r, t, al, n)


def check_transport(b: StepBuilder, terms: TransportTerms, total: str) -> None:
    """total = v_A + omega x r (a_A + alpha x r - omega^2 r), each term checked."""
    if not terms.alpha:
        b.check("cross", terms.rotation, terms.omega, terms.r)
        b.check("sum", total, terms.base, terms.rotation)
        return
    b.check("cross", terms.rotation, terms.alpha, terms.r)
    b.check("product", terms.normal, terms.omega, terms.omega, terms.r, factor=-1.0)
    b.check("sum", total, terms.base, terms.rotation, terms.normal)


def origin_column(b: StepBuilder, ctx: LinkageContext, point: str, key: str) -> str:
    """The motion ``key`` of ``point`` as a column, 0 for a fixed point at rest."""
    return V0 if ctx.is_fixed(point) and b.is_zero(key) else b.col(key)


@dataclass(frozen=True)
class LawValues:
    """The keys of t, s(t), s'(t) and s''(t)."""

    t: str
    s: str
    s_dot: str
    s_ddot: str


@dataclass(frozen=True)
class ArcValues:
    """The keys of M = C + R (cos psi, sin psi): the centre C, R, psi and r_CM."""

    center: str
    radius: str
    psi: str
    r: str


@dataclass(frozen=True)
class LineValues:
    """The keys of M = P_0 + s u: the start P_0, u and r_P0M."""

    start: str
    u: str
    r: str


@dataclass(frozen=True)
class TransportParts:
    """The keys of a_tr's tangential and normal parts (along and across v_tr), of v_tr and of
    the check a_tr^n . v_tr = 0."""

    tangential: str
    normal: str
    velocity: str
    dot: str


@dataclass(frozen=True)
class RelativeAcceleration:
    """The keys of a_rel = s'' tau + (s'^2 / R) n: s', s'', tau, n, 1/R and the two parts."""

    s_dot: str
    s_ddot: str
    tau: str
    n: str
    curvature: str
    tangential: str
    normal: str


class MovingPointSteps:
    def __init__(self, ctx: LinkageContext, mp: MovingPoint, motion: MovingPointMotion) -> None:
        self.ctx = ctx
        self.mp = mp
        self.m = motion
        self.name = mp.name
        self.n = tex.name(mp.name)
        self.carrier = mp.link

    def src(self, field: str) -> tuple[str, ...]:
        return ("moving_points", self.name, field)

    def put(self, b: StepBuilder, name: str) -> str:
        """One part of v = v_tr + v_rel or a = a_tr + a_rel + a_cor of M (``name`` a field of
        the motion, e.g. 'transport_velocity'), with its path in the response."""
        key, unit = split_part(name, self.name)
        return b.put(key, getattr(self.m, name), unit, self.src(name))

    @property
    def turn(self) -> float:
        """+1 for an arc run counter-clockwise, -1 clockwise."""
        return 1.0 if self.mp.path.direction == "ccw" else -1.0

    def path_radius(self) -> float:
        """R = |P_0 - C|, the arc's radius on the drawing (P_0 its start, C its centre)."""
        route = self.mp.path
        assert route.center is not None
        drawn = self.ctx.scene.drawn
        return float(np.hypot(*(drawn(route.start) - drawn(route.center))))

    def tangent_normal(self) -> tuple[np.ndarray, np.ndarray, float]:
        """Unit tangent (increasing s), inward normal and curvature of the path at M, now."""
        ctx, route = self.ctx, self.mp.path
        position = np.asarray(self.m.position, dtype=float)
        if route.type == "line":
            assert route.through is not None
            u = ctx.pos(route.through) - ctx.pos(route.start)
            u = u / float(np.hypot(*u))
            return u, perp(u), 0.0
        assert route.center is not None
        radial = position - ctx.pos(route.center)
        radius = float(np.hypot(*radial))
        radial = radial / radius
        return self.turn * perp(radial), -radial, 1.0 / radius

    # --- the time law and the place on the path -------------------------------------------------

    def law_step(self) -> Step:
        """s = s(t), s' = ds/dt and s'' = d^2 s/dt^2 at the instant, then M on its path."""
        b = self.ctx.builder("relative.law", f"Moving point {self.name}: time law and position")
        law = self.law_values(b)
        self.law_lines(b, law)
        m = b.put(f"pos({self.name})", self.m.position, "m", self.src("position"))
        if self.mp.path.type == "arc":
            self.arc_lines(b, m, self.arc_values(b, m))
        else:
            self.line_lines(b, m, self.line_values(b, law, m))
        return b.build()

    def law_values(self, b: StepBuilder) -> LawValues:
        """t, s(t), s'(t) and s''(t), the solver's numbers with their paths."""
        return LawValues(
            b.put("t", self.ctx.scene.time, "s"),
            b.put("s", float(self.m.s), "m", self.src("s")),
            b.put("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot")),
            b.put("s_ddot", float(self.m.s_ddot), "m/s^2", self.src("s_ddot")),
        )

    def law_lines(self, b: StepBuilder, v: LawValues) -> None:
        """Write s(t), s'(t), s''(t) as formulas, then their values at t."""
        law, digits = parse_time_law(self.mp.s_law), self.ctx.fmt.digits
        b.line(
            rf"&s(t) = {tex.law(law.expression, digits)}, \quad \dot{{s}}(t) = "
            rf"{tex.law(law.first_derivative, digits)}, \quad \ddot{{s}}(t) = "
            rf"{tex.law(law.second_derivative, digits)}"
        )
        b.line(
            rf"&t = {b.numu(v.t)}: \quad s = {b.numu(v.s)}, \quad \dot{{s}} = "
            rf"{b.numu(v.s_dot)}, \quad \ddot{{s}} = {b.numu(v.s_ddot)}"
        )
        b.say(
            f"{self.name} moves along a path fixed in link {self.carrier}; its arc length from "
            f"{self.mp.path.start} is s(t) = {self.mp.s_law} (m). At t = {b.txt(v.t)}: s = "
            f"{b.txt(v.s)}, s-dot = {b.txt(v.s_dot)}, s-double-dot = {b.txt(v.s_ddot)}."
        )

    def arc_values(self, b: StepBuilder, m: str) -> ArcValues:
        """M = C + R (cos psi, sin psi), psi = psi_0 + theta_carrier +- s / R (psi_0 the drawn
        start's angle about C, + counter-clockwise)."""
        ctx, route = self.ctx, self.mp.path
        assert route.center is not None
        center = ctx.pos(route.center)
        c = b.put(f"pos({route.center})", center, "m", ("points", route.center, "position"))
        radius = self.path_radius()
        r = b.put("R", radius, "m")
        start = ctx.scene.drawn(route.start) - ctx.scene.drawn(route.center)
        theta = float(ctx.analysis.motion.links[self.carrier].theta[0])
        psi = math.atan2(start[1], start[0]) + theta + self.turn * float(self.m.s) / radius
        angle = b.put("angle", psi, "rad")
        d_key = f"r({route.center},{self.name})"
        d = b.put(d_key, np.asarray(self.m.position) - center, "m")
        b.check("phasor", d, r, angle)
        b.check("sum", m, c, d)
        return ArcValues(c, r, angle, d)

    def arc_lines(self, b: StepBuilder, m: str, v: ArcValues) -> None:
        """Write M = C + R (cos psi, sin psi) with the numbers."""
        route = self.mp.path
        assert route.center is not None
        sense = "counter-clockwise" if self.turn > 0 else "clockwise"
        b.line(
            rf"&\text{{arc about }} {tex.name(route.center)}, \; R = {b.numu(v.radius)}, \; "
            rf"\text{{{sense} from }} {tex.name(route.start)}: \; {self.n} = "
            rf"{tex.name(route.center)} + R\,(\cos\psi, \sin\psi), \; \psi = {b.numu(v.psi)}"
        )
        b.line(
            rf"&{self.n} = {b.point(v.center)} + {b.point(v.r)} = "
            rf"{tex.boxed_result(b.point(m) + latex_unit('m'))}"
        )
        b.say(
            f"The path is an arc of radius R = {b.txt(v.radius)} about {route.center}, run "
            f"{sense} from {route.start}; {self.name} is at the angle psi = {b.txt(v.psi)} on "
            f"it: {self.name} = {b.txt(m)}."
        )

    def line_values(self, b: StepBuilder, law: LawValues, m: str) -> LineValues:
        """M = P_0 + s u, u the unit vector from the line's start P_0 towards its second point."""
        ctx, route = self.ctx, self.mp.path
        assert route.through is not None
        start = ctx.pos(route.start)
        s0 = b.put(f"pos({route.start})", start, "m", ("points", route.start, "position"))
        u_np = ctx.pos(route.through) - start
        u = b.put("u", u_np / float(np.hypot(*u_np)), "")
        d = b.put(f"r({route.start},{self.name})", np.asarray(self.m.position) - start, "m")
        b.check("product", d, law.s, u)
        b.check("sum", m, s0, d)
        return LineValues(s0, u, d)

    def line_lines(self, b: StepBuilder, m: str, v: LineValues) -> None:
        """Write M = P_0 + s u with the numbers."""
        route = self.mp.path
        b.line(
            rf"&{self.n} = {tex.name(route.start)} + s\,\vec{{u}} = {b.point(v.start)} + "
            rf"{b.num('s')} \cdot {b.point(v.u)} = "
            rf"{tex.boxed_result(b.point(m) + latex_unit('m'))}"
        )
        b.say(
            f"The path is the line from {route.start} towards {route.through} (direction "
            f"{b.txtn(v.u)}): {self.name} = {b.txt(m)}."
        )

    # --- velocity -------------------------------------------------------------------------------

    def transport(self, b: StepBuilder, order: int) -> TransportTerms:
        """The terms of v_tr = v_A + omega x r_AM (a_tr = a_A + alpha x r_AM - omega^2 r_AM), A
        the carrier's reference point."""
        a = self.ctx.reference_point(self.carrier)
        carrier = Carrier(
            self.carrier,
            float(self.m.omega_carrier),
            float(self.m.alpha_carrier),
            lambda rate: self.src(f"{rate}_carrier"),
        )
        r_np = np.asarray(self.m.position) - self.ctx.pos(a)
        return transport_terms(b, self.ctx, carrier, (a, self.name), r_np, order)

    def velocity_steps(self) -> list[Step]:
        """v_tr, v_rel and v = v_tr + v_rel of M, one step each."""
        return [
            self.transport_velocity_step(),
            self.relative_velocity_step(),
            self.absolute_velocity_step(),
        ]

    def transport_velocity_step(self) -> Step:
        """v_tr = v_A + omega x r_AM: the velocity of the carrier's point under M."""
        ctx, carrier = self.ctx, self.carrier
        b = ctx.builder("relative.transport_velocity", f"Transport velocity of {self.name}")
        v = self.transport(b, VELOCITY)
        tr = self.put(b, "transport_velocity")
        check_transport(b, v, tr)
        a = v.origin
        b.line(
            rf"&\vec{{v}}_{{{self.n},\mathrm{{tr}}}} = \vec{{v}}_{{{tex.name(a)}}} + "
            rf"\vec{{\omega}}_{{{tex.name(carrier)}}} \times "
            rf"\vec{{r}}_{{{tex.pair(a, self.name)}}} = {origin_column(b, ctx, a, v.base)} + "
            rf"{tex.determinant3(det_row_z(b, v.omega), b.entries(v.r))} = "
            rf"{tex.boxed_result(b.colu(tr))}"
        )
        if b.is_zero(v.omega):
            b.say(
                f"The carrier {carrier} translates at this instant (omega = 0): every point of "
                f"it, including the one under {self.name}, moves like {a}: v_tr = {b.txt(tr)}."
            )
        else:
            b.say(
                f"Transport velocity: the velocity of the point of {carrier} under "
                f"{self.name}, v({a}) + omega({carrier}) cross r({a},{self.name}) = "
                f"{b.txt(v.base)} + {b.txt(v.rotation)} = {b.txt(tr)}."
            )
        return b.build()

    def relative_velocity_step(self) -> Step:
        """v_rel = s' tau, tau the path's unit tangent (the carrier's rate does not enter)."""
        b = self.ctx.builder("relative.relative_velocity", f"Relative velocity of {self.name}")
        sd = b.put("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot"))
        t = b.put("tau", self.tangent_normal()[0], "")
        rel = self.put(b, "relative_velocity")
        b.check("product", rel, sd, t)
        b.line(
            rf"&\vec{{v}}_{{{self.n},\mathrm{{rel}}}} = \dot{{s}}\,\vec{{\tau}} = "
            rf"{b.num(sd)} \cdot {b.col(t)} = {tex.boxed_result(b.colu(rel))}"
        )
        b.say(
            f"Relative velocity: along the path's tangent tau = {b.txtn(t)} (the direction of "
            f"increasing s), v_rel = s-dot tau = {b.txt(rel)}. It is the velocity an observer "
            f"on {self.carrier} sees: the carrier's rate does not enter it."
        )
        return b.build()

    def absolute_velocity_step(self) -> Step:
        """v = v_tr + v_rel."""
        b = self.ctx.builder("relative.velocity", f"Absolute velocity of {self.name}")
        tr = self.put(b, "transport_velocity")
        rel = self.put(b, "relative_velocity")
        v = self.put(b, "velocity")
        b.check("sum", v, tr, rel)
        b.line(
            rf"&\vec{{v}}_{{{self.n}}} = \vec{{v}}_{{{self.n},\mathrm{{tr}}}} + "
            rf"\vec{{v}}_{{{self.n},\mathrm{{rel}}}} = {b.col(tr)} + {b.col(rel)} = "
            rf"{tex.boxed_result(b.colu(v))}"
        )
        b.say(f"v({self.name}) = v_tr + v_rel = {b.txt(tr)} + {b.txt(rel)} = {b.txt(v)}.")
        return b.build()

    # --- acceleration ---------------------------------------------------------------------------

    def acceleration_steps(self) -> list[Step]:
        """a_tr, a_rel, a_Cor and a = a_tr + a_rel + a_Cor of M, one step each."""
        return [
            self.transport_acceleration_step(),
            self.relative_acceleration_step(),
            self.coriolis_step(),
            self.absolute_acceleration_step(),
        ]

    def transport_acceleration_step(self) -> Step:
        """a_tr = a_A + alpha x r_AM - omega^2 r_AM, and its parts along and across v_tr."""
        b = self.ctx.builder(
            "relative.transport_acceleration", f"Transport acceleration of {self.name}"
        )
        terms = self.transport(b, ACCELERATION)
        tr = self.put(b, "transport_acceleration")
        check_transport(b, terms, tr)
        self.transport_acceleration_lines(b, terms, tr, self.transport_parts(b, tr))
        return b.build()

    def transport_parts(self, b: StepBuilder, tr: str) -> TransportParts:
        """a_tr = a_tr^tau + a_tr^n, a_tr^n . v_tr = 0 (the normal part is across v_tr)."""
        tt = b.put(
            "a_tr tangential",
            self.m.transport_tangential,
            "m/s^2",
            self.src("transport_tangential"),
        )
        tn = b.put("a_tr normal", self.m.transport_normal, "m/s^2", self.src("transport_normal"))
        vtr = self.put(b, "transport_velocity")
        normal, velocity = self.m.transport_normal, self.m.transport_velocity
        d = b.put(
            "a_tr normal . v_tr",
            float(np.dot(normal, velocity)),
            "m^2/s^3",
            reference=float(np.hypot(*normal) * np.hypot(*velocity)),
        )
        b.check("sum", tr, tt, tn)
        b.check("dot", d, tn, vtr)
        return TransportParts(tt, tn, vtr, d)

    def transport_acceleration_lines(
        self, b: StepBuilder, v: TransportTerms, tr: str, parts: TransportParts
    ) -> None:
        """Write a_tr = a_A + alpha x r - omega^2 r, then its parts a_tr^tau and a_tr^n."""
        sub, k, a = self.n, tex.name(self.carrier), v.origin
        base = origin_column(b, self.ctx, a, v.base)
        b.line(
            rf"&\vec{{a}}_{{{sub},\mathrm{{tr}}}} = \vec{{a}}_{{{tex.name(a)}}} + "
            rf"\vec{{\alpha}}_{{{k}}} \times \vec{{r}} - \omega_{{{k}}}^2\,\vec{{r}} = {base} + "
            rf"{tex.determinant3(det_row_z(b, v.alpha), b.entries(v.r))} - "
            rf"{tex.paren(b.num(v.omega))}^2 \cdot {b.col(v.r)}"
        )
        b.line(
            rf"&\phantom{{\vec{{a}}}} = {base} + {b.col(v.rotation)} + {b.col(v.normal)} = "
            rf"{tex.boxed_result(b.colu(tr))}"
        )
        b.line(
            rf"&\vec{{a}}^{{\tau}}_{{{sub},\mathrm{{tr}}}} = {b.col(parts.tangential)}, \quad "
            rf"\vec{{a}}^{{n}}_{{{sub},\mathrm{{tr}}}} = {b.col(parts.normal)} \quad "
            r"\text{(along and across } \vec{v}_{\mathrm{tr}}\text{)}"
        )
        self.transport_acceleration_text(b, v, tr, parts)

    def transport_acceleration_text(
        self, b: StepBuilder, v: TransportTerms, tr: str, parts: TransportParts
    ) -> None:
        """Say a_tr (or that the carrier translates) and its two parts."""
        carrier, a = self.carrier, v.origin
        if b.is_zero(v.omega) and b.is_zero(v.alpha):
            b.say(
                f"The carrier {carrier} translates (omega = alpha = 0): all its points have "
                f"the acceleration of {a}, so a_tr = a({a}) = {b.txt(tr)}."
            )
        else:
            b.say(
                f"Transport acceleration: a({a}) + alpha({carrier}) cross r - "
                f"omega({carrier}) squared r = {b.txt(v.base)} + {b.txt(v.rotation)} + "
                f"{b.txt(v.normal)} = {b.txt(tr)}."
            )
        b.say(
            f"Its tangential part (along v_tr) is {b.txt(parts.tangential)} and its normal part "
            f"(across it) {b.txt(parts.normal)}."
        )

    def relative_acceleration_step(self) -> Step:
        """a_rel = s'' tau + (s'^2 / R) n, n towards the arc's centre (no normal part on a
        line)."""
        b = self.ctx.builder(
            "relative.relative_acceleration", f"Relative acceleration of {self.name}"
        )
        v = self.relative_acceleration_values(b)
        rel = self.put(b, "relative_acceleration")
        b.check("product", v.tangential, v.s_ddot, v.tau)
        b.check("product", v.normal, v.s_dot, v.s_dot, v.curvature, v.n)
        b.check("sum", rel, v.tangential, v.normal)
        self.relative_acceleration_lines(b, v, rel)
        return b.build()

    def relative_acceleration_values(self, b: StepBuilder) -> RelativeAcceleration:
        """s', s'', tau, n, 1/R and the parts s'' tau and (s'^2 / R) n of a_rel."""
        tau, normal, curvature = self.tangent_normal()
        return RelativeAcceleration(
            b.put("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot")),
            b.put("s_ddot", float(self.m.s_ddot), "m/s^2", self.src("s_ddot")),
            b.put("tau", tau, ""),
            b.put("n", normal, ""),
            b.put("1/R", curvature, "1/m" if curvature else ""),
            b.put(
                "a_rel tangential",
                self.m.relative_tangential,
                "m/s^2",
                self.src("relative_tangential"),
            ),
            b.put("a_rel normal", self.m.relative_normal, "m/s^2", self.src("relative_normal")),
        )

    def relative_acceleration_lines(
        self, b: StepBuilder, v: RelativeAcceleration, rel: str
    ) -> None:
        """Write a_rel^tau = s'' tau, a_rel^n = (s'^2 / R) n (0 on a line) and their sum."""
        sub, curved = self.n, b.scalar(v.curvature) != 0.0
        b.line(
            rf"&\vec{{a}}^{{\tau}}_{{{sub},\mathrm{{rel}}}} = \ddot{{s}}\,\vec{{\tau}} = "
            rf"{b.num(v.s_ddot)} \cdot {b.col(v.tau)} = {b.col(v.tangential)}"
        )
        if curved:
            radius = self.ctx.fmt.latex(1 / b.scalar(v.curvature))
            b.line(
                rf"&\vec{{a}}^{{n}}_{{{sub},\mathrm{{rel}}}} = \frac{{\dot{{s}}^2}}{{R}}\,"
                rf"\vec{{n}} = \frac{{{tex.paren(b.num(v.s_dot))}^2}}{{{radius}}}"
                rf" \cdot {b.col(v.n)} = {b.col(v.normal)}"
            )
        else:
            b.line(
                rf"&\vec{{a}}^{{n}}_{{{sub},\mathrm{{rel}}}} = {V0} \quad "
                r"\text{(straight path)}"
            )
        b.line(
            rf"&\vec{{a}}_{{{sub},\mathrm{{rel}}}} = {b.col(v.tangential)} + {b.col(v.normal)} = "
            rf"{tex.boxed_result(b.colu(rel))}"
        )
        normal = (
            f", normal s-dot squared over R towards the centre = {b.txt(v.normal)}"
            if curved
            else ", no normal part on a straight path"
        )
        b.say(
            f"Relative acceleration: tangential s-double-dot tau = {b.txt(v.tangential)} (along "
            f"the direction of increasing s){normal}; a_rel = {b.txt(rel)}."
        )

    def coriolis_step(self) -> Step:
        """a_Cor = 2 omega_carrier x v_rel, or zero where the carrier translates."""
        carrier, omega = self.carrier, float(self.m.omega_carrier)
        b = self.ctx.builder("relative.coriolis", f"Coriolis acceleration of {self.name}")
        w = b.put(f"omega({carrier})", omega, "rad/s", self.src("omega_carrier"))
        vrel = self.put(b, "relative_velocity")
        cor = self.put(b, "coriolis_acceleration")
        b.check("cross", cor, w, vrel, factor=2.0)
        formula = (
            rf"\vec{{a}}_{{{self.n},\mathrm{{Cor}}}} = 2\,"
            rf"\vec{{\omega}}_{{{tex.name(carrier)}}} \times "
            rf"\vec{{v}}_{{{self.n},\mathrm{{rel}}}}"
        )
        if b.is_zero(w):
            b.line(
                rf"&{formula} = {tex.boxed_result(V0 + latex_unit('m/s^2'))} \quad "
                rf"(\omega_{{{tex.name(carrier)}}} = 0)"
            )
            b.say(
                f"The carrier {carrier} does not rotate (omega({carrier}) = {b.txt(w)}): it "
                "translates, so there is no Coriolis acceleration, even if the links that "
                "drive it turn."
            )
            return b.build()
        half = b.put("omega x v_rel", k_cross(omega, self.m.relative_velocity), "m/s^2")
        b.check("cross", half, w, vrel)
        b.line(
            rf"&{formula} = 2 \cdot {tex.determinant3(det_row_z(b, w), b.entries(vrel))}"
            rf" = 2 \cdot {b.col(half)} = {tex.boxed_result(b.colu(cor))}"
        )
        b.say(
            f"Coriolis acceleration: 2 omega({carrier}) cross v_rel = 2 (0, 0, "
            f"{b.txtn(w)}) cross {b.txt(vrel)} = {b.txt(cor)}."
        )
        return b.build()

    def absolute_acceleration_step(self) -> Step:
        """a = a_tr + a_rel + a_Cor."""
        sub = self.n
        b = self.ctx.builder("relative.acceleration", f"Absolute acceleration of {self.name}")
        tr = self.put(b, "transport_acceleration")
        rel = self.put(b, "relative_acceleration")
        cor = self.put(b, "coriolis_acceleration")
        total = self.put(b, "acceleration")
        b.check("sum", total, tr, rel, cor)
        b.line(
            rf"&\vec{{a}}_{{{sub}}} = \vec{{a}}_{{{sub},\mathrm{{tr}}}} + "
            rf"\vec{{a}}_{{{sub},\mathrm{{rel}}}} + \vec{{a}}_{{{sub},\mathrm{{Cor}}}} = "
            rf"{b.col(tr)} + {b.col(rel)} + {V0 if b.is_zero(cor) else b.col(cor)} = "
            rf"{tex.boxed_result(b.colu(total))}"
        )
        b.say(
            f"a({self.name}) = a_tr + a_rel + a_Cor = {b.txt(tr)} + {b.txt(rel)} + "
            f"{b.txt(cor)} = {b.txt(total)}."
        )
        return b.build()

    # --- events ---------------------------------------------------------------------------------

    def event_step(self) -> Step | None:
        """s(t_e) = pi R (M opposite its start) and s(t_e) = 2 pi R (M back at its start), each
        for the first t_e > 0 (``first_time_at``); None on a line or if neither is reached."""
        route = self.mp.path
        if route.type != "arc":
            return None
        law = parse_time_law(self.mp.s_law)
        in_math = sympy.lambdify(sympy.Symbol("t"), law.expression, "math")

        def s_of_t(t: float) -> float:  # where math raises (overflow), the law's inf or nan
            try:
                return float(in_math(t))
            except (OverflowError, ValueError, ZeroDivisionError):
                return law.value(t)

        radius = self.path_radius()
        b = self.ctx.builder(
            "relative.event", f"When {self.name} reaches the far end and its start"
        )
        r = b.put("R", radius, "m")
        pi = b.put("pi", math.pi, "")
        found = False
        for turns, where in (
            (1, "opposite its start (half a turn, s = pi R)"),
            (2, f"back at {route.start} (a full turn, s = 2 pi R)"),
        ):
            level = turns * math.pi * radius
            t_e = first_time_at(s_of_t, level)
            if t_e is None:
                continue
            lv = b.put(f"s_{turns}", level, "m", reference=level)
            te = b.put(f"t_{turns}", t_e, "s")
            b.check("product", lv, pi, r, factor=float(turns))
            self.event_lines(b, turns, where, lv, te)
            found = True
        return b.build() if found else None

    def event_lines(self, b: StepBuilder, turns: int, where: str, lv: str, te: str) -> None:
        """Write s(t) = k pi R solved for its first root t_k."""
        law = parse_time_law(self.mp.s_law)
        factor = "" if turns == 1 else "2"
        b.line(
            rf"&s(t) = {factor}\pi R = {b.numu(lv)} \;\Rightarrow\; "
            rf"{tex.law(law.expression, self.ctx.fmt.digits)} = {b.num(lv)} \;\Rightarrow\; "
            rf"t = {tex.boxed_result(b.numu(te))}"
        )
        b.say(
            f"{self.name} is {where} when s(t) = {b.txt(lv)}: the first positive root of "
            f"{self.mp.s_law} = {b.txtn(lv)} is t = {b.txt(te)}."
        )

    def steps(self) -> list[Step]:
        event = self.event_step()
        return [
            self.law_step(),
            *self.velocity_steps(),
            *self.acceleration_steps(),
            *([event] if event is not None else []),
        ]


def first_time_at(s_of_t: Callable[[float], float], level: float) -> float | None:
    """The first t in [0, EVENT_HORIZON] with s(t) = level: a sign change of s(t) - level on
    EVENT_SAMPLES points, then Brent's method; None without one."""
    grid = np.linspace(0.0, EVENT_HORIZON, EVENT_SAMPLES)
    values = np.array([float(s_of_t(float(t))) for t in grid]) - level
    crossing = np.nonzero(np.sign(values[1:]) * np.sign(values[:-1]) <= 0)[0]
    if crossing.size == 0:
        return None
    k = int(crossing[0])
    root = brentq(lambda t: float(s_of_t(t)) - level, grid[k], grid[k + 1], xtol=1e-14, rtol=1e-15)
    return float(root)


def moving_point_steps(ctx: LinkageContext) -> list[Step]:
    """The composite-motion steps of every moving point of the scene (none without them)."""
    moving = getattr(ctx.analysis, "moving_points", {}) or {}
    out: list[Step] = []
    for mp in ctx.scene.moving_points:
        if mp.name in moving:
            out += MovingPointSteps(ctx, mp, moving[mp.name]).steps()
    return out
