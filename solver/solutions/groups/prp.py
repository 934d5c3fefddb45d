"""PRP in the worked solutions: a pin in two slots (one solution). The vector method equates
the pin through both slots; there is no closed form of the position written, and no single
loop of the loop-closure method."""

from __future__ import annotations

from typing import TYPE_CHECKING

from solver.position.topology import DyadStep
from solver.solutions.groups.base import DyadSolution, SolutionGroup
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

if TYPE_CHECKING:
    from solver.solutions.loop import Loop, LoopMethod


class PRP(DyadSolution):
    """The pin in two slots."""

    def position_step(self, ctx: LinkageContext, step: DyadStep) -> Step | None:
        """None: the solver's pose is taken as it is."""
        return None

    def loop(self, method: LoopMethod, step: DyadStep) -> Loop:
        return method.no_loop(
            f"{step.point} is carried by two slots: not a four-bar, slider-crank or "
            "slotted-lever loop"
        )


GROUP: SolutionGroup = PRP("PRP", loop_mistakes=("loop.real_slider",))
