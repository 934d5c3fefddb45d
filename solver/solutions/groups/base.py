"""What a worked solution asks of a closed-form group (``solver.position.groups``), and the
share of the groups that locate one point on two loci.

A group's solution module gives, for a plan step of its kind: its position step (the closed form
of the analysed pose, or None), its steps in the vector method (the point seen from both loci,
equated component by component), the loop it closes in the loop-closure method, the circles
about its known centres (a link whose rate the group finds) and its typical mistakes (the
Coriolis slips at its slots, the slips of the loop method). The methods ask ``solution_group``
instead of dispatching on the step's type; the arithmetic of the group comes from the position
layer (``solver.position.groups``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

from solver.position.topology import CircleSpec, DyadStep, LineSpec

if TYPE_CHECKING:
    from solver.solutions.linkage import LinkageContext
    from solver.solutions.loop import Loop, LoopMethod
    from solver.solutions.mistakes import LinkageMistakes
    from solver.solutions.model import Step
    from solver.solutions.vector import VectorMethod


class SolutionGroup(Protocol):
    """A closed-form group as the worked solutions write it: one module of
    ``solver.solutions.groups`` each, keyed like ``solver.position.groups.GROUPS``."""

    @property
    def kind(self) -> str:
        """Its name as an Assur group: RRR, RRP, PRP, RPR."""
        ...

    @property
    def loop_mistakes(self) -> tuple[str, ...]:
        """The typical mistakes of the loop method it brings (ids of the catalogue)."""
        ...

    def position_step(self, ctx: LinkageContext, step: Any) -> Step | None:
        """The closed form of the analysed pose (None: nothing to derive)."""
        ...

    def vector_steps(self, method: VectorMethod, step: Any, order: int) -> list[Step]:
        """Its velocity (``order`` 1) or acceleration (2) steps in the vector method."""
        ...

    def loop(self, method: LoopMethod, step: Any) -> Loop:
        """The loop it closes in the loop-closure method (``LoopMethod.no_loop`` where none)."""
        ...

    def circles(self, step: Any) -> list[CircleSpec]:
        """The circles about known centres it lies on: links whose rates it finds."""
        ...

    def coriolis_mistakes(self, mistakes: LinkageMistakes, step: Any) -> None:
        """The Coriolis slips at its slots (none without a slot)."""
        ...


@dataclass(frozen=True)
class DyadSolution:
    """A group that locates one joint point X on two loci (``topology.DyadStep``: RRR, RRP,
    PRP): in the vector method, X through each locus (v_X = v_C + omega x r_CX on a circle,
    v_tr + s' u in a slot), equated."""

    kind: str
    loop_mistakes: tuple[str, ...] = ()

    def vector_steps(self, method: VectorMethod, step: DyadStep, order: int) -> list[Step]:
        return method.dyad(step, order)

    def circles(self, step: DyadStep) -> list[CircleSpec]:
        return [spec for spec in step.loci if isinstance(spec, CircleSpec)]

    def slots(self, step: DyadStep) -> list[LineSpec]:
        """The slots X slides in."""
        return [spec for spec in step.loci if isinstance(spec, LineSpec)]

    def coriolis_mistakes(self, mistakes: LinkageMistakes, step: DyadStep) -> None:
        for line in self.slots(step):
            mistakes.slot_coriolis(step, line)
