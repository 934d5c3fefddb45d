"""The protocol of a closed-form group, and the shared form of the groups that locate one point.

A closed-form group (an Assur group of the plan: ``topology.DyadStep``, ``topology.LeverStep``)
is asked two things by the assembler, in this order: ``close`` gives its length margin m over
the samples (the smallest of its smooth pieces, with their rates: the branch search screens
them) and why it fails to close where m < 0; the ``Closure``'s ``place`` then solves it on a
branch sign per sample, with velocities and accelerations up to ``order``, and gives what it
made known (points or links) and the sine between its constraint gradients (0 at a dead centre).
``gradients`` gives those gradients at a pose in any arithmetic
(``polish`` reads the branch and the sine from them in 40 digits).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Protocol

from solver.kinematics.rigid import Array, LinkMotion, PointMotion, Relative
from solver.position.groups.loci import Circle, Intersection, Locus, Piece, point_motion

if TYPE_CHECKING:
    from solver.position.topology import DyadStep, LocusSpec


# (Nothing to add to a group's answer: its mappings' default, never written.)
NOTHING: Mapping[Any, Any] = MappingProxyType({})


@dataclass(frozen=True, init=False)
class Placed:
    """A group solved on its branches: the sine between its constraint gradients per sample,
    and the points and links it made known; ``relative``: a located point seen from a known
    one, (known, located) -> ``rigid.Relative``, where the group computed it (a link through
    both takes it instead of computing it again). (Frozen, its fields written at once as
    ``rigid.PointMotion``'s.)"""

    gradient_sine: Array
    points: Mapping[str, PointMotion]
    links: Mapping[str, LinkMotion]
    relative: Mapping[tuple[str, str], Relative]

    def __init__(
        self,
        gradient_sine: Array,
        points: Mapping[str, PointMotion] = NOTHING,
        links: Mapping[str, LinkMotion] = NOTHING,
        relative: Mapping[tuple[str, str], Relative] = NOTHING,
    ) -> None:
        fields = self.__dict__
        fields["gradient_sine"], fields["points"] = gradient_sine, points
        fields["links"], fields["relative"] = links, relative


@dataclass(frozen=True, init=False)
class Closure:
    """A group at the samples before its branch is chosen: its margin m (metres) and smooth
    ``pieces`` (made when called: only a branch screen needs their rates), named by ``label``
    (the point, or the slot, it locates); ``two_branch`` false where it has one solution;
    ``place(sign, order)`` solves it on the branch ``sign`` (one per sample, or one for all).
    (Frozen, its fields written at once as ``rigid.PointMotion``'s.)"""

    label: str
    margin: Array
    pieces: Callable[[], tuple[Piece, ...]]
    describe: Callable[[], str]
    two_branch: bool
    place: Callable[[Array | float, int], Placed]

    def __init__(
        self,
        label: str,
        margin: Array,
        pieces: Callable[[], tuple[Piece, ...]],
        describe: Callable[[], str],
        two_branch: bool,
        place: Callable[[Array | float, int], Placed],
    ) -> None:
        fields = self.__dict__
        fields["label"], fields["margin"], fields["pieces"] = label, margin, pieces
        fields["describe"], fields["two_branch"], fields["place"] = describe, two_branch, place


class Known(Protocol):
    """What the assembler knows when it reaches a group: the motions solved so far."""

    @property
    def points(self) -> Mapping[str, PointMotion]: ...

    def resting(self, point: str) -> bool:
        """Whether a known point is at rest by construction (fixed, or a driver's pivot): its
        velocity and acceleration are zeros."""
        ...

    @property
    def at_drawn(self) -> Array:
        """The samples at the drawn pose (every driver unturned)."""
        ...

    def locus(self, spec: LocusSpec) -> Locus: ...

    def drawn(self, point: str) -> Array: ...


# In any arithmetic (``polish``: 40 digits): where a link's point is, and (cos, sin) of a link's
# turn from its drawn pose.
Where = Callable[[str, str], Any]
Turning = Callable[[str], tuple[Any, Any]]


class Group(Protocol):
    """A closed-form group type: one module of ``solver.position.groups`` each."""

    @property
    def kind(self) -> str:
        """Its name as an Assur group: RRR, RRP, PRP, RPR."""
        ...

    def close(self, step: Any, known: Known) -> Closure: ...

    def gradients(self, step: Any, where: Where, turning: Turning) -> tuple[Any, Any] | None:
        """Its two constraint gradients at its solution, in any arithmetic (their cross
        product's sign is its branch); None where ``polish`` does not check its branch."""
        ...


# The intersection of a group's two loci (its circles first), as its module types them.
Intersect = Callable[[Any, Any, str], Intersection]


@dataclass(frozen=True)
class DyadGroup:
    """A group that locates one joint point on two loci (``topology.DyadStep``) by its
    ``intersect`` (circles first), its rates from the differentiated constraints
    (``loci.point_motion``)."""

    kind: str
    intersect: Intersect
    two_branch: bool  # whether it has two solutions (a pin in two slots has one)

    def gradients(self, step: DyadStep, where: Where, turning: Turning) -> tuple[Any, Any] | None:
        """Its two constraint gradients at the located point X, in the arithmetic of ``where``
        and ``turning`` (``polish``: the branch and the sine between them in 40 digits): X - C
        for a circle about C, the slot's normal for a line; None with one solution."""
        if not self.two_branch:
            return None
        carrier = next(link for spec in step.loci if (link := spec.carrier) is not None)
        X = where(carrier, step.point)
        first, second = (spec.gradient(X, where, turning) for spec in step.loci)
        return first, second

    def close(self, step: DyadStep, known: Known) -> Closure:
        first, second = (known.locus(spec) for spec in step.loci)
        circle_first = isinstance(first, Circle) or not isinstance(second, Circle)
        cut = self.intersect(*((first, second) if circle_first else (second, first)), step.point)

        def place(sign: Array | float, order: int) -> Placed:
            X = cut.point(sign)
            X[known.at_drawn] = known.drawn(step.point)
            motion, sine = point_motion(first, second, X, order)
            return Placed(sine, points={step.point: motion})

        return Closure(
            step.point, cut.margin, lambda: cut.pieces, cut.describe, self.two_branch, place
        )
