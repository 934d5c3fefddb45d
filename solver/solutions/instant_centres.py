"""Instant centres by Kennedy's theorem, step by step (kind ``instant_centres``).

The primary centres are read off the joints: a pin is the centre of the two links it joins; a
slider's centre is at infinity, perpendicular to its slot. Kennedy's theorem (the three centres of
three links lie on one line) then gives each other centre P_ij as the intersection of the lines
P_ik P_kj and P_im P_mj, solved as A + t d1 = B + s d2, t = ((B - A) x d2) / (d1 x d2). Each
centre found so is compared with the solver's (from the velocity fields), and the centre of a
link with the ground with that link's velocity pole.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import combinations, pairwise

import numpy as np

from solver.kinematics.rigid import cross, perp
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Equation, Frac, Num, Piece, Pt, Ref, Signed, joined
from solver.solutions.figures import Arrow, Dot, model_scale, scale_text, svg
from solver.solutions.format import latex_unit
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

Pair = frozenset[str]


class Kennedy:
    def __init__(self, ctx: LinkageContext) -> None:
        self.ctx = ctx
        self.links = list(ctx.scene.links)
        self.points: dict[Pair, np.ndarray] = {}
        self.directions: dict[Pair, np.ndarray] = {}  # centres at infinity
        self.loci: dict[Pair, tuple[np.ndarray, np.ndarray]] = {}  # a line the centre is on
        self.names = {name: str(i + 1) for i, name in enumerate(self.links)}
        self.kennedy_lines: list[tuple[Pair, Pair]] = []  # (from a known centre, to the found)

    def sym(self, pair: Pair) -> str:
        i, j = sorted(pair, key=self.links.index)
        return f"P_{{{self.names[i]}{self.names[j]}}}"

    def text(self, pair: Pair) -> str:
        i, j = sorted(pair, key=self.links.index)
        return f"P{self.names[i]}{self.names[j]}"

    def primary(self, b: StepBuilder) -> None:
        ctx = self.ctx
        rows: list[tuple[Piece, ...]] = []
        texts: list[tuple[Piece, ...]] = []
        legend = ", ".join(f"{n} = {name}" for name, n in self.names.items())
        b.say(f"Links numbered {legend}.")
        for joint in ctx.scene.joints:
            pair: Pair = frozenset(joint.links)
            if joint.type == "revolute":
                key = b.value(f"{self.text(pair)}", ctx.pos(joint.point), "m", None)
                self.points[pair] = ctx.pos(joint.point)
                rows.append((f"{self.sym(pair)} = {tex.name(joint.point)} = ", Pt(key)))
                texts.append((f"{self.text(pair)} = {joint.point} = ", Pt(key), " (pin)"))
                self.tie(b, pair, key, ctx.scene.size)
            elif joint.type == "slider":  # a pin in a slot: the centre is on the slot's normal
                normal = perp(ctx.slot_direction(joint))
                self.loci[pair] = (ctx.pos(joint.point), normal)
                texts.append(
                    (
                        f"{self.text(pair)} lies on the normal to the slot through "
                        f"{joint.point} (the pin turns and slides)",
                    )
                )
            else:
                direction = perp(ctx.slot_direction(joint))
                self.directions[pair] = direction
                key = b.value(f"{self.text(pair)} direction", direction, "")
                rows.append((rf"{self.sym(pair)} \text{{ at infinity along }} ", Pt(key)))
                texts.append(
                    (f"{self.text(pair)} at infinity, perpendicular to the slot at {joint.point}",)
                )
        for i in range(0, len(rows), 3):
            b.line("&", *joined(r", \quad ", rows[i : i + 3]), latex_unit("m"))
        b.say("Primary centres, from the joints: ", *joined("; ", texts), ".")

    def line(self, first: Pair, second: Pair) -> tuple[np.ndarray, np.ndarray] | None:
        """A point and a direction of the line through two known centres (one may be at
        infinity), or None when it is not determined."""
        p, q = self.points.get(first), self.points.get(second)
        if p is not None and q is not None:
            d = q - p
            return (p, d) if float(np.hypot(*d)) > 1e-12 * self.ctx.scene.size else None
        if p is not None and second in self.directions:
            return p, self.directions[second]
        if q is not None and first in self.directions:
            return q, self.directions[first]
        return None

    def secondary(self, b: StepBuilder) -> None:
        size = self.ctx.scene.size
        todo = [frozenset(c) for c in combinations(self.links, 2)]
        todo = [p for p in todo if p not in self.points and p not in self.directions]
        progress = True
        while todo and progress:
            progress = False
            for pair in list(todo):
                i, j = sorted(pair, key=self.links.index)
                lines: list[tuple[str, tuple[np.ndarray, np.ndarray]]] = []
                for k in (k for k in self.links if k not in pair):
                    line = self.line(frozenset((i, k)), frozenset((k, j)))
                    if line is not None:
                        lines.append((k, line))
                if pair in self.loci:
                    lines.append(("", self.loci[pair]))
                found = None
                for (k, first), (m, second) in combinations(lines, 2):
                    det = float(cross(first[1], second[1]))
                    scale = float(np.hypot(*first[1]) * np.hypot(*second[1]))
                    if abs(det) > 1e-9 * scale:
                        found = (k, m, first, second)
                        break
                if found is not None:
                    self.intersect(b, pair, *found, size)
                elif len(lines) >= 2:  # all the lines are parallel: the centre is at infinity
                    direction = lines[0][1][1] / float(np.hypot(*lines[0][1][1]))
                    self.directions[pair] = direction
                    key = b.value(f"{self.text(pair)} direction", direction, "")
                    b.line(rf"&{self.sym(pair)} \text{{ at infinity along }} ", Pt(key))
                    b.say(
                        f"{self.text(pair)} (links {i} and {j}): the lines Kennedy's theorem "
                        "puts it on are parallel, so it lies at infinity: the two links "
                        "translate relative to each other at this instant."
                    )
                else:
                    continue
                todo.remove(pair)
                progress = True
        if todo:
            b.say(
                "Not found by Kennedy's theorem from these lines (parallel or undetermined): "
                + ", ".join(self.text(p) for p in todo)
                + "."
            )

    def intersect(
        self,
        b: StepBuilder,
        pair: Pair,
        k: str,
        m: str,
        first: tuple[np.ndarray, np.ndarray],
        second: tuple[np.ndarray, np.ndarray],
        size: float,
    ) -> None:
        i, j = sorted(pair, key=self.links.index)
        name = self.text(pair)
        (a, d1), (c, d2) = first, second
        ak = b.value(f"{name}: A", a, "m")
        d1k = b.value(f"{name}: d1", d1, "m")
        ck = b.value(f"{name}: B", c, "m")
        d2k = b.value(f"{name}: d2", d2, "m")
        w = b.value(f"{name}: B-A", c - a, "m")
        det = b.value(f"{name}: d1 x d2", float(cross(d1, d2)), "m^2")
        num = b.value(
            f"{name}: (B-A) x d2",
            float(cross(c - a, d2)),
            "m^2",
            reference=float(np.hypot(*(c - a)) * np.hypot(*d2)),
        )
        t = b.value(f"{name}: t", float(cross(c - a, d2)) / float(cross(d1, d2)), "")
        step = b.value(f"{name}: t d1", b.scalar(t) * d1, "m")
        point = a + b.scalar(t) * d1
        pk = b.value(name, point, "m")
        b.check("sum", w, ck, -ak)
        b.check("cross", det, d1k, d2k)
        b.check("cross", num, w, d2k)
        b.check("quotient", t, num, det)
        b.check("product", step, t, d1k)
        b.check("sum", pk, ak, step)
        self.points[pair] = point
        for other in (k, m):
            if other:
                self.kennedy_lines.append((frozenset((i, other)), pair))
        first_tex, first_text = self.through(i, k, j)
        second_tex, second_text = self.through(i, m, j)
        parameter = Equation.of("t", Frac(num, det), Num(t))
        b.line(
            rf"&{self.sym(pair)}: \; {first_tex} \cap {second_tex}: \; ",
            parameter,
            rf", \; {self.sym(pair)} = ",
            Pt(ak),
            " ",
            Signed(t),
            r"\,",
            Pt(d1k),
            " = ",
            Boxed((Pt(pk, "m"),)),
        )
        b.say(
            f"{name} (links {i} and {j}) lies on {first_text} and on {second_text}; their "
            "intersection, ",
            parameter,
            f", is {name} = ",
            Pt(pk),
            ".",
        )
        self.tie(b, pair, pk, size)

    def through(self, i: str, k: str, j: str) -> tuple[str, str]:
        """The line a centre P_ij is on: P_ik P_kj by Kennedy (links i, k, j), or, with k = '',
        the normal to the slot of the pin joining i and j."""
        if not k:
            pair = self.text(frozenset((i, j)))
            return r"n_{\text{slot}}", f"the normal to the slot (the locus of {pair})"
        ik, kj = frozenset((i, k)), frozenset((k, j))
        return (
            self.sym(ik) + self.sym(kj),
            f"the line {self.text(ik)}{self.text(kj)} (Kennedy, links {i}, {k}, {j})",
        )

    def tie(self, b: StepBuilder, pair: Pair, key: Ref, size: float) -> None:
        """The centre equals the solver's (velocity fields) and, with the ground, the pole."""
        ctx = self.ctx
        for index, centre in enumerate(ctx.analysis.instant_centres):
            if frozenset(centre.links) != pair or centre.position is None:
                continue
            solver = b.value(
                f"{self.text(pair)} (solver)",
                centre.position,
                "m",
                ("instant_centres", index, "position"),
            )
            b.check("sum", key, solver)
        ground = ctx.scene.ground
        if ground in pair:
            link = next(x for x in pair if x != ground)
            pole = ctx.analysis.links[link].velocity_pole
            if pole is not None:
                pk = b.value(f"P({link})", pole, "m", ("links", link, "velocity_pole"))
                b.check("sum", key, pk)
                b.say(
                    f"It is the velocity pole of link {link} found analytically from "
                    f"v = omega x r: P({link}) = ",
                    Pt(pk),
                    ".",
                )


FAR = 10.0  # scene sizes: a centre farther from the mechanism is not drawn


def figure(kennedy: Kennedy) -> str:
    """The mechanism with its instant centres and the Kennedy lines that found them."""
    ctx = kennedy.ctx
    positions = [ctx.pos(p) for p in ctx.scene.points]
    middle = np.mean(positions, axis=0)
    near = {
        pair: at
        for pair, at in kennedy.points.items()
        if float(np.hypot(*(at - middle))) <= FAR * ctx.scene.size
    }
    per_mm = model_scale(positions + list(near.values()))
    segments = []
    for link in ctx.scene.moving_links:
        points = ctx.scene.links[link].points
        segments += [(ctx.pos(a), ctx.pos(c), "link") for a, c in pairwise(points)]
    arrows = [
        Arrow(
            near[start],
            near[end],
            f"ic({','.join(sorted(end))})-ic({','.join(sorted(start))})",
            "",
            "position",
        )
        for start, end in kennedy.kennedy_lines
        if start in near and end in near and not np.allclose(near[start], near[end])
    ]
    dots = [Dot(at, kennedy.text(pair)) for pair, at in near.items()]
    k = per_mm * 10.0
    return svg(
        "Instant centres",
        arrows,
        dots,
        segments,
        per_mm,
        f"Instant centres and Kennedy lines, {scale_text(k, 'm')}",
        {"data-kind": "instant_centres", "data-scale": repr(k), "data-unit": "m"},
    )


def instant_centres_step(ctx: LinkageContext) -> Step:
    """All instant centres of the linkage: primary from the joints, the rest by Kennedy."""
    b = ctx.builder("instant_centres", "Instant centres (Kennedy's theorem)")
    kennedy = Kennedy(ctx)
    kennedy.primary(b)
    kennedy.secondary(b)
    return replace(b.build(), figure=figure(kennedy))
