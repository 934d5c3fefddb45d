"""The worked solution of a gear train (docs/GEARS.md): the tabular (Willis) method written out,
and the formula method beside it (Shigley/Uicker ch. 13, Rattan ch. 10).

Seen from its carrier (the arm), a planetary stage is an ordinary train: with the arm locked,
turning the reference gear (F, usually the sun) x rad/s turns every gear i of the stage by
e_i x, e_i the product of the tooth ratios -N_a/N_b (external mesh) and +N_a/N_b (internal)
from F to i. Turning the whole stage with the arm adds y = omega_arm to every member. The sum is
the absolute motion, omega_i = e_i x + y; two known members (an input, a fixed ring, a shaft
keyed to a member already found) give x and y. The formula method is the same relation between
two gears, e = (omega_L - omega_arm) / (omega_F - omega_arm). Gears on axes fixed in the frame
form ordinary (simple or compound) trains, omega_i = e_i omega_F. Stages are solved in the
order their known members allow; every number shown is the solver's (``solver.gears``), and the
steps' checks state the arithmetic between them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import numpy as np

from solver.errors import KinematicsError
from solver.gears import GearTrainScene, analyze_gear_train, exact, willis_relation
from solver.gears.train import relations
from solver.solutions import latex as tex
from solver.solutions.builder import Source, StepBuilder, Unknown, present_solution
from solver.solutions.equation import (
    CDOT,
    Alt,
    Boxed,
    Equation,
    Frac,
    Num,
    Paren,
    Piece,
    Ref,
    Signed,
    Sym,
    joined,
    latex_only,
)
from solver.solutions.figures import model_scale, paper_document, scale_text
from solver.solutions.format import Formatter
from solver.solutions.model import Mistake, Solution, Step, Value
from solver.teaching.mistakes import rings_as_external, typical_mistake
from solver.teaching.svg import Canvas, View

CONVENTION = (
    "Angular velocities are absolute (relative to the frame), counter-clockwise positive seen "
    "from the front, in rad/s. An external mesh turns its gears opposite ways (ratio -N_a/N_b), "
    "an internal mesh (an annulus and its pinion) the same way (+N_a/N_b)."
)


@dataclass(frozen=True)
class Link:
    """One edge of a path through a stage: from gear ``start`` to gear ``end`` by a mesh
    (``internal`` as the mesh is), or keyed on one shaft (``mesh`` False: ratio 1)."""

    start: str
    end: str
    mesh: bool
    internal: bool = False


@dataclass(frozen=True)
class Stage:
    """The gears whose meshes one body holds (``carrier``; None: the frame), connected by those
    meshes and by shafts: seen from that body an ordinary train. ``reference`` is the gear F
    turned with the body locked; ``paths`` the links from F to each other gear."""

    carrier: str | None
    reference: str
    gears: tuple[str, ...]
    paths: Mapping[str, tuple[Link, ...]]

    @property
    def members(self) -> tuple[str, ...]:
        return self.gears + ((self.carrier,) if self.carrier is not None else ())

    def ratio(self, scene: GearTrainScene, gear: str) -> Fraction:
        """e_i = (omega_i - omega_arm) / (omega_F - omega_arm): the product of the tooth
        ratios along the path (``willis_relation``)."""
        out = Fraction(1)
        for link in self.paths[gear]:
            if link.mesh:
                a, b = scene.gear(link.start), scene.gear(link.end)
                out *= willis_relation(a.teeth, b.teeth, link.internal)
        return out


def _edges(scene: GearTrainScene, carrier: str | None) -> dict[str, list[Link]]:
    """The links between the gears meshing in ``carrier``'s frame: its meshes both ways, and
    gears of one shaft among them."""
    edges: dict[str, list[Link]] = {}
    for mesh in scene.meshes:
        if mesh.carrier == carrier:
            a, b = mesh.gears
            edges.setdefault(a, []).append(Link(a, b, True, mesh.internal))
            edges.setdefault(b, []).append(Link(b, a, True, mesh.internal))
    for shaft in scene.shafts:
        keyed = [m for m in shaft if m in edges]
        for a in keyed:
            edges[a] += [Link(a, b, False) for b in keyed if b != a]
    return edges


def _paths(edges: Mapping[str, list[Link]], start: str) -> dict[str, tuple[Link, ...]]:
    """The shortest path of links from ``start`` to every gear it reaches (breadth first)."""
    paths: dict[str, tuple[Link, ...]] = {start: ()}
    queue = [start]
    while queue:
        name = queue.pop(0)
        for link in edges[name]:
            if link.end not in paths:
                paths[link.end] = (*paths[name], link)
                queue.append(link.end)
    return paths


def stages(scene: GearTrainScene, known: set[str]) -> list[Stage]:
    """Every stage, its reference F a known gear where one is (else its first gear on the
    frame's axes, the sun, else its first gear)."""
    out = []
    order = [g.name for g in scene.gears]
    for carrier in (None, *scene.carriers):
        edges = _edges(scene, carrier)
        seen: set[str] = set()
        for start in (g for g in order if g in edges):
            if start in seen:
                continue
            group = sorted(_paths(edges, start), key=order.index)
            seen.update(group)
            fixed = [g for g in group if scene.mount(g) is None]
            reference = next((g for g in fixed + group if g in known), (fixed or group)[0])
            out.append(Stage(carrier, reference, tuple(group), _paths(edges, reference)))
    return out


# --- the solution -------------------------------------------------------------------------------


class GearContext:
    """The scene, the solver's /analyze body and the formatter the steps share."""

    def __init__(self, scene: GearTrainScene, digits: int) -> None:
        self.scene = scene
        self.body: Mapping[str, Any] = analyze_gear_train(scene).as_dict()
        self.fmt = Formatter(digits)

    def omega(self, name: str) -> float:
        value: float = self.body["members"][name]["omega"]
        return value

    def builder(self, kind: str, title: str) -> StepBuilder:
        return StepBuilder(self.fmt, kind, title)


def _quotient(numerator: Ref, denominator: Ref) -> Alt:
    """numerator / denominator: a fraction in LaTeX, 'a/b' in text (a negative denominator
    without parentheses, as these steps have always written it)."""
    return Alt((Frac(numerator, denominator),), (Num(numerator), "/", Num(denominator)))


def _w(name: str) -> Sym:
    """omega of a member: \\omega_{sun} and 'omega_sun'."""
    return Sym(rf"\omega_{{{tex.name(name)}}}", f"omega_{name}")


def _teeth(b: StepBuilder, scene: GearTrainScene, name: str) -> Ref:
    return b.value(f"N({name})", float(scene.gear(name).teeth), "", ("members", name, "teeth"))


def _speed(b: StepBuilder, ctx: GearContext, name: str) -> Ref:
    return b.value(f"omega({name})", ctx.omega(name), "rad/s", ("members", name, "omega"))


def data_step(ctx: GearContext) -> Step:
    """The train: its gears, carriers, meshes and inputs, the sign convention and the figure."""
    scene = ctx.scene
    b = ctx.builder("gears.data", scene.title or "The gear train")
    rows: list[tuple[Piece, ...]] = []
    for gear in scene.gears:
        n = _teeth(b, scene, gear.name)
        axis = f"on {gear.carrier}" if gear.carrier else "fixed in the frame"
        kind = "internal (annulus)" if gear.internal else "external"
        row = (
            Sym(rf"\text{{{tex.escape_text(gear.name)}}} & N = ", f"Gear {gear.name}: "),
            Num(n),
            Sym(
                rf" & \text{{{kind}, axis {tex.escape_text(axis)}}}",
                f" teeth, {kind}, its axis {axis}.",
            ),
        )
        rows.append(row)
        b.say(*row)
    b.line(r"&\begin{array}{lll} ", *joined(r" \\ ", rows), r" \end{array}")
    for carrier in scene.carriers:
        held = [g.name for g in scene.gears if g.carrier == carrier]
        b.say(f"Carrier (arm) {carrier} turns about the frame, holding {', '.join(held)}.")
    for shaft in scene.shafts:
        b.say(f"Keyed to one shaft (turning as one): {', '.join(shaft)}.")
    meshes = "; ".join(
        f"{m.gears[0]}-{m.gears[1]} ({'internal' if m.internal else 'external'})"
        for m in scene.meshes
    )
    b.say(f"Meshes: {meshes}.")
    given = []
    for name, _ in scene.inputs:
        speed = Equation.of(_w(name), Num(_speed(b, ctx, name), unit=True))
        given.append((speed,))
        b.say("Given: ", speed, " (fixed)." if ctx.omega(name) == 0 else ".")
    b.line("&", *joined(r",\quad ", given))
    b.say(CONVENTION)
    step = b.build()
    return replace(step, figure=train_figure(scene))


def freedom_step(ctx: GearContext) -> Step:
    """f = n - r: the members less the independent relations (meshes and shafts)."""
    scene = ctx.scene
    members = len(scene.members)
    rank = exact.rank(relations(scene), members)
    b = ctx.builder("gears.freedom", "Degrees of freedom")
    n = b.value("n", float(members), "")
    r = b.value("r", float(rank), "")
    f = b.value("f", float(ctx.body["degrees_of_freedom"]), "", ("degrees_of_freedom",))
    b.check("sum", f, n, -r)
    freedom = Equation.of("f", "n - r", latex_only(Num(n), " - ", Num(r)), Num(f))
    b.line(freedom)
    b.say(
        "Each mesh gives one Willis relation and each keyed member one equality; of these, ",
        Num(r),
        " are independent, so the ",
        Num(n),
        " members (gears and carriers) have ",
        freedom,
        f" degree{'s' if members - rank != 1 else ''} of freedom, fixed by the "
        f"{len(scene.inputs)} given speed{'s' if len(scene.inputs) != 1 else ''}.",
    )
    return b.build()


def _ratio_pieces(
    b: StepBuilder, scene: GearTrainScene, link: Link
) -> tuple[Ref, tuple[Piece, ...]]:
    """The oriented ratio of a mesh, r = -N_a/N_b (external) or +N_a/N_b (internal), registered
    with its check, and its written form '(-\\frac{20}{30})'."""
    na, nb = _teeth(b, scene, link.start), _teeth(b, scene, link.end)
    value = willis_relation(scene.gear(link.start).teeth, scene.gear(link.end).teeth, link.internal)
    r = b.value(f"r({link.start},{link.end})", float(value), "")
    sign = 1.0 if link.internal else -1.0
    b.check("quotient", r, na, nb, factor=sign)
    frac = Frac(na, nb)
    if link.internal:
        return r, (frac,)
    return r, (Sym("(-", "(-"), frac, ")")


def _stage_ratio(
    b: StepBuilder, ctx: GearContext, stage: Stage, gear: str
) -> tuple[Ref, tuple[Piece, ...]]:
    """e_i from F to ``gear``: the product of the mesh ratios on the path, with its check and its
    written product (the shaft links add nothing)."""
    scene = ctx.scene
    meshes = [link for link in stage.paths[gear] if link.mesh]
    if not meshes:
        return b.value("1", 1.0, ""), ("1",)
    factors = [_ratio_pieces(b, scene, link) for link in meshes]
    if len(factors) == 1:
        return factors[0]
    e = b.value(f"e({stage.reference},{gear})", float(stage.ratio(scene, gear)), "")
    b.check("product", e, *(r for r, _ in factors))
    written: list[Piece] = []
    for i, (_, pieces) in enumerate(factors):
        if i:
            written.append(CDOT)
        written.extend(pieces)
    return e, tuple(written)


def _e_symbol(stage: Stage, gear: str) -> Sym:
    ref, g = tex.name(stage.reference), tex.name(gear)
    return Sym(rf"e_{{{ref}\to {g}}}", f"e({stage.reference} -> {gear})")


def ordinary_step(ctx: GearContext, stage: Stage) -> Step:
    """omega_i = e_i omega_F on fixed axes: the train value as the product of tooth ratios."""
    f = stage.reference
    b = ctx.builder("gears.ordinary", f"Ordinary train from {f} (axes fixed in the frame)")
    wf = _speed(b, ctx, f)
    b.say(
        "On axes fixed in the frame each mesh turns the driven gear at -N_a/N_b (external) or "
        "+N_a/N_b (internal) times the driver; the train value from ",
        _w(f),
        " is the product of these ratios along the gears, and ",
        _w(f),
        " = ",
        Num(wf, unit=True),
        " is known.",
    )
    for gear in stage.gears:
        if gear == f:
            continue
        e, written = _stage_ratio(b, ctx, stage, gear)
        wi = _speed(b, ctx, gear)
        b.check("product", wi, e, wf)
        value = Equation.of(_e_symbol(stage, gear), written, Num(e))
        speed = Equation.of(_w(gear), (Num(e), CDOT, Paren(wf)), Boxed((Num(wi, unit=True),)))
        b.line(value)
        b.line(speed)
        b.say(value, ", so ", speed, ".")
    return b.build()


def tabular_step(ctx: GearContext, stage: Stage, known: Sequence[str]) -> Step:
    """The table: the arm locked and F turned x, everything turned with the arm y, the sum
    omega_i = e_i x + y; two known members give x and y."""
    arm = stage.carrier
    assert arm is not None
    f = stage.reference
    b = ctx.builder("gears.tabular", f"Tabular method, carrier {arm}")
    ratios: dict[str, tuple[Ref, tuple[Piece, ...]]] = {
        gear: _stage_ratio(b, ctx, stage, gear) for gear in stage.gears if gear != f
    }
    one = b.value("1", 1.0, "")
    zero = b.value("0", 0.0, "")
    for gear, (e, written) in ratios.items():
        b.line("&", Equation.of(_e_symbol(stage, gear), written, Num(e)))
    header = " & ".join(rf"\text{{{tex.escape_text(m)}}}" for m in stage.members)
    locked: list[Piece] = [r"\text{" + tex.escape_text(f"{arm} locked, {f} +x") + "}"]
    turned: list[Piece] = [r"\text{" + tex.escape_text(f"all with {arm} +y") + "}"]
    total: list[Piece] = [r"\text{sum } \omega"]
    for member in stage.members:
        if member == f:
            locked.append(" & x")
            total.append(" & x + y")
        elif member == arm:
            locked.append(" & 0")
            total.append(" & y")
        else:
            e = ratios[member][0]
            locked += [" & ", Num(e), r"\,x"]
            total += [" & ", Num(e), r"\,x + y"]
        turned.append(" & y")
    b.line(
        r"&\begin{array}{l|" + "c" * len(stage.members) + "} & " + header + r" \\ \hline ",
        *locked,
        r" \\ ",
        *turned,
        r" \\ \hline ",
        *total,
        r" \end{array}",
    )
    b.say(
        f"Tabular method (Willis). Row 1: with the carrier {arm} locked, turn {f} by x (rad/s); "
        "each gear of the stage turns by its train value from ",
        _w(f),
        " times x: ",
        *joined("; ", [(f"{g}: ", Num(e), " x") for g, (e, _) in ratios.items()]),
        "; the arm 0. Row 2: turn everything with the arm by y: y for every member. "
        "Row 3, the sum, is the absolute motion: omega = e x + y, and omega of the arm = y.",
    )
    rows = []
    for member in known[:2]:
        coefficient = zero if member == arm else (one if member == f else ratios[member][0])
        rows.append(([coefficient, one], _speed(b, ctx, member)))
    b.say(f"Known: {', '.join(known[:2])}.")
    x_value = ctx.omega(f) - ctx.omega(arm)
    unknowns = [
        Unknown("x", "x", "x", "rad/s", x_value, None, f"{f} relative to {arm}"),
        Unknown("y", "y", "y", "rad/s", ctx.omega(arm), None, f"the speed of the carrier {arm}"),
    ]  # fmt: skip
    present_solution(b, unknowns, [r[0] for r in rows], [r[1] for r in rows], "xy: ")
    x, y = Ref("x"), Ref("y")
    for member in stage.members:
        if member in known[:2]:
            continue
        w = _speed(b, ctx, member)
        if member == arm:
            b.check("sum", w, y)
            b.line("&", Equation.of(_w(member), "y", Boxed((Num(w, unit=True),))))
            continue
        e = one if member == f else ratios[member][0]
        b.check("linear", w, e, x, one, y)
        speed = Equation.of(
            _w(member),
            (Num(e), Sym(r"\,x + y", " x + y")),
            latex_only(Num(e), r" \cdot ", Paren(x), " ", Signed(y)),
            Boxed((Num(w, unit=True),)),
        )
        b.line(speed)
        b.say(speed, ".")
    return b.build()


def formula_step(ctx: GearContext, stage: Stage, known: Sequence[str]) -> Step:
    """The formula method: e = (omega_L - omega_arm) / (omega_F - omega_arm) between the known
    gear F and, with the arm unknown, the other known gear L: omega_arm = (omega_L - e omega_F) /
    (1 - e); then every other gear i, omega_i = omega_arm + e_i (omega_F - omega_arm)."""
    arm = stage.carrier
    assert arm is not None
    f = stage.reference
    b = ctx.builder("gears.formula", f"Formula method, carrier {arm}")
    wf = _speed(b, ctx, f)
    wa = _speed(b, ctx, arm)
    one = b.value("1", 1.0, "")
    general = Equation.of(
        Sym("e", "e"),
        Sym(r"\frac{\omega_L - \omega_{arm}}{\omega_F - \omega_{arm}}",
            "(omega_L - omega_arm)/(omega_F - omega_arm)"),
        Sym(r"\pm\frac{\text{product of driving teeth}}{\text{product of driven teeth}}",
            "+-(product of driving teeth)/(product of driven teeth)"),
    )  # fmt: skip
    b.line("&", general)
    b.say(
        "Formula method: seen from the arm the stage is an ordinary train, so ",
        general,
        ", the sign - for an odd number of external meshes from F to L.",
    )
    others = [g for g in stage.gears if g != f]
    if arm not in known[:2]:
        last = next(g for g in known[:2] if g != f)
        e, written = _stage_ratio(b, ctx, stage, last)
        wl = _speed(b, ctx, last)
        ef = b.value(f"e omega({f})", b.scalar(e) * ctx.omega(f), "rad/s")
        num = b.value("numerator", ctx.omega(last) - b.scalar(ef), "rad/s")
        den = b.value("1 - e", 1.0 - b.scalar(e), "")
        b.check("product", ef, e, wf)
        b.check("sum", num, wl, -ef)
        b.check("sum", den, one, -e)
        b.check("quotient", wa, num, den)
        sym_e = _e_symbol(stage, last)
        value = Equation.of(sym_e, latex_only(*written), Num(e))
        b.line(value)
        b.line(
            "&",
            Equation.of(
                Sym(rf"\frac{{\omega_{{{tex.name(last)}}} - \omega_{{{tex.name(arm)}}}}}"
                    rf"{{\omega_{{{tex.name(f)}}} - \omega_{{{tex.name(arm)}}}}}",
                    f"(omega_{last} - omega_{arm})/(omega_{f} - omega_{arm})"),
                Num(e),
            ),
        )  # fmt: skip
        carrier = Equation.of(
            _w(arm),
            Alt(
                (rf"\frac{{\omega_{{{tex.name(last)}}} - e\,\omega_{{{tex.name(f)}}}}}{{1 - e}}",),
                ("(", Num(wl), " - ", Paren(e), " x ", Paren(wf), ")/(1 - ", Paren(e), ")"),
            ),
            _quotient(num, den),
            Boxed((Num(wa, unit=True),)),
        )
        b.line(carrier)
        b.say(
            "With ", Equation.of(_w(f), Num(wf, unit=True)), " and ",
            Equation.of(_w(last), Num(wl, unit=True)), ": ", value, ", ", carrier, ".",
        )  # fmt: skip
        others = [g for g in others if g != last]
    else:
        b.say("The arm's speed ", _w(arm), " = ", Num(wa, unit=True), " is known.")
    if others:
        d = b.value(f"omega({f}) - omega({arm})", ctx.omega(f) - ctx.omega(arm), "rad/s")
        b.check("sum", d, wf, -wa)
    for gear in others:
        e, written = _stage_ratio(b, ctx, stage, gear)
        wi = _speed(b, ctx, gear)
        term = b.value(f"e(->{gear}) (omega_F - omega_arm)", b.scalar(e) * b.scalar(d), "rad/s")
        b.check("product", term, e, d)
        b.check("sum", wi, wa, term)
        b.line("&", Equation.of(_e_symbol(stage, gear), written, Num(e)))
        speed = Equation.of(
            _w(gear),
            Sym(rf"\omega_{{{tex.name(arm)}}} + e\,(\omega_{{{tex.name(f)}}} - "
                rf"\omega_{{{tex.name(arm)}}})",
                f"omega_{arm} + e (omega_{f} - omega_{arm})"),
            (Num(wa), " + ", Paren(e), CDOT, Paren(d)),
            Boxed((Num(wi, unit=True),)),
        )  # fmt: skip
        b.line(speed)
        b.say(speed, ".")
    return b.build()


def keyed_step(ctx: GearContext, found: Sequence[tuple[str, str]]) -> Step:
    """Members keyed to a member already found turn with it."""
    b = ctx.builder("gears.keyed", "Keyed members")
    for member, source in found:
        w = _speed(b, ctx, member)
        keyed = Equation.of(_w(member), _w(source), Num(w, unit=True))
        b.line(keyed)
        b.say(f"{member} is keyed to {source}: ", keyed, ".")
    return b.build()


def system_step(ctx: GearContext, members: Sequence[str]) -> Step:
    """What the stage-by-stage method does not reach: the whole train's relations at once."""
    b = ctx.builder("gears.system", "The remaining members from all relations at once")
    b.say(
        "No stage has enough known members to be solved alone: the Willis relations of every "
        "mesh and the shafts are solved together as one linear system (the solver's), giving: "
    )
    for member in members:
        w = _speed(b, ctx, member)
        speed = Equation.of(_w(member), Boxed((Num(w, unit=True),)))
        b.line(speed)
        b.say(speed, ".")
    return b.build()


def train_value_step(ctx: GearContext) -> Step | None:
    """Each member's train value omega_i / omega_first (None where the first input is still)."""
    first = ctx.body["first_input"]
    if first is None or ctx.omega(first) == 0.0:
        return None
    b = ctx.builder("gears.train_value", f"Train values from {first}")
    w1 = _speed(b, ctx, first)
    for name in ctx.scene.members:
        if name == first:
            continue
        wi = _speed(b, ctx, name)
        tv = b.value(
            f"e({name})",
            ctx.body["members"][name]["train_value"],
            "",
            ("members", name, "train_value"),
        )
        b.check("quotient", tv, wi, w1)
        value = Equation.of(
            latex_only(rf"\frac{{\omega_{{{tex.name(name)}}}}}{{\omega_{{{tex.name(first)}}}}}"),
            _quotient(wi, w1),
            Num(tv),
        )
        b.line(value)
        b.say(f"Train value of {name}: ", value, ".")
    return b.build()


def summary_step(ctx: GearContext) -> Step:
    """Every member's absolute angular velocity, and each planet's relative to its carrier."""
    b = ctx.builder("summary", "Results")
    rows: list[tuple[Piece, ...]] = []
    for name in ctx.scene.members:
        w = _speed(b, ctx, name)
        entry = ctx.body["members"][name]
        sense = "" if entry["omega"] == 0 else (" (ccw)" if entry["omega"] > 0 else " (cw)")
        row: tuple[Piece, ...] = (
            Sym(f"{_w(name).tex} = ", f"{name}: "),
            Num(w, unit=True),
            Sym(rf"\text{{{sense}}}", sense),
        )
        if entry.get("carrier"):
            rel = b.value(f"omega({name}) rel", entry["omega_relative"], "rad/s",
                          ("members", name, "omega_relative"))  # fmt: skip
            arm = _speed(b, ctx, entry["carrier"])
            b.check("sum", rel, w, -arm)
            row += (
                Sym(
                    rf" & \omega_{{{tex.name(name)}/{tex.name(entry['carrier'])}}} = ",
                    f", relative to {entry['carrier']}: ",
                ),
                Num(rel, unit=True),
            )
        else:
            row += (Sym(" &", ""),)
        b.say(*row, ".")
        rows.append(row)
    b.line(r"&\begin{array}{ll} ", *joined(r" \\ ", rows), r" \end{array}")
    return b.build()


def gear_train_steps(ctx: GearContext) -> list[Step]:
    """The steps: data, degrees of freedom, then the stages in the order their known members
    allow (tabular and formula method for a carrier's, the product of ratios for fixed axes),
    the train values and the results."""
    scene = ctx.scene
    known = {name for name, _ in scene.inputs}
    order = [name for name, _ in scene.inputs]
    steps = [data_step(ctx), freedom_step(ctx)]

    def spread() -> None:
        found = []
        changed = True
        while changed:
            changed = False
            for shaft in scene.shafts:
                source = next((m for m in shaft if m in known), None)
                for member in shaft:
                    if source is not None and member not in known:
                        known.add(member)
                        order.append(member)
                        found.append((member, source))
                        changed = True
        if found:
            steps.append(keyed_step(ctx, found))

    spread()
    pending = stages(scene, known)
    progress = True
    while pending and progress:
        progress = False
        for stage in list(pending):
            have = sorted(
                (m for m in order if m in stage.members), key=lambda m: m != stage.reference
            )
            if len(have) < (1 if stage.carrier is None else 2):
                continue
            # the reference F: a known gear, the stage's first on the frame's axes if one is known
            stage = next(s for s in stages(scene, known) if set(s.members) == set(stage.members))
            pending = [s for s in pending if set(s.members) != set(stage.members)]
            if stage.carrier is None:
                steps.append(ordinary_step(ctx, stage))
            else:
                steps.append(tabular_step(ctx, stage, have))
                steps.append(formula_step(ctx, stage, have))
            for member in stage.members:
                if member not in known:
                    known.add(member)
                    order.append(member)
            spread()
            progress = True
    rest = [m for m in scene.members if m not in known]
    if rest:
        steps.append(system_step(ctx, rest))
    values = train_value_step(ctx)
    if values is not None:
        steps.append(values)
    steps.append(summary_step(ctx))
    return steps


def _speed_value(ctx: GearContext, omega: float, source: Source | None = None) -> Value:
    return Value(omega, "rad/s", ctx.fmt.display(omega, "rad/s"), source)


def gear_train_mistakes(ctx: GearContext, steps: Sequence[Step]) -> list[Mistake]:
    """The sign and frame mistakes of this train, each with the wrong number it gives beside the
    right one, under the first stage's tabular step (else the results): an annulus taken as an
    external gear (``teaching.mistakes.rings_as_external``, the solver's speeds of that train),
    a planet's speed relative to its carrier taken for its absolute speed."""
    kinds = [s.kind for s in steps]
    at = kinds.index("gears.tabular") if "gears.tabular" in kinds else len(steps) - 1
    scene, members = ctx.scene, ctx.body["members"]
    given = {name for name, _ in scene.inputs}
    out = []
    if any(g.internal for g in scene.gears):
        try:
            wrong = analyze_gear_train(rings_as_external(scene)).as_dict()["members"]
        except KinematicsError:
            wrong = None
        order = [*scene.carriers, *(g.name for g in scene.gears)]
        name = next((n for n in order if n not in given), None)
        if wrong is not None and name is not None:
            mistake = typical_mistake("internal_mesh_as_external")
            w, r = wrong[name]["omega"], members[name]["omega"]
            out.append(
                Mistake(
                    mistake.id,
                    mistake.title,
                    f"An annulus turns the same way as its pinion seen from the carrier: "
                    f"+N_a/N_b. Taken as external (-N_a/N_b) it gives omega_{name} = "
                    f"{ctx.fmt.display(w, 'rad/s')} instead of {ctx.fmt.display(r, 'rad/s')}.",
                    {
                        "wrong": _speed_value(ctx, w),
                        "right": _speed_value(ctx, r, ("members", name, "omega")),
                    },
                    step=at,
                )
            )
    planet = next((g for g in scene.gears if g.carrier is not None), None)
    if planet is not None:
        mistake = typical_mistake("relative_for_absolute")
        rel, absolute = members[planet.name]["omega_relative"], members[planet.name]["omega"]
        out.append(
            Mistake(
                mistake.id,
                mistake.title,
                f"Row 1 of the table (the carrier {planet.carrier} locked) gives {planet.name}'s "
                f"speed relative to the carrier, {ctx.fmt.display(rel, 'rad/s')}; its absolute "
                f"speed adds the carrier's (row 2): {ctx.fmt.display(absolute, 'rad/s')}.",
                {
                    "wrong": _speed_value(ctx, rel, ("members", planet.name, "omega_relative")),
                    "right": _speed_value(ctx, absolute, ("members", planet.name, "omega")),
                },
                step=at,
            )
        )
    return out


def solve_gear_train(scene: GearTrainScene, digits: int) -> Solution:
    """The worked solution of a gear train (the method 'tabular': the tabular and the formula
    method side by side), its ``analysis`` the /analyze body."""
    ctx = GearContext(scene, digits)
    steps = gear_train_steps(ctx)
    mistakes = gear_train_mistakes(ctx, steps)
    return Solution(tuple(steps), tuple(mistakes), ctx.body, "tabular", "tabular", digits)


# --- the figure ---------------------------------------------------------------------------------


def figure_centres(
    scene: GearTrainScene, members: Mapping[str, Any]
) -> dict[str, tuple[float, float]]:
    """Each member's axis in the figure: the solver's centre (/analyze), the parts of the train
    that no mesh joins (two stages in series, keyed on one shaft) moved side by side along x
    where they would lie on one another."""
    part = {name: name for name in scene.members}

    def find(name: str) -> str:
        while part[name] != name:
            name = part[name]
        return name

    for mesh in scene.meshes:
        part[find(mesh.gears[0])] = find(mesh.gears[1])
    for gear in scene.gears:
        if gear.carrier is not None:
            part[find(gear.name)] = find(gear.carrier)
    boxes: dict[str, list[float]] = {}
    for gear in scene.gears:
        (x, y), r = members[gear.name]["centre"], members[gear.name]["pitch_radius"] * 1.15
        box = boxes.setdefault(find(gear.name), [x - r, y - r, x + r, y + r])
        boxes[find(gear.name)] = [min(box[0], x - r), box[1], max(box[2], x + r), box[3]]
    shift: dict[str, float] = {}
    right = -math.inf
    for key, box in boxes.items():
        shift[key] = right + 0.1 * (box[2] - box[0]) - box[0] if box[0] < right else 0.0
        right = box[2] + shift[key]
    out = {}
    for name in scene.members:
        x, y = members[name]["centre"]
        out[name] = (x + shift.get(find(name), 0.0), y)
    return out


def train_figure(scene: GearTrainScene) -> str:
    """The train to scale at t = 0: pitch circles (an annulus drawn with its rim), each axis,
    the carriers as bars from their axis to their planets'; '' without a module."""
    if scene.module is None:
        return ""
    members = analyze_gear_train(scene).as_dict()["members"]
    axis_of = figure_centres(scene, members)
    gears = scene.gears
    extent = [
        (axis_of[g.name][0] + sx * members[g.name]["pitch_radius"] * k,
         axis_of[g.name][1] + sy * members[g.name]["pitch_radius"] * k)
        for g in gears for k in ((1.15,) if g.internal else (1.0,))
        for sx, sy in ((1, 1), (-1, -1))
    ]  # fmt: skip
    per_mm = model_scale([np.asarray(p) for p in extent])
    canvas = Canvas(View.paper(per_mm))
    drawn = [canvas.px(p) for p in extent]
    xs, ys = [p[0] for p in drawn], [p[1] for p in drawn]
    margin = 10.0
    x0, y0 = min(xs) - margin, min(ys) - margin
    width, height = max(xs) - min(xs) + 2 * margin, max(ys) - min(ys) + 2 * margin + 8.0
    ink = ("stroke", "#222222")
    for gear in sorted(gears, key=lambda g: not g.internal):  # an annulus under its pinions
        entry = members[gear.name]
        centre = canvas.px(axis_of[gear.name])
        r = entry["pitch_radius"] / per_mm
        if gear.internal:
            canvas.circle(centre, r * 1.15, [("fill", "#eeeeee"), ink, ("stroke-width", "0.3")], 3)
            canvas.circle(centre, r, [("fill", "#ffffff"), ink, ("stroke-width", "0.35"),
                                      ("stroke-dasharray", "2 1")], 3)  # fmt: skip
        else:
            canvas.circle(centre, r, [("fill", "none"), ink, ("stroke-width", "0.35"),
                                      ("stroke-dasharray", "2 1")], 3)  # fmt: skip
    for shaft in scene.shafts:  # keyed members drawn apart: a dashed line joins them
        for a, b in itertools.pairwise(shaft):
            if axis_of[a] != axis_of[b]:
                style = [
                    ("stroke", "#777777"),
                    ("stroke-width", "0.4"),
                    ("stroke-dasharray", "1 1"),
                ]
                canvas.line(
                    canvas.px(axis_of[a]), canvas.px(axis_of[b]), style, [("class", "shaft")], 3
                )
    for carrier in scene.carriers:
        axis = canvas.px(axis_of[carrier])
        for gear in gears:
            if gear.carrier == carrier:
                canvas.line(axis, canvas.px(axis_of[gear.name]),
                            [("stroke", "#b5471b"), ("stroke-width", "1.2"),
                             ("stroke-linecap", "round")], [("class", "carrier")], 3)  # fmt: skip
                canvas.keep_off(axis, canvas.px(axis_of[gear.name]), 1.6)
        held = [g for g in gears if g.carrier == carrier]
        end = canvas.px(axis_of[held[0].name]) if held else axis
        middle = ((axis[0] + end[0]) / 2, (axis[1] + end[1]) / 2 + 3.6)
        canvas.label([(middle, "middle")], carrier, 3, [("fill", "#b5471b")], 2)
    for gear in gears:
        entry = members[gear.name]
        centre = canvas.px(axis_of[gear.name])
        r = entry["pitch_radius"] / per_mm
        canvas.circle(centre, "0.8", [("fill", "#ffffff"), ink, ("stroke-width", "0.3")], 3)
        label = f"{gear.name} ({gear.teeth})"
        # an annulus inside its rim, top left; a planet above it; a gear on the frame below it;
        # where that place is taken (coaxial gears of one size: a differential's side gears),
        # the next line under it, else above the gear
        below = [((centre[0], centre[1] + r + 3.6 + 3.6 * k), "middle") for k in range(3)]
        above = ((centre[0], centre[1] - r - 1.2), "middle")
        if gear.internal:
            places = [((centre[0] - r * 0.7, centre[1] - r * 0.72), "start"), *below]
        elif gear.carrier is not None:
            places = [above, *below]
        else:
            places = [*below, above]
        canvas.label(places, label, 3, [("fill", "#000000")], 2)
    caption = f"pitch circles to scale, {scale_text(per_mm * 10, 'm')}"
    title = f"The gear train {scene.title or ''}".strip()
    return paper_document(canvas, (x0, y0, width, height), title, caption, {})
