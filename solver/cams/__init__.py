"""Cams: the follower's motion laws, the SVAJ diagrams, the cam profile, the pressure angle and
the radius of curvature (docs/CAMS.md).

A scene of ``"kind": "cam"`` (``parse_cam``) goes in; ``sweep_cam`` (a revolution) and
``analyze_cam`` (one cam angle) give the bodies of POST /sweep and POST /analyze. The laws are
in ``solver.cams.laws``, the geometry (envelope, pressure angle, curvature) in
``solver.cams.geometry``, the warnings and extremes in ``solver.cams.analysis``.
"""

from solver.cams.analysis import analyze_cam, cam_warnings, smallest_base_radius, sweep_cam
from solver.cams.geometry import CamGeometry, cam_geometry, follower_lift
from solver.cams.laws import LAW_NAMES, LAWS
from solver.cams.model import CamScene, parse_cam

__all__ = [
    "LAWS",
    "LAW_NAMES",
    "CamGeometry",
    "CamScene",
    "analyze_cam",
    "cam_geometry",
    "cam_warnings",
    "follower_lift",
    "parse_cam",
    "smallest_base_radius",
    "sweep_cam",
]
