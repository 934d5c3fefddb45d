"""The loop-closure method in complex form (seed 001): loop, derivatives, Cramer's rule.

A linkage qualifies when its plan is a chain of single loops through the ground, each closed by
one group of the plan on a link that turns about a fixed pivot (a crank, or a rocker or lever
solved by an earlier loop):

- four-bar loop (RRR dyad with one centre on that link and the other fixed):
  a2 e^(i th12) + a3 e^(i th13) = a1 e^(i th11) + a4 e^(i th14);
- slider-crank loop (pin on a fixed straight guide of direction phi, offset c):
  a2 e^(i th12) + a3 e^(i th13) = (s14 + i c1) e^(i phi);
- slotted-lever loop (the pin in the slot of a lever turning about a fixed pivot Q):
  a2 e^(i th12) = a1 e^(i th11) + (s + i c) e^(i beta), (s + i c) e^(i beta) = r_QP.

The first time derivative is linear in the unknown rates; its real and imaginary parts are two
equations, solved by Cramer's rule with the determinants written out. The second derivative gives
the same matrix for the angular and sliding accelerations. For any other topology (a moving slot
of a dyad, a prismatic block, a Newton group...) ``LoopUnavailable`` says why, and ``solve``
falls back to the vector method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal, NoReturn

import numpy as np

from solver.position.groups.rrr import chord
from solver.position.topology import CircleSpec, DriverStep, LeverStep, LineSpec, TwoPointStep
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder, Unknown, present_solution
from solver.solutions.equation import (
    Boxed,
    Frac,
    Num,
    Paren,
    Piece,
    Ref,
    Shows,
    Signed,
    Token,
    joined,
)
from solver.solutions.format import latex_unit
from solver.solutions.groups import solution_group
from solver.solutions.groups.rpr import TURN_LATEX, LeverNotation, lever_closed_form, wrap_turn
from solver.solutions.linkage import (
    ACCELERATION,
    MOTION,
    VELOCITY,
    LinkageContext,
    SlotMotion,
    acceleration_pole_step,
    put_motion,
    velocity_pole_step,
    write_turning_parts,
)
from solver.solutions.model import Step


def join_sum(parts: list[str]) -> str:
    """Terms joined with + and -, a negative term written as a subtraction ('0' if none)."""
    if not parts:
        return "0"
    out = parts[0]
    for p in parts[1:]:
        out += f" - {p[1:]}" if p.startswith("-") else f" + {p}"
    return out


@dataclass(frozen=True)
class Degrees:
    """An angle value in degrees, in parentheses when negative (for e^{i ...})."""

    ref: Ref

    def latex(self, shows: Shows) -> str:
        degrees = shows.fmt_of(self.ref).latex(math.degrees(shows.scalar(self.ref)), "deg")
        return tex.paren(degrees + r"{}^{\circ}")

    def text(self, shows: Shows) -> str:
        return self.latex(shows)


@dataclass(frozen=True)
class Complex:
    """A 2-vector value as a complex number: 'a', 'b i', '(a + b i)'; with ``unknown`` (its
    LaTeX) the coefficient of that unknown: 'u', '-u', '(a + b i)\\,u'; ``whole``: always
    '(a + b i)', a vector's two components even where one is 0 (a velocity written as a complex
    number is not set equal to a scalar)."""

    ref: Ref
    unknown: str = ""
    whole: bool = False

    def latex(self, shows: Shows) -> str:
        re, im = shows.entries(self.ref, 2)
        imaginary = {"1": "i", "-1": "-i"}.get(im, im + r"\,i")
        number = (
            f"({re} {tex.signed(imaginary)})"
            if self.whole
            else re
            if im == "0"
            else imaginary
            if re == "0"
            else f"({re} {tex.signed(imaginary)})"
        )
        if not self.unknown:
            return number
        if number in ("1", "-1"):
            return number[:-1] + self.unknown
        return number + r"\," + self.unknown

    def text(self, shows: Shows) -> str:
        return self.latex(shows)


@dataclass(frozen=True)
class Offset:
    """(s + c i) of a slider or a slot with the numbers; just s when the offset c is zero."""

    s: Ref
    c: Ref

    def latex(self, shows: Shows) -> str:
        s, c = shows.num(self.s), shows.num(self.c)
        if c == "0":
            return tex.paren(s)
        return f"({s} {tex.signed(c)}\\,i)"

    def text(self, shows: Shows) -> str:
        return self.latex(shows)


@dataclass(frozen=True)
class SumOf:
    """Terms joined with + and -, a negative term written as a subtraction (``join_sum``)."""

    terms: tuple[Token, ...]

    def latex(self, shows: Shows) -> str:
        return join_sum([t.latex(shows) for t in self.terms])

    def text(self, shows: Shows) -> str:
        return join_sum([t.text(shows) for t in self.terms])


def angle_name(member: Member) -> str:
    """The one symbol of a straight guide's angle: phi for a fixed slider guide, beta for a
    turning slot (the same in LaTeX, text and value keys)."""
    return "beta" if member.kind == "slot" else "phi"


class LoopUnavailable(Exception):
    """The loop-closure method does not cover this linkage (the message says why)."""


@dataclass
class Member:
    """One vector of a loop: a link vector a e^(i theta) turning with ``link`` (``rotating``), the
    fixed ground vector, or a slider's (s + i c) e^(i phi) along a fixed guide (``slider``)."""

    kind: str  # "rotating" | "ground" | "slider" | "slot"
    first: str
    second: str
    number: str  # the link's number in the loop notation (2, 3, ...)
    link: str | None = None
    slot: SlotMotion | None = None


@dataclass
class Loop:
    kind: str  # "four-bar" | "slider-crank" | "slotted lever"
    left: list[Member]
    right: list[Member]
    unknown_links: list[str]
    slot: SlotMotion | None = None
    joint: str = ""  # the point that closes the loop


@dataclass
class _Term:
    """A term of a differentiated loop: factor * prod(values) * (i) e^(i angle) [* unknown]."""

    latex: str
    text: str
    kind: Literal["phasor", "iphasor"]
    factors: list[tuple[str, float]]  # (key, value)
    angle: tuple[str, float]
    factor: float = 1.0
    unknown: Unknown | None = None

    def value(self) -> np.ndarray:
        magnitude = self.factor * math.prod(v for _, v in self.factors)
        theta = self.angle[1]
        unit = np.array([math.cos(theta), math.sin(theta)])
        if self.kind == "iphasor":
            unit = np.array([-unit[1], unit[0]])
        return magnitude * unit

    def put(self, b: StepBuilder, key: str, unit: str) -> str:
        """Register the term's value as ``key`` with its phasor check; return the key."""
        b.put(key, self.value(), unit)
        operands = [k for k, _ in self.factors] + [self.angle[0]]
        b.check(self.kind, key, *operands, factor=self.factor)
        return key


@dataclass(frozen=True)
class SliderCrankClosedForm:
    """The keys of a slider-crank loop's closed form (``LoopMethod.slider_crank_values``) and the
    branch of the drawn assembly (the sign of cos(th13 - phi))."""

    a3: str
    th13: str
    s14: str
    c: str
    lift: str
    sin13: str
    q2: str
    q3: str
    branch: str


@dataclass(frozen=True)
class FourBarClosedForm:
    """The keys of a four-bar loop's closed form (``LoopMethod.four_bar_values``), the sign of
    the drawn assembly and the whole turn ('', '2pi' or '-2pi') its angle sum needs."""

    d: str
    a: str
    b: str
    c: str
    a3_sq: str
    a4_sq: str
    d_sq: str
    radius: str
    cos: str
    gamma: str
    delta: str
    th13: str
    th14: str
    r_coupler: str
    sign: float
    turn: str


def member_parts(m: Member) -> tuple[str, str]:
    """The real and imaginary parts of a loop member in symbols: a cos theta and a sin theta of
    a e^(i theta); s cos phi - c sin phi and s sin phi + c cos phi of (s + i c) e^(i phi)."""
    n = m.number
    if m.kind in ("slider", "slot"):
        angle = rf"\varphi_{{{n}}}" if m.kind == "slider" else rf"\beta_{{{n}}}"
        s, c = f"s_{{1{n}}}", f"c_{{{n}}}"
        return (
            rf"({s}\cos{angle} - {c}\sin{angle})",
            rf"({s}\sin{angle} + {c}\cos{angle})",
        )
    return rf"a_{{{n}}}\cos\theta_{{1{n}}}", rf"a_{{{n}}}\sin\theta_{{1{n}}}"


@dataclass
class LoopMethod:
    ctx: LinkageContext
    numbers: dict[str, str] = field(default_factory=dict)
    rotating: dict[str, str] = field(default_factory=dict)  # link -> fixed pivot
    solved: set[str] = field(default_factory=set)
    loops: list[Loop] = field(default_factory=list)

    # --- topology -------------------------------------------------------------------------------

    def number(self, link: str) -> str:
        if link not in self.numbers:
            self.numbers[link] = str(len(self.numbers) + 1)
        return self.numbers[link]

    def crank_of(self, point: str) -> str:
        """The known link turning about a fixed pivot that carries ``point`` (not as its pivot)."""
        for link, pivot in self.rotating.items():
            if point in self.ctx.scene.links[link].points and point != pivot:
                return link
        raise LoopUnavailable(
            f"point {point} is not carried by a link turning about a fixed "
            "pivot, so no single loop through the ground closes there"
        )

    def analyse(self) -> None:
        scene = self.ctx.scene
        ground = scene.ground
        self.number(ground)
        for step in self.ctx.analysis.plan.steps:
            group = solution_group(step)
            if group is not None:
                self.loops.append(group.loop(self, step))
            elif isinstance(step, DriverStep):
                self.rotating[step.link] = step.pivot
                self.number(step.link)
            elif isinstance(step, TwoPointStep):
                if step.link not in self.solved:
                    raise LoopUnavailable(f"link {step.link} is not closed by a loop")
            else:
                raise LoopUnavailable(
                    f"the solving order contains a {type(step).__name__.replace('Step', '')} "
                    "group, which is not a four-bar, slider-crank or slotted-lever loop"
                )
        if not self.loops:
            raise LoopUnavailable("the linkage has no closed loop (only driven links)")

    def no_loop(self, why: str) -> NoReturn:
        """A group that closes no single loop through the ground: the method does not apply."""
        raise LoopUnavailable(why)

    def four_bar_loop(self, x: str, first: CircleSpec, second: CircleSpec) -> Loop:
        """a2 e^(i th12) + a3 e^(i th13) = a1 e^(i th11) + a4 e^(i th14): crank, coupler about
        the crank's moving point, ground, rocker about a fixed pivot."""
        ctx, ground = self.ctx, self.ctx.scene.ground
        fixed = [c for c in (first, second) if ctx.is_fixed(c.center)]
        moving = [c for c in (first, second) if not ctx.is_fixed(c.center)]
        if len(fixed) != 1 or len(moving) != 1:
            raise LoopUnavailable(
                f"the dyad at {x} is not a four-bar loop (one centre on a crank, the other fixed)"
            )
        coupler, rocker = moving[0], fixed[0]
        crank = self.crank_of(coupler.center)
        pivot = self.rotating[crank]
        for link in (coupler.link, rocker.link):
            self.number(link)
        self.solved.update((coupler.link, rocker.link))
        self.rotating[rocker.link] = rocker.center
        return Loop(
            "four-bar",
            [
                Member("rotating", pivot, coupler.center, self.numbers[crank], crank),
                Member("rotating", coupler.center, x, self.numbers[coupler.link], coupler.link),
            ],
            [
                Member("ground", pivot, rocker.center, self.numbers[ground]),
                Member("rotating", rocker.center, x, self.numbers[rocker.link], rocker.link),
            ],
            [coupler.link, rocker.link],
            joint=x,
        )

    def slider_crank_loop(self, x: str, coupler: CircleSpec, line: LineSpec) -> Loop:
        """a2 e^(i th12) + a3 e^(i th13) = (s14 + i c1) e^(i phi): crank, coupler about the
        crank's moving point, the slider along a fixed guide."""
        ctx = self.ctx
        if line.guide != ctx.scene.ground:
            raise LoopUnavailable(
                f"{x} slides in a moving slot of {line.guide}: not a slider-crank loop"
            )
        if ctx.is_fixed(coupler.center):
            raise LoopUnavailable(f"the dyad at {x} turns about a fixed point: no loop")
        crank = self.crank_of(coupler.center)
        pivot = self.rotating[crank]
        self.number(coupler.link)
        slider_number = str(len(self.numbers) + 1)
        self.numbers[f"slider at {x}"] = slider_number
        self.solved.add(coupler.link)
        slot = ctx.slot(line.guide, x)
        return Loop(
            "slider-crank",
            [
                Member("rotating", pivot, coupler.center, self.numbers[crank], crank),
                Member("rotating", coupler.center, x, self.numbers[coupler.link], coupler.link),
            ],
            [Member("slider", pivot, x, slider_number, slot=slot)],
            [coupler.link],
            slot,
            joint=x,
        )

    def lever_loop(self, step: LeverStep) -> Loop:
        ctx = self.ctx
        if not ctx.is_fixed(step.pivot):
            raise LoopUnavailable(
                f"the lever {step.link} turns about the moving point "
                f"{step.pivot}: not a single loop through the ground"
            )
        crank = self.crank_of(step.pin)
        pivot = self.rotating[crank]
        self.number(step.link)
        self.solved.add(step.link)
        self.rotating[step.link] = step.pivot
        slot = ctx.slot(step.link, step.pin)
        return Loop(
            "slotted lever",
            [Member("rotating", pivot, step.pin, self.numbers[crank], crank)],
            [
                Member("ground", pivot, step.pivot, self.numbers[ctx.scene.ground]),
                Member("slot", step.pivot, step.pin, self.numbers[step.link], step.link, slot),
            ],
            [step.link],
            slot,
            joint=step.pin,
        )

    # --- symbols and values ---------------------------------------------------------------------

    def register_member(self, b: StepBuilder, member: Member) -> tuple[str, str]:
        """Put the member's vector, length and angle with their checks; return (a key, th key)."""
        ctx = self.ctx
        r_np = ctx.pos(member.second) - ctx.pos(member.first)
        n = member.number
        p1 = b.put(
            f"pos({member.first})", ctx.pos(member.first), "m", ("points", member.first, "position")
        )
        p2 = b.put(
            f"pos({member.second})",
            ctx.pos(member.second),
            "m",
            ("points", member.second, "position"),
        )
        r = b.put(f"r({member.first},{member.second})", r_np, "m")
        b.check("sum", r, p2, f"-{p1}")
        if member.kind in ("slider", "slot"):
            assert member.slot is not None
            u = member.slot.direction
            phi = b.put(f"{angle_name(member)}{n}", math.atan2(u[1], u[0]), "rad")
            s = b.put(f"s1{n}", float(np.dot(r_np, u)), "m")
            c = b.put(f"c{n}", float(u[0] * r_np[1] - u[1] * r_np[0]), "m")
            uk = b.put(f"u{n}", u, "")
            b.check("angle", phi, uk)
            b.check("dot", s, r, uk)
            b.check("cross", c, uk, r)
            if member.kind == "slider":
                return s, phi
        a = b.put(f"a{n}", float(np.hypot(*r_np)), "m")
        th = b.put(f"theta1{n}", math.atan2(r_np[1], r_np[0]), "rad")
        b.check("norm", a, r)
        b.check("angle", th, r)
        return a, th

    # --- the steps ------------------------------------------------------------------------------

    def loop_step(self, loop: Loop, index: int) -> Step:
        """The loop closes: sum of the left side's vectors = sum of the right side's, both the
        position of the joint relative to the loop's first pivot."""
        ctx = self.ctx
        title = f"Loop {index}: the {loop.kind} closing at {loop.joint}"
        b = ctx.builder("loop.position", title)
        legend = ", ".join(f"{n} = {name}" for name, n in self.numbers.items())
        b.say(
            f"Links are numbered {legend}. Every vector of the loop is written as a complex "
            "number: length times e to the i times its angle from the x axis."
        )
        members = [self.loop_member(b, m) for m in (*loop.left, *loop.right)]
        total = b.put(f"z({loop.joint})", ctx.pos(loop.joint) - ctx.pos(loop.left[0].first), "m")
        b.check("sum", total, *[z for _, _, z in members[: len(loop.left)]])
        b.check("sum", total, *[z for _, _, z in members[len(loop.left) :]])
        self.loop_lines(b, loop, members, total)
        return b.build()

    def loop_member(self, b: StepBuilder, m: Member) -> tuple[str, str, str]:
        """A member's keys: a (s for a slider), theta (its guide's angle) and z, its vector as a
        complex number, = a e^(i theta) (the sum of its ends' positions for a slider)."""
        a, th = self.register_member(b, m)
        z = b.put(f"z({m.first},{m.second})", self.ctx.pos(m.second) - self.ctx.pos(m.first), "m")
        if m.kind == "slider":
            b.check("sum", z, f"r({m.first},{m.second})")
        else:
            b.check("phasor", z, a, th)
        return a, th, z

    def member_latex(self, m: Member, a: str, th: str) -> tuple[str, tuple[Piece, ...]]:
        """The member in symbols and with its numbers: a e^(i theta), (s + i c) e^(i phi)."""
        n = m.number
        if m.kind in ("slider", "slot"):
            angle = r"\varphi" if m.kind == "slider" else r"\beta"
            degrees = Degrees(Ref(f"{angle_name(m)}{n}"))
            return (
                rf"(s_{{1{n}}} + i\,c_{{{n}}})\,e^{{i{angle}_{{{n}}}}}",
                (Offset(Ref(f"s1{n}"), Ref(f"c{n}")), r"\,e^{i\,", degrees, "}"),
            )
        symbol = rf"a_{{{n}}}\,e^{{i\theta_{{1{n}}}}}"
        return symbol, (Num(Ref(a)), r"\,e^{i\,", Degrees(Ref(th)), "}")

    def loop_lines(
        self, b: StepBuilder, loop: Loop, members: list[tuple[str, str, str]], total: str
    ) -> None:
        """Write the loop in symbols, with its numbers and its value; say it with the data."""
        written = [
            self.member_latex(m, a, th)
            for m, (a, th, _) in zip((*loop.left, *loop.right), members, strict=True)
        ]
        left, right = written[: len(loop.left)], written[len(loop.left) :]
        b.line("&" + " + ".join(s for s, _ in left) + " = " + " + ".join(s for s, _ in right))
        parts = [member_parts(m) for m in (*loop.left, *loop.right)]
        for label, k in (("Re", 0), ("Im", 1)):
            sides = [
                " + ".join(p[k] for p in side)
                for side in (parts[: len(loop.left)], parts[len(loop.left) :])
            ]
            b.line(rf"&\text{{{label}: }} " + " = ".join(sides))
        b.say(
            "In symbols first: its real and imaginary parts are the loop's two scalar equations, "
            "each vector giving length times cos and length times sin of its angle."
        )
        b.line(
            "&",
            *joined(" + ", [n for _, n in left]),
            " = ",
            *joined(" + ", [n for _, n in right]),
        )
        b.line(r"&\text{both sides} = ", Complex(Ref(total)), latex_unit("m"))
        data: list[tuple[Piece, ...]] = []
        for key in b.values:
            if key[0] in "asc" and "(" not in key and key not in ("a", "s", "c"):
                data.append((f"{key} = ", Num(Ref(key), unit=True)))
            elif key.startswith(("theta1", "phi", "beta")):
                degrees = self.ctx.fmt.text(math.degrees(b.scalar(key)), "deg")
                data.append((f"{key} = ", Num(Ref(key), unit=True), f" ({degrees} deg)"))
        b.say(
            f"Loop closure: {' + '.join(self.member_text(m) for m in loop.left)} = "
            f"{' + '.join(self.member_text(m) for m in loop.right)}. With ",
            *joined("; ", data),
            f", both sides give the position of {loop.joint} relative to {loop.left[0].first}: ",
            Num(Ref(total), unit=True),
            ".",
        )

    def closed_form_step(self, loop: Loop, index: int) -> Step:
        """Seed 001's position for a slider-crank loop, in the guide's frame (times e^(-i phi)):
        imaginary part a2 sin(th12 - phi) + a3 sin(th13 - phi) = c gives th13, the real part
        s14 = a2 cos(th12 - phi) + a3 cos(th13 - phi)."""
        b = self.ctx.builder("position.loop", f"Loop {index}: the position in closed form")
        found = self.slider_crank_values(b, loop)
        self.slider_crank_lines(b, loop, found)
        return b.build()

    def slider_crank_values(self, b: StepBuilder, loop: Loop) -> SliderCrankClosedForm:
        """sin(th13 - phi) = (c - a2 sin(th12 - phi)) / a3 and s14 = a2 cos(th12 - phi) +
        a3 cos(th13 - phi), each piece of arithmetic put with its check."""
        crank, coupler = loop.left
        n2, n3, n4 = crank.number, coupler.number, loop.right[0].number
        a2, th12 = self.register_member(b, crank)
        a3, th13 = self.register_member(b, coupler)
        s14, phi = self.register_member(b, loop.right[0])
        c = f"c{n4}"
        one = b.put("1", 1.0, "")
        rel = {}
        for name, th in ((n2, th12), (n3, th13)):
            d = b.put(f"theta1{name} - phi{n4}", b.scalar(th) - b.scalar(phi), "rad")
            b.check("sum", d, th, f"-{phi}")
            turned = (math.cos(b.scalar(d)), math.sin(b.scalar(d)))
            rel[name] = b.put(f"e^(i(theta1{name} - phi{n4}))", turned, "")
            b.check("phasor", rel[name], one, d)
        lift = b.put(f"a{n2} sin", b.scalar(a2) * b.vector(rel[n2])[1], "m")
        b.check("product", lift, a2, f"{rel[n2]}[1]")
        reference = abs(b.scalar(c)) + abs(b.scalar(lift))
        num = b.put(f"c{n4} - a{n2} sin", b.scalar(c) - b.scalar(lift), "m", reference=reference)
        b.check("sum", num, c, f"-{lift}")
        sin13 = b.put(f"sin(theta1{n3} - phi{n4})", b.scalar(num) / b.scalar(a3), "", reference=1.0)
        b.check("quotient", sin13, num, a3)
        b.check("sum", sin13, f"{rel[n3]}[1]")
        q2 = b.put(f"a{n2} cos", b.scalar(a2) * b.vector(rel[n2])[0], "m")
        q3 = b.put(f"a{n3} cos", b.scalar(a3) * b.vector(rel[n3])[0], "m")
        b.check("product", q2, a2, f"{rel[n2]}[0]")
        b.check("product", q3, a3, f"{rel[n3]}[0]")
        b.check("sum", s14, q2, q3)
        branch = "cos(theta13 - phi) > 0" if b.vector(rel[n3])[0] >= 0 else "cos(theta13 - phi) < 0"
        return SliderCrankClosedForm(a3, th13, s14, c, lift, sin13, q2, q3, branch)

    def slider_crank_lines(self, b: StepBuilder, loop: Loop, f: SliderCrankClosedForm) -> None:
        """Write the closed form: Im and Re in the guide's frame, then the numbers."""
        n2, n3, n4 = loop.left[0].number, loop.left[1].number, loop.right[0].number
        t2, t3, p4 = f"\\theta_{{1{n2}}}", f"\\theta_{{1{n3}}}", f"\\varphi_{{{n4}}}"
        sin2, sin3 = rf"\sin({t2} - {p4})", rf"\sin({t3} - {p4})"
        cos2, cos3 = rf"\cos({t2} - {p4})", rf"\cos({t3} - {p4})"
        b.line(
            rf"&\text{{Im: }} a_{{{n2}}} {sin2} + a_{{{n3}}} {sin3} = c_{{{n4}}} \;\Rightarrow\; "
            rf"{sin3} = \frac{{c_{{{n4}}} - a_{{{n2}}} {sin2}}}{{a_{{{n3}}}}}"
        )
        b.line(rf"&\text{{Re: }} s_{{1{n4}}} = a_{{{n2}}} {cos2} + a_{{{n3}}} {cos3}")
        c, lift, a3 = Ref(f.c), Ref(f.lift), Ref(f.a3)
        b.line(
            f"&{sin3} = ",
            r"\frac{",
            Num(c),
            " - ",
            Paren(lift),
            "}{",
            Num(a3),
            "} = ",
            Num(Ref(f.sin13)),
            rf", \quad {t3} = ",
            Num(Ref(f.th13), unit=True),
        )
        b.line(
            f"&s_{{1{n4}}} = ",
            Num(Ref(f.q2)),
            " ",
            Signed(Ref(f.q3)),
            " = ",
            Boxed((Num(Ref(f.s14), unit=True),)),
        )
        b.say(
            f"Turned into the guide's frame (times e^(-i phi{n4})), the imaginary part of the loop "
            f"gives sin(theta1{n3} - phi{n4}) = (c{n4} - a{n2} sin(theta1{n2} - phi{n4}))/a{n3} = ",
            Num(Ref(f.sin13)),
            f", and the real part s1{n4} = a{n2} cos(theta1{n2} - phi{n4}) + "
            f"a{n3} cos(theta1{n3} - phi{n4}) = ",
            Num(Ref(f.s14), unit=True),
            f". Of the two angles with this sine the one taken has {f.branch}, the assembly as "
            f"drawn: theta1{n3} = ",
            Num(Ref(f.th13), unit=True),
            ".",
        )

    def four_bar_closed_form_step(self, loop: Loop, index: int) -> Step:
        """The rocker's angle of a four-bar loop a2 e^(i th12) + a3 e^(i th13) = a1 e^(i th11) +
        a4 e^(i th14): with d = a1 e^(i th11) - a2 e^(i th12), a3 e^(i th13) = d + a4 e^(i th14);
        squaring and adding the real and imaginary parts eliminates th13 and leaves
        A cos th14 + B sin th14 = C, A = 2 a4 d_x, B = 2 a4 d_y, C = a3^2 - a4^2 - |d|^2, so
        th14 = delta +- gamma with delta = arg d and cos gamma = C / (2 a4 |d|); then
        th13 = arg(d + a4 e^(i th14))."""
        b = self.ctx.builder("position.loop", f"Loop {index}: the position in closed form")
        found = self.four_bar_values(b, loop)
        self.four_bar_lines(b, loop, found)
        return b.build()

    def four_bar_values(self, b: StepBuilder, loop: Loop) -> FourBarClosedForm:
        """Put the closed form's numbers, with a check for each piece of arithmetic:
        d = a1 e^(i th11) - a2 e^(i th12), then ``eliminate_coupler`` and ``rocker_angle``."""
        crank, coupler = loop.left
        ground, rocker = loop.right
        self.register_member(b, crank)
        a3, th13 = self.register_member(b, coupler)
        self.register_member(b, ground)
        a4, th14 = self.register_member(b, rocker)
        r_ground = f"r({ground.first},{ground.second})"
        r_crank = f"r({crank.first},{crank.second})"
        r_coupler = f"r({coupler.first},{coupler.second})"
        d_np = np.asarray(b.vector(r_ground)) - np.asarray(b.vector(r_crank))
        d = b.put("d", d_np, "m")
        b.check("sum", d, r_ground, f"-{r_crank}")
        # the position layer's RRR: circles about the rocker's pivot (a4) and the crank pin (a3)
        cut = chord(-d_np[None], b.scalar(a4), b.scalar(a3))
        d_len = b.put("|d|", float(cut.d[0]), "m")
        b.check("norm", d_len, d)
        cos_gamma = -float(cut.a[0]) / b.scalar(a4)
        coef_a, coef_b, coef_c, squares, radius, cos = self.eliminate_coupler(
            b, a3, a4, (d, d_len), cos_gamma
        )
        gamma, delta, sign, turn = self.rocker_angle(b, th14, d, cos)
        b.check("sum", r_coupler, d, f"r({rocker.first},{rocker.second})")
        return FourBarClosedForm(
            d, coef_a, coef_b, coef_c, *squares, radius, cos, gamma, delta, th13, th14,
            r_coupler, sign, turn,
        )  # fmt: skip

    def eliminate_coupler(
        self, b: StepBuilder, a3: str, a4: str, ds: tuple[str, str], cos_gamma: float
    ) -> tuple[str, str, str, tuple[str, str, str], str, str]:
        """A cos th14 + B sin th14 = C with A = 2 a4 d_x, B = 2 a4 d_y, C = a3^2 - a4^2 - |d|^2,
        and cos gamma = C / R, R = 2 a4 |d| (= -a / a4, a the distance of the rocker's pivot
        from the common chord of ``rrr.chord``, given as ``cos_gamma``); ``ds`` the keys of d and
        |d|: the keys of A, B, C, the three squares, R, cos."""
        d, d_len = ds
        a4v, d_np = b.scalar(a4), b.vector(d)
        coef_a = b.put("A", 2 * a4v * d_np[0], "m^2")
        coef_b = b.put("B", 2 * a4v * d_np[1], "m^2")
        b.check("product", coef_a, a4, f"{d}[0]", factor=2.0)
        b.check("product", coef_b, a4, f"{d}[1]", factor=2.0)
        squares = {k: b.put(f"{k}^2", b.scalar(k) ** 2, "m^2") for k in (a3, a4, d_len)}
        for k, v in squares.items():
            b.check("product", v, k, k)
        sq3, sq4, sq_d = squares[a3], squares[a4], squares[d_len]
        sizes = sum(b.scalar(v) for v in squares.values())
        value = b.scalar(sq3) - b.scalar(sq4) - b.scalar(sq_d)
        coef_c = b.put("C", value, "m^2", reference=sizes)
        b.check("sum", coef_c, sq3, f"-{sq4}", f"-{sq_d}")
        radius = b.put("R", 2 * a4v * b.scalar(d_len), "m^2")
        b.check("product", radius, a4, d_len, factor=2.0)
        cos = b.put("cos gamma", cos_gamma, "", reference=1.0)
        b.check("quotient", cos, coef_c, radius)
        return coef_a, coef_b, coef_c, (sq3, sq4, sq_d), radius, cos

    def rocker_angle(
        self, b: StepBuilder, th14: str, d: str, cos: str
    ) -> tuple[str, str, float, str]:
        """th14 = delta +- gamma (+ a whole turn), delta = arg d, gamma >= 0 with cos gamma = C/R:
        the keys of gamma and delta, the sign of the drawn assembly and the turn."""
        d_np = b.vector(d)
        delta = b.put("delta", math.atan2(d_np[1], d_np[0]), "rad")
        b.check("angle", delta, d)
        # gamma from the drawn pose (acos loses digits where the loop is nearly flat)
        off = math.remainder(b.scalar(th14) - b.scalar(delta), 2 * math.pi)
        gamma = b.put("gamma", abs(off), "rad")
        one = b.put("1", 1.0, "")
        unit = b.put("e^(i gamma)", (math.cos(abs(off)), math.sin(abs(off))), "")
        b.check("phasor", unit, one, gamma)
        b.check("sum", cos, f"{unit}[0]")
        sign = 1.0 if off >= 0 else -1.0
        turn, _ = wrap_turn(b, b.scalar(delta) + sign * abs(off), b.scalar(th14))
        b.check("sum", th14, delta, gamma if sign > 0 else f"-{gamma}", *([turn] if turn else []))
        return gamma, delta, sign, turn

    def four_bar_lines(self, b: StepBuilder, loop: Loop, f: FourBarClosedForm) -> None:
        """Write the closed form: the loop rearranged, Re and Im, the elimination, the numbers."""
        crank, coupler = loop.left
        ground, rocker = loop.right
        n1, n2, n3, n4 = ground.number, crank.number, coupler.number, rocker.number
        t = {k: rf"\theta_{{1{k}}}" for k in (n1, n2, n3, n4)}
        pm = "+" if f.sign > 0 else "-"
        b.line(
            rf"&a_{{{n3}}}\,e^{{i{t[n3]}}} = \vec{{d}} + a_{{{n4}}}\,e^{{i{t[n4]}}}, \quad "
            rf"\vec{{d}} = a_{{{n1}}}\,e^{{i{t[n1]}}} - a_{{{n2}}}\,e^{{i{t[n2]}}}"
        )
        b.line(
            rf"&\text{{Re: }} a_{{{n3}}}\cos{t[n3]} = d_x + a_{{{n4}}}\cos{t[n4]}, \quad "
            rf"\text{{Im: }} a_{{{n3}}}\sin{t[n3]} = d_y + a_{{{n4}}}\sin{t[n4]}"
        )
        b.line(
            rf"&A\cos{t[n4]} + B\sin{t[n4]} = C, \quad A = 2a_{{{n4}}}d_x, \; B = 2a_{{{n4}}}d_y, "
            rf"\; C = a_{{{n3}}}^2 - a_{{{n4}}}^2 - |\vec{{d}}|^2"
        )
        b.line(
            rf"&{t[n4]} = \delta \pm \gamma, \quad \delta = \arg\vec{{d}}, \quad \cos\gamma = "
            rf"\frac{{C}}{{\sqrt{{A^2 + B^2}}}} = \frac{{C}}{{2a_{{{n4}}}|\vec{{d}}|}}"
        )
        b.line(
            r"&\vec{d} = ",
            Complex(Ref(f.d)),
            latex_unit("m"),
            r", \quad A = ",
            Num(Ref(f.a), unit=True),
            r", \quad B = ",
            Num(Ref(f.b), unit=True),
            r", \quad C = ",
            Num(Ref(f.a3_sq)),
            " - ",
            Num(Ref(f.a4_sq)),
            " - ",
            Num(Ref(f.d_sq)),
            " = ",
            Num(Ref(f.c), unit=True),
        )
        b.line(
            r"&\cos\gamma = ",
            Frac(Ref(f.c), Ref(f.radius)),
            " = ",
            Num(Ref(f.cos)),
            r", \quad \gamma = ",
            Num(Ref(f.gamma), unit=True),
            r", \quad \delta = ",
            Num(Ref(f.delta), unit=True),
        )
        b.line(
            f"&{t[n4]} = ",
            Num(Ref(f.delta)),
            f" {pm} ",
            Num(Ref(f.gamma)),
            f"{TURN_LATEX[f.turn]} = ",
            Boxed((Num(Ref(f.th14), unit=True),)),
            rf", \quad {t[n3]} = \arg(\vec{{d}} + a_{{{n4}}}e^{{i{t[n4]}}}) = \arg ",
            Complex(Ref(f.r_coupler)),
            " = ",
            Boxed((Num(Ref(f.th13), unit=True),)),
        )
        self.four_bar_sentence(b, loop, f)
        self.freudenstein_lines(b, loop)

    def freudenstein_lines(self, b: StepBuilder, loop: Loop) -> None:
        """Freudenstein's equation K1 cos phi4 - K2 cos phi2 + K3 = cos(phi2 - phi4), angles
        from the ground line (phi_k = th1k - th11), K1 = a1/a2, K2 = a1/a4,
        K3 = (a2^2 - a3^2 + a4^2 + a1^2) / (2 a2 a4): the phase form divided by 2 a2 a4, since
        A cos th14 + B sin th14 - C = 2 a2 a4 (K1 cos phi4 - K2 cos phi2 + K3 - cos(phi2 - phi4))
        with |d|^2 = a1^2 + a2^2 - 2 a1 a2 cos phi2; both sides evaluated at the solved pose."""
        crank, coupler = loop.left
        ground, rocker = loop.right
        n1, n2, n3, n4 = ground.number, crank.number, coupler.number, rocker.number
        a1, a2, a3, a4 = (b.scalar(f"a{n}") for n in (n1, n2, n3, n4))
        th11 = b.scalar(f"theta1{n1}")
        phi2 = b.put(f"phi{n2}", b.scalar(f"theta1{n2}") - th11, "rad")
        phi4 = b.put(f"phi{n4}", b.scalar(f"theta1{n4}") - th11, "rad")
        b.check("sum", phi2, f"theta1{n2}", f"-theta1{n1}")
        b.check("sum", phi4, f"theta1{n4}", f"-theta1{n1}")
        k1 = b.put("K1", a1 / a2, "")
        k2 = b.put("K2", a1 / a4, "")
        k3 = b.put("K3", (a2**2 - a3**2 + a4**2 + a1**2) / (2.0 * a2 * a4), "")
        b.check("quotient", k1, f"a{n1}", f"a{n2}")
        b.check("quotient", k2, f"a{n1}", f"a{n4}")
        p2, p4 = b.scalar(phi2), b.scalar(phi4)
        left = b.put(
            "Freudenstein: left",
            b.scalar(k1) * math.cos(p4) - b.scalar(k2) * math.cos(p2) + b.scalar(k3),
            "",
            reference=abs(b.scalar(k1)) + abs(b.scalar(k2)) + abs(b.scalar(k3)),
        )
        right = b.put("Freudenstein: right", math.cos(p2 - p4), "", reference=1.0)
        ph = {n: rf"\varphi_{{{n}}}" for n in (n2, n4)}
        sub = {n: f"a_{{{n}}}" for n in (n1, n2, n3, n4)}
        b.line(
            rf"&\text{{Freudenstein: }} K_1\cos{ph[n4]} - K_2\cos{ph[n2]} + K_3 = "
            rf"\cos({ph[n2]} - {ph[n4]}), \quad {ph[n2]} = \theta_{{1{n2}}} - \theta_{{1{n1}}}, "
            rf"\; {ph[n4]} = \theta_{{1{n4}}} - \theta_{{1{n1}}}"
        )
        b.line(
            rf"&K_1 = \frac{{{sub[n1]}}}{{{sub[n2]}}} = ",
            Num(Ref(k1)),
            rf", \quad K_2 = \frac{{{sub[n1]}}}{{{sub[n4]}}} = ",
            Num(Ref(k2)),
            rf", \quad K_3 = \frac{{{sub[n2]}^2 - {sub[n3]}^2 + {sub[n4]}^2 + {sub[n1]}^2}}"
            rf"{{2{sub[n2]}{sub[n4]}}} = ",
            Num(Ref(k3)),
        )
        b.line(
            rf"&A\cos\theta_{{1{n4}}} + B\sin\theta_{{1{n4}}} - C = 2{sub[n2]}{sub[n4]}"
            rf"\left(K_1\cos{ph[n4]} - K_2\cos{ph[n2]} + K_3 - \cos({ph[n2]} - {ph[n4]})\right)"
            rf", \quad |\vec{{d}}|^2 = {sub[n1]}^2 + {sub[n2]}^2 - 2{sub[n1]}{sub[n2]}\cos{ph[n2]}"
        )
        b.line(
            rf"&{ph[n2]} = ",
            Num(Ref(phi2), unit=True),
            rf", \; {ph[n4]} = ",
            Num(Ref(phi4), unit=True),
            r": \quad ",
            Num(Ref(left)),
            " = ",
            Num(Ref(right)),
        )
        b.say(
            f"The same equation in Freudenstein's form, with the angles measured from the ground "
            f"line (phi{n2} = theta1{n2} - theta1{n1}, phi{n4} = theta1{n4} - theta1{n1}): "
            f"K1 cos phi{n4} - K2 cos phi{n2} + K3 = cos(phi{n2} - phi{n4}) with "
            f"K1 = a{n1}/a{n2} = ",
            Num(Ref(k1)),
            f", K2 = a{n1}/a{n4} = ",
            Num(Ref(k2)),
            f" and K3 = (a{n2}^2 - a{n3}^2 + a{n4}^2 + a{n1}^2)/(2 a{n2} a{n4}) = ",
            Num(Ref(k3)),
            f"; it is the phase form divided by 2 a{n2} a{n4}, since |d|^2 = a{n1}^2 + a{n2}^2 - "
            f"2 a{n1} a{n2} cos phi{n2}. At the solved pose both sides are ",
            Num(Ref(left)),
            " and ",
            Num(Ref(right)),
            ".",
        )

    def four_bar_sentence(self, b: StepBuilder, loop: Loop, f: FourBarClosedForm) -> None:
        """Say the closed form: the elimination of th13, then the assembly taken."""
        crank, coupler = loop.left
        ground, rocker = loop.right
        n1, n2, n3, n4 = ground.number, crank.number, coupler.number, rocker.number
        pm = "+" if f.sign > 0 else "-"
        x = loop.joint
        where = "left" if f.sign > 0 else "right"
        b.say(
            f"Moving the crank to the right side, a{n3} e^(i theta1{n3}) = d + a{n4} e^(i "
            f"theta1{n4}) with d = a{n1} e^(i theta1{n1}) - a{n2} e^(i theta1{n2}) = ",
            Num(Ref(f.d), unit=True),
            f", the vector from {crank.second} to {ground.second}. Squaring and adding the real "
            f"and imaginary parts eliminates theta1{n3}: A cos theta1{n4} + B sin theta1{n4} = C "
            f"with A = 2 a{n4} d_x = ",
            Num(Ref(f.a)),
            f", B = 2 a{n4} d_y = ",
            Num(Ref(f.b)),
            f" and C = a{n3}^2 - a{n4}^2 - |d|^2 = ",
            Num(Ref(f.c), unit=True),
            f". So theta1{n4} = delta +- gamma with delta = arg d = ",
            Num(Ref(f.delta), unit=True),
            f" and cos gamma = C / (2 a{n4} |d|) = ",
            Num(Ref(f.cos)),
            ", gamma = ",
            Num(Ref(f.gamma), unit=True),
            f". The two signs are the two assemblies, {x} on the left or on the right of "
            f"{crank.second}{ground.second}; the one taken is {x} on the {where} of "
            f"{crank.second}{ground.second} (sign {pm}), as drawn (the solver keeps the drawn "
            f"branch): theta1{n4} = ",
            Num(Ref(f.th14), unit=True),
            f", and theta1{n3} = arg(d + a{n4} e^(i theta1{n4})) = ",
            Num(Ref(f.th13), unit=True),
            ".",
        )

    def lever_closed_form_step(self, loop: Loop, index: int) -> Step:
        """The slotted lever's loop a2 e^(i th12) = a1 e^(i th11) + (s + i c) e^(i beta): with
        w = a2 e^(i th12) - a1 e^(i th11), (s + i c) e^(i beta) = w (``lever_closed_form``)."""
        (crank,) = loop.left
        ground, lever = loop.right
        n1, n2, n3 = ground.number, crank.number, lever.number
        b = self.ctx.builder("position.loop", f"Loop {index}: the position in closed form")
        self.register_member(b, crank)
        self.register_member(b, ground)
        r_crank = f"r({crank.first},{crank.second})"
        r_ground = f"r({ground.first},{ground.second})"
        w = b.put("w", np.asarray(b.vector(r_crank)) - np.asarray(b.vector(r_ground)), "m")
        b.check("sum", w, r_crank, f"-{r_ground}")
        assert lever.slot is not None
        b.line(
            rf"&(s_{{1{n3}}} + i\,c_{{{n3}}})\,e^{{i\beta_{{{n3}}}}} = w = a_{{{n2}}}\,"
            rf"e^{{i\theta_{{1{n2}}}}} - a_{{{n1}}}\,e^{{i\theta_{{1{n1}}}}}"
        )
        b.say(
            f"The crank's side minus the ground vector gives the pin {loop.joint} seen from the "
            f"lever's pivot {lever.first}: w = a{n2} e^(i theta1{n2}) - a{n1} e^(i theta1{n1}) = ",
            Num(Ref(w), unit=True),
            ".",
        )
        notation = LeverNotation(
            f"s1{n3}", f"c{n3}", f"beta{n3}", f"s_{{1{n3}}}", f"c_{{{n3}}}", rf"\beta_{{{n3}}}"
        )
        lever_closed_form(b, Ref(w), lever.slot.direction, notation)
        return b.build()

    def member_text(self, m: Member) -> str:
        n = m.number
        if m.kind in ("slider", "slot"):
            return f"(s1{n} + i c{n}) e^(i {angle_name(m)}{n})"
        return f"a{n} e^(i theta1{n})"

    def derivative_terms(
        self, loop: Loop, order: int, b: StepBuilder
    ) -> tuple[list[_Term], list[_Term]]:
        """The terms of the first (order 1) or second (order 2) time derivative of each side:
        d/dt a e^(i th) = i a omega e^(i th), d/dt (s e^(i phi)) = s-dot e^(i phi) (the ground
        vector is constant)."""
        sides: tuple[list[_Term], list[_Term]] = ([], [])
        for side, terms in ((loop.left, sides[0]), (loop.right, sides[1])):
            for m in side:
                a, th = self.register_member(b, m)
                if m.kind == "slider":
                    u = self.slide_unknown(m, order)
                    angle = (th, b.scalar(th))
                    phasor = rf"{u.latex}\,e^{{i\varphi_{{{m.number}}}}}"
                    text = f"{u.text} e^(i phi{m.number})"
                    terms.append(_Term(phasor, text, "phasor", [], angle, 1.0, u))
                elif m.kind != "ground":
                    terms += self.link_terms(b, m, (a, th), order, m.link in loop.unknown_links)
        return sides

    def link_terms(
        self, b: StepBuilder, m: Member, keys: tuple[str, str], order: int, unknown: bool
    ) -> list[_Term]:
        """d/dt a e^(i th) = i a omega e^(i th); d2/dt2 = i a alpha e^(i th) - a omega^2 e^(i th)
        (after the slot's own terms for a turning slot, ``slot_terms``)."""
        link, n = m.link, m.number
        assert link is not None
        omega = self.ctx.omega(link)
        w_key = b.put(f"omega1{n}", omega, "rad/s", ("links", link, "omega"))
        a_f, angle = (keys[0], b.scalar(keys[0])), (keys[1], b.scalar(keys[1]))
        terms = self.slot_terms(b, m, (w_key, omega), order) if m.kind == "slot" else []
        if order == VELOCITY:
            name, known = "omega", (w_key, omega)
        else:
            alpha = self.ctx.alpha(link)
            name = "alpha"
            known = (b.put(f"alpha1{n}", alpha, "rad/s^2", ("links", link, "alpha")), alpha)
        phasor = rf"i\,a_{{{n}}}\,\{name}_{{1{n}}}\,e^{{i\theta_{{1{n}}}}}"
        text = f"i a{n} {name}1{n} e^(i theta1{n})"
        if unknown:
            rate = self.rate_unknown(link, n, order)
            terms.append(_Term(phasor, text, "iphasor", [a_f], angle, 1.0, rate))
        else:
            terms.append(_Term(phasor, text, "iphasor", [a_f, known], angle, 1.0))
        if order == ACCELERATION:
            phasor = rf"-a_{{{n}}}\,\omega_{{1{n}}}^2\,e^{{i\theta_{{1{n}}}}}"
            text = f"- a{n} omega1{n} squared e^(i theta1{n})"
            omega2 = [a_f, (w_key, omega), (w_key, omega)]
            terms.append(_Term(phasor, text, "phasor", omega2, angle, -1.0))
        return terms

    def slot_terms(
        self, b: StepBuilder, m: Member, omega: tuple[str, float], order: int
    ) -> list[_Term]:
        """The pin's slide in a turning slot: s-dot e^(i beta) (velocity); s-ddot e^(i beta) +
        2 i omega s-dot e^(i beta), the Coriolis term (acceleration)."""
        n = m.number
        su = self.slide_unknown(m, order)
        beta = (f"beta{n}", b.scalar(f"beta{n}"))
        phasor = rf"{su.latex}\,e^{{i\beta_{{{n}}}}}"
        terms = [_Term(phasor, f"{su.text} e^(i beta{n})", "phasor", [], beta, 1.0, su)]
        if order == ACCELERATION:
            s_dot = b.put(f"s_dot1{n}", self.slide_value(m, VELOCITY), "m/s")
            coriolis = rf"2\,i\,\omega_{{1{n}}}\,\dot{{s}}_{{1{n}}}\,e^{{i\beta_{{{n}}}}}"
            text = f"2 i omega1{n} s-dot1{n} e^(i beta{n}) (Coriolis)"
            factors = [omega, (s_dot, self.slide_value(m, VELOCITY))]
            terms.append(_Term(coriolis, text, "iphasor", factors, beta, 2.0))
        return terms

    def rate_unknown(self, link: str, n: str, order: int) -> Unknown:
        ctx = self.ctx
        if order == VELOCITY:
            return Unknown(
                f"omega1{n}",
                rf"\omega_{{1{n}}}",
                f"omega1{n}",
                "rad/s",
                ctx.omega(link),
                ("links", link, "omega"),
                f"the angular velocity of link {n} ({link})",
            )
        return Unknown(
            f"alpha1{n}",
            rf"\alpha_{{1{n}}}",
            f"alpha1{n}",
            "rad/s^2",
            ctx.alpha(link),
            ("links", link, "alpha"),
            f"the angular acceleration of link {n} ({link})",
        )

    def slide_value(self, m: Member, order: int) -> float:
        assert m.slot is not None
        u = m.slot.direction
        if order == VELOCITY:
            return float(np.dot(m.slot.relative_velocity, u))
        assert m.slot.relative_acceleration is not None
        return float(np.dot(m.slot.relative_acceleration, u))

    def slide_unknown(self, m: Member, order: int) -> Unknown:
        n = m.number
        where = f"along the {'guide' if m.kind == 'slider' else 'slot'} at {m.second}"
        if order == VELOCITY:
            return Unknown(
                f"s_dot1{n}",
                rf"\dot{{s}}_{{1{n}}}",
                f"s-dot1{n}",
                "m/s",
                self.slide_value(m, order),
                None,
                f"the signed sliding rate {where} (positive in the direction of its angle)",
            )
        return Unknown(
            f"s_ddot1{n}",
            rf"\ddot{{s}}_{{1{n}}}",
            f"s-double-dot1{n}",
            "m/s^2",
            self.slide_value(m, order),
            None,
            f"the sliding acceleration {where}",
        )

    def derivative_step(self, loop: Loop, index: int, order: int) -> Step:
        """The loop differentiated once (twice): the terms with the unknown rates to the left,
        the known terms to the right, sum(col_j u_j) = -sum(known), solved by Cramer's rule."""
        what, unit = MOTION[order]
        b = self.ctx.builder(
            f"loop.{what}",
            f"Loop {index}: {what} equation "
            f"({'first' if order == VELOCITY else 'second'} time derivative)",
        )
        left, right = self.derivative_terms(loop, order, b)
        shown, known, columns = self.put_terms(b, left + right, len(left), unit)
        coefficients, rhs = self.loop_system(b, known, columns, unit)
        self.derivative_lines(b, (left, right), shown)
        self.derivative_sentences(b, loop, index, order, (left, right))
        b.say(
            "Unknowns to the left, known terms to the right; the real and imaginary parts are "
            "two linear equations:"
        )
        present_solution(b, [u for u, _, _ in columns], coefficients, rhs, "", cramer=True)
        if loop.slot is not None and loop.kind != "four-bar":
            self.slide_in_slot(b, loop, [u for u, _, _ in columns], order)
        return b.build()

    def put_terms(
        self, b: StepBuilder, terms: list[_Term], n_left: int, unit: str
    ) -> tuple[list[str], list[tuple[str, float]], list[tuple[Unknown, str, float]]]:
        """Put each term's value: a known term as term1, term2... and the coefficient of an
        unknown as col(u); returns the keys in order, the known terms and the unknowns' columns,
        each with its side (+1 left, -1 right)."""
        shown: list[str] = []
        known: list[tuple[str, float]] = []
        columns: list[tuple[Unknown, str, float]] = []
        for k, t in enumerate(terms):
            side_sign = 1.0 if k < n_left else -1.0
            if t.unknown is not None:
                shown.append(t.put(b, f"col({t.unknown.key})", ""))
                columns.append((t.unknown, shown[-1], side_sign))
            else:
                shown.append(t.put(b, f"term{len(known) + 1}", unit))
                known.append((shown[-1], side_sign))
        return shown, known, columns

    def loop_system(
        self,
        b: StepBuilder,
        known: list[tuple[str, float]],
        columns: list[tuple[Unknown, str, float]],
        unit: str,
    ) -> tuple[list[list[str]], list[str]]:
        """sum(side * col_j) u_j = -sum(side * known) in real and imaginary parts: the
        coefficients c_ij and right-hand sides b_i, with their checks."""
        known_total = np.zeros(2)
        for k, s in known:
            known_total = known_total + s * np.asarray(b.vector(k))
        rhs_vec = b.put("rhs", -known_total, unit)
        b.check("sum", rhs_vec, *[("-" if s > 0 else "") + k for k, s in known])
        coefficients: list[list[str]] = [[], []]
        rhs = []
        known_size = sum(math.hypot(*b.vector(k)) for k, _ in known)
        for i in range(2):
            for j, (_, key, sign) in enumerate(columns):
                reference = math.hypot(*b.vector(key))
                c = b.put(f"c{i + 1}{j + 1}", sign * b.vector(key)[i], "", reference=reference)
                b.check("sum", c, f"{'-' if sign < 0 else ''}{key}[{i}]")
                coefficients[i].append(c)
            bi = b.put(f"b{i + 1}", b.vector(rhs_vec)[i], "", reference=known_size)
            b.check("sum", bi, f"{rhs_vec}[{i}]")
            rhs.append(bi)
        return coefficients, rhs

    def derivative_lines(
        self,
        b: StepBuilder,
        sides: tuple[list[_Term], list[_Term]],
        shown: list[str],
    ) -> None:
        """Write the differentiated loop in symbols, then with the numbers (``shown``: the keys
        of the terms, left side first)."""
        left, right = sides
        sym_left = " + ".join(t.latex for t in left).replace("+ -", "- ")
        sym_right = " + ".join(t.latex for t in right).replace("+ -", "- ") or "0"
        b.line(rf"&{sym_left} = {sym_right}")
        numbers = [
            Complex(Ref(k), "" if t.unknown is None else t.unknown.latex)
            for t, k in zip(left + right, shown, strict=True)
        ]
        b.line("&", SumOf(tuple(numbers[: len(left)])), " = ", SumOf(tuple(numbers[len(left) :])))

    def derivative_sentences(
        self, b: StepBuilder, loop: Loop, index: int, order: int, sides: tuple[list[_Term], ...]
    ) -> None:
        """Say how the loop was differentiated, and why it is the vector method's equation."""
        text_left = " + ".join(t.text for t in sides[0]).replace("+ -", "-")
        text_right = (" + ".join(t.text for t in sides[1]) or "0").replace("+ -", "-")
        sliding = any(m.kind in ("slider", "slot") for m in (*loop.left, *loop.right))
        b.say(
            f"Differentiating the loop {'once' if order == VELOCITY else 'twice'} with respect "
            "to time ("
            + (
                "the lengths a of the links are constant, while the slider's s varies and is "
                "differentiated as an unknown; "
                if sliding
                else "the lengths of the links are constant; "
            )
            + "d/dt e^(i theta) = i omega e^(i theta)): "
            f"{text_left} = {text_right}."
        )
        if index == 1 and order == VELOCITY:
            b.say(
                "The real and imaginary parts of this equation are the x and y components of the "
                "vector method's v_B = v_A + omega x r_AB: i a omega e^(i theta) is omega x r in "
                "complex numbers, so both methods solve the same two equations."
            )
        if order == ACCELERATION and loop.kind == "slotted lever":
            b.say(
                "The term 2 i omega s-dot e^(i beta) is the Coriolis acceleration of the pin in "
                "the turning slot (with the factor 2)."
            )

    def slide_in_slot(
        self, b: StepBuilder, loop: Loop, unknowns: list[Unknown], order: int
    ) -> None:
        """s-dot (s-ddot) = u . v_rel (a_rel): the sliding unknown is the relative motion's
        component along the slot."""
        assert loop.slot is not None
        what, unit = MOTION[order]
        field_name = "relative_velocity" if order == VELOCITY else "relative_acceleration"
        rel = getattr(loop.slot, field_name)
        r = b.put(f"{what[0]}_rel({loop.joint})", rel, unit, loop.slot.source(field_name))
        direction = b.put("u", loop.slot.direction, "")
        slide = next(u for u in unknowns if u.key.startswith("s_"))
        b.check("dot", slide.key, r, direction)
        b.say(
            f"{slide.text} is the component along the slot of the relative "
            f"{what} of {loop.joint}: ",
            Num(Ref(r), unit=True),
            ".",
        )

    def joint_motion_step(self, loop: Loop, index: int, order: int) -> Step | None:
        """v (a) of the loop's joint as the sum of the left side's derivative terms."""
        if loop.kind == "slotted lever":
            return None
        ctx = self.ctx
        what, unit = MOTION[order]
        x = loop.joint
        b = ctx.builder(f"loop.{what}.point", f"{what.capitalize()} of {x} from loop {index}")
        left, _ = self.derivative_terms(Loop(loop.kind, loop.left, [], []), order, b)
        keys = [t.put(b, f"t{k + 1}", unit) for k, t in enumerate(left)]
        total = put_motion(b, ctx, x, order)
        b.check("sum", total, *keys)
        b.line(
            rf"&\vec{{{what[0]}}}_{{{tex.name(x)}}} = "
            + " + ".join(t.latex for t in left).replace("+ -", "- ")
        )
        b.line(
            r"&\phantom{\vec{v}} = ",
            SumOf(tuple(Complex(Ref(k)) for k in keys)),
            " = ",
            Boxed((Complex(Ref(total), whole=True), latex_unit(unit))),
        )
        b.say(
            f"The {what} of {x} is the derivative of the left side of the loop (the position "
            f"of {x}): ",
            *joined(" + ", [(Num(Ref(k), unit=True),) for k in keys]),
            " = ",
            Num(Ref(total), unit=True),
            " (x + i y).",
        )
        return b.build()

    def other_points(self) -> list[Step]:
        """Points of solved links not on a loop: X = B + b e^(i theta_BX) on a known link."""
        ctx = self.ctx
        on_loops = {
            p for loop in self.loops for m in loop.left + loop.right for p in (m.first, m.second)
        }
        out = []
        for order in (VELOCITY, ACCELERATION):
            links = [k for k in self.numbers if k in self.rotating or k in self.solved]
            for link in links:
                points = ctx.scene.links[link].points
                base = next((p for p in points if p in on_loops), points[0])
                for p in points:
                    if p in on_loops or ctx.is_fixed(p):
                        continue
                    out.append(self.point_step(link, base, p, order))
        return out

    def point_step(self, link: str, base: str, point: str, order: int) -> Step:
        """X = B + b e^(i theta) on a known link: v_X = v_B + i b omega e^(i theta), a_X too."""
        ctx = self.ctx
        what, _ = MOTION[order]
        b = ctx.builder(f"loop.{what}.point", f"{what.capitalize()} of {point} (link {link})")
        r_np = ctx.pos(point) - ctx.pos(base)
        r = b.put(f"r({base},{point})", r_np, "m")
        bl = b.put("b", float(np.hypot(*r_np)), "m")
        th = b.put("theta", math.atan2(r_np[1], r_np[0]), "rad")
        b.check("norm", bl, r)
        b.check("angle", th, r)
        w = b.put("omega", ctx.omega(link), "rad/s", ctx.link_source(link, "omega"))
        ends = (put_motion(b, ctx, base, order), put_motion(b, ctx, point, order))
        if order == VELOCITY:
            t = b.put(
                "i b omega e^(i theta)", ctx.omega(link) * np.array([-r_np[1], r_np[0]]), "m/s"
            )
            b.check("iphasor", t, bl, w, th)
            b.check("sum", ends[1], ends[0], t)
            self.point_velocity_lines(b, (link, base, point), ends, t)
        else:
            al = b.put("alpha", ctx.alpha(link), "rad/s^2", ctx.link_source(link, "alpha"))
            t = b.put(
                "i b alpha e^(i theta)", ctx.alpha(link) * np.array([-r_np[1], r_np[0]]), "m/s^2"
            )
            n = b.put("normal term", -(ctx.omega(link) ** 2) * r_np, "m/s^2")
            b.check("iphasor", t, bl, al, th)
            b.check("phasor", n, bl, w, w, th, factor=-1.0)
            b.check("sum", ends[1], ends[0], t, n)
            self.point_acceleration_lines(b, (link, base, point), ends, (t, n))
            if base == ctx.ground_pivot(link):  # a_X = a_X^t + a_X^n, as the vector method
                w2 = b.value(f"omega^2({link})", ctx.omega(link) ** 2, "1/s^2")
                b.check("product", w2, w, w)
                parts = (Ref(al), Ref(r), Ref(t), Ref(n), Ref(ends[1]), w2)
                write_turning_parts(b, (link, base, point), parts)
        return b.build()

    def point_velocity_lines(
        self, b: StepBuilder, where: tuple[str, str, str], ends: tuple[str, str], t: str
    ) -> None:
        """Write v_X = v_B + i b omega e^(i theta) with its numbers (``where``: link, B, X)."""
        link, base, point = where
        x0, x1 = ends
        sub = f"1{self.numbers[link]}"
        b.line(
            rf"&\vec{{v}}_{{{tex.name(point)}}} = \vec{{v}}_{{{tex.name(base)}}} + "
            rf"i\,b\,\omega_{{{sub}}}\,e^{{i\theta}}, \quad b = ",
            Num(Ref("b"), unit=True),
            r", \quad \theta = ",
            Degrees(Ref("theta")),
        )
        b.line(
            r"&\phantom{\vec{v}} = ",
            Complex(Ref(x0)),
            " + ",
            Complex(Ref(t)),
            " = ",
            Boxed((Complex(Ref(x1)), latex_unit("m/s"))),
        )
        b.say(
            f"{point} is fixed on link {link}: {point} = {base} + b e^(i theta) with b = ",
            Num(Ref("b"), unit=True),
            f"; differentiating, v({point}) = v({base}) + i b omega e^(i theta) = ",
            Num(Ref(x0), unit=True),
            " + ",
            Num(Ref(t), unit=True),
            " = ",
            Num(Ref(x1), unit=True),
            ".",
        )

    def point_acceleration_lines(
        self,
        b: StepBuilder,
        where: tuple[str, str, str],
        ends: tuple[str, str],
        parts: tuple[str, str],
    ) -> None:
        """Write a_X = a_B + i b alpha e^(i theta) - b omega^2 e^(i theta) with its numbers."""
        link, base, point = where
        (x0, x1), (t, n) = ends, parts
        sub = f"1{self.numbers[link]}"
        b.line(
            rf"&\vec{{a}}_{{{tex.name(point)}}} = \vec{{a}}_{{{tex.name(base)}}} + "
            rf"i\,b\,\alpha_{{{sub}}}\,e^{{i\theta}} - b\,\omega_{{{sub}}}^2\,e^{{i\theta}}"
        )
        b.line(
            r"&\phantom{\vec{a}} = ",
            Complex(Ref(x0)),
            " + ",
            Complex(Ref(t)),
            " + ",
            Complex(Ref(n)),
            " = ",
            Boxed((Complex(Ref(x1)), latex_unit("m/s^2"))),
        )
        b.say(
            f"Differentiating again: a({point}) = a({base}) + i b alpha e^(i theta) - b omega "
            "squared e^(i theta) = ",
            *joined(" + ", [(Num(Ref(k), unit=True),) for k in (x0, t, n)]),
            " = ",
            Num(Ref(x1), unit=True),
            ".",
        )

    def steps(self) -> list[Step]:
        self.analyse()
        out: list[Step] = []
        for i, loop in enumerate(self.loops, start=1):
            out.append(self.loop_step(loop, i))
            closed_form = {
                "slider-crank": self.closed_form_step,
                "four-bar": self.four_bar_closed_form_step,
                "slotted lever": self.lever_closed_form_step,
            }[loop.kind]
            out.append(closed_form(loop, i))
        for order in (VELOCITY, ACCELERATION):
            for i, loop in enumerate(self.loops, start=1):
                out.append(self.derivative_step(loop, i, order))
                point = self.joint_motion_step(loop, i, order)
                if point is not None:
                    out.append(point)
        out += self.other_points()
        # the poles are the same in both methods: P and G of every moving link
        out += [velocity_pole_step(self.ctx, link) for link in self.ctx.scene.moving_links]
        out += [acceleration_pole_step(self.ctx, link) for link in self.ctx.scene.moving_links]
        return out


def loop_steps(ctx: LinkageContext) -> list[Step]:
    """The loop-closure steps, or ``LoopUnavailable`` (why) for another topology."""
    return LoopMethod(ctx).steps()
