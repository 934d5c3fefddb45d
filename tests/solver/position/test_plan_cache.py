"""build_plan keeps one plan per live scene object (the fixed cost of a sweep is paid once)."""

from __future__ import annotations

import gc
import weakref

import pytest

from solver.model.scene import parse_linkage
from solver.position import topology
from solver.teaching.presets import build_preset


@pytest.mark.slow
def test_one_plan_per_scene_object_forgotten_with_it() -> None:
    """build_plan returns the same plan for the same scene object, another for another scene;
    the plan is that of a scene parsed afresh from the same document; it is freed with its scene
    (a weak reference to it is dead once the scene is collected)."""
    four_bar = parse_linkage(build_preset("four_bar", {}))
    slider = parse_linkage(build_preset("slider_crank", {}))
    plan = topology.build_plan(four_bar)
    assert topology.build_plan(four_bar) is plan
    assert topology.build_plan(slider) is not plan
    afresh = topology.build_plan(parse_linkage(build_preset("slider_crank", {})))
    assert topology.build_plan(slider) == afresh
    freed = weakref.ref(plan)
    del four_bar, plan
    gc.collect()
    assert freed() is None
