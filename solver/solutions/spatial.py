"""Worked solution of a spatial chain (seed 002): compose rates, turn the axes, five terms.

Body by body from the ground: omega_k = omega_{k-1} + rate_k e_k; the axis e_k is fixed in body
k-1 and turns with it, de_k/dt = omega_{k-1} x e_k; alpha_k = alpha_{k-1} + rate_dot_k e_k +
rate_k de_k/dt. The joint origins carry the velocity and acceleration along, and every point gets
v_P = v_O + omega x r and the five-term acceleration
a_P = a_O + alpha x r + omega x (omega x r) + 2 omega x v_rel + a_rel, each term written out.

The data step carries an axonometric figure of the chain (``chain_figure``); a ``reading`` step
says each body's rotation and each point's motion in words. Kennedy's theorem, instant centres
and the graphical polygons are planar methods and are not offered here (docs/SOLUTIONS.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from solver.kinematics.spatial import (
    GROUND,
    BodyMotion,
    OriginTerms,
    PointMotion,
    SpatialAnalysis,
    SpatialChain,
    SpatialJoint,
    SpatialPoint,
    ground_motion,
    origin_terms,
)
from solver.solutions import figures
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import (
    TIMES,
    Alt,
    Boxed,
    Col,
    Equation,
    Num,
    Paren,
    Piece,
    Pt,
    Ref,
    Shows,
    Sym,
    Words,
    joined,
    latex_only,
    text_only,
)
from solver.solutions.format import Formatter
from solver.solutions.linkage import sense_clause, speed_trend
from solver.solutions.model import Step

V0 = r"\vec{0}"
# The isometric drawing: x towards the viewer on the lower left, y to the lower right, z up,
# full length along each axis: (X, Y) = (cos 30 (y - x), z - sin 30 (x + y)).
ISOMETRIC = np.array([[-math.cos(math.pi / 6), math.cos(math.pi / 6), 0.0], [-0.5, -0.5, 1.0]])
OMEGA_PAPER_CM = 3.0  # the largest omega is drawn at most this long
UNITS = r"\mathbf{E}_1 & \mathbf{E}_2 & \mathbf{E}_3"
# the results of a body and of a point: their units, names in the keys and LaTeX letters
RESULT_UNITS = {"omega": "rad/s", "alpha": "rad/s^2", "velocity": "m/s", "acceleration": "m/s^2"}
SHORT = {"omega": "omega", "alpha": "alpha", "velocity": "v", "acceleration": "a"}
SYMBOL = {"omega": r"\omega", "alpha": r"\alpha", "velocity": "v", "acceleration": "a"}


def _scales(chain: SpatialChain, analysis: SpatialAnalysis) -> dict[str, float]:
    def largest(vectors: list[np.ndarray]) -> float:
        return max((float(np.max(np.abs(v))) for v in vectors), default=0.0)

    positions = [j.origin for j in chain.joints] + [p.position for p in chain.points]
    return {
        "m": max(largest(positions), 1e-300),
        "m/s": largest(
            [p.velocity for p in analysis.points.values()]
            + [b.velocity_origin for b in analysis.bodies.values()]
        ),
        "m/s^2": largest(
            [p.acceleration for p in analysis.points.values()]
            + [b.acceleration_origin for b in analysis.bodies.values()]
        ),
        "rad/s": largest(
            [b.omega for b in analysis.bodies.values()]
            + [b.axis_rate for b in analysis.bodies.values()]
        ),
        "rad/s^2": largest([b.alpha for b in analysis.bodies.values()]),
    }


@dataclass(frozen=True)
class Cross:
    """a x b of two vector values as a determinant with the fixed unit vectors E1, E2, E3 in its
    first row in LaTeX, '(a) cross (b)' in text."""

    a: Ref
    b: Ref

    def latex(self, shows: Shows) -> str:
        return tex.determinant3(shows.entries(self.a), shows.entries(self.b), UNITS)

    def text(self, shows: Shows) -> str:
        return f"{shows.txt(self.a)} cross {shows.txt(self.b)}"


def column(b: StepBuilder, key: Ref) -> Piece:
    """A vector value as a column, the zero vector in LaTeX where it displays as zero."""
    return Alt((V0,), (Col(key),)) if b.is_zero(key) else Col(key)


def vector(symbol: str, sub: str, plain: str) -> Sym:
    """'\\vec{symbol}_{sub}' in LaTeX, ``plain`` in text."""
    return Sym(tex.vec(symbol, sub), plain)


R = Sym(r"\vec{r}", "r")


class FiveTerms(NamedTuple):
    """A point's five-term acceleration in its step:
    a_P = a_O + alpha x r + omega x (omega x r) + 2 omega x v_rel + a_rel."""

    a_origin: Ref
    alpha: Ref
    omega: Ref
    r: Ref
    tangential: Ref
    omega_x_r: Ref
    centripetal: Ref
    coriolis: Ref
    relative: Ref
    a: Ref


class SpatialSteps:
    def __init__(self, chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter) -> None:
        self.chain = chain
        self.analysis = analysis
        self.fmt = Formatter(fmt.digits, _scales(chain, analysis))
        self.shown: set[str] = set()  # points already shown (at a joint origin)

    def builder(self, kind: str, title: str) -> StepBuilder:
        return StepBuilder(self.fmt, kind, title)

    def data(self) -> Step:
        b = self.builder("data", "Data")
        b.say(
            "Method: composition of angular velocities in a chain of rotating frames. Joint k "
            "connects body k-1 (the ground for the first joint) to body k; its axis e_k is "
            "fixed in body k-1 and turns with it. Vectors are components in the fixed frame "
            "E1, E2, E3 at the instant."
        )
        rows: list[tuple[Piece, ...]] = []
        for j in self.chain.joints:
            e = b.value(f"e({j.name})", j.axis, "")
            o = b.value(f"O({j.name})", j.origin, "m")
            rate_unit = ("rad/s", "rad/s^2") if j.type == "revolute" else ("m/s", "m/s^2")
            q = b.value(f"rate({j.name})", j.rate, rate_unit[0])
            qd = b.value(f"rate_dot({j.name})", j.rate_dot, rate_unit[1])
            n = tex.name(j.name)
            symbol = r"\omega" if j.type == "revolute" else "v"
            place = Equation.of(Sym(f"O_{{{n}}}", "O"), Pt(o, "m"))
            axis = Equation.of(vector("e", n, "axis e"), Pt(e))
            rows.append(
                (
                    rf"&\text{{joint }} {n} \text{{ ({j.type})}}: \; ",
                    place,
                    r", \; ",
                    axis,
                    rf", \; {symbol}_{{{n}}} = ",
                    Num(q, unit=True),
                    rf", \; \dot{{{symbol}}}_{{{n}}} = ",
                    Num(qd, unit=True),
                )
            )
            b.say(
                f"Joint {j.name} ({j.type}) at ",
                place,
                ", ",
                axis,
                ", rate ",
                Num(q, unit=True),
                ", rate of change ",
                Num(qd, unit=True),
                ".",
            )
        for row in rows:
            b.line(*row)
        return b.build()

    def parent_name(self, index: int) -> str:
        return GROUND if index == 0 else self.chain.joints[index - 1].name

    def parent_motion(self, index: int) -> BodyMotion:
        """Body k-1's motion: omega, alpha, its origin's (zeros for the ground)."""
        if index == 0:
            return ground_motion(np.zeros(3))
        return self.analysis.bodies[self.chain.joints[index - 1].name]

    def parent_rate(self, b: StepBuilder, index: int, name: str, value: np.ndarray) -> Ref:
        """omega_{k-1} (or alpha_{k-1}) of body k-1; the ground's is zero and has no source."""
        parent = self.parent_name(index)
        unit = "rad/s" if name == "omega" else "rad/s^2"
        return b.value(
            f"{name}({parent})", value, unit, None if index == 0 else ("bodies", parent, name)
        )

    def point_at_origin(self, index: int, joint: SpatialJoint) -> str | None:
        """A named point of body k-1 at the origin of joint k: its own steps carry the origin's
        motion, so the origin is not computed twice."""
        parent = self.parent_name(index)
        tolerance = 1e-12 * max(1.0, float(np.max(np.abs(joint.origin))))
        for point in self.chain.points:
            if point.body == parent and np.max(np.abs(point.position - joint.origin)) <= tolerance:
                return point.name
        return None

    def body_steps(self, index: int, joint: SpatialJoint) -> list[Step]:
        """omega_k, de_k/dt and alpha_k of body k, then the motion of its joint origin O_k."""
        parent = self.parent_motion(index)
        out = [
            self.omega_step(index, joint, parent),
            self.axis_rate_step(index, joint, parent),
            self.alpha_step(index, joint, parent),
        ]
        at_origin = self.point_at_origin(index, joint)
        if at_origin is not None:
            self.shown.add(at_origin)
            out += self.point_steps(at_origin, f" (the origin O{joint.name} of joint {joint.name})")
        else:
            terms = origin_terms(parent, joint)
            out.append(self.origin_velocity_step(index, joint, parent, terms))
            out.append(self.origin_acceleration_step(index, joint, parent, terms))
        return out

    def omega_step(self, index: int, joint: SpatialJoint, parent: BodyMotion) -> Step:
        """omega_k = omega_{k-1} + omega_k e_k (a revolute joint), omega_k = omega_{k-1} (a
        prismatic one)."""
        body = self.analysis.bodies[joint.name]
        parent_name = self.parent_name(index)
        n = tex.name(joint.name)
        b = self.builder("spatial.omega", f"Angular velocity of body {joint.name}")
        wp = self.parent_rate(b, index, "omega", parent.omega)
        w = b.value(f"omega({joint.name})", body.omega, "rad/s", ("bodies", joint.name, "omega"))
        e = b.value(f"e({joint.name})", joint.axis, "")
        omega = vector(r"\omega", n, f"omega({joint.name})")
        omega_parent = vector(r"\omega", tex.name(parent_name), f"omega({parent_name})")
        if joint.type != "revolute":
            b.check("sum", w, wp)
            same = Equation.of(omega, omega_parent, Boxed((Col(w, unit=True),)))
            b.line(same)
            b.say("A prismatic joint adds no rotation: ", same, ".")
            return b.build()
        q = b.value(f"rate({joint.name})", joint.rate, "rad/s")
        term = b.value(f"rate e({joint.name})", body.composition.rate_axis, "rad/s")
        b.check("product", term, q, e)
        b.check("sum", w, wp, term)
        composition = Equation.of(
            omega,
            (
                omega_parent,
                " + ",
                Alt((rf"\omega_{{{n}}}\,\vec{{e}}_{{{n}}}",), (Num(q), f" times e({joint.name})")),
            ),
            (column(b, wp), " + ", Alt((Paren(q), r" \cdot ", Col(e)), (Col(term),))),
            Boxed((Col(w, unit=True),)),
        )
        b.line(composition)
        b.say("Angular velocities add: ", composition, ".")
        return b.build()

    def axis_rate_step(self, index: int, joint: SpatialJoint, parent: BodyMotion) -> Step:
        """de_k/dt = omega_{k-1} x e_k: the axis is fixed in body k-1 and turns with it."""
        body = self.analysis.bodies[joint.name]
        parent_name = self.parent_name(index)
        n, p = tex.name(joint.name), tex.name(parent_name)
        b = self.builder("spatial.axis_rate", f"Rate of change of the axis of joint {joint.name}")
        wp = self.parent_rate(b, index, "omega", parent.omega)
        e = b.value(f"e({joint.name})", joint.axis, "")
        ed = b.value(f"e_dot({joint.name})", body.axis_rate, "1/s")
        b.check("cross", ed, wp, e)
        turning = Equation.of(
            latex_only(rf"\dot{{\vec{{e}}}}_{{{n}}}"),
            (
                vector(r"\omega", p, f"omega({parent_name})"),
                TIMES,
                vector("e", n, f"e({joint.name})"),
            ),
            latex_only(Cross(wp, e)),
            Boxed((Col(ed, unit=True),)),
        )
        b.line(turning)
        b.say(
            f"The axis e({joint.name}) is fixed in body {parent_name}, so it turns with "
            f"omega({parent_name}): its rate of change is ",
            turning,
            ".",
        )
        return b.build()

    def alpha_step(self, index: int, joint: SpatialJoint, parent: BodyMotion) -> Step:
        """alpha_k = alpha_{k-1} + omega_dot_k e_k + omega_k de_k/dt (a revolute joint),
        alpha_k = alpha_{k-1} (a prismatic one)."""
        body = self.analysis.bodies[joint.name]
        parent_name = self.parent_name(index)
        n = tex.name(joint.name)
        b = self.builder("spatial.alpha", f"Angular acceleration of body {joint.name}")
        alp = self.parent_rate(b, index, "alpha", parent.alpha)
        al = b.value(f"alpha({joint.name})", body.alpha, "rad/s^2", ("bodies", joint.name, "alpha"))
        alpha = vector(r"\alpha", n, f"alpha({joint.name})")
        alpha_parent = vector(r"\alpha", tex.name(parent_name), f"alpha({parent_name})")
        if joint.type != "revolute":
            b.check("sum", al, alp)
            same = Equation.of(alpha, alpha_parent, Boxed((Col(al, unit=True),)))
            b.line(same)
            b.say(same, " (prismatic joint).")
            return b.build()
        e = b.value(f"e({joint.name})", joint.axis, "")
        ed = b.value(f"e_dot({joint.name})", body.axis_rate, "1/s")
        q = b.value(f"rate({joint.name})", joint.rate, "rad/s")
        qd = b.value(f"rate_dot({joint.name})", joint.rate_dot, "rad/s^2")
        terms = body.composition
        t1 = b.value(f"rate_dot e({joint.name})", terms.rate_dot_axis, "rad/s^2")
        t2 = b.value(f"rate e_dot({joint.name})", terms.rate_axis_rate, "rad/s^2")
        b.check("product", t1, qd, e)
        b.check("product", t2, q, ed)
        b.check("sum", al, alp, t1, t2)
        composition = Equation.of(
            alpha,
            (
                alpha_parent,
                " + ",
                Sym(rf"\dot{{\omega}}_{{{n}}}\,\vec{{e}}_{{{n}}}", "rate-dot e"),
                " + ",
                Sym(rf"\omega_{{{n}}}\,\dot{{\vec{{e}}}}_{{{n}}}", "rate times de/dt"),
            ),
            (
                column(b, alp),
                " + ",
                Alt((Paren(qd), r" \cdot ", Col(e)), (Col(t1),)),
                " + ",
                Alt((Paren(q), r" \cdot ", Col(ed)), (Col(t2),)),
            ),
            Boxed((Col(al, unit=True),)),
        )
        b.line(composition)
        b.say(
            f"Differentiating omega({joint.name}) = omega({parent_name}) + rate e: ",
            composition,
            ". The last term comes from the turning axis; leaving it out is a common mistake.",
        )
        return b.build()

    def origin_velocity_step(
        self, index: int, joint: SpatialJoint, parent: BodyMotion, terms: OriginTerms
    ) -> Step:
        """v_{O_k} = v_{O_{k-1}} + omega_{k-1} x r (+ v_k e_k where joint k slides)."""
        body = self.analysis.bodies[joint.name]
        parent_name = self.parent_name(index)
        n, p = tex.name(joint.name), tex.name(parent_name)
        origin_p = "O_{" + p + "}" if index else "O"
        b = self.builder("spatial.origin.velocity", f"Velocity of the joint origin O{joint.name}")
        vp = b.value(f"v(O{parent_name})", parent.velocity_origin, "m/s")
        wp = self.parent_rate(b, index, "omega", parent.omega)
        r = b.value("r", terms.r, "m")
        wxr = b.value("omega x r", terms.omega_x_r, "m/s")
        v = b.value(f"v(O{joint.name})", body.velocity_origin, "m/s")
        b.check("cross", wxr, wp, r)
        parts = [vp, wxr]
        sliding: tuple[Piece, ...] = ()
        slide_term: tuple[Piece, ...] = ()
        if joint.type == "prismatic":
            e = b.value(f"e({joint.name})", joint.axis, "")
            q = b.value(f"rate({joint.name})", joint.rate, "m/s")
            parts.append(b.value("v_rel", terms.v_rel, "m/s"))
            b.check("product", parts[2], q, e)
            sliding = (latex_only(rf" + v_{{{n}}}\,\vec{{e}}_{{{n}}}"),)
            slide_term = (" + ", Col(parts[2]), text_only(" (sliding)"))
        b.check("sum", v, *parts)
        carried = Equation.of(
            Sym(rf"\vec{{v}}_{{O_{{{n}}}}}", "v"),
            (
                vector("v", origin_p, f"v(O{parent_name})"),
                " + ",
                vector(r"\omega", p, f"omega({parent_name})"),
                TIMES,
                vector("r", f"{origin_p} O_{{{n}}}", "r"),
                *sliding,
            ),
            (column(b, vp), " + ", Alt((Cross(wp, r),), (Col(wxr),)), *slide_term),
            Boxed((Col(v, unit=True),)),
        )
        b.line(carried)
        b.say(
            f"The origin O{joint.name} of joint {joint.name} moves with body {parent_name}: ",
            carried,
            ".",
        )
        return b.build()

    def origin_acceleration_step(
        self, index: int, joint: SpatialJoint, parent: BodyMotion, terms: OriginTerms
    ) -> Step:
        """a_{O_k} = a_{O_{k-1}} + alpha_{k-1} x r + omega_{k-1} x (omega_{k-1} x r)
        (+ 2 omega_{k-1} x v_rel + a_rel where joint k slides)."""
        body = self.analysis.bodies[joint.name]
        parent_name = self.parent_name(index)
        b = self.builder(
            "spatial.origin.acceleration", f"Acceleration of the joint origin O{joint.name}"
        )
        ap = b.value(f"a(O{parent_name})", parent.acceleration_origin, "m/s^2")
        wp = self.parent_rate(b, index, "omega", parent.omega)
        alp = self.parent_rate(b, index, "alpha", parent.alpha)
        r = b.value("r", terms.r, "m")
        t = b.value("alpha x r", terms.alpha_x_r, "m/s^2")
        inner = b.value("omega x r", terms.omega_x_r, "m/s")
        c = b.value("omega x (omega x r)", terms.centripetal, "m/s^2")
        a = b.value(f"a(O{joint.name})", body.acceleration_origin, "m/s^2")
        b.check("cross", t, alp, r)
        b.check("cross", inner, wp, r)
        b.check("cross", c, wp, inner)
        parts = [ap, t, c]
        if joint.type == "prismatic":
            parts += self.sliding_terms(b, joint, terms, wp)
        b.check("sum", a, *parts)
        self.write_origin_acceleration(b, index, joint, parts, a)
        return b.build()

    def sliding_terms(
        self, b: StepBuilder, joint: SpatialJoint, terms: OriginTerms, wp: Ref
    ) -> list[Ref]:
        """2 omega_{k-1} x v_rel and a_rel = v_dot_k e_k of a sliding joint k, v_rel = v_k e_k."""
        e = b.value(f"e({joint.name})", joint.axis, "")
        q = b.value(f"rate({joint.name})", joint.rate, "m/s")
        qd = b.value(f"rate_dot({joint.name})", joint.rate_dot, "m/s^2")
        rel_v = b.value("v_rel", terms.v_rel, "m/s")
        cor = b.value("2 omega x v_rel", terms.coriolis, "m/s^2")
        rel_a = b.value("a_rel", terms.a_rel, "m/s^2")
        b.check("product", rel_v, q, e)
        b.check("cross", cor, wp, rel_v, factor=2.0)
        b.check("product", rel_a, qd, e)
        return [cor, rel_a]

    def write_origin_acceleration(
        self, b: StepBuilder, index: int, joint: SpatialJoint, parts: list[Ref], a: Ref
    ) -> None:
        """The equation a_{O_k} = a_{O_{k-1}} + ... and its sum, in LaTeX and in words."""
        parent_name = self.parent_name(index)
        n, p = tex.name(joint.name), tex.name(parent_name)
        origin_p = "O_{" + p + "}" if index else "O"
        omega = vector(r"\omega", p, f"omega({parent_name})")
        sliding = (
            (
                Sym(
                    r" + 2\,\vec{\omega} \times \vec{v}_{\mathrm{rel}} + \vec{a}_{\mathrm{rel}}",
                    " + 2 omega cross v_rel + a_rel",
                ),
            )
            if joint.type == "prismatic"
            else ()
        )
        carried = Equation.of(
            latex_only(rf"\vec{{a}}_{{O_{{{n}}}}}"),
            (
                vector("a", origin_p, f"a(O{parent_name})"),
                " + ",
                vector(r"\alpha", p, f"alpha({parent_name})"),
                TIMES,
                R,
                " + ",
                omega,
                TIMES,
                "(",
                omega,
                TIMES,
                R,
                ")",
                *sliding,
            ),
            joined(" + ", [(column(b, k),) for k in parts]),
            Boxed((Col(a, unit=True),)),
            breaks=(2,),
            phantom=r"\vec{a}",
        )
        b.line(carried)
        b.say(f"Acceleration of O{joint.name}: ", carried, ".")

    def point_steps(self, name: str, role: str = "") -> list[Step]:
        """The velocity and the five-term acceleration of a point of a moving body (one step
        for a point of the ground)."""
        point = next(p for p in self.chain.points if p.name == name)
        if point.body == GROUND:
            return [self.fixed_point_step(point)]
        return [self.point_velocity_step(point, role), self.point_acceleration_step(point, role)]

    def fixed_point_step(self, point: SpatialPoint) -> Step:
        """v_P = a_P = 0 for a point of the ground."""
        name = point.name
        motion = self.analysis.points[name]
        b = self.builder("spatial.point.fixed", f"Point {name} (fixed)")
        v = b.value(f"v({name})", motion.velocity, "m/s", ("points", name, "velocity"))
        a = b.value(f"a({name})", motion.acceleration, "m/s^2", ("points", name, "acceleration"))
        b.line(rf"&\vec{{v}}_{{{tex.name(name)}}} = \vec{{a}}_{{{tex.name(name)}}} = {V0}")
        b.say(f"{name} is a point of the ground: v = ", Col(v), ", a = ", Col(a), ".")
        return b.build()

    def point_velocity_step(self, point: SpatialPoint, role: str) -> Step:
        """v_P = v_O + omega x r, r from the body's joint origin O to P."""
        name = point.name
        body = self.analysis.bodies[point.body]
        terms = self.analysis.points[name].rigid
        n, k = tex.name(name), tex.name(point.body)
        b = self.builder("spatial.point.velocity", f"Velocity of {name}{role}")
        vo = b.value(f"v(O{point.body})", body.velocity_origin, "m/s")
        w = b.value(f"omega({point.body})", body.omega, "rad/s", ("bodies", point.body, "omega"))
        r = b.value(f"r(O{point.body},{name})", terms.r, "m")
        wxr = b.value("omega x r", terms.omega_x_r, "m/s")
        v = b.value(
            f"v({name})", self.analysis.points[name].velocity, "m/s", ("points", name, "velocity")
        )
        b.check("cross", wxr, w, r)
        b.check("sum", v, vo, wxr)
        origin = column(b, vo)
        rigid = Equation.of(
            vector("v", n, f"v({name})"),
            (
                vector("v", f"O_{{{k}}}", f"v(O{point.body})"),
                " + ",
                vector(r"\omega", k, f"omega({point.body})"),
                TIMES,
                vector("r", f"O_{{{k}}}{n}", "r"),
            ),
            latex_only(origin, " + ", Cross(w, r)),
            (origin, " + ", Col(wxr)),
            Boxed((Col(v, unit=True),)),
            breaks=(3,),
        )
        b.line(rigid)
        b.say(f"{name} is fixed in body {point.body}: ", rigid, ".")
        return b.build()

    def point_acceleration_step(self, point: SpatialPoint, role: str) -> Step:
        """a_P = a_O + alpha x r + omega x (omega x r) + 2 omega x v_rel + a_rel."""
        name = point.name
        motion = self.analysis.points[name]
        body = self.analysis.bodies[point.body]
        b = self.builder(
            "spatial.point.acceleration", f"Acceleration of {name}{role}: the five-term formula"
        )
        src = ("points", name, "acceleration_terms")
        ao = b.value("a_O", motion.a_origin, "m/s^2", (*src, "origin"))
        al = b.value(f"alpha({point.body})", body.alpha, "rad/s^2", ("bodies", point.body, "alpha"))
        w = b.value(f"omega({point.body})", body.omega, "rad/s", ("bodies", point.body, "omega"))
        r = b.value(f"r(O{point.body},{name})", motion.rigid.r, "m")
        t = b.value("alpha x r", motion.tangential, "m/s^2", (*src, "tangential"))
        inner = b.value("omega x r", motion.rigid.omega_x_r, "m/s")
        c = b.value("omega x (omega x r)", motion.centripetal, "m/s^2", (*src, "centripetal"))
        cor = b.value("2 omega x v_rel", motion.coriolis, "m/s^2", (*src, "coriolis"))
        rel = b.value("a_rel", motion.relative, "m/s^2", (*src, "relative"))
        a = b.value(f"a({name})", motion.acceleration, "m/s^2", ("points", name, "acceleration"))
        b.check("cross", t, al, r)
        b.check("cross", inner, w, r)
        b.check("cross", c, w, inner)
        b.check("sum", a, ao, t, c, cor, rel)
        self.write_five_terms(b, point, FiveTerms(ao, al, w, r, t, inner, c, cor, rel, a))
        return b.build()

    def write_five_terms(self, b: StepBuilder, point: SpatialPoint, keys: FiveTerms) -> None:
        """The five-term formula, its cross products and its sum, in LaTeX and in words."""
        n, k = tex.name(point.name), tex.name(point.body)
        alpha, omega = vector(r"\alpha", k, "alpha"), vector(r"\omega", k, "omega")
        tangential = Equation.of(
            (alpha, TIMES, R), latex_only(Cross(keys.alpha, keys.r)), Col(keys.tangential)
        )
        omega_x_r = Equation.of(
            (omega, TIMES, R), latex_only(Cross(keys.omega, keys.r)), Col(keys.omega_x_r)
        )
        centripetal = Equation.of(
            (omega, TIMES, "(", omega, TIMES, R, ")"),
            latex_only(Cross(keys.omega, keys.omega_x_r)),
            Col(keys.centripetal),
        )
        terms = (keys.a_origin, keys.tangential, keys.centripetal, keys.coriolis, keys.relative)
        total = Equation.of(
            vector("a", n, f"a({point.name})"),
            latex_only(*joined(" + ", [(column(b, key),) for key in terms])),
            Boxed((Col(keys.a, unit=True),)),
        )
        b.line(
            rf"&\vec{{a}}_{{{n}}} = \vec{{a}}_{{O_{{{k}}}}} + \vec{{\alpha}}_{{{k}}} \times "
            rf"\vec{{r}} + \vec{{\omega}}_{{{k}}} \times (\vec{{\omega}}_{{{k}}} \times "
            rf"\vec{{r}}) + 2\,\vec{{\omega}} \times \vec{{v}}_{{\mathrm{{rel}}}} + "
            rf"\vec{{a}}_{{\mathrm{{rel}}}}"
        )
        b.line("&", tangential, r", \quad ", omega_x_r)
        b.line("&", centripetal)
        b.line(total)
        b.say(
            f"Five-term formula for {point.name} with r = r(O{point.body},{point.name}) = ",
            Col(keys.r),
            ": a_O = ",
            Col(keys.a_origin),
            "; ",
            tangential,
            "; ",
            centripetal,
            "; ",
            *self.relative_terms_why(point, keys),
            ". Sum: ",
            total,
            ".",
        )

    def relative_terms_why(self, point: SpatialPoint, keys: FiveTerms) -> tuple[Piece, ...]:
        """Why 2 omega x v_rel and a_rel are what they are: a sliding joint, or a fixed point."""
        joint = next(j for j in self.chain.joints if j.name == point.body)
        if joint.type == "prismatic":
            parent = self.parent_of(joint)
            return (
                f"joint {joint.name} slides, so the Coriolis term 2 omega({parent}) cross v_rel = ",
                Col(keys.coriolis),
                " and the relative term ",
                Col(keys.relative),
                " appear",
            )
        return (
            f"{point.name} is fixed in body {point.body} (v_rel = 0, a_rel = 0), so the Coriolis "
            "and relative terms are zero",
        )

    def parent_of(self, joint: SpatialJoint) -> str:
        index = self.chain.joints.index(joint)
        return self.parent_name(index)

    def summary(self) -> Step:
        b = self.builder("summary", "Results")
        rows: list[tuple[Piece, ...]] = []
        results = [
            (f"Body {name}", "bodies", name, (("omega", body.omega), ("alpha", body.alpha)))
            for name, body in self.analysis.bodies.items()
        ] + [
            (
                f"Point {name}",
                "points",
                name,
                (("velocity", p.velocity), ("acceleration", p.acceleration)),
            )
            for name, p in self.analysis.points.items()
        ]
        for what, kind, name, ((first, x), (second, y)) in results:
            x_unit, y_unit = RESULT_UNITS[first], RESULT_UNITS[second]
            xk = b.value(f"{SHORT[first]}({name})", x, x_unit, (kind, name, first))
            yk = b.value(f"{SHORT[second]}({name})", y, y_unit, (kind, name, second))
            row = (
                Equation.of(vector(SYMBOL[first], tex.name(name), SHORT[first]), Pt(xk, x_unit)),
                Sym(", & ", ", "),
                Equation.of(vector(SYMBOL[second], tex.name(name), SHORT[second]), Pt(yk, y_unit)),
            )
            rows.append(row)
            b.say(f"{what}: ", *row, ".")
        b.line(r"&\begin{array}{ll} ", *joined(r" \\ ", rows), r" \end{array}")
        return b.build()

    def reading(self) -> Step:
        """Reading the answer: each body turns with |omega| about the unit axis u = omega/|omega|,
        counter-clockwise seen from the tip of u (the right-hand rule); omega . alpha > 0 means
        |omega| grows. Each point moves with speed |v| along v/|v|; v . a > 0 means it speeds up."""
        b = self.builder("reading", "Reading the answer")
        for name, body in self.analysis.bodies.items():
            self.read_body(b, name, body)
        for point in self.chain.points:
            self.read_point(b, point.name, self.analysis.points[point.name])
        return b.build()

    def read_body(self, b: StepBuilder, name: str, body: BodyMotion) -> None:
        """|omega|, u = omega/|omega| and omega . alpha of one body, said in words."""
        n = tex.name(name)
        w = b.value(f"omega({name})", body.omega, "rad/s", ("bodies", name, "omega"))
        al = b.value(f"alpha({name})", body.alpha, "rad/s^2", ("bodies", name, "alpha"))
        size = float(np.linalg.norm(body.omega))
        speed = b.value(f"|omega({name})|", size, "rad/s")
        b.check("norm", speed, w)
        if b.is_zero(speed):
            words = f"body {name} does not turn at this instant"
            _write_at_rest(b, rf"|\vec{{\omega}}_{{{n}}}|", speed, words)
            b.say(f"omega({name}) = ", Col(w), f": {words}.")
            return
        axis = b.value(f"u({name})", body.omega / size, "")
        power = _put_power(b, f"omega.alpha({name})", body.omega, body.alpha, "rad^2/s^3")
        b.check("dot", power, w, al)
        trend = speed_trend(b, power, "at a steady rate")
        turning = np.cross(body.omega, body.alpha) / size  # du/dt |omega|: the axis turns
        if not all(self.fmt.is_zero(float(x), "rad/s^2") for x in turning):
            trend += ", and the axis itself turns (alpha is not along omega)"
        b.line(
            rf"&|\vec{{\omega}}_{{{n}}}| = ",
            Num(speed, unit=True),
            rf", \quad \vec{{u}}_{{{n}}} = \vec{{\omega}}_{{{n}}} / |\vec{{\omega}}_{{{n}}}| = ",
            Pt(axis),
            rf", \quad \vec{{\omega}}_{{{n}}} \cdot \vec{{\alpha}}_{{{n}}} = ",
            Num(power, unit=True),
            r" \quad \Rightarrow \text{"
            + tex.escape_text(f"counter-clockwise about u, {trend}")
            + "}",
        )
        b.say(
            f"omega({name}) = ",
            Col(w),
            f", alpha({name}) = ",
            Col(al),
            f": body {name} turns at ",
            Num(speed, unit=True),
            " about the axis u = ",
            Pt(axis),
            f" (nearest {_nearest_axis(body.omega)}), counter-clockwise seen from the tip of u, "
            f"{trend} (omega . alpha = ",
            Num(power, unit=True),
            f"{sense_clause(b, power, 'the rotation speeding up')}).",
        )

    def read_point(self, b: StepBuilder, name: str, motion: PointMotion) -> None:
        """|v| and v . a of one point, said in words."""
        n = tex.name(name)
        v = b.value(f"v({name})", motion.velocity, "m/s", ("points", name, "velocity"))
        a = b.value(f"a({name})", motion.acceleration, "m/s^2", ("points", name, "acceleration"))
        speed = b.value(f"|v({name})|", float(np.linalg.norm(motion.velocity)), "m/s")
        b.check("norm", speed, v)
        if b.is_zero(speed):
            words = f"{name} is at rest at this instant"
            _write_at_rest(b, rf"|\vec{{v}}_{{{n}}}|", speed, words)
            b.say(f"v({name}) = ", Col(v), f": {words}.")
            return
        power = _put_power(b, f"v.a({name})", motion.velocity, motion.acceleration, "m^2/s^3")
        b.check("dot", power, v, a)
        said = Words(
            (
                f"{name} moves at a speed of ",
                Num(speed, unit=True),
                f", mostly {_nearest_axis(motion.velocity)}, "
                f"{speed_trend(b, power, 'at a steady speed')}",
            )
        )
        b.line(
            rf"&|\vec{{v}}_{{{n}}}| = ",
            Num(speed, unit=True),
            rf", \quad \vec{{v}}_{{{n}}} \cdot \vec{{a}}_{{{n}}} = ",
            Num(power, unit=True),
            r" \quad \Rightarrow ",
            said,
        )
        b.say(
            f"v({name}) = ",
            Col(v),
            f", a({name}) = ",
            Col(a),
            ": ",
            said,
            " (v . a = ",
            Num(power, unit=True),
            f"{sense_clause(b, power, 'speeding up')}).",
        )

    def figure(self) -> str:
        """The chain at the instant in an isometric drawing: the joint axes (dashed, through their
        origins), the bodies from joint to joint and to their points, the fixed frame E1, E2, E3,
        and each body's omega from its joint origin at its own stated scale."""
        project = ISOMETRIC
        places = [j.origin for j in self.chain.joints] + [p.position for p in self.chain.points]
        drawn = [project @ x for x in places]
        per_mm = figures.model_scale([*drawn, np.zeros(2)])
        extent = figures.PAPER * per_mm  # m: the drawing's size
        omegas = [float(np.linalg.norm(b.omega)) for b in self.analysis.bodies.values()]
        k = figures.nice_scale(max(omegas, default=0.0), OMEGA_PAPER_CM)
        segments, arrows, dots = self.chain_drawing(extent, 10.0 * per_mm / k)
        corner = np.min(drawn, axis=0) - 0.2 * extent  # the frame E1, E2, E3 below on the left
        for i, label in enumerate(("E1", "E2", "E3")):
            unit = np.zeros(3)
            unit[i] = 0.25 * extent
            arrows.append(figures.Arrow(corner, corner + project @ unit, label, label, "position"))
        length_scale = 10.0 * per_mm
        caption = (
            f"Isometric view: lengths 1 cm = {length_scale:g} m; "
            f"{figures.scale_text(k, 'rad/s')} for omega"
        )
        title = f"The chain at the instant{': ' + self.chain.title if self.chain.title else ''}"
        return figures.svg(
            title,
            arrows,
            dots,
            segments,
            per_mm,
            caption,
            {
                "data-scale": f"{k:g}",
                "data-unit": "rad/s",
                "data-length-scale": f"{length_scale:g}",
                "data-projection": ";".join(",".join(f"{x:.17g}" for x in row) for row in project),
            },
        )

    def chain_drawing(
        self, extent: float, to_model: float
    ) -> tuple[list[tuple[np.ndarray, np.ndarray, str]], list[figures.Arrow], list[figures.Dot]]:
        """The joint axes, each body's omega (to_model: rad/s -> m of the drawing), the bodies
        from their joint origin to what they carry, and a dot per place, projected."""
        project = ISOMETRIC
        segments: list[tuple[np.ndarray, np.ndarray, str]] = []
        arrows: list[figures.Arrow] = []
        marks: dict[tuple[float, ...], tuple[np.ndarray, list[str], bool]] = {}

        def mark(at: np.ndarray, label: str, fixed: bool) -> None:
            """One dot per place, its labels joined: 'O3 = A' where a point sits on an origin."""
            key = tuple(np.round(at / max(extent, 1e-300), 9))
            marks.setdefault(key, (at, [], fixed))[1].append(label)

        half = 0.12 * extent
        attached: dict[str, list[np.ndarray]] = {GROUND: []}
        attached.update({joint.name: [joint.origin] for joint in self.chain.joints})
        for index, joint in enumerate(self.chain.joints):
            attached[self.parent_name(index)].append(joint.origin)
            ends = (joint.origin - half * joint.axis, joint.origin + half * joint.axis)
            segments.append((project @ ends[0], project @ ends[1], "position"))
            mark(joint.origin, f"O{joint.name}", index == 0)
            start = project @ joint.origin
            tip = start + to_model * (project @ self.analysis.bodies[joint.name].omega)
            arrows.append(
                figures.Arrow(start, tip, f"omega({joint.name})", f"ω{joint.name}", "absolute")
            )
        for point in self.chain.points:
            attached[point.body].append(point.position)
            mark(point.position, point.name, point.body == GROUND)
        for body, where in attached.items():  # body k from its joint origin to what it carries
            if body != GROUND:
                segments += [(project @ where[0], project @ x, "link") for x in where[1:]]
        dots = [
            figures.Dot(project @ at, " = ".join(dict.fromkeys(labels)), fixed)
            for at, labels, fixed in marks.values()
        ]
        return segments, arrows, dots

    def steps(self) -> list[Step]:
        out = [replace(self.data(), figure=self.figure())]
        for index, joint in enumerate(self.chain.joints):
            out += self.body_steps(index, joint)
        for point in self.chain.points:
            if point.name not in self.shown:
                out += self.point_steps(point.name)
        out.append(self.reading())
        out.append(self.summary())
        return out


def _put_power(b: StepBuilder, key: str, rate: np.ndarray, change: np.ndarray, unit: str) -> Ref:
    """x . x_dot, which has the sign of d|x|/dt; shown as 0 below the rounding of |x| |x_dot|."""
    reference = float(np.linalg.norm(rate)) * float(np.linalg.norm(change))
    return b.value(key, float(np.dot(rate, change)), unit, reference=reference)


def _write_at_rest(b: StepBuilder, size: str, speed: Ref, words: str) -> None:
    """|x| = 0 => the words saying the body or point does not move."""
    b.line(
        f"&{size} = ",
        Num(speed, unit=True),
        r" \quad \Rightarrow \text{" + tex.escape_text(words) + "}",
    )


def _nearest_axis(vector: np.ndarray) -> str:
    """The fixed axis closest to a vector's direction, with its sign: '+E3', '-E1'."""
    i = int(np.argmax(np.abs(vector)))
    return f"{'+' if vector[i] > 0 else '-'}E{i + 1}"


def spatial_steps(chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter) -> list[Step]:
    """The steps of a spatial chain's solution (numbers from ``analysis``)."""
    return SpatialSteps(chain, analysis, fmt).steps()
