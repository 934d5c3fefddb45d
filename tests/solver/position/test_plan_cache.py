"""build_plan keeps one plan per live scene object (issue 8: the fixed cost of a sweep)."""

from __future__ import annotations

import gc

from solver.model.scene import parse_linkage
from solver.position import topology
from solver.teaching.presets import build_preset


def test_one_plan_per_scene_object_forgotten_with_it() -> None:
    four_bar = parse_linkage(build_preset("four_bar", {}))
    slider = parse_linkage(build_preset("slider_crank", {}))
    plan = topology.build_plan(four_bar)
    assert topology.build_plan(four_bar) is plan
    assert topology.build_plan(slider) is not plan
    assert topology.build_plan(slider) == topology._Decomposition(slider).run()
    key = id(four_bar)
    del four_bar
    gc.collect()
    assert key not in topology._PLANS
