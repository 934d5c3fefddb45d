"""Kinematics of mechanisms: planar linkages, moving points on moving bodies, spatial chains.

A plain library (numpy, scipy, sympy; no web imports). A scene goes in, a frozen result comes out;
nothing here mutates a scene. Each entry point accepts a scene-v1 dict or a parsed scene, and each
result's ``as_dict()`` is the body of the HTTP endpoint of the same name::

    import solver

    doc = {"kind": "linkage", "points": {...}, "links": {...}, "joints": [...], "drivers": [...]}
    instant = solver.analyze(doc)                    # POST /api/v1/analyze
    cycle = solver.sweep(doc, 360, ["position", "velocity"])   # POST /api/v1/sweep
    cycle["links"]["rocker"]["omega"]                # a read-only numpy array over the samples
    steps = solver.solve(doc, "loop")                # POST /api/v1/solution
    design = solver.synthesize({"task": "quick_return", "time_ratio": 1.25,
                                "rocker_length": 0.1, "swing_deg": 60})   # POST /api/v1/synthesis

Errors are the exceptions of ``solver.errors``; an unknown key in a scene is a warning in the
result's ``warnings`` (an ``InvalidScene`` with ``strict=True``).
"""

from solver.analysis.results import (
    AnalysisResult,
    EventResult,
    Result,
    SolutionResult,
    SweepResult,
    TimeSweepResult,
)
from solver.analysis.work_estimate import WorkEstimate, estimate_work, exercise_work
from solver.api import (
    ReadScene,
    SceneWarning,
    analyze,
    find_event,
    parse_scene,
    read_scene,
    solve,
    sweep,
    sweep_time,
    synthesize,
)
from solver.errors import (
    InvalidExpression,
    InvalidScene,
    KinematicsError,
    LimitExceeded,
    NoEvent,
    NotAssemblable,
    SingularConfiguration,
)
from solver.model.quantities import InstantQuantity, Quantity
from solver.solutions import Method
from solver.synthesis import SynthesisResult

__all__ = [
    "AnalysisResult",
    "EventResult",
    "InstantQuantity",
    "InvalidExpression",
    "InvalidScene",
    "KinematicsError",
    "LimitExceeded",
    "Method",
    "NoEvent",
    "NotAssemblable",
    "Quantity",
    "ReadScene",
    "Result",
    "SceneWarning",
    "SingularConfiguration",
    "SolutionResult",
    "SweepResult",
    "SynthesisResult",
    "TimeSweepResult",
    "WorkEstimate",
    "analyze",
    "estimate_work",
    "exercise_work",
    "find_event",
    "parse_scene",
    "read_scene",
    "solve",
    "sweep",
    "sweep_time",
    "synthesize",
]
