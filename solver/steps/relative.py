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

import numpy as np
import sympy
from scipy.optimize import brentq

from solver.laws import parse_time_law
from solver.relative_motion import MovingPointMotion
from solver.rigid import perp
from solver.scene import MovingPoint
from solver.steps import latex as tex
from solver.steps.builder import StepBuilder
from solver.steps.format import latex_unit
from solver.steps.linkage import V0, LinkageContext, det_row_z, k_cross, split_part
from solver.steps.model import Step

EVENT_HORIZON = 60.0  # s: the event search looks this far ahead (the /events default t_max)
EVENT_SAMPLES = 6001


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
        turn = 1.0 if route.direction == "ccw" else -1.0
        return turn * perp(radial), -radial, 1.0 / radius

    def law_step(self) -> Step:
        ctx, mp = self.ctx, self.mp
        b = ctx.builder("relative.law", f"Moving point {self.name}: time law and position")
        law = parse_time_law(mp.s_law)
        t = b.put("t", ctx.scene.time, "s")
        s = b.put("s", float(self.m.s), "m", self.src("s"))
        sd = b.put("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot"))
        sdd = b.put("s_ddot", float(self.m.s_ddot), "m/s^2", self.src("s_ddot"))
        b.line(
            rf"&s(t) = {tex.law(law.expression, ctx.fmt.digits)}, \quad \dot{{s}}(t) = "
            rf"{tex.law(law.first_derivative, ctx.fmt.digits)}, \quad \ddot{{s}}(t) = "
            rf"{tex.law(law.second_derivative, ctx.fmt.digits)}"
        )
        b.line(
            rf"&t = {b.numu(t)}: \quad s = {b.numu(s)}, \quad \dot{{s}} = {b.numu(sd)}, \quad "
            rf"\ddot{{s}} = {b.numu(sdd)}"
        )
        b.say(
            f"{self.name} moves along a path fixed in link {self.carrier}; its arc length from "
            f"{mp.path.start} is s(t) = {mp.s_law} (m). At t = {b.txt(t)}: s = {b.txt(s)}, "
            f"s-dot = {b.txt(sd)}, s-double-dot = {b.txt(sdd)}."
        )
        route = mp.path
        m = b.put(f"pos({self.name})", self.m.position, "m", self.src("position"))
        if route.type == "arc":
            assert route.center is not None
            c = b.put(
                f"pos({route.center})",
                ctx.pos(route.center),
                "m",
                ("points", route.center, "position"),
            )
            radius = float(
                np.hypot(*(ctx.scene.drawn(route.start) - ctx.scene.drawn(route.center)))
            )
            r = b.put("R", radius, "m")
            start = ctx.scene.drawn(route.start) - ctx.scene.drawn(route.center)
            theta = float(ctx.analysis.motion.links[self.carrier].theta[0])
            turn = 1.0 if route.direction == "ccw" else -1.0
            angle = b.put(
                "angle",
                math.atan2(start[1], start[0]) + theta + turn * float(self.m.s) / radius,
                "rad",
            )
            d = b.put(
                f"r({route.center},{self.name})",
                np.asarray(self.m.position) - ctx.pos(route.center),
                "m",
            )
            b.check("phasor", d, r, angle)
            b.check("sum", m, c, d)
            b.line(
                rf"&\text{{arc about }} {tex.name(route.center)}, \; R = {b.numu(r)}, \; "
                rf"\text{{{'counter-clockwise' if turn > 0 else 'clockwise'} from }} "
                rf"{tex.name(route.start)}: \; {self.n} = {tex.name(route.center)} + "
                rf"R\,(\cos\psi, \sin\psi), \; \psi = {b.numu(angle)}"
            )
            b.line(
                rf"&{self.n} = {b.point(c)} + {b.point(d)} = "
                rf"{tex.boxed_result(b.point(m) + latex_unit('m'))}"
            )
            b.say(
                f"The path is an arc of radius R = {b.txt(r)} about {route.center}, run "
                f"{'counter-clockwise' if turn > 0 else 'clockwise'} from {route.start}; "
                f"{self.name} is at the angle psi = {b.txt(angle)} on it: {self.name} = "
                f"{b.txt(m)}."
            )
        else:
            assert route.through is not None
            s0 = b.put(
                f"pos({route.start})",
                ctx.pos(route.start),
                "m",
                ("points", route.start, "position"),
            )
            u_np = ctx.pos(route.through) - ctx.pos(route.start)
            u = b.put("u", u_np / float(np.hypot(*u_np)), "")
            d = b.put(
                f"r({route.start},{self.name})",
                np.asarray(self.m.position) - ctx.pos(route.start),
                "m",
            )
            b.check("product", d, s, u)
            b.check("sum", m, s0, d)
            b.line(
                rf"&{self.n} = {tex.name(route.start)} + s\,\vec{{u}} = {b.point(s0)} + "
                rf"{b.num(s)} \cdot {b.point(u)} = "
                rf"{tex.boxed_result(b.point(m) + latex_unit('m'))}"
            )
            b.say(
                f"The path is the line from {route.start} towards {route.through} (direction "
                f"{b.txtn(u)}): {self.name} = {b.txt(m)}."
            )
        return b.build()

    def velocity_steps(self) -> list[Step]:
        ctx, carrier = self.ctx, self.carrier
        a = ctx.reference_point(carrier)
        r_np = np.asarray(self.m.position) - ctx.pos(a)
        omega = float(self.m.omega_carrier)
        out = []
        b = ctx.builder("relative.transport_velocity", f"Transport velocity of {self.name}")
        va = b.put(f"v({a})", ctx.vel(a), "m/s", ("points", a, "velocity"))
        w = b.put(f"omega({carrier})", omega, "rad/s", self.src("omega_carrier"))
        r = b.put(f"r({a},{self.name})", r_np, "m")
        wxr = b.put("omega x r", k_cross(omega, r_np), "m/s")
        tr = self.put(b, "transport_velocity")
        b.check("cross", wxr, w, r)
        b.check("sum", tr, va, wxr)
        base = V0 if ctx.is_fixed(a) and b.is_zero(va) else b.col(va)
        sub = self.n + r",\mathrm{tr}"
        b.line(
            rf"&\vec{{v}}_{{{sub}}} = \vec{{v}}_{{{tex.name(a)}}} + "
            rf"\vec{{\omega}}_{{{tex.name(carrier)}}} \times "
            rf"\vec{{r}}_{{{tex.pair(a, self.name)}}}"
            rf" = {base} + {tex.determinant3(det_row_z(b, w), b.entries(r))} = "
            rf"{tex.boxed_result(b.colu(tr))}"
        )
        if b.is_zero(w):
            b.say(
                f"The carrier {carrier} translates at this instant (omega = 0): every point of "
                f"it, including the one under {self.name}, moves like {a}: v_tr = {b.txt(tr)}."
            )
        else:
            b.say(
                f"Transport velocity: the velocity of the point of {carrier} under "
                f"{self.name}, v({a}) + omega({carrier}) cross r({a},{self.name}) = "
                f"{b.txt(va)} + {b.txt(wxr)} = {b.txt(tr)}."
            )
        out.append(b.build())
        tau, _, _ = self.tangent_normal()
        b = ctx.builder("relative.relative_velocity", f"Relative velocity of {self.name}")
        sd = b.put("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot"))
        t = b.put("tau", tau, "")
        rel = self.put(b, "relative_velocity")
        b.check("product", rel, sd, t)
        b.line(
            rf"&\vec{{v}}_{{{self.n},\mathrm{{rel}}}} = \dot{{s}}\,\vec{{\tau}} = "
            rf"{b.num(sd)} \cdot {b.col(t)} = {tex.boxed_result(b.colu(rel))}"
        )
        b.say(
            f"Relative velocity: along the path's tangent tau = {b.txtn(t)} (the direction of "
            f"increasing s), v_rel = s-dot tau = {b.txt(rel)}. It is the velocity an observer "
            f"on {carrier} sees: the carrier's rate does not enter it."
        )
        out.append(b.build())
        b = ctx.builder("relative.velocity", f"Absolute velocity of {self.name}")
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
        out.append(b.build())
        return out

    def acceleration_steps(self) -> list[Step]:
        ctx, carrier = self.ctx, self.carrier
        a_pt = ctx.reference_point(carrier)
        r_np = np.asarray(self.m.position) - ctx.pos(a_pt)
        omega, alpha = float(self.m.omega_carrier), float(self.m.alpha_carrier)
        out = []
        sub = self.n
        b = ctx.builder("relative.transport_acceleration", f"Transport acceleration of {self.name}")
        aa = b.put(f"a({a_pt})", ctx.acc(a_pt), "m/s^2", ("points", a_pt, "acceleration"))
        w = b.put(f"omega({carrier})", omega, "rad/s", self.src("omega_carrier"))
        al = b.put(f"alpha({carrier})", alpha, "rad/s^2", self.src("alpha_carrier"))
        r = b.put(f"r({a_pt},{self.name})", r_np, "m")
        t = b.put("alpha x r", k_cross(alpha, r_np), "m/s^2")
        n = b.put("normal", -(omega**2) * r_np, "m/s^2")
        tr = self.put(b, "transport_acceleration")
        tt = b.put(
            "a_tr tangential",
            self.m.transport_tangential,
            "m/s^2",
            self.src("transport_tangential"),
        )
        tn = b.put("a_tr normal", self.m.transport_normal, "m/s^2", self.src("transport_normal"))
        vtr = self.put(b, "transport_velocity")
        d = b.put(
            "a_tr normal . v_tr",
            float(np.dot(self.m.transport_normal, self.m.transport_velocity)),
            "m^2/s^3",
            reference=float(
                np.hypot(*self.m.transport_normal) * np.hypot(*self.m.transport_velocity)
            ),
        )
        b.check("cross", t, al, r)
        b.check("product", n, w, w, r, factor=-1.0)
        b.check("sum", tr, aa, t, n)
        b.check("sum", tr, tt, tn)
        b.check("dot", d, tn, vtr)
        base = V0 if ctx.is_fixed(a_pt) and b.is_zero(aa) else b.col(aa)
        b.line(
            rf"&\vec{{a}}_{{{sub},\mathrm{{tr}}}} = \vec{{a}}_{{{tex.name(a_pt)}}} + "
            rf"\vec{{\alpha}}_{{{tex.name(carrier)}}} \times \vec{{r}} - "
            rf"\omega_{{{tex.name(carrier)}}}^2\,\vec{{r}} = {base} + "
            rf"{tex.determinant3(det_row_z(b, al), b.entries(r))} - "
            rf"{tex.paren(b.num(w))}^2 \cdot {b.col(r)}"
        )
        b.line(
            rf"&\phantom{{\vec{{a}}}} = {base} + {b.col(t)} + {b.col(n)} = "
            rf"{tex.boxed_result(b.colu(tr))}"
        )
        b.line(
            rf"&\vec{{a}}^{{\tau}}_{{{sub},\mathrm{{tr}}}} = {b.col(tt)}, \quad "
            rf"\vec{{a}}^{{n}}_{{{sub},\mathrm{{tr}}}} = {b.col(tn)} \quad "
            r"\text{(along and across } \vec{v}_{\mathrm{tr}}\text{)}"
        )
        if b.is_zero(w) and b.is_zero(al):
            b.say(
                f"The carrier {carrier} translates (omega = alpha = 0): all its points have "
                f"the acceleration of {a_pt}, so a_tr = a({a_pt}) = {b.txt(tr)}."
            )
        else:
            b.say(
                f"Transport acceleration: a({a_pt}) + alpha({carrier}) cross r - "
                f"omega({carrier}) squared r = {b.txt(aa)} + {b.txt(t)} + {b.txt(n)} = "
                f"{b.txt(tr)}."
            )
        b.say(
            f"Its tangential part (along v_tr) is {b.txt(tt)} and its normal part (across it) "
            f"{b.txt(tn)}."
        )
        out.append(b.build())
        tau, normal, curvature = self.tangent_normal()
        b = ctx.builder("relative.relative_acceleration", f"Relative acceleration of {self.name}")
        sd = b.put("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot"))
        sdd = b.put("s_ddot", float(self.m.s_ddot), "m/s^2", self.src("s_ddot"))
        tk = b.put("tau", tau, "")
        nk = b.put("n", normal, "")
        kappa = b.put("1/R", curvature, "1/m" if curvature else "")
        rt = b.put(
            "a_rel tangential", self.m.relative_tangential, "m/s^2", self.src("relative_tangential")
        )
        rn = b.put("a_rel normal", self.m.relative_normal, "m/s^2", self.src("relative_normal"))
        rel = self.put(b, "relative_acceleration")
        b.check("product", rt, sdd, tk)
        b.check("product", rn, sd, sd, kappa, nk)
        b.check("sum", rel, rt, rn)
        b.line(
            rf"&\vec{{a}}^{{\tau}}_{{{sub},\mathrm{{rel}}}} = \ddot{{s}}\,\vec{{\tau}} = "
            rf"{b.num(sdd)} \cdot {b.col(tk)} = {b.col(rt)}"
        )
        if curvature:
            radius = ctx.fmt.latex(1 / curvature)
            b.line(
                rf"&\vec{{a}}^{{n}}_{{{sub},\mathrm{{rel}}}} = \frac{{\dot{{s}}^2}}{{R}}\,"
                rf"\vec{{n}} = \frac{{{tex.paren(b.num(sd))}^2}}{{{radius}}}"
                rf" \cdot {b.col(nk)} = {b.col(rn)}"
            )
        else:
            b.line(
                rf"&\vec{{a}}^{{n}}_{{{sub},\mathrm{{rel}}}} = {V0} \quad "
                r"\text{(straight path)}"
            )
        b.line(
            rf"&\vec{{a}}_{{{sub},\mathrm{{rel}}}} = {b.col(rt)} + {b.col(rn)} = "
            rf"{tex.boxed_result(b.colu(rel))}"
        )
        b.say(
            f"Relative acceleration: tangential s-double-dot tau = {b.txt(rt)} (along the "
            "direction of increasing s)"
            + (
                f", normal s-dot squared over R towards the centre = {b.txt(rn)}"
                if curvature
                else ", no normal part on a straight path"
            )
            + f"; a_rel = {b.txt(rel)}."
        )
        out.append(b.build())
        b = ctx.builder("relative.coriolis", f"Coriolis acceleration of {self.name}")
        w = b.put(f"omega({carrier})", omega, "rad/s", self.src("omega_carrier"))
        vrel = self.put(b, "relative_velocity")
        cor = self.put(b, "coriolis_acceleration")
        b.check("cross", cor, w, vrel, factor=2.0)
        formula = (
            rf"\vec{{a}}_{{{sub},\mathrm{{Cor}}}} = 2\,"
            rf"\vec{{\omega}}_{{{tex.name(carrier)}}} \times "
            rf"\vec{{v}}_{{{sub},\mathrm{{rel}}}}"
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
        else:
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
        out.append(b.build())
        b = ctx.builder("relative.acceleration", f"Absolute acceleration of {self.name}")
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
        out.append(b.build())
        return out

    def event_step(self) -> Step | None:
        """s(t_e) = pi R (M opposite its start) and s(t_e) = 2 pi R (M back at its start), each
        solved for the first t_e > 0 by a sign change of s(t) - level and Brent's method."""
        route = self.mp.path
        if route.type != "arc":
            return None
        assert route.center is not None
        law = parse_time_law(self.mp.s_law)
        s_of_t = sympy.lambdify(sympy.Symbol("t"), law.expression, "math")
        radius = float(
            np.hypot(*(self.ctx.scene.drawn(route.start) - self.ctx.scene.drawn(route.center)))
        )
        b = self.ctx.builder(
            "relative.event", f"When {self.name} reaches the far end and its start"
        )
        r = b.put("R", radius, "m")
        pi = b.put("pi", math.pi, "")
        grid = np.linspace(0.0, EVENT_HORIZON, EVENT_SAMPLES)
        found = False
        for turns, where in (
            (1, "opposite its start (half a turn, s = pi R)"),
            (2, f"back at {route.start} (a full turn, s = 2 pi R)"),
        ):
            level = turns * math.pi * radius
            values = np.array([float(s_of_t(float(t))) for t in grid]) - level
            crossing = np.nonzero(np.sign(values[1:]) * np.sign(values[:-1]) <= 0)[0]
            if crossing.size == 0:
                continue
            k = int(crossing[0])
            t_e = float(
                brentq(
                    lambda t, level=level: float(s_of_t(t)) - level,
                    grid[k],
                    grid[k + 1],
                    xtol=1e-14,
                    rtol=1e-15,
                )
            )
            lv = b.put(f"s_{turns}", level, "m", reference=level)
            te = b.put(f"t_{turns}", t_e, "s")
            b.check("product", lv, pi, r, factor=float(turns))
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
            found = True
        if not found:
            return None
        return b.build()

    def steps(self) -> list[Step]:
        event = self.event_step()
        return [
            self.law_step(),
            *self.velocity_steps(),
            *self.acceleration_steps(),
            *([event] if event is not None else []),
        ]


def moving_point_steps(ctx: LinkageContext) -> list[Step]:
    """The composite-motion steps of every moving point of the scene (none without them)."""
    moving = getattr(ctx.analysis, "moving_points", {}) or {}
    out: list[Step] = []
    for mp in ctx.scene.moving_points:
        if mp.name in moving:
            out += MovingPointSteps(ctx, mp, moving[mp.name]).steps()
    return out
