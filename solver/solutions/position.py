"""The position analysis, derived: how each point of the analysed pose follows from the ones
before it, group by group of the solver's plan.

- a driven crank (``position.crank``): B = A + a e^(i theta);
- a closed-form group: its own solution module writes it (``solver.solutions.groups``: the
  triangle of an RRR dyad, a circle and a guide, the slotted lever);
- a Newton group (``position.newton``): the joints' equations Phi(q) = 0 and the solver's own
  Newton-Raphson iterations.

Closed forms come first, then the numbers; the result is the solver's own position.
"""

from __future__ import annotations

import math

import numpy as np

from solver.position import constraints, newton
from solver.position.topology import DriverStep, NewtonStep, PlanStep
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Num, Pt
from solver.solutions.groups import solution_group
from solver.solutions.groups.pose import point_value
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

DEGREE = r"{}^{\circ}"


def crank_step(ctx: LinkageContext, step: DriverStep) -> Step | None:
    """B = A + a e^(i theta): the driven link's point at its length a and angle theta."""
    others = [p for p in ctx.scene.links[step.link].points if p != step.pivot]
    if not others:
        return None
    x = others[0]
    b = ctx.builder("position.crank", f"Position of {x} (driven link {step.link})")
    a = point_value(b, ctx, step.pivot)
    target = point_value(b, ctx, x)
    r = ctx.pos(x) - ctx.pos(step.pivot)
    length = b.value(f"|{step.pivot}{x}|", float(np.hypot(*r)), "m")
    theta = b.value(f"theta({step.link})", math.atan2(r[1], r[0]), "rad")
    arm = b.value(f"r({step.pivot},{x})", r, "m")
    b.check("phasor", arm, length, theta)
    b.check("sum", target, a, arm)
    degrees = math.degrees(b.scalar(theta))  # in the solution's digits, as the driver is given
    deg = tex.paren(ctx.fmt.latex(degrees) + DEGREE)
    b.line(
        rf"&{tex.name(x)} = {tex.name(step.pivot)} + a\,e^{{i\theta}} = ",
        Pt(a),
        " + ",
        Num(length),
        rf"\,e^{{i\,{deg}}} = ",
        Boxed((Pt(target, "m"),)),
    )
    b.say(
        f"The driven link {step.link} of length a = ",
        Num(length, unit=True),
        f" is at theta = {ctx.fmt.text(degrees)} deg: {x} = {step.pivot} + a "
        "(cos theta, sin theta) = ",
        Pt(target),
        ".",
    )
    return b.build()


# --- a Newton group: the loop-closure equations solved numerically ---------------------------

MAX_SHOWN_ITERATIONS = 12


def _power(x: float) -> str:
    """A residual in LaTeX with a power of ten (2 digits): rounding-level numbers are the point."""
    if x == 0.0:
        return "0"
    mantissa, exponent = f"{x:.1e}".split("e")
    return rf"{mantissa} \cdot 10^{{{int(exponent)}}}"


def _joint_equation(ctx: LinkageContext, joint_index: int) -> tuple[str, str]:
    """One joint's loop-closure equation (LaTeX, text): the joint's point as carried by either
    link (a pin), on the guide's line (a slot), no relative turn (a prismatic joint)."""
    joint = ctx.scene.joints[joint_index]
    i, j = (tex.name(k) for k in joint.links)
    p = tex.name(joint.point)
    if joint.type == "revolute":
        return (
            rf"\vec{{r}}_{{{i}}} + e^{{i\theta_{{{i}}}}}\vec{{d}}_{{{p}}}^{{\,{i}}} = "
            rf"\vec{{r}}_{{{j}}} + e^{{i\theta_{{{j}}}}}\vec{{d}}_{{{p}}}^{{\,{j}}}",
            f"{joint.point} carried by {joint.links[0]} = {joint.point} carried by "
            f"{joint.links[1]} (2 equations)",
        )
    g, f = tex.name(joint.guide), tex.name(joint.follower)
    line = (
        rf"\vec{{n}}_{{{g}}} \cdot ({p}^{{\,{f}}} - {p}^{{\,{g}}}) = 0",
        f"{joint.point} of {joint.follower} on the slot line of {joint.guide} (normal n)",
    )
    if joint.type == "prismatic":
        return (
            line[0] + rf", \quad \theta_{{{f}}} = \theta_{{{g}}}",
            line[1] + f", and {joint.follower} does not turn relative to {joint.guide}",
        )
    return line


def newton_iterations(ctx: LinkageContext, step: NewtonStep) -> tuple[list[float], bool]:
    """|Phi(q_k)| of Newton-Raphson q_(k+1) = q_k - J(q_k)^-1 Phi(q_k) on the group's joint
    equations from the drawn pose q_0, the group's known neighbours where the solver put them
    (the solver's own ``newton_raphson``, one iteration more each time, until the solver's
    tolerance), and whether the pose reached is the solver's."""
    scene = ctx.scene
    system = constraints.ConstraintSystem(scene, step.links)
    known = constraints.states({k: ctx.analysis.motion.links[k] for k in system.known}, scene)
    tolerance = group_report(ctx, step).tolerance
    q0 = system.drawn()[None]
    residuals: list[float] = []
    q = q0
    for k in range(MAX_SHOWN_ITERATIONS + 1):
        q, residual, done, _ = newton.newton_raphson(
            system, known, q0, tolerance, polish=False, max_iterations=k
        )
        residuals.append(float(residual[0]))
        if done < k or residual[0] <= tolerance:
            break
    solver_q = np.concatenate(
        [
            np.append(ctx.pos(scene.links[k].points[0]), ctx.analysis.motion.links[k].theta[0])
            for k in step.links
        ]
    )
    weights = np.tile([1.0, 1.0, scene.size], len(step.links))
    gap = float(np.max(np.abs((q[0] - solver_q) * weights)))
    return residuals, gap <= 1e-9 * scene.size


def group_report(ctx: LinkageContext, step: NewtonStep) -> newton.NewtonReport:
    """The solver's diagnostics of the group: its iterations, residual and tolerance."""
    return next(r for r in ctx.analysis.diagnostics.newton if set(r.links) == set(step.links))


def newton_position_step(ctx: LinkageContext, step: NewtonStep) -> Step:
    """Phi(q) = 0, the joints' equations in q = (x, y, theta) of each link of the group (its first
    point and its rotation from the drawing), solved numerically (``newton_iterations``)."""
    b = ctx.builder("position.newton", f"Position of links {', '.join(step.links)}: Newton-Raphson")
    residuals, same = newton_iterations(ctx, step)
    report = group_report(ctx, step)
    for k, r in enumerate(residuals):
        b.put(f"|Phi(q_{k})|", r, "m")
    b.put("iterations (solver)", float(report.iterations), "")
    b.put("residual (solver)", report.residual_norm, "m")
    b.put("tolerance", report.tolerance, "m")
    newton_lines(b, ctx, step, residuals, same)
    return b.build()


def newton_lines(
    b: StepBuilder, ctx: LinkageContext, step: NewtonStep, residuals: list[float], same: bool
) -> None:
    """Write the joints' equations, the iteration, the residuals and the solver's diagnostics."""
    report = group_report(ctx, step)
    joints = [n for n, joint in enumerate(ctx.scene.joints) if set(joint.links) & set(step.links)]
    equations = [_joint_equation(ctx, n) for n in joints]
    unknowns = ", ".join(
        rf"x_{{{tex.name(k)}}}, y_{{{tex.name(k)}}}, \theta_{{{tex.name(k)}}}" for k in step.links
    )
    for latex, _ in equations:
        b.line("&" + latex)
    b.line(
        rf"&\vec{{q}} = ({unknowns}), \quad \vec{{q}}_{{k+1}} = \vec{{q}}_k - "
        rf"J(\vec{{q}}_k)^{{-1}}\,\Phi(\vec{{q}}_k), \quad \vec{{q}}_0 = \text{{drawn pose}}"
    )
    header = " & ".join(str(k) for k in range(len(residuals)))
    row = " & ".join(_power(r) for r in residuals)
    b.line(
        r"&\begin{array}{c|" + "c" * len(residuals) + r"} k & " + header + r" \\ \hline "
        r"|\Phi(\vec{q}_k)|\ (\mathrm{m}) & " + row + r" \end{array}"
    )
    plural = "" if report.iterations == 1 else "s"
    b.line(
        rf"&\text{{solver: }} {report.iterations} \text{{ iteration{plural}, residual }} "
        rf"{_power(report.residual_norm)}\,\mathrm{{m}} \le "
        rf"{_power(report.tolerance)}\,\mathrm{{m}}"
    )
    b.say(newton_text(step, [text for _, text in equations], report, residuals, same))


def newton_text(
    step: NewtonStep,
    equations: list[str],
    report: newton.NewtonReport,
    residuals: list[float],
    same: bool,
) -> str:
    """The Newton step in words: the equations, the iteration, the residuals, the solver's."""
    plural = "" if report.iterations == 1 else "s"
    reached = (
        ", and the pose reached is the solver's."
        if same
        else ", and lands on another assembly than the solver's, which follows the "
        "linkage continuously from its drawing (the branch rule): the solver's pose is used."
    )
    return (
        f"Links {', '.join(step.links)} form no group with a closed-form solution: their joints "
        "give as many equations Phi(q) = 0 as unknowns, each link's first point (x, y) and its "
        "rotation theta from the drawing: "
        + "; ".join(equations)
        + ". The equations are not linear in the angles, so they are solved numerically, by "
        "Newton-Raphson: q(k+1) = q(k) - J(q(k))^-1 Phi(q(k)), J the Jacobian of Phi. Started "
        "from the drawn pose, the residual |Phi| falls as "
        + ", ".join(f"{r:.1e} m" for r in residuals)
        + reached
        + f" The solver (solver diagnostics) took {report.iterations} iteration{plural} from "
        f"its continuation's start, to a residual of {report.residual_norm:.1e} m, below the "
        f"tolerance {report.tolerance:.1e} m: the numbers are exact to rounding."
    )


def group_step(ctx: LinkageContext, step: PlanStep) -> Step | None:
    """The position step of one group of the solver's plan (None: nothing to derive)."""
    group = solution_group(step)
    if group is not None:
        return group.position_step(ctx, step)
    if isinstance(step, DriverStep):
        return crank_step(ctx, step)
    if isinstance(step, NewtonStep):
        return newton_position_step(ctx, step)
    return None


def position_steps(ctx: LinkageContext) -> list[Step]:
    """The position analysis of the analysed pose, group by group of the solver's plan."""
    built = (group_step(ctx, step) for step in ctx.analysis.plan.steps)
    return [step for step in built if step is not None]
