"""What every worked solution of a planar linkage shares: its context and the common steps.

``LinkageContext`` reads the solver's analysis (positions, rates, slider components, poles) and
names things the way the steps write them. The common steps are the data, the position vectors,
the rigid-body velocity v_Y = v_X + omega x r_XY and acceleration
a_Y = a_X + alpha x r_XY - omega^2 r_XY of one point from another, the velocity and acceleration
poles of each moving link, and the summary of results. Every number is the solver's own; the
cross products and sums written out are derived from those numbers and agree with them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from solver.analysis.instant import LinkageAnalysis
from solver.kinematics.relative_motion import (
    MovingPointMotion,
    sliding_acceleration_parts,
    sliding_velocity_parts,
)
from solver.kinematics.rigid import omega_cross
from solver.model.laws import parse_time_law
from solver.model.scene import Joint, LinkageScene, ground_pivot
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder, Unknown, present_solution
from solver.solutions.equation import (
    TIMES,
    Alt,
    Boxed,
    Col,
    ColumnOf,
    Component,
    Equation,
    Num,
    Paren,
    Piece,
    Pt,
    Ref,
    Sym,
    Words,
    ZCol,
    ZCross,
    joined,
)
from solver.solutions.format import Formatter, latex_unit
from solver.solutions.model import Step

V0 = r"\vec{0}"
VELOCITY, ACCELERATION = 1, 2  # the order of a time derivative
MOTION = {VELOCITY: ("velocity", "m/s"), ACCELERATION: ("acceleration", "m/s^2")}


def unit_scales(analysis: LinkageAnalysis, size: float) -> dict[str, float]:
    """The largest magnitude of each unit in the analysis (what 'rounding noise' is relative to)."""

    def largest(values: Sequence[np.ndarray | float | None]) -> float:
        found = [float(np.max(np.abs(v))) for v in values if v is not None]
        return max(found, default=0.0)

    points = analysis.points.values()
    links = analysis.links.values()
    return {
        "rad": math.pi,
        "deg": 180.0,
        "m": size,
        "m/s": largest([p.velocity for p in points]),
        "m/s^2": largest([p.acceleration for p in points]),
        "rad/s": largest([link.omega for link in links]),
        "rad/s^2": largest([link.alpha for link in links]),
        "1/s": largest([link.omega for link in links]),
        "1/s^2": max(
            largest([link.omega for link in links]) ** 2, largest([link.alpha for link in links])
        ),
    }


def split_part(name: str, point: str) -> tuple[str, str]:
    """Key and unit of one part of v = v_tr + v_rel or a = a_tr + a_rel + a_cor at ``point``:
    'relative_velocity' -> ('v_rel(X)', 'm/s'), 'acceleration' -> ('a(X)', 'm/s^2')."""
    prefix, _, what = name.rpartition("_")
    short = {"transport": "_tr", "relative": "_rel", "coriolis": "_cor", "": ""}[prefix]
    unit = MOTION[VELOCITY if what == "velocity" else ACCELERATION][1]
    return f"{what[0]}{short}({point})", unit


@dataclass(frozen=True)
class SlotMotion:
    """A point in a slot: the textbook split of its velocity and acceleration.

    ``index`` is the joint's index in the analysis' ``joints`` (None for a derived split).
    """

    index: int | None
    joint: Joint
    omega_guide: float
    direction: np.ndarray
    transport_velocity: np.ndarray
    relative_velocity: np.ndarray
    velocity: np.ndarray
    transport_acceleration: np.ndarray | None
    relative_acceleration: np.ndarray | None
    coriolis_acceleration: np.ndarray | None
    acceleration: np.ndarray | None

    def source(self, name: str) -> tuple[str | int, ...] | None:
        return None if self.index is None else ("joints", self.index, name)

    def put(self, b: StepBuilder, name: str, point: str) -> str:
        """Register one part of the split (``name`` a field, e.g. 'relative_velocity') as
        'v_rel(X)', 'a_tr(X)', 'a_cor(X)', 'v(X)'..., with its path in the response."""
        value = getattr(self, name)
        assert value is not None, name
        key, unit = split_part(name, point)
        return b.put(key, value, unit, self.source(name))

    @property
    def guide(self) -> str:
        return self.joint.guide


@dataclass
class LinkageContext:
    """The scene, its analysis, the formatter, and what the steps have shown so far."""

    scene: LinkageScene
    analysis: LinkageAnalysis
    fmt: Formatter
    written: bool = True  # False: the steps' structure only (``StepBuilder``)
    used_vectors: list[tuple[str, str]] = field(default_factory=list)
    shown_velocity: set[str] = field(default_factory=set)
    shown_acceleration: set[str] = field(default_factory=set)
    slots: dict[tuple[str, str], SlotMotion] = field(default_factory=dict)  # made once each

    # --- the solver's numbers -------------------------------------------------------------------

    def pos(self, point: str) -> np.ndarray:
        p = self.analysis.points[point].position
        assert p is not None
        return p

    def vel(self, point: str) -> np.ndarray:
        v = self.analysis.points[point].velocity
        assert v is not None
        return v

    def acc(self, point: str) -> np.ndarray:
        a = self.analysis.points[point].acceleration
        assert a is not None
        return a

    def omega(self, link: str) -> float:
        if link == self.scene.ground:
            return 0.0
        value = self.analysis.links[link].omega
        assert value is not None
        return value

    def alpha(self, link: str) -> float:
        if link == self.scene.ground:
            return 0.0
        value = self.analysis.links[link].alpha
        assert value is not None
        return value

    def link_source(self, link: str, key: str) -> tuple[str, ...] | None:
        return None if link == self.scene.ground else ("links", link, key)

    def is_fixed(self, point: str) -> bool:
        return point in self.scene.links[self.scene.ground].points

    def reference_point(self, link: str) -> str:
        """A point of ``link`` to carry its motion from: its fixed pivot, else its first point."""
        pivot = self.ground_pivot(link)
        return pivot if pivot is not None else self.scene.links[link].points[0]

    def ground_pivot(self, link: str) -> str | None:
        """The point of a revolute joint between ``link`` and the ground, if any."""
        return ground_pivot(link, self.scene.joints, self.scene.ground)

    def slot(self, guide: str, point: str) -> SlotMotion:
        """The motion of ``point`` in the slot of ``guide``: transport, relative, Coriolis.

        For the joint's own point these are the solver's ``SlidingJoint`` numbers (with their
        paths in the response); for another point of a prismatic follower they are derived from
        the guide's rigid motion in the same way.
        """
        if (guide, point) not in self.slots:
            self.slots[(guide, point)] = self._slot(guide, point)
        return self.slots[(guide, point)]

    def _slot(self, guide: str, point: str) -> SlotMotion:
        index = 0
        for joint in self.scene.joints:
            if joint.type == "revolute":
                continue
            carried = joint.point == point or (
                joint.type == "prismatic" and point in self.scene.links[joint.follower].points
            )
            if joint.guide == guide and carried:
                direction = self.slot_direction(joint)
                if joint.point == point:
                    s = self.analysis.joints[index]
                    return SlotMotion(
                        index,
                        joint,
                        float(s.omega_guide),
                        direction,
                        s.transport_velocity,
                        s.relative_velocity,
                        s.velocity,
                        s.transport_acceleration,
                        s.relative_acceleration,
                        s.coriolis_acceleration,
                        s.acceleration,
                    )
                return self._derived_slot(joint, point, direction)
            index += 1
        raise AssertionError(f"no slot of {guide} carries {point}")

    def _derived_slot(self, joint: Joint, point: str, direction: np.ndarray) -> SlotMotion:
        guide = joint.guide
        anchor = self.scene.links[guide].points[0]
        r = self.pos(point) - self.pos(anchor)
        omega, alpha = self.omega(guide), self.alpha(guide)
        w, al = np.asarray(omega), np.asarray(alpha)
        v_tr, v_rel = sliding_velocity_parts(self.vel(anchor), w, r, self.vel(point))
        a_tr, a_rel, a_cor = sliding_acceleration_parts(
            self.acc(anchor), w, al, r, v_rel, self.acc(point)
        )
        return SlotMotion(
            None,
            joint,
            omega,
            direction,
            v_tr,
            v_rel,
            self.vel(point),
            a_tr,
            a_rel,
            a_cor,
            self.acc(point),
        )

    def slot_direction(self, joint: Joint) -> np.ndarray:
        """The unit direction of the slot now: the drawn axis turned with the guide."""
        assert joint.axis is not None
        theta = float(self.analysis.motion.links[joint.guide].theta[0])
        c, s = math.cos(theta), math.sin(theta)
        x, y = joint.axis
        return np.array([c * x - s * y, s * x + c * y])

    # --- names ----------------------------------------------------------------------------------

    def builder(self, kind: str, title: str) -> StepBuilder:
        """A step's builder (written with references, it settles its own digits when built)."""
        return StepBuilder(self.fmt, kind, title, self.written)

    def use(self, first: str, second: str) -> None:
        if (first, second) not in self.used_vectors:
            self.used_vectors.append((first, second))


# --- symbols ----------------------------------------------------------------------------------


def w_sym(link: str) -> str:
    return tex.scalar(r"\omega", tex.name(link))


def a_sym(link: str) -> str:
    return tex.scalar(r"\alpha", tex.name(link))


def v_vec(point: str, extra: str = "") -> str:
    return tex.vec("v", tex.name(point) + extra)


def a_vec(point: str, extra: str = "") -> str:
    return tex.vec("a", tex.name(point) + extra)


def r_vec(first: str, second: str) -> str:
    return tex.vec("r", tex.pair(first, second))


def w_vec(link: str) -> str:
    return tex.vec(r"\omega", tex.name(link))


def al_vec(link: str) -> str:
    return tex.vec(r"\alpha", tex.name(link))


def put_motion(b: StepBuilder, ctx: LinkageContext, point: str, order: int) -> str:
    """v_X (order 1) or a_X (order 2): the solver's number for ``point``, as 'v(X)' / 'a(X)'."""
    field_name, unit = MOTION[order]
    return b.put(
        f"{field_name[0]}({point})",
        getattr(ctx.analysis.points[point], field_name),
        unit,
        ("points", point, field_name),
    )


def origin(b: StepBuilder, ctx: LinkageContext, point: str, motion: Ref) -> Piece:
    """The motion of ``point`` as a column: the zero vector in LaTeX for a fixed point at rest
    (its value in text)."""
    if ctx.is_fixed(point) and b.is_zero(motion):
        return Alt((V0,), (Col(motion),))
    return Col(motion)


def det_row_z(b: StepBuilder, key: str) -> list[str]:
    return ["0", "0", b.num(key)]


def omega_squared(b: StepBuilder, link: str, w: Ref, write: bool = True) -> Ref:
    """omega_L^2 = (omega_L)^2 as a value of its own, checked, and (``write``) on a line of its
    own (``omega_squared_line``): the normal term -omega^2 r then multiplies r by it, at r's
    precision (never 0.347195^2 beside 1.582)."""
    w2 = b.value(f"omega^2({link})", b.scalar(w) ** 2, "1/s^2")
    b.check("product", w2, w, w)
    if write:
        omega_squared_line(b, link, w, w2)
    return w2


def omega_squared_line(b: StepBuilder, link: str, w: Ref, w2: Ref) -> None:
    """The line omega_L^2 = (omega_L)^2 = value."""
    b.line(rf"&\omega_{{{tex.name(link)}}}^2 = ", Paren(w), "^2 = ", Num(w2), latex_unit("1/s^2"))


# --- the common steps -------------------------------------------------------------------------


def data_step(ctx: LinkageContext, method_sentence: str) -> Step:
    """The given data: drivers (with their time laws), joints, the analysed instant."""
    scene, b = ctx.scene, ctx.builder("data", "Data")
    b.say(method_sentence)
    b.say(
        "Sign convention: x to the right, y up, z out of the page; angular velocities and "
        "accelerations are z-components, counter-clockwise positive."
    )
    for driver in scene.drivers:
        link = driver.link
        w = b.value(f"omega({link})", ctx.omega(link), "rad/s", ctx.link_source(link, "omega"))
        al = b.value(f"alpha({link})", ctx.alpha(link), "rad/s^2", ctx.link_source(link, "alpha"))
        if driver.angle_law is not None:
            _write_time_law(ctx, b, link, driver.angle_law, (w, al))
            continue
        b.line(
            f"&{w_vec(link)} = ",
            ZCol(w),
            latex_unit("rad/s") + rf", \quad {al_vec(link)} = ",
            ZCol(al),
            latex_unit("rad/s^2"),
        )
        b.say(
            f"The driven link {link} turns about {driver.pivot} with omega({link}) = ",
            Num(w, unit=True),
            f" and angular acceleration alpha({link}) = ",
            Num(al, unit=True),
            ".",
        )
    for link, degrees in ctx.analysis.diagnostics.driver_angles.items():
        key = b.value(f"angle({link})", math.radians(degrees), "rad")
        b.line(
            rf"&\theta_{{{tex.name(link)}}} = {ctx.fmt.latex(degrees, 'deg')}{{}}^{{\circ}} = ",
            Num(key, unit=True),
            r" \quad \text{(the analysed instant)}",
        )
        b.say(
            f"The analysed instant has link {link} at {ctx.fmt.text(degrees, 'deg')} deg from "
            "the x axis."
        )
    for joint in scene.joints:
        if joint.type != "revolute":
            b.say(_slot_sentence(joint, joint.links[0] == scene.ground))
    return b.build()


def _write_time_law(
    ctx: LinkageContext, b: StepBuilder, link: str, angle_law: str, keys: tuple[Ref, Ref]
) -> None:
    """omega = phi_dot(t), alpha = phi_ddot(t) of a driver turned by the time law phi(t)."""
    w, al = keys
    law = parse_time_law(angle_law)
    t = b.value("t", ctx.scene.time, "s")
    sub = "_{" + tex.name(link) + "}"
    phi, dphi, ddphi = (
        rf"{head}{sub}" for head in (r"\varphi", r"\dot{\varphi}", r"\ddot{\varphi}")
    )
    b.line(
        rf"&{phi}(t) = {tex.law(law.expression, ctx.fmt.digits)}, \quad "
        rf"{dphi}(t) = {tex.law(law.first_derivative, ctx.fmt.digits)}, \quad "
        rf"{ddphi}(t) = {tex.law(law.second_derivative, ctx.fmt.digits)}"
    )
    b.line(
        "&t = ",
        Num(t, unit=True),
        rf": \quad {w_sym(link)} = {dphi}(t) = ",
        Num(w, unit=True),
        rf", \quad {a_sym(link)} = {ddphi}(t) = ",
        Num(al, unit=True),
    )
    b.say(
        f"Link {link} turns by phi(t) = {tex.law_text(angle_law, law.expression)} (rad) from "
        "its drawn pose; "
        "its derivatives give, at t = ",
        Num(t, unit=True),
        f", omega({link}) = ",
        Num(w, unit=True),
        f" and alpha({link}) = ",
        Num(al, unit=True),
        ".",
    )


def _slot_sentence(joint: Joint, fixed: bool) -> str:
    """The words for a sliding joint: which point slides in which link's slot."""
    guide, follower = joint.links
    return (
        f"{joint.point} of link {follower} slides in a straight slot of link {guide}"
        + (" (a fixed guide)." if fixed else " (a moving guide).")
        + (" The block cannot turn relative to the guide." if joint.type == "prismatic" else "")
    )


def positions_step(ctx: LinkageContext) -> Step:
    """The points at the analysed instant and the position vectors the steps use."""
    b = ctx.builder("positions", "Positions" if not ctx.used_vectors else "Position vectors")
    names = sorted(
        {p for pair in ctx.used_vectors for p in pair} or set(ctx.scene.points),
        key=list(ctx.scene.points).index,
    )
    at = {p: b.value(f"pos({p})", ctx.pos(p), "m", ("points", p, "position")) for p in names}
    b.line(
        "&",
        *joined(r", \quad ", [(f"{tex.name(p)} = ", Pt(at[p])) for p in names]),
        latex_unit("m"),
    )
    b.say(
        "Points at the analysed instant: ",
        *joined("; ", [(f"{p} = ", Pt(at[p])) for p in names]),
        ".",
    )
    rows: list[tuple[Piece, ...]] = []
    texts: list[tuple[Piece, ...]] = []
    for first, second in ctx.used_vectors:
        key = b.value(f"r({first},{second})", ctx.pos(second) - ctx.pos(first), "m")
        b.check("sum", key, at[second], -at[first])
        rows.append((f"{r_vec(first, second)} = ", Col(key)))
        texts.append((f"r({first},{second}) = ", Col(key)))
    for i in range(0, len(rows), 3):
        b.line("&", *joined(r" \quad ", rows[i : i + 3]), latex_unit("m"))
    if texts:
        b.say("Position vectors: ", *joined("; ", texts), ".")
    return b.build()


def fixed_points_step(ctx: LinkageContext, order: int) -> Step | None:
    """v_X = 0 (a_X = 0) for the points of the ground; None when the ground has no point."""
    fixed = list(ctx.scene.links[ctx.scene.ground].points)
    if not fixed:
        return None
    which, unit = MOTION[order]
    symbol = v_vec if order == VELOCITY else a_vec
    b = ctx.builder(f"{which}.fixed", "Fixed points")
    for p in fixed:
        put_motion(b, ctx, p, order)
    b.line(
        "&" + r" = ".join(symbol(p) for p in fixed) + rf" = {V0}{latex_unit(unit)}"
        r" \quad \text{(fixed joints)}"
    )
    b.say(f"The points of the ground ({', '.join(fixed)}) are fixed: their {which} is zero.")
    (ctx.shown_velocity if order == VELOCITY else ctx.shown_acceleration).update(fixed)
    return b.build()


def rigid_velocity_step(
    ctx: LinkageContext, link: str, base: str, target: str, reason: str = ""
) -> Step:
    """v_Y = v_X + omega x r_XY with the cross product as a determinant."""
    b = ctx.builder("velocity.rigid", f"Velocity of {target} (link {link})")
    ctx.use(base, target)
    vx = b.value(f"v({base})", ctx.vel(base), "m/s", ("points", base, "velocity"))
    w = b.value(f"omega({link})", ctx.omega(link), "rad/s", ctx.link_source(link, "omega"))
    r = b.value(f"r({base},{target})", ctx.pos(target) - ctx.pos(base), "m")
    wxr = b.value(
        f"omega x r({base},{target})",
        omega_cross(ctx.omega(link), ctx.pos(target) - ctx.pos(base)),
        "m/s",
    )
    vy = b.value(f"v({target})", ctx.vel(target), "m/s", ("points", target, "velocity"))
    b.check("cross", wxr, w, r)
    b.check("sum", vy, vx, wxr)
    base_v = origin(b, ctx, base, vx)
    relative_velocity = Equation.of(
        Sym(v_vec(target), f"v({target})"),
        (
            Sym(v_vec(base), f"v({base})"),
            " + ",
            Sym(w_vec(link), f"omega({link})"),
            TIMES,
            Sym(r_vec(base, target), f"r({base},{target})"),
        ),
        (base_v, " + ", ZCross(w, r)),
        (base_v, " + ", Col(wxr)),
        Boxed((Col(vy, unit=True),)),
        breaks=(3,),
    )
    b.line(relative_velocity)
    if reason:
        b.say(reason)
    b.say(relative_velocity, ".")
    ctx.shown_velocity.add(target)
    return b.build()


def rigid_acceleration_step(
    ctx: LinkageContext, link: str, base: str, target: str, reason: str = ""
) -> Step:
    """a_Y = a_X + alpha x r_XY - omega^2 r_XY: tangential term as a determinant, normal term."""
    b = ctx.builder("acceleration.rigid", f"Acceleration of {target} (link {link})")
    ctx.use(base, target)
    r_np = ctx.pos(target) - ctx.pos(base)
    omega, alpha = ctx.omega(link), ctx.alpha(link)
    ax = b.value(f"a({base})", ctx.acc(base), "m/s^2", ("points", base, "acceleration"))
    w = b.value(f"omega({link})", omega, "rad/s", ctx.link_source(link, "omega"))
    al = b.value(f"alpha({link})", alpha, "rad/s^2", ctx.link_source(link, "alpha"))
    r = b.value(f"r({base},{target})", r_np, "m")
    t = b.value(f"alpha x r({base},{target})", omega_cross(alpha, r_np), "m/s^2")
    n = b.value(f"normal({base},{target})", -(omega**2) * r_np, "m/s^2")
    ay = b.value(f"a({target})", ctx.acc(target), "m/s^2", ("points", target, "acceleration"))
    if reason:
        b.say(reason)
    w2 = omega_squared(b, link, w)
    b.check("cross", t, al, r)
    b.check("product", n, w2, r, factor=-1.0)
    b.check("sum", ay, ax, t, n)
    base_a = origin(b, ctx, base, ax)
    _write_rigid_acceleration(b, (link, base, target), base_a, (w, al, r, t, n, ay, w2))
    if base == ctx.ground_pivot(link):
        write_turning_parts(b, (link, base, target), (al, r, t, n, ay, w2))
    ctx.shown_acceleration.add(target)
    return b.build()


def write_turning_parts(
    b: StepBuilder, names: tuple[str, str, str], refs: tuple[Ref, Ref, Ref, Ref, Ref, Ref]
) -> None:
    """a_Y = a_Y^t + a_Y^n for Y turning about the fixed pivot X: |a^t| = |alpha| |r_XY|
    (perpendicular to XY), |a^n| = omega^2 |r_XY| (from Y towards X), |a_Y| = sqrt(|a^t|^2 +
    |a^n|^2)."""
    link, base, target = names
    al, r, t, n, ay, w2 = refs
    length = b.value(f"|r({base},{target})|", float(np.linalg.norm(b.vector(r))), "m")
    tangential = b.value(f"|a_t({target})|", float(np.linalg.norm(b.vector(t))), "m/s^2")
    radial = b.value(f"|a_n({target})|", float(np.linalg.norm(b.vector(n))), "m/s^2")
    size = b.value(f"|a({target})|", float(np.linalg.norm(b.vector(ay))), "m/s^2")
    alpha = b.value(f"|alpha({link})|", abs(b.scalar(al)), "rad/s^2")
    b.check("norm", length, r)
    b.check("norm", tangential, t)
    b.check("norm", radial, n)
    b.check("norm", size, ay)
    b.check("product", tangential, alpha, length)
    b.check("product", radial, w2, length)
    sub, link_sub = tex.name(target), tex.name(link)
    b.line(
        rf"&{a_vec(target)} = \vec{{a}}^{{\,t}}_{{{sub}}} + \vec{{a}}^{{\,n}}_{{{sub}}}, \quad "
        rf"|\vec{{a}}^{{\,t}}_{{{sub}}}| = |\alpha_{{{link_sub}}}|\,|{r_vec(base, target)}| = ",
        Num(alpha), r" \cdot ", Num(length), " = ", Num(tangential, unit=True),
    )  # fmt: skip
    b.line(
        rf"&|\vec{{a}}^{{\,n}}_{{{sub}}}| = \omega_{{{link_sub}}}^2\,"
        rf"|{r_vec(base, target)}| = ", Num(w2), r" \cdot ", Num(length), " = ",
        Num(radial, unit=True),
        rf", \quad |{a_vec(target)}| = ", Num(size, unit=True),
    )  # fmt: skip
    b.say(
        f"{target} turns about the fixed pivot {base}, so its acceleration has a tangential part "
        f"a_t = alpha({link}) cross r({base},{target}), perpendicular to {base}-{target}, of "
        f"magnitude |alpha| |r| = ",
        Num(tangential, unit=True),
        f", and a radial (normal) part a_n = -omega^2 r({base},{target}), from {target} towards "
        f"{base}, of magnitude omega^2 |r| = ",
        Num(radial, unit=True),
        "; together |a| = ",
        Num(size, unit=True),
        ".",
    )


def _write_rigid_acceleration(
    b: StepBuilder,
    names: tuple[str, str, str],
    base_a: Piece,
    refs: tuple[Ref, Ref, Ref, Ref, Ref, Ref, Ref],
) -> None:
    """The equation a_Y = a_X + alpha x r - omega^2 r, its determinant and its sum, in LaTeX and
    in words (``base_a`` is a_X: the zero vector in LaTeX where X is fixed)."""
    link, base, target = names
    w, al, r, t, n, ay, w2 = refs
    again = rf"&\phantom{{{a_vec(target)}}} = "
    b.line(
        rf"&{a_vec(target)} = {a_vec(base)} + {al_vec(link)} \times {r_vec(base, target)} - "
        rf"\omega_{{{tex.name(link)}}}^2\, {r_vec(base, target)}"
    )
    b.line(again, base_a, " + ", ZCross(al, r), " - ", Num(w2), r" \cdot ", Col(r))
    b.line(
        again,
        base_a,
        " + ",
        Col(t),
        " + ",
        Col(n),
        " = ",
        Boxed((Col(ay, unit=True),)),
    )
    b.say(
        f"a({target}) = a({base}) + alpha({link}) cross r({base},{target}) - omega({link}) "
        f"squared times r({base},{target}) = ",
        base_a,
        " + ",
        Col(t),
        " + ",
        Col(n),
        " = ",
        Col(ay),
        "; the normal term is -(",
        Num(w),
        ") squared = -",
        Num(w2),
        f" times r, pointing from {target} towards {base}.",
    )


def _pole_at_pivot(
    ctx: LinkageContext, b: StepBuilder, link: str, pole: Ref, sub: str, order: int, why: str
) -> Step | None:
    """P = Q (G = Q): the pole of a link turning about the fixed joint Q, else None."""
    pivot = ctx.ground_pivot(link)
    if pivot is None:
        return None
    o = b.value(f"pos({pivot})", ctx.pos(pivot), "m", ("points", pivot, "position"))
    b.check("sum", pole, o)
    symbol = v_vec if order == VELOCITY else a_vec
    b.line(
        rf"&{sub} = {tex.name(pivot)} = ",
        Pt(pole, "m"),
        rf" \quad \text{{(fixed pivot: }} {symbol(pivot)} = {V0}\text{{)}}",
    )
    b.say(
        f"Link {link} turns about the fixed joint {pivot}{why}: its {MOTION[order][0]} pole is "
        f"{pivot} = ",
        Pt(pole),
        ".",
    )
    return b.build()


def velocity_pole_step(ctx: LinkageContext, link: str) -> Step:
    """The velocity pole P of a moving link: from v_X = omega x r_PX at two points."""
    result = ctx.analysis.links[link]
    b = ctx.builder("poles.velocity", f"Velocity pole of link {link}")
    sub = "P_{" + tex.name(link) + "}"
    w = b.value(f"omega({link})", ctx.omega(link), "rad/s", ctx.link_source(link, "omega"))
    if result.velocity_pole is None:
        b.line(
            rf"&{w_sym(link)} = ",
            Num(w, unit=True),
            r" \;\Rightarrow\; \text{no velocity pole (it is at infinity)}",
        )
        b.say(
            f"Link {link} translates at this instant (omega({link}) = ",
            Num(w, unit=True),
            "): all its points have the same velocity, so its velocity pole is at infinity.",
        )
        return b.build()
    pole = b.value(f"P({link})", result.velocity_pole, "m", ("links", link, "velocity_pole"))
    at_pivot = _pole_at_pivot(ctx, b, link, pole, sub, VELOCITY, "")
    if at_pivot is not None:
        return at_pivot
    points = ctx.scene.links[link].points[:2]
    b.say(
        f"The velocity pole P of link {link} is the point of the link with zero velocity: "
        f"v(X) = omega({link}) cross r(P,X) for every point X."
    )
    b.say("It lies on the perpendiculars to the velocities of two points, drawn through them.")
    for x in points:
        _velocity_pole_from(ctx, b, link, x, result.velocity_pole)
    if len(points) == 2:
        b.say(f"Check: {points[0]} and {points[1]} give the same pole.")
    return b.build()


def _velocity_pole_from(
    ctx: LinkageContext, b: StepBuilder, link: str, x: str, pole_np: np.ndarray
) -> None:
    """v_X = omega x r_PX solved for r_PX = (v_y / omega, -v_x / omega), then P = X - r_PX;
    r_PX . v_X = 0 shows the pole on the perpendicular to v_X."""
    sub = "P_{" + tex.name(link) + "}"
    w, pole = Ref(f"omega({link})"), Ref(f"P({link})")
    v = ctx.vel(x)
    r_np = ctx.pos(x) - pole_np
    vx = b.value(f"v({x})", v, "m/s", ("points", x, "velocity"))
    px = b.value(f"pos({x})", ctx.pos(x), "m", ("points", x, "position"))
    r = b.value(f"r(P,{x})", r_np, "m")
    d = b.value(
        f"r(P,{x}).v({x})",
        float(np.dot(r_np, v)),
        "m^2/s",
        reference=float(np.hypot(*r_np) * np.hypot(*v)),
    )
    b.check("cross", vx, w, r)
    b.check("sum", pole, px, -r)
    b.check("dot", d, r, vx)
    rx, ry = (rf"r_{{{sub}{tex.name(x)},{c}}}" for c in "xy")
    r_px = rf"\vec{{r}}_{{{sub}{tex.name(x)}}}"
    expanded = ColumnOf((("-", Paren(w), rf"\, {ry}"), (Num(w), rf"\, {rx}"), ("0",)))
    b.line("&", Col(vx), f" = {V0} + ", ZCross(w, (rx, ry)), " = ", expanded)
    b.line(
        rf"&\Rightarrow {ry} = -\frac{{",
        Component(vx, 0),
        "}{",
        Num(w),
        rf"}}, \quad {rx} = \frac{{",
        Component(vx, 1),
        "}{",
        Num(w),
        rf"}}, \quad {r_px} = ",
        Col(r, unit=True),
        rf", \quad {sub} = {tex.name(x)} - {r_px} = ",
        Boxed((Pt(pole, "m"),)),
    )
    b.say(
        f"From {x}: v({x}) = ",
        Col(vx),
        f" = omega({link}) cross r(P,{x}) gives r(P,{x}) = ",
        Col(r),
        f", perpendicular to v({x}) (dot product ",
        Num(d),
        f"), so P = {x} - r(P,{x}) = ",
        Pt(pole),
        ".",
    )


def acceleration_pole_step(ctx: LinkageContext, link: str) -> Step:
    """The acceleration pole G: a_X = alpha x r_GX - omega^2 r_GX solved for r_GX (Cramer)."""
    result = ctx.analysis.links[link]
    b = ctx.builder("poles.acceleration", f"Acceleration pole of link {link}")
    sub = "G_{" + tex.name(link) + "}"
    w = b.value(f"omega({link})", ctx.omega(link), "rad/s", ctx.link_source(link, "omega"))
    al = b.value(f"alpha({link})", ctx.alpha(link), "rad/s^2", ctx.link_source(link, "alpha"))
    if result.acceleration_pole is None:
        b.line(
            rf"&{w_sym(link)} = ",
            Num(w, unit=True),
            rf", \quad {a_sym(link)} = ",
            Num(al, unit=True),
            r" \;\Rightarrow\; \text{no acceleration pole}",
        )
        b.say(
            f"omega({link}) and alpha({link}) are both zero: the link translates without "
            "turning and all its points have the same acceleration; there is no acceleration "
            "pole."
        )
        return b.build()
    pole = b.value(
        f"G({link})", result.acceleration_pole, "m", ("links", link, "acceleration_pole")
    )
    at_pivot = _pole_at_pivot(ctx, b, link, pole, sub, ACCELERATION, ", whose acceleration is zero")
    if at_pivot is not None:
        return at_pivot
    points = ctx.scene.links[link].points[:2]
    _acceleration_pole_from(ctx, b, link, points[-1], result.acceleration_pole)
    if len(points) == 2 and points[0] != points[-1]:
        _acceleration_pole_check(ctx, b, link, points[0], result.acceleration_pole)
    return b.build()


def _acceleration_pole_from(
    ctx: LinkageContext, b: StepBuilder, link: str, x: str, pole_np: np.ndarray
) -> None:
    """a_X = alpha x r_GX - omega^2 r_GX: the 2x2 system
    [-omega^2, -alpha; alpha, -omega^2] r_GX = a_X solved by Cramer's rule, then G = X - r_GX."""
    sub = "G_{" + tex.name(link) + "}"
    w, al, pole = Ref(f"omega({link})"), Ref(f"alpha({link})"), Ref(f"G({link})")
    alpha = ctx.alpha(link)
    a = ctx.acc(x)
    r_np = ctx.pos(x) - pole_np
    ax = b.value(f"a({x})", a, "m/s^2", ("points", x, "acceleration"))
    px = b.value(f"pos({x})", ctx.pos(x), "m", ("points", x, "position"))
    rx_sym, ry_sym = (rf"r_{{{sub}{tex.name(x)},{c}}}" for c in "xy")
    w2 = omega_squared(b, link, w)
    b.line(
        rf"&{a_vec(x)} = \vec{{a}}_{{{sub}}} + {al_vec(link)} \times \vec{{r}}_{{{sub}"
        rf"{tex.name(x)}}} - \omega_{{{tex.name(link)}}}^2\,\vec{{r}}_{{{sub}{tex.name(x)}}}, "
        rf"\quad \vec{{a}}_{{{sub}}} = {V0}"
    )
    b.line(
        "&",
        Col(ax),
        " = ",
        ZCross(al, (rx_sym, ry_sym)),
        " - ",
        Num(w2),
        r"\, " + tex.column([rx_sym, ry_sym, "0"]),
    )
    coefficients = _pole_coefficients(b, alpha, w2, al)
    b1 = b.value("b1", float(a[0]), "m/s^2")
    b2 = b.value("b2", float(a[1]), "m/s^2")
    b.check("sum", b1, ax[0])
    b.check("sum", b2, ax[1])
    b.say(
        f"The acceleration pole G of link {link} is the point of the link with zero "
        f"acceleration: a({x}) = alpha cross r(G,{x}) - omega squared r(G,{x}), two equations "
        f"for the components of r(G,{x})."
    )
    r = b.value(f"r(G,{x})", r_np, "m")
    unknowns = [
        Unknown(f"{r.key}[0]", rx_sym, f"r(G,{x}) x-component", "m", float(r_np[0])),
        Unknown(f"{r.key}[1]", ry_sym, f"r(G,{x}) y-component", "m", float(r_np[1])),
    ]
    present_vector_unknowns(b, unknowns, coefficients, [b1, b2], "G:")
    b.check("sum", pole, px, -r)
    b.line(
        rf"&{sub} = {tex.name(x)} - \vec{{r}}_{{{sub}{tex.name(x)}}} = ",
        Boxed((Pt(pole, "m"),)),
    )
    b.say(f"G = {x} - r(G,{x}) = ", Pt(pole), ".")


def _pole_coefficients(b: StepBuilder, alpha: float, w2: Ref, al: Ref) -> list[list[Ref]]:
    """The matrix of a_X = alpha x r - omega^2 r in r: [[-omega^2, -alpha], [alpha, -omega^2]]
    (``w2``: omega^2)."""
    c11 = b.value("c11", -b.scalar(w2), "")
    c12 = b.value("c12", -alpha, "")
    c21 = b.value("c21", alpha, "")
    c22 = b.value("c22", -b.scalar(w2), "")
    b.check("product", c11, w2, factor=-1.0)
    b.check("product", c12, al, factor=-1.0)
    b.check("product", c21, al)
    b.check("product", c22, w2, factor=-1.0)
    return [[c11, c12], [c21, c22]]


def _acceleration_pole_check(
    ctx: LinkageContext, b: StepBuilder, link: str, y: str, pole_np: np.ndarray
) -> None:
    """The check at a second point Y: a_Y = alpha x r_GY - omega^2 r_GY."""
    sub = "G_{" + tex.name(link) + "}"
    w2, al, pole = Ref(f"omega^2({link})"), Ref(f"alpha({link})"), Ref(f"G({link})")
    ry_np = ctx.pos(y) - pole_np
    ay = b.value(f"a({y})", ctx.acc(y), "m/s^2", ("points", y, "acceleration"))
    ry = b.value(f"r(G,{y})", ry_np, "m")
    py = b.value(f"pos({y})", ctx.pos(y), "m", ("points", y, "position"))
    t = b.value(f"alpha x r(G,{y})", omega_cross(ctx.alpha(link), ry_np), "m/s^2")
    n = b.value(f"normal(G,{y})", -(ctx.omega(link) ** 2) * ry_np, "m/s^2")
    b.check("sum", ry, py, -pole)
    b.check("cross", t, al, ry)
    b.check("product", n, w2, ry, factor=-1.0)
    b.check("sum", ay, t, n)
    b.line(
        rf"&\text{{check at }} {tex.name(y)}: \; {al_vec(link)} \times "
        rf"\vec{{r}}_{{{sub}{tex.name(y)}}} - \omega^2 \vec{{r}}_{{{sub}{tex.name(y)}}} = ",
        Col(t),
        " + ",
        Col(n),
        " = ",
        Col(ay, unit=True),
        f" = {a_vec(y)}",
    )
    b.say(
        f"Check at {y}: alpha cross r(G,{y}) - omega squared r(G,{y}) = ",
        Col(t),
        " + ",
        Col(n),
        " = ",
        Col(ay),
        f", the acceleration of {y}.",
    )


def present_vector_unknowns(
    b: StepBuilder,
    unknowns: list[Unknown],
    coefficients: Sequence[Sequence[str | Ref]],
    rhs: Sequence[str | Ref],
    prefix: str,
) -> None:
    """``present_solution`` for unknowns that are components of an already registered vector."""
    # The unknowns' values live in the vector value; register scalar copies for the checks.
    renamed = []
    for u in unknowns:
        key = b.value(u.key.replace("[0]", ".x").replace("[1]", ".y"), u.value, u.unit)
        b.check("sum", key, u.key)
        renamed.append(Unknown(key.key, u.latex, u.text, u.unit, u.value, u.source, u.meaning))
    present_solution(b, renamed, coefficients, rhs, prefix)


SENSE = {1: "counter-clockwise", -1: "clockwise"}


def direction_words(angle: float) -> str:
    """A direction of motion in words: 'to the right', 'up', 'to the left and down (at 210 deg)'."""
    degrees = math.degrees(angle) % 360.0
    for centre, words in ((0, "to the right"), (90, "up"), (180, "to the left"), (270, "down")):
        if min(abs(degrees - centre), 360.0 - abs(degrees - centre)) < 1.0:
            return words
    horizontal = "to the right" if math.cos(angle) > 0 else "to the left"
    vertical = "up" if math.sin(angle) > 0 else "down"
    return f"{horizontal} and {vertical} (at {degrees:.0f} deg from the x axis)"


def _trend(fmt: Formatter, rate: float, rate_unit: str, change: float, change_unit: str) -> str:
    """'speeding up', 'slowing down', 'at a steady rate' or 'momentarily at rest'."""
    if fmt.is_zero(rate, rate_unit):
        return "momentarily at rest"
    if fmt.is_zero(change, change_unit):
        return "at a steady rate"
    return "speeding up" if rate * change > 0 else "slowing down"


def reading_step(ctx: LinkageContext) -> Step:
    """Reading the answer: each rotation's sense in words and whether the link speeds up or slows
    down (omega and alpha of the same sign: speeding up), each slider's direction of motion."""
    b = ctx.builder("reading", "Reading the answer")
    for link in ctx.scene.moving_links:
        _read_link(ctx, b, link)
    for joint in ctx.scene.joints:
        if joint.type != "revolute":
            _read_slider(ctx, b, joint)
    for name, m in ctx.analysis.moving_points.items():
        _read_moving_point(b, name, m)
    return b.build()


def _rotation_words(link: str, w_sense: str, a_sense: str, trend: str) -> str:
    """A link's rotation in words from the senses of omega and alpha ('' where zero)."""
    if not w_sense:
        return f"link {link} does not turn at this instant" + (
            f"; alpha {a_sense} starts it turning {a_sense}" if a_sense else ""
        )
    if not a_sense:
        return f"omega {w_sense}, alpha zero: link {link} turns {w_sense} at a steady rate"
    return f"omega {w_sense}, alpha {a_sense}: link {link} is {trend}"


def _read_link(ctx: LinkageContext, b: StepBuilder, link: str) -> None:
    """omega and alpha of one link: the senses of rotation, speeding up where omega alpha > 0."""
    omega, alpha = ctx.omega(link), ctx.alpha(link)
    w = b.value(f"omega({link})", omega, "rad/s", ("links", link, "omega"))
    al = b.value(f"alpha({link})", alpha, "rad/s^2", ("links", link, "alpha"))
    w_sense = "" if b.is_zero(w) else SENSE[1 if omega > 0 else -1]
    a_sense = "" if b.is_zero(al) else SENSE[1 if alpha > 0 else -1]
    trend = _trend(ctx.fmt, omega, "rad/s", alpha, "rad/s^2")
    words = _rotation_words(link, w_sense, a_sense, trend)
    b.line(
        f"&{w_sym(link)} = ",
        Num(w, unit=True),
        rf", \quad {a_sym(link)} = ",
        Num(al, unit=True),
        r" \quad \Rightarrow ",
        Words((words,)),
    )
    b.say(
        f"omega({link}) = ",
        Num(w, unit=True),
        f", alpha({link}) = ",
        Num(al, unit=True),
        f": {words}.",
    )


def _read_slider(ctx: LinkageContext, b: StepBuilder, joint: Joint) -> None:
    """v_rel and a_rel of a sliding joint: its direction, speeding up where v_rel . a_rel > 0."""
    slot = ctx.slot(joint.guide, joint.point)
    assert slot.relative_acceleration is not None
    point = joint.point
    rel = Ref(slot.put(b, "relative_velocity", point))
    arel = Ref(slot.put(b, "relative_acceleration", point))
    v, a = slot.relative_velocity, slot.relative_acceleration
    power = b.value(
        f"v_rel.a_rel({point})",
        float(np.dot(v, a)),
        "m^2/s^3",
        reference=float(np.hypot(*v) * np.hypot(*a)),
    )
    b.check("dot", power, rel, arel)
    frame = "" if joint.guide == ctx.scene.ground else f" relative to link {joint.guide}"
    if b.is_zero(rel):
        words = f"{point} does not slide{frame} at this instant"
    else:
        heading = b.value(f"heading({point})", math.atan2(v[1], v[0]), "rad")
        b.check("angle", heading, rel)
        trend = speed_trend(b, power, "at a steady rate")
        words = f"{point} slides {direction_words(math.atan2(v[1], v[0]))}{frame}, {trend}"
    b.line(
        rf"&\vec{{v}}_{{{tex.name(point)},\mathrm{{rel}}}} = ",
        Pt(rel, "m/s"),
        rf", \quad \vec{{a}}_{{{tex.name(point)},\mathrm{{rel}}}} = ",
        Pt(arel, "m/s^2"),
        r" \quad \Rightarrow ",
        Words((words,)),
    )
    b.say(
        f"v_rel({point}) = ",
        Pt(rel),
        f", a_rel({point}) = ",
        Pt(arel),
        " (their dot product ",
        Num(power, unit=True),
        f"{sense_clause(b, power, 'speeding up')}): {words}.",
    )


def _read_moving_point(b: StepBuilder, name: str, m: MovingPointMotion) -> None:
    """|v| and v . a of a moving point: its direction, speeding up where v . a > 0."""
    source = ("moving_points", name)
    vk = b.value(f"v({name})", m.velocity, "m/s", (*source, "velocity"))
    ak = b.value(f"a({name})", m.acceleration, "m/s^2", (*source, "acceleration"))
    speed = b.value(f"|v({name})|", float(np.hypot(*m.velocity)), "m/s")
    power = b.value(
        f"v.a({name})",
        float(np.dot(m.velocity, m.acceleration)),
        "m^2/s^3",
        reference=float(np.hypot(*m.velocity) * np.hypot(*m.acceleration)),
    )
    b.check("norm", speed, vk)
    b.check("dot", power, vk, ak)
    vv = np.asarray(m.velocity, dtype=float)
    words: tuple[Piece, ...] = (f"{name} is momentarily at rest",)
    if not b.is_zero(vk):
        words = (
            f"{name} moves {direction_words(math.atan2(vv[1], vv[0]))} with speed ",
            Num(speed, unit=True),
            f", {speed_trend(b, power, 'at a steady speed')}",
        )
    b.line(
        rf"&|\vec{{v}}_{{{tex.name(name)}}}| = ",
        Num(speed, unit=True),
        r" \quad \Rightarrow ",
        Words(words),
    )
    b.say(f"v({name}) = ", Pt(vk), f", a({name}) = ", Pt(ak), ": ", *words, ".")


def speed_trend(b: StepBuilder, power: str | Ref, steady: str) -> str:
    """The sign of v . a in words: steady (shown as 0), speeding up or slowing down."""
    if b.is_zero(power):
        return steady
    return "speeding up" if b.scalar(power) > 0 else "slowing down"


def sense_clause(b: StepBuilder, power: str | Ref, speeding: str) -> str:
    """What the sign of a dot product v . a (omega . alpha) says, after its number: the same
    sense means ``speeding`` up; zero, that the rate neither grows nor falls at this instant."""
    if b.is_zero(power):
        return ": zero, so the rate neither grows nor falls at this instant"
    return f": the same sense means {speeding}"


def summary_step(ctx: LinkageContext) -> Step:
    """The results: every moving link's omega and alpha, every point's velocity and acceleration."""
    b = ctx.builder("summary", "Results")
    rows: list[tuple[Piece, ...]] = []
    for link in ctx.scene.moving_links:
        w = b.value(f"omega({link})", ctx.omega(link), "rad/s", ("links", link, "omega"))
        al = b.value(f"alpha({link})", ctx.alpha(link), "rad/s^2", ("links", link, "alpha"))
        rows.append(
            (f"{w_sym(link)} = ", Num(w, unit=True), f", & {a_sym(link)} = ", Num(al, unit=True))
        )
        b.say(f"Link {link}: omega = ", Num(w, unit=True), ", alpha = ", Num(al, unit=True), ".")
    for p in ctx.scene.points:
        v = b.value(f"v({p})", ctx.vel(p), "m/s", ("points", p, "velocity"))
        a = b.value(f"a({p})", ctx.acc(p), "m/s^2", ("points", p, "acceleration"))
        rows.append((f"{v_vec(p)} = ", Pt(v, "m/s"), f", & {a_vec(p)} = ", Pt(a, "m/s^2")))
        b.say(f"Point {p}: v = ", Pt(v), ", a = ", Pt(a), ".")
    for name, m in ctx.analysis.moving_points.items():
        source = ("moving_points", name)
        x = b.value(f"pos({name})", m.position, "m", (*source, "position"))
        v = b.value(f"v({name})", m.velocity, "m/s", (*source, "velocity"))
        a = b.value(f"a({name})", m.acceleration, "m/s^2", (*source, "acceleration"))
        rows.append(
            (
                f"{v_vec(name)} = ",
                Pt(v, "m/s"),
                f", & {a_vec(name)} = ",
                Pt(a, "m/s^2"),
                rf" \\ \text{{moving point }} {tex.name(name)} = ",
                Pt(x, "m"),
                " &",
            )
        )
        b.say(
            f"Moving point {name} (at ",
            Pt(x),
            "): v = ",
            Pt(v),
            ", a = ",
            Pt(a),
            " (absolute, transport plus relative plus Coriolis).",
        )
    b.line(r"&\begin{array}{ll} ", *joined(r" \\ ", rows), r" \end{array}")
    return b.build()
