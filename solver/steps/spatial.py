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
from dataclasses import replace

import numpy as np

from solver.spatial import GROUND, SpatialAnalysis, SpatialChain, SpatialJoint
from solver.steps import figures
from solver.steps import latex as tex
from solver.steps.builder import StepBuilder
from solver.steps.digits import DigitPlan
from solver.steps.format import Formatter, latex_unit
from solver.steps.model import Step

V0 = r"\vec{0}"
# The isometric drawing: x towards the viewer on the lower left, y to the lower right, z up,
# full length along each axis: (X, Y) = (cos 30 (y - x), z - sin 30 (x + y)).
ISOMETRIC = np.array([[-math.cos(math.pi / 6), math.cos(math.pi / 6), 0.0], [-0.5, -0.5, 1.0]])
OMEGA_PAPER_CM = 3.0  # the largest omega is drawn at most this long
UNITS = r"\mathbf{E}_1 & \mathbf{E}_2 & \mathbf{E}_3"


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


class SpatialSteps:
    def __init__(
        self,
        chain: SpatialChain,
        analysis: SpatialAnalysis,
        fmt: Formatter,
        plan: DigitPlan | None = None,
    ) -> None:
        self.plan = plan
        self.chain = chain
        self.analysis = analysis
        self.fmt = Formatter(fmt.digits, _scales(chain, analysis))
        self.shown: set[str] = set()  # points already shown (at a joint origin)

    def builder(self, kind: str, title: str) -> StepBuilder:
        return StepBuilder(self.fmt, kind, title, self.plan)

    def col(self, b: StepBuilder, key: str) -> str:
        return V0 if b.is_zero(key) else b.col(key)

    def data(self) -> Step:
        b = self.builder("data", "Data")
        b.say(
            "Method: composition of angular velocities in a chain of rotating frames. Joint k "
            "connects body k-1 (the ground for the first joint) to body k; its axis e_k is "
            "fixed in body k-1 and turns with it. Vectors are components in the fixed frame "
            "E1, E2, E3 at the instant."
        )
        rows = []
        for j in self.chain.joints:
            e = b.put(f"e({j.name})", j.axis, "")
            o = b.put(f"O({j.name})", j.origin, "m")
            rate_unit = ("rad/s", "rad/s^2") if j.type == "revolute" else ("m/s", "m/s^2")
            q = b.put(f"rate({j.name})", j.rate, rate_unit[0])
            qd = b.put(f"rate_dot({j.name})", j.rate_dot, rate_unit[1])
            n = tex.name(j.name)
            symbol = r"\omega" if j.type == "revolute" else "v"
            rows.append(
                rf"&\text{{joint }} {n} \text{{ ({j.type})}}: \; O_{{{n}}} = "
                rf"({', '.join(b.entries(o))}){latex_unit('m')}, \; \vec{{e}}_{{{n}}} = "
                rf"({', '.join(b.entries(e))}), \; {symbol}_{{{n}}} = {b.numu(q)}, \; "
                rf"\dot{{{symbol}}}_{{{n}}} = {b.numu(qd)}"
            )
            b.say(
                f"Joint {j.name} ({j.type}) at O = {b.txt(o)}, axis e = {b.txtn(e)}, rate "
                f"{b.txt(q)}, rate of change {b.txt(qd)}."
            )
        for line in rows:
            b.line(line)
        return b.build()

    def parent_name(self, index: int) -> str:
        return GROUND if index == 0 else self.chain.joints[index - 1].name

    def parent_vectors(
        self, index: int
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """omega, alpha, origin, v_origin, a_origin of body k-1 (zeros for the ground)."""
        if index == 0:
            z = np.zeros(3)
            return z, z, z, z, z
        body = self.analysis.bodies[self.chain.joints[index - 1].name]
        return (body.omega, body.alpha, body.origin, body.velocity_origin, body.acceleration_origin)

    def parent_rate(self, b: StepBuilder, index: int, name: str, value: np.ndarray) -> str:
        """omega_{k-1} (or alpha_{k-1}) of body k-1; the ground's is zero and has no source."""
        parent = self.parent_name(index)
        unit = "rad/s" if name == "omega" else "rad/s^2"
        return b.put(
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
        body = self.analysis.bodies[joint.name]
        w_parent, al_parent, o_parent, v_parent, a_parent = self.parent_vectors(index)
        parent = self.parent_name(index)
        n, p = tex.name(joint.name), tex.name(parent)
        out = []
        # angular velocity
        b = self.builder("spatial.omega", f"Angular velocity of body {joint.name}")
        wp = self.parent_rate(b, index, "omega", w_parent)
        w = b.put(f"omega({joint.name})", body.omega, "rad/s", ("bodies", joint.name, "omega"))
        e = b.put(f"e({joint.name})", joint.axis, "")
        if joint.type == "revolute":
            q = b.put(f"rate({joint.name})", joint.rate, "rad/s")
            term = b.put(f"rate e({joint.name})", joint.rate * joint.axis, "rad/s")
            b.check("product", term, q, e)
            b.check("sum", w, wp, term)
            b.line(
                rf"&\vec{{\omega}}_{{{n}}} = \vec{{\omega}}_{{{p}}} + \omega_{{{n}}}\,"
                rf"\vec{{e}}_{{{n}}} = {self.col(b, wp)} + {tex.paren(b.num(q))} \cdot "
                rf"{b.col(e)} = {tex.boxed_result(b.colu(w))}"
            )
            b.say(
                f"Angular velocities add: omega({joint.name}) = omega({parent}) + "
                f"{b.txtn(q)} times e({joint.name}) = {b.txt(wp)} + {b.txt(term)} = "
                f"{b.txt(w)}."
            )
        else:
            b.check("sum", w, wp)
            b.line(
                rf"&\vec{{\omega}}_{{{n}}} = \vec{{\omega}}_{{{p}}} = "
                rf"{tex.boxed_result(b.colu(w))}"
            )
            b.say(
                f"A prismatic joint adds no rotation: omega({joint.name}) = omega({parent}) = "
                f"{b.txt(w)}."
            )
        out.append(b.build())
        # the turning axis
        b = self.builder("spatial.axis_rate", f"Rate of change of the axis of joint {joint.name}")
        wp = self.parent_rate(b, index, "omega", w_parent)
        e = b.put(f"e({joint.name})", joint.axis, "")
        ed = b.put(f"e_dot({joint.name})", body.axis_rate, "1/s")
        b.check("cross", ed, wp, e)
        b.line(
            rf"&\dot{{\vec{{e}}}}_{{{n}}} = \vec{{\omega}}_{{{p}}} \times \vec{{e}}_{{{n}}} = "
            rf"{tex.determinant3(b.entries(wp), b.entries(e), UNITS)} = "
            rf"{tex.boxed_result(b.colu(ed))}"
        )
        b.say(
            f"The axis e({joint.name}) is fixed in body {parent}, so it turns with "
            f"omega({parent}): its rate of change is omega({parent}) cross e({joint.name}) = "
            f"{b.txt(ed)}."
        )
        out.append(b.build())
        # angular acceleration
        b = self.builder("spatial.alpha", f"Angular acceleration of body {joint.name}")
        alp = self.parent_rate(b, index, "alpha", al_parent)
        al = b.put(f"alpha({joint.name})", body.alpha, "rad/s^2", ("bodies", joint.name, "alpha"))
        if joint.type == "revolute":
            e = b.put(f"e({joint.name})", joint.axis, "")
            ed = b.put(f"e_dot({joint.name})", body.axis_rate, "1/s")
            q = b.put(f"rate({joint.name})", joint.rate, "rad/s")
            qd = b.put(f"rate_dot({joint.name})", joint.rate_dot, "rad/s^2")
            t1 = b.put(f"rate_dot e({joint.name})", joint.rate_dot * joint.axis, "rad/s^2")
            t2 = b.put(f"rate e_dot({joint.name})", joint.rate * body.axis_rate, "rad/s^2")
            b.check("product", t1, qd, e)
            b.check("product", t2, q, ed)
            b.check("sum", al, alp, t1, t2)
            b.line(
                rf"&\vec{{\alpha}}_{{{n}}} = \vec{{\alpha}}_{{{p}}} + \dot{{\omega}}_{{{n}}}\,"
                rf"\vec{{e}}_{{{n}}} + \omega_{{{n}}}\,\dot{{\vec{{e}}}}_{{{n}}} = "
                rf"{self.col(b, alp)} + {tex.paren(b.num(qd))} \cdot {b.col(e)} + "
                rf"{tex.paren(b.num(q))} \cdot {b.col(ed)} = {tex.boxed_result(b.colu(al))}"
            )
            b.say(
                f"Differentiating omega({joint.name}) = omega({parent}) + rate e: "
                f"alpha({joint.name}) = alpha({parent}) + rate-dot e + rate times de/dt = "
                f"{b.txt(alp)} + {b.txt(t1)} + {b.txt(t2)} = {b.txt(al)}. The last term comes "
                "from the turning axis; leaving it out is a common mistake."
            )
        else:
            b.check("sum", al, alp)
            b.line(
                rf"&\vec{{\alpha}}_{{{n}}} = \vec{{\alpha}}_{{{p}}} = "
                rf"{tex.boxed_result(b.colu(al))}"
            )
            b.say(f"alpha({joint.name}) = alpha({parent}) = {b.txt(al)} (prismatic joint).")
        out.append(b.build())
        at_origin = self.point_at_origin(index, joint)
        if at_origin is not None:
            self.shown.add(at_origin)
            out += self.point_steps(at_origin, f" (the origin O{joint.name} of joint {joint.name})")
        else:
            out += self.origin_steps(
                index, joint, w_parent, al_parent, o_parent, v_parent, a_parent
            )
        return out

    def origin_steps(
        self,
        index: int,
        joint: SpatialJoint,
        w_parent: np.ndarray,
        al_parent: np.ndarray,
        o_parent: np.ndarray,
        v_parent: np.ndarray,
        a_parent: np.ndarray,
    ) -> list[Step]:
        body = self.analysis.bodies[joint.name]
        parent = self.parent_name(index)
        n, p = tex.name(joint.name), tex.name(parent)
        r_np = joint.origin - o_parent
        origin_p = "O_{" + p + "}" if index else "O"
        out = []
        b = self.builder("spatial.origin.velocity", f"Velocity of the joint origin O{joint.name}")
        vp = b.put(f"v(O{parent})", v_parent, "m/s")
        wp = self.parent_rate(b, index, "omega", w_parent)
        r = b.put("r", r_np, "m")
        wxr = b.put("omega x r", np.cross(w_parent, r_np), "m/s")
        v = b.put(f"v(O{joint.name})", body.velocity_origin, "m/s")
        b.check("cross", wxr, wp, r)
        terms = [vp, wxr]
        extra = ""
        if joint.type == "prismatic":
            e = b.put(f"e({joint.name})", joint.axis, "")
            q = b.put(f"rate({joint.name})", joint.rate, "m/s")
            rel = b.put("v_rel", joint.rate * joint.axis, "m/s")
            b.check("product", rel, q, e)
            terms.append(rel)
            extra = rf" + v_{{{n}}}\,\vec{{e}}_{{{n}}}"
        b.check("sum", v, *terms)
        b.line(
            rf"&\vec{{v}}_{{O_{{{n}}}}} = \vec{{v}}_{{{origin_p}}} + \vec{{\omega}}_{{{p}}} "
            rf"\times \vec{{r}}_{{{origin_p} O_{{{n}}}}}{extra} = {self.col(b, vp)} + "
            rf"{tex.determinant3(b.entries(wp), b.entries(r), UNITS)}"
            + (rf" + {b.col(terms[2])}" if len(terms) > 2 else "")
            + rf" = {tex.boxed_result(b.colu(v))}"
        )
        b.say(
            f"The origin O{joint.name} of joint {joint.name} moves with body {parent}: "
            f"v = v(O{parent}) + omega({parent}) cross r = {b.txt(vp)} + {b.txt(wxr)}"
            + (f" + {b.txt(terms[2])} (sliding)" if len(terms) > 2 else "")
            + f" = {b.txt(v)}."
        )
        out.append(b.build())
        b = self.builder(
            "spatial.origin.acceleration", f"Acceleration of the joint origin O{joint.name}"
        )
        ap = b.put(f"a(O{parent})", a_parent, "m/s^2")
        wp = self.parent_rate(b, index, "omega", w_parent)
        alp = self.parent_rate(b, index, "alpha", al_parent)
        r = b.put("r", r_np, "m")
        t = b.put("alpha x r", np.cross(al_parent, r_np), "m/s^2")
        inner = b.put("omega x r", np.cross(w_parent, r_np), "m/s")
        c = b.put("omega x (omega x r)", np.cross(w_parent, np.cross(w_parent, r_np)), "m/s^2")
        a = b.put(f"a(O{joint.name})", body.acceleration_origin, "m/s^2")
        b.check("cross", t, alp, r)
        b.check("cross", inner, wp, r)
        b.check("cross", c, wp, inner)
        terms = [ap, t, c]
        if joint.type == "prismatic":
            e = b.put(f"e({joint.name})", joint.axis, "")
            q = b.put(f"rate({joint.name})", joint.rate, "m/s")
            qd = b.put(f"rate_dot({joint.name})", joint.rate_dot, "m/s^2")
            rel_v = b.put("v_rel", joint.rate * joint.axis, "m/s")
            cor = b.put(
                "2 omega x v_rel", 2.0 * np.cross(w_parent, joint.rate * joint.axis), "m/s^2"
            )
            rel_a = b.put("a_rel", joint.rate_dot * joint.axis, "m/s^2")
            b.check("product", rel_v, q, e)
            b.check("cross", cor, wp, rel_v, factor=2.0)
            b.check("product", rel_a, qd, e)
            terms += [cor, rel_a]
        b.check("sum", a, *terms)
        b.line(
            rf"&\vec{{a}}_{{O_{{{n}}}}} = \vec{{a}}_{{{origin_p}}} + \vec{{\alpha}}_{{{p}}} "
            rf"\times \vec{{r}} + \vec{{\omega}}_{{{p}}} \times (\vec{{\omega}}_{{{p}}} \times "
            rf"\vec{{r}})"
            + (
                r" + 2\,\vec{\omega} \times \vec{v}_{\mathrm{rel}} + "
                r"\vec{a}_{\mathrm{rel}}"
                if joint.type == "prismatic"
                else ""
            )
        )
        b.line(
            r"&\phantom{\vec{a}} = "
            + " + ".join(self.col(b, k) for k in terms)
            + rf" = {tex.boxed_result(b.colu(a))}"
        )
        b.say(
            f"Acceleration of O{joint.name}: a(O{parent}) + alpha({parent}) cross r + "
            f"omega({parent}) cross (omega({parent}) cross r)"
            + (" + 2 omega cross v_rel + a_rel" if joint.type == "prismatic" else "")
            + " = "
            + " + ".join(b.txt(k) for k in terms)
            + f" = {b.txt(a)}."
        )
        out.append(b.build())
        return out

    def point_steps(self, name: str, role: str = "") -> list[Step]:
        point = next(p for p in self.chain.points if p.name == name)
        motion = self.analysis.points[name]
        if point.body == GROUND:
            b = self.builder("spatial.point.fixed", f"Point {name} (fixed)")
            v = b.put(f"v({name})", motion.velocity, "m/s", ("points", name, "velocity"))
            a = b.put(f"a({name})", motion.acceleration, "m/s^2", ("points", name, "acceleration"))
            b.line(rf"&\vec{{v}}_{{{tex.name(name)}}} = \vec{{a}}_{{{tex.name(name)}}} = {V0}")
            b.say(f"{name} is a point of the ground: v = {b.txt(v)}, a = {b.txt(a)}.")
            return [b.build()]
        body = self.analysis.bodies[point.body]
        joint = next(j for j in self.chain.joints if j.name == point.body)
        r_np = point.position - body.origin
        n, k = tex.name(name), tex.name(point.body)
        out = []
        b = self.builder("spatial.point.velocity", f"Velocity of {name}{role}")
        vo = b.put(f"v(O{point.body})", body.velocity_origin, "m/s")
        w = b.put(f"omega({point.body})", body.omega, "rad/s", ("bodies", point.body, "omega"))
        r = b.put(f"r(O{point.body},{name})", r_np, "m")
        wxr = b.put("omega x r", np.cross(body.omega, r_np), "m/s")
        v = b.put(f"v({name})", motion.velocity, "m/s", ("points", name, "velocity"))
        b.check("cross", wxr, w, r)
        b.check("sum", v, vo, wxr)
        b.line(
            rf"&\vec{{v}}_{{{n}}} = \vec{{v}}_{{O_{{{k}}}}} + \vec{{\omega}}_{{{k}}} \times "
            rf"\vec{{r}}_{{O_{{{k}}}{n}}} = {self.col(b, vo)} + "
            rf"{tex.determinant3(b.entries(w), b.entries(r), UNITS)}"
        )
        b.line(
            rf"&\phantom{{\vec{{v}}_{{{n}}}}} = {self.col(b, vo)} + {b.col(wxr)} = "
            rf"{tex.boxed_result(b.colu(v))}"
        )
        b.say(
            f"{name} is fixed in body {point.body}: v({name}) = v(O{point.body}) + "
            f"omega({point.body}) cross r = {b.txt(vo)} + {b.txt(wxr)} = {b.txt(v)}."
        )
        out.append(b.build())
        b = self.builder(
            "spatial.point.acceleration", f"Acceleration of {name}{role}: the five-term formula"
        )
        src = ("points", name, "acceleration_terms")
        ao = b.put("a_O", motion.a_origin, "m/s^2", (*src, "origin"))
        al = b.put(f"alpha({point.body})", body.alpha, "rad/s^2", ("bodies", point.body, "alpha"))
        w = b.put(f"omega({point.body})", body.omega, "rad/s", ("bodies", point.body, "omega"))
        r = b.put(f"r(O{point.body},{name})", r_np, "m")
        t = b.put("alpha x r", motion.tangential, "m/s^2", (*src, "tangential"))
        inner = b.put("omega x r", np.cross(body.omega, r_np), "m/s")
        c = b.put("omega x (omega x r)", motion.centripetal, "m/s^2", (*src, "centripetal"))
        cor = b.put("2 omega x v_rel", motion.coriolis, "m/s^2", (*src, "coriolis"))
        rel = b.put("a_rel", motion.relative, "m/s^2", (*src, "relative"))
        a = b.put(f"a({name})", motion.acceleration, "m/s^2", ("points", name, "acceleration"))
        b.check("cross", t, al, r)
        b.check("cross", inner, w, r)
        b.check("cross", c, w, inner)
        b.check("sum", a, ao, t, c, cor, rel)
        b.line(
            rf"&\vec{{a}}_{{{n}}} = \vec{{a}}_{{O_{{{k}}}}} + \vec{{\alpha}}_{{{k}}} \times "
            rf"\vec{{r}} + \vec{{\omega}}_{{{k}}} \times (\vec{{\omega}}_{{{k}}} \times "
            rf"\vec{{r}}) + 2\,\vec{{\omega}} \times \vec{{v}}_{{\mathrm{{rel}}}} + "
            rf"\vec{{a}}_{{\mathrm{{rel}}}}"
        )
        b.line(
            rf"&\vec{{\alpha}}_{{{k}}} \times \vec{{r}} = "
            rf"{tex.determinant3(b.entries(al), b.entries(r), UNITS)} = {b.col(t)}, \quad "
            rf"\vec{{\omega}}_{{{k}}} \times \vec{{r}} = "
            rf"{tex.determinant3(b.entries(w), b.entries(r), UNITS)} = {b.col(inner)}"
        )
        b.line(
            rf"&\vec{{\omega}}_{{{k}}} \times (\vec{{\omega}}_{{{k}}} \times \vec{{r}}) = "
            rf"{tex.determinant3(b.entries(w), b.entries(inner), UNITS)} = {b.col(c)}"
        )
        b.line(
            rf"&\vec{{a}}_{{{n}}} = {self.col(b, ao)} + {self.col(b, t)} + {self.col(b, c)} + "
            rf"{self.col(b, cor)} + {self.col(b, rel)} = {tex.boxed_result(b.colu(a))}"
        )
        if joint.type == "prismatic":
            parent = self.parent_of(joint)
            why = (
                f"joint {joint.name} slides, so the Coriolis term 2 omega({parent}) cross "
                f"v_rel = {b.txt(cor)} and the relative term {b.txt(rel)} appear"
            )
        else:
            why = (
                f"{name} is fixed in body {point.body} (v_rel = 0, a_rel = 0), so the Coriolis "
                "and relative terms are zero"
            )
        b.say(
            f"Five-term formula for {name} with r = r(O{point.body},{name}) = {b.txt(r)}: "
            f"a_O = {b.txt(ao)}; alpha cross r = {b.txt(t)}; omega cross (omega cross r) = "
            f"{b.txt(c)}; {why}. Sum: a({name}) = {b.txt(a)}."
        )
        out.append(b.build())
        return out

    def parent_of(self, joint: SpatialJoint) -> str:
        index = self.chain.joints.index(joint)
        return self.parent_name(index)

    def summary(self) -> Step:
        b = self.builder("summary", "Results")
        rows = []
        for name, body in self.analysis.bodies.items():
            w = b.put(f"omega({name})", body.omega, "rad/s", ("bodies", name, "omega"))
            al = b.put(f"alpha({name})", body.alpha, "rad/s^2", ("bodies", name, "alpha"))
            rows.append(
                rf"\vec{{\omega}}_{{{tex.name(name)}}} = ({', '.join(b.entries(w))})"
                rf"{latex_unit('rad/s')}, & \vec{{\alpha}}_{{{tex.name(name)}}} = "
                rf"({', '.join(b.entries(al))}){latex_unit('rad/s^2')}"
            )
            b.say(f"Body {name}: omega = {b.txt(w)}, alpha = {b.txt(al)}.")
        for name, p in self.analysis.points.items():
            v = b.put(f"v({name})", p.velocity, "m/s", ("points", name, "velocity"))
            a = b.put(f"a({name})", p.acceleration, "m/s^2", ("points", name, "acceleration"))
            rows.append(
                rf"\vec{{v}}_{{{tex.name(name)}}} = ({', '.join(b.entries(v))})"
                rf"{latex_unit('m/s')}, & \vec{{a}}_{{{tex.name(name)}}} = "
                rf"({', '.join(b.entries(a))}){latex_unit('m/s^2')}"
            )
            b.say(f"Point {name}: v = {b.txt(v)}, a = {b.txt(a)}.")
        b.line(r"&\begin{array}{ll} " + r" \\ ".join(rows) + r" \end{array}")
        return b.build()

    def reading(self) -> Step:
        """Reading the answer: each body turns with |omega| about the unit axis u = omega/|omega|,
        counter-clockwise seen from the tip of u (the right-hand rule); omega . alpha > 0 means
        |omega| grows. Each point moves with speed |v| along v/|v|; v . a > 0 means it speeds up."""
        b = self.builder("reading", "Reading the answer")
        for name, body in self.analysis.bodies.items():
            n = tex.name(name)
            w = b.put(f"omega({name})", body.omega, "rad/s", ("bodies", name, "omega"))
            al = b.put(f"alpha({name})", body.alpha, "rad/s^2", ("bodies", name, "alpha"))
            size = float(np.linalg.norm(body.omega))
            speed = b.put(f"|omega({name})|", size, "rad/s")
            b.check("norm", speed, w)
            if b.is_zero(speed):
                words = f"body {name} does not turn at this instant"
                b.line(
                    rf"&|\vec{{\omega}}_{{{n}}}| = {b.numu(speed)} \quad \Rightarrow \text{{"
                    + tex.escape_text(words)
                    + "}"
                )
                b.say(f"omega({name}) = {b.txt(w)}: {words}.")
                continue
            axis = b.put(f"u({name})", body.omega / size, "")
            power = b.put(
                f"omega.alpha({name})",
                float(np.dot(body.omega, body.alpha)),
                "rad^2/s^3",
                reference=size * float(np.linalg.norm(body.alpha)),
            )
            b.check("dot", power, w, al)
            trend = (
                "at a steady rate"
                if b.is_zero(power)
                else "speeding up"
                if float(np.dot(body.omega, body.alpha)) > 0
                else "slowing down"
            )
            turning = np.cross(body.omega, body.alpha) / size  # du/dt |omega|: the axis turns
            if not all(self.fmt.is_zero(float(x), "rad/s^2") for x in turning):
                trend += ", and the axis itself turns (alpha is not along omega)"
            words = (
                f"body {name} turns at {b.txt(speed)} about the axis u = {b.txtn(axis)} (nearest "
                f"{_nearest_axis(body.omega)}), counter-clockwise seen from the tip of u, {trend}"
            )
            b.line(
                rf"&|\vec{{\omega}}_{{{n}}}| = {b.numu(speed)}, \quad \vec{{u}}_{{{n}}} = "
                rf"\vec{{\omega}}_{{{n}}} / |\vec{{\omega}}_{{{n}}}| = "
                rf"({', '.join(b.entries(axis))}), \quad \vec{{\omega}}_{{{n}}} \cdot "
                rf"\vec{{\alpha}}_{{{n}}} = {b.numu(power)} \quad \Rightarrow \text{{"
                + tex.escape_text(f"counter-clockwise about u, {trend}")
                + "}"
            )
            b.say(
                f"omega({name}) = {b.txt(w)}, alpha({name}) = {b.txt(al)}: {words} (omega . "
                f"alpha = {b.txt(power)}: the same sense means the rotation speeds up)."
            )
        for point in self.chain.points:
            motion = self.analysis.points[point.name]
            n = tex.name(point.name)
            v = b.put(
                f"v({point.name})", motion.velocity, "m/s", ("points", point.name, "velocity")
            )
            a = b.put(
                f"a({point.name})",
                motion.acceleration,
                "m/s^2",
                ("points", point.name, "acceleration"),
            )
            size = float(np.linalg.norm(motion.velocity))
            speed = b.put(f"|v({point.name})|", size, "m/s")
            b.check("norm", speed, v)
            if b.is_zero(speed):
                words = f"{point.name} is at rest at this instant"
                b.line(
                    rf"&|\vec{{v}}_{{{n}}}| = {b.numu(speed)} \quad \Rightarrow \text{{"
                    + tex.escape_text(words)
                    + "}"
                )
                b.say(f"v({point.name}) = {b.txt(v)}: {words}.")
                continue
            power = b.put(
                f"v.a({point.name})",
                float(np.dot(motion.velocity, motion.acceleration)),
                "m^2/s^3",
                reference=size * float(np.linalg.norm(motion.acceleration)),
            )
            b.check("dot", power, v, a)
            trend = (
                "at a steady speed"
                if b.is_zero(power)
                else "speeding up"
                if float(np.dot(motion.velocity, motion.acceleration)) > 0
                else "slowing down"
            )
            words = (
                f"{point.name} moves at a speed of {b.txt(speed)}, mostly "
                f"{_nearest_axis(motion.velocity)}, {trend}"
            )
            b.line(
                rf"&|\vec{{v}}_{{{n}}}| = {b.numu(speed)}, \quad \vec{{v}}_{{{n}}} \cdot "
                rf"\vec{{a}}_{{{n}}} = {b.numu(power)} \quad \Rightarrow \text{{"
                + tex.escape_text(words)
                + "}"
            )
            b.say(
                f"v({point.name}) = {b.txt(v)}, a({point.name}) = {b.txt(a)}: {words} (v . a = "
                f"{b.txt(power)}: the same sense means speeding up)."
            )
        return b.build()

    def figure(self) -> str:
        """The chain at the instant in an isometric drawing: the joint axes (dashed, through their
        origins), the bodies from joint to joint and to their points, the fixed frame E1, E2, E3,
        and each body's omega from its joint origin at its own stated scale."""
        project = ISOMETRIC
        origins = [j.origin for j in self.chain.joints]
        places = origins + [p.position for p in self.chain.points]
        drawn = [project @ x for x in places]
        per_mm = figures.model_scale([*drawn, np.zeros(2)])
        extent = figures.PAPER * per_mm  # m: the drawing's size
        omegas = {name: b.omega for name, b in self.analysis.bodies.items()}
        largest = max((float(np.linalg.norm(w)) for w in omegas.values()), default=0.0)
        k = figures.nice_scale(largest, OMEGA_PAPER_CM)
        to_model = 10.0 * per_mm / k  # (rad/s) -> cm on paper -> m of the drawing
        segments: list[tuple[np.ndarray, np.ndarray, str]] = []
        arrows: list[figures.Arrow] = []
        marks: dict[tuple[float, ...], tuple[np.ndarray, list[str], bool]] = {}

        def mark(at: np.ndarray, label: str, fixed: bool) -> None:
            """One dot per place, its labels joined: 'O3 = A' where a point sits on an origin."""
            key = tuple(np.round(at / max(extent, 1e-300), 9))
            place = marks.setdefault(key, (at, [], fixed))
            place[1].append(label)

        half = 0.12 * extent
        attached: dict[str, list[np.ndarray]] = {GROUND: []}
        for joint in self.chain.joints:
            attached[joint.name] = [joint.origin]
        for index, joint in enumerate(self.chain.joints):
            parent = self.parent_name(index)
            attached[parent].append(joint.origin)
            ends = (joint.origin - half * joint.axis, joint.origin + half * joint.axis)
            segments.append((project @ ends[0], project @ ends[1], "position"))
            mark(joint.origin, f"O{joint.name}", index == 0)
            start = project @ joint.origin
            arrows.append(
                figures.Arrow(
                    start,
                    start + to_model * (project @ omegas[joint.name]),
                    f"omega({joint.name})",
                    f"ω{joint.name}",
                    "absolute",
                )
            )
        for point in self.chain.points:
            attached[point.body].append(point.position)
            mark(point.position, point.name, point.body == GROUND)
        for body, where in attached.items():  # body k from its joint origin to what it carries
            if body == GROUND:
                continue
            segments += [(project @ where[0], project @ x, "link") for x in where[1:]]
        dots = [
            figures.Dot(project @ at, " = ".join(dict.fromkeys(labels)), fixed)
            for at, labels, fixed in marks.values()
        ]
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


def _nearest_axis(vector: np.ndarray) -> str:
    """The fixed axis closest to a vector's direction, with its sign: '+E3', '-E1'."""
    i = int(np.argmax(np.abs(vector)))
    return f"{'+' if vector[i] > 0 else '-'}E{i + 1}"


def spatial_steps(
    chain: SpatialChain, analysis: SpatialAnalysis, fmt: Formatter, plan: DigitPlan | None = None
) -> list[Step]:
    """The steps of a spatial chain's solution (numbers from ``analysis``)."""
    return SpatialSteps(chain, analysis, fmt, plan).steps()
