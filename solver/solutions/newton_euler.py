"""The worked solution of the dynamics of one instant by Newton-Euler (method ``newton_euler``).

After the kinematics (the vector method's steps), the textbook's order: the masses and loads, the
acceleration of every centre of mass, a free-body diagram of every link (data and SVG), the
equations of motion of each link, the linear system they form with its matrix and right-hand
side, its solution, and the power balance that gives the driving torque again.

Moments are taken about a point R of each link (its fixed pivot, else its first point), with the
full right-hand side I_G alpha + (r_G - R) x m a_G: about an accelerating point the sum of moments
is not I_R alpha (the seed's mistake E004-7), and alpha is counter-clockwise positive like the
moments (E004-8).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from solver.dynamics.analysis import (
    LinkageDynamics,
    linkage_dynamics,
    non_convergence,
    self_locking,
)
from solver.dynamics.loads import dynamics_of, link_state
from solver.dynamics.newton_euler import slot_normal
from solver.errors import SingularConfiguration
from solver.kinematics.rigid import cross, dot, omega_cross, rotate
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import (
    TIMES,
    Boxed,
    Col,
    Component,
    Cross,
    Frac,
    Num,
    Operand,
    Paren,
    Piece,
    Pt,
    Ref,
    Signed,
    Sum,
    Sym,
    joined,
)
from solver.solutions.free_body import Arrow, Assumed, Couple, figure
from solver.solutions.linkage import LinkageContext
from solver.solutions.members import (
    Acting,
    force_symbol,
    is_two_force,
    three_force_step,
    two_force_step,
)
from solver.solutions.model import Mistake, Step, Value

FORCE, MOMENT = "N", "N m"


def _unknown(name: str) -> tuple[str, str]:
    """(LaTeX, text) of a system unknown: Fx_O -> F_{O,x}; N_C -> N_C; M_crank -> M_crank."""
    kind, _, owner = name.partition("_")
    if kind in ("Fx", "Fy"):
        return rf"F_{{{tex.name(owner)},{kind[1]}}}", f"F{kind[1]}({owner})"
    return rf"{kind}_{{{tex.name(owner)}}}", f"{kind}({owner})"


class _Dynamics:
    """The instant's dynamics with the names the steps use."""

    def __init__(self, ctx: LinkageContext, statics: bool = False) -> None:
        self.ctx = ctx
        self.statics = statics
        scene = ctx.scene
        self.result: LinkageDynamics = linkage_dynamics(
            scene, ctx.analysis.motion, np.array([scene.time]), statics=statics
        )
        self.forces = self.result.forces
        self.friction = self.result.friction
        if self.friction is not None and not (
            self.friction.converged[0] and not self.friction.locked[0]
        ):
            angle = np.zeros(1)  # the first driver's angle, as /analyze reports it
            if scene.drivers:
                link = scene.drivers[0].link
                angle = link_state(scene, ctx.analysis.motion, [link])[link][0]
            why = self_locking(scene, self.result, angle)
            words = non_convergence(self.result, angle)
            raise SingularConfiguration(
                "joints[].friction: " + (why.reason if why is not None else str(words)),
                float("inf"),
            )
        self.system = self.forces.system
        self.u = self.forces.solution[0]
        self.gravity = np.array(dynamics_of(scene).gravity)
        self.symbols = [_unknown(name) for name in self.system.unknowns]

    def source(self, column: int) -> tuple[str | int, ...] | None:
        """The unknown's path in the response (None for a slot's normal force: the response has
        its vector N n)."""
        kind, index, part = self.system.origins[column]
        if kind == "driver":
            return ("drivers", index, "torque")
        if part == 2:
            return ("joints", index, "moment")
        if self.ctx.scene.joints[index].type != "revolute":
            return None
        return ("joints", index, "force", part)

    def unit(self, column: int) -> str:
        kind, _, part = self.system.origins[column]
        return MOMENT if kind == "driver" or part == 2 else FORCE


def _data_step(d: _Dynamics) -> Step:
    ctx = d.ctx
    b = ctx.builder("dynamics.data", "Masses and loads at this instant")
    lines: list[tuple[Piece, ...]] = []
    for e in d.forces.elements:
        m = b.value(f"m({e.name})", e.mass, "kg")
        G = b.value(f"r_G({e.name})", e.p[0], "m")
        name = rf"&\text{{{tex.escape_text(e.name)}}}: m = "
        if e.inertia:
            inertia = b.value(f"I_G({e.name})", e.inertia, "kg m^2")
            lines.append(
                (
                    name,
                    Num(m, unit=True),
                    r",\; I_G = ",
                    Num(inertia, unit=True),
                    r",\; \vec r_G = ",
                    Pt(G),
                )
            )
        else:
            lines.append((name, Num(m, unit=True), r",\; \vec r = ", Pt(G)))
    g = b.value("g", d.gravity, "m/s^2")
    lines.append((r"&\vec g = ", Pt(g), r"\,\mathrm{m/s^2}"))
    for f in d.forces.forces:
        key = b.value(f"F({f.name})", f.force[0], FORCE, None)
        lines.append(
            (
                rf"&\vec F_{{{tex.name(f.name)}}} = ",
                Pt(key),
                r"\,\mathrm{N}"
                rf"\text{{ at {tex.escape_text(f.point)} on {tex.escape_text(f.link)}}}",
            )
        )
    for m_ in d.forces.moments:
        key = b.value(f"M({m_.name})", m_.moment[0], MOMENT)
        lines.append((rf"&M_{{{tex.name(m_.name)}}} = ", Num(key, unit=True)))
    for line in lines:
        b.line(*line)
    b.say(
        "The masses of the moving links (bodies and point masses) with their centres at this "
        "pose, gravity, and the external loads evaluated at this instant."
    )
    return b.build()


def _center_step(d: _Dynamics, index: int) -> Step:
    """a_G = a_R + alpha x r_RG - omega^2 r_RG from the link's point R."""
    ctx = d.ctx
    e = d.forces.elements[index]
    R = ctx.reference_point(e.link)
    what = f"the centre of {e.name}" if e.name == e.link else f"the point mass {e.name}"
    b = ctx.builder("dynamics.center_acceleration", f"Acceleration of {what}")
    r = e.p[0] - ctx.pos(R)
    w, al = ctx.omega(e.link), ctx.alpha(e.link)
    aR = b.value(f"a({R})", ctx.acc(R), "m/s^2", ("points", R, "acceleration"))
    kw = b.value(f"omega({e.link})", w, "rad/s", ctx.link_source(e.link, "omega"))
    ka = b.value(f"alpha({e.link})", al, "rad/s^2", ctx.link_source(e.link, "alpha"))
    kr = b.value(f"r({R},G)", r, "m")
    t = b.value("a_t = alpha x r", omega_cross(al, r), "m/s^2")
    n = b.value("a_n = -omega^2 r", -(w**2) * r, "m/s^2")
    aG = b.value(f"a_G({e.name})", e.a[0], "m/s^2")
    b.check("cross", t, ka, kr)
    b.check("product", n, kw, kw, kr, factor=-1.0)
    b.check("sum", aG, aR, t, n)
    sub = tex.name(R)
    b.line(
        rf"&\vec a_G = \vec a_{{{sub}}} + \vec\alpha \times \vec r_{{{sub}G}} - \omega^2 "
        rf"\vec r_{{{sub}G}} = ",
        *joined(" + ", [(Col(k, dims=2),) for k in (aR, t, n)]),
        " = ",
        Boxed((Col(aG, unit=True, dims=2),)),
    )
    b.say(
        f"a_G = a({R}) + alpha x r({R},G) - omega^2 r({R},G) = ",
        *joined(" + ", [(Col(k),) for k in (aR, t, n)]),
        " = ",
        Col(aG),
        ".",
    )
    return b.build()


def _xy(vector: np.ndarray) -> tuple[float, float]:
    return float(vector[0]), float(vector[1])


def _on_link(
    d: _Dynamics, link: str, pins: tuple[str, str] | None = None
) -> tuple[list[Arrow], list[Assumed], list[Couple]]:
    """Every force on ``link`` at this instant as solved (joint forces from the solution), the
    unknown components with their assumed senses (a joint's force as its first link exerts it on
    its second: + on the second link, - on the first; a slot's N along its normal n; a two-force
    member's, with its ``pins`` P, Q, as one S along e_PQ at Q and -e_PQ at P), and the moments
    (a driver's and a prismatic joint's unknown)."""
    scene = d.ctx.scene
    arrows, unknowns, couples = [], [], []
    for index, (joint, solved) in enumerate(zip(scene.joints, d.forces.joints, strict=True)):
        if link not in joint.links:
            continue
        sign = 1.0 if joint.links[1] == link else -1.0
        minus = "" if sign > 0 else "-"
        label = ("F" if joint.type == "revolute" else "N") + f"_{joint.point}"
        at = _xy(d.ctx.pos(joint.point))
        arrows.append(Arrow(minus + label, "joint", at, _xy(sign * solved.force[0])))
        if pins is not None:
            e = d.ctx.pos(pins[1]) - d.ctx.pos(pins[0])
            e = e / float(np.hypot(*e)) * (1.0 if joint.point == pins[1] else -1.0)
            value = float(np.dot(sign * solved.force[0], e))
            unknowns.append(Assumed(f"S_{pins[0]}{pins[1]}", at, _xy(e), value))
        elif joint.type == "revolute":
            for axis, sense in (("x", (sign, 0.0)), ("y", (0.0, sign))):
                value = float(solved.force[0][0 if axis == "x" else 1])
                unknowns.append(Assumed(f"{label},{axis}", at, sense, value))
        else:
            n = slot_normal(joint, d.ctx.analysis.motion)[0]
            value = float(np.dot(solved.force[0], n))
            unknowns.append(Assumed(label, at, _xy(sign * n), value))
        if solved.moment is not None:
            moment = sign * float(solved.moment[0])
            couples.append(Couple(f"{minus}M_{joint.point}", "joint", moment, unknown=True))
        if d.friction is not None and index in d.friction.forces:  # known at the answer
            f = sign * d.friction.forces[index][0]
            arrows.append(Arrow(f"{minus}f_{joint.point}", "friction", at, _xy(f)))
        if d.friction is not None and index in d.friction.moments:
            moment = sign * float(d.friction.moments[index][0])
            couples.append(Couple(f"{minus}M_f,{joint.point}", "friction", moment))
    for e in d.forces.elements:
        if e.link == link and np.any(d.gravity):
            arrows.append(Arrow(f"W_{e.name}", "weight", _xy(e.p[0]), _xy(e.mass * d.gravity)))
    for f in d.forces.forces:
        if f.link == link:
            arrows.append(Arrow(f.name, "load", _xy(f.position[0]), _xy(f.force[0])))
    for m in d.forces.moments:
        if m.link == link:
            couples.append(Couple(m.name, "load", float(m.moment[0])))
    for driver in scene.drivers:
        if driver.link == link:
            torque = float(d.forces.torques[link][0])
            couples.append(Couple(f"M_{link}", "driver", torque, unknown=True))
    return arrows, unknowns, couples


def _free_body_step(d: _Dynamics, link: str, pins: tuple[str, str] | None = None) -> Step:
    """The link cut free: its forces as solved, the unknowns with assumed senses (a two-force
    member's, with its ``pins``, as one force along their line)."""
    ctx = d.ctx
    b = ctx.builder("dynamics.free_body", f"Free-body diagram of {link}")
    arrows, unknowns, couples = _on_link(d, link, pins)
    for a in arrows:
        b.put(f"{a.name}", a.vector, FORCE)
    for c in couples:
        b.put(f"{c.name}", c.value, MOMENT)
    bodies = [b_ for b_ in dynamics_of(ctx.scene).bodies if b_.link == link]
    body = next((e for e in d.forces.elements if bodies and e.name == link), None)
    center = None if body is None else _xy(body.p[0])
    points = {p: _xy(ctx.pos(p)) for p in ctx.scene.links[link].points}
    known = [a.name for a in arrows if a.kind != "joint"]
    wanted = list(dict.fromkeys(u.name.replace("_", "(", 1) + ")" for u in unknowns)) + [
        c.name for c in couples if c.unknown
    ]
    moments = [c.name for c in couples if not c.unknown]
    names = ", ".join(wanted) + (
        "; known: " + ", ".join(known + moments) if known or moments else ""
    )
    b.line(rf"\text{{Forces on {tex.escape_text(link)}: {tex.escape_text(names)}}}")
    if pins is None:
        b.say(
            f"Link {link} cut free. Unknown: {', '.join(wanted) or 'none'}, each joint force by "
            "its components with an assumed sense (dashed: positive along x and y on the joint's "
            "second link, the reaction, negative, on its first; a slot's N along its normal n) "
            "and the driving torque counter-clockwise; a negative answer means the other sense. "
            f"Known: {', '.join(known + moments) or 'none'}, drawn to the force scale under the "
            "diagram."
        )
    else:
        P, Q = pins
        b.say(
            f"Link {link} cut free: loaded at its pins {P} and {Q} alone, a two-force member "
            f"(next step). Unknown: the one magnitude {wanted[0]} along {P}{Q}, drawn dashed as "
            f"tension (S e({P},{Q}) at {Q}, -S e({P},{Q}) at {P}); a negative answer means "
            "compression."
        )
    step = b.build()
    drawing = figure(link, points, center, arrows, couples, unknowns)
    svg = drawing.pop("svg")
    return replace(step, figure=svg, diagram=drawing)


TIMES_DOT = Sym(r" \cdot ", " x ")
THIN = Sym(r"\,", " ")


@dataclass
class _Row:
    """One equation of a link being written: its unknowns' terms (coefficient, column), the
    known terms as symbols and as numbers on the left, the inertia terms on the right (symbols,
    numbers), the known terms moved to the right, and the operands of the collected right-hand
    side."""

    unknowns: list[tuple[Ref, int]] = field(default_factory=list)
    symbols: list[tuple[Piece, ...]] = field(default_factory=list)
    numbers: list[tuple[Piece, ...]] = field(default_factory=list)
    right_symbols: list[tuple[Piece, ...]] = field(default_factory=list)
    right_numbers: list[tuple[Piece, ...]] = field(default_factory=list)
    moved: list[tuple[Piece, ...]] = field(default_factory=list)
    operands: list[Operand] = field(default_factory=list)

    def known(self, symbol: Sym, number: tuple[Piece, ...], value: Operand) -> None:
        """A known force or moment on the left (``value``: its number as the check sees it,
        negated where it acts as a reaction), moved to the right when the equation is
        collected."""
        plus, minus = ("+ ", "- ") if value.sign > 0 else ("- ", "+ ")
        self.symbols.append((plus, symbol))
        self.numbers.append((plus, *number))
        shown = (
            Paren(value.ref)
            if value.component is None
            else Component(value.ref, value.component, factor=True)
        )
        self.moved.append((minus, shown))
        self.operands.append(-value)

    def inertia(self, symbol: Sym, number: tuple[Piece, ...], value: Operand) -> None:
        """A term of the right-hand side (m a_G, I_G alpha, r x m a_G)."""
        self.right_symbols.append(("+ ", symbol))
        self.right_numbers.append(("+ ", *number))
        self.operands.append(value)


def _term(d: _Dynamics, b: StepBuilder, coefficient: Ref, column: int) -> tuple[Piece, ...]:
    r"""c u as a term of a sum: '+ F_{B,x}' for c = 1, '- F_{B,x}' for -1, else '+ 0.3\,F_{B,x}';
    nothing for c = 0 exactly (a slot's normal across an axis)."""
    symbol = Sym(*d.symbols[column])
    value = b.scalar(coefficient)
    if value == 0.0:
        return ()
    if abs(value) == 1.0:
        return ("+ " if value > 0 else "- ", symbol)
    return (Signed(coefficient), THIN, symbol)


def _link_unknowns(d: _Dynamics, link: str) -> list[tuple[int, ...]]:
    """The columns of the unknowns acting on ``link``, grouped: a revolute joint's (Fx, Fy), a
    slot's (N,), a prismatic joint's or a driver's moment (M,)."""
    groups: dict[tuple[str, int, bool], list[int]] = {}
    scene = d.ctx.scene
    for column, (kind, index, part) in enumerate(d.system.origins):
        if kind == "driver":
            acts = scene.drivers[index].link == link
        else:
            acts = link in scene.joints[index].links
        if acts:
            groups.setdefault((kind, index, part == 2), []).append(column)
    return [tuple(columns) for columns in groups.values()]


def _sense(d: _Dynamics, column: int, link: str) -> float:
    """+1 where the unknown acts on ``link`` as named (its joint's second link, a driver's own
    link), -1 on its joint's first link (the reaction)."""
    kind, index, _ = d.system.origins[column]
    return 1.0 if kind == "driver" or d.ctx.scene.joints[index].links[1] == link else -1.0


def _frictions(
    d: _Dynamics, b: StepBuilder, link: str
) -> tuple[dict[int, tuple[Ref, float]], dict[int, tuple[Ref, float]]]:
    """The friction on ``link`` at the converged answer, registered in ``b``: each slot's force
    f (N) and each pin's moment M_f (N m) as on its joint's second link, with +1 on that link
    and -1 on the first (the reaction), by the joint's index."""
    slots: dict[int, tuple[Ref, float]] = {}
    pins: dict[int, tuple[Ref, float]] = {}
    if d.friction is None:
        return slots, pins
    for index, joint in enumerate(d.ctx.scene.joints):
        if link not in joint.links:
            continue
        sense = 1.0 if joint.links[1] == link else -1.0
        if index in d.friction.forces:
            f = d.friction.forces[index][0]
            slots[index] = (b.value(f"f({joint.point})", f, FORCE), sense)
        if index in d.friction.moments:
            m = float(d.friction.moments[index][0])
            pins[index] = (b.value(f"M_f({joint.point})", m, MOMENT), sense)
    return slots, pins


def _friction_step(d: _Dynamics) -> Step:
    """Each joint's friction at this instant, with its reasoning: at a pin the friction circle
    (radius mu r) and M_f = -mu r |F| sgn(omega_rel); at a slot the friction angle atan mu and
    f = -mu |N| sgn(v_rel . u) u; then the iteration that finds |F| and |N|."""
    ctx = d.ctx
    scene = ctx.scene
    friction = d.friction
    assert friction is not None
    b = ctx.builder("dynamics.friction", "Friction at the joints")
    motion = ctx.analysis.motion
    for index, joint in enumerate(scene.joints):
        spec = joint.friction
        if spec is None:
            continue
        P, (first, second) = joint.point, joint.links
        mu = b.value(f"mu({P})", spec.coefficient, "")
        if index in friction.moments:
            assert spec.pin_radius is not None
            r = b.value(f"r_pin({P})", spec.pin_radius, "m")
            rho = b.value(f"mu r({P})", spec.circle_radius, "m")
            b.check("product", rho, mu, r)
            w_rel = ctx.omega(second) - ctx.omega(first)
            rel = b.value(f"omega_rel({P})", w_rel, "rad/s")
            F = d.forces.joints[index].force[0]
            size = b.value(f"|F({P})|", float(np.hypot(*F)), FORCE)
            m = b.value(f"M_f({P})", float(friction.moments[index][0]), MOMENT)
            sense = float(np.sign(w_rel))
            b.check("product", m, rho, size, factor=-sense)
            turns = "counter-clockwise" if w_rel > 0 else "clockwise"
            b.line(
                rf"&\text{{pin }}{tex.name(P)}:\; \rho = \mu r = ",
                Num(mu), TIMES_DOT, Num(r), " = ", Num(rho, unit=True),
                r",\; M_f = -\rho\,|\vec F|\,\operatorname{sgn}\omega_\text{rel} = ",
                Sym("-" if sense > 0 else "", "-" if sense > 0 else ""),
                Num(rho), TIMES_DOT, Num(size), " = ", Num(m, unit=True),
            )  # fmt: skip
            b.say(
                f"Pin {P}: {second} turns {turns} relative to {first} (omega_rel = ",
                Num(rel, unit=True),
                "), so the reaction there is tangent to the friction circle of radius mu r = ",
                Num(rho, unit=True),
                f" on the side that opposes that rotation: on {second} the friction moment is "
                "M_f = -mu r |F| sgn(omega_rel) = ",
                Num(m, unit=True),
                " (|F| = ",
                Num(size, unit=True),
                f"), on {first} the opposite.",
            )
        elif index in friction.forces:
            angle = b.value(f"phi({P})", float(np.degrees(np.arctan(spec.coefficient))), "deg")
            normal = d.forces.joints[index].force[0] - friction.forces[index][0]
            n = slot_normal(joint, motion)[0]
            N = b.value(f"|N({P})|", abs(float(np.dot(normal, n))), FORCE)
            f = b.value(f"f({P})", friction.forces[index][0], FORCE)
            u = rotate(np.array(joint.axis, dtype=float), motion.links[first].theta[0])
            along = float(np.dot(friction.forces[index][0], u))
            direction = b.value(f"u({P})", u, "")
            sense = float(np.sign(-along))  # the follower's motion along u
            b.check("product", f, mu, N, direction, factor=-sense)
            b.line(
                rf"&\text{{slot }}{tex.name(P)}:\; \varphi = \arctan\mu = ",
                Num(angle),
                r"^\circ,\; \vec f = -\mu\,|N|\,\operatorname{sgn}(v_\text{rel})\,\vec u = ",
                Sym("-" if sense > 0 else "", "-" if sense > 0 else ""),
                Num(mu), TIMES_DOT, Num(N), TIMES_DOT, Col(direction, dims=2), " = ",
                Col(f, unit=True, dims=2),
            )  # fmt: skip
            moves = "along +u" if sense > 0 else "against u"
            b.say(
                f"Slot {P}: {second} slides {moves} relative to {first}, so Coulomb friction "
                "acts against that motion, f = -mu |N| sgn(v_rel . u) u = ",
                Col(f),
                f" on {second} (|N| = ",
                Num(N, unit=True),
                "); the whole reaction N n + f leans from the normal by the friction angle "
                "phi = atan mu = ",
                Num(angle, unit=True),
                " towards the side that resists the sliding (no Coriolis or other velocity "
                "term enters: only the sense of the relative velocity).",
            )
    b.say(
        "|F| and |N| depend on the unknowns, so the equations with friction are not linear: "
        "they are solved by iteration from the frictionless answer, each step taking the "
        f"senses and the magnitudes of the step before (converged in {friction.iterations} "
        "steps). The friction terms in the equations below are those of the converged answer, "
        "which satisfies them."
    )
    return b.build()


def _equations_step(d: _Dynamics, link: str) -> Step:
    """The three equations of ``link`` written term by term: sum F = sum m a_G with every force
    and every m a_G with its numbers, then sum M_R = sum [I_G alpha + r_RG x m a_G] with every
    moment r x F as a determinant, each I_G alpha and r_RG x m a_G; each equation then collected
    (the unknowns on the left, the known terms moved to the right) and checked against the
    solved unknowns."""
    ctx = d.ctx
    R = ctx.reference_point(link)
    sub, origin = tex.name(R), ctx.pos(R)
    title = "Equilibrium equations" if d.statics else "Equations of motion"
    b = ctx.builder("dynamics.equations", f"{title} of {link}")
    elements = [e for e in d.forces.elements if e.link == link]
    loads = [f for f in d.forces.forces if f.link == link]
    couples = [m for m in d.forces.moments if m.link == link]
    groups = _link_unknowns(d, link)
    weighty = bool(np.any(d.gravity))
    g = b.value("g", d.gravity, "m/s^2")
    mass, accel, inertial, weight, names = {}, {}, {}, {}, {}
    at = {pm.name: pm.point for pm in dynamics_of(ctx.scene).point_masses}
    where = {e.name: at.get(e.name, "G") for e in elements}  # G of a body, a point mass's point
    for e in elements:
        names[e.name] = tex.name(e.name)
        mass[e.name] = b.value(f"m({e.name})", e.mass, "kg")
        if not d.statics:
            accel[e.name] = b.value(f"a_G({e.name})", e.a[0], "m/s^2")
            inertial[e.name] = b.value(f"m a_G({e.name})", e.mass * e.a[0], FORCE)
            b.check("product", inertial[e.name], mass[e.name], accel[e.name])
        if weighty:
            weight[e.name] = b.value(f"m g({e.name})", e.mass * d.gravity, FORCE)
            b.check("product", weight[e.name], mass[e.name], g)
    force = {f.name: b.value(f"F({f.name})", f.force[0], FORCE) for f in loads}
    slots, pins = _frictions(d, b, link)
    for column in (c for group in groups for c in group):
        b.put(d.system.unknowns[column], d.u[column], d.unit(column), d.source(column))

    rows = [_Row(), _Row(), _Row()]
    for k, axis in enumerate("xy"):  # the force equations
        row = rows[k]
        for group in groups:
            kind, index, part = d.system.origins[group[0]]
            if kind == "driver" or part == 2:
                continue
            sense = _sense(d, group[0], link)
            name = d.system.unknowns[group[0]]
            if len(group) == 2:  # a pin's F_x, F_y: the one along this axis
                c = b.value(f"c_{axis}({d.system.unknowns[group[k]]})", sense, "")
                row.unknowns.append((c, group[k]))
                continue
            n = b.value(
                f"n({name})", slot_normal(ctx.scene.joints[index], ctx.analysis.motion)[0], ""
            )
            c = b.value(f"c_{axis}({name})", sense * b.vector(n)[k], "")
            b.check("product", c, n[k], factor=sense)
            row.unknowns.append((c, group[0]))
        for e in elements:
            if weighty and d.gravity[k] != 0.0:
                row.known(
                    Sym(rf"m_{{{names[e.name]}}}\,g_{axis}", f"m({e.name}) g{axis}"),
                    (Num(mass[e.name]), TIMES_DOT, Component(g, k, factor=True)),
                    weight[e.name][k],
                )
            if d.statics:
                continue
            row.inertia(
                Sym(
                    rf"m_{{{names[e.name]}}}\,a_{{{tex.name(where[e.name])},{axis}}}",
                    f"m({e.name}) a{axis}({where[e.name]})",
                ),
                (Num(mass[e.name]), TIMES_DOT, Component(accel[e.name], k, factor=True)),
                inertial[e.name][k],
            )
        for f in loads:
            row.known(
                Sym(force_symbol(f.name, axis), f"{f.name}_{axis}"),
                (Component(force[f.name], k, factor=True),),
                force[f.name][k],
            )
        for index, (friction, sense) in slots.items():
            P = ctx.scene.joints[index].point
            row.known(
                Sym(rf"f_{{{tex.name(P)},{axis}}}", f"f{axis}({P})"),
                (Component(friction, k, factor=True),),
                friction[k] if sense > 0 else -friction[k],
            )

    row = rows[2]  # the moment equation about R
    arms: dict[str, Ref] = {}
    lines: list[tuple[Piece, ...]] = []
    through: list[str] = []

    def arm(name: str, at: np.ndarray) -> tuple[Ref, Sym]:
        if name not in arms:
            arms[name] = b.value(f"r({R},{name})", at - origin, "m")
        return arms[name], Sym(rf"\vec r_{{{sub}{tex.name(name)}}}", f"r({R},{name})")

    for group in groups:
        kind, index, part = d.system.origins[group[0]]
        sense = _sense(d, group[0], link)
        if kind == "driver" or part == 2:
            c = b.value(f"c_M({d.system.unknowns[group[0]]})", sense, "")
            row.unknowns.append((c, group[0]))
            continue
        P = ctx.scene.joints[index].point
        if float(np.hypot(*(ctx.pos(P) - origin))) == 0.0:
            through.append(P)
            continue
        r, r_sym = arm(P, ctx.pos(P))
        minus = "" if sense > 0 else "-"
        if len(group) == 2:
            sx, sy = (d.symbols[column][0] for column in group)
            cx = b.value(f"c_M({d.system.unknowns[group[0]]})", -sense * b.vector(r)[1], "m")
            cy = b.value(f"c_M({d.system.unknowns[group[1]]})", sense * b.vector(r)[0], "m")
            b.check("product", cx, r[1], factor=-sense)
            b.check("product", cy, r[0], factor=sense)
            on = Sym(rf"{minus}\vec F_{{{tex.name(P)}}}", f"{minus}F({P})")
            (_, tx), (_, ty) = (d.symbols[column] for column in group)
            determinant = Cross(r, ((Sym(minus + sx, minus + tx),), (Sym(minus + sy, minus + ty),)))
            terms = [(cx, group[0]), (cy, group[1])]
        else:
            symbol, text = d.symbols[group[0]]
            name = d.system.unknowns[group[0]]
            n = b.value(
                f"n({name})", slot_normal(ctx.scene.joints[index], ctx.analysis.motion)[0], ""
            )
            c = b.value(
                f"c_M({name})",
                sense * float(cross(np.array(b.vector(r)), np.array(b.vector(n)))),
                "m",
            )
            b.check("cross", c, r, n, factor=sense)
            on = Sym(rf"{minus}{symbol}\,\vec n_{{{tex.name(P)}}}", f"{minus}{text} n({P})")
            normal = Sym(symbol, text)
            determinant = Cross(r, ((minus, Component(n, 0), THIN, normal),
                                    (minus, Component(n, 1), THIN, normal)))  # fmt: skip
            terms = [(c, group[0])]
        row.unknowns += terms
        lines.append((r_sym, TIMES, on, " = ", determinant, " = ",
                      Sum(tuple(_term(d, b, c, column) for c, column in terms))))  # fmt: skip

    def moment_of(key: str, point: str, at: np.ndarray, vector: Ref, on: Sym) -> tuple[Ref, Sym]:
        """r_RP x V (``vector`` the key of a force or of m a_G at ``point``) as a determinant of
        numbers, its line written; the moment's key and its symbol r_RP x ``on``."""
        r, r_sym = arm(point, at)
        moment = b.value(key, cross(at - origin, np.array(b.vector(vector))), MOMENT)
        b.check("cross", moment, r, vector)
        named = Sym(rf"{r_sym.tex} \times {on.tex}", f"{r_sym.plain} cross {on.plain}")
        lines.append((named, " = ", Cross(r, vector), " = ", Num(moment, unit=True)))
        return moment, named

    for e in elements if weighty else []:
        weighs = Sym(rf"m_{{{names[e.name]}}}\vec g", f"m({e.name}) g")
        moment, named = moment_of(
            f"r x m g({e.name})", where[e.name], e.p[0], weight[e.name], weighs
        )
        row.known(named, (Paren(moment),), moment.operand)
    for f in loads:
        on = Sym(force_symbol(f.name), f.name)
        moment, named = moment_of(f"r x F({f.name})", f.point, f.position[0], force[f.name], on)
        row.known(named, (Paren(moment),), moment.operand)
    for index, (friction, sense) in slots.items():
        P = ctx.scene.joints[index].point
        on = Sym(rf"\vec f_{{{tex.name(P)}}}", f"f({P})")
        moment, named = moment_of(f"r x f({P})", P, ctx.pos(P), friction, on)
        row.known(named, (Paren(moment),), moment.operand if sense > 0 else -moment)
    for index, (friction, sense) in pins.items():
        P = ctx.scene.joints[index].point
        named = Sym(rf"M_{{f,{tex.name(P)}}}", f"M_f({P})")
        row.known(named, (Paren(friction),), friction.operand if sense > 0 else -friction)
    for m_ in couples:
        moment = b.value(f"M({m_.name})", m_.moment[0], MOMENT)
        row.known(
            Sym(rf"M_{{{tex.name(m_.name)}}}", f"M({m_.name})"), (Paren(moment),), moment.operand
        )
    alpha = b.value(f"alpha({link})", ctx.alpha(link), "rad/s^2", ctx.link_source(link, "alpha"))
    for e in [] if d.statics else elements:
        if e.inertia:
            inertia = b.value(f"I_G({e.name})", e.inertia, "kg m^2")
            spin = b.value(f"I_G alpha({e.name})", e.inertia * ctx.alpha(link), MOMENT)
            b.check("product", spin, inertia, alpha)
            named = Sym(rf"I_{{G,{names[e.name]}}}\,\alpha", f"I_G({e.name}) alpha")
            lines.append(
                (named, " = ", Num(inertia), TIMES_DOT, Paren(alpha), " = ", Num(spin, unit=True))
            )
            row.inertia(named, (Paren(spin),), spin.operand)
        G = where[e.name]
        accelerated = Sym(rf"m_{{{names[e.name]}}}\vec a_{{{tex.name(G)}}}", f"m({e.name}) a({G})")
        key = f"r x m a_G({e.name})"
        moment, named = moment_of(key, G, e.p[0], inertial[e.name], accelerated)
        row.inertia(named, (Paren(moment),), moment.operand)

    heads = (
        Sym(r"\textstyle\sum F_x = 0", "sum Fx = 0"),
        Sym(r"\textstyle\sum F_y = 0", "sum Fy = 0"),
        Sym(rf"\textstyle\sum M_{{{sub}}} = 0", f"sum M({R}) = 0"),
    ) if d.statics else (
        Sym(r"\textstyle\sum F_x = \sum m\,a_{G,x}", "sum Fx = sum m aGx"),
        Sym(r"\textstyle\sum F_y = \sum m\,a_{G,y}", "sum Fy = sum m aGy"),
        Sym(rf"\textstyle\sum M_{{{sub}}} = \sum \left[I_G \alpha + \vec r_{{{sub}G}} \times "
            rf"m \vec a_G\right]", f"sum M({R}) = sum [I_G alpha + r({R},G) cross m aG]"),
    )  # fmt: skip
    for k, (row, head, unit) in enumerate(zip(rows, heads, (FORCE, FORCE, MOMENT), strict=True)):
        label = ("Fx", "Fy", f"Mz({R})")[k]
        values = [
            b.scalar(o.ref) if o.component is None else b.vector(o.ref)[o.component]
            for o in row.operands
        ]
        signs = [o.sign for o in row.operands]
        rhs = b.value(f"b_{label}", sum(s * v for s, v in zip(signs, values, strict=True)), unit,
                      reference=sum(abs(v) for v in values))  # fmt: skip
        if row.operands:
            b.check("sum", rhs, *row.operands)
        linear: list[Ref] = []
        for c, column in row.unknowns:
            linear += [c, Ref(d.system.unknowns[column])]
        b.check("linear", rhs, *linear)
        left = Sum(tuple(_term(d, b, c, column) for c, column in row.unknowns))
        unknowns_and = Sum(
            tuple(_term(d, b, c, column) for c, column in row.unknowns) + tuple(row.symbols)
        )
        unknowns_numbers = Sum(
            tuple(_term(d, b, c, column) for c, column in row.unknowns) + tuple(row.numbers)
        )
        b.line("&", head, r":\quad ", unknowns_and, " = ", Sum(tuple(row.right_symbols)))
        if k == 2:
            for line in lines:
                b.line("&", *line)
        b.line("&", unknowns_numbers, " = ", Sum(tuple(row.right_numbers)))
        b.line("&", left, " = ", Sum(tuple(row.right_numbers) + tuple(row.moved)), " = ",
               Num(rhs, unit=True))  # fmt: skip
        b.say(head, ": ", unknowns_and, " = ", Sum(tuple(row.right_symbols)), ". ",
              *((*joined("; ", lines), ". ") if k == 2 and lines else ()),
              "With the numbers: ", unknowns_numbers, " = ", Sum(tuple(row.right_numbers)),
              "; collected: ", left, " = ", Num(rhs, unit=True), ".")  # fmt: skip
    passing = (
        f" The force at {', '.join(through)} passes through {R}: it has no moment about it."
        if through else ""
    )  # fmt: skip
    if d.statics:
        b.say(
            "In equilibrium the forces and the moments about any point add up to zero (the "
            "masses count only through their weight). Every force is written with its numbers "
            "before the equation is collected (the unknowns on the left, the weights and loads "
            f"moved to the right); moments are about {R}." + passing
        )
    else:
        b.say(
            "Every force and every m a_G is written with its numbers before the equation is "
            "collected (the unknowns on the left, the weights and loads moved to the right). "
            f"Moments are about {R}, with the terms r({R},G) x m a_G because that point may "
            "accelerate." + passing
        )
    return b.build()


def _system_step(d: _Dynamics) -> Step:
    b = d.ctx.builder("dynamics.system", "The linear system A u = b")
    A, rhs = d.system.matrix(0), d.system.rhs[0]
    fmt = d.ctx.fmt
    rows = []
    for row in A:
        size = float(np.abs(row).max())
        rows.append(" & ".join(fmt.latex(x, "", size) for x in row))
    matrix = r" \\ ".join(rows)
    unknowns = r" \\ ".join(symbol for symbol, _ in d.symbols)
    terms = np.abs(A * d.u).max(axis=1)
    right = r" \\ ".join(fmt.latex(x, "", size) for x, size in zip(rhs, terms, strict=True))
    b.line(
        r"&\begin{pmatrix} " + matrix + r" \end{pmatrix} \begin{pmatrix} " + unknowns
        + r" \end{pmatrix} = \begin{pmatrix} " + right + r" \end{pmatrix}"
    )  # fmt: skip
    b.put("A", tuple(A.ravel()), "")
    b.put("b", tuple(rhs), "")
    b.say(
        f"{len(rhs)} equations (three per moving link) in {len(rhs)} unknowns: "
        + ", ".join(text for _, text in d.symbols)
        + ". Rows in the order "
        + ", ".join(d.system.equations)
        + "; A is stored row by row in the value A."
    )
    return b.build()


def _solution_step(d: _Dynamics) -> Step:
    b = d.ctx.builder("dynamics.solution", "The joint forces and the driving torque")
    for column, (symbol, _) in enumerate(d.symbols):
        key = b.value(d.system.unknowns[column], d.u[column], d.unit(column), d.source(column))
        b.line(f"&{symbol} = ", Boxed((Num(key, unit=True),)))
    solved = [
        (f"{text} = ", Num(Ref(name), unit=True))
        for name, (_, text) in zip(d.system.unknowns, d.symbols, strict=True)
    ]
    b.say("The solution of the system: ", *joined(", ", solved), ".")
    if d.friction is not None and len(d.ctx.scene.drivers) == 1:
        _without_friction(d, b)
    return b.build()


def _without_friction(d: _Dynamics, b: StepBuilder) -> None:
    """The driving torque without friction M_0 beside M, and at a driven pose (M_0 omega > 0,
    M omega > 0) the instantaneous efficiency M_0 / M."""
    link = d.ctx.scene.drivers[0].link
    driver = d.result.drivers[0]
    assert driver.torque_frictionless is not None
    M0 = b.value(
        "M_0", float(driver.torque_frictionless[0]), MOMENT, ("drivers", 0, "torque_frictionless")
    )
    M = Ref(d.system.unknowns[d.system.origins.index(("driver", 0, 0))])
    b.line(r"&M_0 = ", Num(M0, unit=True), r"\quad\text{(without friction)}")
    omega = d.ctx.omega(link)
    if b.scalar(M0) * omega > 0 and b.scalar(M) * omega > 0:
        eta = b.value("eta", b.scalar(M0) / b.scalar(M), "")
        b.check("quotient", eta, M0, M)
        b.line(r"&\eta = \frac{M_0}{M} = ", Frac(M0, M), " = ", Boxed((Num(eta),)))
        b.say(
            "Without friction the driver would need M_0 = ",
            Num(M0, unit=True),
            "; at this pose the driver drives the machine, so its instantaneous efficiency is "
            "eta = M_0 / M = ",
            Num(eta),
            " (over a revolution: the sweep's cycle.efficiency, the mean powers' ratio).",
        )
    else:
        b.say(
            "Without friction the driver would need M_0 = ",
            Num(M0, unit=True),
            "; at this pose the driver does not drive the machine (the loads drive it, or it "
            "holds them back), so no efficiency is defined here.",
        )


def _energy_rate(
    d: _Dynamics, b: StepBuilder, net_key: str
) -> tuple[Ref, Ref, Ref, Ref | None, Ref]:
    """dT/dt + dV/dt - P_loads - P_friction, with dT/dt = sum (m a_G . v_G + I omega alpha),
    dV/dt = -sum m g . v_G, P_loads the power of the loads and P_friction that of the joints'
    friction (never positive; None without friction): the keys of the terms and of the net
    (``net_key``)."""
    elements, g = d.forces.elements, d.gravity
    dT = sum(
        e.mass * float(dot(e.a[0], e.v[0])) + e.inertia * float(e.omega[0] * e.alpha[0])
        for e in elements
    )
    dV = -sum(e.mass * float(dot(g, e.v[0])) for e in elements)
    P = sum(float(f.power[0]) for f in d.forces.forces) + sum(
        float(m.power[0]) for m in d.forces.moments
    )
    kT, kV = b.value("dT/dt", dT, "W"), b.value("dV/dt", dV, "W")
    kP = b.value("P_loads", P, "W")
    if d.friction is None:
        net = b.value(net_key, dT + dV - P, "W")
        b.check("sum", net, kT, kV, -kP)
        return kT, kV, kP, None, net
    friction = float(d.friction.power[0])
    kF = b.value("P_friction", friction, "W")
    net = b.value(net_key, dT + dV - P - friction, "W")
    b.check("sum", net, kT, kV, -kP, -kF)
    return kT, kV, kP, kF, net


def _energy_latex(kT: Ref, kV: Ref, kP: Ref, kF: Ref | None) -> tuple[Piece, ...]:
    """dT/dt + dV/dt - P_loads (- P_friction) with the numbers, as LaTeX pieces."""
    friction: tuple[Piece, ...] = () if kF is None else (" - ", Paren(kF))
    return (Num(kT), " ", Signed(kV), " - ", Paren(kP), *friction)


def _power_step(d: _Dynamics) -> Step:
    """M omega = dT/dt + dV/dt - P_loads: the single driver's torque again, without the joint
    forces."""
    ctx = d.ctx
    link = ctx.scene.drivers[0].link
    omega = ctx.omega(link)
    title = (
        "Check: the holding torque by virtual work"
        if d.statics
        else "Check: the driving torque from the power balance"
    )
    b = ctx.builder("dynamics.power_balance", title)
    kT, kV, kP, kF, net = _energy_rate(d, b, "M omega")
    kw = b.value(f"omega({link})", omega, "rad/s", ctx.link_source(link, "omega"))
    rubbing: tuple[Piece, ...] = () if kF is None else (" - ", Paren(kF))
    lost = "" if kF is None else r" - P_\text{friction}"
    if d.statics:  # dT/dt is left out with the inertia: 0
        b.line(
            rf"&M\,\omega = \frac{{dV}}{{dt}} - P_\text{{loads}}{lost} = ",
            Num(kV),
            " - ",
            Paren(kP),
            *rubbing,
            " = ",
            Num(net, unit=True),
        )
    else:
        b.line(
            rf"&M\,\omega = \frac{{dT}}{{dt}} + \frac{{dV}}{{dt}} - P_\text{{loads}}{lost} = ",
            *_energy_latex(kT, kV, kP, kF),
            " = ",
            Num(net, unit=True),
        )
    if omega == 0.0:
        b.say("The driver is at rest (omega = 0): the power balance does not give its torque.")
        return b.build()
    torque = b.value(
        "M_power_balance",
        float(d.result.drivers[0].torque_from_power_balance[0]),
        MOMENT,
        ("drivers", 0, "torque_from_power_balance"),
    )
    ne = b.value(
        "M_newton_euler", float(d.forces.torques[link][0]), MOMENT, ("drivers", 0, "torque")
    )
    b.check("quotient", torque, net, kw)
    b.line(
        "&M = ",
        Frac(net, kw),
        " = ",
        Boxed((Num(torque, unit=True),)),
        r"\quad (\text{equilibrium: } " if d.statics else r"\quad (\text{Newton-Euler: } ",
        Num(ne, unit=True),
        ")",
    )
    if kF is not None:
        b.say(
            "The joints' friction does the power P_friction = ",
            Num(kF, unit=True),
            " (never positive: it opposes every relative motion), which the driver pays too.",
        )
    if d.statics:
        b.say(
            "Virtual work: in equilibrium the power of every force for the motion the driver "
            "would give (its omega) adds up to zero, and frictionless joints do none, so "
            "M omega + sum m g . v_G + P_loads (+ P_friction) = 0: M omega = ",
            Num(net, unit=True),
            ", M = ",
            Num(torque, unit=True),
            ", the same as from the equilibrium equations (",
            Num(ne, unit=True),
            ").",
        )
        return b.build()
    b.say(
        "Frictionless joints do no work, so the driver's power goes into the kinetic and "
        "potential energy and against the loads (and the friction, where there is some): "
        "M omega = dT/dt + dV/dt - P_loads (- P_friction) = ",
        Num(net, unit=True),
        ", M = ",
        Num(torque, unit=True),
        ", the same as from Newton-Euler (",
        Num(ne, unit=True),
        ").",
    )
    return b.build()


def _drivers_power_step(d: _Dynamics) -> Step:
    """sum_i M_i omega_i = dT/dt + dV/dt - P_loads: the drivers' total power (each M_i omega_i
    from the Newton-Euler torques) against the energy rate and the loads' power."""
    ctx = d.ctx
    b = ctx.builder("dynamics.power_balance", "Check: the drivers' power from the power balance")
    terms: list[Ref] = []
    products: list[tuple[Piece, ...]] = []
    texts: list[tuple[Piece, ...]] = []
    for i, driver in enumerate(ctx.scene.drivers):
        link = driver.link
        M = b.value(f"M_{link}", float(d.forces.torques[link][0]), MOMENT, ("drivers", i, "torque"))
        w = b.value(f"omega({link})", ctx.omega(link), "rad/s", ctx.link_source(link, "omega"))
        power = b.value(
            f"P({link})", float(d.result.drivers[i].power[0]), "W", ("drivers", i, "power")
        )
        b.check("product", power, M, w)
        terms.append(power)
        products.append((Paren(M), r" \cdot ", Paren(w)))
        texts.append(
            (f"M_{link} omega({link}) = ", Paren(M), " x ", Paren(w), " = ", Num(power, unit=True))
        )
    total = b.value("P_drivers", sum(float(dr.power[0]) for dr in d.result.drivers), "W")
    b.check("sum", total, *terms)
    kT, kV, kP, kF, net = _energy_rate(d, b, "dT/dt + dV/dt - P_loads")
    b.check("sum", net, total)
    symbols = " + ".join(
        rf"M_{{{tex.name(dr.link)}}}\,\omega_{{{tex.name(dr.link)}}}" for dr in ctx.scene.drivers
    )
    b.line(
        rf"&\textstyle\sum_i M_i\,\omega_i = {symbols} = ",
        *joined(" + ", products),
        " = ",
        Num(total, unit=True),
    )
    b.line(
        r"&\frac{dT}{dt} + \frac{dV}{dt} - P_\text{loads} = ",
        *_energy_latex(kT, kV, kP, kF),
        " = ",
        Boxed((Num(net, unit=True),)),
    )
    b.say(
        "Frictionless joints do no work, so the drivers' total power goes into the kinetic and "
        "potential energy and against the loads: sum of M_i omega_i = dT/dt + dV/dt - P_loads. "
        "Drivers: ",
        *joined("; ", texts),
        "; in total ",
        Num(total, unit=True),
        ". Energy and loads: ",
        Num(kT, unit=True),
        " + (",
        Num(kV, unit=True),
        ") - (",
        Num(kP, unit=True),
        ") = ",
        Num(net, unit=True),
        ", the same. With several drivers the balance checks only their total; each torque "
        "alone is checked by the virtual power of its driver's own motion "
        "(torque_from_power_balance).",
    )
    return b.build()


def _whole_mechanism_step(d: _Dynamics) -> Step:
    """sum m a_G = sum R_ground + sum m g + sum F (+ sum f at the ground's slots): the whole
    mechanism cut free from its frame, where the joint forces between moving links cancel (seed
    004's 7th question; in statics sum m a_G = 0)."""
    ctx = d.ctx
    scene = ctx.scene
    title = "The whole mechanism, cut free from the frame: the ground's reactions" + (
        "" if d.statics else " beside the sum of m a_G"
    )
    b = ctx.builder("dynamics.whole_mechanism", title)
    external: list[Ref] = []
    words: list[tuple[Piece, ...]] = []
    for index, (joint, solved) in enumerate(zip(scene.joints, d.forces.joints, strict=True)):
        if scene.ground not in joint.links:
            continue
        sign = 1.0 if joint.links[0] == scene.ground else -1.0  # the ground's force on the link
        source = ("joints", index, "force") if sign > 0 else None
        key = b.value(f"R({joint.point})", sign * solved.force[0], FORCE, source)
        external.append(key)
        words.append((f"R({joint.point}) = ", Col(key)))
    reactions = list(external)
    for e in d.forces.elements:
        if np.any(d.gravity):
            key = b.value(f"m g({e.name})", e.mass * d.gravity, FORCE)
            external.append(key)
            words.append((f"m g({e.name}) = ", Col(key)))
    for f in d.forces.forces:
        key = b.value(f"F({f.name})", f.force[0], FORCE)
        external.append(key)
        words.append((f"{f.name} = ", Col(key)))
    inertial = []
    if not d.statics:
        for e in d.forces.elements:
            inertial.append(b.value(f"m a_G({e.name})", e.mass * e.a[0], FORCE))
    vectors = [np.array(b.vector(k)) for k in external]
    size = float(sum(np.hypot(*v) for v in vectors))
    left = b.value("sum external", sum(vectors, np.zeros(2)), FORCE, reference=size)
    b.check("sum", left, *external)
    ground = b.value(
        "sum R_ground",
        sum((np.array(b.vector(k)) for k in reactions), np.zeros(2)),
        FORCE,
        reference=size,
    )
    b.check("sum", ground, *reactions)
    right = b.value(
        "sum m a_G",
        sum((np.array(b.vector(k)) for k in inertial), np.zeros(2)),
        FORCE,
        reference=size,
    )
    if inertial:
        b.check("sum", right, *inertial)
    b.check("sum", left, right)
    b.line(
        r"&\textstyle\sum \vec R_\text{ground} + \sum m\vec g + \sum \vec F = ",
        *joined(" + ", [(Col(k, dims=2),) for k in external]),
        " = ",
        Col(left, unit=True, dims=2),
    )
    if inertial:
        b.line(
            r"&\textstyle\sum m\,\vec a_G = ",
            *joined(" + ", [(Col(k, dims=2),) for k in inertial]),
            " = ",
            Boxed((Col(right, unit=True, dims=2),)),
        )
    b.line(
        r"&\textstyle\sum \vec R_\text{ground} = ",
        *joined(" + ", [(Col(k, dims=2),) for k in reactions]),
        " = ",
        Boxed((Col(ground, unit=True, dims=2),)),
    )
    b.say(
        "Cut the whole mechanism free from its frame: the forces between moving links cancel in "
        "pairs, so the ground's reactions, the weights and the loads add up to "
        + ("zero in equilibrium" if d.statics else "the sum of m a_G of every mass")
        + ". External forces: ",
        *joined("; ", words),
        "; their sum ",
        Col(left),
        ("." if d.statics else "; sum of m a_G: "),
        *(() if d.statics else (Col(right), ", the same.")),
        " The ground's reactions alone add up to ",
        Col(ground, unit=True),
        (
            "."
            if d.statics
            else ": sum m a_G less the weights and the loads, what the frame must supply."
        ),
    )
    return b.build()


def _acting(d: _Dynamics, link: str) -> list[Acting] | None:
    """The forces on ``link`` as solved, where it carries forces alone: None where it carries a
    couple (a driver's torque, a moment, a prismatic joint's moment) or, in dynamics, a mass (its
    inertia). A weight counts as a force at its centre; a pin's friction moment shifts its
    force's line (``Acting.through``)."""
    scene = d.ctx.scene
    elements = [e for e in d.forces.elements if e.link == link and e.mass != 0.0]
    if any(dr.link == link for dr in scene.drivers) or any(
        m.link == link for m in d.forces.moments
    ):
        return None
    if elements and not d.statics:
        return None
    out = []
    for index, (joint, solved) in enumerate(zip(scene.joints, d.forces.joints, strict=True)):
        if link not in joint.links:
            continue
        if solved.moment is not None:
            return None
        sign = 1.0 if joint.links[1] == link else -1.0
        moment = 0.0
        if d.friction is not None and index in d.friction.moments:
            moment = sign * float(d.friction.moments[index][0])
        direction = None
        if joint.type != "revolute" and (d.friction is None or index not in d.friction.forces):
            direction = slot_normal(joint, d.ctx.analysis.motion)[0]
        label = ("F" if joint.type == "revolute" else "N") + f"_{joint.point}"
        at = d.ctx.pos(joint.point)
        pin = joint.type == "revolute"
        out.append(Acting(label, at, sign * solved.force[0], moment, index, direction, pin=pin))
    if np.any(d.gravity):
        for e in elements:
            weight = e.mass * d.gravity
            out.append(Acting(f"W_{e.name}", e.p[0], weight, direction=weight, whole=True))
    for f in d.forces.forces:
        if f.link == link:
            force = f.force[0]
            out.append(Acting(f.name, f.position[0], force, direction=force, whole=True))
    return out


def _member_steps(d: _Dynamics) -> tuple[dict[str, Step], dict[str, tuple[str, str]]]:
    """Each two- or three-force member's step by link, and the pins (P, Q) of each two-force
    member without friction: two-force members first, whose pins' lines are then known to their
    neighbours' three-force steps."""
    acting = {link: _acting(d, link) for link in d.ctx.scene.moving_links}
    steps: dict[str, Step] = {}
    pins: dict[str, tuple[str, str]] = {}
    along: dict[int, np.ndarray] = {}  # a two-force member's pin: the pins' line
    for link, forces in acting.items():
        if forces is not None and is_two_force(forces):
            steps[link] = two_force_step(d.ctx, link, forces)
            if all(a.moment == 0.0 for a in forces):
                P, Q = (d.ctx.scene.joints[a.joint].point for a in forces if a.joint is not None)
                pins[link] = (P, Q)
                for a in forces:
                    assert a.joint is not None
                    along[a.joint] = forces[1].at - forces[0].at
    for link, forces in acting.items():
        if forces is not None and len(forces) == 3 and link not in steps:
            known = [
                a if a.joint not in along else replace(a, direction=along[a.joint]) for a in forces
            ]
            steps[link] = three_force_step(d.ctx, link, known)
    return steps, pins


def newton_euler_steps(ctx: LinkageContext, statics: bool = False) -> list[Step]:
    """The dynamics steps of one instant (after the kinematics); ``statics``: the static force
    analysis (no accelerations of the centres, no inertia terms, the virtual-work check)."""
    d = _Dynamics(ctx, statics)
    steps = [_data_step(d)]
    if not statics:
        steps += [_center_step(d, k) for k in range(len(d.forces.elements))]
    if d.friction is not None and (d.friction.forces or d.friction.moments):
        steps.append(_friction_step(d))
    members, two_force = _member_steps(d)
    for link in ctx.scene.moving_links:
        steps.append(_free_body_step(d, link, two_force.get(link)))
        if link in members:
            steps.append(members[link])
        steps.append(_equations_step(d, link))
    steps += [_system_step(d), _solution_step(d), _whole_mechanism_step(d)]
    if len(ctx.scene.drivers) == 1:
        steps.append(_power_step(d))
    elif ctx.scene.drivers:
        steps.append(_drivers_power_step(d))
    return steps


def newton_euler_mistakes(ctx: LinkageContext) -> list[Mistake]:
    """E004-7: moments about an accelerating pin without the m a_G term."""
    d = _Dynamics(ctx)
    out = []
    for e in d.forces.elements:
        R = ctx.reference_point(e.link)
        a_R = ctx.acc(R)
        if ctx.is_fixed(R) or not e.inertia or float(np.hypot(*a_R)) == 0.0:
            continue
        r = e.p[0] - ctx.pos(R)
        right = e.inertia * float(e.alpha[0]) + float(cross(r, e.mass * e.a[0]))
        wrong = (e.inertia + e.mass * float(dot(r, r))) * float(e.alpha[0])
        fmt = ctx.fmt
        out.append(
            Mistake(
                "dynamics.moment_about_accelerating_point",
                f"Sum of moments about the moving point {R} of {e.link}",
                f"{R} accelerates (a = {fmt.text_vector(a_R, 'm/s^2')}), so the sum of moments "
                f"about it is I_G alpha + r_{R}G x m a_G, not I_{R} alpha with I_{R} = I_G + m "
                f"r^2 (the seed's Q6 mistake, E004-7, which alone adds 1.53 kW to its mean power).",
                {
                    "wrong": Value(wrong, MOMENT, fmt.text_value(wrong, MOMENT)),
                    "right": Value(right, MOMENT, fmt.text_value(right, MOMENT)),
                },
                (("dynamics.equations", f"Equations of motion of {e.link}"),),
            )
        )
    return out


def in_scene_order(steps: list[Step], mistakes: list[Mistake], ctx: LinkageContext) -> None:
    """Renumber the kinematic steps' ``joints`` sources in place: with ``forces`` the response
    lists every joint in the scene's order, not only the slider and prismatic ones."""
    sliding = [k for k, j in enumerate(ctx.scene.joints) if j.type != "revolute"]

    def renumbered(values: Mapping[str, Value]) -> dict[str, Value]:
        out = {}
        for key, v in values.items():
            if v.source is not None and v.source[0] == "joints":
                index = sliding[int(v.source[1])]
                v = replace(v, source=("joints", index, *v.source[2:]))
            out[key] = v
        return out

    for k, step in enumerate(steps):
        if not step.kind.startswith("dynamics."):
            steps[k] = replace(step, values=renumbered(step.values))
    for k, mistake in enumerate(mistakes):
        mistakes[k] = replace(mistake, values=renumbered(mistake.values))
