"""Reading a scene (solver.model.scene): a key the contract does not know is named with its path and
the nearest valid name; the one ground-pivot finder.
"""

from __future__ import annotations

from solver.model.scene import ground_pivot, parse_linkage, unknown_keys
from solver.teaching.presets import build_preset
from tests.solver.test_api import example


def test_unknown_keys_name_the_key_its_path_and_the_nearest_name() -> None:
    doc = example("S003-T2-rotating-carrier")
    doc["drivers"][0]["angle"] = 120
    doc["drivers"][0]["omegaa"] = 1.0
    doc["links"]["carrier"]["grond"] = True
    doc["moving_points"][0]["path"]["centre"] = "P"
    doc["titel"] = "x"
    doc["zzz"] = 1
    assert unknown_keys(doc) == [
        "titel is not a scene field; did you mean title?",
        "zzz is not a scene field; the fields are drivers, forces, gravity, joints, kind, links, "
        "masses, moving_points, point_masses, points, time, title, torques",
        "links.carrier.grond is not a scene field; did you mean ground?",
        "drivers[0].angle is not a scene field; did you mean angle_deg?",
        "drivers[0].omegaa is not a scene field; did you mean omega?",
        "moving_points[0].path.centre is not a scene field; did you mean center?",
    ]
    spatial = example("S002-spatial-arm")
    spatial["joints"][0]["rate_ddot"] = 0.0
    spatial["points"]["A"]["bodyy"] = "2"
    assert unknown_keys(spatial) == [
        "joints[0].rate_ddot is not a scene field; did you mean rate_dot?",
        "points.A.bodyy is not a scene field; did you mean body?",
    ]


def test_the_ground_pivot_is_the_revolute_joint_with_the_ground() -> None:
    """S000-T1: crank A-B, coupler B-C, rocker D-C. The quick-return's crank slides in the
    lever (a slider, not a pivot) but turns about O2; the ram's rod has no ground pivot."""
    scene = parse_linkage(example("S000-T1"))
    pivots = {link: ground_pivot(link, scene.joints, scene.ground) for link in scene.links}
    assert {link: pivot for link, pivot in pivots.items() if pivot is not None} == {
        "crank": "A",
        "rocker": "D",
    }
    assert [driver.pivot for driver in scene.drivers] == ["A"]
    shaper = parse_linkage(build_preset("quick_return", {}))
    assert ground_pivot("crank", shaper.joints, "ground") == "O2"
    assert ground_pivot("lever", shaper.joints, "ground") == "O4"
    assert ground_pivot("rod", shaper.joints, "ground") is None  # it slides on the ground
