"""Linkage synthesis: the four-bar for two or three coupler positions, for a function, or for a
quick-return time ratio, each checked by the project's own analysis (docs/SYNTHESIS.md).

``synthesize(task)`` takes a task document (``"task": "motion"``, ``"function"`` or
``"quick_return"``) and returns the body of POST /synthesis: a scene-v1 linkage (links
ground, crank, coupler, rocker; pivots A, B, C, D and the coupler point P), its dimensions, the
checks at each precision position (from /analyze at the crank's angle there), the defects
(branch, order, Grashof; from /sweep) and warnings in words. The constructions are in
``motion`` (poles, centre and circle points), ``function`` (Freudenstein's equation, Chebyshev
spacing) and ``quick_return`` (the time-ratio construction); ``verify`` writes and analyses
the scene.
"""

from solver.synthesis.answer import SynthesisResult, synthesize
from solver.synthesis.function import chebyshev_spacing, freudenstein_coefficients
from solver.synthesis.motion import circumcentre, pole
from solver.synthesis.quick_return import crank_angle_difference
from solver.synthesis.task import parse_task

__all__ = [
    "SynthesisResult",
    "chebyshev_spacing",
    "circumcentre",
    "crank_angle_difference",
    "freudenstein_coefficients",
    "parse_task",
    "pole",
    "synthesize",
]
