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
from dataclasses import replace

import numpy as np

from solver.dynamics.analysis import LinkageDynamics, linkage_dynamics
from solver.dynamics.loads import dynamics_of
from solver.kinematics.rigid import cross, dot, omega_cross
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Col, Frac, Num, Paren, Piece, Pt, Ref, Signed, joined
from solver.solutions.free_body import Arrow, Couple, figure
from solver.solutions.linkage import LinkageContext
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

    def __init__(self, ctx: LinkageContext) -> None:
        self.ctx = ctx
        scene = ctx.scene
        self.result: LinkageDynamics = linkage_dynamics(
            scene, ctx.analysis.motion, np.array([scene.time])
        )
        self.forces = self.result.forces
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


def _on_link(d: _Dynamics, link: str) -> tuple[list[Arrow], list[Couple]]:
    """Every force and moment on ``link`` at this instant (joint forces from the solution)."""
    scene = d.ctx.scene
    arrows, couples = [], []
    for joint, solved in zip(scene.joints, d.forces.joints, strict=True):
        if link not in joint.links:
            continue
        sign = 1.0 if joint.links[1] == link else -1.0
        minus = "" if sign > 0 else "-"
        label = ("F" if joint.type == "revolute" else "N") + f"_{joint.point}"
        at = _xy(d.ctx.pos(joint.point))
        arrows.append(Arrow(minus + label, "joint", at, _xy(sign * solved.force[0])))
        if solved.moment is not None:
            moment = sign * float(solved.moment[0])
            couples.append(Couple(f"{minus}M_{joint.point}", "joint", moment))
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
            couples.append(Couple(f"M_{link}", "driver", float(d.forces.torques[link][0])))
    return arrows, couples


def _free_body_step(d: _Dynamics, link: str) -> Step:
    ctx = d.ctx
    b = ctx.builder("dynamics.free_body", f"Free-body diagram of {link}")
    arrows, couples = _on_link(d, link)
    for a in arrows:
        b.put(f"{a.name}", a.vector, FORCE)
    for c in couples:
        b.put(f"{c.name}", c.value, MOMENT)
    bodies = [b_ for b_ in dynamics_of(ctx.scene).bodies if b_.link == link]
    body = next((e for e in d.forces.elements if bodies and e.name == link), None)
    center = None if body is None else _xy(body.p[0])
    points = {p: _xy(ctx.pos(p)) for p in ctx.scene.links[link].points}
    names = (
        ", ".join(a.name for a in arrows)
        + ("; moments " if couples else "")
        + ", ".join(c.name for c in couples)
    )
    b.line(rf"\text{{Forces on {tex.escape_text(link)}: {tex.escape_text(names)}}}")
    b.say(
        f"Link {link} cut free: each joint force as the force its joint's first link exerts on "
        f"the second (with a minus sign on the first link), the weights, the loads and the "
        f"moments: {names}."
    )
    step = b.build()
    drawing = figure(link, points, center, arrows, couples)
    svg = drawing.pop("svg")
    return replace(step, figure=svg, diagram=drawing)


def _equations_step(d: _Dynamics, link: str) -> Step:
    """The three rows of the system that belong to ``link``: sum F = m a, sum M_R = ..."""
    ctx = d.ctx
    row = 3 * ctx.scene.moving_links.index(link)
    R = ctx.reference_point(link)
    A = d.system.matrix(0)
    b = ctx.builder("dynamics.equations", f"Equations of motion of {link}")
    symbolic = [
        r"&\textstyle\sum F_x = \sum m\, a_{G,x}",
        r"&\textstyle\sum F_y = \sum m\, a_{G,y}",
        rf"&\textstyle\sum M_{{{tex.name(R)}}} = \sum \left[I_G \alpha + "
        rf"(\vec r_G - \vec r_{{{tex.name(R)}}}) \times m \vec a_G\right]",
    ]
    for k, label in enumerate(("Fx", "Fy", f"Mz({R})")):
        size = float(np.abs(A[row + k] * d.u).max())
        rhs = b.value(
            f"b_{label}", d.system.rhs[0, row + k], MOMENT if k == 2 else FORCE, reference=size
        )
        arm = float(np.abs(A[row + k]).max())
        operands: list[Ref] = []
        terms: list[tuple[Piece, ...]] = []
        text_terms: list[tuple[Piece, ...]] = []
        for column in map(int, np.flatnonzero(A[row + k])):
            unit = "m" if k == 2 and d.unit(column) == FORCE else ""
            c = b.value(
                f"A({label},{d.system.unknowns[column]})", A[row + k, column], unit, reference=arm
            )
            u = b.value(d.system.unknowns[column], d.u[column], d.unit(column), d.source(column))
            operands += [c, u]
            symbol, text = d.symbols[column]
            terms.append((Signed(c) if terms else Num(c), r"\," + symbol))
            text_terms.append((Num(c), f" {text}"))
        b.check("linear", rhs, *operands)
        b.line(symbolic[k])
        b.line("&", *(joined(" ", terms) or ("0",)), " = ", Num(rhs, unit=True))
        b.say(f"{label}: ", *(joined(" + ", text_terms) or ("0",)), " = ", Num(rhs, unit=True), ".")
    b.say(
        "The right-hand sides hold the inertia terms m a_G and I_G alpha with the weights and "
        f"the loads moved across; moments are about {R}, with the term (r_G - r_{R}) x m a_G "
        "because that point may accelerate."
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
    return b.build()


def _energy_rate(d: _Dynamics, b: StepBuilder, net_key: str) -> tuple[Ref, Ref, Ref, Ref]:
    """dT/dt + dV/dt - P_loads, with dT/dt = sum (m a_G . v_G + I omega alpha), dV/dt =
    -sum m g . v_G and P_loads the power of the loads: the keys of the three terms and of the
    net (``net_key``)."""
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
    net = b.value(net_key, dT + dV - P, "W")
    b.check("sum", net, kT, kV, -kP)
    return kT, kV, kP, net


def _energy_latex(kT: Ref, kV: Ref, kP: Ref) -> tuple[Piece, ...]:
    """dT/dt + dV/dt - P_loads with the numbers, as LaTeX pieces."""
    return (Num(kT), " ", Signed(kV), " - ", Paren(kP))


def _power_step(d: _Dynamics) -> Step:
    """M omega = dT/dt + dV/dt - P_loads: the single driver's torque again, without the joint
    forces."""
    ctx = d.ctx
    link = ctx.scene.drivers[0].link
    omega = ctx.omega(link)
    b = ctx.builder("dynamics.power_balance", "Check: the driving torque from the power balance")
    kT, kV, kP, net = _energy_rate(d, b, "M omega")
    kw = b.value(f"omega({link})", omega, "rad/s", ctx.link_source(link, "omega"))
    b.line(
        r"&M\,\omega = \frac{dT}{dt} + \frac{dV}{dt} - P_\text{loads} = ",
        *_energy_latex(kT, kV, kP),
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
        r"\quad (\text{Newton-Euler: } ",
        Num(ne, unit=True),
        ")",
    )
    b.say(
        "Frictionless joints do no work, so the driver's power goes into the kinetic and "
        "potential energy and against the loads: M omega = dT/dt + dV/dt - P_loads = ",
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
    kT, kV, kP, net = _energy_rate(d, b, "dT/dt + dV/dt - P_loads")
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
        *_energy_latex(kT, kV, kP),
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


def newton_euler_steps(ctx: LinkageContext) -> list[Step]:
    """The dynamics steps of one instant (after the kinematics)."""
    d = _Dynamics(ctx)
    steps = [_data_step(d)]
    steps += [_center_step(d, k) for k in range(len(d.forces.elements))]
    for link in ctx.scene.moving_links:
        steps.append(_free_body_step(d, link))
        steps.append(_equations_step(d, link))
    steps += [_system_step(d), _solution_step(d)]
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
