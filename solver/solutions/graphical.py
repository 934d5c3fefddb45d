"""The graphical method: the mechanism to scale, the velocity and acceleration polygons.

``graphical.velocity``: from the pole p, the image of every moving point is drawn at the scale
k_v (1 cm = k_v m/s); for each link, the image of its first point and the relative velocity
v_Y - v_X = omega x r_XY, perpendicular to XY, lead to the image of every other point. The
lengths read off the drawing are |v| / k_v. Mehmke's theorem is the check: the image of a link is
similar to the link (ratio |omega|, turned by 90 degrees), so the image of a third point follows
from two. ``graphical.acceleration``: the same with the normal part -omega^2 r_XY (parallel to
XY, towards X) and the tangential part alpha x r_XY, and at a slot the transport, Coriolis and
relative parts. The figures are built from the solver's numbers (``figures.svg``).
"""

from __future__ import annotations

import math

import numpy as np

from solver.kinematics.rigid import omega_cross
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Equation, Frac, Num, Piece, Ref, joined
from solver.solutions.figures import (
    SHORTEST,
    Arrow,
    Dot,
    Groove,
    Slider,
    figure_name,
    model_scale,
    polygon_scale,
    scale_text,
    svg,
)
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

READING = 0.05  # cm: what a careful drawing is read to (half a millimetre)


COMPONENT = {
    "normal": "normal omega^2 r",
    "tangential": "tangential alpha r",
    "transport": "transport",
    "coriolis": "Coriolis",
    "relative": "relative",
}  # the parts of an acceleration polygon, by their arrows' style
COMPONENT_LATEX = {
    "normal": r"\omega^2 r_{{{}}}",
    "tangential": r"\alpha\, r_{{{}}}",
    "transport": r"a_{{{},\mathrm{{tr}}}}",
    "coriolis": r"a_{{{},\mathrm{{Cor}}}}",
    "relative": r"a_{{{},\mathrm{{rel}}}}",
}


def undrawn(size: float, scale: float) -> bool:
    """True for a vector of length ``size`` that the figure at 1 cm = ``scale`` does not draw:
    shorter than ``SHORTEST`` mm on paper (a subnormal rate's image, 1e-311 cm): it has no
    length to read off and no reading error."""
    return 10.0 * size / scale < SHORTEST


def link_pairs(ctx: LinkageContext) -> list[tuple[str, str, str]]:
    """(link, X, Y) for every moving link and every point Y of it after its first point X."""
    out = []
    for link in ctx.scene.moving_links:
        points = ctx.scene.links[link].points
        out += [(link, points[0], y) for y in points[1:]]
    return out


def slot_points(ctx: LinkageContext) -> list[tuple[str, str]]:
    """(guide, point) of every point in a slot."""
    return [(j.guide, j.point) for j in ctx.scene.joints if j.type != "revolute"]


def sliders(ctx: LinkageContext) -> list[Slider]:
    """Every sliding joint's block on its guide as it lies now (the slot's direction turned with
    the guide)."""
    return [
        Slider(j.point, ctx.pos(j.point), ctx.slot_direction(j), j.guide == ctx.scene.ground)
        for j in ctx.scene.joints
        if j.type != "revolute"
    ]


def grooves(ctx: LinkageContext) -> list[Groove]:
    """Every moving point's path in its carrier as it lies now: an arc about its centre from its
    start through its sweep, in a disc about that centre reaching past the carrier's points; or a
    line from its start through the point it passes, reaching the moving point."""
    out = []
    for mp in ctx.scene.moving_points:
        start = ctx.pos(mp.path.start)
        m = np.asarray(ctx.analysis.moving_points[mp.name].position)
        if mp.path.center is None:
            assert mp.path.through is not None
            through = ctx.pos(mp.path.through)
            u = (through - start) / float(np.hypot(*(through - start)))
            reach = max(float(np.hypot(*(through - start))), float(u @ (m - start)))
            out.append(Groove(mp.name, None, 0.0, 0.0, 0.0, start, start + reach * u))
            continue
        centre = ctx.pos(mp.path.center)
        radius = float(np.hypot(*(start - centre)))
        sweep = math.radians(mp.path.sweep_deg) * (1.0 if mp.path.direction == "ccw" else -1.0)
        carrier = [ctx.pos(p) for p in ctx.scene.links[mp.link].points]
        disc = 1.15 * max([radius, *(float(np.hypot(*(p - centre))) for p in carrier)])
        angle = math.atan2(*(start - centre)[::-1])
        out.append(Groove(mp.name, centre, radius, angle, sweep, start, start, disc))
    return out


def mechanism_figure(ctx: LinkageContext) -> str:
    """The mechanism at the analysed instant, to scale, with the position vectors of the steps:
    the links, every slider's block on its guide, every moving point's groove in its carrier
    and the point itself."""
    positions = [ctx.pos(p) for p in ctx.scene.points]
    per_mm = model_scale(positions)
    fixed = set(ctx.scene.links[ctx.scene.ground].points)
    segments = []
    for link in ctx.scene.moving_links:
        points = ctx.scene.links[link].points
        for a, b in zip(points, points[1:] + points[:1], strict=True):
            if a != b and not (len(points) == 2 and a == points[1]):
                segments.append((ctx.pos(a), ctx.pos(b), "link"))
    arrows = [
        Arrow(ctx.pos(a), ctx.pos(b), f"r({a},{b})", "", "position")
        for a, b in ctx.used_vectors
        if not np.allclose(ctx.pos(a), ctx.pos(b))
    ]
    dots = [Dot(ctx.pos(p), p, p in fixed) for p in ctx.scene.points]
    dots += [Dot(np.asarray(m.position), name) for name, m in ctx.analysis.moving_points.items()]
    k = per_mm * 10.0
    return svg(
        "The mechanism at the analysed instant",
        arrows,
        dots,
        segments,
        per_mm,
        f"Mechanism, {scale_text(k, 'm')}",
        {"data-kind": "mechanism", "data-scale": repr(k), "data-unit": "m"},
        sliders(ctx),
        grooves(ctx),
    )


class Polygons:
    def __init__(self, ctx: LinkageContext) -> None:
        self.ctx = ctx
        self.moving = [
            p for p in ctx.scene.points if p not in ctx.scene.links[ctx.scene.ground].points
        ]

    def velocity(self) -> Step:
        """The velocity polygon from the pole p at the scale k_v: for each link the image of
        v_Y = v_X + omega x r_XY, for a slot v = v_tr + v_rel."""
        ctx = self.ctx
        moving = {p: ctx.vel(p) for p in self.moving}
        extra = {name: np.asarray(m.velocity) for name, m in ctx.analysis.moving_points.items()}
        k = polygon_scale([*moving.values(), *extra.values()])
        b = ctx.builder("graphical.velocity", "Velocity polygon (graphical method)")
        kv = b.value("k_v", k, "m/s")
        b.say(
            f"Scale k_v: {scale_text(k, 'm/s')}. From the pole p (all fixed points have their "
            "image at p) the construction runs link by link:"
        )
        arrows, order = self.velocity_arrows(moving)
        b.say("; ".join(order) + ".")
        velocities = {**moving, **extra}
        self.lengths(b, kv, velocities, "v", "m/s")
        self.mehmke(b, "v")
        caption = f"Velocity polygon, {scale_text(k, 'm/s')}"
        return _with_figure(b.build(), _polygon("Velocity polygon", arrows, velocities, k, caption))

    def velocity_arrows(self, moving: dict[str, np.ndarray]) -> tuple[list[Arrow], list[str]]:
        """The relative velocities v_Y - v_X of each link and the transport and relative parts
        at a slot or of a moving point, with the order of the construction in words."""
        ctx = self.ctx
        arrows: list[Arrow] = []
        order = []
        for link, x, y in link_pairs(ctx):
            vx = moving.get(x, np.zeros(2))
            vy = moving.get(y, np.zeros(2))
            if float(np.hypot(*(vy - vx))) > 0:
                label = figure_name(y.lower()) + figure_name(x.lower())
                arrows.append(Arrow(vx, vy, f"v({y})-v({x})", label, "relative"))
            order.append(
                f"through {x.lower()} (the image of {x}) the direction perpendicular to {x}{y} "
                f"(link {link}) gives {y.lower()}"
            )
        for guide, point in slot_points(ctx):
            slot = ctx.slot(guide, point)
            if guide != ctx.scene.ground:
                transport = Arrow(
                    np.zeros(2), slot.transport_velocity, f"v_tr({point})", "", "transport"
                )
                arrows.append(transport)
            arrows.append(
                Arrow(slot.transport_velocity, slot.velocity, f"v_rel({point})", "", "relative")
            )
            order.append(
                f"{point} in the slot of {guide}: the transport velocity, then the relative "
                "velocity along the slot"
            )
        for name, m in ctx.analysis.moving_points.items():
            v_tr, v = np.asarray(m.transport_velocity), np.asarray(m.velocity)
            arrows.append(Arrow(np.zeros(2), v_tr, f"v_tr({name})", "", "transport"))
            arrows.append(Arrow(v_tr, v, f"v_rel({name})", "", "relative"))
        return arrows, order

    def acceleration(self) -> Step:
        """The acceleration polygon from the pole p' at the scale k_a: for each link the normal
        part -omega^2 r_XY and the tangential part alpha x r_XY, for a slot a = a_tr + a_cor +
        a_rel."""
        ctx = self.ctx
        accelerations = {p: ctx.acc(p) for p in self.moving}
        for name, m in ctx.analysis.moving_points.items():
            accelerations[name] = np.asarray(m.acceleration)
        k = polygon_scale(list(accelerations.values()))
        b = ctx.builder("graphical.acceleration", "Acceleration polygon (graphical method)")
        ka = b.value("k_a", k, "m/s^2")
        b.say(
            f"Scale k_a: {scale_text(k, 'm/s^2')}. From the pole p' link by link: from the "
            "image of the first point, the normal part -omega^2 r (parallel to the link, towards "
            "that point), then the tangential part alpha x r (perpendicular to the link) lead to "
            "the image of the next point; at a slot, the transport, Coriolis and relative parts."
        )
        arrows = self.link_acceleration_arrows(accelerations) + self.slot_acceleration_arrows()
        self.component_lengths(b, ka, arrows)
        self.lengths(b, ka, accelerations, "a", "m/s^2")
        self.mehmke(b, "a")
        caption = (
            f"Acceleration polygon, {scale_text(k, 'm/s^2')}; n normal, t tangential, "
            "tr transport, Cor Coriolis, rel relative"
        )
        figure = _polygon("Acceleration polygon", arrows, accelerations, k, caption)
        return _with_figure(b.build(), figure)

    def link_acceleration_arrows(self, accelerations: dict[str, np.ndarray]) -> list[Arrow]:
        """a_Y = a_X + (-omega^2 r_XY) + alpha x r_XY: the normal then the tangential part."""
        ctx = self.ctx
        arrows: list[Arrow] = []
        for link, x, y in link_pairs(ctx):
            r = ctx.pos(y) - ctx.pos(x)
            ax = accelerations.get(x, np.zeros(2))
            pair = figure_name(y) + figure_name(x)
            normal = -(ctx.omega(link) ** 2) * r
            tangential = omega_cross(ctx.alpha(link), r)
            if float(np.hypot(*normal)) > 0:
                arrows.append(Arrow(ax, ax + normal, f"an({link}:{x},{y})", f"n {pair}", "normal"))
            if float(np.hypot(*tangential)) > 0:
                end = ax + normal + tangential
                name = f"at({link}:{x},{y})"
                arrows.append(Arrow(ax + normal, end, name, f"t {pair}", "tangential"))
        return arrows

    def slot_acceleration_arrows(self) -> list[Arrow]:
        """a = a_tr + a_cor + a_rel at every slot and of every moving point, from the pole."""
        ctx = self.ctx
        parts: list[tuple[str, np.ndarray, np.ndarray, np.ndarray]] = []
        for guide, point in slot_points(ctx):
            slot = ctx.slot(guide, point)
            tr, cor = slot.transport_acceleration, slot.coriolis_acceleration
            assert tr is not None and cor is not None
            parts.append((point, tr, cor, ctx.acc(point)))
        for name, m in ctx.analysis.moving_points.items():
            tr, cor = np.asarray(m.transport_acceleration), np.asarray(m.coriolis_acceleration)
            parts.append((name, tr, cor, np.asarray(m.acceleration)))
        arrows: list[Arrow] = []
        for point, tr, cor, total in parts:
            if float(np.hypot(*tr)) > 0:
                arrows.append(Arrow(np.zeros(2), tr, f"a_tr({point})", "tr", "transport"))
            if float(np.hypot(*cor)) > 0:
                arrows.append(Arrow(tr, tr + cor, f"a_cor({point})", "Cor", "coriolis"))
            arrows.append(Arrow(tr + cor, total, f"a_rel({point})", "rel", "relative"))
        return arrows

    def component_lengths(self, b: StepBuilder, scale: Ref, arrows: list[Arrow]) -> None:
        """|component| / k_a = its length on paper, for every part drawn (normal omega^2 r,
        tangential alpha r, transport, Coriolis, relative), in the order it is drawn, so a
        student can check the drawing step by step."""
        rows: list[tuple[Piece, ...]] = []
        texts: list[tuple[Piece, ...]] = []
        for arrow in arrows:
            size = float(np.hypot(*(arrow.end - arrow.start)))
            if b.fmt.is_zero(size, "m/s^2") or undrawn(size, b.scalar(scale)):
                continue
            norm = b.value(f"|{arrow.name}|", size, "m/s^2")
            length = b.value(f"length {arrow.name}", size / b.scalar(scale), "cm")
            b.check("quotient", length, norm, scale)
            inside = arrow.name.partition("(")[2].rstrip(")")  # 'link:X,Y' or a slot's point
            ends = inside.partition(":")[2].split(",") if ":" in inside else []
            if ends:  # r_YX, from X to Y
                what = f"{COMPONENT[arrow.style]} {ends[1]}{ends[0]}"
                sub = tex.pair(ends[1], ends[0])
            else:
                what, sub = f"{COMPONENT[arrow.style]} of {inside}", tex.name(inside)
            rows.append(
                (
                    COMPONENT_LATEX[arrow.style].format(sub) + " = ",
                    Num(norm, unit=True),
                    r" \to ",
                    Equation.of(Frac(norm, scale), Num(length, unit=True)),
                )
            )
            texts.append((f"{what} ", Num(norm, unit=True), ", drawn ", Num(length, unit=True)))
        for i in range(0, len(rows), 2):
            b.line("&", *joined(r", \quad ", rows[i : i + 2]))
        if texts:
            b.say("The parts at the scale, in the order drawn: ", *joined("; ", texts), ".")

    def lengths(
        self, b: StepBuilder, scale: Ref, vectors: dict[str, np.ndarray], letter: str, unit: str
    ) -> None:
        """|v| / k_v = length on paper, for every image (and the reading error of the shortest)."""
        rows: list[tuple[Piece, ...]] = []
        texts: list[tuple[Piece, ...]] = []
        shortest: Ref | None = None
        for p, v in vectors.items():
            size = float(np.hypot(*v))
            if size == 0.0 or b.fmt.is_zero(size, unit) or undrawn(size, b.scalar(scale)):
                continue
            src = ("moving_points", p, "velocity" if letter == "v" else "acceleration")
            if p in self.ctx.scene.points:
                src = ("points", p, "velocity" if letter == "v" else "acceleration")
            key = b.value(f"{letter}({p})", v, unit, src)
            norm = b.value(f"|{letter}({p})|", size, unit)
            length = b.value(f"length {letter}({p})", size / b.scalar(scale), "cm")
            b.check("norm", norm, key)
            b.check("quotient", length, norm, scale)
            sym = tex.vec(letter, tex.name(p))
            rows.append(
                (
                    f"|{sym}| = ",
                    Num(norm, unit=True),
                    r" \to ",
                    Equation.of(Frac(norm, scale), Num(length, unit=True)),
                )
            )
            texts.append(
                (f"|{letter}({p})| = ", Num(norm, unit=True), ", drawn ", Num(length, unit=True))
            )
            if shortest is None or b.scalar(length) < b.scalar(shortest):
                shortest = length
        for i in range(0, len(rows), 2):
            b.line("&", *joined(r", \quad ", rows[i : i + 2]))
        if texts:
            b.say("Lengths at the scale: ", *joined("; ", texts), ".")
        if shortest is not None:
            reading = b.value("reading", READING, "cm")
            error = b.value("relative error", READING / b.scalar(shortest), "")
            b.check("quotient", error, reading, shortest)
            b.line(
                r"&\text{read to } ",
                Num(reading, unit=True),
                r": \; ",
                Equation.of(Frac(reading, shortest), Num(error)),
                r" \text{ relative error on the shortest image}",
            )
            b.say(
                "A careful drawing is read to ",
                Num(reading, unit=True),
                ": on the shortest image (",
                Num(shortest, unit=True),
                ") that is a relative error of ",
                Num(error, unit=True),
                ".",
            )

    def mehmke(self, b: StepBuilder, letter: str) -> None:
        """The image of a link is similar to the link (Mehmke): check on links of 3+ points."""
        ctx = self.ctx
        for link in ctx.scene.moving_links:
            points = ctx.scene.links[link].points
            if len(points) < 3:
                continue
            x, y, z = points[:3]
            omega, alpha = ctx.omega(link), ctx.alpha(link)
            motion = ctx.vel if letter == "v" else ctx.acc
            unit = "m/s" if letter == "v" else "m/s^2"
            for first, second in ((x, y), (x, z)):
                r = ctx.pos(second) - ctx.pos(first)
                diff = b.value(
                    f"{letter}({second})-{letter}({first})", motion(second) - motion(first), unit
                )
                rk = b.value(f"r({first},{second}) in {link}", r, "m")
                if letter == "v":
                    w = b.value(f"omega({link})", omega, "rad/s", ("links", link, "omega"))
                    b.check("cross", diff, w, rk)
                else:
                    al = b.value(f"alpha({link})", alpha, "rad/s^2", ("links", link, "alpha"))
                    t = b.value(f"alpha x r({first},{second})", omega_cross(alpha, r), unit)
                    n = b.value(f"normal({first},{second})", -(omega**2) * r, unit)
                    b.check("cross", t, al, rk)
                    b.check("sum", diff, t, n)
            image = r"\,".join(tex.name(p.lower()) for p in (x, y, z))
            ratio = abs(omega) if letter == "v" else math.sqrt(omega**4 + alpha**2)
            factor = b.value(f"ratio({link})", ratio, "1/s" if letter == "v" else "1/s^2")
            what = "|omega|" if letter == "v" else "sqrt(omega^4 + alpha^2)"
            b.line(
                rf"&\text{{Mehmke: the image }} {image} \text{{ of link "
                rf"{tex.escape_text(link)} is similar to }} {tex.name(x)}{tex.name(y)}{tex.name(z)}"
                r"\text{, ratio } ",
                Num(factor, unit=True),
            )
            b.say(
                f"Mehmke's check: the image {x.lower()}{y.lower()}{z.lower()} of link {link} is "
                f"similar to the triangle {x}{y}{z}, every side times {what} = ",
                Num(factor, unit=True),
                f"; so the image of the third point {z} follows from those of {x} and {y}.",
            )


def _polygon(
    title: str, arrows: list[Arrow], images: dict[str, np.ndarray], k: float, caption: str
) -> str:
    """The polygon's figure at 1 cm = k: the absolute vectors from the pole first (p for the
    velocities, p' for the accelerations), then ``arrows``, and a dot at every image."""
    velocity = title.startswith("Velocity")
    letter, prime = ("v", "") if velocity else ("a", "'")
    drawn = [(p, v) for p, v in images.items() if float(np.hypot(*v)) > 0]
    absolute = [Arrow(np.zeros(2), v, f"{letter}({p})", "", "absolute") for p, v in drawn]
    dots = [Dot(np.zeros(2), "p" + prime)]
    dots += [Dot(v, figure_name(p.lower()) + prime) for p, v in drawn]
    kind, unit = ("velocity", "m/s") if velocity else ("acceleration", "m/s^2")
    attributes = {"data-kind": kind, "data-scale": repr(k), "data-unit": unit}
    return svg(title, absolute[::-1] + arrows, dots, [], k / 10.0, caption, attributes)


def _with_figure(step: Step, figure: str) -> Step:
    return Step(step.kind, step.title, step.latex, step.text, step.values, step.checks, figure)


def graphical_steps(ctx: LinkageContext) -> list[Step]:
    """The velocity and acceleration polygons, drawn and read at their scales."""
    polygons = Polygons(ctx)
    return [polygons.velocity(), polygons.acceleration()]
