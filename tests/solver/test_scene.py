"""Reading a scene (solver.scene): a key the contract does not know is named with its path and
the nearest valid name.
"""

from __future__ import annotations

from solver.scene import unknown_keys
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
