"""constraints.constraint_system keeps one ConstraintSystem per live scene object and set of
unknowns (a Newton group's sweep builds its two systems once, not on every sweep), as
topology.build_plan keeps plans: reused, the systems give the same sweep to the last bit."""

from __future__ import annotations

import gc
import weakref

import numpy as np
import pytest

from benchmarks.bench_newton import FULL_TURN, PARTIAL
from solver.analysis.sweeps import Sweep, sweep
from solver.model.scene import LinkageScene, parse_linkage
from solver.position import constraints
from solver.position.constraints import ConstraintSystem

ALL = ["position", "velocity", "acceleration"]


def _bytes(result: Sweep) -> bytes:
    """Every number of a sweep: angles, limits, each link's and point's motion, residuals."""
    motion = result.motion
    parts: list[object] = [result.driver_angle, result.limits, motion.converged]
    for link in sorted(motion.links):
        m = motion.links[link]
        parts += [m.anchor.p, m.anchor.v, m.anchor.a, m.theta, m.omega, m.alpha]
    for point in sorted(motion.points):
        p = motion.points[point]
        parts += [p.p, p.v, p.a]
    parts += [(r.residual_norm, r.iterations) for r in motion.newton]
    return b"".join(np.asarray(x, dtype=float).tobytes() for x in parts)


def _systems_of(scene: LinkageScene) -> list[int]:
    """The ids of the live constraint systems built for ``scene``."""
    gc.collect()
    return sorted(
        id(o) for o in gc.get_objects() if isinstance(o, ConstraintSystem) and o.scene is scene
    )


@pytest.mark.slow
def test_sweeps_of_one_scene_share_its_systems_and_are_identical() -> None:
    scene = parse_linkage(FULL_TURN)
    first = _bytes(sweep(scene, 360, ALL))
    systems = _systems_of(scene)
    assert len(systems) == 2  # the branch's (whole linkage) and the group's
    again = _bytes(sweep(scene, 360, ALL))
    assert _systems_of(scene) == systems  # the same objects, none built again
    assert again == first
    assert _bytes(sweep(parse_linkage(FULL_TURN), 360, ALL)) == first  # as built afresh


@pytest.mark.slow
def test_one_system_per_scene_and_unknowns_forgotten_with_the_scene() -> None:
    scene = parse_linkage(FULL_TURN)
    moving = scene.moving_links
    system = constraints.constraint_system(scene, moving)
    assert constraints.constraint_system(scene, list(moving)) is system
    held = constraints.constraint_system(scene, moving, ["crank"])
    assert held is not system and held.angles == ("crank",)
    freed = [weakref.ref(system), weakref.ref(held)]
    del scene, system, held
    gc.collect()
    assert [ref() for ref in freed] == [None, None]
    # A later scene (whatever its id) is given systems of its own, not the freed scene's.
    other = parse_linkage(PARTIAL)
    assert constraints.constraint_system(other, other.moving_links).scene is other
    assert _bytes(sweep(other, 36, ALL)) == _bytes(sweep(parse_linkage(PARTIAL), 36, ALL))
