"""The entry point: ``solve(scene, method, digits) -> Solution``.

One analysis of the scene (the same call /analyze makes, all quantities), then the steps of the
requested method built from its numbers, then the typical mistakes for the scene. A method that
does not apply to the scene (the loop-closure method for a linkage that is not a chain of
four-bar / slider-crank / slotted-lever loops, or for a spatial chain) falls back to the vector
method; the solution then says so in its first step and in ``method``/``requested_method``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Literal, get_args

from solver.analysis.instant import LinkageAnalysis, analyze
from solver.cams.model import CamScene
from solver.errors import InvalidScene
from solver.gears import GearTrainScene
from solver.kinematics.spatial import SpatialChain, analyze_spatial_chain
from solver.model.scene import LinkageScene
from solver.solutions import latex as tex
from solver.solutions.cam import cam_solution
from solver.solutions.classification import (
    angle_extreme_steps,
    classification_steps,
    slider_classification_steps,
)
from solver.solutions.format import Formatter
from solver.solutions.gear_train import solve_gear_train
from solver.solutions.graphical import graphical_steps, mechanism_figure
from solver.solutions.instant_centres import instant_centres_step
from solver.solutions.linkage import (
    LinkageContext,
    data_step,
    positions_step,
    reading_step,
    summary_step,
    unit_scales,
)
from solver.solutions.loop import LoopUnavailable, loop_steps
from solver.solutions.mistakes import (
    linkage_mistakes,
    loop_mistakes,
    place_mistakes,
    spatial_mistakes,
)
from solver.solutions.model import Solution, Step
from solver.solutions.newton_euler import in_scene_order, newton_euler_mistakes, newton_euler_steps
from solver.solutions.position import position_steps
from solver.solutions.relative import moving_point_steps
from solver.solutions.spatial import spatial_steps
from solver.solutions.vector import vector_steps

Method = Literal[
    "vector", "loop", "newton_euler", "statics"
]  # declared once; the server imports it
METHODS: tuple[Method, ...] = get_args(Method)
MIN_DIGITS, MAX_DIGITS = 1, 15

_SENTENCES = {
    "vector": "Method: relative velocities (vector method). Point by point in the solver's order, "
    "v_B = v_A + omega x r_AB and a_B = a_A + alpha x r_AB - omega^2 r_AB, with the "
    "transport, relative and Coriolis terms at every slot.",
    "loop": "Method: loop closure in complex form. Each loop of link vectors closes; its time "
    "derivatives are linear in the unknown rates, solved by Cramer's rule.",
    "newton_euler": "Method: Newton-Euler. The kinematics by relative velocities, then for every "
    "moving link sum F = m a_G and the sum of moments about a point of the link, one linear "
    "system for the joint forces and the driving torque, checked by the power balance.",
    "statics": "Method: static force analysis. The velocities by relative velocities (for the "
    "virtual-work check), then for every moving link sum F = 0 and the sum of moments about a "
    "point of the link = 0, the masses counting only through their weight: one linear system "
    "for the joint forces and the torque that holds the mechanism, checked by virtual work.",
}


def _fallback_step(requested: str, reason: str) -> Step:
    title = f"The {requested} method is not available for this scene"
    text = f"{reason} The solution below uses the relative-velocity (vector) method instead."
    return Step("fallback", title, r"\text{" + tex.escape_text(title) + "}", text)


def _linkage_steps(
    scene: LinkageScene,
    analysis: LinkageAnalysis,
    fmt: Formatter,
    method: str,
    angle_extremes: bool,
) -> tuple[list[Step], LinkageContext, str]:
    """The steps by ``method`` (or the vector method, when it does not apply), the context they
    were built in, and the method used (``angle_extremes``: with the step of the links' extreme
    angles over a turn). Every step is written with typed references and settles its digits as
    it is built, so that its shown arithmetic recomputes: the solution is built once."""
    ctx = LinkageContext(scene, analysis, fmt)
    used = method
    lead: list[Step] = []
    if method == "loop":
        try:
            body = loop_steps(ctx)
            body += moving_point_steps(ctx)
        except LoopUnavailable as why:
            reason = str(why)
            lead.append(_fallback_step("loop-closure", reason[:1].upper() + reason[1:] + "."))
            ctx = LinkageContext(scene, analysis, fmt)
            used = "vector"
            body = _vector_method(ctx)
    else:
        body = _vector_method(ctx)
    body += graphical_steps(ctx)
    body.append(instant_centres_step(ctx))
    if method in ("newton_euler", "statics"):
        body += newton_euler_steps(ctx, statics=method == "statics")
    positions = positions_step(ctx)
    positions = replace(positions, figure=mechanism_figure(ctx))
    steps = [
        *lead,
        data_step(ctx, _SENTENCES[used]),
        positions,
        *position_steps(ctx),
        *classification_steps(ctx),
        *(angle_extreme_steps(ctx) if angle_extremes else ()),
        *slider_classification_steps(ctx),
        *body,
        reading_step(ctx),
        summary_step(ctx),
    ]
    return steps, ctx, used


def _formatter(scene: LinkageScene, analysis: LinkageAnalysis, digits: int) -> Formatter:
    """Numbers with ``digits`` significant digits, the units scaled to the scene's size."""
    return Formatter(digits, unit_scales(analysis, scene.size))


def _vector_method(ctx: LinkageContext) -> list[Step]:
    """The vector method's steps: the plan's groups, then the moving points."""
    return vector_steps(ctx) + moving_point_steps(ctx)


def vector_method_steps(scene: LinkageScene, analysis: LinkageAnalysis, digits: int) -> list[Step]:
    """The vector method's steps alone, as the vector solution of ``analysis`` holds them, their
    structure only (kinds, values with their sources, checks; nothing written: ``StepBuilder``):
    what the polygons follow, whichever method a solution uses, without the solution's other
    steps and mistakes, and without writing them (more than half of the steps' time)."""
    fmt = _formatter(scene, analysis, digits)
    return _vector_method(LinkageContext(scene, analysis, fmt, written=False))


def _linkage(scene: LinkageScene, method: str, digits: int, angle_extremes: bool) -> Solution:
    analysis = analyze(scene)
    fmt = _formatter(scene, analysis, digits)
    steps, ctx, used = _linkage_steps(scene, analysis, fmt, method, angle_extremes)
    mistakes = linkage_mistakes(ctx)
    if used == "loop":
        mistakes += loop_mistakes(ctx)
    if used == "newton_euler":
        mistakes += newton_euler_mistakes(ctx)
    if used in ("newton_euler", "statics"):
        in_scene_order(steps, mistakes, ctx)
    placed = place_mistakes(steps, mistakes, used == "loop")
    return Solution(tuple(steps), tuple(placed), analysis, used, method, digits)


def solve(
    scene: LinkageScene | SpatialChain | GearTrainScene | CamScene,
    method: str = "vector",
    digits: int = 4,
    angle_deg: float = 0.0,
    angle_extremes: bool = True,
) -> Solution:
    """The worked solution of ``scene`` by ``method`` ('vector', 'loop', 'newton_euler' or
    'statics': the static force analysis, inertia left out), numbers shown with
    ``digits`` significant digits (1..15); a cam's at cam angle ``angle_deg``, by its own method
    ('cam', whatever ``method`` says); a gear train's by the tabular and the formula method
    (``solver.solutions.gear_train``, method 'tabular', whatever is asked). ``angle_extremes``
    False leaves out a linkage's step of the coupler's and the rocker's extreme angles over a
    turn (``angle_extremes``: a question that does not ask them need not pay for the turn). Raises
    ``InvalidScene`` for an unknown method or a bad digit count, and the analysis' own errors
    (NotAssemblable, SingularConfiguration...)."""
    if method not in METHODS:
        raise InvalidScene(f"method: unknown method {method!r}; available: {', '.join(METHODS)}")
    if (
        isinstance(digits, bool)
        or not isinstance(digits, int)
        or not (MIN_DIGITS <= digits <= MAX_DIGITS)
    ):
        raise InvalidScene(
            f"digits: expected an integer from {MIN_DIGITS} to {MAX_DIGITS}, got {digits!r}"
        )
    if isinstance(scene, LinkageScene):
        return _linkage(scene, method, digits, angle_extremes)
    if isinstance(scene, GearTrainScene):
        return solve_gear_train(scene, digits)
    if isinstance(scene, CamScene):
        return cam_solution(scene, angle_deg, digits)
    analysis = analyze_spatial_chain(scene)
    fmt = Formatter(digits)
    lead = []
    if method == "loop":
        lead.append(
            _fallback_step(
                "loop-closure",
                "A spatial chain is an open chain of rotating frames: it has no loop "
                "to close; its velocities follow from the composition of angular velocities.",
            )
        )
    elif method in ("newton_euler", "statics"):
        lead.append(
            _fallback_step(
                "Newton-Euler" if method == "newton_euler" else "statics",
                "Masses and forces are defined for planar linkages only.",
            )
        )
    steps = lead + spatial_steps(scene, analysis, fmt)
    mistakes = place_mistakes(steps, spatial_mistakes(scene, analysis, fmt), False)
    return Solution(tuple(steps), tuple(mistakes), analysis, "vector", method, digits)
