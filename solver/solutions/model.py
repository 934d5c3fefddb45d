"""The data a worked solution is made of: values, checks, steps, mistakes, the solution itself.

A ``Step`` is what a good instructor writes on the board for one equation: a title, the LaTeX
(KaTeX subset), a plain-text form a screen reader can read, and the named ``values`` it uses, each
with its full-precision number, unit, display string and, where it is one of the solver's own
results, the path of that number in the /analyze response (``source``). ``checks`` state the
arithmetic of the step as relations between those values, so that any program can re-evaluate the
step and confirm that the numbers it shows belong together (see docs/SOLUTIONS.md).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

from solver.kinematics.spatial import SpatialAnalysis
from solver.solutions.equation import Operand

Number = float | tuple[float, ...]

Relation = Literal[
    "sum",  # result = factor * sum(operands); an operand written "-name" is subtracted
    "cross",  # result = factor * (op0 x op1); a scalar operand is a z-component (planar)
    "product",  # result = factor * op0 * op1 * ...; at most one operand is a vector
    "quotient",  # result = factor * op0 / op1 (op1 scalar)
    "det2",  # result = op0 * op3 - op1 * op2 (the 2x2 determinant, entries row by row)
    "linear",  # result = sum(op[2k] * op[2k+1]): a linear equation, coefficients and unknowns
    "dot",  # result = factor * op0 . op1
    "phasor",  # result = factor * op0 * ... * op[-2] * e^(i op[-1]) as (re, im)
    "iphasor",  # result = factor * op0 * ... * op[-2] * i e^(i op[-1]) as (re, im)
    "angle",  # result = atan2(op0[1], op0[0]) (a direction in rad, within 2 pi)
    "norm",  # result = |op0|
]


@dataclass(frozen=True)
class Value:
    """One named number of a step: scalar or vector, SI unit, its display, and its source.

    ``source`` is the path of the number in the /analyze response of the same scene, as a list of
    keys and indices (``["points", "B", "velocity"]``, ``["joints", 0, "coriolis_acceleration"]``);
    None for a number the step derives from the solver's (a cross product, a determinant).
    """

    value: Number
    unit: str
    display: str
    source: tuple[str | int, ...] | None = None

    def as_json(self) -> dict[str, Any]:
        number: Any = list(self.value) if isinstance(self.value, tuple) else self.value
        return {
            "value": number,
            "unit": self.unit,
            "display": self.display,
            "source": None if self.source is None else list(self.source),
        }


@dataclass(frozen=True)
class Check:
    """A relation the step's values satisfy: ``result = relation(operands)`` (see ``Relation``).

    Operands are typed references to the step's ``values`` (``Operand``); the /solution body
    names them by key, '-key' for a value subtracted and 'key[i]' for component i of a vector.
    """

    relation: Relation
    result: Operand
    operands: tuple[Operand, ...]
    factor: float = 1.0

    def as_json(self) -> dict[str, Any]:
        return {
            "relation": self.relation,
            "result": self.result.name,
            "operands": [o.name for o in self.operands],
            "factor": self.factor,
        }


@dataclass(frozen=True)
class Step:
    """One step of a worked solution (``kind`` is a stable machine name, e.g. 'velocity.dyad')."""

    kind: str
    title: str
    latex: str
    text: str
    values: Mapping[str, Value] = field(default_factory=dict)
    checks: tuple[Check, ...] = ()
    figure: str = ""  # a standalone SVG drawing beside the step ('' for none)
    diagram: Mapping[str, Any] | None = None  # the figure as data (a free-body diagram)

    def as_json(self) -> dict[str, Any]:
        out = {
            "kind": self.kind,
            "title": self.title,
            "latex": self.latex,
            "text": self.text,
            "values": {k: v.as_json() for k, v in self.values.items()},
            "checks": [c.as_json() for c in self.checks],
        }
        if self.figure:
            out["figure"] = self.figure
        if self.diagram is not None:
            out["diagram"] = dict(self.diagram)
        return out


@dataclass(frozen=True)
class Mistake:
    """A typical mistake for this scene: what students write, why it is wrong, and, where it can be
    computed, the wrong number it leads to next to the right one."""

    kind: str
    title: str
    text: str
    values: Mapping[str, Value] = field(default_factory=dict)
    # where it belongs: (step kind prefix, part of the step's title), alternatives in order
    anchors: tuple[tuple[str, str], ...] = ()
    step: int | None = None  # the index of that step in the solution, once placed

    def as_json(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "title": self.title,
            "text": self.text,
            "step": self.step,
            "values": {k: v.as_json() for k, v in self.values.items()},
        }


@dataclass(frozen=True)
class Solution:
    """A worked solution: the steps, the mistakes to avoid, and the analysis the numbers are from.

    ``method`` is the method actually used; ``requested_method`` differs from it when the request
    asked for a method that does not apply to the scene (the first step then says why).
    """

    steps: tuple[Step, ...]
    mistakes: tuple[Mistake, ...]
    analysis: Any
    method: str
    requested_method: str
    digits: int

    @property
    def convention(self) -> str:
        """The sign convention, one sentence for the page's header (planar or spatial)."""
        if self.method == "cam":
            return (
                "cam centre at the origin, x to the right, y up; omega counter-clockwise "
                "positive; s, v, a, j positive away from the cam centre"
            )
        if isinstance(self.analysis, SpatialAnalysis):
            return (
                "vectors are components in the fixed frame E1, E2, E3; angular velocities "
                "follow the right-hand rule about their axes"
            )
        return "z out of the page, angular velocities counter-clockwise positive"

    @property
    def fell_back(self) -> bool:
        return self.method != self.requested_method


def solution_body(
    solution: Solution,
    results: dict[str, Any],
    polygons: dict[str, Any] | None,
    warnings: list[str],
) -> dict[str, Any]:
    """The /solution body: steps, mistakes, methods, the /analyze body as ``results``, and the
    polygons' segments of a linkage (``solver.solutions.polygons``)."""
    body = {
        "method": solution.method,
        "requested_method": solution.requested_method,
        "digits": solution.digits,
        "convention": solution.convention,
        "steps": [step.as_json() for step in solution.steps],
        "mistakes": [mistake.as_json() for mistake in solution.mistakes],
        "results": results,
        "warnings": list(warnings),
    }
    if polygons is not None:
        body["polygons"] = polygons
    return body
